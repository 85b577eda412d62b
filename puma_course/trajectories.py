"""Cartesian paths of the end effector and the joint paths that follow them (lecture 10).

A path is a sequence of poses (n, 4, 4) with a fixed orientation: a straight
line (:func:`line_path`) or a circle (:func:`circle_path`). An arm with several
inverse-kinematics solutions per pose must pick one at every step;
:func:`follow` picks the solution nearest the previous configuration (wrapped
joint distance), :func:`naive` the first solution the solver lists. Solvers
are passed as *candidate functions* ``Ts (n, 4, 4) -> (Q (n, k, 6), valid (n, k))``:
:func:`puma_candidates` (the batched closed form of :mod:`puma_course.puma_ik`)
and :func:`porter_candidates` (Porter's Ver.1, :mod:`puma_course.porter`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._validate import as_array, as_positive, as_rotation, as_transform
from .transforms import wrap_angle

__all__ = [
    "line_path",
    "circle_path",
    "JointPath",
    "follow",
    "naive",
    "step_distance",
    "unwrap",
    "puma_candidates",
    "porter_candidates",
]

Candidates = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]


def _poses(R: np.ndarray, P: np.ndarray) -> np.ndarray:
    n = P.shape[0]
    T = np.zeros((n, 4, 4))
    T[:, :3, :3] = R
    T[:, :3, 3] = P
    T[:, 3, 3] = 1.0
    return T


def line_path(T0: Any, T1: Any, n: int) -> np.ndarray:
    """n poses (n, 4, 4) from T0's position to T1's on a straight line, keeping T0's orientation.

    ``T1`` may be a pose (4, 4) (its rotation is ignored: the orientation stays
    fixed) or a point (3,). Positions p(s) = (1 - s) p0 + s p1, s = 0..1.

    >>> P = line_path(np.eye(4), [1.0, 2.0, 0.0], 3)[:, :3, 3]
    >>> P
    array([[0. , 0. , 0. ],
           [0.5, 1. , 0. ],
           [1. , 2. , 0. ]])
    """
    T0 = as_transform(T0, "T0")
    try:
        shape = np.shape(T1)
    except ValueError:  # ragged nested lists
        shape = None
    if shape == (4, 4):
        p1 = as_transform(T1, "T1")[:3, 3]
    else:
        p1 = as_array(T1, "T1", (3,), what="a pose (4, 4) or a point (3,)")
    n = int(as_positive(n, "n"))
    if n < 2:
        raise ValueError(f"n: expected at least 2 poses on the path, got {n}")
    s = np.linspace(0.0, 1.0, n)[:, None]
    return _poses(T0[:3, :3], (1.0 - s) * T0[:3, 3] + s * p1)


def circle_path(center: Any, radius: float, normal: Any, R: Any, n: int, start: Any | None = None) -> np.ndarray:
    """n poses (n, 4, 4) around a full circle (closed: the last equals the first), orientation R fixed.

    The circle lies in the plane through ``center`` perpendicular to ``normal``
    and runs counter-clockwise seen from the tip of ``normal``, starting in the
    direction ``start`` (projected into the plane; default: the plane direction
    closest to x, or to y if normal ∥ x). p(t) = c + r (cos t e1 + sin t e2).

    >>> P = circle_path([0, 0, 1], 0.5, [0, 0, 1], np.eye(3), 5)[:, :3, 3]
    >>> np.round(P, 6) + 0.0
    array([[ 0.5,  0. ,  1. ],
           [ 0. ,  0.5,  1. ],
           [-0.5,  0. ,  1. ],
           [ 0. , -0.5,  1. ],
           [ 0.5,  0. ,  1. ]])
    """
    c = as_array(center, "center", (3,))
    r = as_positive(radius, "radius")
    nv = as_array(normal, "normal", (3,))
    if np.linalg.norm(nv) == 0:
        raise ValueError("normal: expected a non-zero vector perpendicular to the circle's plane, got zeros")
    nv = nv / np.linalg.norm(nv)
    Rm = as_rotation(R, "R")
    n = int(as_positive(n, "n"))
    if n < 2:
        raise ValueError(f"n: expected at least 2 poses on the path, got {n}")
    if start is None:
        guess = np.array([1.0, 0.0, 0.0]) if abs(nv[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    else:
        guess = as_array(start, "start", (3,))
    e1 = guess - (guess @ nv) * nv
    if np.linalg.norm(e1) < 1e-12:
        raise ValueError("start: expected a direction not parallel to normal, got a parallel one")
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(nv, e1)
    t = np.linspace(0.0, 2 * np.pi, n)[:, None]
    return _poses(Rm, c + r * (np.cos(t) * e1 + np.sin(t) * e2))


def _revolute(revolute: Any | None, m: int) -> np.ndarray:
    """The revolute mask (m,) (default all True), or ValueError if it does not match the m joints."""
    if revolute is None:
        return np.ones(m, dtype=bool)
    rev = np.asarray(revolute)
    if rev.shape != (m,):
        raise ValueError(f"revolute: expected a mask of shape ({m},) (one flag per joint), got shape {rev.shape}")
    return rev.astype(bool)


def step_distance(qa: Any, qb: Any, revolute: Any | None = None) -> np.ndarray:
    """Distance between joint vectors over the last axis: angle differences wrapped to (-π, π].

    ``revolute`` (a boolean mask, default all True) says which joints are
    angles; the others (prismatic) are compared as they are.

    >>> round(float(step_distance([3.1, 0.0], [-3.1, 0.0])), 4)  # across ±π the step is small
    0.0832
    """
    qa = as_array(qa, "qa", batch=True, what="joint values")
    qb = as_array(qb, "qb", batch=True, what="joint values")
    if qa.ndim == 0 or qb.ndim == 0 or qa.shape[-1] != qb.shape[-1]:
        raise ValueError(f"qa, qb: expected joint vectors of the same length, got shapes {qa.shape} and {qb.shape}")
    d = qa - qb
    rev = _revolute(revolute, d.shape[-1])
    d = np.where(rev, wrap_angle(d), d)
    return np.round(np.sqrt(np.sum(d * d, axis=-1)), 12)


def unwrap(q: Any, revolute: Any | None = None) -> np.ndarray:
    """A joint path (n, m) with the 2π jumps of its angle columns removed (for plotting).

    >>> unwrap([[3.0], [-3.0]])[:, 0].round(4)
    array([3.    , 3.2832])
    """
    q = as_array(q, "q", (None, None), what="a joint path of shape (n, m)")
    rev = _revolute(revolute, q.shape[1])
    out = q.copy()
    out[:, rev] = np.unwrap(q[:, rev], axis=0)
    return out


@dataclass
class JointPath:
    """A joint path along a Cartesian path.

    ``q`` (n, m) the chosen configuration at every pose; ``choice`` (n,) which
    candidate (column of the solver's output) was chosen; ``step`` (n-1,)
    wrapped distance between successive configurations (``step[0]`` from the
    first pose's choice to the second's); ``start_jump`` the distance from the
    starting configuration ``q0`` to ``q[0]`` (0 for :func:`naive` called without q0).

    Usually made by :func:`follow` or :func:`naive`; by hand:

    >>> jp = JointPath(q=np.array([[0.0, 0.0], [0.1, 0.0]]), choice=np.array([0, 0]), step=np.array([0.1]),
    ...                start_jump=0.0)
    >>> jp.max_step
    0.1
    """

    q: np.ndarray
    choice: np.ndarray
    step: np.ndarray
    start_jump: float

    @property
    def max_step(self) -> float:
        """The largest jump between successive poses (radians, wrapped)."""
        return float(self.step.max()) if len(self.step) else 0.0


def _candidates(path_Ts: Any, ik_all: Candidates) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    Ts = as_transform(path_Ts, "path_Ts", batch=True)
    if Ts.ndim == 2:
        Ts = Ts[None]
    Q, valid = ik_all(Ts)
    Q = np.asarray(Q, dtype=float)
    valid = np.asarray(valid, dtype=bool)
    bad = ~valid.any(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(
            f"path_Ts: no configuration reaches pose {i} of the path (position {np.round(Ts[i, :3, 3], 4).tolist()})"
        )
    return Ts, Q, valid


def follow(path_Ts: Any, ik_all: Candidates, q0: Any, *, revolute: Any | None = None) -> JointPath:
    """At each pose, the solution nearest the previous configuration (starting from ``q0``).

    ``ik_all(Ts)`` returns every candidate (n, k, m) and a validity mask (n, k)
    for all poses at once (a batched solver); the choice itself is a short loop
    over the path, since each step depends on the one before.

    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> q0 = arm.q("qn")
    >>> path = line_path(arm.fk(q0), arm.fk(q0)[:3, 3] + [0.0, 0.1, 0.0], 20)
    >>> jp = follow(path, puma_candidates(arm), q0)
    >>> jp.q.shape, jp.start_jump < 1e-9, jp.max_step < 0.05
    ((20, 6), True, True)
    """
    Ts, Q, valid = _candidates(path_Ts, ik_all)
    m = Q.shape[-1]
    prev = as_array(q0, "q0", (m,), what=f"a starting configuration of shape ({m},)")
    rev = _revolute(revolute, m)
    n = Q.shape[0]
    choice = np.empty(n, dtype=int)
    inf = np.where(valid, 0.0, np.inf)
    twopi = 2 * np.pi
    for i in range(n):
        d = Q[i] - prev
        d[:, rev] = np.pi - np.mod(np.pi - d[:, rev], twopi)
        j = int(np.argmin(np.einsum("kj,kj->k", d, d) + inf[i]))
        choice[i] = j
        prev = Q[i, j]
    q = Q[np.arange(n), choice]
    return JointPath(
        q=q,
        choice=choice,
        step=step_distance(q[1:], q[:-1], rev),
        start_jump=float(step_distance(q[0], q0, rev)),
    )


def naive(path_Ts: Any, ik_all: Candidates, q0: Any | None = None, *, revolute: Any | None = None) -> JointPath:
    """At each pose, simply the first valid solution the solver lists (for comparison with :func:`follow`).

    ``q0``, if given, is where the arm starts: ``start_jump`` is then the jump
    from it to the first chosen configuration (else 0).

    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> path = line_path(arm.fk(arm.q("qn")), [0.5, 0.2, 0.3], 10)
    >>> naive(path, puma_candidates(arm)).choice.tolist() == [0] * 10  # always branch left/up/noflip
    True
    """
    Ts, Q, valid = _candidates(path_Ts, ik_all)
    choice = np.argmax(valid, axis=1)
    q = Q[np.arange(Q.shape[0]), choice]
    m = Q.shape[-1]
    rev = _revolute(revolute, m)
    start = 0.0
    if q0 is not None:
        q0 = as_array(q0, "q0", (m,), what=f"a starting configuration of shape ({m},)")
        start = float(step_distance(q[0], q0, rev))
    return JointPath(q=q, choice=choice, step=step_distance(q[1:], q[:-1], rev), start_jump=start)


def puma_candidates(chain: Any) -> Candidates:
    """Candidate function for a PUMA-560 chain: its batched closed form (N, 8, 6) and validity mask.

    >>> from puma_course.robots import puma560
    >>> Q, valid = puma_candidates(puma560())(puma560().fk(np.zeros((2, 6)) + 0.3))
    >>> Q.shape, valid.shape
    ((2, 8, 6), (2, 8))
    """
    if not hasattr(chain, "ik_batch"):
        raise ValueError(
            f"chain: expected a PUMA-560 chain with ik_batch (robots.puma560()), got {type(chain).__name__}"
        )

    def candidates(Ts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        sol = chain.ik_batch(Ts)
        return sol.q, sol.valid

    return candidates


def porter_candidates(l1: float, l3: float, l4: float) -> Candidates:
    """Candidate function for Porter's chain: Ver.1 (:func:`puma_course.porter.ik_explicit_batch`).

    Porter's q = (α1, α2, q2, α3, α4, α5): angles in [0, 2π) and q2 (index 2) a length: use
    ``revolute=PORTER_REVOLUTE`` with :func:`follow` and :func:`unwrap`. Invalid candidates
    (no solution on that branch) come back as zeros with ``valid`` False, never NaN.

    >>> from puma_course import porter
    >>> q = np.array([0.3, 0.4, 1.0, 0.5, 0.6, 0.7])
    >>> Q, valid = porter_candidates(1.0, 0.5, 0.3)(porter.fk(q, 1.0, 0.5, 0.3)[None])
    >>> Q.shape, valid.tolist()
    ((1, 4, 6), [[True, True, True, True]])
    >>> np.round(Q[0, 0], 6) + 0.0  # the first candidate is the configuration we started from
    array([0.3, 0.4, 1. , 0.5, 0.6, 0.7])
    """
    from . import porter  # imported on use: Porter's module is optional for the PUMA-560 part

    def candidates(Ts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        Q, _flags = porter.ik_explicit_batch(Ts, l1, l3, l4)
        Q = np.asarray(Q, dtype=float)
        valid = np.isfinite(Q).all(axis=-1)
        Q = np.where(np.isfinite(Q), Q, 0.0)
        return Q, valid

    return candidates


#: Which of Porter's joints are angles (q2, index 2, is a prismatic length).
PORTER_REVOLUTE = np.array([True, True, False, True, True, True])
__all__.append("PORTER_REVOLUTE")
