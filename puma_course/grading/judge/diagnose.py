"""Naming the mistake: recognise a common wrong answer before the generic "values differ".

A :class:`Mistake` is a key (what the class summary counts, e.g. ``"transposed"``), a title for the
instructor, and a check ``check(got, expected, args, reference) -> message or None`` that says whether
the returned value is exactly what that mistake produces. Most checks rebuild the wrong answer from
the right one (``R.T`` for a transposed rotation, the degrees of an angle, one row negated) or from the
arguments with the mistaken formula (the standard-DH link matrix, the factors in reverse order, the
axis left unnormalised); :func:`matches` turns such a "wrong formula" into a mistake.

:func:`diagnose` tries a question's mistakes in order and returns the first that fits. It runs in the
grader's process on plain numbers; a check that cannot apply (another shape, a failing formula) is
skipped, never raised. :data:`TITLES` names every key the graders emit (here and in
:mod:`puma_course.grading.judge.judges`), so the class summary can say what a key means.

>>> R = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
>>> diagnose((TRANSPOSED, SIGN_FLIP), R.T, R, (), None)[0]
'transposed'
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..remake import made
from .angle_mistakes import DEGREES_OUT, angle_2pi, degrees_in, degrees_out, unit_axis_out
from .mistake import TITLES, Mistake, base_key, close, finite_floats

__all__ = [
    "Mistake",
    "TITLES",
    "base_key",
    "diagnose",
    "diagnose_all",
    "close",
    "matches",
    "matches_set",
    "DUPLICATES",
    "TRANSPOSED",
    "INVERSE",
    "SIGN_FLIP",
    "DEGREES_OUT",
    "sign_flip",
    "degrees_out",
    "degrees_in",
    "angle_2pi",
    "unit_axis_out",
    "negated",
    "TRANSLATION",
    "matches_entries",
]


def diagnose(
    mistakes: Sequence[Mistake], got: Any, expected: Any, args: tuple[Any, ...], reference: Any
) -> tuple[str, str] | None:
    """The first of ``mistakes`` that ``got`` is, as (key, message for the student), or None.

    ``expected`` is the reference value for ``args`` and ``reference`` the question's reference
    function (for checks that recompute it with a mistaken input). A check that raises is skipped.

    >>> diagnose((DEGREES_OUT,), [90.0], np.array([np.pi / 2]), (), None)[0]
    'degrees'
    >>> diagnose((DEGREES_OUT,), [1.0], np.array([2.0]), (), None) is None
    True
    """
    arr = finite_floats(got)
    if arr is None:
        return None
    for mistake in mistakes:
        try:
            message = mistake.check(arr, expected, args, reference)
        except Exception:  # noqa: BLE001 - a check that does not apply to this value says nothing
            continue
        if message:
            return mistake.key, message
    return None


def diagnose_all(
    mistakes: Sequence[Mistake], got: Any, expected: Any, args: tuple[Any, ...], reference: Any
) -> list[tuple[str, str]]:
    """Every one of ``mistakes`` that ``got`` is, as (key, message), in order (the first message per key).

    >>> diagnose_all((DEGREES_OUT, sign_flip()), [-90.0], np.array([np.pi / 2]), (), None)
    []
    >>> [k for k, _ in diagnose_all((DEGREES_OUT, SIGN_FLIP), [-1.0], np.array([1.0]), (), None)]
    ['sign_flip']
    """
    arr = finite_floats(got)
    if arr is None:
        return []
    found: dict[str, str] = {}
    for mistake in mistakes:
        if mistake.key in found:
            continue
        try:
            message = mistake.check(arr, expected, args, reference)
        except Exception:  # noqa: BLE001 - a check that does not apply to this value says nothing
            continue
        if message:
            found[mistake.key] = message
    return list(found.items())


def matches(key: str, message: str, wrong: Callable[..., Any]) -> Mistake:
    """The mistake whose answer is ``wrong(*args)`` (the mistaken formula applied to the same arguments).

    >>> m = matches("order", "reversed", lambda a, b: b @ a)
    >>> A, B = np.diag([1.0, 2.0]), np.array([[0.0, 1.0], [1.0, 0.0]])
    >>> m.check(B @ A, A @ B, (A, B), None)
    'reversed'
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        if isinstance(expected, np.ndarray) and close(expected, wrong(*args)):
            return None  # the mistake gives the right answer here: nothing to say
        return message if close(got, wrong(*args)) else None

    return Mistake(key, made(check, matches, key, message, wrong, attr="check"))


def _transposed(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
    ref = np.asarray(expected, dtype=float)
    if ref.ndim != 2 or ref.shape[0] != ref.shape[1] or ref.shape[0] not in (3, 4) or got.shape != ref.shape:
        return None
    R = ref[:3, :3]
    if close(ref, ref.T):
        return None
    if close(got, ref.T):
        whole = " of the whole 4×4 matrix" if ref.shape[0] == 4 else ""
        return f"you returned the transpose{whole}: column k of a rotation is where the k-th axis goes (lecture 01 §1)"
    if ref.shape[0] == 4 and not close(R, R.T) and close(got[:3, :3], R.T):
        return "the rotation part is transposed (Rᵀ for R): column k of R is where the k-th axis goes (lecture 01 §1)"
    return None


#: A transposed rotation (Rᵀ), or a 4×4 whose rotation block (or whole matrix) is transposed.
TRANSPOSED = Mistake("transposed", _transposed)


def _inverse(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
    ref = np.asarray(expected, dtype=float)
    if ref.shape != (4, 4) or got.shape != (4, 4):
        return None
    R, p = ref[:3, :3], ref[:3, 3]
    inv = np.eye(4)
    inv[:3, :3], inv[:3, 3] = R.T, -R.T @ p
    if close(inv, ref) or not close(got, inv):
        return None
    return "you returned the inverse: the transform maps the child's coordinates into the parent's, not back"


#: The inverse of the expected rigid transform (the frames swapped).
INVERSE = Mistake("inverse", _inverse)


def sign_flip(names: Sequence[str] | None = None) -> Mistake:
    """One row or one column of a matrix (one entry of a vector) negated, the rest right.

    ``names`` name a vector's entries in the message (default "entry i").

    >>> R = np.array([[1.0, 0.0], [0.0, 2.0]])
    >>> sign_flip().check(np.array([[1.0, 0.0], [0.0, -2.0]]), R, (), None)
    'row 2 has the wrong sign (the rest is right): check the sign of the terms in that row'
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        ref = np.asarray(expected, dtype=float)
        if got.shape != ref.shape or ref.ndim not in (1, 2):
            return None
        scale = max(1.0, float(np.max(np.abs(ref))))
        if ref.ndim == 1:
            for i in range(ref.size):
                flipped = ref.copy()
                flipped[i] = -flipped[i]
                if abs(ref[i]) > 1e-6 * scale and close(got, flipped):
                    what = names[i] if names is not None and i < len(names) else f"entry {i + 1}"
                    return f"{what} has the wrong sign (the rest is right)"
            return None
        for axis, word in ((0, "row"), (1, "column")):
            for i in range(ref.shape[axis]):
                flipped = ref.copy()
                line = flipped[i] if axis == 0 else flipped[:, i]
                if np.max(np.abs(line)) <= 1e-6 * scale:
                    continue
                line *= -1.0
                if close(got, flipped):
                    hint = "terms in that row" if axis == 0 else "terms in that column"
                    return f"{word} {i + 1} has the wrong sign (the rest is right): check the sign of the {hint}"
        return None

    return Mistake("sign_flip", made(check, sign_flip, names, attr="check"))


#: :func:`sign_flip` with generic entry names.
SIGN_FLIP = sign_flip()


def matches_set(key: str, message: str, wrong: Callable[..., Any], tol: float = 1e-6) -> Mistake:
    """Like :func:`matches` for an answer that is a set of rows (any order): ``got`` is the rows of ``wrong(*args)``.

    >>> m = matches_set("printed_formula", "printed", lambda: np.array([[1.0, 0.0], [0.0, 1.0]]))
    >>> m.check(np.array([[0.0, 1.0], [1.0, 0.0]]), np.zeros((2, 2)), (), None)
    'printed'
    """

    def same_rows(a: np.ndarray, b: np.ndarray) -> bool:
        if a.ndim != 2 or a.shape != b.shape:
            return False
        scale = max(1.0, float(np.max(np.abs(b))))
        d = np.max(np.abs(a[:, None, :] - b[None, :, :]), axis=-1) <= tol * scale
        return bool(d.any(axis=0).all() and d.any(axis=1).all())

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        bad = np.asarray(wrong(*args), dtype=float)
        if same_rows(np.asarray(expected, dtype=float), bad):
            return None
        return message if same_rows(got, bad) else None

    return Mistake(key, made(check, matches_set, key, message, wrong, tol, attr="check"))


def negated(key: str, message: str) -> Mistake:
    """The whole answer with its sign flipped (for an axis-angle pair, (-k, -θ): the same rotation, outside the range).

    >>> negated("range", "flip both signs").check(np.array([-1.0, 2.0]), np.array([1.0, -2.0]), (), None)
    'flip both signs'
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        return message if close(got, -np.asarray(expected, dtype=float)) else None

    return Mistake(key, made(check, negated, key, message, attr="check"))


def _translation(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
    ref_ = np.asarray(expected, dtype=float)
    if got.shape != (4, 4) or not close(got[:3, :3], ref_[:3, :3]) or close(got[:3, 3], ref_[:3, 3]):
        return None
    return "the rotation part is right, the translation is not: the inverse moves by -Rᵀp (not -p or p)"


#: An inverse transform whose rotation part is right and whose translation is not.
TRANSLATION = Mistake("translation", _translation)


def _duplicates(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
    if got.ndim != 2 or len(got) < 2:
        return None
    scale = max(1.0, float(np.max(np.abs(got))))
    d = np.max(np.abs(got[:, None, :] - got[None, :, :]), axis=-1) <= 1e-9 * scale
    twice = np.argwhere(np.triu(d, k=1))
    if not twice.size:
        return None
    i, j = (int(v) + 1 for v in twice[0])
    return f"rows {i} and {j} are the same: list each answer once"


#: A set answer with the same row twice.
DUPLICATES = Mistake("duplicates", _duplicates)


def matches_entries(
    key: str, message: str, wrong: Callable[..., Any], entries: Sequence[int], angles: Sequence[int] = ()
) -> Mistake:
    """Like :func:`matches`, on the ``entries`` of a flat answer only (``angles`` among them equal modulo 2π).

    For an answer some of whose entries the mistaken formula does not fix: the parameters read off a matrix
    that is not a link matrix, whose d depends on which entries the student read it from.

    >>> m = matches_entries("inverse", "swapped", lambda x: np.array([x, -1.0, 5.0]), [0, 1], angles=[0])
    >>> m.check(np.array([0.5 + 2 * np.pi, -1.0, 7.0]), np.array([0.5, 1.0, 5.0]), (0.5,), None)
    'swapped'
    >>> m.check(np.array([0.5, 1.0, 7.0]), np.array([0.5, 1.0, 5.0]), (0.5,), None) is None
    True
    """
    idx, ang = [int(i) for i in entries], [int(i) for i in angles]

    def same(a: np.ndarray, b: np.ndarray) -> bool:
        a, b = a.reshape(-1), b.reshape(-1)
        if a.size != b.size or not idx or max(idx) >= b.size:
            return False
        diff = a[idx] - b[idx]
        turn = np.array([i in ang for i in idx])
        diff[turn] = np.angle(np.exp(1j * diff[turn]))
        scale = max(1.0, float(np.max(np.abs(b[idx]))))
        return bool(np.max(np.abs(diff)) <= 1e-6 * scale)

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        bad = finite_floats(wrong(*args))
        if bad is None:
            return None
        if isinstance(expected, np.ndarray) and same(np.asarray(expected, dtype=float), bad):
            return None  # the mistake gives the right entries here: nothing to say
        return message if same(got, bad) else None

    return Mistake(key, made(check, matches_entries, key, message, wrong, tuple(idx), tuple(ang), attr="check"))
