"""Judging a DH table by the poses its chain reaches over hidden joint values."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ....kinematics import DHChain, Link
from ....kinematics.standard_dh import standard_dh
from ...remake import made
from ..verdict import Judge, Verdict
from .poses import POS_TOL, as_floats, is_constant_transform, offset_text, pose_ok

# ------------------------------------------------------------------------------------------ DH tables
TableFk = Callable[[np.ndarray, np.ndarray], np.ndarray]


def modified_table_fk(table: Any, Q: Any) -> np.ndarray:
    """The poses of a table's chain (rows α_{i-1}, a_{i-1}, θ_i, d_i, σ_i; σ = 1 prismatic) at Q (N, n) or q (n,).

    Craig's modified link matrices, through :class:`~puma_course.kinematics.DHChain` (an RP chain by hand:
    the prismatic joint slides 0.5 along z, which θ1 = π/2 leaves where it is).

    >>> T = modified_table_fk([[0, 0, 0, 0, 0], [0, 0, 0, 0, 1]], [np.pi / 2, 0.5])
    >>> np.round(T[:3, 3], 12).tolist()
    [0.0, 0.0, 0.5]
    """
    rows = np.asarray(table, dtype=float).reshape(-1, 5)
    chain = DHChain([Link(r[0], r[1], r[3], r[2], "P" if r[4] > 0.5 else "R") for r in rows])
    return chain.fk(np.asarray(Q, dtype=float))


def standard_table_fk(table: Any, Q: Any) -> np.ndarray:
    """The same table read as a standard-DH table: Rot(Z, θ) Trans(Z, d) Trans(X, a) Rot(X, α) per row.

    >>> T = standard_table_fk([[0, 1.0, 0, 0, 0]], [np.pi / 2])  # a = 1 along the turned x axis
    >>> np.round(T[:3, 3], 12).tolist()
    [0.0, 1.0, 0.0]
    """
    rows = np.asarray(table, dtype=float).reshape(-1, 5)
    Qs = np.atleast_2d(np.asarray(Q, dtype=float))
    prism = rows[:, 4] > 0.5
    out = []
    for q in Qs:
        T = np.eye(4)
        for i, r in enumerate(rows):
            theta, d = (r[2], r[3] + q[i]) if prism[i] else (r[2] + q[i], r[3])
            T = T @ standard_dh(theta, d, r[1], r[0])
        out.append(T)
    return np.stack(out) if np.ndim(Q) > 1 else out[0]


def diagnosis_points(Q: Any, revolute: Any, scale: float) -> list[np.ndarray]:
    """Every set of joint values, besides ``Q``, at which the table judge's diagnosis asks the reference's fk.

    ``Q`` with each joint's value negated (a joint turning the wrong way), then q = 0, then each joint moved
    alone from q = 0 (right only at q = 0). A student edition records the reference's poses at these too
    (:mod:`puma_course.grading.publish.public`), so that its self-check names the same mistakes as the course.

    >>> [P.tolist() for P in diagnosis_points([[0.1, 0.2]], [True, False], 2.0)]
    [[[-0.1, 0.2]], [[0.1, -0.2]], [[0.0, 0.0]], [[0.7, 0.0]], [[0.0, 0.6]]]
    """
    Q = np.atleast_2d(np.asarray(Q, dtype=float))
    rev = np.asarray(revolute, dtype=bool)
    n = len(rev)
    out = []
    for j in range(n):
        flipped = Q.copy()
        flipped[:, j] = -flipped[:, j]
        out.append(flipped)
    zero = np.zeros((1, n))
    out.append(zero)
    for j in range(n):
        single = zero.copy()
        single[0, j] = 0.7 if rev[j] else 0.3 * max(float(scale), 1e-9)
        out.append(single)
    return out


def record_diagnosis(expected: Any) -> None:
    """Ask ``expected["fk"]`` (a table judge's reference) for the poses at every :func:`diagnosis_points`."""
    fk = expected["fk"]
    for P in diagnosis_points(expected["Q"], expected["revolute"], float(expected["scale"])):
        fk(P)


def table_judge(
    chain_fk: TableFk = modified_table_fk,
    standard_fk: TableFk = standard_table_fk,
    standard_section: str = "lecture 02 §5",
) -> Judge:
    """Judge a DH table (rows α_{i-1}, a_{i-1}, θ_i, d_i, σ_i) by the poses its chain reaches.

    ``chain_fk(table, Q)`` evaluates a table with Craig's modified link matrices and
    ``standard_fk(table, Q)`` with the standard (distal) ones, for joint values Q (N, n) (default: the
    engine's :func:`modified_table_fk` and :func:`standard_table_fk`, which a student edition carries). The
    reference gives ``{"fk": poses of Q, "Q": hidden joint values (N, n), "revolute": (n,) mask,
    "scale": the mechanism's size}`` and may add ``"shifts"`` (``(key, message, t)``: a chain whose every pose is
    the reference's moved by t in frame {0} made that mistake); the table passes when its chain reaches every
    reference pose.
    ``standard_section`` is where a standard-DH table is sent to read (the question's own lecture section).
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        fk, Q = expected["fk"], np.asarray(expected["Q"], dtype=float)
        rev, scale = np.asarray(expected["revolute"], dtype=bool), float(expected["scale"])
        n = len(rev)
        table = as_floats(got)
        if table is None or not np.all(np.isfinite(table)):
            return Verdict(f"expected a table of numbers, {n} rows of (α_(i-1), a_(i-1), θ_i, d_i, σ_i)")
        if table.shape != (n, 5):
            extra = " (each row needs σ_i too: 0 revolute, 1 prismatic)" if table.shape == (n, 4) else ""
            return Verdict(f"expected a table of shape ({n}, 5), one row per joint, got shape {table.shape}{extra}")
        sigma = table[:, 4]
        bad = np.flatnonzero((np.abs(sigma) > 1e-9) & (np.abs(sigma - 1) > 1e-9))
        if bad.size:
            return Verdict(f"row {bad[0] + 1}: σ must be 0 (revolute) or 1 (prismatic), got {sigma[bad[0]]:g}")
        wrong = np.flatnonzero((sigma < 0.5) != rev)
        if wrong.size:
            j = int(wrong[0])
            kind, yours = ("revolute", "prismatic") if rev[j] else ("prismatic", "revolute")
            return Verdict(
                f"row {j + 1}: joint {j + 1} is {kind} in the mechanism, your table makes it {yours}", "joint_type"
            )
        T_ref = fk(Q)
        try:
            T_got = chain_fk(table, Q)
        except ValueError as exc:
            return Verdict(f"your table cannot be evaluated: {str(exc)[:200]}")
        if np.all(pose_ok(T_got, T_ref, scale)):
            return Verdict(None)
        try:
            named = _named_shift(T_got, T_ref, scale, expected.get("shifts", ()))
            if named is not None:
                return named
            return _table_mistake(table, T_got, T_ref, fk, Q, rev, scale, chain_fk, standard_fk, standard_section)
        except LookupError:  # a student edition without a recorded pose: say what differs, name nothing
            return Verdict(
                f"your chain reaches other poses: at the hidden joint values the tool is off by up to "
                f"{offset_text(T_got, T_ref)}"
            )

    return made(judge, table_judge, chain_fk, standard_fk, standard_section)


def _named_shift(T_got: np.ndarray, T_ref: np.ndarray, scale: float, shifts: Any) -> Verdict | None:
    """The question's own named shift (``(key, message, t)`` of the reference's ``"shifts"``): every pose moved by the
    same translation t in frame {0}, the rotations right (a length of the mechanism left out of the table), or None."""
    M = T_got @ np.linalg.inv(T_ref)
    if not is_constant_transform(M, scale) or np.max(np.abs(M[0, :3, :3] - np.eye(3))) > 1e-6:
        return None
    for key, message, t in shifts:
        if np.max(np.abs(M[0, :3, 3] - np.asarray(t, dtype=float))) <= POS_TOL * scale:
            return Verdict(str(message), str(key))
    return None


def _table_mistake(
    table: np.ndarray,
    T_got: np.ndarray,
    T_ref: np.ndarray,
    fk: Callable[..., Any],
    Q: np.ndarray,
    rev: np.ndarray,
    scale: float,
    chain_fk: TableFk,
    standard_fk: TableFk,
    standard_section: str,
) -> Verdict:
    angles = table[:, [0, 2]]
    if np.max(np.abs(angles)) > 2 * np.pi + 1e-6:
        fixed = table.copy()
        fixed[:, [0, 2]] = np.radians(angles)
        worst = float(np.max(np.abs(angles)))
        note = " (converted to radians it is right)" if np.all(pose_ok(chain_fk(fixed, Q), T_ref, scale)) else ""
        return Verdict(f"your angles look like degrees (up to {worst:g}): the table takes radians{note}", "degrees")
    try:
        standard = bool(np.all(pose_ok(standard_fk(table, Q), T_ref, scale)))
    except ValueError:
        standard = False
    if standard:
        return Verdict(
            "this is a standard-DH table (Paul, Robotics Toolbox): with the link matrix Rot(Z, θ) Trans(Z, d) "
            "Trans(X, a) Rot(X, α) it reaches the right poses, but the course uses Craig's modified DH, where row i "
            "holds α_(i-1) and a_(i-1) of the previous frame "
            f"({standard_section})",
            "standard_dh",
        )
    n = len(rev)
    points = diagnosis_points(Q, rev, scale)  # the reference is asked at these only (an edition records them)
    for j in range(n):
        if np.all(pose_ok(T_got, fk(points[j]), scale)):
            what = "turns" if rev[j] else "slides"
            return Verdict(
                f"joint {j + 1} {what} the wrong way: your z_{j + 1} points against the positive sense the picture "
                "shows (everything else is right)",
                "joint_sign",
            )
    for side, M in (("base", T_got @ np.linalg.inv(T_ref)), ("tool", np.linalg.inv(T_ref) @ T_got)):
        if not is_constant_transform(M, scale):
            continue
        shift = M[0, :3, 3]
        if np.max(np.abs(M[0, :3, :3] - np.eye(3))) <= 1e-6 and np.max(np.abs(shift[:2])) > POS_TOL * scale:
            # a pure shift across z0 (or the tool's z): a wrong offset (d_i, a_(i-1)) in the middle of the chain
            # along an axis parallel to it moves every pose the same way, so it need not be the base or tool
            # frame: say what differs, name no mistake. A shift along z0 is frame {0}'s height (d1), along the
            # tool's z its distance (the last d): the frames the question fixes.
            t = ", ".join(f"{v:.4g}" for v in np.where(np.abs(M[0, :3, 3]) < 1e-9, 0.0, M[0, :3, 3]))
            where = "in frame {0}" if side == "base" else "in the tool frame"
            return Verdict(
                f"your chain moves like the mechanism, but every pose is shifted by the same ({t}) {where}: check "
                f"the offsets d_i and a_(i-1) of your table (their signs) and where your {side} frame is"
            )
        if side == "base":
            return Verdict(
                "your chain moves like the mechanism, but your frame {0} is not the base frame the question fixes "
                "(every pose is off by the same transform on the base side)",
                "base_frame",
            )
        return Verdict(
            "your chain moves like the mechanism, but your last frame is not the tool frame the question fixes "
            "(every pose is off by the same transform on the tool side)",
            "tool_frame",
        )
    zero = points[n]
    if np.all(pose_ok(chain_fk(table, zero), fk(zero), scale)):
        for j in range(n):
            single = points[n + 1 + j]
            if not np.all(pose_ok(chain_fk(table, single), fk(single), scale)):
                return Verdict(
                    f"your table gives the right pose at q = 0 but not when the joints move: moving joint {j + 1} "
                    f"alone already gives another pose. Check where joint {j + 1}'s axis z_{j + 1} is and how it "
                    f"points (α_{j}, a_{j} and the rows before it)",
                    "only_at_zero",
                )
        return Verdict("your table gives the right pose at q = 0 but not when several joints move", "only_at_zero")
    return Verdict(
        f"your chain reaches other poses: at the hidden joint values the tool is off by up to "
        f"{offset_text(T_got, T_ref)}, already at q = 0"
    )
