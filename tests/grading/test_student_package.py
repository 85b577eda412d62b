"""puma_course.grading.student: the student-side package holds the self-check stub and the allowed names, nothing else.

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
from puma_course.grading.sandbox import choose
from puma_course.grading.student import build, requirements


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
