"""Input checks shared by every layer of the package.

Every public function validates its arguments here, so that a mistake is reported as a
``ValueError`` naming the argument, what was expected and what arrived, never as a NaN, a
silently dropped imaginary part, an overflow or a numpy broadcasting error three calls later.

The contract, in one place:

* numbers are real and finite: strings, ``None``, booleans, complex numbers, NaN and infinity
  are refused (``np.asarray(z, dtype=float)`` would silently drop an imaginary part);
* lengths and coordinates are at most :data:`MAX_MAGNITUDE` in size, so that their squares,
  and sums of a few squares, stay finite (1e150² = 1e300 < 1.8e308);
* rotations are orthonormal with determinant +1 and transforms are rigid (last row 0 0 0 1);
* tolerances are positive and small; counts are integers; choices are one of the listed words.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = [
    "MAX_MAGNITUDE",
    "check_broadcast",
    "as_array",
    "as_angle",
    "as_rotation",
    "as_transform",
    "as_positive",
    "as_length",
    "as_robot_length",
    "ROBOT_LENGTHS",
    "as_tol",
    "TOL_FLOOR",
    "MAX_COUNT",
    "as_count",
    "as_choice",
    "as_mask",
    "check_magnitude",
    "describe",
]

#: Largest length or coordinate accepted: squares and sums of a few squares stay finite.
MAX_MAGNITUDE = 1e150


def describe(value: Any) -> str:
    """A short description of what arrived, for error messages.

    >>> describe("abc"), describe(None), describe(np.zeros((2, 3)))
    ("str 'abc'", 'None', 'an array of shape (2, 3)')
    """
    if value is None:
        return "None"
    if isinstance(value, (str, bytes)):
        return f"{type(value).__name__} {value!r}"[:120]
    try:
        arr = np.asarray(value)
    except Exception:  # noqa: BLE001 - ragged lists and exotic objects
        return f"a {type(value).__name__} that is not a regular array of numbers"
    if arr.dtype.kind == "c":
        return f"complex numbers ({np.array2string(arr.ravel()[:3], precision=3)}...)"[:120]
    if arr.dtype == object or arr.dtype.kind in "USVb":
        return f"{type(value).__name__} {value!r}"[:120]
    if arr.ndim == 0:
        return f"the number {value!r}"
    return f"an array of shape {arr.shape}"


def _refuse_kind(value: Any, name: str, expected: str) -> None:
    """Raise unless ``value`` converts to real floats without losing anything."""
    if value is None:
        raise ValueError(f"{name}: expected {expected}, got None")
    if isinstance(value, (str, bytes)):
        raise ValueError(f"{name}: expected {expected} of real numbers, got {type(value).__name__} {value!r}")
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name}: expected {expected} of real numbers, got the boolean {value!r}")
    if isinstance(value, (complex, np.complexfloating)):
        raise ValueError(f"{name}: expected {expected} of real numbers, got the complex number {value!r}")


def as_array(
    value: Any,
    name: str,
    shape: tuple[int | None, ...] | None = None,
    *,
    batch: bool = False,
    what: str | None = None,
    max_magnitude: float | None = None,
) -> np.ndarray:
    """Return ``value`` as a finite real float64 array, or raise ``ValueError``.

    ``shape`` gives the trailing shape (``None`` = any size in that place). With ``batch=True``
    one extra leading axis is allowed (a batch of N items). ``what`` describes the expectation in
    the message. ``max_magnitude`` (optional) refuses entries larger in size.

    >>> as_array([1, 2, 3], "p", (3,))
    array([1., 2., 3.])
    >>> as_array([1 + 2j, 0, 0], "p", (3,))
    Traceback (most recent call last):
    ...
    ValueError: p: expected shape (3,) of real numbers, got complex numbers [1.+2.j 0.+0.j 0.+0.j]
    """
    if shape is not None:
        trail = ", ".join("n" if s is None else str(s) for s in shape) + ("," if len(shape) == 1 else "")
        default = f"shape ({trail})" + (f" or (N, {trail.rstrip(',')})" if batch and shape else "")
    else:
        default = "numbers"
    expected = what or default
    _refuse_kind(value, name, expected)
    if isinstance(value, np.ndarray) and value.dtype == np.float64:
        arr = value
    else:
        try:
            raw = np.asarray(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name}: expected {expected} of real numbers, got {describe(value)}") from None
        kind = raw.dtype.kind
        if kind == "c":
            shown = np.array2string(raw.ravel()[:3], precision=3)
            raise ValueError(f"{name}: expected {expected} of real numbers, got complex numbers {shown}")
        if kind == "b":
            raise ValueError(f"{name}: expected {expected} of real numbers, got booleans")
        if kind not in "iuf":
            if kind == "O":
                for item in raw.flat:
                    _refuse_kind(item, name, expected)
            try:
                raw = np.asarray(raw, dtype=float)
            except (TypeError, ValueError, OverflowError):
                raise ValueError(f"{name}: expected {expected} of real numbers, got {describe(value)}") from None
        arr = np.asarray(raw, dtype=float)
    if shape is not None:
        nd = len(shape)
        ok_nd = arr.ndim == nd or (batch and arr.ndim == nd + 1)
        ok = ok_nd and all(s is None or s == a for s, a in zip(shape, arr.shape[arr.ndim - nd :], strict=True))
        if not ok:
            raise ValueError(f"{name}: expected {expected}, got an array of shape {arr.shape}")
    if not np.isfinite(arr).all():
        where = arr.tolist() if arr.size <= 16 else "the array"
        raise ValueError(f"{name}: expected finite numbers, got NaN or infinity in {where}")
    if max_magnitude is not None:
        check_magnitude(arr, name, max_magnitude)
    return arr


def as_angle(value: Any, name: str = "angle") -> np.ndarray:
    """Return ``value`` as angles in radians: a number (shape ()) or an array of shape (N,).

    >>> as_angle([0.1, 0.2], "phi")
    array([0.1, 0.2])
    >>> as_angle(np.zeros((2, 2)), "phi")
    Traceback (most recent call last):
    ...
    ValueError: phi: expected a number or an array of shape (N,), got an array of shape (2, 2)
    """
    t = as_array(value, name, what="an angle in radians (a number, or an array of shape (N,))")
    if t.ndim > 1:
        raise ValueError(f"{name}: expected a number or an array of shape (N,), got an array of shape {t.shape}")
    return t


def check_magnitude(arr: np.ndarray, name: str, limit: float = MAX_MAGNITUDE) -> None:
    """Raise ``ValueError`` if an entry of ``arr`` exceeds ``limit`` in size (its square would overflow).

    >>> check_magnitude(np.array([1e200]), "p")
    Traceback (most recent call last):
    ...
    ValueError: p: expected values of size at most 1e+150 (their squares must stay finite), got 1e+200
    """
    if arr.size and float(np.max(np.abs(arr))) > limit:
        raise ValueError(
            f"{name}: expected values of size at most {limit:g} (their squares must stay finite), "
            f"got {float(np.max(np.abs(arr))):g}"
        )


def as_rotation(value: Any, name: str, *, batch: bool = False, tol: float = 1e-6) -> np.ndarray:
    """Return ``value`` as a 3x3 rotation matrix (orthonormal, det +1), or (N, 3, 3) with ``batch``.

    >>> as_rotation(np.diag([1.0, 1.0, -1.0]), "R")
    Traceback (most recent call last):
    ...
    ValueError: R: expected a rotation (det +1), got a reflection (det -1)
    """
    R = as_array(value, name, (3, 3), batch=batch, what="a 3x3 rotation matrix" + (" or (N, 3, 3)" if batch else ""))
    err = np.abs(np.swapaxes(R, -1, -2) @ R - np.eye(3)).max(axis=(-2, -1))
    if np.any(err > tol):
        raise ValueError(
            f"{name}: expected a rotation matrix (R^T R = I within {tol:g}), "
            f"but R^T R differs from I by {float(np.max(err)):.3g}"
        )
    # the determinant of an orthonormal matrix is ±1: only its sign matters, far from 0
    det = (
        R[..., 0, 0] * (R[..., 1, 1] * R[..., 2, 2] - R[..., 1, 2] * R[..., 2, 1])
        - R[..., 0, 1] * (R[..., 1, 0] * R[..., 2, 2] - R[..., 1, 2] * R[..., 2, 0])
        + R[..., 0, 2] * (R[..., 1, 0] * R[..., 2, 1] - R[..., 1, 1] * R[..., 2, 0])
    )
    if np.any(det < 0):
        raise ValueError(f"{name}: expected a rotation (det +1), got a reflection (det {float(np.min(det)):.3g})")
    return R


def _rigid_fast(value: Any, tol: float) -> bool:
    """True when ``value`` is one float64 4x4 rigid transform (the hot single-pose path of the
    solvers): the same checks as the general path, in plain floats, at a fraction of the cost."""
    if type(value) is not np.ndarray or value.shape != (4, 4) or value.dtype != np.float64:
        return False
    (r11, r12, r13, px), (r21, r22, r23, py), (r31, r32, r33, pz), last = value.tolist()
    if last != [0.0, 0.0, 0.0, 1.0]:
        return False
    entries = (r11, r12, r13, r21, r22, r23, r31, r32, r33)
    if not all(math.isfinite(v) for v in entries) or not all(math.isfinite(v) and abs(v) <= MAX_MAGNITUDE
                                                             for v in (px, py, pz)):  # fmt: skip
        return False
    cols = ((r11, r21, r31), (r12, r22, r32), (r13, r23, r33))
    for i in range(3):
        for j in range(i, 3):
            a, b = cols[i], cols[j]
            if abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2] - (i == j)) > tol:
                return False
    det = r11 * (r22 * r33 - r23 * r32) - r12 * (r21 * r33 - r23 * r31) + r13 * (r21 * r32 - r22 * r31)
    return det > 0


def as_transform(value: Any, name: str, *, batch: bool = False, tol: float = 1e-6) -> np.ndarray:
    """Return ``value`` as a 4x4 rigid homogeneous transform, or raise ``ValueError``.

    Checks: shape (4, 4) (or (N, 4, 4) with ``batch``), finite real entries, last row
    0 0 0 1 (within ``tol``), an orthonormal rotation part with det +1, and a translation
    no larger than :data:`MAX_MAGNITUDE`.

    >>> as_transform(np.ones((4, 4)), "T")
    Traceback (most recent call last):
    ...
    ValueError: T: expected the last row of a homogeneous transform to be [0, 0, 0, 1], got [1.0, 1.0, 1.0, 1.0]
    """
    if _rigid_fast(value, tol):
        return value
    what = "a 4x4 homogeneous transform" + (" or (N, 4, 4)" if batch else "")
    T = as_array(value, name, (4, 4), batch=batch, what=what)
    last = T[..., 3, :]
    if np.any(np.abs(last - np.array([0.0, 0.0, 0.0, 1.0])) > tol):
        bad = last.reshape(-1, 4)[int(np.argmax(np.abs(last - [0, 0, 0, 1]).reshape(-1, 4).max(axis=1)))]
        raise ValueError(
            f"{name}: expected the last row of a homogeneous transform to be [0, 0, 0, 1], "
            f"got {np.round(bad, 6).tolist()}"
        )
    as_rotation(T[..., :3, :3], f"{name} (rotation part)", batch=batch, tol=tol)
    check_magnitude(T[..., :3, 3], f"{name} (translation part)")
    return T


def as_positive(value: Any, name: str) -> float:
    """Return ``value`` as a positive finite float (at most :data:`MAX_MAGNITUDE`), or raise.

    >>> as_positive(2, "l1")
    2.0
    """
    return as_length(value, name, positive=True)


def as_length(value: Any, name: str, *, positive: bool = False, what: str | None = None) -> float:
    """Return ``value`` as one finite length (at most :data:`MAX_MAGNITUDE` in size), or raise.

    With ``positive=True`` zero and negative values are refused too.

    >>> as_length(-0.1, "d3")
    -0.1
    >>> as_length(0, "a2", positive=True)
    Traceback (most recent call last):
    ...
    ValueError: a2: expected a positive length, got 0.0
    """
    arr = as_array(value, name, (), what=what or ("a single positive number" if positive else "a single number"))
    x = float(arr)
    check_magnitude(arr, name)
    if positive and not x > 0:
        raise ValueError(f"{name}: expected a positive length, got {x}")
    return x


#: Sizes accepted for a closed-form robot's non-zero lengths: its solvers form fourth powers of lengths
#: (and of coordinates of that size), which must neither overflow nor underflow in float64.
ROBOT_LENGTHS = (1e-50, 1e50)


def as_robot_length(value: Any, name: str, *, positive: bool = False, what: str | None = None) -> float:
    """A robot's length: :func:`as_length`, and zero or between 1e-50 and 1e50 in size.

    >>> as_robot_length(1.5e100, "l1")
    Traceback (most recent call last):
    ...
    ValueError: l1: expected 0 or a size from 1e-50 to 1e+50 (its 4th power must stay finite), got 1.5e+100
    """
    x = as_length(value, name, positive=positive, what=what)
    lo, hi = ROBOT_LENGTHS
    if x != 0.0 and not lo <= abs(x) <= hi:
        why = "its 4th power must stay finite"
        raise ValueError(f"{name}: expected 0 or a size from {lo:g} to {hi:g} ({why}), got {x:g}")
    return x


#: Smallest tolerance accepted anywhere: a few units of float64 rounding (2.2e-16) of a quantity of size 1.
#: Below it a tolerance cannot be honoured and would only switch a singularity or equality test off (issue 21).
TOL_FLOOR = 1e-15


def as_tol(value: Any, name: str = "tol", *, upper: float = 1e-2, lower: float = TOL_FLOOR) -> float:
    """Return ``value`` as a tolerance: a finite number with ``lower`` <= tol <= ``upper`` (and tol > 0).

    A tolerance decides what counts as singular or equal; NaN, negative or huge values would
    silently switch those decisions off or on for every input, so they are refused; so is a
    tolerance below ``lower``, what float64 rounding of the quantity it is compared with can honour
    (:data:`TOL_FLOOR` unless the caller knows better).

    >>> as_tol(1e-16, lower=1e-12)
    Traceback (most recent call last):
    ...
    ValueError: tol: expected a tolerance with 1e-12 <= tol <= 0.01 (float64 cannot honour less), got 1e-16

    >>> as_tol(1e-9)
    1e-09
    >>> as_tol(float("inf"))
    Traceback (most recent call last):
    ...
    ValueError: tol: expected finite numbers, got NaN or infinity in inf
    """
    if type(value) is float and 0.0 < value <= upper and value >= lower:
        return value  # the common case, checked in plain floats
    x = float(as_array(value, name, (), what=f"a small positive tolerance (0 < {name} <= {upper:g})"))
    if not 0.0 < x <= upper:
        raise ValueError(f"{name}: expected a small positive tolerance (0 < {name} <= {upper:g}), got {x:g}")
    if x < lower:
        why = "float64 cannot honour less"
        raise ValueError(f"{name}: expected a tolerance with {lower:g} <= {name} <= {upper:g} ({why}), got {x:g}")
    return x


#: Largest count accepted (samples, steps, bins): larger ones cannot be held in memory anyway.
MAX_COUNT = 10**8


def as_count(value: Any, name: str, *, minimum: int = 0, maximum: int = MAX_COUNT) -> int:
    """Return ``value`` as an integer in [``minimum``, ``maximum``]; a fractional number is refused, not truncated.

    >>> as_count(5, "n", minimum=2)
    5
    >>> as_count(2.5, "n")
    Traceback (most recent call last):
    ...
    ValueError: n: expected a whole number, got 2.5
    """
    if isinstance(value, (bool, np.bool_)) or value is None or isinstance(value, (str, bytes)):
        raise ValueError(f"{name}: expected a whole number >= {minimum}, got {describe(value)}")
    if isinstance(value, (int, np.integer)):
        n = int(value)
    else:
        x = float(as_array(value, name, (), what=f"a whole number >= {minimum}"))
        if not x.is_integer():
            raise ValueError(f"{name}: expected a whole number, got {x:g}")
        n = int(x)
    # a huge integer has no float (10**400) and no decimal text past 4,300 digits: say its size (issue 31)
    huge = n.bit_length() >= 1000
    size = f"about {'-' if n < 0 else ''}10^{int(n.bit_length() * 0.30103)}"
    if n < minimum:
        raise ValueError(f"{name}: expected a whole number >= {minimum}, got {size if huge else n}")
    if n > maximum:
        shown = size if huge else f"{n:g}"
        raise ValueError(f"{name}: expected a whole number from {minimum} to {maximum:g}, got {shown}")
    return n


def as_choice(value: Any, name: str, choices: Sequence[str]) -> str:
    """Return ``value`` if it is one of the words ``choices``, else raise ``ValueError``.

    >>> as_choice("up", "elbow", ("up", "down"))
    'up'
    >>> as_choice(np.array(["up"]), "elbow", ("up", "down"))
    Traceback (most recent call last):
    ...
    ValueError: elbow: expected one of 'up', 'down', got ndarray array(['up'], dtype='<U2')
    """
    if not isinstance(value, str) or value not in choices:
        listed = ", ".join(repr(c) for c in choices)
        got = repr(value) if isinstance(value, str) else describe(value)
        raise ValueError(f"{name}: expected one of {listed}, got {got}")
    return value


def as_mask(value: Any, name: str, n: int) -> np.ndarray:
    """Return ``value`` as a boolean mask of shape (n,); integers or other types are refused.

    >>> as_mask([True, False], "revolute", 2)
    array([ True, False])
    """
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        arr = np.asarray(None)
    if arr.dtype != bool or arr.shape != (n,):
        got = f"dtype {arr.dtype} and shape {arr.shape}" if arr.dtype != object else describe(value)
        raise ValueError(f"{name}: expected a boolean mask of shape ({n},) (one True/False per joint), got {got}")
    return arr


def check_broadcast(**shapes: tuple[int, ...]) -> tuple[int, ...]:
    """The common batch shape of arguments that broadcast together, or a ``ValueError`` naming them
    (not numpy's "operands could not be broadcast" three calls later; issue 21).

    >>> check_broadcast(phi=(2,), theta=(), psi=(2,))
    (2,)
    >>> check_broadcast(phi=(2,), theta=(3,))
    Traceback (most recent call last):
    ...
    ValueError: phi, theta: expected batch shapes that broadcast together, got phi (2,), theta (3,)
    """
    try:
        return tuple(np.broadcast_shapes(*shapes.values()))
    except ValueError:
        names = ", ".join(shapes)
        got = ", ".join(f"{n} {tuple(s)}" for n, s in shapes.items())
        raise ValueError(f"{names}: expected batch shapes that broadcast together, got {got}") from None
