"""The question bank (puma_course.grading.bank): consistent, fair, worked by hand, one file per exercise."""

from __future__ import annotations

import ast
import json

import numpy as np
import pytest

from puma_course.grading import EXERCISES, Exercise, Question, bank
from puma_course.grading.model import register
from puma_course.grading.runner import _jsonable
from tests.support import ROOT

BANK = ROOT / "puma_course" / "grading" / "bank"


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
                json.dumps([_jsonable(a) for a in args])


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


def test_one_bank_file_per_exercise_named_after_it():
    files = sorted(p.stem for p in BANK.glob("ex*.py"))
    assert files == sorted(EXERCISES)
    for module in bank.MODULES:
        assert module.EXERCISE is EXERCISES[module.__name__.rsplit(".", 1)[1]]


def _imports(path):
    """(module, names) of every import statement in a file, relative ones with their dots."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out += [(alias.name, None) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            out.append(("." * node.level + (node.module or ""), tuple(a.name for a in node.names)))
    return out


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_bank_files_call_the_kinematics_only_through_reference(name):
    """The kinematics API may change: only bank/_reference.py may import it."""
    allowed = {"__future__", "numpy", "..model", "..compare", "._inputs", "."}
    for module, names in _imports(BANK / f"{name}.py"):
        if module == ".":
            assert names == ("_reference",), (name, names)
        elif module.startswith(".ex"):  # a sibling's declarations (Porter's public pose)
            assert (BANK / f"{module[1:]}.py").is_file()
        else:
            assert module in allowed, (name, module)
    assert {m for m, _ in _imports(BANK / "_inputs.py")} <= {"__future__", "typing", "numpy"}
    kinematics = {m for m, _ in _imports(BANK / "_reference.py") if m.startswith("...")}
    assert kinematics <= {"...", "...kinematics"}, kinematics  # transforms and the robots


def test_register_refuses_a_second_exercise_of_the_same_name_and_repeated_question_ids():
    q = EXERCISES["ex01_rotations"].question("q1")
    with pytest.raises(ValueError, match="registered already"):
        register(Exercise("ex01_rotations", "again", (q,)))
    with pytest.raises(ValueError, match="distinct question ids"):
        register(Exercise("ex99_twice", "twice", (q, q)))
    assert "ex99_twice" not in EXERCISES


def test_a_question_needs_positive_points():
    with pytest.raises(ValueError, match="points: expected a positive number of points for q1, got 0"):
        Question("q1", "f", 0, "t", public=((1.0,),), hidden=lambda rng: [], reference=lambda x: x)
