"""Porter's PUMA-like chain as a robot: one prismatic and five revolute joints (J. Porter, "PUMA").

The configuration is q = (α1, α2, q2, α3, α4, α5): five angles (radians, wrapped to (-π, π] like
every revolute joint of the course; Porter writes 0 <= αi < 2π, the same angles) and the
prismatic stroke q2 >= 0; the constant lengths l1, l3, l4 are unitless.

* direct problem: :meth:`Porter.fk` (the corrected local-frame product, :mod:`.fk`);
* inverse problem: :meth:`Porter.ik` with ``method="explicit"`` (Ver.1, eqs. 8-16, all four
  configurations, :mod:`.explicit`) or ``method="geometric"`` (Ver.2, eqs. 17-19, the two of one
  arm plane, :mod:`.geometric`); :meth:`Porter.ik_batch` runs Ver.1 on N poses at once.

Every pose is reachable without a stroke limit; with ``q2_max`` far poses are not (``success``
False, with the reason). Singular families (:mod:`.families`) return one representative per
branch, the one nearest ``near`` when given.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..._validate import as_choice, as_robot_length, as_tol
from ...transforms import wrap_angle
from .._ops import ARRAY, SCALAR
from ..ik import IKBatch, IKSolutions, dedupe_mask, keep_start
from ..jacobian_columns import from_axes
from ..robot import Robot
from .explicit import BRANCH_LABELS, PLANE, SIGN, branch, pose_terms
from .families import REVOLUTE, nearest_parallel, split_q2zero
from .fk import fk_entries, frames_array
from .geometric import angle, construct

__all__ = ["Porter", "angle", "FLAG_KEYS", "MESSAGES", "BRANCH_LABELS", "REVOLUTE", "TOL"]

#: Relative tolerance deciding "exactly singular" (lengths are scaled by l1 + l3 + l4 + |p5|; c4 absolute).
TOL = 1e-12
FLAG_KEYS = ("p4_on_z0_axis", "planes_parallel", "q2_zero")
MESSAGES = {
    "p4_on_z0_axis": "p4 lies on the z0 axis: the arm plane, hence α1, is free (eq. 9 gives 0/0)",
    "planes_parallel": "x5 is normal to the arm plane (c4 = 0, n024 ∥ x5): eqs. 11, 12, 14, 15 divide by c4 = 0; "
    "only α2 + α3 + α5 (s4 = 1) or α2 + α3 - α5 (s4 = -1) is fixed",
    "q2_zero": "q2 = 0 (p3 = p2): the prismatic axis, hence α2, is free; only α2 + α3 is fixed",
}
_BLOCK = 10_000


class Porter(Robot):
    """Porter's chain with lengths l1, l3, l4 (unitless) and an optional stroke limit ``q2_max``.

    >>> arm = Porter(1.0, 0.5, 0.3)
    >>> np.round(arm.fk([0, 0, 2, 0, 0, 0]), 12) + 0.0  # p5 = (q2 + l4, 0, l1 - l3)
    array([[1. , 0. , 0. , 2.3],
           [0. , 1. , 0. , 0. ],
           [0. , 0. , 1. , 0.5],
           [0. , 0. , 0. , 1. ]])
    >>> q = np.array([0.3, 0.2, 1.0, 0.4, 0.5, 0.6])
    >>> sol = arm.ik(arm.fk(q), near=q)
    >>> len(sol), sol.labels[0], bool(np.allclose(sol[0], q))
    (4, 'front/c4+', True)
    """

    def __init__(self, l1: float = 1.0, l3: float = 0.5, l4: float = 0.3, *, q2_max: float | None = None) -> None:
        self._L: tuple[float, float, float] = (
            as_robot_length(l1, "l1", positive=True),
            as_robot_length(l3, "l3", positive=True),
            as_robot_length(l4, "l4", positive=True),
        )
        self.q2_max = None if q2_max is None else as_robot_length(q2_max, "q2_max", positive=True)
        self.name, self.units = "Porter's chain", ""
        stroke = self.q2_max if self.q2_max is not None else 2.0 * sum(self._L)
        lim = [(-np.pi, np.pi)] * 6
        lim[2] = (0.0, stroke)
        self._init_joints(REVOLUTE, {"qz": np.zeros(6), "qn": np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]) * stroke / 2},
                          lim, ("α1", "α2", "q2", "α3", "α4", "α5"))  # fmt: skip

    @property
    def lengths(self) -> dict[str, float]:
        """The three lengths l1, l3, l4."""
        return dict(zip(("l1", "l3", "l4"), self._L, strict=True))

    def parameters(self) -> dict[str, float]:
        """The lengths (and the stroke limit, if any)."""
        out = dict(self.lengths)
        if self.q2_max is not None:
            out["q2_max"] = self.q2_max
        return out

    # ---- direct problem -----------------------------------------------------------------
    def fk(self, q: Any) -> np.ndarray:
        """F05 = Rz(α1) Tz(l1) Ry(α2) Tx(q2) Ry(α3) Tz(-l3) Rz(α4) Tx(l4) Rx(α5): (4, 4) or (N, 4, 4).

        Maps coordinates of the end-effector frame F5 into the scene frame F0 (Porter's eq. 6 with
        the corrected local-frame product).
        """
        from ..dh import frame_array, split_q

        cols, batch = split_q(q, 6, self.check_q)
        return frame_array(fk_entries(SCALAR if batch is None else ARRAY, cols, *self._L), batch)

    def frames(self, q: Any) -> np.ndarray:
        """The frames F0..F5 of the chain (scene coordinates): (6, 4, 4) or (N, 6, 4, 4).

        >>> F = Porter(1, 1, 1).frames([0, 0, 1, 0, 0, 0])
        >>> F[:, :3, 3]
        array([[0., 0., 0.],
               [0., 0., 0.],
               [0., 0., 1.],
               [1., 0., 1.],
               [1., 0., 0.],
               [2., 0., 0.]])
        """
        return frames_array(self.check_q(q), *self._L)

    def jacobian(self, q: Any) -> np.ndarray:
        """The geometric Jacobian [J_v; J_ω] of p5 (6, 6), or (N, 6, 6) for q (N, 6), scene coordinates.

        The joint axes are read off the frames: α1 turns about z of F1, α2 about y of F2, q2 slides
        along x of F2, α3 turns about y of F3, α4 about z of F4 and α5 about x of F5, each through
        its frame's origin; columns as in :func:`~..jacobian.jacobian_from_axes`.

        >>> J = Porter(1.0, 0.5, 0.3).jacobian([0, 0, 2, 0, 0, 0])
        >>> J[:, 2] + 0.0  # the stroke q2 moves p5 along x2 = x0 and turns nothing
        array([1., 0., 0., 0., 0., 0.])
        """
        F = self.frames(q)  # q checked here, once; the frames are the package's own
        pick = [(1, 2), (2, 1), (2, 0), (3, 1), (4, 2), (5, 0)]  # (frame, column) of each joint's axis
        axes = np.stack([F[..., k, :3, c] for k, c in pick], axis=-2)
        points = np.stack([F[..., k, :3, 3] for k, _ in pick], axis=-2)
        return from_axes(axes, points, F[..., 5, :3, 3], self.revolute)

    # ---- inverse problem ------------------------------------------------------------------
    def classify(self, T: Any, *, tol: float = TOL) -> tuple[str, ...]:
        """The singular cases of the pose T that affect at least one Ver.1 branch (empty in general position).

        >>> arm = Porter(1, 1, 1)
        >>> arm.classify(arm.fk([0, 0, 1, 0, 0, 0])), arm.classify(arm.fk([0, 0, 1, 0, np.pi / 2, 0]))
        ((), ('planes_parallel',))
        """
        tol = as_tol(tol, "tol")
        b = self._batch(self._check_poses(T)[:1], None, tol)
        bits = int(np.bitwise_or.reduce(b.flags[0]))
        return tuple(k for i, k in enumerate(FLAG_KEYS) if bits >> i & 1)

    def _none(self, why: str, method: str) -> IKSolutions:
        """No configuration: ``success`` False and ``why`` as the reason."""
        return IKSolutions(np.zeros((0, 6)), (), (), MESSAGES, False, why, self.name, method, REVOLUTE,
                           joints=self.joint_symbols)  # fmt: skip

    def ik(
        self, T: Any, near: Any = None, *, method: str = "explicit", tol: float = TOL, planes: str = "front"
    ) -> IKSolutions:
        """Every configuration reaching T, by Ver.1 (``"explicit"``) or Ver.2 (``"geometric"``).

        Ver.1 gives four configurations in general position (front/back arm plane x sign of c4),
        Ver.2 the two of the front plane (one for parallel planes), or with ``planes="both"`` the
        front plane's and the back plane's (the plane turned by π about z0: all four). Singular poses return one
        representative per branch (nearest ``near`` when given; see :mod:`.families`) with a
        :class:`~..ik.SingularityWarning`; with a stroke limit an unreachable pose gives
        ``success`` False and the reason.

        >>> arm = Porter(1.0, 0.5, 0.3, q2_max=2.0)
        >>> arm.ik(arm.fk([0.3, 0.2, 9.0, 0.4, 0.5, 0.6])).reason[:40]
        'unreachable: every configuration needs q'
        """
        method = as_choice(method, "method", ("explicit", "geometric"))
        planes = as_choice(planes, "planes", ("front", "both"))
        if planes == "both" and method != "geometric":
            raise ValueError('planes: "both" extends Ver.2 (method="geometric"); Ver.1 always gives both planes')
        tol = as_tol(tol, "tol")
        Tm = self._check_poses(T)
        if Tm.shape[0] != 1:
            raise ValueError(f"T: expected one pose (4, 4) (use ik_batch for several), got shape {Tm.shape}")
        nr = self._check_near(near)
        if method == "explicit":
            rows, keys, labels = self._explicit_one(Tm[0], nr, tol)
        else:
            found = [(q, k, "front") for q, k in construct(Tm[0], self._L, nr, tol)]
            if planes == "both":
                found += [(q, k, "back") for q, k in construct(Tm[0], self._L, nr, tol, plane="back")]
            rows = [q for q, _, _ in found]
            keys = [k for _, k, _ in found]
            labels = [f"{side}/c4{'+' if np.cos(q[4]) >= 0 else '-'}" for q, _, side in found]
        guarded = self._guard(Tm[0], rows, keys, labels, method)
        if isinstance(guarded, str):
            return self._none(guarded, method)
        Q, keys, labels = guarded
        if nr is not None and (method == "explicit" or planes == "both"):
            # the start configuration among the solutions at compound near-singular poses; only where every
            # configuration is returned (Ver.2 on the front plane alone may not hold the start's branch at all)
            Q = self._keep_start(Q[None], np.ones((1, len(Q)), dtype=bool), nr[None], Tm)[0]
        present = {k for f in keys for k in f}
        if self.q2_max is not None:
            over = Q[:, 2] > self.q2_max
            if over.all():
                need = float(Q[:, 2].min())
                why = (f"unreachable: every configuration needs q2 > q2_max = {self.q2_max:g} "
                       f"(the smallest is {need:.6g})")  # fmt: skip
                return self._none(why, method)
            Q, keys, labels = Q[~over], [k for k, o in zip(keys, over, strict=True) if not o], \
                [lab for lab, o in zip(labels, over, strict=True) if not o]  # fmt: skip
        sol = IKSolutions(Q, tuple(labels), tuple(keys), {k: MESSAGES[k] for k in present}, True, "", self.name,
                          method, REVOLUTE, joints=self.joint_symbols)  # fmt: skip
        return self._finish(sol, nr)

    def _keep_start(self, q: np.ndarray, valid: np.ndarray, nr: np.ndarray, Tb: np.ndarray) -> np.ndarray:
        """:func:`~..ik.keep_start` for Porter: a start beyond the stroke limit is never put in."""
        T_near = self.fk(nr).reshape(-1, 4, 4)
        outside = (nr[:, 2] < 0) | (nr[:, 2] > (np.inf if self.q2_max is None else self.q2_max))
        T_near = np.where(outside[:, None, None], np.nan, T_near)
        size = max(1.0, float(np.abs(Tb[:, :3, 3]).max()))
        return keep_start(q, valid, nr, Tb, T_near, REVOLUTE, size)

    def _guard(self, T: np.ndarray, rows: list, keys: list, labels: list,
               method: str) -> tuple[np.ndarray, list, list] | str:  # fmt: skip
        """Rows wrapped; at singular poses keep rows that really reach T and drop coinciding representatives
        (shared by ``ik`` and ``ik_batch`` so that both answer the same); a reason when none is left."""
        Q = wrap_angle(np.array(rows)) * REVOLUTE + np.array(rows) * ~REVOLUTE
        if any(keys):
            err = np.abs(self.fk(Q) - T).max(axis=(-2, -1)) / max(1.0, float(np.abs(T[:3, 3]).max()))
            keep = np.flatnonzero(err < 1e-8)
            if len(keep) == 0:  # never silently "success" with nothing: say the solver failed
                why = f"the {method} solver found no configuration reaching T (pose error {err.min():.3g})"
                return why + ": please report"
            keep = keep[dedupe_mask(Q[keep], REVOLUTE)]
            Q, keys, labels = Q[keep], [keys[i] for i in keep], [labels[i] for i in keep]
        return Q, keys, labels

    def _explicit_one(self, T: np.ndarray, near: np.ndarray | None, tol: float) -> tuple[list, list, list]:
        """Ver.1 for one pose in plain floats: the four branches, then the nearest family members."""
        (r11, r12, r13, px), (r21, r22, r23, py), (r31, r32, r33, pz), _ = T.tolist()
        R = (r11, r12, r13, r21, r22, r23, r31, r32, r33)
        terms = pose_terms(SCALAR, R, (px, py, pz), self._L, tol, None if near is None else float(near[0]))
        rows, keys, labels = [], [], []
        for j in range(4):
            q, parallel, q2zero = branch(SCALAR, terms, float(PLANE[j]), float(SIGN[j]), self._L[1], tol)
            if parallel and SIGN[j] < 0:
                continue  # c4 = 0: both signs give the same configuration
            q = np.array(q)
            if near is not None and parallel:
                q = nearest_parallel(T[:3, :3], T[:3, 3], self._L, float(q[0]), near, tol)
                q2zero = q[2] == 0.0
            if near is not None and q2zero:
                q = split_q2zero(q, near)
            rows.append(q)
            keys.append(tuple(k for k, on in zip(FLAG_KEYS, (terms[8], parallel, q2zero), strict=True) if on))
            labels.append(BRANCH_LABELS[j])
        return rows, keys, labels

    def ik_batch(self, T: Any, near: Any = None, *, tol: float = TOL) -> IKBatch:
        """Ver.1 for N poses (N, 4, 4), vectorised: four branches each, in the order :data:`BRANCH_LABELS`.

        At singular poses the branches hold Porter's representatives (minimal q2, α2 = 0, α1 with
        s4 = 0, or α1 from ``near``); branches that coincide are marked invalid.

        >>> arm = Porter(1.0, 0.5, 0.3)
        >>> b = arm.ik_batch(arm.fk(np.array([[0.3, 0.2, 1.0, 0.4, 0.5, 0.6]])))
        >>> b.q.shape, b.valid.tolist(), b.flags.tolist()
        ((1, 4, 6), [[True, True, True, True]], [[0, 0, 0, 0]])
        """
        tol = as_tol(tol, "tol")
        Tb = self._check_poses(T)
        return self._batch(Tb, self._check_near(near, batch=Tb.shape[0]), tol)

    def _batch(self, Tb: np.ndarray, nr: np.ndarray | None, tol: float) -> IKBatch:
        N = Tb.shape[0]
        q = np.zeros((N, 4, 6))
        flags = np.zeros((N, 4), dtype=np.int64)
        valid = np.zeros((N, 4), dtype=bool)
        reason = np.full(N, "", dtype=object)
        for start in range(0, N, _BLOCK):
            sl = slice(start, min(start + _BLOCK, N))
            T = Tb[sl]
            R = tuple(T[:, i, j, None] for i in range(3) for j in range(3))
            P = tuple(T[:, i, 3, None] for i in range(3))
            terms = pose_terms(ARRAY, R, P, self._L, tol, None if nr is None else nr[sl, 0, None])
            cfg, parallel, q2zero = branch(ARRAY, terms, PLANE, SIGN, self._L[1], tol)
            for j, v in enumerate(cfg):
                q[sl, :, j] = wrap_angle(v) if REVOLUTE[j] else v
            flags[sl] = terms[8] * 1 + parallel * 2 + q2zero * 4
            ok = ~(parallel & (SIGN < 0))
            if self.q2_max is not None:
                ok = ok & (q[sl, :, 2] <= self.q2_max)
            valid[sl] = ok
        # singular poses (rare): the same per-pose path as ``ik`` (family members nearest ``near``, the guard),
        # so that ik and ik_batch agree on both sides of every threshold (issue 21)
        for i in np.flatnonzero(flags.any(axis=1)):
            rows, keys, labels = self._explicit_one(Tb[i], None if nr is None else nr[i], tol)
            guarded = self._guard(Tb[i], rows, keys, labels, "explicit")
            valid[i] = False
            if isinstance(guarded, str):
                reason[i] = guarded
                continue
            for r, k, lab in zip(*guarded, strict=True):
                j = BRANCH_LABELS.index(lab)
                q[i, j] = r
                flags[i, j] = sum(1 << FLAG_KEYS.index(f) for f in k)
                valid[i, j] = self.q2_max is None or r[2] <= self.q2_max
        if nr is not None:
            q = self._keep_start(q, valid, nr, Tb)
        q = np.where(valid[..., None], q, 0.0)
        flags = np.where(valid, flags, 0)
        for i in np.flatnonzero(~valid.any(axis=1) & (reason == "")):
            reason[i] = f"unreachable: every configuration needs q2 > q2_max = {self.q2_max:g}"
        return IKBatch(q, valid, BRANCH_LABELS, flags, FLAG_KEYS, MESSAGES, reason.astype(str), self.name,
                       "explicit", REVOLUTE, joints=self.joint_symbols)  # fmt: skip
