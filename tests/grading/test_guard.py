"""The tripwire, the second line where an answer must stay within reach: tricks that switch it off fail the case.

The first line is that an answer is not in the student side at all (tests/grading/test_student_package.py);
here an exercise allows ``rodrigues`` and one question forbids it, so the worker's watch is all there is.
"""

from __future__ import annotations

import nbformat
import numpy as np
import pytest

from puma_course.grading import Exercise, Question
from puma_course.grading.run.runner import grade_notebook

KEY = ("puma_course.transforms:rodrigues",)

STEAL = "from puma_course import rodrigues\nimport sys, threading, gc\n"
TRICKS = {
    "plain call": "def turn(a, t):\n    return rodrigues(a, t)",
    "unwrapped": (
        "def turn(a, t):\n    f = rodrigues\n    while hasattr(f, '__wrapped__'):\n        f = f.__wrapped__\n"
        "    return f(a, t)"
    ),
    "setprofile first": "def turn(a, t):\n    sys.setprofile(None)\n    return rodrigues(a, t)",
    "settrace first": "def turn(a, t):\n    sys.settrace(None)\n    sys.setprofile(None)\n    return rodrigues(a, t)",
    "profile put back": (
        "def turn(a, t):\n    p = sys.getprofile()\n    sys.setprofile(None)\n    r = rodrigues(a, t)\n"
        "    sys.setprofile(p)\n    return r"
    ),
    "threading.setprofile first": (
        "def turn(a, t):\n    threading.setprofile(None)\n    box = []\n"
        "    th = threading.Thread(target=lambda: box.append(rodrigues(a, t)))\n    th.start()\n    th.join()\n"
        "    return box[0]"
    ),
    "original through gc": (
        "import types\n"
        "ORIG = [o for o in gc.get_objects() if isinstance(o, types.FunctionType)"
        " and o.__code__.co_name == 'rodrigues' and o is not rodrigues]\n"
        "def turn(a, t):\n    sys.setprofile(None)\n    return (ORIG or [rodrigues])[0](a, t)"
    ),
    "sys.setprofile replaced in a cell": (
        "sys.setprofile = lambda f: None\nsys.getprofile = lambda: None\ndef turn(a, t):\n    return rodrigues(a, t)"
    ),
}


def _exercise() -> Exercise:
    from puma_course import rodrigues

    q = Question(
        "q1",
        "turn",
        1,
        "K(a, t)",
        ((np.array([0.0, 0.0, 1.0]), 0.3), (np.array([1.0, 0.0, 0.0]), -1.2)),
        lambda rng: [],
        reference=lambda a, t: rodrigues(a, t),
        forbidden=KEY,
    )
    return Exercise("ex98_tripwire", "a helper that is also the answer", (q,), allowed=KEY)


@pytest.mark.parametrize("trick", sorted(TRICKS))
def test_switching_the_watch_off_gains_nothing(tmp_path, trick):
    nb = tmp_path / "ex98_tripwire.ipynb"
    cells = [nbformat.v4.new_code_cell(STEAL), nbformat.v4.new_code_cell(TRICKS[trick])]
    nbformat.write(nbformat.v4.new_notebook(cells=cells), nb)
    r = grade_notebook(nb, _exercise())
    notes = " ".join(r.question_notes["q1"])
    assert r.status == "ok" and r.score == 0, (trick, r.status, r.notes, notes)
    assert "used the course package's answer" in notes or "switched off the grader's watch" in notes, notes


def test_an_honest_answer_beside_the_allowed_helper_keeps_its_points(tmp_path):
    """The watch costs an honest answer nothing: its own Rodrigues formula, numpy and a thread-free call."""
    nb = tmp_path / "ex98_tripwire.ipynb"
    code = (
        "import numpy as np\n"
        "def turn(a, t):\n    a = np.asarray(a, float) / np.linalg.norm(a)\n"
        "    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])\n"
        "    return np.eye(3) + np.sin(t) * K + (1 - np.cos(t)) * K @ K"
    )
    nbformat.write(nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)]), nb)
    r = grade_notebook(nb, _exercise())
    assert (r.status, r.score) == ("ok", 1), (r.notes, r.question_notes)


def test_the_tripwire_leaves_no_path_back_to_the_original():
    """install_tripwires' wrapper has no __wrapped__ (the original is found by code object, not through it)."""
    import sys
    import types

    from puma_course.grading.run.worker.guard import forbidden_codes, guarded_call, install_tripwires

    mod = types.ModuleType("puma_course_guard_probe")
    exec("def key(x):\n    '''The answer.'''\n    return 2 * x\n", mod.__dict__)
    sys.modules[mod.__name__] = mod
    try:
        original = mod.key
        spec = f"{mod.__name__}:key"
        codes = forbidden_codes([spec])
        install_tripwires({spec}, {"guard": set(), "hit": None})
        assert mod.key is not original and not hasattr(mod.key, "__wrapped__")
        assert (mod.key.__name__, mod.key.__doc__) == ("key", "The answer.")
        assert guarded_call(lambda x: original(x), (3,), codes) == (6, spec)
        assert guarded_call(lambda x: 3 * x, (3,), codes) == (9, None)
    finally:
        del sys.modules[mod.__name__]


def test_numpy_general_inverses_are_caught_where_a_question_asks_to_do_without_and_numpy_stays_whole(tmp_path):
    """ex01 q4 forbids numpy's general inverses and solvers (inv, pinv, solve, lstsq, ...): a call to one fails the
    case, saying so; the rest of numpy (norm, cross, a transpose) is fine."""
    from puma_course.grading import EXERCISES

    ex = EXERCISES["ex01_rotations"]
    for spec in ("numpy.linalg:inv", "numpy.linalg:pinv", "numpy.linalg:solve", "numpy.linalg:lstsq"):
        assert spec in ex.question("q4").forbidden and spec not in ex.answer_keys, spec
    answers = {
        "np.linalg.inv": "def relative_pose(T_a, T_b):\n    return np.linalg.inv(T_a) @ T_b",
        "imported inv": "from numpy.linalg import inv\ndef relative_pose(T_a, T_b):\n    return inv(T_a) @ T_b",
        "solve": "def relative_pose(T_a, T_b):\n    return np.linalg.solve(T_a, T_b)",
        "pinv": "def relative_pose(T_a, T_b):\n    return np.linalg.pinv(T_a) @ T_b",
        "norm and cross": (
            "def relative_pose(T_a, T_b):\n"
            "    R, p = T_a[:3, :3], T_a[:3, 3]\n"
            "    assert np.isclose(np.linalg.norm(np.cross(R[:, 0], R[:, 1]) - R[:, 2]), 0.0)\n"
            "    inv = np.eye(4)\n"
            "    inv[:3, :3], inv[:3, 3] = R.T, -R.T @ p\n"
            "    return inv @ T_b"
        ),
    }
    scores = {}
    for name, code in answers.items():
        nb = tmp_path / name / "ex01_rotations.ipynb"
        nb.parent.mkdir()
        cells = [
            nbformat.v4.new_code_cell("import numpy as np\nnp.linalg.norm([3.0, 4.0])"),
            nbformat.v4.new_code_cell(code),
        ]
        nbformat.write(nbformat.v4.new_notebook(cells=cells), nb)
        r = grade_notebook(nb, ex)
        assert r.status == "ok", (name, r.notes)
        scores[name] = (r.scores["q4"], " ".join(r.question_notes["q4"]))
    for name, called in (("np.linalg.inv", "inv"), ("imported inv", "inv"), ("solve", "solve"), ("pinv", "pinv")):
        assert (
            scores[name][0] == 0
            and f"called numpy.linalg.{called}, which this question asks you to do without" in scores[name][1]
        ), scores[name]
    assert scores["norm and cross"][0] == 2, scores["norm and cross"]
