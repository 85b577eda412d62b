"""The mistakes of angles and axes: degrees where radians were expected (returned or given), an angle off by a
whole turn, an axis not of length 1 (:mod:`.diagnose` re-exports them).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ..remake import made
from .mistake import Mistake, close

__all__ = ["DEGREES_OUT", "angle_2pi", "degrees_in", "degrees_out", "unit_axis_out"]


def degrees_out(indices: Sequence[int] | None = None) -> Mistake:
    """Angles returned in degrees: ``got`` is the answer with the entries ``indices`` (default all) in degrees.

    >>> degrees_out([1]).check(np.array([2.0, 90.0]), np.array([2.0, np.pi / 2]), (), None)[:28]
    'the angles you returned look'
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        ref = np.asarray(expected, dtype=float)
        if got.size != ref.size:
            return None
        flat = ref.reshape(-1).copy()
        idx = list(range(flat.size)) if indices is None else list(indices)
        if np.max(np.abs(flat[idx]), initial=0.0) < 1e-3:
            return None
        flat[idx] = np.degrees(flat[idx])
        if close(got.reshape(-1), flat):
            return "the angles you returned look like degrees: the course works in radians (no np.degrees)"
        return None

    return Mistake("degrees", made(check, degrees_out, indices, attr="check"))


#: Every returned number taken as an angle in degrees.
DEGREES_OUT = degrees_out()


def degrees_in(*positions: int) -> Mistake:
    """The arguments at ``positions`` (angles in radians) used as if they were degrees (``np.radians`` applied).

    >>> m = degrees_in(0)
    >>> m.check(np.array([np.cos(np.radians(0.5))]), np.array([np.cos(0.5)]), (0.5,), lambda t: [np.cos(t)])[:24]
    'your result is what the '
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        changed = tuple(np.radians(np.asarray(a, dtype=float)) if i in positions else a for i, a in enumerate(args))
        if close(got, reference(*changed)):
            return (
                "your result is what the formula gives for angles in degrees: the angles you receive are "
                "radians already, and np.cos/np.sin take radians (no np.radians)"
            )
        return None

    return Mistake("degrees", made(check, degrees_in, *positions, attr="check"))


def angle_2pi(indices: Sequence[int] | None = None, where: str = "the range asked for") -> Mistake:
    """Angles (the entries ``indices``, default all) off by a non-zero whole number of turns.

    >>> angle_2pi().check(np.array([0.5 + 2 * np.pi]), np.array([0.5]), (), None)[:30]
    'the angle is right up to a who'
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        ref = np.asarray(expected, dtype=float).reshape(-1)
        g = got.reshape(-1)
        if g.size != ref.size:
            return None
        idx = np.arange(ref.size) if indices is None else np.asarray(indices)
        turns = (g[idx] - ref[idx]) / (2 * np.pi)
        whole = np.round(turns)
        rest = np.delete(np.arange(ref.size), idx)
        if np.all(np.abs(turns - whole) < 1e-7) and np.any(whole != 0) and close(g[rest], ref[rest]):
            return f"the angle is right up to a whole turn (off by 2π): return it in {where}"
        return None

    return Mistake("angle_2pi", made(check, angle_2pi, indices, where, attr="check"))


def unit_axis_out(stop: int = 3, what: str = "axis") -> Mistake:
    """The axis (the first ``stop`` entries) in the right direction but not of length 1 (``what``: its name).

    >>> unit_axis_out().check(np.array([0.0, 0.0, 2.0, 1.0]), np.array([0.0, 0.0, 1.0, 1.0]), (), None)[:24]
    'the axis you returned ha'
    """

    def check(got: np.ndarray, expected: Any, args: tuple[Any, ...], reference: Any) -> str | None:
        ref = np.asarray(expected, dtype=float).reshape(-1)
        g = got.reshape(-1)
        if g.size != ref.size:
            return None
        norm = float(np.linalg.norm(g[:stop]))
        fixed = g.copy()
        if norm < 1e-12 or abs(norm - 1.0) < 1e-6:
            return None
        fixed[:stop] = g[:stop] / norm
        if close(fixed, ref):
            return f"the {what} you returned has length {norm:.4g}, not 1: divide it by its norm"
        return None

    return Mistake("unnormalised", made(check, unit_axis_out, stop, what, attr="check"))
