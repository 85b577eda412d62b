"""The tripwire, the second line where an answer must stay within reach: tricks that switch it off fail the case.

The first line is that an answer is not in the student side at all (tests/grading/run/test_student_package.py);
here an exercise allows ``rodrigues`` and one question forbids it, so the worker's watch is all there is.
"""

from __future__ import annotations

import nbformat
import numpy as np
import pytest

from puma_course.grading import Exercise, Question
from puma_course.grading.run.runner import grade_notebook
from puma_course.grading.run.worker.guard import forbidden_codes, guarded_call

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


#: numpy's Python implementation of ``name``, found through gc (the grader replaces every name it had in numpy).
IMPL = (
    "import gc, types\n"
    "def impl(name):\n"
    "    return [o for o in gc.get_objects() if isinstance(o, types.FunctionType) and o.__name__ == name\n"
    "            and o.__module__ == 'numpy.linalg._linalg' and 'a' in o.__code__.co_varnames][0]\n"
)

#: Routes to a general inverse or solver that do not go through ``np.linalg.inv``'s own name (issue 30): numpy's
#: compiled ufuncs and lapack_lite reached every way a student can, and rebuilt or pasted copies of numpy's code.
ROUTES = {
    "_umath_linalg.inv": (
        "def relative_pose(T_a, T_b):\n    return np.linalg._umath_linalg.inv(T_a, signature='d->d') @ T_b"
    ),
    "_umath_linalg.solve": (
        "def relative_pose(T_a, T_b):\n    return np.linalg._umath_linalg.solve(T_a, T_b, signature='dd->d')"
    ),
    "_umath_linalg.solve1": (
        "def relative_pose(T_a, T_b):\n    s = np.linalg._umath_linalg.solve1\n"
        "    return np.stack([s(T_a, T_b[:, j], signature='dd->d') for j in range(4)], axis=1)"
    ),
    "_umath_linalg.lstsq": (
        "def relative_pose(T_a, T_b):\n"
        "    return np.linalg._umath_linalg.lstsq(T_a, T_b, -1.0, signature='ddd->ddid')[0]"
    ),
    "through sys.modules": (
        "import sys\ndef relative_pose(T_a, T_b):\n"
        "    return sys.modules['numpy.linalg._umath_linalg'].inv(T_a, signature='d->d') @ T_b"
    ),
    "through importlib, imported again": (
        "import importlib\ndef relative_pose(T_a, T_b):\n"
        "    m = importlib.reload(importlib.import_module('numpy.linalg._umath_linalg'))\n"
        "    return m.inv(T_a, signature='d->d') @ T_b"
    ),
    "imported by name in a cell": (
        "from numpy.linalg._umath_linalg import solve as _s\n"
        "def relative_pose(T_a, T_b):\n    return _s(T_a, T_b, signature='dd->d')"
    ),
    "partial and map": (
        "import functools\nINV = functools.partial(np.linalg._umath_linalg.inv, signature='d->d')\n"
        "def relative_pose(T_a, T_b):\n    return list(map(INV, [T_a]))[0] @ T_b"
    ),
    "dug out of the wrapper and gc": (
        "import gc\nw = np.linalg._umath_linalg.inv\n"
        "found = [c.cell_contents for c in (getattr(w, '__closure__', None) or ())"
        " if isinstance(c.cell_contents, np.ufunc)]\n"
        "found += [r for o in gc.get_objects() for r in gc.get_referents(o)"
        " if isinstance(r, np.ufunc) and r.__name__ == 'inv']\n"
        "INV = (found or [w])[0]\n"
        "def relative_pose(T_a, T_b):\n    return INV(T_a, signature='d->d') @ T_b"
    ),
    "lapack_lite.dgelsd": (
        "from numpy.linalg import lapack_lite\n"
        "def relative_pose(T_a, T_b):\n"
        "    a, b = np.ascontiguousarray(T_a.T), np.ascontiguousarray(T_b.T)\n"
        "    s, work, iwork = np.zeros(4), np.zeros(1000), np.zeros(1000, dtype=np.intc)\n"
        "    lapack_lite.dgelsd(4, 4, 4, a, 4, b, 4, s, -1.0, 0, work, 1000, iwork, 0)\n"
        "    return b.T"
    ),
    "dgelsd found through gc, called by partial": (
        "import gc, functools\n"
        "from numpy.linalg import lapack_lite\n"
        "C = [o for o in gc.get_objects() if type(o) is type(len) and o.__name__ == 'dgelsd'] or [lapack_lite.dgelsd]\n"
        "def relative_pose(T_a, T_b):\n"
        "    a, b = np.ascontiguousarray(T_a.T), np.ascontiguousarray(T_b.T)\n"
        "    s, work, iwork = np.zeros(4), np.zeros(1000), np.zeros(1000, dtype=np.intc)\n"
        "    functools.partial(C[0], 4, 4, 4, a, 4, b, 4, s, -1.0, 0, work, 1000, iwork, 0)()\n"
        "    return b.T"
    ),
    "inv rebuilt from its code object": (
        "import types\n" + IMPL + "f = impl('inv')\n"
        "INV = types.FunctionType(f.__code__.replace(co_firstlineno=7), f.__globals__, 'mine')\n"
        "def relative_pose(T_a, T_b):\n    return INV(T_a) @ T_b"
    ),
    "pinv rebuilt with its own globals": (
        "import types\n" + IMPL + "f = impl('pinv')\n"
        "g = dict(f.__globals__)\n"
        "PINV = types.FunctionType(f.__code__.replace(co_firstlineno=3, co_name='p', co_filename='<cell 2>'), g,"
        " 'p', f.__defaults__)\n"
        "PINV.__kwdefaults__ = f.__kwdefaults__\n"
        "def relative_pose(T_a, T_b):\n    return PINV(T_a) @ T_b"
    ),
    "pinv's source pasted and run": (
        "import inspect, textwrap\n" + IMPL + "f = impl('pinv')\n"
        "src = textwrap.dedent(inspect.getsource(f))\nsrc = src[src.index('def '):]\n"
        "g = dict(f.__globals__)\nexec(compile(src, '<cell 2>', 'exec'), g)\n"
        "def relative_pose(T_a, T_b):\n    return g['pinv'](T_a) @ T_b"
    ),
    "matrix_power -1": "def relative_pose(T_a, T_b):\n    return np.linalg.matrix_power(T_a, -1) @ T_b",
    "np.matrix .I": "def relative_pose(T_a, T_b):\n    return np.asarray(np.matrix(T_a).I) @ T_b",
}

HONEST = {
    "norm, cross, det and svd": (
        "def relative_pose(T_a, T_b):\n"
        "    R, p = T_a[:3, :3], T_a[:3, 3]\n"
        "    assert np.isclose(np.linalg.norm(np.cross(R[:, 0], R[:, 1]) - R[:, 2]), 0.0)\n"
        "    assert np.isclose(np.linalg.det(R), 1.0) and np.allclose(np.linalg.svd(R)[1], 1.0)\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3], out[:3, 3] = R.T, -R.T @ p\n"
        "    return out @ T_b"
    ),
}


def _grade_q4(tmp_path, name, code):
    from puma_course.grading import EXERCISES

    nb = tmp_path / name.replace(" ", "_") / "ex01_rotations.ipynb"
    nb.parent.mkdir()
    cells = [nbformat.v4.new_code_cell("import numpy as np"), nbformat.v4.new_code_cell(code)]
    nbformat.write(nbformat.v4.new_notebook(cells=cells), nb)
    r = grade_notebook(nb, EXERCISES["ex01_rotations"])
    assert r.status == "ok", (name, r.notes)
    return r.scores["q4"], " ".join(r.question_notes["q4"])


@pytest.mark.parametrize("route", sorted(ROUTES))
def test_numpy_c_routes_and_copies_of_a_general_inverse_earn_nothing(tmp_path, route):
    """Each route computes the right pose (checked here, outside the grader), and earns 0 with the tripwire's words."""
    T_a = np.array([[0.0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]])
    T_b = np.array([[1.0, 0, 0, 0.5], [0, 0, -1, -1], [0, 1, 0, 0.25], [0, 0, 0, 1]])
    ns: dict = {"np": np}
    exec(ROUTES[route], ns)
    assert np.allclose(T_a @ ns["relative_pose"](T_a, T_b), T_b), route  # the route works: it is a real attack
    score, notes = _grade_q4(tmp_path, route, ROUTES[route])
    assert score == 0 and "which this question asks you to do without" in notes, (route, score, notes)


@pytest.mark.parametrize("name", sorted(HONEST))
def test_the_rest_of_numpy_linalg_stays_usable_where_general_inverses_are_watched(tmp_path, name):
    assert _grade_q4(tmp_path, name, HONEST[name])[0] == 2


def test_a_copy_is_matched_by_its_bytecode_and_names_not_by_where_it_came_from():
    import types

    from puma_course.grading.run.worker.guard import fingerprint

    f = np.linalg._linalg.inv._implementation
    codes = forbidden_codes(["numpy.linalg:inv"])
    moved = types.FunctionType(f.__code__.replace(co_firstlineno=1, co_filename="<cell 1>", co_name="x"), f.__globals__)
    assert moved.__code__ not in codes  # what the tripwire missed: equality counts line numbers
    assert guarded_call(moved, (np.eye(3) * 2,), codes)[1] == "numpy.linalg:inv"
    assert fingerprint(f.__code__) != fingerprint(np.linalg._linalg.pinv._implementation.__code__)
    honest = "def inv(a):\n    a = np.asarray(a)\n    return a.T\n"
    ns: dict = {"np": np}
    exec(honest, ns)
    assert guarded_call(ns["inv"], (np.eye(3),), codes)[1] is None  # a function of the same name is not a copy
