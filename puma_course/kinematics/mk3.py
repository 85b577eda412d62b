"""The Yaskawa Motoman MK3 (5R) of Meghdari's lecture: its table, fk and a closed-form ik.

Table (modified DH, millimetres):

======  =========  =======  =====
i       α_{i-1}    a_{i-1}  d_i
======  =========  =======  =====
1       0          0        d1
2       90°        a1       0
3       0          a2       0
4       0          a3       0
5       90°        0        d5
======  =========  =======  =====

Inverse kinematics (the 5R arm as Craig treats the Motoman L-3; re-derived with sympy in the
tests): with M = Rz(-θ1) R the product of the table gives

    M = [[c5 C, -s5 C, S], [-s5, -c5, 0], [c5 S, -s5 S, -C]],   C, S = cos, sin(θ2 + θ3 + θ4)

and p = Rz(θ1) (a1 + a2 c2 + a3 c23 + d5 S, 0, d1 + a2 s2 + a3 s23 - d5 C). So:

* the tool point p, the approach vector z5 and the wrist point w = p - d5 z5 all lie in the
  *arm plane*, the vertical plane through the base axis at azimuth θ1. **A 5-DOF arm reaches only
  poses whose approach vector lies in that plane**; any other pose is refused with the reason
  (``success`` False), never approximated;
* θ1 = azimuth of w (or of z5 when w is on the base axis), or that plus π (reaching over the back);
* θ2 + θ3 + θ4 = atan2(M[0, 2], -M[2, 2]) and θ5 = atan2(-M[1, 0], -M[1, 1]) are always defined;
* θ2, θ3 are the planar two-link solution for w seen from joint 2: r = c1 wx + s1 wy - a1,
  z = wz - d1, c3 = (r² + z² - a2² - a3²) / (2 a2 a3), elbow up or down; θ4 closes the sum.

The nearest attainable pose (Craig's treatment of the Motoman L-3): a goal whose approach vector z leaves
the vertical plane through the base axis and the tool point p is turned, as a whole, about the axis
K = z × z' by the smallest angle that brings z into that plane (z' the normalised projection of z onto it,
the angle asin |m · z| with m the plane's unit normal); the position is kept. The wrist point p - d5 z'
depends on z': when the arm does not reach it, z' is turned on along the plane to the nearest direction whose
wrist point it reaches, and only a position no such direction serves is refused. :meth:`MK3.nearest_attainable`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._validate import as_robot_length, as_tol
from ..transforms import rodrigues, wrap_angle
from ._ops import ARRAY
from .dh import DHChain, Link
from .ik import IKBatch, IKSolutions
from .mk3_reach import nearest_on_arcs, wrist_arcs, wrist_range

__all__ = ["MK3", "Attainable", "BRANCH_LABELS", "FLAG_KEYS", "MESSAGES", "DEFAULTS"]

#: The lecture's lengths (millimetres).
DEFAULTS = {"d1": 360.0, "a1": 135.0, "a2": 250.0, "a3": 215.0, "d5": 100.0}
BRANCH_LABELS = ("front/up", "front/down", "back/up", "back/down")
FLAG_KEYS = ("elbow", "base_axis", "joint2_axis")
MESSAGES = {
    "elbow": "the wrist point is at the largest or smallest distance a2 ± a3 from joint 2: elbow up and down coincide",
    "base_axis": "the wrist point is on the base axis and the tool points vertically: θ1 and θ5 turn about the same "
    "axis, only θ1 - θ5 is defined (θ1 from `near`, else 0), and front = back",
    "joint2_axis": "the wrist point is on the axis of joint 2 (possible when a2 = a3): θ2 is free "
    "(from `near`, else 0)",
}
_PLANE = np.array([0.0, 0.0, 1.0, 1.0])  # + π for the back branches
_EL = np.array([1.0, -1.0, 1.0, -1.0])
_H = math.pi / 2
_BLOCK = 10_000
#: An approach whose projection onto the arm plane is shorter than this (within 1e-6 rad of perpendicular to the
#: plane) counts as perpendicular in :meth:`MK3.nearest_attainable`: every plane direction is then 90° away to 1e-6
#: rad, and a shorter projection would carry a direction error above 1e-10 rad.
_PERPENDICULAR = 1e-6
#: The smallest accepted ``tol`` (on the sine of z5's angle to the arm plane): below 1e-12 rounding noise
#: would refuse reachable poses (384 of 2,000 random ones at 1e-16).
TOL_MIN = 1e-12


def _plane(o: Any, P: tuple[Any, ...], R: tuple[Any, ...], d5: float, ltol: float, near: Any) -> tuple[Any, ...]:
    """The arm plane's azimuth φ, whether it is free, and how far the pose leaves it (position, angle)."""
    px, py, _ = P
    r13, r23 = R[2], R[5]
    wx, wy = px - d5 * r13, py - d5 * r23
    w_h, z_h = o.hypot(wx, wy), o.hypot(r13, r23)
    free = (w_h <= ltol) & (z_h <= 1e-9)  # w on the base axis and z5 vertical: the plane is free
    # w = p - d5 z5 carries a rounding error of a few 1e-16 (|p| + d5): its azimuth is off by that over w_h.
    # z5's azimuth is off by about 4e-16 / z_h: take the plane from whichever is known better (a wrist
    # point microns from the base axis, z5 tilted: from z5, turned to w's side) when w's is off by > 1e-12.
    err_w = 4e-16 * (o.abs(px) + o.abs(py) + abs(d5) + ltol)
    use_z = (z_h > 1e-9) & (err_w > w_h * 1e-12) & (z_h * err_w > w_h * 4e-16)  # w's azimuth off > 1e-12
    phi_z = o.atan2(r23, r13) + o.where((w_h > ltol) & (wx * r13 + wy * r23 < 0.0), o.pi, 0.0)
    phi = o.where(free, 0.0 if near is None else near[0], o.where(use_z, phi_z, o.atan2(wy, wx)))
    c, s = o.cos(phi), o.sin(phi)
    off_p = o.abs(-s * px + c * py)  # distance of the tool point from the plane
    off_z = o.abs(-s * r13 + c * r23)  # sine of the angle between z5 and the plane
    return phi, free, off_p, off_z


def _branch(o: Any, P: tuple[Any, ...], R: tuple[Any, ...], L: tuple[float, ...], t1: Any, el: Any, ltol: float,
            near: Any) -> tuple[Any, ...]:  # fmt: skip
    """θ1..θ5 of one (plane, elbow) branch, whether the wrist point is within reach, and the flags."""
    d1, a1, a2, a3, d5 = L
    px, py, pz = P
    r11, r12, r13, r21, r22, r23, _, _, r33 = R
    c1, s1 = o.cos(t1), o.sin(t1)
    t234 = o.atan2(c1 * r13 + s1 * r23, -r33)
    t5 = o.atan2(s1 * r11 - c1 * r21, s1 * r12 - c1 * r22)
    r = c1 * (px - d5 * r13) + s1 * (py - d5 * r23) - a1  # the wrist point seen from joint 2
    z = pz - d5 * r33 - d1
    c3 = (r * r + z * z - a2 * a2 - a3 * a3) / (2.0 * a2 * a3)
    D = 1.0 - c3 * c3
    reach = D >= -1e-12
    S3 = o.sqrt(o.maximum(D, 0.0))
    el_sing = S3 < 1e-7
    S3, c3 = o.where(el_sing, 0.0, S3), o.where(el_sing, o.where(c3 > 0, 1.0, -1.0), c3)
    t3 = o.atan2(-el * o.where(r >= -ltol, 1.0, -1.0) * S3, c3)  # elbow up: s3 sign(r) < 0
    j2 = o.hypot(r, z) < ltol
    t2 = o.where(j2, 0.0 if near is None else near[1], o.atan2(z, r) - o.atan2(a3 * o.sin(t3), a2 + a3 * o.cos(t3)))
    return t1, t2, t3, t234 - t2 - t3, t5, reach, el_sing, j2


def _turn(R: np.ndarray, zn: np.ndarray, m: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """R turned the least (about z × zn) so that its approach z becomes the unit ``zn``: (R', axis, angle).

    z = -zn turns by π about ``m`` (the arm plane's normal, perpendicular to both then); z = zn does not turn.
    """
    z = R[:, 2]
    k = np.cross(z, zn)
    sk = math.hypot(*k)
    angle = math.atan2(sk, float(z[0] * zn[0] + z[1] * zn[1] + z[2] * zn[2]))  # asin |m · z| for a projection
    if sk <= 1e-15:
        if angle < _H:
            return R.copy(), np.zeros(3), 0.0
        k, sk = m, 1.0
    axis = k / sk
    Rk = rodrigues(axis, angle)
    out = (Rk[:, :, None] * R[None, :, :]).sum(axis=1)  # Rk @ R without a BLAS call
    out[:, 2] = zn  # exactly the new approach (the product carries rounding)
    return out, axis, angle


@dataclass(frozen=True)
class Attainable:
    """What :meth:`MK3.nearest_attainable` did to a goal pose.

    ``angle`` is the rotation applied to the goal's orientation (radians, in [0, π]; 0 when the goal is
    attainable as it is) about the unit ``axis`` (zeros when nothing turned); ``along`` is how far the
    approach was turned along the arm plane beyond the goal's projection onto it, because the projection's
    wrist point is out of reach (radians, 0 when the projection will do); ``unique`` is False when the
    approach was perpendicular to the arm plane (every direction in the plane is then 90° away: the tool is
    turned to point straight down, or as near that as the arm reaches); ``success`` says whether the arm
    reaches the returned pose (``reason`` says why not: no orientation at that position puts the wrist point
    within reach); ``message`` is one sentence on what was done.
    """

    angle: float
    axis: np.ndarray = field(repr=False)
    unique: bool
    success: bool
    reason: str
    message: str
    along: float = 0.0


class MK3(DHChain):
    """The Yaskawa Motoman MK3 (5R) of the lecture's table (modified DH, millimetres).

    Named configurations: ``qz`` all zeros (both arm links horizontal, the tool axis z5
    pointing straight down); ``qr`` ready (upper arm vertical, forearm horizontal, tool down).

    ``joint_limits`` is None: neither Meghdari's lecture (the course's source for this arm) nor a
    reference we could find publishes the MK3's joint ranges, so none are invented here.

    >>> arm = MK3()
    >>> np.round(arm.fk(np.zeros(5))[:3, 3], 6) + 0.0  # (a1 + a2 + a3, 0, d1 - d5)
    array([600.,   0., 260.])
    >>> sol = arm.ik(arm.fk(arm.q("qr")), near=arm.q("qr"))  # the back plane is out of reach here
    >>> len(sol), sol.labels[0], bool(np.allclose(sol[0], arm.q("qr")))
    (2, 'front/up', True)
    """

    def __init__(
        self,
        d1: float = DEFAULTS["d1"],
        a1: float = DEFAULTS["a1"],
        a2: float = DEFAULTS["a2"],
        a3: float = DEFAULTS["a3"],
        d5: float = DEFAULTS["d5"],
    ) -> None:
        d1, a1, d5 = (
            as_robot_length(v, n, what=f"the length {n} in mm") for v, n in ((d1, "d1"), (a1, "a1"), (d5, "d5"))
        )
        a2, a3 = (as_robot_length(v, n, positive=True, what=f"the link length {n} in mm (positive)")
                  for v, n in ((a2, "a2"), (a3, "a3")))  # fmt: skip
        self._L = (d1, a1, a2, a3, d5)
        self._ltol = 1e-9 * (abs(d1) + abs(a1) + a2 + a3 + abs(d5))
        links = [Link(0.0, 0.0, d1), Link(_H, a1, 0.0), Link(0.0, a2, 0.0), Link(0.0, a3, 0.0), Link(_H, 0.0, d5)]
        configs = {"qz": np.zeros(5), "qr": np.array([0.0, _H, -_H, 0.0, 0.0])}
        super().__init__(links, name="Motoman MK3", units="mm", configurations=configs)

    @property
    def lengths(self) -> dict[str, float]:
        """The five lengths of the table: d1, a1, a2, a3, d5 (millimetres)."""
        return dict(zip(("d1", "a1", "a2", "a3", "d5"), self._L, strict=True))

    def parameters(self) -> dict[str, float]:
        """The five lengths of the table (millimetres)."""
        return self.lengths

    def __repr__(self) -> str:
        return "MK3(" + ", ".join(f"{k}={v:g}" for k, v in self.lengths.items()) + ")"

    def _unreachable(self, off_p: float, off_z: float) -> str:
        return (
            "a 5-DOF arm reaches only poses whose approach vector z5 lies in the arm plane (the vertical plane "
            f"through the base axis and the wrist point w = p - d5 z5): this pose leaves it (tool point "
            f"{off_p:.3g} mm off that plane, z5 at {math.degrees(math.asin(min(off_z, 1.0))):.3g}° to it)"
        )

    def nearest_attainable(self, T: Any, *, tol: float = 1e-9) -> tuple[np.ndarray, Attainable]:
        """The attainable pose nearest the goal T: its orientation turned the least, its position kept.

        Craig's treatment of the Motoman L-3: a five-joint arm reaches only poses whose approach vector
        z5 lies in the arm plane, the vertical plane through the base axis and the tool point p. First the
        goal's whole frame is turned about K = z × z' by the angle asin |m · z| that takes z onto z', its
        normalised projection onto that plane (m the plane's unit normal, (-py, px, 0) / |(px, py)|); no
        rotation moving z onto the plane is smaller, and z5's spin is kept as far as it can be. The position p
        is kept. But the wrist point w' = p - d5 z' depends on z': if the arm does not reach it, the approach
        is turned on along the plane, to the nearest direction whose wrist point it reaches (the circle of
        wrist points against joint 2's annulus, lecture 04 §8; :mod:`.mk3_reach`), and the frame is turned the
        least that takes z there. Returns the pose (4, 4) and an :class:`Attainable`.

        * a goal whose approach is in the plane (|m · z| <= ``tol``, the tolerance of :meth:`ik`) and whose
          wrist point is in reach comes back unchanged, as does a reachable goal whose tool point is on the
          base axis (every vertical plane holds it; else the plane through its approach is searched);
        * an approach perpendicular to the plane (horizontal, along m; within 1e-6 rad) is 90° from every
          direction in it: it is turned to point straight down (the MK3's working posture), or to the
          reachable direction nearest straight down, ``unique`` False;
        * only if no approach in the plane puts the wrist point in reach (the position itself is out of reach
          for every orientation) is the projected pose returned with ``success`` False and the reason.

        >>> from puma_course.transforms import rotx
        >>> arm = MK3()
        >>> T = arm.fk([0.3, 1.6, 1.2, 0.2, 0.4])
        >>> T[:3, :3] = T[:3, :3] @ rotx(0.2)  # z5 turned 0.2 rad about x5: out of the arm plane
        >>> T2, info = arm.nearest_attainable(T)
        >>> bool(arm.ik(T).success), bool(arm.ik(T2).success), info.success, bool(np.allclose(T2[:3, 3], T[:3, 3]))
        (False, True, True, True)
        """
        tol = as_tol(tol, "tol", lower=TOL_MIN)
        Tm = self._check_poses(T)
        if Tm.shape[0] != 1:
            raise ValueError(f"T: expected one pose (4, 4), got shape {Tm.shape}")
        out = Tm[0].copy()
        px, py = float(out[0, 3]), float(out[1, 3])
        z = out[:3, 2].copy()
        h = math.hypot(px, py)
        axis, angle, unique = np.zeros(3), 0.0, True
        if h <= self._ltol:  # every vertical plane holds p: the one through the approach turns it the least
            zh = math.hypot(z[0], z[1])
            er = np.array([z[0] / zh, z[1] / zh, 0.0]) if zh > 1e-12 else np.array([1.0, 0.0, 0.0])
            beta0 = math.atan2(z[2], zh)
            message = "the tool point is on the base axis: every vertical plane holds it, the goal is kept"
        else:
            er = np.array([px / h, py / h, 0.0])
            m = np.array([-py / h, px / h, 0.0])  # the arm plane's unit normal
            s = float(m[0] * z[0] + m[1] * z[1])  # sine of z's angle to the plane
            beta0 = math.atan2(z[2], float(er[0] * z[0] + er[1] * z[1]))
            if abs(s) <= tol:
                message = "the approach vector lies in the arm plane: the goal is attainable as it is"
            else:
                zp = z - s * m
                c = math.hypot(*zp)
                if c <= _PERPENDICULAR:  # z along ±m (horizontal): every direction in the plane is 90° away
                    unique, beta0 = False, -_H
                    zn = np.array([0.0, 0.0, -1.0])
                    message = (
                        "the approach vector is perpendicular to the arm plane: every direction in the plane is "
                        "90° away, and the tool is turned to point straight down"
                    )
                else:
                    zn = zp / c
                    message = (
                        "the approach vector was {:.3g}° out of the arm plane: the goal's frame is turned by that "
                        "much about z × z', z' its projection onto the plane"
                    )
                out[:3, :3], axis, angle = _turn(out[:3, :3], zn, m)
                message = message.format(math.degrees(angle))
        sol = self.ik(out, tol=max(tol, 1e-9))
        if sol.success:
            return out, Attainable(angle, axis, unique, True, "", message)
        return self._search(Tm[0], out, er, beta0, unique, Attainable(angle, axis, unique, False, "", message), tol)

    def _search(self, goal: np.ndarray, first: np.ndarray, er: np.ndarray, beta0: float, unique: bool,
                info: Attainable, tol: float) -> tuple[np.ndarray, Attainable]:  # fmt: skip
        """Turn the approach along the arm plane (unit horizontal ``er``) from ``beta0`` to the nearest direction
        whose wrist point is in reach; ``first`` (the projected pose) with the reason when there is none."""
        rho, pz = float(er[0] * goal[0, 3] + er[1] * goal[1, 3]), float(goal[2, 3])
        arcs = wrist_arcs(rho, pz, self._L)
        found = nearest_on_arcs(beta0, arcs)
        if found is None:
            (f0, f1), (b0, b1) = wrist_range(rho, pz, self._L)
            _, _, a2, a3, d5 = self._L
            why = (
                f"out of reach at this position for every orientation: as the approach z' turns in the arm plane, "
                f"the wrist point p - d5 z' runs round a circle of radius d5 = {abs(d5):g} mm about p, {f0:.4g} to "
                f"{f1:.4g} mm from joint 2 (front) and {b0:.4g} to {b1:.4g} mm from it reaching over the base, "
                f"never within the arm's reach of {abs(a2 - a3):g} to {a2 + a3:g} mm"
            )
            return first, Attainable(info.angle, info.axis, unique, False, why, info.message)
        m = np.array([-er[1], er[0], 0.0])
        beta, lo, hi = found
        at_lo = abs(wrap_angle(beta - lo)) <= abs(wrap_angle(beta - hi))  # which end beta is: step inwards
        inward = beta + math.copysign(min(1e-9, (hi - lo) / 2.0), 1.0 if at_lo else -1.0)
        for b in (beta,) if beta == beta0 else (inward, beta):  # 1e-9 rad inside the reach first: not stretched
            zn = np.array([math.cos(b) * er[0], math.cos(b) * er[1], math.sin(b)])
            out = goal.copy()
            out[:3, :3], axis, angle = _turn(goal[:3, :3], zn, m)
            sol = self.ik(out, tol=max(tol, 1e-9))
            if sol.success:
                break
        along = abs(wrap_angle(b - beta0))
        message = (
            f"the wrist point w' = p - d5 z' of the approach nearest the goal's in the arm plane is out of reach: "
            f"the approach is turned a further {math.degrees(along):.3g}° along the plane, to the nearest "
            f"direction whose wrist point the arm reaches; the goal's frame is turned by "
            f"{math.degrees(angle):.3g}° about z × z'"
        )
        return out, Attainable(angle, axis, unique, bool(sol.success), "" if sol.success else sol.reason, message,
                               along=along)  # fmt: skip

    def ik(self, T: Any, near: Any = None, *, tol: float = 1e-9) -> IKSolutions:
        """Every joint vector reaching T: up to four (front/back arm plane x elbow up/down).

        Poses whose approach vector z5 is not in the arm plane cannot be reached by a 5-DOF arm:
        ``success`` is False and the reason says so (``tol`` is the tolerance on the sine of the
        angle between z5 and the plane). Out-of-reach poses likewise. ``near`` sorts the
        solutions (nearest first) and fixes the joints left free at a singularity.

        >>> from puma_course.transforms import rotx
        >>> arm = MK3()
        >>> T = arm.fk([0.3, 1.6, 1.2, 0.2, 0.4])  # the arm bent back over its base: four solutions
        >>> len(arm.ik(T))
        4
        >>> T[:3, :3] = T[:3, :3] @ rotx(0.2)  # turn z5 out of the arm plane
        >>> arm.ik(T).reason[:38]
        'a 5-DOF arm reaches only poses whose a'
        """
        tol = as_tol(tol, "tol", lower=TOL_MIN)
        Tm = self._check_poses(T)
        if Tm.shape[0] != 1:
            raise ValueError(f"T: expected one pose (4, 4) (use ik_batch for several), got shape {Tm.shape}")
        nr = self._check_near(near)
        b = self._ik_batch(Tm, None if nr is None else nr[None], tol)
        return self._finish(b.solutions(0), nr)

    def ik_batch(self, T: Any, near: Any = None, *, tol: float = 1e-9) -> IKBatch:
        """All four branches for N poses (N, 4, 4), vectorised: an :class:`~.ik.IKBatch`.

        >>> arm = MK3()
        >>> b = arm.ik_batch(arm.fk([[0.3, 1.6, 1.2, 0.2, 0.4], [0.0, 0.2, 0.2, 0.2, 0.2]]))
        >>> b.q.shape, b.valid.sum(axis=1).tolist()  # the second pose is too far to reach over the back
        ((2, 4, 5), [4, 2])
        """
        tol = as_tol(tol, "tol", lower=TOL_MIN)
        Tb = self._check_poses(T)
        return self._ik_batch(Tb, self._check_near(near, batch=Tb.shape[0]), tol)

    def _ik_batch(self, Tb: np.ndarray, nr: np.ndarray | None, tol: float) -> IKBatch:
        N = Tb.shape[0]
        q = np.zeros((N, 4, 5))
        valid = np.zeros((N, 4), dtype=bool)
        flags = np.zeros((N, 4), dtype=np.int64)
        reason = np.full(N, "", dtype=object)
        o, L = ARRAY, self._L
        with np.errstate(all="ignore"):
            for start in range(0, N, _BLOCK):
                sl = slice(start, min(start + _BLOCK, N))
                T = Tb[sl]
                col = [T[:, i, j, None] for i in range(3) for j in range(4)]
                P = (col[3], col[7], col[11])
                R = (col[0], col[1], col[2], col[4], col[5], col[6], col[8], col[9], col[10])
                near = None if nr is None else [nr[sl, j, None] for j in range(5)]
                phi, free, off_p, off_z = _plane(o, P, R, L[4], self._ltol, near)
                out_of_plane = (off_p > self._ltol * 1e2) | (off_z > tol)
                t1, t2, t3, t4, t5, reach, el_sing, j2 = _branch(o, P, R, L, phi + np.pi * _PLANE, _EL, self._ltol,
                                                                 near)  # fmt: skip
                for j, t in enumerate((t1, t2, t3, t4, t5)):
                    q[sl, :, j] = wrap_angle(t)
                ok = reach & ~out_of_plane & ~(el_sing & (_EL < 0)) & ~(free & (_PLANE > 0))
                valid[sl] = ok
                flags[sl] = np.where(ok, el_sing * 1 + free * 2 + j2 * 4, 0)
                q[sl] = np.where(ok[..., None], q[sl], 0.0)
                for i in np.flatnonzero(~ok.any(axis=1)):
                    if out_of_plane[i, 0]:
                        reason[start + i] = self._unreachable(float(off_p[i, 0]), float(off_z[i, 0]))
                    else:
                        reason[start + i] = (
                            "out of reach: the wrist point w = p - d5 z5 is farther than a2 + a3 (or nearer than "
                            "|a2 - a3|) from joint 2 in both arm planes"
                        )
        return IKBatch(q, valid, BRANCH_LABELS, flags, FLAG_KEYS, MESSAGES, reason.astype(str), self.name,
                       "closed form", self.revolute, joints=self.joint_symbols)  # fmt: skip
