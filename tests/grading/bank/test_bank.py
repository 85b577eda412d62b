"""The question bank (the course folder's bank/, imported as puma_course_bank): consistent, fair, worked by hand,
one file per exercise."""

from __future__ import annotations

import ast
import json

import numpy as np
import pytest

import puma_course_bank as bank
from puma_course import MK3, Porter, Puma560, transforms
from puma_course.grading import EXERCISES, Exercise, Question
from puma_course.grading.bank_loader import register
from puma_course.grading.plan import _jsonable
from puma_course.grading.run.worker import forbidden_codes, resolve
from puma_course_bank import _formulas
from puma_course_bank._reference import chains, motion, porter_chain
from tests.support import ROOT

BANK = ROOT / "bank"
QUESTIONS = [(ex.name, q.qid) for ex in EXERCISES.values() for q in ex.questions]


def _expected(q, args):
    value = q.reference(*args)
    return value if callable(value) or isinstance(value, dict) else np.asarray(value, dtype=float)


@pytest.mark.parametrize(("name", "qid"), QUESTIONS, ids=[f"{n}:{q}" for n, q in QUESTIONS])
def test_every_case_is_judged_right_for_a_right_answer_and_wrong_for_a_wrong_one(name, qid):
    q = EXERCISES[name].question(qid)
    assert q.points > 0 and q.public and float(q.points).is_integer()
    for seed in (0, 1):
        cases = q.cases(np.random.default_rng(seed))
        assert len(cases) > len(q.public), "every question needs hidden cases"
        for args in cases:
            expected = _expected(q, args)
            right = np.asarray(q.right_answer(*args), dtype=float)
            assert np.all(np.isfinite(right))
            assert q.judge(right, expected, tuple(args)).passed, (name, qid, args)
            # ... and the judge can fail: a clearly wrong answer (every entry off by 0.1) is refused; where the
            # right answer is no configuration at all (an unreachable pose), one row of zeros is clearly wrong
            wrong = right + 0.1 if right.size else np.zeros((1, *right.shape[1:]))
            assert not q.judge(wrong, expected, tuple(args)).passed, (name, qid)
            json.dumps([_jsonable(a) for a in args])  # every input can travel to the student's process


def test_points_are_integers_and_ten_exercises_one_per_lecture():
    assert sorted(EXERCISES) == [
        "ex01_rotations",
        "ex02_dh_frames",
        "ex03_puma_fk",
        "ex04_mk3_fk",
        "ex05_porter_fk",
        "ex06_porter_explicit",
        "ex07_porter_geometric",
        "ex08_three_step",
        "ex09_puma_ik",
        "ex10_trajectories",
    ]
    for ex in EXERCISES.values():
        assert all(float(q.points).is_integer() for q in ex.questions), ex.name
        assert ex.max_score >= 9


def test_bonus_points_are_not_in_the_maximum():
    ex = EXERCISES["ex06_porter_explicit"]
    bonus = [q for q in ex.questions if q.bonus]
    assert bonus and ex.max_score == sum(q.points for q in ex.questions) - sum(q.points for q in bonus)


def test_reference_answers_agree_with_hand_worked_values():
    # independent truths worked by hand, so the question bank cannot drift silently
    ex1, ex8 = EXERCISES["ex01_rotations"], EXERCISES["ex08_three_step"]
    R = ex1.question("q1").reference("z", np.pi / 2)
    assert np.allclose(R @ [1, 0, 0], [0, 1, 0])
    assert np.allclose(ex1.question("q1").reference("-z", np.pi / 2) @ [1, 0, 0], [0, -1, 0])
    R_a = ex1.question("q1").reference("x", 0.3)  # q3: the quarter turn about the base's z, after any R_a
    assert np.allclose(ex1.question("q3").reference(R_a, R @ R_a), [0, 0, 1, np.pi / 2])
    # the three-step exercise: w = (1/2, 1/2, 2) lies at 45 degrees; l3^2 = 4.5 (lecture 08 §4). Exercise 8's arm
    # reads its base angle from e_y: from the reading 0 (the arm along e_y) it turns by 45° - 90° = -45°
    w = np.array([0.5, 0.5, 2.0])
    F1 = ex8.question("q1").reference(w, np.zeros(3), np.eye(3))
    assert np.allclose(F1[:, 0], [np.sqrt(0.5), -np.sqrt(0.5), 0.0])
    theta1, theta2 = ex8.question("q2").reference(w, 1.5, 1.0, "up")
    l3 = np.sqrt(4.5)
    theta = np.arccos((l3**2 + 1.5**2 - 1.0) / (2 * 1.5 * l3))
    assert np.isclose(theta1, np.arctan2(2.0, np.hypot(0.5, 0.5)) + theta)
    # its θ2 is the forearm's elevation (a parallelogram): the bend at the elbow is θ2 - θ1
    assert np.isclose(np.cos(np.pi + (theta2 - theta1)), (1.5**2 + 1.0 - l3**2) / (2 * 1.5)) and theta2 < theta1
    assert np.isclose(np.degrees(theta2), 30.5277, atol=1e-3)  # lecture 08 §5: the forearm 30.53° above horizontal
    # from a bent start the base turns by (45° - 90°) - theta0_bar and carries the start frame along
    F_bar = transforms.rotx(0.4)
    F1 = ex8.question("q1").reference(w, np.array([0.3, 0.0, 0.0]), F_bar)
    assert np.allclose(F1, transforms.rotz(np.pi / 4 - np.pi / 2 - 0.3) @ F_bar)


def test_link_parameters_invert_the_package_mdh():
    rng = np.random.default_rng(5)
    for alpha, a, theta, d in zip(
        rng.uniform(-3, 3, 20), rng.uniform(-1, 1, 20), rng.uniform(-3, 3, 20), rng.uniform(-1, 1, 20), strict=True
    ):
        assert np.allclose(_formulas.link_parameters(chains.mdh(alpha, a, theta, d)), [alpha, a, theta, d])


def test_the_mechanisms_are_what_their_questions_describe():
    """The references of the modelling questions against hand-worked geometry (not against a DH table)."""
    h, d2 = 0.8, 0.2
    for q1, q2, q3 in [(0.0, 0.0, 0.6), (0.7, -0.4, 1.1), (-2.0, 1.2, 0.3)]:
        T = chains.rrp_fk([q1, q2, q3], h, d2)
        reach = q3 * np.cos(q2)
        tip = [reach * np.cos(q1) - d2 * np.sin(q1), reach * np.sin(q1) + d2 * np.cos(q1), h + q3 * np.sin(q2)]
        assert np.allclose(T[:3, 3], tip)
        assert np.allclose(T[:3, 2], [np.cos(q1) * np.cos(q2), np.sin(q1) * np.cos(q2), np.sin(q2)])  # the boom
    assert np.allclose(chains.rrp_fk([0.0, 0.0, 0.5], h, d2)[:3, 0], [0, 0, 1])  # x_T up at q = 0
    # the PUMA-560 stands upright at q = 0, its tool d6 above the wrist centre, pointing up
    a2, a3, d3, d4, hp, d6 = 0.4318, 0.0203, 0.15005, 0.4318, 0.66, 0.05
    T = chains.puma_pedestal_fk(np.zeros(6), a2, a3, d3, d4, hp, d6)
    assert np.allclose(T[:3, 3], [-a3, d3, hp + a2 + d4 + d6]) and np.allclose(T[:3, :3], np.diag([-1.0, -1, 1]))
    # on the rail the MK3 is the MK3, shifted along y0 by q1 and up by c
    q = np.array([250.0, 0.3, 0.5, -0.7, 0.2, 1.0])
    expected = MK3().fk(q[1:])
    expected[:3, 3] += [0.0, 250.0, 450.0]
    assert np.allclose(chains.mk3_rail_fk(q, 450.0, 360.0, 135.0, 250.0, 215.0, 100.0), expected)
    # Porter's tool frame: z_T = x5, x_T = y5, y_T = z5
    q = np.array([0.3, 0.7, 1.3, -0.4, 0.9, 0.6])
    F, T = Porter(1.0, 0.5, 0.3).fk(q), porter_chain.porter_tool_fk(q, 1.0, 0.5, 0.3)
    assert np.allclose(T[:3, 2], F[:3, 0]) and np.allclose(T[:3, 0], F[:3, 1]) and np.allclose(T[:3, 3], F[:3, 3])
    # the misprinted 4T5 of lecture 04 puts the flange at (600, 100, 360) mm at q = 0
    assert np.allclose(chains.mk3_printed_fk(np.zeros(5), 360, 135, 250, 215, 100)[:3, 3], [600, 100, 360])


def test_near_singular_hidden_poses_are_near_but_not_at_the_singularities():
    arm = Puma560()
    (T_wrist, *L1), (T_elbow, *L2), (T_shoulder, *L3), *_ = motion.puma_cases(np.random.default_rng(3), 4)
    sols = [np.asarray(Puma560(*L).ik(T).q) for T, L in ((T_wrist, L1), (T_elbow, L2), (T_shoulder, L3))]
    assert [len(s) for s in sols] == [8, 8, 8]  # the package does not snap them: all eight branches exist
    assert np.min(np.abs(np.sin(sols[0][:, 4]))) < 2e-5  # sin θ5 = 1e-5 on one arm
    assert arm.revolute.all()


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
    """The kinematics API may change: only bank/_reference/ may import it."""
    allowed = {
        "__future__",
        "typing",
        "numpy",
        "puma_course.grading.spec",
        "puma_course.grading.judge.compare",
        "puma_course.grading.judge.diagnose",
        "puma_course.grading.judge.judges",
        "._inputs",
        "._formulas",
        "._reference",
        ".",
    }
    for module, names in _imports(BANK / f"{name}.py"):
        if module == ".":
            assert set(names) <= {"_keys", "_reference"}, (name, names)
        elif module.startswith(".ex"):  # a sibling's declarations (Porter's public pose)
            assert (BANK / f"{module[1:]}.py").is_file()
        else:
            assert module in allowed, (name, module)
    for helper in ("_inputs.py", "_formulas.py", "_keys.py"):
        assert {m for m, _ in _imports(BANK / helper)} <= {
            "__future__",
            "typing",
            "math",
            "zlib",
            "numpy",
            "puma_course.transforms",
        }, helper
    for path in (BANK / "_reference").glob("*.py"):
        package = {m for m, _ in _imports(path) if m.startswith("puma_course")}
        allowed_package = {"puma_course", "puma_course.kinematics", "puma_course.kinematics.porter"}
        assert package <= allowed_package, (path.name, package)


@pytest.mark.parametrize(("name", "qid"), QUESTIONS, ids=[f"{n}:{q}" for n, q in QUESTIONS])
def test_every_answer_key_names_a_function_of_the_package(name, qid):
    """A tripwire on a name that no longer exists would silently guard nothing."""
    q = EXERCISES[name].question(qid)
    for spec in q.forbidden:
        assert resolve(spec) is not None, spec
    # each name is watched: by its code (Python) or itself (C function) in the profile, or, a ufunc no profile sees,
    # by the wrapper that replaces it wherever the student can reach it
    ufuncs = {spec for spec in q.forbidden if type(resolve(spec)).__name__ == "ufunc"}
    assert set(forbidden_codes(q.forbidden).values()) | ufuncs == set(q.forbidden), q.forbidden


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_every_allowed_name_exists(name):
    for spec in EXERCISES[name].allowed:
        assert ":" in spec and resolve(spec) is not None, spec


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
