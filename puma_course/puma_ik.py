"""Closed-form inverse kinematics of the PUMA-560 (Craig's modified DH, lecture 09).

The model is the table of :func:`puma_course.robots.puma560` (Meghdari's lecture,
Craig §3.7): α = (0, -90°, 0, -90°, 90°, -90°), a2 and d3 on link 3, a3 and d4
on link 4, a spherical wrist whose centre is the origin of frames {4}, {5}, {6}.
So the position column p of ^0T_6 is the wrist centre and depends on θ1, θ2, θ3
only; the orientation then fixes θ4, θ5, θ6 (Craig §4.7, re-derived in notebook 09):

* θ1: the wrist centre seen from above satisfies  -s1 px + c1 py = d3, so with
  ρ = sqrt(px² + py²) ≥ |d3|:  θ1 = atan2(py, px) - atan2(d3, ±sqrt(ρ² - d3²)).
  The sign is the *shoulder*: "left" (+, the reach X = c1 px + s1 py ≥ 0) or
  "right" (-, X ≤ 0).
* θ3: |p|² = a2² + a3² + d3² + d4² + 2 a2 (a3 c3 - d4 s3), so with
  K = (|p|² - a2² - a3² - d3² - d4²) / (2 a2) and |K| ≤ sqrt(a3² + d4²):
  θ3 = atan2(a3, d4) - atan2(K, ±sqrt(a3² + d4² - K²)).
  The *elbow* is "up" when it lies above the shoulder-wrist line as seen
  facing the wrist: sign(X) (a3 s3 + d4 c3) > 0.
* θ2: in the arm plane (X, -pz) = Rot(θ2) (a2 + a3 c3 - d4 s3, a3 s3 + d4 c3),
  so θ2 = atan2(-pz, X) - atan2(a3 s3 + d4 c3, a2 + a3 c3 - d4 s3).
* wrist: ^3R_6 = (^0R_3)^T R has third column (-s5 c4, c5, s4 s5) and second row
  (s5 c6, -s5 s6, c5): θ5 = atan2(±sqrt(r13² + r33²), r23) and θ4, θ6 follow.
  "noflip" takes θ5 in [0, π], "flip" the other solution (θ4 + π, -θ5, θ6 + π).

Angles are wrapped to (-π, π]. Lengths are in the model's units (metres).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._validate import as_array, as_transform
from .transforms import wrap_angle

__all__ = [
    "IKResult",
    "IKBatch",
    "SingularityWarning",
    "BRANCH_LABELS",
    "SHOULDER_SINGULAR",
    "ELBOW_SINGULAR",
    "WRIST_SINGULAR",
    "BASE_AXIS_SINGULAR",
    "JOINT2_AXIS_SINGULAR",
    "ik",
    "ik_batch",
    "wrap",
    "joint_distance",
]

#: The eight branches, in the order of the second axis of :func:`ik_batch`'s ``q``.
BRANCH_LABELS: tuple[str, ...] = tuple(
    f"{s}/{e}/{w}" for s in ("left", "right") for e in ("up", "down") for w in ("noflip", "flip")
)
_SH = np.array([1.0 if lab.startswith("left") else -1.0 for lab in BRANCH_LABELS])
_EL = np.array([1.0 if "/up/" in lab else -1.0 for lab in BRANCH_LABELS])
_WR = np.array([1.0 if lab.endswith("noflip") else -1.0 for lab in BRANCH_LABELS])
_RIGHT, _DOWN, _FLIP = _SH < 0, _EL < 0, _WR < 0

# singularity flags (bits of IKBatch.flags / IKResult.flags)
SHOULDER_SINGULAR = 1  #: ρ = |d3|: the wrist centre is on the cylinder of radius |d3|; left = right
ELBOW_SINGULAR = 2  #: |K| = sqrt(a3² + d4²): arm stretched or folded; elbow up = down
WRIST_SINGULAR = 4  #: sin θ5 = 0: axes 4 and 6 aligned; only θ4 ± θ6 is defined
BASE_AXIS_SINGULAR = 8  #: d3 = 0 and the wrist centre on the base axis: θ1 undefined
JOINT2_AXIS_SINGULAR = 16  #: the wrist centre on the axis of joint 2: θ2 undefined

_REASONS = {
    SHOULDER_SINGULAR: "shoulder singularity: the wrist centre lies on the cylinder ρ = |d3| around the base axis, "
    "so the left and right shoulder solutions coincide",
    ELBOW_SINGULAR: "elbow singularity: the arm is fully stretched or folded (|K| = sqrt(a3² + d4²)), "
    "so elbow up and elbow down coincide",
    WRIST_SINGULAR: "wrist singularity: sin θ5 = 0, the axes of joints 4 and 6 are aligned and only "
    "θ4 + θ6 (θ5 = 0) or θ4 - θ6 (θ5 = π) is defined; θ4 was set to a representative value "
    "(its value in `near`, else 0) and flip = noflip",
    BASE_AXIS_SINGULAR: "base-axis singularity: d3 = 0 and the wrist centre is on the base axis, θ1 is arbitrary "
    "(set to its value in `near`, else 0)",
    JOINT2_AXIS_SINGULAR: "the wrist centre is on the axis of joint 2, θ2 is arbitrary "
    "(set to its value in `near`, else 0)",
}


class SingularityWarning(UserWarning):
    """A pose reached at a singular configuration: some joints are not uniquely defined."""


wrap = wrap_angle  # angles to (-π, π]; the package's one rule (transforms.wrap_angle)


def joint_distance(q: Any, q_ref: Any) -> np.ndarray:
    """Euclidean norm of the wrapped joint differences wrap(q - q_ref), over the last axis.

    >>> float(joint_distance([np.pi - 0.1, 0], [-np.pi + 0.1, 0]))  # across ±π: 0.2, not 2π - 0.2
    0.2
    """
    q, q_ref = np.asarray(q, dtype=float), np.asarray(q_ref, dtype=float)
    if q.ndim == 0 or q_ref.ndim == 0 or q.shape[-1] != q_ref.shape[-1]:
        raise ValueError(f"q, q_ref: expected joint vectors of the same length, got shapes {q.shape} and {q_ref.shape}")
    d = wrap(q - q_ref)
    return np.round(np.sqrt(np.sum(d * d, axis=-1)), 15)


@dataclass
class IKBatch:
    """All eight branches for N poses (see :func:`ik_batch`).

    ``q`` (N, 8, 6) radians in (-π, π], branch order :data:`BRANCH_LABELS`;
    ``valid`` (N, 8): the branch reaches the pose and is not a duplicate of an
    earlier branch at a singularity; ``reachable`` (N,); ``reason`` (N,) an
    empty string or why the pose cannot be reached; ``flags`` (N, 8) bit mask of
    singularities. Entries of unreachable poses are 0 (never NaN) and invalid.

    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> T_far = np.eye(4)
    >>> T_far[:3, 3] = [2.0, 0.0, 0.0]
    >>> b = ik_batch(np.stack([arm.fk(arm.q("qn")), T_far]))
    >>> b.q.shape, b.valid.sum(axis=1).tolist(), b.reachable.tolist()
    ((2, 8, 6), [8, 0], [True, False])
    >>> b.reason[1][:13], float(np.abs(b.q[1]).max())
    ('out of reach:', 0.0)
    """

    q: np.ndarray
    valid: np.ndarray
    reachable: np.ndarray
    reason: np.ndarray
    flags: np.ndarray


@dataclass
class IKResult:
    """Every configuration reaching one pose; behaves like the (k, 6) array ``q``.

    ``labels[i]`` names the branch of ``q[i]`` (shoulder/elbow/wrist);
    ``flags[i]`` its singularity bits; ``singular`` the reasons, in words.

    >>> r = IKResult(q=np.zeros((1, 6)), labels=["left/up/noflip"], flags=np.zeros(1, dtype=int))
    >>> np.asarray(r).shape, len(r), r.is_singular
    ((1, 6), 1, False)
    """

    q: np.ndarray
    labels: list[str]
    flags: np.ndarray
    singular: list[str] = field(default_factory=list)

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return self.q if dtype is None else self.q.astype(dtype)

    def __len__(self) -> int:
        return len(self.q)

    def __getitem__(self, i: Any) -> np.ndarray:
        return self.q[i]

    def __iter__(self):
        return iter(self.q)

    @property
    def is_singular(self) -> bool:
        """True when any solution sits at a singularity."""
        return bool(self.singular)

    def nearest(self, q_ref: Any) -> np.ndarray:
        """The solution closest to ``q_ref`` in wrapped joint distance."""
        ref = as_array(q_ref, "q_ref", (6,), what="a joint vector of shape (6,)")
        return self.q[int(np.argmin(joint_distance(self.q, ref)))].copy()

    def __repr__(self) -> str:
        lines = [f"IKResult: {len(self.q)} solution(s)" + (" [singular]" if self.singular else "")]
        for lab, row in zip(self.labels, self.q, strict=True):
            values = " ".join(f"{v:8.4f}" for v in np.round(row, 4) + 0.0)  # fixed width: rows line up
            lines.append(f"  {lab:<18} q = [{values}]")
        return "\n".join(lines)


def _lengths(a2: float, a3: float, d3: float, d4: float) -> tuple[float, float, float, float]:
    if all(type(v) is float and np.isfinite(v) for v in (a2, a3, d3, d4)) and a2 > 0 and (a3 or d4):
        return a2, a3, d3, d4  # fast path: already plain floats
    pairs = (("a2", a2), ("a3", a3), ("d3", d3), ("d4", d4))
    out = tuple(float(as_array(v, n, (), what="a length (a number)")) for n, v in pairs)
    if out[0] <= 0:
        raise ValueError(f"a2: expected a positive upper-arm length, got {out[0]}")
    if np.hypot(out[1], out[3]) <= 0:
        raise ValueError("a3, d4: expected a forearm of non-zero length (a3² + d4² > 0), got a3 = d4 = 0")
    return out  # type: ignore[return-value]


def _reason_reach(dist: float, K: float, a3: float, d4: float) -> str:
    return (
        f"out of reach: the wrist centre is {dist:.6g} from the origin (where axes 1 and 2 cross); "
        f"|K| = {abs(K):.6g} exceeds sqrt(a3² + d4²) = {math.hypot(a3, d4):.6g}"
    )


def _reason_base(rho: float, d3: float) -> str:
    return (
        f"too close to the base axis: the wrist centre is at distance ρ = {rho:.6g} "
        f"from the base (z0) axis, less than the shoulder offset |d3| = {abs(d3):.6g}"
    )


def _wrap1(a: float) -> float:
    return math.pi - (math.pi - a) % (2.0 * math.pi)


def _solve_one(
    T: np.ndarray, a2: float, a3: float, d3: float, d4: float, near: np.ndarray | None, tol: float
) -> tuple[list[tuple[int, list[float], int]], str]:
    """The closed form for one pose in plain floats (the fast path of :func:`ik`; :func:`_core` is the batch).

    Same formulas, branch order and tolerances as :func:`_core`, but only the distinct
    branches are computed (2 shoulders, 2 elbows, 4 wrists, the flip by symmetry).
    Returns ``([(branch index, q, flags), ...], reason)``; reason is "" when reachable.
    """
    (r11, r12, r13, px), (r21, r22, r23, py), (r31, r32, r33, pz), _ = T.tolist()
    nr = None if near is None else near.tolist()
    L = a2 + math.hypot(a3, d4) + abs(d3)
    ltol, sqtol = 1e-7 * L, 1e-12 * L * L
    rho2 = px * px + py * py
    S1sq = rho2 - d3 * d3
    K = (rho2 + pz * pz - a2 * a2 - a3 * a3 - d3 * d3 - d4 * d4) / (2.0 * a2)
    S3sq = a3 * a3 + d4 * d4 - K * K
    if S1sq < -sqtol:
        return [], _reason_base(math.sqrt(rho2), d3)
    if S3sq < -sqtol:
        return [], _reason_reach(math.sqrt(rho2 + pz * pz), K, a3, d4)
    S1, S3 = math.sqrt(max(S1sq, 0.0)), math.sqrt(max(S3sq, 0.0))
    sh_sing, el_sing = S1 < ltol, S3 < ltol
    axis_case = math.sqrt(rho2) < ltol
    phi = (nr[0] if nr is not None else 0.0) if axis_case else math.atan2(py, px)
    psi = math.atan2(a3, d4)
    base_flags = SHOULDER_SINGULAR * sh_sing + ELBOW_SINGULAR * el_sing + BASE_AXIS_SINGULAR * axis_case
    out: list[tuple[int, list[float], int]] = []
    w = _wrap1
    for ish, sh in enumerate((1.0, -1.0)):
        if ish and sh_sing:
            continue
        X = sh * S1
        t1 = phi - math.atan2(d3, X)
        c1, s1 = math.cos(t1), math.sin(t1)
        u0, u1, u2 = c1 * r11 + s1 * r21, c1 * r12 + s1 * r22, c1 * r13 + s1 * r23
        m20, m22 = -s1 * r11 + c1 * r21, -s1 * r13 + c1 * r23
        for iel, el in enumerate((1.0, -1.0)):
            if iel and el_sing:
                continue
            t3 = psi - math.atan2(K, sh * el * S3)
            c3, s3 = math.cos(t3), math.sin(t3)
            vx, vy = a2 + a3 * c3 - d4 * s3, a3 * s3 + d4 * c3
            flags = base_flags
            if math.hypot(vx, vy) < ltol:
                t2 = nr[1] if nr is not None else 0.0
                flags |= JOINT2_AXIS_SINGULAR
            else:
                t2 = math.atan2(-pz, X) - math.atan2(vy, vx)
            t23 = t2 + t3
            c23, s23 = math.cos(t23), math.sin(t23)
            m02, m12 = c23 * u2 - s23 * r33, -s23 * u2 - c23 * r33
            m10, m11 = -s23 * u0 - c23 * r31, -s23 * u1 - c23 * r32
            s5 = math.hypot(m02, m22)
            k = 4 * ish + 2 * iel
            arm = [w(t1), w(t2), w(t3)]
            if s5 < tol:
                t4 = nr[3] if nr is not None else 0.0
                m00, m01 = c23 * u0 - s23 * r31, c23 * u1 - s23 * r32
                if m12 >= 0:
                    t5, t6 = 0.0, math.atan2(-m20, m00) - t4
                else:
                    t5, t6 = math.pi, t4 - math.atan2(-m01, -m00)
                out.append((k, arm + [w(t4), w(t5), w(t6)], flags | WRIST_SINGULAR))
            else:
                t4, t5, t6 = math.atan2(m22, -m02), math.atan2(s5, m12), math.atan2(-m11, m10)
                out.append((k, arm + [w(t4), w(t5), w(t6)], flags))
                out.append((k + 1, arm + [w(t4 + math.pi), w(-t5), w(t6 + math.pi)], flags))
    return out, ""


def _core(T: np.ndarray, a2: float, a3: float, d3: float, d4: float, near: np.ndarray | None, tol: float) -> IKBatch:
    """The closed form on validated transforms T (N, 4, 4); near None or (N, 6)."""
    N = T.shape[0]
    L = a2 + np.hypot(a3, d4) + abs(d3)  # length scale for tolerances
    ltol = 1e-7 * L
    sqtol = 1e-12 * L * L
    px, py, pz = T[:, 0, 3, None], T[:, 1, 3, None], T[:, 2, 3, None]  # (N, 1)

    # --- θ1 (shoulder) ---------------------------------------------------------
    rho2 = px * px + py * py
    S1sq = rho2 - d3 * d3
    base = S1sq < -sqtol
    S1 = np.sqrt(np.maximum(S1sq, 0.0))
    sh_sing = S1 < ltol
    X = _SH * S1  # (N, 8) reach along x1 for each branch
    axis_case = np.sqrt(rho2) < ltol  # only possible (reachable) when d3 = 0
    phi = np.arctan2(py, px)
    if near is not None:
        phi = np.where(axis_case, near[:, 0:1], phi)
    else:
        phi = np.where(axis_case, 0.0, phi)
    t1 = phi - np.arctan2(d3, X)  # also right for d3 = 0: atan2(0, ±S1) = 0 or π (signed zero)

    # --- θ3 (elbow) ------------------------------------------------------------
    K = (rho2 + pz * pz - a2 * a2 - a3 * a3 - d3 * d3 - d4 * d4) / (2.0 * a2)
    S3sq = a3 * a3 + d4 * d4 - K * K
    reach = S3sq < -sqtol
    S3 = np.sqrt(np.maximum(S3sq, 0.0))
    el_sing = S3 < ltol
    sgn3 = _SH * _EL  # + root when left/up or right/down (elbow up <=> sign(X)(a3 s3 + d4 c3) > 0)
    t3 = np.arctan2(a3, d4) - np.arctan2(K, sgn3 * S3)

    # --- θ2 --------------------------------------------------------------------
    c3, s3 = np.cos(t3), np.sin(t3)
    vx = a2 + a3 * c3 - d4 * s3
    vy = a3 * s3 + d4 * c3
    j2 = np.hypot(vx, vy) < ltol
    t2 = np.arctan2(-pz, X) - np.arctan2(vy, vx)
    any_j2 = j2.any()
    if any_j2:
        t2 = np.where(j2, near[:, 1:2] if near is not None else 0.0, t2)

    # --- wrist: ^3R_6 = (^0R_3)^T R --------------------------------------------
    t23 = t2 + t3
    c1, s1 = np.cos(t1), np.sin(t1)
    c23, s23 = np.cos(t23), np.sin(t23)
    R = T[:, :3, :3]
    u = [c1 * R[:, 0, j, None] + s1 * R[:, 1, j, None] for j in range(3)]  # x1 components of the columns
    r3 = [R[:, 2, j, None] for j in range(3)]
    m02 = c23 * u[2] - s23 * r3[2]  # -s5 c4
    m12 = -s23 * u[2] - c23 * r3[2]  # c5
    m22 = -s1 * R[:, 0, 2, None] + c1 * R[:, 1, 2, None]  # s4 s5
    m10 = -s23 * u[0] - c23 * r3[0]  # s5 c6
    m11 = -s23 * u[1] - c23 * r3[1]  # -s5 s6
    s5abs = np.hypot(m02, m22)
    wr_sing = s5abs < tol
    w = _WR
    t5 = np.arctan2(w * s5abs, m12)
    t4 = np.arctan2(w * m22, -w * m02)
    t6 = np.arctan2(-w * m11, w * m10)
    any_wr = wr_sing.any()
    if any_wr:
        m00 = c23 * u[0] - s23 * r3[0]  # c5 = +1: cos(θ4 + θ6)
        m20 = -s1 * R[:, 0, 0, None] + c1 * R[:, 1, 0, None]  # c5 = +1: -sin(θ4 + θ6)
        m01 = c23 * u[1] - s23 * r3[1]  # c5 = -1: -sin(θ4 - θ6)
        t4s = np.broadcast_to(near[:, 3:4] if near is not None else np.zeros((N, 1)), t4.shape)
        up = m12 >= 0
        total = np.where(up, np.arctan2(-m20, m00), np.arctan2(-m01, -m00))  # θ4 + θ6 or θ4 - θ6
        t6s = np.where(up, total - t4s, t4s - total)
        t4 = np.where(wr_sing, t4s, t4)
        t6 = np.where(wr_sing, t6s, t6)
        t5 = np.where(wr_sing, np.where(up, 0.0, np.pi), t5)

    q = wrap(np.stack([t1, t2, t3, t4, t5, t6], axis=-1))
    # --- validity: reachable and not a duplicate at a singularity ---------------
    bad = base | reach  # (N, 1)
    reachable = ~bad[:, 0]
    # invalid: unreachable, or a duplicate at a singularity (right = left, down = up, flip = noflip)
    valid = ~(bad | (sh_sing & _RIGHT) | (el_sing & _DOWN) | (wr_sing & _FLIP))
    flags = sh_sing * SHOULDER_SINGULAR + el_sing * ELBOW_SINGULAR + wr_sing * WRIST_SINGULAR
    if axis_case.any():
        flags = flags + axis_case * BASE_AXIS_SINGULAR
    if any_j2:
        flags = flags + j2 * JOINT2_AXIS_SINGULAR
    flags = np.broadcast_to(flags, (N, 8))
    reason = np.full(N, "", dtype=object)
    if not reachable.all():
        flags = flags.copy()
        q[~reachable] = 0.0
        flags[~reachable] = 0
        rp = np.sqrt(rho2[:, 0] + pz[:, 0] ** 2)
        for i in np.flatnonzero(reach[:, 0]):
            reason[i] = _reason_reach(rp[i], K[i, 0], a3, d4)
        for i in np.flatnonzero(base[:, 0]):
            reason[i] = _reason_base(np.sqrt(rho2[i, 0]), d3)
    flags = np.ascontiguousarray(flags, dtype=np.int64)
    return IKBatch(q=q, valid=valid, reachable=reachable, reason=reason.astype(str), flags=flags)


_LAST = np.array([0.0, 0.0, 0.0, 1.0])


def _fast_transform(T: Any) -> np.ndarray:
    """as_transform for one (4, 4) pose, with a cheap check first; the full check (and its message) on failure."""
    if isinstance(T, np.ndarray) and T.shape == (4, 4) and T.dtype == np.float64:
        (r11, r12, r13, _), (r21, r22, r23, _), (r31, r32, r33, _), last = T.tolist()
        cols = ((r11, r21, r31), (r12, r22, r32), (r13, r23, r33))
        ok = last == [0.0, 0.0, 0.0, 1.0] and all(math.isfinite(v) for row in cols for v in row)
        if ok:
            for i in range(3):
                for j in range(i, 3):
                    dot = sum(x * y for x, y in zip(cols[i], cols[j], strict=True))
                    if abs(dot - (i == j)) > 1e-6:
                        ok = False
            det = r11 * (r22 * r33 - r23 * r32) - r12 * (r21 * r33 - r23 * r31) + r13 * (r21 * r32 - r22 * r31)
            if ok and det > 0 and math.isfinite(T[0, 3] + T[1, 3] + T[2, 3]):
                return T
    return as_transform(T, "T")


def ik_batch(
    T: Any,
    a2: float = 0.4318,
    a3: float = 0.0203,
    d3: float = 0.15005,
    d4: float = 0.4318,
    *,
    near: Any | None = None,
    tol: float = 1e-7,
    check: bool = True,
) -> IKBatch:
    """All eight closed-form solutions for a batch of PUMA-560 poses T (N, 4, 4).

    Returns an :class:`IKBatch` with ``q`` (N, 8, 6) in branch order
    :data:`BRANCH_LABELS` and a ``valid`` mask; unreachable poses are marked,
    never raised (their reason is in ``reason``). ``near`` (6,) or (N, 6) gives
    the representative value of joints left free at a singularity. Vectorised:
    one pass of array operations for the whole batch (Craig §4.7).

    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> q0 = np.array([[0.1, -0.5, 0.3, 0.4, 0.6, -0.7]])
    >>> sol = ik_batch(arm.fk(q0))
    >>> sol.q.shape, int(sol.valid.sum())
    ((1, 8, 6), 8)
    >>> bool(np.allclose(arm.fk(sol.q[0]), arm.fk(q0[0])))
    True
    """
    a2, a3, d3, d4 = _lengths(a2, a3, d3, d4)
    Tb = as_transform(T, "T", batch=True) if check else np.asarray(T, dtype=float)
    if Tb.ndim == 2:
        Tb = Tb[None]
    nr = None
    if near is not None:
        nr = as_array(near, "near", (6,), batch=True, what="a joint vector of shape (6,) or (N, 6)")
        nr = np.broadcast_to(nr, (Tb.shape[0], 6))
    return _core(Tb, a2, a3, d3, d4, nr, tol)


def ik(
    T: Any,
    a2: float = 0.4318,
    a3: float = 0.0203,
    d3: float = 0.15005,
    d4: float = 0.4318,
    *,
    near: Any | None = None,
    tol: float = 1e-7,
    stacklevel: int = 2,
) -> IKResult:
    """Every joint vector of the PUMA-560 that reaches the pose T (closed form, Craig §4.7).

    Eight solutions in general (shoulder left/right x elbow up/down x wrist
    noflip/flip), fewer at a singularity (duplicates removed; a
    :class:`SingularityWarning` says which joints are not unique). With
    ``near`` the solutions are sorted by wrapped joint distance to it, nearest
    first, and free joints at a singularity take their value from it.
    Raises ``ValueError`` with the reason when T cannot be reached.
    ``tol`` is the threshold on sin θ5 below which the wrist counts as singular;
    ``stacklevel`` is passed to ``warnings.warn`` (3 when called through a method).

    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> q0 = np.array([0.1, -0.5, 0.3, 0.4, 0.6, -0.7])
    >>> sol = ik(arm.fk(q0), near=q0)
    >>> len(sol), sol.labels[0], bool(np.allclose(sol[0], q0))
    (8, 'left/up/noflip', True)
    """
    T = _fast_transform(T)
    if near is None:
        nr = None
    elif isinstance(near, np.ndarray) and near.shape == (6,) and near.dtype == np.float64 and np.isfinite(near).all():
        nr = near
    else:
        nr = as_array(near, "near", (6,), what="a joint vector of shape (6,)")
    a2, a3, d3, d4 = _lengths(a2, a3, d3, d4)
    found, reason = _solve_one(T, a2, a3, d3, d4, nr, tol)
    if reason:
        raise ValueError(f"T: the PUMA-560 cannot reach this pose: {reason}")
    q = np.array([row for _, row, _ in found])
    flags = np.array([f for _, _, f in found], dtype=np.int64)
    labels = [BRANCH_LABELS[k] for k, _, _ in found]
    if nr is not None:
        d = wrap(q - nr)
        order = np.argsort(np.einsum("kj,kj->k", d, d), kind="stable")
        q, flags, labels = q[order], flags[order], [labels[i] for i in order]
    allf = int(np.bitwise_or.reduce(flags)) if len(flags) else 0
    reasons = [text for bit, text in _REASONS.items() if allf & bit]
    if reasons:
        warnings.warn("; ".join(reasons), SingularityWarning, stacklevel=stacklevel)
    return IKResult(q=q, labels=labels, flags=flags, singular=reasons)
