"""Unit tests of puma_course.grading: comparisons, the release transform, the question bank, check()."""

from __future__ import annotations

import json

import nbformat
import numpy as np
import pytest

from puma_course import grading
from puma_course.grading import (
    EXERCISES,
    check,
    compare_angles,
    compare_close,
    compare_solution_set,
    release_notebook,
    use_exercise,
)

# ---------------------------------------------------------------------------- comparisons


def test_compare_close_accepts_equal_and_reports_differences():
    ref = np.array([[1.0, 2.0], [3.0, 4.0]])
    assert compare_close(ref.tolist(), ref) is None
    assert compare_close(ref + 1e-9, ref) is None
    assert "differ" in compare_close(ref + 1e-3, ref)
    assert "shape" in compare_close(ref.ravel()[:3], ref)
    assert compare_close("a string", ref) == "did not return numbers"
    assert "NaN" in compare_close([[np.nan, 2], [3, 4]], ref)


def test_compare_close_tolerance_scales_with_the_reference():
    # millimetre-sized values (MK3): an error of 1e-5 mm on 600 mm is a rounding error, not a mistake
    ref = np.array([600.0, 0.0, 260.0])
    assert compare_close(ref + 1e-5, ref) is None
    assert compare_close(ref + 1e-2, ref) is not None


def test_compare_close_accepts_a_squeezable_shape():
    assert compare_close([[0.5]], np.array(0.5)) is None
    assert compare_close(0.5, np.array([0.5])) is None


def test_compare_angles_is_modulo_two_pi():
    assert compare_angles([0.1 - 2 * np.pi, np.pi], np.array([0.1, -np.pi])) is None
    assert compare_angles([0.2], np.array([0.1])) is not None


def test_compare_solution_set_ignores_order_and_wraps_only_angle_columns():
    cmp = compare_solution_set([0, 2])
    ref = np.array([[0.1, 1.0, 0.2], [3.0, 2.0, 6.0]])
    assert cmp(ref[::-1] + [[2 * np.pi, 0, -2 * np.pi], [0, 0, 0]], ref) is None
    # column 1 is a length: adding 2π there is wrong
    assert cmp(ref + [[0, 2 * np.pi, 0], [0, 0, 0]], ref) is not None
    assert "misses" in cmp(ref[:1], ref)
    assert "not a solution" in cmp(np.vstack([ref, [[1.0, 1.0, 1.0]]]), ref)
    assert "shape" in cmp(ref.ravel(), ref)


# ---------------------------------------------------------------------------- release transform


def _nb(*cells):
    nb = nbformat.v4.new_notebook()
    for kind, src, tags in cells:
        make = nbformat.v4.new_code_cell if kind == "code" else nbformat.v4.new_markdown_cell
        nb.cells.append(make(src, metadata={"tags": tags} if tags else {}))
    return nb


def test_release_replaces_solutions_by_a_stub_and_drops_hidden_tests():
    src = (
        "def f(x):\n    '''doc'''\n    ### BEGIN SOLUTION\n    secret = x * 42\n    return secret\n"
        "    ### END SOLUTION\n"
    )
    hidden = "### BEGIN HIDDEN TESTS\nassert f(1) == 42\n### END HIDDEN TESTS"
    mixed = "check('q1', f)\n### BEGIN HIDDEN TESTS\nassert f(2) == 84\n### END HIDDEN TESTS\nprint('after')"
    md = "Explain.\n### BEGIN SOLUTION\nBecause 42.\n### END SOLUTION"
    nb = _nb(
        ("code", src, ["question:q1", "points:2"]),
        ("code", hidden, ["hidden-tests"]),
        ("code", mixed, None),
        ("markdown", md, None),
    )
    nb.cells[0].outputs = [nbformat.v4.new_output("stream", text="old output")]
    nb.cells[0].execution_count = 7
    out = release_notebook(nb)
    assert len(out.cells) == 3  # the hidden-test cell vanished
    code = out.cells[0]
    assert code.source == "def f(x):\n    '''doc'''\n    " + grading.STUB
    assert code.outputs == [] and code.execution_count is None
    assert code.metadata == {"tags": ["question:q1", "points:2"]}
    assert out.cells[1].source == "check('q1', f)\nprint('after')"
    assert "42" not in out.cells[2].source and "Write your answer here" in out.cells[2].source
    assert out.metadata["kernelspec"]["name"] == "python3"
    # the stub only raises when the function is called
    ns: dict = {}
    exec(code.source, ns)
    with pytest.raises(NotImplementedError):
        ns["f"](1)


def test_release_rejects_unbalanced_markers_and_top_level_solutions():
    with pytest.raises(ValueError, match="not closed"):
        release_notebook(_nb(("code", "def f():\n    ### BEGIN SOLUTION\n    return 1", None)))
    with pytest.raises(ValueError, match="unbalanced"):
        release_notebook(_nb(("code", "x = 1\n### END SOLUTION", None)))
    with pytest.raises(ValueError, match="inside a function"):
        release_notebook(_nb(("code", "### BEGIN SOLUTION\nx = 1\n### END SOLUTION", None)))


def test_release_is_deterministic():
    nb = _nb(("code", "def f():\n    ### BEGIN SOLUTION\n    return 1\n    ### END SOLUTION", ["question:q1"]))
    nb.cells[0]["id"] = "fixed-id"
    a = grading.notebook_text(release_notebook(nb))
    b = grading.notebook_text(release_notebook(nb))
    assert a == b and a.endswith("\n")
    assert json.loads(a)["cells"][0]["id"] == "fixed-id"


# ---------------------------------------------------------------------------- the question bank


def test_question_bank_is_consistent():
    assert len(EXERCISES) >= 6
    rng = np.random.default_rng(0)
    for ex in EXERCISES.values():
        qids = [q.qid for q in ex.questions]
        assert len(set(qids)) == len(qids)
        assert ex.max_score > 0
        for q in ex.questions:
            assert q.points > 0 and q.public, (ex.name, q.qid)
            cases = q.cases(rng)
            assert len(cases) > len(q.public), "every question needs hidden cases"
            for args in cases:
                ref = np.asarray(q.reference(*args), dtype=float)
                assert np.all(np.isfinite(ref))
                assert q.compare(ref, ref) is None
                # ... and the comparison can fail: a clearly wrong answer (every entry off by 0.1) is refused
                assert q.compare(ref + 0.1, ref) is not None, (ex.name, q.qid)
                # every input can travel to the student's process as JSON
                json.dumps([grading._jsonable(a) for a in args])


def test_hidden_inputs_depend_on_the_seed_and_are_reproducible():
    ex = EXERCISES["ex01_rotations"]
    a, b, c = grading._plan(ex, 1), grading._plan(ex, 1), grading._plan(ex, 2)
    assert [x["args"] for x in a] == [x["args"] for x in b]
    assert [x["args"] for x in a] != [x["args"] for x in c]


def test_bonus_points_are_not_in_the_maximum():
    ex = EXERCISES["ex05_porter_ik"]
    bonus = [q for q in ex.questions if q.bonus]
    assert bonus and ex.max_score == sum(q.points for q in ex.questions) - sum(q.points for q in bonus)


def test_reference_answers_agree_with_hand_worked_values():
    # independent truths worked by hand, so the question bank cannot drift silently
    ex1, ex6 = EXERCISES["ex01_rotations"], EXERCISES["ex06_three_step"]
    R = ex1.question("q1").reference("z", np.pi / 2)
    assert np.allclose(R @ [1, 0, 0], [0, 1, 0])
    assert np.allclose(ex1.question("q3").reference(R), [0, 0, 1, np.pi / 2])
    # the three-step exercise: w = (1/2, 1/2, 2) lies at 45 degrees; l3^2 = 4.5
    assert np.isclose(ex6.question("q1").reference(np.array([0.5, 0.5, 2.0])), np.pi / 4)
    theta, theta1, theta2 = ex6.question("q3").reference(np.array([0.5, 0.5, 2.0]), 1.5, 1.0)
    l3 = np.sqrt(4.5)
    assert np.isclose(np.cos(theta), (l3**2 + 1.5**2 - 1.0) / (2 * 1.5 * l3))
    assert np.isclose(theta1, np.arctan2(2.0, np.hypot(0.5, 0.5)) + theta)
    assert np.isclose(np.cos(np.pi + theta2), (1.5**2 + 1.0 - l3**2) / (2 * 1.5))


# ---------------------------------------------------------------------------- self-check


def _right_rotation(axis, angle):
    c, s = np.cos(angle), np.sin(angle)
    return {
        "x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
        "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
        "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
    }[axis]


def test_check_prints_one_clear_line(capsys):
    use_exercise("ex01_rotations")
    check("q1", _right_rotation)
    assert "passed" in capsys.readouterr().out

    def stub(axis, angle):
        raise NotImplementedError("write your answer here")

    check("q1", stub)
    assert "not attempted yet" in capsys.readouterr().out

    check("q1", lambda axis, angle: _right_rotation(axis, -angle))
    out = capsys.readouterr().out
    assert "FAILED" in out and "Hint:" in out and "Traceback" not in out

    def crashes(axis, angle):
        return undefined_name  # noqa: F821

    check("q1", crashes)
    out = capsys.readouterr().out
    assert "NameError" in out and "Traceback" not in out

    check("q1", 42)
    assert "FAILED" in capsys.readouterr().out


def test_check_flags_the_answer_key(capsys):
    from puma_course import rodrigues

    check("ex01_rotations:q2", lambda axis, angle: rodrigues(axis, angle))
    out = capsys.readouterr().out
    assert "FAILED" in out and "rodrigues" in out


def test_check_rejects_unknown_names():
    with pytest.raises(ValueError, match="ex01_rotations"):
        use_exercise("no_such_exercise")
    with pytest.raises(ValueError, match="q1"):
        check("ex01_rotations:q99", _right_rotation)


def test_the_child_never_receives_expected_values(monkeypatch, tmp_path):
    seen = {}

    def fake_run_child(cells, calls, workdir, timeout_cell, timeout_total, forbidden=None):
        seen["calls"] = calls
        return [], False, 0, False

    monkeypatch.setattr(grading, "_run_child", fake_run_child)
    sub = tmp_path / "ex01_rotations.ipynb"
    nbformat.write(nbformat.v4.new_notebook(), sub)
    result = grading.grade_notebook(sub, EXERCISES["ex01_rotations"], "s", seed=1)
    assert result.status == "crashed" and result.score == 0
    assert seen["calls"] and all(set(c) == {"qid", "case", "function", "args"} for c in seen["calls"])
