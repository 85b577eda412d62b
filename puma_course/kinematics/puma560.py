"""The PUMA-560 of Meghdari's lecture: its modified-DH table, closed-form fk and closed-form ik.

Table (Craig's frame assignment, frame {0} coincident with {1} at θ1 = 0; lengths in metres):

======  =========  =======  =====
i       α_{i-1}    a_{i-1}  d_i
======  =========  =======  =====
1       0          0        0
2       -90°       0        0
3       0          a2       d3
4       -90°       a3       d4
5       90°        0        0
6       -90°       0        0
======  =========  =======  =====

The wrist is spherical: the origin of frames {4}, {5}, {6} is the wrist centre, so the position
column p of ^0T_6 depends on θ1, θ2, θ3 only and the orientation then fixes θ4, θ5, θ6
(Craig §4.7, re-derived with sympy in lecture 09):

* θ1: seen from above, -s1 px + c1 py = d3, so with ρ = sqrt(px² + py²) ≥ |d3|:
  θ1 = atan2(py, px) - atan2(d3, ±sqrt(ρ² - d3²)); the sign is the *shoulder*: "left" (+, the
  reach X = c1 px + s1 py ≥ 0) or "right" (-).
* θ3: |p|² = a2² + a3² + d3² + d4² + 2 a2 (a3 c3 - d4 s3), so with
  κ = (|p|² - a2² - a3² - d3² - d4²) / (2 a2) (Craig's K, renamed: K is a rotation in this course),
  |κ| ≤ sqrt(a3² + d4²):
  θ3 = atan2(a3, d4) - atan2(κ, ±sqrt(a3² + d4² - κ²)). The *elbow* is "up" when it lies above
  the shoulder-wrist line seen facing the wrist: sign(X) (a3 s3 + d4 c3) > 0.
* θ2: in the arm plane (X, -pz) = Rot(θ2) (a2 + a3 c3 - d4 s3, a3 s3 + d4 c3).
* wrist: ^3R_6 = (^0R_3)^T R has third column (-s5 c4, c5, s4 s5) and second row
  (s5 c6, -s5 s6, c5): θ5 = atan2(±sqrt(r13² + r33²), r23), then θ4, θ6. "noflip" takes
  θ5 in [0, π], "flip" the other solution (θ4 + π, -θ5, θ6 + π).

Singular boundaries are decided with explicit tolerances and snapped (the square roots set to
exactly 0, θ5 to exactly 0 or π), so no answer depends on the last bit of a BLAS kernel.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._validate import as_robot_length, as_tol
from ..transforms import wrap_angle
from ._ops import ARRAY, SCALAR
from .dh import DHChain, Link, split_q
from .ik import IKBatch, IKSolutions
from .joint_limits import FROM_CORKE_DEG, JOINT_LIMITS, PUBLISHED_QLIM_DEG
from .puma560_jacobian import puma560_jacobian

__all__ = ["Puma560", "BRANCH_LABELS", "FLAG_KEYS", "MESSAGES", "DEFAULTS", "PUBLISHED_QLIM_DEG", "FROM_CORKE_DEG",
           "JOINT_LIMITS"]  # fmt: skip

#: The lecture's lengths (metres).
DEFAULTS = {"a2": 0.4318, "a3": 0.0203, "d3": 0.15005, "d4": 0.4318}


#: The eight branches, in the order of the second axis of ``ik_batch``'s ``q``.
BRANCH_LABELS: tuple[str, ...] = tuple(
    f"{s}/{e}/{w}" for s in ("left", "right") for e in ("up", "down") for w in ("noflip", "flip")
)
#: Singularity keys; bit b of ``IKBatch.flags`` stands for ``FLAG_KEYS[b]``.
FLAG_KEYS = ("shoulder", "elbow", "wrist", "base_axis", "joint2_axis")
MESSAGES = {
    "shoulder": "the wrist centre lies on the cylinder ρ = |d3| around the base axis, so the left and right "
    "shoulder solutions coincide",
    "elbow": "the arm is fully stretched or folded (|κ| = sqrt(a3² + d4²)), so elbow up and elbow down coincide",
    "wrist": "sin θ5 = 0: the axes of joints 4 and 6 are aligned and only θ4 + θ6 (θ5 = 0) or θ4 - θ6 (θ5 = π) "
    "is defined; θ4 takes its value in `near` (else 0) and flip = noflip",
    "base_axis": "d3 = 0 and the wrist centre is on the base axis: θ1 is free (its value in `near`, else 0)",
    "joint2_axis": "the wrist centre is on the axis of joint 2: θ2 is free (its value in `near`, else 0)",
}
_SH = np.array([1.0 if lab.startswith("left") else -1.0 for lab in BRANCH_LABELS])
_EL = np.array([1.0 if "/up/" in lab else -1.0 for lab in BRANCH_LABELS])
_WR = np.array([1.0 if lab.endswith("noflip") else -1.0 for lab in BRANCH_LABELS])
_H = math.pi / 2
_FREE = 1e-3  # a free joint takes `near` only within 1e-3 x ltol = 1e-10 x size of the singular point
_WRIST_FREE = 5e-10  # likewise θ4 only where that moves the hand by < 5e-10 (sin θ5 |sin Δθ4|)
#: The smallest accepted ``tol``: sin θ5 is computed with an error of a few 1e-16, so a threshold below
#: 1e-12 would let rounding noise decide the branch structure.
TOL_MIN = 1e-12
_BLOCK = 10_000  # ik_batch works through the poses in blocks: working memory stays a few times the result's


# ----------------------------------------------------------------------------- the closed forms (written once)
def _fk_entries(o: Any, q: list[Any], a2: float, a3: float, d3: float, d4: float) -> tuple[Any, ...]:
    """^0T_6 as 12 entries (rows of R | p), eq. 3.14 and Craig's (3.13); floats or arrays."""
    c1, s1, c2, s2 = o.cos(q[0]), o.sin(q[0]), o.cos(q[1]), o.sin(q[1])
    c4, s4, c5, s5, c6, s6 = o.cos(q[3]), o.sin(q[3]), o.cos(q[4]), o.sin(q[4]), o.cos(q[5]), o.sin(q[5])
    t23 = q[1] + q[2]
    c23, s23 = o.cos(t23), o.sin(t23)
    a = c4 * c5 * c6 - s4 * s6  # shared sub-expressions of eq. 3.14
    b = s4 * c5 * c6 + c4 * s6
    e = -c4 * c5 * s6 - s4 * c6
    f = c4 * c6 - s4 * c5 * s6
    g = c23 * c4 * s5 + s23 * c5
    u1, u2, u3 = c23 * a - s23 * s5 * c6, c23 * e + s23 * s5 * s6, a2 * c2 + a3 * c23 - d4 * s23
    return (
        c1 * u1 + s1 * b, c1 * u2 + s1 * f, -c1 * g - s1 * s4 * s5, c1 * u3 - d3 * s1,
        s1 * u1 - c1 * b, s1 * u2 - c1 * f, -s1 * g + c1 * s4 * s5, s1 * u3 + d3 * c1,
        -s23 * a - c23 * s5 * c6, -s23 * e + c23 * s5 * s6, s23 * c4 * s5 - c23 * c5, -a3 * s23 - a2 * s2 - d4 * c23,
    )  # fmt: skip


def _reach(o: Any, px: Any, py: Any, pz: Any, L: tuple[float, ...], ltol: float) -> tuple[Any, ...]:
    """Pose terms shared by every branch: ρ², κ, S1 = sqrt(ρ² - d3²), S3 = sqrt(a3² + d4² - κ²),
    unreachable flags and the singular flags (a root below ``ltol``). S3 is snapped to exactly 0 there,
    and S1 where the two shoulder branches are one (|d3| >= ltol, or the wrist centre on the base axis):
    that moves the wrist centre by about S²/size < 1e-14 size (|p| and ρ depend on the roots to second
    order), while with d3 = 0 a wrist centre at ρ ≈ S1 from the axis keeps both distinct branches."""
    a2, a3, d3, d4 = L
    sqtol = ltol * ltol * 1e2  # 1e-12 L²: how far inside the boundary rounding may land
    rho2 = px * px + py * py
    S1sq = rho2 - d3 * d3
    K = (rho2 + pz * pz - a2 * a2 - a3 * a3 - d3 * d3 - d4 * d4) / (2.0 * a2)
    S3sq = a3 * a3 + d4 * d4 - K * K
    base, reach = S1sq < -sqtol, S3sq < -sqtol
    S1, S3 = o.sqrt(o.maximum(S1sq, 0.0)), o.sqrt(o.maximum(S3sq, 0.0))
    sh_sing, el_sing = S1 < ltol, S3 < ltol
    rho = o.sqrt(rho2)
    axis = rho < ltol  # possible (and reachable) only when d3 = 0
    # θ1 is set free (taken from `near`) only where that moves the hand by at most 1e-9 x size (2 ρ)
    axis_free = rho < ltol * _FREE
    # left and right are one solution when S1 is tiny beside |d3|; with d3 = 0 they differ by π in θ1
    sh_drop = sh_sing & ((abs(d3) >= ltol) | axis_free)
    S1, S3 = o.where(sh_drop, 0.0, S1), o.where(el_sing, 0.0, S3)
    return rho2, K, S1, S3, base, reach, sh_sing, el_sing, axis, sh_drop, axis_free


def _arm(o: Any, P: tuple[Any, Any, Any], terms: tuple[Any, ...], L: tuple[float, ...], sh: Any, el: Any,
         near: Any, ltol: float) -> tuple[Any, ...]:  # fmt: skip
    """θ1, θ2, θ3 of one (shoulder, elbow) branch and whether θ2 was free (wrist centre on joint 2's axis)."""
    px, py, pz = P
    a2, a3, d3, d4 = L
    _, K, S1, S3, _, _, _, _, _, _, axis_free = terms
    phi = o.where(axis_free, 0.0 if near is None else near[0], o.atan2(py, px))
    X = sh * S1  # reach along x1
    t1 = phi - o.atan2(d3, X)  # also right for d3 = 0: atan2(0, ±S1) = 0 or π (signed zero)
    t3 = o.atan2(a3, d4) - o.atan2(K, sh * el * S3)  # + root for left/up and right/down
    c3, s3 = o.cos(t3), o.sin(t3)
    vx, vy = a2 + a3 * c3 - d4 * s3, a3 * s3 + d4 * c3
    v = o.hypot(vx, vy)
    j2 = v < ltol
    t2 = o.where(v < ltol * _FREE, 0.0 if near is None else near[1], o.atan2(-pz, X) - o.atan2(vy, vx))
    return t1, t2, t3, j2


def _wrist_terms(o: Any, R: tuple[Any, ...], t1: Any, t23: Any) -> tuple[Any, ...]:
    """Entries of M = ^3R_6 = (^0R_3)^T R that fix the wrist: (m02, m12, m22) = (-s5 c4, c5, s4 s5)
    give θ4; then ^4R_6 = Ry(θ4)^T M (M = Ry(θ4) Rz(θ5) Rx(-90°) Rz(θ6)) gives θ5 and θ6 from m00, m01,
    m20, m21 as well."""
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = R
    c1, s1, c23, s23 = o.cos(t1), o.sin(t1), o.cos(t23), o.sin(t23)
    u0, u1, u2 = c1 * r11 + s1 * r21, c1 * r12 + s1 * r22, c1 * r13 + s1 * r23
    m02, m12, m22 = c23 * u2 - s23 * r33, -s23 * u2 - c23 * r33, -s1 * r13 + c1 * r23
    m10, m11 = -s23 * u0 - c23 * r31, -s23 * u1 - c23 * r32
    m00, m20, m01 = c23 * u0 - s23 * r31, -s1 * r11 + c1 * r21, c23 * u1 - s23 * r32
    m21 = -s1 * r12 + c1 * r22
    return m02, m12, m22, m10, m11, m00, m20, m01, m21


def _wrist(o: Any, m: tuple[Any, ...], w: Any, near: Any, tol: float) -> tuple[Any, Any, Any, Any, Any]:
    """θ4, θ5, θ6 of the wrist branch ``w`` (+1 noflip, -1 flip), the singular flag (sin θ5 < tol) and
    whether θ4 was set free (flip is then the same solution and dropped): without ``near`` where
    sin θ5 < min(tol, 5e-10), with it where sin θ5 < tol and θ4 = near[3] moves the hand by < 5e-10.

    θ4 comes from the third column of M = ^3R_6; θ5 and θ6 then come from ^4R_6 = Ry(θ4)^T M, so
    they absorb any error of θ4 and the three angles reproduce M to rounding whatever θ4 is. At the
    free wrist θ4 takes its value in ``near`` (else 0) and θ5, θ6 follow from it; that moves the hand by
    at most 5e-10. Elsewhere below ``tol`` both branches are kept (flagged), each exact."""
    m02, m12, m22, m10, m11, m00, m20, m01, m21 = m
    s5 = o.hypot(m02, m22)
    t4 = o.atan2(w * m22, -w * m02)
    sing = s5 < tol
    if near is None:
        free = s5 < min(tol, _WRIST_FREE)
        take = free
    else:  # θ4 = near[3] moves the hand by about s5 |sin(near[3] - θ4)|: free where that stays below 5e-10
        free = sing & (s5 * o.abs(o.sin(near[3] - t4)) < _WRIST_FREE)
        # and a branch whose θ4 is within the rounding cone of near[3] takes it (keeps the start exactly)
        take = free | (s5 * o.abs(o.atan2(o.sin(near[3] - t4), o.cos(near[3] - t4))) < _WRIST_FREE)
    if o.any(take):
        t4 = o.where(take, 0.0 if near is None else near[3], t4)
    c4, s4 = o.cos(t4), o.sin(t4)
    # ^4R_6 = Rz(θ5) Rx(-90°) Rz(θ6) = [[c5 c6, -c5 s6, -s5], [s5 c6, -s5 s6, c5], [-s6, -c6, 0]]
    t5 = o.atan2(s4 * m22 - c4 * m02, m12)
    t6 = o.atan2(-(s4 * m00 + c4 * m20), -(s4 * m01 + c4 * m21))
    return t4, t5, t6, sing, free


def _reason(terms: tuple[Any, ...], i: Any, L: tuple[float, ...]) -> str:
    rho2, K, _, _, base, reach, *_ = terms
    a2, a3, d3, d4 = L
    rho2_i, K_i = float(rho2[i] if np.ndim(rho2) else rho2), float(K[i] if np.ndim(K) else K)
    if bool(base[i] if np.ndim(base) else base):
        return (
            f"too close to the base axis: the wrist centre is at distance ρ = {math.sqrt(rho2_i):.6g} "
            f"from the base (z0) axis, less than the shoulder offset |d3| = {abs(d3):.6g}"
        )
    return (
        f"out of reach: |κ| = {abs(K_i):.6g} exceeds sqrt(a3² + d4²) = {math.hypot(a3, d4):.6g} "
        f"(the wrist centre is too far from, or too near to, the shoulder)"
    )


class Puma560(DHChain):
    """The PUMA-560 of the lecture's table (modified DH, metres), with closed-form fk and ik.

    Named configurations (``arm.q(name)``): ``qz`` all zeros (upper arm horizontal, forearm
    hanging down); ``qr`` ready, arm straight up; ``qs`` stretched, arm horizontal along x;
    ``qn`` nominal, elbow bent with the wrist pointing down.

    ``joint_limits`` are the published joint ranges (:data:`JOINT_LIMITS`, from Corke's Robotics
    Toolbox and Wang & Chen 1991, in this model's angles); ``sol.within_limits(arm.joint_limits)``
    keeps the IK solutions a real PUMA-560 can take. ``qlim`` stays a full turn per joint (the
    sliders' range): the limits are a choice a lecture makes, not a property of the table.

    >>> arm = Puma560()
    >>> np.round(arm.fk(np.zeros(6))[:3, 3], 5)  # (a2 + a3, d3, -d4)
    array([ 0.4521 ,  0.15005, -0.4318 ])
    >>> sol = arm.ik(arm.fk(arm.q("qn")), near=arm.q("qn"))
    >>> len(sol), sol.labels[0], bool(np.allclose(sol[0], arm.q("qn")))
    (8, 'left/up/noflip', True)
    """

    #: The foot of the drawn pedestal, this far below the base origin (metres; drawing only).
    pedestal = 0.35
    #: The published joint ranges (radians, (6, 2), read-only): :data:`JOINT_LIMITS`.
    joint_limits: np.ndarray | None = JOINT_LIMITS

    def __init__(
        self,
        a2: float = DEFAULTS["a2"],
        a3: float = DEFAULTS["a3"],
        d3: float = DEFAULTS["d3"],
        d4: float = DEFAULTS["d4"],
    ) -> None:
        a2 = as_robot_length(a2, "a2", positive=True, what="the upper-arm length a2 in metres (a positive number)")
        a3, d3, d4 = (
            as_robot_length(v, n, what=f"the length {n} in metres") for v, n in ((a3, "a3"), (d3, "d3"), (d4, "d4"))
        )
        if math.hypot(a3, d4) <= 0.0:
            raise ValueError("a3, d4: expected a forearm of non-zero length (a3² + d4² > 0), got a3 = d4 = 0")
        self._L = (a2, a3, d3, d4)
        self._ltol = 1e-7 * (a2 + math.hypot(a3, d4) + abs(d3))  # length tolerance: singular boundaries
        links = [
            Link(0.0, 0.0, 0.0), Link(-_H, 0.0, 0.0), Link(0.0, a2, d3),
            Link(-_H, a3, d4), Link(_H, 0.0, 0.0), Link(-_H, 0.0, 0.0),
        ]  # fmt: skip
        configs = {
            "qz": np.zeros(6),
            "qr": np.array([0.0, -_H, -_H, 0.0, 0.0, 0.0]),
            "qs": np.array([0.0, 0.0, -_H, 0.0, 0.0, 0.0]),
            "qn": np.array([0.0, -np.pi / 4, -np.pi / 4, 0.0, np.pi / 4, 0.0]),
        }
        super().__init__(links, name="PUMA-560", units="m", configurations=configs)

    @property
    def lengths(self) -> dict[str, float]:
        """The four lengths of the table: a2, a3, d3, d4 (metres)."""
        return dict(zip(("a2", "a3", "d3", "d4"), self._L, strict=True))

    def parameters(self) -> dict[str, float]:
        """The four lengths of the table (metres)."""
        return self.lengths

    def __repr__(self) -> str:
        return f"Puma560(a2={self._L[0]:g}, a3={self._L[1]:g}, d3={self._L[2]:g}, d4={self._L[3]:g})"

    # ---- forward kinematics ------------------------------------------------------------
    def fk(self, q: Any) -> np.ndarray:
        """^0T_6 from the closed form (eq. 3.14): (4, 4) for q (6,), (N, 4, 4) for q (N, 6).

        Equal to the product of the six link matrices (the tests check it against
        :meth:`DHChain.fk`'s column walk), a few µs for one pose in plain floats.
        """
        cols, batch = split_q(q, 6, self.check_q)
        e = _fk_entries(SCALAR if batch is None else ARRAY, cols, *self._L)
        if batch is None:
            return np.array([e[0:4], e[4:8], e[8:12], (0.0, 0.0, 0.0, 1.0)])
        T = np.zeros((batch, 4, 4))
        for k, v in enumerate(e):
            T[:, k // 4, k % 4] = v
        T[:, 3, 3] = 1.0
        return T

    def jacobian(self, q: Any) -> np.ndarray:
        """The geometric Jacobian (6, 6) or (N, 6, 6) in closed form: :mod:`~.puma560_jacobian`."""
        return puma560_jacobian(*split_q(q, 6, self.check_q), self._L)

    def points(self, q: Any) -> np.ndarray:
        """Six points drawing the arm with its shoulder offset visible: (6, 3) or (N, 6, 3).

        A polyline through the frame origins hides the sideways offset d3 (frames {1}, {2} sit at
        the base origin and {4} = {5} = {6} at the wrist centre). The points are: the foot of the
        pedestal, the base origin, the end of the offset d3 along z2, the origin of {3} (end of
        a2), the end of the step a3 along x3, and the wrist centre (end of d4).

        >>> np.round(Puma560().points(np.zeros(6)), 5) + 0.0  # at qz the wrist centre is (a2 + a3, d3, -d4)
        array([[ 0.     ,  0.     , -0.35   ],
               [ 0.     ,  0.     ,  0.     ],
               [ 0.     ,  0.15005,  0.     ],
               [ 0.4318 ,  0.15005,  0.     ],
               [ 0.4521 ,  0.15005,  0.     ],
               [ 0.4521 ,  0.15005, -0.4318 ]])
        """
        F = self.frames(q)
        o = F[..., :3, 3]
        _, a3, d3, _ = self._L
        foot = o[..., 0, :] - self.pedestal * F[..., 0, :3, 2]
        shoulder = o[..., 2, :] + d3 * F[..., 2, :3, 2]
        step = o[..., 3, :] + a3 * F[..., 3, :3, 0]
        return np.stack([foot, o[..., 0, :], shoulder, o[..., 3, :], step, o[..., 4, :]], axis=-2)

    # ---- inverse kinematics ------------------------------------------------------------
    def ik(self, T: Any, near: Any = None, *, tol: float = 1e-7) -> IKSolutions:
        """Every joint vector reaching the pose T (closed form, Craig §4.7): up to eight, labelled.

        Eight solutions in general (shoulder left/right x elbow up/down x wrist noflip/flip),
        fewer at a singularity (duplicates removed; each remaining row is flagged and a
        :class:`~.ik.SingularityWarning` says which joints are not unique). With ``near`` the
        solutions are sorted by wrapped joint distance to it, nearest first, and joints left
        free at a singularity take their value from it. An unreachable T gives ``success``
        False and the reason. ``tol`` is the threshold on sin θ5 below which the wrist counts
        as singular.

        >>> arm = Puma560()
        >>> T = np.eye(4)
        >>> T[:3, 3] = [2.0, 0.0, 0.0]
        >>> arm.ik(T).reason[:13]
        'out of reach:'
        """
        tol = as_tol(tol, "tol", lower=TOL_MIN)
        Tm = self._check_poses(T)
        if Tm.shape[0] != 1:
            raise ValueError(f"T: expected one pose (4, 4) (use ik_batch for several), got shape {Tm.shape}")
        nr = self._check_near(near)
        (r11, r12, r13, px), (r21, r22, r23, py), (r31, r32, r33, pz), _ = Tm[0].tolist()
        nl = None if nr is None else nr.tolist()
        o, L, P, R = SCALAR, self._L, (px, py, pz), (r11, r12, r13, r21, r22, r23, r31, r32, r33)
        terms = _reach(o, px, py, pz, L, self._ltol)
        if terms[4] or terms[5]:
            return IKSolutions(np.zeros((0, 6)), (), (), MESSAGES, False, _reason(terms, 0, L), self.name,
                               "closed form", self.revolute, joints=self.joint_symbols)  # fmt: skip
        sh_sing, el_sing, axis, sh_drop = terms[6], terms[7], terms[8], terms[9]
        rows, labels, flags = [], [], []
        for ish, sh in enumerate((1.0, -1.0)):
            if ish and sh_drop:
                continue
            for iel, el in enumerate((1.0, -1.0)):
                if iel and el_sing:
                    continue
                t1, t2, t3, j2 = _arm(o, P, terms, L, sh, el, nl, self._ltol)
                m = _wrist_terms(o, R, t1, t2 + t3)
                for iwr, wr in enumerate((1.0, -1.0)):
                    t4, t5, t6, sing, free = _wrist(o, m, wr, nl, tol)
                    if iwr and free:
                        continue
                    rows.append((t1, t2, t3, t4, t5, t6))
                    labels.append(BRANCH_LABELS[4 * ish + 2 * iel + iwr])
                    on = (sh_sing, el_sing, sing, axis, j2)
                    flags.append(tuple(k for k, f in zip(FLAG_KEYS, on, strict=True) if f) if any(on) else ())
        keys = FLAG_KEYS if any(flags) else ()
        sol = IKSolutions(wrap_angle(np.array(rows)), tuple(labels), tuple(flags),
                          {k: MESSAGES[k] for k in keys if any(k in f for f in flags)}, True, "", self.name,
                          "closed form", self.revolute, joints=self.joint_symbols)  # fmt: skip
        return self._finish(sol, nr)

    def ik_batch(self, T: Any, near: Any = None, *, tol: float = 1e-7) -> IKBatch:
        """All eight branches for N poses T (N, 4, 4), vectorised: an :class:`~.ik.IKBatch`.

        Branch order :data:`BRANCH_LABELS`; unreachable poses are marked (``reason``), never
        raised, their entries 0. ``near`` (6,) or (N, 6) gives the representative of joints
        left free at a singularity. The poses are processed in blocks of 10,000, so the working
        memory stays a few times the size of the result.

        >>> arm = Puma560()
        >>> b = arm.ik_batch(arm.fk(np.zeros((2, 6)) + 0.3))
        >>> b.q.shape, int(b.valid.sum()), b.reachable.tolist()
        ((2, 8, 6), 16, [True, True])
        """
        tol = as_tol(tol, "tol", lower=TOL_MIN)
        Tb = self._check_poses(T)
        N = Tb.shape[0]
        nr = self._check_near(near, batch=N)
        q = np.zeros((N, 8, 6))
        valid = np.zeros((N, 8), dtype=bool)
        flags = np.zeros((N, 8), dtype=np.int64)
        reason = np.full(N, "", dtype=object)
        with np.errstate(all="ignore"):  # unreachable poses may overflow or take roots of negatives: masked below
            for start in range(0, N, _BLOCK):
                sl = slice(start, min(start + _BLOCK, N))
                self._batch_block(Tb[sl], None if nr is None else nr[sl], tol, q[sl], valid[sl], flags[sl], reason[sl])
        return IKBatch(q, valid, BRANCH_LABELS, flags, FLAG_KEYS, MESSAGES, reason.astype(str), self.name,
                       "closed form", self.revolute, joints=self.joint_symbols)  # fmt: skip

    def _batch_block(self, T: np.ndarray, near: np.ndarray | None, tol: float, q: np.ndarray, valid: np.ndarray,
                     flags: np.ndarray, reason: np.ndarray) -> None:  # fmt: skip
        o, L = ARRAY, self._L
        col = [T[:, i, j, None] for i in range(3) for j in range(4)]  # (n, 1) each
        P = (col[3], col[7], col[11])
        R = (col[0], col[1], col[2], col[4], col[5], col[6], col[8], col[9], col[10])
        nr = None if near is None else [near[:, j, None] for j in range(6)]
        terms = _reach(o, *P, L, self._ltol)
        t1, t2, t3, j2 = _arm(o, P, terms, L, _SH, _EL, nr, self._ltol)
        t4, t5, t6, wr_sing, wr_free = _wrist(o, _wrist_terms(o, R, t1, t2 + t3), _WR, nr, tol)
        base, reach, sh_sing, el_sing, axis, sh_drop = terms[4:10]
        bad = base | reach  # (n, 1)
        for j, t in enumerate((t1, t2, t3, t4, t5, t6)):
            q[..., j] = np.where(bad, 0.0, wrap_angle(t))
        valid[:] = ~(bad | (sh_drop & (_SH < 0)) | (el_sing & (_EL < 0)) | (wr_free & (_WR < 0)))
        bits = sh_sing * 1 + el_sing * 2 + wr_sing * 4 + axis * 8 + j2 * 16
        flags[:] = np.where(bad, 0, bits)
        for i in np.flatnonzero(bad[:, 0]):
            reason[i] = _reason(terms, (i, 0), L)
