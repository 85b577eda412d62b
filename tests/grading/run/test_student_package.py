"""grading.run.student: the student-side package holds the self-check stub and the allowed names, nothing else.

Each test builds a student-side package and imports it in a fresh ``python -I -S`` (so the real package
is not on the path), as the worker does.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from puma_course import MK3, Porter, Puma560, ThreeStepArm, rodrigues
from puma_course.grading import EXERCISES
from puma_course.grading.run.sandbox import choose
from puma_course.grading.run.student import build, requirements


def _run(folder, code: str) -> dict:
    """Run ``code`` (which fills ``result``) with only the student-side package and site-packages on the path."""
    prog = (
        f"import sys, json\nsys.path[:0] = [{str(folder)!r}]\nsys.path += {list(choose('none').sites)!r}\n"
        f"result = {{}}\n{code}\nprint(json.dumps(result))"
    )
    out = subprocess.run([sys.executable, "-I", "-S", "-c", prog], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout.splitlines()[-1])


def test_nothing_but_the_self_check_when_nothing_is_allowed(tmp_path):
    build("ex01_rotations", (), tmp_path)
    files = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.py"))
    assert files == ["puma_course/__init__.py", "puma_course/grading/__init__.py"]
    got = _run(
        tmp_path,
        """
from puma_course.grading import check, use_exercise
use_exercise("ex01_rotations")
check("q1", print)
for stmt in ("from puma_course import rotx", "import puma_course.transforms",
             "from puma_course.grading import EXERCISES", "import puma_course.grading.bank",
             "import puma_course; puma_course.Puma560"):
    try:
        exec(stmt)
        result[stmt] = "imported"
    except ImportError as exc:
        result[stmt] = str(exc)
""",
    )
    for stmt, said in got.items():
        assert "is not available in this exercise" in said and "nothing but the self-check" in said, (stmt, said)


def test_an_allowed_name_comes_with_what_it_needs_and_nothing_more(tmp_path):
    build("ex08_three_step", ("puma_course.transforms:rodrigues",), tmp_path)
    text = (tmp_path / "puma_course" / "transforms.py").read_text(encoding="utf-8")
    assert "def rodrigues(" in text and "def skew(" in text
    for other in ("def rotx", "def axis_angle", "def inverse_transform", "def trot"):
        assert other not in text, other
    got = _run(
        tmp_path,
        """
import numpy as np
from puma_course import rodrigues
from puma_course.transforms import rodrigues as same
result["value"] = rodrigues([1.0, 2.0, 3.0], 0.7).tolist()
result["same"] = rodrigues is same
for name in ("rotx", "axis_angle", "Puma560"):
    try:
        exec(f"from puma_course import {name}")
        result[name] = "imported"
    except ImportError as exc:
        result[name] = str(exc)
""",
    )
    assert np.allclose(got["value"], rodrigues([1.0, 2.0, 3.0], 0.7)) and got["same"]
    assert all("not available in this exercise" in got[n] for n in ("rotx", "axis_angle", "Puma560"))


@pytest.mark.parametrize(
    ("spec", "code", "expected"),
    [
        (
            "puma_course:Puma560",
            "result['v'] = puma_course.Puma560().fk([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]).tolist()",
            lambda: Puma560().fk([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]),
        ),
        (
            "puma_course:MK3",
            "result['v'] = puma_course.MK3().fk([0.1, 0.2, 0.3, 0.4, 0.5]).tolist()",
            lambda: MK3().fk([0.1, 0.2, 0.3, 0.4, 0.5]),
        ),
        (
            "puma_course.kinematics.porter:Porter",
            "from puma_course.kinematics.porter import Porter\n"
            "p = Porter(1, 0.5, 0.3)\nresult['v'] = p.ik(p.fk([0.3, 0.7, 1.3, 5.9, 0.9, 0.6])).q.tolist()",
            lambda: Porter(1, 0.5, 0.3).ik(Porter(1, 0.5, 0.3).fk([0.3, 0.7, 1.3, 5.9, 0.9, 0.6])).q,
        ),
        (
            "puma_course:ThreeStepArm",
            "import numpy as np\n"
            "s = puma_course.ThreeStepArm(1.5, 1.0).three_step(np.array([0.5, 0.5, 2.0]), np.eye(3))\n"
            "result['v'] = [s.theta0, s.theta1]",
            lambda: [
                ThreeStepArm(1.5, 1.0).three_step(np.array([0.5, 0.5, 2.0]), np.eye(3)).theta0,
                ThreeStepArm(1.5, 1.0).three_step(np.array([0.5, 0.5, 2.0]), np.eye(3)).theta1,
            ],
        ),
    ],
)
def test_a_copied_class_behaves_as_the_package(tmp_path, spec, code, expected):
    build("exNN", (spec,), tmp_path)
    got = _run(tmp_path, "import puma_course\n" + code)
    assert np.allclose(got["v"], expected())
    assert not (tmp_path / "puma_course" / "grading" / "bank").exists()


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("numpy:array", "inside puma_course"),
        ("puma_course.grading.bank._reference", "answer key"),
        ("puma_course.grading:EXERCISES", "answer key"),
        ("puma_course.nothing", "expected a module"),
        ("puma_course.transforms:nothing", "has no 'nothing'"),
        ("puma_course.transforms:a:b", "module:name"),
        (3, "module:name"),
    ],
)
def test_a_bad_allowed_entry_is_refused(tmp_path, spec, message):
    with pytest.raises(ValueError, match="^allowed:.*" + message):
        requirements([spec])


def test_every_exercise_of_the_bank_builds():
    for ex in EXERCISES.values():
        assert requirements(ex.allowed) is not None


_RESOLVE = """
import importlib
for spec in KEYS:
    module, _, path = spec.partition(":")
    try:
        obj = importlib.import_module(module)
        for part in path.split("."):
            obj = getattr(obj, part)
        result[spec] = "there"
    except (ImportError, AttributeError) as exc:
        result[spec] = f"{type(exc).__name__}: {exc}"
"""


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_no_answer_key_of_an_exercise_is_in_its_student_side(tmp_path, name):
    """Every answer key the exercise does not allow by name is absent, class members included, saying why."""
    ex = EXERCISES[name]
    build(name, ex.allowed, tmp_path, ex.answer_keys)
    bank = (".grading.", "puma_course_bank")  # the question bank itself is never on the student side at all
    keys = [k for k in ex.answer_keys if k not in ex.allowed and not any(b in k for b in bank)]
    got = _run(tmp_path, f"KEYS = {keys!r}\n{_RESOLVE}")
    assert {k: v for k, v in got.items() if v == "there"} == {}
    for spec, said in got.items():
        assert "not available in this exercise" in said or "No module named" not in said, (spec, said)


@pytest.mark.parametrize(
    ("name", "cls", "module", "gone", "helpers"),
    [
        ("ex09_puma_ik", "Puma560", "puma_course.kinematics.puma560", ("ik", "ik_batch", "_batch_block"),
         ("_arm", "_wrist", "_reach", "_wrist_terms", "_reason")),
        ("ex06_porter_explicit", "Porter", "puma_course.kinematics.porter", ("ik", "ik_batch", "classify", "_batch"),
         ("branch", "pose_terms", "construct", "angle")),
        ("ex07_porter_geometric", "Porter", "puma_course.kinematics.porter", ("ik", "ik_batch", "_explicit_one"),
         ("branch", "pose_terms", "construct", "angle")),
    ],
)  # fmt: skip
def test_an_allowed_robot_keeps_its_allowed_members_only(tmp_path, name, cls, module, gone, helpers):
    """fk, frames, points and the named configurations work as in the package; ik and its kernels are not there."""
    ex = EXERCISES[name]
    build(name, ex.allowed, tmp_path, ex.answer_keys)
    every = "\n".join(p.read_text(encoding="utf-8") for p in (tmp_path / "puma_course").rglob("*.py"))
    path = tmp_path / module.replace(".", "/")
    own = (path / "__init__.py" if path.is_dir() else path.with_suffix(".py")).read_text(encoding="utf-8")
    for helper in helpers:
        assert f"def {helper}(" not in every, helper  # not wrapped: not there at all
    for member in gone:  # (the bases' abstract ik, which computes nothing, stays in robot.py and dh.py)
        assert f"def {member}(" not in own and f"{member} = _AbsentMember()" in own, member
    got = _run(
        tmp_path,
        f"""
import numpy as np
from {module} import {cls}
arm = {cls}()
q = np.array([0.3, -0.4, 0.5, 0.2, 0.6, 0.1])
result["fk"] = arm.fk(q).tolist()
result["frames"] = arm.frames(q).tolist()
result["points"] = arm.points(q).tolist()
result["configurations"] = {{k: np.asarray(v).tolist() for k, v in arm.configurations.items()}}
for member in {gone!r}:
    for owner in (arm, {cls}):
        try:
            getattr(owner, member)
            result[member] = "there"
        except AttributeError as exc:
            result[member] = str(exc)
    result[member + "?"] = hasattr(arm, member)
result["mro"] = [k.__name__ for k in type(arm).__mro__]
""",
    )
    real = {"Puma560": Puma560, "Porter": Porter}[cls]()
    q = np.array([0.3, -0.4, 0.5, 0.2, 0.6, 0.1])
    assert np.allclose(got["fk"], real.fk(q)) and np.allclose(got["frames"], real.frames(q))
    assert np.allclose(got["points"], real.points(q))
    assert got["configurations"].keys() == real.configurations.keys()
    for member in gone:
        assert got[member].startswith(f"{cls}.{member} is not available in this exercise"), got[member]
        assert got[member + "?"] is False
    assert got["mro"][0] == cls


def test_an_answer_of_another_exercise_stays_where_it_is_allowed(tmp_path):
    """Exercise 10 uses Puma560.ik (exercise 9's answer) but not the nearest-solution helpers (its own)."""
    ex = EXERCISES["ex10_trajectories"]
    build(ex.name, ex.allowed, tmp_path, ex.answer_keys)
    got = _run(
        tmp_path,
        """
import numpy as np
from puma_course.kinematics.puma560 import Puma560
arm = Puma560()
sol = arm.ik(arm.fk(np.array([0.3, -0.4, 0.5, 0.2, 0.6, 0.1])))
result["q"] = np.asarray(sol).tolist()
result["html"] = "<table" in sol._repr_html_()  # what answers nothing stays (the notebook display)
try:
    sol.nearest(np.zeros(6))
    result["nearest"] = "there"
except AttributeError as exc:
    result["nearest"] = str(exc)
""",
    )
    assert len(got["q"]) == 8
    real = Puma560()
    assert all(np.allclose(real.fk(q), real.fk([0.3, -0.4, 0.5, 0.2, 0.6, 0.1])) for q in got["q"])
    assert got["nearest"].startswith("IKSolutions.nearest is not available in this exercise")
    assert got["html"] is True
