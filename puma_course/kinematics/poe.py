"""Two more ways to write a chain's forward kinematics: an elementary transform sequence (ETS) and a
product of exponentials (PoE, Brockett's formula; Lynch & Park §4.1).

* ETS: the pose is a product of elementary transforms, each a fixed ``Tx/Ty/Tz`` (a length) or
  ``Rx/Ry/Rz`` (an angle), or a joint's: ``("Rz", "q0")`` turns by q[0] about z, ``("Tx", "q2")``
  slides by q[2] along x (Corke's ETS, Robotics, Vision and Control §7.1.1).
* PoE: with every joint at zero the end frame is M; joint i's screw axis S_i = (ω_i, v_i) in base
  coordinates at that zero pose (ω_i the unit axis and v_i = -ω_i × r_i for a revolute joint through
  r_i; ω_i = 0 and v_i the unit direction for a prismatic one). Then

      T(q) = exp([S_1] q_1) exp([S_2] q_2) ... exp([S_n] q_n) M .

Porter's product of motions (:meth:`~.porter.Porter.fk`) is an ETS already; :func:`porter_ets` and
:func:`porter_screws` write it both ways.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._validate import MAX_MAGNITUDE, as_array, as_length, as_transform
from ..transforms import rodrigues, skew

__all__ = ["ets_fk", "twist_exp", "poe_fk", "porter_ets", "porter_screws"]

_AXES = {"x": 0, "y": 1, "z": 2}


def _elementary(kind: str, value: float) -> np.ndarray:
    T = np.eye(4)
    axis = np.zeros(3)
    axis[_AXES[kind[1]]] = 1.0
    if kind[0] == "R":
        T[:3, :3] = rodrigues(axis, value)
    else:
        T[:3, 3] = axis * value
    return T


def ets_fk(ets: Sequence[tuple[str, Any]], q: Any) -> np.ndarray:
    """The pose (4, 4) of an elementary transform sequence at the joint values q.

    >>> np.round(ets_fk([("Rz", "q0"), ("Tx", 1.0)], [np.pi / 2])[:3, 3], 12) + 0.0
    array([0., 1., 0.])
    """
    qv = as_array(q, "q", (None,), what="joint values of shape (n,)", max_magnitude=MAX_MAGNITUDE)
    if isinstance(ets, (str, bytes)) or not isinstance(ets, (list, tuple)):
        raise ValueError(f"ets: expected a list of (kind, value) steps, got {type(ets).__name__} {ets!r}"[:200])
    T = np.eye(4)
    for i, step in enumerate(ets):
        if not (isinstance(step, tuple) and len(step) == 2 and step[0] in {a + b for a in "RT" for b in "xyz"}):
            raise ValueError(f"ets[{i}]: expected (kind, value) with kind one of Rx..Tz, got {step!r}")
        kind, value = step
        if isinstance(value, str):
            if not (value.startswith("q") and value[1:].isdigit() and int(value[1:]) < len(qv)):
                raise ValueError(f"ets[{i}]: expected a joint name q0..q{len(qv) - 1}, got {value!r}")
            v = float(qv[int(value[1:])])
        else:
            v = float(as_length(value, f"ets[{i}]"))
        T = T @ _elementary(kind, v)
    return T


def twist_exp(S: Any, theta: float) -> np.ndarray:
    """exp([S] θ) (4, 4) for a screw axis S = (ω, v) with |ω| = 1 (revolute) or ω = 0, |v| = 1 (prismatic).

    >>> np.round(twist_exp([0, 0, 1, 0, -1, 0], np.pi)[:3, 3], 12) + 0.0  # a half turn about x = 1
    array([2., 0., 0.])
    """
    s = as_array(S, "S", (6,), what="a screw axis (ω, v) of shape (6,)", max_magnitude=MAX_MAGNITUDE)
    theta = float(as_array(theta, "theta", (), what="a joint value (one number)", max_magnitude=MAX_MAGNITUDE))
    w, v = s[:3], s[3:]
    nw = float(np.linalg.norm(w))
    T = np.eye(4)
    if abs(nw - 1.0) < 1e-9:
        W = skew(w)
        T[:3, :3] = rodrigues(w, theta)
        T[:3, 3] = (np.eye(3) * theta + (1 - math.cos(theta)) * W + (theta - math.sin(theta)) * W @ W) @ v
    elif nw < 1e-12 and abs(float(np.linalg.norm(v)) - 1.0) < 1e-9:
        T[:3, 3] = v * theta
    else:
        raise ValueError(f"S: expected |ω| = 1, or ω = 0 and |v| = 1, got ω = {w.tolist()}, v = {v.tolist()}")
    return T


def poe_fk(screws: Any, M: Any, q: Any) -> np.ndarray:
    """The product of exponentials exp([S_1] q_1) ... exp([S_n] q_n) M (4, 4); screws (n, 6), M the zero pose.

    >>> planar = [[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]]  # two unit links along x, joints at x = 0 and 1
    >>> M = np.eye(4); M[0, 3] = 2.0
    >>> np.round(poe_fk(planar, M, [0.0, np.pi / 2])[:3, 3], 12) + 0.0
    array([1., 1., 0.])
    """
    S = as_array(screws, "screws", (None, 6), what="screw axes of shape (n, 6)", max_magnitude=MAX_MAGNITUDE)
    M = as_transform(M, "M")
    qv = as_array(q, "q", (len(S),), what=f"joint values of shape ({len(S)},)", max_magnitude=MAX_MAGNITUDE)
    T = np.eye(4)
    for i, (Si, qi) in enumerate(zip(S, qv, strict=True)):
        try:
            T = T @ twist_exp(Si, float(qi))
        except ValueError as err:  # name the row of `screws`, not twist_exp's own argument
            raise ValueError(f"screws[{i}]{str(err)[1:]}") from None
    return T @ M


def porter_ets(l1: float, l3: float, l4: float) -> list[tuple[str, Any]]:
    """Porter's product of motions as an ETS: Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5).

    Joints in the order of :class:`~.porter.Porter`'s q = (α1, α2, q2, α3, α4, α5).

    >>> [k for k, _ in porter_ets(1.0, 0.5, 0.3)]
    ['Rz', 'Tz', 'Ry', 'Tx', 'Ry', 'Tz', 'Rz', 'Tx', 'Rx']
    """
    l1, l3, l4 = (as_length(v, n, positive=True) for v, n in ((l1, "l1"), (l3, "l3"), (l4, "l4")))
    return [("Rz", "q0"), ("Tz", l1), ("Ry", "q1"), ("Tx", "q2"), ("Ry", "q3"), ("Tz", -l3), ("Rz", "q4"),
            ("Tx", l4), ("Rx", "q5")]  # fmt: skip


def porter_screws(l1: float, l3: float, l4: float) -> tuple[np.ndarray, np.ndarray]:
    """Porter's chain as a product of exponentials: the screw axes (6, 6) at q = 0 and the zero pose M.

    At q = 0 the end frame F5 sits at (l4, 0, l1 - l3) with the scene's axes; α1 turns about z0, α2
    and α3 about the same y axis through (0, 0, l1) (q2 = 0 puts them on one line), q2 slides along
    x0, α4 turns about z through (0, 0, l1 - l3) and α5 about x through (l4, 0, l1 - l3).

    >>> S, M = porter_screws(1.0, 0.5, 0.3)
    >>> S[1], M[:3, 3]
    (array([ 0.,  1.,  0., -1.,  0.,  0.]), array([0.3, 0. , 0.5]))
    """
    l1, l3, l4 = (as_length(v, n, positive=True) for v, n in ((l1, "l1"), (l3, "l3"), (l4, "l4")))
    ex, ey, ez = np.eye(3)

    def rev(w: np.ndarray, r: Any) -> np.ndarray:
        return np.concatenate([w, -np.cross(w, np.asarray(r, dtype=float))])

    S = np.stack([
        rev(ez, [0.0, 0.0, 0.0]),
        rev(ey, [0.0, 0.0, l1]),
        np.concatenate([np.zeros(3), ex]),
        rev(ey, [0.0, 0.0, l1]),
        rev(ez, [0.0, 0.0, l1 - l3]),
        rev(ex, [l4, 0.0, l1 - l3]),
    ]) + 0.0  # fmt: skip
    M = np.eye(4)
    M[:3, 3] = [l4, 0.0, l1 - l3]
    return S, M
