"""puma_course.grading.publish.release: the solution-to-exercise transform, points from the bank, the release check."""

from __future__ import annotations

import json
import shutil

import nbformat
import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES, release, release_notebook
from puma_course.grading.publish.release import (
    NOTEBOOK_METADATA,
    STUB,
    essentials,
    notebook_text,
    points_summary,
    question_heading,
)
from tests.support import ROOT

# ---------------------------------------------------------------------------- the transform


def test_release_replaces_solutions_by_a_stub_and_drops_hidden_tests(make_notebook):
    src = (
        "def f(x):\n    '''doc'''\n    ### BEGIN SOLUTION\n    secret = x * 42\n    return secret\n"
        "    ### END SOLUTION\n"
    )
    hidden = "### BEGIN HIDDEN TESTS\nassert f(1) == 42\n### END HIDDEN TESTS"
    mixed = "check('q1', f)\n### BEGIN HIDDEN TESTS\nassert f(2) == 84\n### END HIDDEN TESTS\nprint('after')"
    md = "Explain.\n### BEGIN SOLUTION\nBecause 42.\n### END SOLUTION"
    nb = make_notebook(
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
    assert code.source == "def f(x):\n    '''doc'''\n    " + STUB
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


def test_release_rejects_unbalanced_markers_and_top_level_solutions(make_notebook):
    with pytest.raises(ValueError, match="not closed"):
        release_notebook(make_notebook(("code", "def f():\n    ### BEGIN SOLUTION\n    return 1", None)))
    with pytest.raises(ValueError, match="unbalanced"):
        release_notebook(make_notebook(("code", "x = 1\n### END SOLUTION", None)))
    with pytest.raises(ValueError, match="inside a function"):
        release_notebook(make_notebook(("code", "### BEGIN SOLUTION\nx = 1\n### END SOLUTION", None)))


def test_release_is_deterministic(make_notebook):
    src = "def f():\n    ### BEGIN SOLUTION\n    return 1\n    ### END SOLUTION"
    nb = make_notebook(("code", src, ["question:q1"]))
    nb.cells[0]["id"] = "fixed-id"
    a = notebook_text(release_notebook(nb))
    b = notebook_text(release_notebook(nb))
    assert a == b and a.endswith("\n")
    assert json.loads(a)["cells"][0]["id"] == "fixed-id"


def test_released_notebooks_carry_jupyterlab_metadata_without_the_python_version(make_notebook):
    out = release_notebook(make_notebook(("markdown", "# Title", None)))
    assert out.metadata == NOTEBOOK_METADATA
    assert out.metadata["kernelspec"]["display_name"] == "Python 3 (ipykernel)"
    assert set(out.metadata["language_info"]) == {
        "codemirror_mode",
        "file_extension",
        "mimetype",
        "name",
        "nbconvert_exporter",
        "pygments_lexer",
    }


# ---------------------------------------------------------------------------- points from the bank


def _small_solution(make_notebook):
    def answer(name, body):
        return f"def {name}(x):\n    ### BEGIN SOLUTION\n    return {body}\n    ### END SOLUTION"

    return make_notebook(
        ("markdown", "# A small exercise", None),
        ("code", answer("double", "2 * x"), ["question:q1"]),
        ("code", "check('q1', double)", ["selfcheck"]),
        ("code", answer("half", "x / 2"), ["question:q2"]),
    )


def test_release_writes_points_tags_headings_and_summary_from_the_bank(make_notebook, small_exercise):
    out = release_notebook(_small_solution(make_notebook), small_exercise)
    kinds = [(c.cell_type, c.metadata.get("tags", [])) for c in out.cells]
    assert kinds == [
        ("markdown", []),
        ("markdown", ["points-summary"]),
        ("markdown", ["heading:q1"]),
        ("code", ["question:q1", "points:2"]),
        ("code", ["selfcheck"]),
        ("markdown", ["heading:q2"]),
        ("code", ["question:q2", "points:1"]),
    ]
    assert out.cells[1].source == "**Points:** q1 2, 2 in all; bonus q2 1 (in your score, not in the maximum)."
    assert out.cells[2].source == "**q1** · 2 points · write `double` below"
    assert out.cells[5].source == "**q2** · bonus, 1 point (in your score, not in the maximum) · write `half` below"
    assert [out.cells[i].id for i in (1, 2, 5)] == ["points-summary", "heading-q1", "heading-q2"]
    assert out.cells[1].source == points_summary(small_exercise)
    assert out.cells[2].source == question_heading(small_exercise.question("q1"))


@pytest.mark.parametrize("tag", ["points:3", "points:2"])
def test_a_hand_written_points_tag_in_a_solution_is_refused(make_notebook, small_exercise, tag):
    # stale (the bank says 2) or not, a second copy of the points is refused: it would go stale later
    nb = _small_solution(make_notebook)
    nb.cells[1].metadata["tags"].append(tag)
    with pytest.raises(ValueError, match=rf"expected no points:N tag in cell 2 .*got '{tag}'.*q1 is worth 2"):
        release_notebook(nb, small_exercise)


def test_a_stale_points_tag_stops_the_release_of_the_course(tmp_path, capsys):
    sol, ex = tmp_path / "solutions", tmp_path / "exercises"
    sol.mkdir()
    nb = nbformat.read(ROOT / "solutions" / "ex01_rotations.ipynb", as_version=4)
    answer = next(c for c in nb.cells if "question:q2" in c.metadata.get("tags", []))
    answer.metadata["tags"].append("points:5")  # the bank gives q2 3 points
    nbformat.write(nb, sol / "ex01_rotations.ipynb")
    with pytest.raises(ValueError, match=r"ex01_rotations.ipynb: .*'points:5'.*q2 is worth 3"):
        release(sol, ex)
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex)]) == 2
    assert "points:5" in capsys.readouterr().err
    assert not ex.exists()


def test_release_refuses_question_tags_that_disagree_with_the_bank(make_notebook, small_exercise):
    unknown = _small_solution(make_notebook)
    unknown.cells[3].metadata["tags"] = ["question:q7"]
    with pytest.raises(ValueError, match=r"question tags among \['q1', 'q2'\].*'question:q7'"):
        release_notebook(unknown, small_exercise)
    missing = _small_solution(make_notebook)
    missing.cells[3].metadata["tags"] = []
    with pytest.raises(ValueError, match=r"none for \['q2'\]"):
        release_notebook(missing, small_exercise)
    twice = _small_solution(make_notebook)
    twice.cells[2].metadata["tags"] = ["question:q1"]
    with pytest.raises(ValueError, match="one cell tagged 'question:q1'"):
        release_notebook(twice, small_exercise)
    wrong_def = _small_solution(make_notebook)
    wrong_def.cells[3].source = wrong_def.cells[3].source.replace("def half", "def halve")
    with pytest.raises(ValueError, match=r"to define half\(\)"):
        release_notebook(wrong_def, small_exercise)
    generated = _small_solution(make_notebook)
    generated.cells[0].metadata["tags"] = ["heading:q1"]
    with pytest.raises(ValueError, match="generates"):
        release_notebook(generated, small_exercise)


def test_release_refuses_a_solution_without_a_bank_entry(tmp_path):
    (tmp_path / "solutions").mkdir()
    nbformat.write(nbformat.v4.new_notebook(), tmp_path / "solutions" / "ex99_nowhere.ipynb")
    with pytest.raises(ValueError, match=r"solutions: .*got ex99_nowhere.ipynb"):
        release(tmp_path / "solutions", tmp_path / "exercises")


def test_release_defaults_to_the_folders_of_the_current_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match="solutions: expected a folder"):
        release()
    (tmp_path / "solutions").mkdir()
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", tmp_path / "solutions")
    assert release() == ["ex01_rotations"]
    assert (tmp_path / "exercises" / "ex01_rotations.ipynb").is_file()
    assert release(check_only=True) == []


# ---------------------------------------------------------------------------- the release check


@pytest.fixture
def course(tmp_path):
    """A copy of the course's solutions/ and exercises/ in a temporary folder."""
    for folder in ("solutions", "exercises"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    return tmp_path / "solutions", tmp_path / "exercises"


def test_release_check_passes_after_every_exercise_is_opened_and_saved_in_jupyterlab(course, jupyterlab_save, capsys):
    sol, ex = course
    for path in sorted(ex.glob("*.ipynb")):
        before = path.read_bytes()
        jupyterlab_save(path)
        assert path.read_bytes() != before  # the save did change the file ...
        saved = json.loads(path.read_text(encoding="utf-8"))
        assert saved["metadata"]["language_info"]["version"] == "3.12.4"
    assert release(sol, ex, check_only=True) == []  # ... but nothing a student works with
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    assert "up to date" in capsys.readouterr().out
    # writing puts the generator's exact bytes back
    assert sorted(release(sol, ex)) == sorted(p.stem for p in sol.glob("*.ipynb"))
    for path in ex.glob("*.ipynb"):
        assert path.read_bytes() == (ROOT / "exercises" / path.name).read_bytes()
    assert release(sol, ex) == []


def test_release_check_passes_when_jupyterlab_saves_a_solution(course, jupyterlab_save):
    sol, ex = course
    jupyterlab_save(sol / "ex02_dh_frames.ipynb", python_version="3.10.12", run=False)
    assert release(sol, ex, check_only=True) == []


def _edit(path, change):
    nb = nbformat.read(path, as_version=4)
    change(nb)
    nbformat.write(nb, path)


def _first(nb, tag):
    return next(c for c in nb.cells if tag in c.metadata.get("tags", []))


@pytest.mark.parametrize(
    ("change", "reason"),
    [
        (lambda nb: setattr(_first(nb, "selfcheck"), "source", 'check("q1", something_else)'), "source differs"),
        (lambda nb: _first(nb, "question:q1").metadata["tags"].remove("points:2"), "tags differ"),
        (lambda nb: _first(nb, "question:q1").metadata["tags"].remove("question:q1"), "tags differ"),
        (lambda nb: nb.cells.pop(), "cells, expected"),
        (lambda nb: nb.cells.insert(3, nb.cells.pop(4)), "differs"),
        (lambda nb: nb.cells.__setitem__(0, nbformat.v4.new_raw_cell(nb.cells[0].source)), "cell 1: type differs"),
    ],
    ids=["edited-source", "removed-points-tag", "removed-question-tag", "removed-cell", "moved-cell", "cell-type"],
)
def test_release_check_still_detects_a_real_change(course, jupyterlab_save, change, reason, capsys):
    sol, ex = course
    path = ex / "ex01_rotations.ipynb"
    jupyterlab_save(path)
    _edit(path, change)
    stale = release(sol, ex, check_only=True)
    assert len(stale) == 1 and stale[0].startswith("ex01_rotations (") and reason in stale[0], stale
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert "ex01_rotations" in capsys.readouterr().err


def test_release_check_detects_points_changed_in_the_bank(course, monkeypatch):
    import dataclasses

    sol, ex = course
    old = EXERCISES["ex03_puma_fk"]
    q1 = dataclasses.replace(old.question("q1"), points=4)
    monkeypatch.setitem(EXERCISES, "ex03_puma_fk", dataclasses.replace(old, questions=(q1, *old.questions[1:])))
    assert release(sol, ex, check_only=True) == ["ex03_puma_fk (cell 2: source differs)"]  # the points summary


def test_release_check_reports_unreadable_missing_and_orphan_exercises(course):
    sol, ex = course
    (ex / "ex01_rotations.ipynb").write_text("{not json", encoding="utf-8")
    (ex / "ex02_dh_frames.ipynb").unlink()
    shutil.copy(ex / "ex03_puma_fk.ipynb", ex / "ex99_orphan.ipynb")
    stale = release(sol, ex, check_only=True)
    assert stale[0].startswith("ex01_rotations (not a readable notebook")
    assert stale[1:] == ["ex02_dh_frames (not generated yet)", "ex99_orphan (no solution)"]


def test_essentials_ignore_volatile_metadata_but_keep_order_types_sources_and_tags():
    a = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1", metadata={"tags": ["t"]})])
    b = nbformat.from_dict(json.loads(nbformat.writes(a)))
    b.metadata["language_info"] = {"name": "python", "version": "3.13.0"}
    b.cells[0].id = "another-id"
    b.cells[0].execution_count = 3
    b.cells[0].metadata["collapsed"] = True
    assert essentials(a) == essentials(b)
    b.cells[0].source = "x = 2"
    assert essentials(a) != essentials(b)
