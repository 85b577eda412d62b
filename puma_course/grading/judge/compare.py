"""How a returned value is judged: ``compare(got, expected)`` is None when right, else the reason why not.

Comparisons run in the grader's process on plain numbers brought back from the student's
process. They are lenient where the mathematics is (a squeezable shape, angles modulo 2π, a set
of solutions in any order) and say precisely what is wrong otherwise.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..remake import made

__all__ = ["Comparison", "compare_close", "compare_angles", "compare_angles_at", "compare_solution_set"]

#: ``compare(got, expected)``: None if ``got`` is right, else a short reason for the student.
Comparison = Callable[[Any, np.ndarray], str | None]


def _as_float_array(value: Any) -> np.ndarray | None:
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None


def _match_shape(got: np.ndarray, ref: np.ndarray) -> np.ndarray | None:
    if got.shape == ref.shape:
        return got
    if got.size == ref.size and np.squeeze(got).shape == np.squeeze(ref).shape:
        return got.reshape(ref.shape)
    return None


def compare_close(got: Any, ref: np.ndarray, tol: float = 1e-6) -> str | None:
    """None if ``got`` equals ``ref`` within ``tol`` (relative to the size of ``ref``), else why not.

    >>> compare_close([1.0, 2.0], np.array([1.0, 2.0])) is None
    True
    >>> compare_close([1.0], np.array([1.0, 2.0]))
    'returned shape (1,), expected shape (2,)'
    """
    shaped, problem = _numbers_like(got, ref)
    if problem:
        return problem
    ref = np.asarray(ref, dtype=float)
    scale = max(1.0, float(np.max(np.abs(ref)))) if ref.size else 1.0
    err = float(np.max(np.abs(shaped - ref))) if ref.size else 0.0
    if err > tol * scale:
        return f"values differ from the reference by up to {err:.3g}{_where(np.abs(shaped - ref))}"
    return None


def _numbers_like(got: Any, ref: Any) -> tuple[np.ndarray, str | None]:
    """``got`` as finite floats in the shape of ``ref``, or the problem in words (and an empty array)."""
    arr = _as_float_array(got)
    if arr is None:
        return np.zeros(0), "did not return numbers"
    ref = np.asarray(ref, dtype=float)
    shaped = _match_shape(arr, ref)
    if shaped is None:
        return np.zeros(0), f"returned shape {arr.shape}, expected shape {ref.shape}"
    if not np.all(np.isfinite(shaped)):
        return np.zeros(0), "returned NaN or infinity"
    return shaped, None


def _where(diff: np.ndarray) -> str:
    """' (largest at index [i, j])' for an array of differences with more than one entry, else ''.

    >>> _where(np.array([[0.0, 0.1], [0.9, 0.0]]))
    ' (largest at index [1, 0])'
    """
    if diff.size <= 1:
        return ""
    index = np.unravel_index(int(np.argmax(diff)), diff.shape)
    return f" (largest at index [{', '.join(str(int(i)) for i in index)}])"


def compare_angles(got: Any, ref: np.ndarray, tol: float = 1e-6) -> str | None:
    """Like :func:`compare_close` but angles equal modulo 2π count as equal.

    >>> compare_angles([2 * np.pi + 0.5], np.array([0.5])) is None
    True
    """
    shaped, problem = _numbers_like(got, ref)
    if problem:
        return problem
    ref = np.asarray(ref, dtype=float)
    diff = np.angle(np.exp(1j * (shaped - ref)))
    err = float(np.max(np.abs(diff))) if ref.size else 0.0
    if err > tol:
        return f"angles differ from the reference by up to {err:.3g} rad{_where(np.abs(diff))}"
    return None


def compare_angles_at(indices: Sequence[int], tol: float = 1e-6) -> Comparison:
    """Like :func:`compare_close` on a flat vector whose entries ``indices`` are angles (equal modulo 2π).

    >>> cmp = compare_angles_at([0])
    >>> cmp([0.5 + 2 * np.pi, 3.0], np.array([0.5, 3.0])) is None, cmp([0.5, 3.0 + 2 * np.pi], np.array([0.5, 3.0]))
    (True, 'values differ from the reference by up to 6.28 (largest at index [1])')
    """
    idx = np.asarray(indices, dtype=int)

    def compare(got: Any, ref: np.ndarray) -> str | None:
        arr = _as_float_array(got)
        if arr is None:
            return "did not return numbers"
        ref = np.asarray(ref, dtype=float)
        shaped = _match_shape(arr, ref)
        if shaped is None:
            return f"returned shape {arr.shape}, expected shape {ref.shape}"
        if not np.all(np.isfinite(shaped)):
            return "returned NaN or infinity"
        diff = (shaped - ref).reshape(-1)
        diff[idx] = np.angle(np.exp(1j * diff[idx]))
        scale = max(1.0, float(np.max(np.abs(ref)))) if ref.size else 1.0
        err = float(np.max(np.abs(diff))) if ref.size else 0.0
        if err > tol * scale:
            return f"values differ from the reference by up to {err:.3g}{_where(np.abs(diff))}"
        return None

    return made(compare, compare_angles_at, indices, tol)


def compare_solution_set(angle_columns: Sequence[int], tol: float = 1e-6) -> Comparison:
    """A comparison of two sets of rows (joint vectors, points), any order; listed columns are angles (mod 2π).

    Every expected row must be returned, once: a row listed twice fails (the count differs).

    >>> cmp = compare_solution_set([0])
    >>> cmp([[0.1, 2.0], [7.0, 1.0]], np.array([[7.0 - 2 * np.pi, 1.0], [0.1, 2.0]])) is None
    True
    >>> cmp([[0.1, 2.0], [0.1, 2.0], [7.0, 1.0]], np.array([[7.0 - 2 * np.pi, 1.0], [0.1, 2.0]]))
    'returned 3 rows for the 2 expected'
    """
    cols = np.asarray(angle_columns, dtype=int)

    def compare(got: Any, ref: np.ndarray) -> str | None:
        arr = _as_float_array(got)
        if arr is None:
            return "did not return numbers"
        ref = np.asarray(ref, dtype=float)
        if arr.ndim != 2 or arr.shape[1:] != ref.shape[1:]:
            return f"returned shape {arr.shape}, expected (k, {ref.shape[1]}) rows of joint values"
        if not np.all(np.isfinite(arr)):
            return "returned NaN or infinity"

        def dist(a: np.ndarray, b: np.ndarray) -> np.ndarray:
            d = np.abs(a[:, None, :] - b[None, :, :])
            d[..., cols] = np.abs(np.angle(np.exp(1j * (a[:, None, cols] - b[None, :, cols]))))
            return d.max(axis=-1)

        n_ref, n_got = ref.shape[0], arr.shape[0]
        missed = int(np.sum(dist(ref, arr).min(axis=1) > tol)) if n_ref and n_got else n_ref
        if missed and n_ref and n_got:
            wrong = np.flatnonzero(dist(arr, ref).min(axis=1) > tol)
            if wrong.size:
                # say what differs: the first returned row that is none of the expected ones, and by how much
                i = int(wrong[0])
                j = int(np.argmin(dist(arr[i : i + 1], ref)[0]))
                off = float(dist(arr[i : i + 1], ref[j : j + 1])[0, 0])
                return (
                    f"row {i + 1} of yours is none of the {n_ref} expected rows: it is off by up to {off:.3g} from "
                    f"the nearest one ({missed} expected row(s) missing)"
                )
        if missed:
            return f"misses {missed} of the {n_ref} expected rows (you returned {n_got})"
        extra = int(np.sum(dist(arr, ref).min(axis=1) > tol)) if n_ref and n_got else n_got
        if extra:
            return (
                f"{extra} of the {n_got} rows returned are not a solution asked for here "
                f"(the expected set has {n_ref} rows)"
            )
        if n_got != n_ref:
            return f"returned {n_got} rows for the {n_ref} expected"
        return None

    return made(compare, compare_solution_set, angle_columns, tol)
