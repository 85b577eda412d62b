"""Judging modelling questions for what is right, not against one answer.

Each factory returns a ``judge(got, expected, args) -> Verdict`` for :attr:`Question.judge_with
<puma_course.grading.model.Question.judge_with>`. ``expected`` is what the question's reference computed
in the grader's process: a dict holding the hidden joint values, the reference poses and the
reference robot's forward kinematics as a callable (``"fk"``), so a judge can test a student's answer
by what it *does*:

* :func:`table_judge`: a DH table is right when its chain reaches the reference poses over hidden
  random joint values (any valid frame assignment passes); otherwise it says whether the table is
  standard DH, right only at q = 0, has a joint turning the wrong way, the wrong joint type, degrees,
  or is off by a constant base or tool transform;
* :func:`solution_set_judge`: every row reaches the pose, no row twice, no solution missing (named by
  its branch), in any order unless the question asks for one;
* :func:`nearest_judge`: a solution, and the nearest one in wrapped joint distance;
* :func:`path_judge`: a joint path reaches every pose of a Cartesian path, starts at the given
  configuration and never jumps (largest step against the smoothest path's);
* :func:`rotation_judge`: angles judged by the rotation they produce (any equivalent triple passes);
* :func:`stroke_judge`: Porter's parallel-planes representative (front plane, minimal stroke).

The judges need no kinematics of their own: the bank passes in what they evaluate (the chain of a
student's table, the robot's forward kinematics) from :mod:`puma_course.grading.bank._reference`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..transforms import wrap_angle
from .diagnose import close
from .model import Judge, Verdict

__all__ = [
    "pose_ok",
    "table_judge",
    "solution_set_judge",
    "nearest_judge",
    "path_judge",
    "rotation_judge",
    "stroke_judge",
]

#: Tolerances of the pose tests: rotation entries, and positions relative to the mechanism's size.
ROT_TOL, POS_TOL = 1e-6, 1e-6


def _floats(value: Any) -> np.ndarray | None:
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None


def pose_errors(Ts: np.ndarray, T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(position error, rotation error) of poses ``Ts`` (m, 4, 4) against ``T`` (4, 4) or (m, 4, 4)."""
    d = np.asarray(Ts, dtype=float) - np.asarray(T, dtype=float)
    return np.max(np.abs(d[..., :3, 3]), axis=-1), np.max(np.abs(d[..., :3, :3]), axis=(-2, -1))


def pose_ok(Ts: Any, T: Any, scale: float = 1.0) -> np.ndarray:
    """Which of the poses ``Ts`` (m, 4, 4) equal ``T`` (position to 1e-6 of ``scale``, rotation to 1e-6).

    >>> pose_ok(np.stack([np.eye(4), 2 * np.eye(4)]), np.eye(4)).tolist()
    [True, False]
    """
    pos, rot = pose_errors(Ts, T)
    return (pos <= POS_TOL * max(1.0, scale)) & (rot <= ROT_TOL)


def _off(Ts: np.ndarray, T: np.ndarray) -> str:
    pos, rot = pose_errors(Ts, T)
    return f"{float(np.max(pos)):.3g} in position and {float(np.max(rot)):.3g} in orientation"


def _wrapped(d: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    return np.where(revolute, wrap_angle(d), d)


def _dist(a: np.ndarray, b: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    """Wrapped joint distance (Euclidean; angle differences in (-π, π]), broadcasting over leading axes."""
    d = _wrapped(a - b, revolute)
    return np.sqrt(np.sum(d * d, axis=-1))


def _radians(rows: np.ndarray, revolute: np.ndarray) -> np.ndarray:
    out = rows.copy()
    out[..., revolute] = np.radians(out[..., revolute])
    return out


def _constant(M: np.ndarray, scale: float) -> bool:
    """True when the transforms M (N, 4, 4) are all the same and not the identity."""
    return bool(np.all(pose_ok(M, M[0], scale)) and not pose_ok(M[:1], np.eye(4), scale)[0])


# ------------------------------------------------------------------------------------------ DH tables
TableFk = Callable[[np.ndarray, np.ndarray], np.ndarray]


def table_judge(chain_fk: TableFk, standard_fk: TableFk) -> Judge:
    """Judge a DH table (rows α_{i-1}, a_{i-1}, θ_i, d_i, σ_i) by the poses its chain reaches.

    ``chain_fk(table, Q)`` evaluates a table with Craig's modified link matrices and
    ``standard_fk(table, Q)`` with the standard (distal) ones, for joint values Q (N, n). The
    reference gives ``{"fk": poses of Q, "Q": hidden joint values (N, n), "revolute": (n,) mask,
    "scale": the mechanism's size}``; the table passes when its chain reaches every reference pose.
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        fk, Q = expected["fk"], np.asarray(expected["Q"], dtype=float)
        rev, scale = np.asarray(expected["revolute"], dtype=bool), float(expected["scale"])
        n = len(rev)
        table = _floats(got)
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
        return _table_mistake(table, T_got, T_ref, fk, Q, rev, scale, chain_fk, standard_fk)

    return judge


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
            "holds α_(i-1) and a_(i-1) of the previous frame (lecture 02 §5)",
            "standard_dh",
        )
    n = len(rev)
    for j in range(n):
        flipped = Q.copy()
        flipped[:, j] = -flipped[:, j]
        if np.all(pose_ok(T_got, fk(flipped), scale)):
            what = "turns" if rev[j] else "slides"
            return Verdict(
                f"joint {j + 1} {what} the wrong way: your z_{j + 1} points against the positive sense the picture "
                "shows (everything else is right)",
                "joint_sign",
            )
    if _constant(T_got @ np.linalg.inv(T_ref), scale):
        return Verdict(
            "your chain moves like the mechanism, but your frame {0} is not the base frame the question fixes "
            "(every pose is off by the same transform on the base side)",
            "base_frame",
        )
    if _constant(np.linalg.inv(T_ref) @ T_got, scale):
        return Verdict(
            "your chain moves like the mechanism, but your last frame is not the tool frame the question fixes "
            "(every pose is off by the same transform on the tool side)",
            "tool_frame",
        )
    zero = np.zeros((1, n))
    if np.all(pose_ok(chain_fk(table, zero), fk(zero), scale)):
        for j in range(n):
            single = zero.copy()
            single[0, j] = 0.7 if rev[j] else 0.3 * max(scale, 1e-9)
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
        f"{_off(T_got, T_ref)}, already at q = 0"
    )


# ------------------------------------------------------------------------------------------ solution sets
def _rows(got: Any, n: int) -> np.ndarray | str:
    arr = _floats(got)
    if arr is None:
        return "did not return numbers"
    if arr.ndim == 1 and arr.size == n:
        arr = arr[None]
    if arr.ndim != 2 or arr.shape[1] != n:
        return f"expected rows of {n} joint values (an array of shape (k, {n})), got shape {arr.shape}"
    if not np.all(np.isfinite(arr)):
        return "returned NaN or infinity (near a singular pose a square root of a tiny negative number is NaN: clip)"
    return arr


def _not_reaching(arr: np.ndarray, expected: dict[str, Any], target: Any) -> Verdict | None:
    """None if every row reaches ``target``; else why not (degrees, a named alternative, or which row)."""
    fk, rev, scale = expected["fk"], np.asarray(expected["revolute"], bool), float(expected["scale"])
    reached = fk(arr)
    ok = pose_ok(reached, target, scale)
    if np.all(ok):
        return None
    if np.all(pose_ok(fk(_radians(arr, rev)), target, scale)):
        return Verdict("your angles are in degrees: the course works in radians", "degrees")
    for key, message, alt in expected.get("alternatives", ()):
        if np.all(pose_ok(reached, alt, scale)):
            return Verdict(message, key)
    i = int(np.flatnonzero(~ok)[0])
    label = f"row {i + 1}" if arr.shape[0] > 1 else "your configuration"
    return Verdict(
        f"{label} does not reach the pose: off by {_off(reached[i : i + 1], np.asarray(target))}", "not_a_solution"
    )


def solution_set_judge(match_tol: float = 1e-6) -> Judge:
    """Judge a set of configurations: each reaches the pose, none twice, none of the reference's missing.

    The reference gives ``{"T", "solutions" (k, n), "labels", "fk", "revolute", "scale"}`` and may
    add ``"alternatives"`` (``(key, message, pose)``: rows that all reach that pose made that
    mistake), ``"stroke"`` (a column that must not be negative) and ``"ordered"`` (True: the rows
    must come in the reference's order).
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        sols, labels = np.asarray(expected["solutions"], dtype=float), tuple(expected["labels"])
        rev = np.asarray(expected["revolute"], dtype=bool)
        k, n = sols.shape
        arr = _rows(got, n)
        if isinstance(arr, str):
            return Verdict(arr)
        if len(arr) == 0:
            return Verdict(f"returned no configuration; the pose has {k}", "missing_solutions")
        why = _not_reaching(arr, expected, expected["T"])
        if why is not None:
            return why
        stroke = expected.get("stroke")
        if stroke is not None and np.any(arr[:, stroke] < -1e-9):
            i = int(np.flatnonzero(arr[:, stroke] < -1e-9)[0])
            return Verdict(
                f"row {i + 1} has q2 = {arr[i, stroke]:.4g} < 0: a stroke cannot be negative; that value "
                "belongs to the other arctan solution of eq. (14) (lecture 06 (d))",
                "negative_stroke",
            )
        D = _dist(arr[:, None, :], arr[None, :, :], rev)
        twice = np.argwhere(np.triu(D < 1e-7, k=1))
        if twice.size:
            i, j = (int(v) + 1 for v in twice[0])
            return Verdict(
                f"rows {i} and {j} are the same configuration: list each solution once (there are {k} here)",
                "duplicates",
            )
        M = _dist(sols[:, None, :], arr[None, :, :], rev) < match_tol
        missing = [labels[i] for i in np.flatnonzero(~M.any(axis=1))]
        if missing:
            return Verdict(f"misses {len(missing)} of the {k} solutions: {', '.join(missing)}", "missing_solutions")
        extra = np.flatnonzero(~M.any(axis=0))
        if extra.size:
            return Verdict(
                f"row {extra[0] + 1} reaches the pose but matches none of the {k} solutions to 1e-6 "
                "(is it accurate enough?)"
            )
        if expected.get("ordered") and not (len(arr) == k and np.all(np.diag(M))):
            return Verdict("the right solutions, in another order: sort them as the question asks", "solution_order")
        return Verdict(None)

    return judge


def nearest_judge() -> Judge:
    """Judge one configuration: it reaches the pose and no solution is nearer ``q_ref`` (wrapped distance).

    The reference gives ``{"T", "q_ref", "solutions", "labels", "fk", "revolute", "scale"}``.
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        sols, labels = np.asarray(expected["solutions"], dtype=float), tuple(expected["labels"])
        rev, q_ref = np.asarray(expected["revolute"], dtype=bool), np.asarray(expected["q_ref"], dtype=float)
        arr = _rows(got, sols.shape[1])
        if isinstance(arr, str):
            return Verdict(arr)
        if len(arr) != 1:
            return Verdict(f"expected one configuration (shape ({sols.shape[1]},)), got {len(arr)} rows")
        why = _not_reaching(arr, expected, expected["T"])
        if why is not None:
            return why
        d, ds = float(_dist(arr[0], q_ref, rev)), _dist(sols, q_ref, rev)
        best = int(np.argmin(ds))
        if d <= ds[best] + 1e-7:
            return Verdict(None)
        mine = _dist(sols, arr[0], rev)
        label = labels[int(np.argmin(mine))] if np.min(mine) < 1e-6 else "yours"
        plain = np.sqrt(np.sum((sols - q_ref) ** 2, axis=-1))
        if np.min(mine) < 1e-6 and int(np.argmin(plain)) == int(np.argmin(mine)):
            return Verdict(
                f"you chose {label}, nearest if angle differences are not wrapped; wrapped to (-π, π] (179° and -179° "
                f"are 2° apart) the nearest is {labels[best]}, {ds[best]:.3g} away against your {d:.3g}",
                "unwrapped_distance",
            )
        return Verdict(
            f"a solution ({label}), but not the nearest: it is {d:.3g} from q_ref, {labels[best]} is {ds[best]:.3g}",
            "not_nearest",
        )

    return judge


def path_judge(slack: float = 0.01) -> Judge:
    """Judge a joint path (n, m): every row reaches its pose, the first is at ``q0``, no step jumps.

    The reference gives ``{"path" (n, 4, 4), "fk", "q0", "ref" (the smoothest joint path), "revolute",
    "scale"}`` and may add ``"alternatives"`` (``(key, message, fk)``: rows whose ``fk`` reaches the
    path made that mistake). A step may be 1.5 times the smoothest path's largest plus ``slack``.
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        path, fk, ref = np.asarray(expected["path"], float), expected["fk"], np.asarray(expected["ref"], float)
        rev, scale, q0 = np.asarray(expected["revolute"], bool), float(expected["scale"]), np.asarray(expected["q0"])
        n, m = ref.shape
        arr = _rows(got, m)
        if isinstance(arr, str):
            return Verdict(arr)
        if arr.shape != (n, m):
            return Verdict(f"expected one configuration per pose, shape ({n}, {m}), got shape {arr.shape}")
        ok = pose_ok(fk(arr), path, scale)
        if not np.all(ok):
            if np.all(pose_ok(fk(_radians(arr, rev)), path, scale)):
                return Verdict("your angles are in degrees: the course works in radians", "degrees")
            for key, message, other_fk in expected.get("alternatives", ()):
                if np.all(pose_ok(other_fk(arr), path, scale)):
                    return Verdict(message, key)
            i = int(np.flatnonzero(~ok)[0])
            return Verdict(
                f"the configuration for pose {i + 1} does not reach it: off by "
                f"{_off(fk(arr[i : i + 1]), path[i : i + 1])}",
                "not_a_solution",
            )
        start, ref_start = float(_dist(arr[0], q0, rev)), float(_dist(ref[0], q0, rev))
        if start > ref_start + slack:
            return Verdict(
                f"your path starts {start:.3g} (joint distance) away from q0, where the arm stands: its "
                "first configuration must be the solution nearest q0",
                "start_jump",
            )
        steps, ref_steps = _dist(arr[1:], arr[:-1], rev), _dist(ref[1:], ref[:-1], rev)
        limit = 1.5 * float(np.max(ref_steps, initial=0.0)) + slack
        if np.max(steps, initial=0.0) > limit:
            k = int(np.argmax(steps))
            moved = np.abs(_wrapped(arr[k + 1] - arr[k], rev))
            joints = ", ".join(str(j + 1) for j in np.flatnonzero(moved > 0.1)) or "several"
            return Verdict(
                f"between poses {k + 1} and {k + 2} joint(s) {joints} jump by up to {np.max(moved):.3g} (a step of "
                f"{steps[k]:.3g}; a smooth path never needs more than {limit:.3g}): pick, at every pose, the solution "
                "nearest the previous configuration",
                "jump",
            )
        return Verdict(None)

    return judge


def rotation_judge(from_angles: Callable[..., np.ndarray]) -> Judge:
    """Judge angles by the rotation ``from_angles(*angles)`` they give (any equivalent triple passes).

    The reference gives ``{"R": the rotation asked for}`` and may add ``"alternatives"``
    (``(key, message, rotation)``).
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        R = np.asarray(expected["R"], dtype=float)
        arr = _floats(got)
        if arr is None or arr.shape != (3,) or not np.all(np.isfinite(arr)):
            return Verdict(f"expected three angles (shape (3,)), got {'no numbers' if arr is None else arr.shape}")
        mine = from_angles(*arr)
        if close(mine, R):
            return Verdict(None)
        if close(from_angles(*np.radians(arr)), R):
            return Verdict("your angles are in degrees: the course works in radians", "degrees")
        for key, message, other in expected.get("alternatives", ()):
            if close(mine, other):
                return Verdict(message, key)
        return Verdict(
            f"the rotation your angles give differs from the one asked for by up to "
            f"{float(np.max(np.abs(mine - R))):.3g}"
        )

    return judge


def stroke_judge() -> Judge:
    """Judge Porter's representative of a parallel-planes pose: it reaches T, in the front plane, minimal q2.

    The reference gives ``{"T", "fk", "revolute", "scale", "alpha1" (the front plane), "q2_min"}``.
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        arr = _rows(got, 6)
        if isinstance(arr, str):
            return Verdict(arr)
        if len(arr) != 1:
            return Verdict(f"expected one configuration (shape (6,)), got {len(arr)} rows")
        why = _not_reaching(arr, expected, expected["T"])
        if why is not None:
            return why
        q = arr[0]
        if abs(float(wrap_angle(q[0] - expected["alpha1"]))) > 1e-6:
            return Verdict(
                f"your arm plane is entered from the back (α1 = {q[0]:.4g}); Porter's construction uses "
                "the plane facing the wrist point, α1 = atan2(p4_y, p4_x)",
                "back_plane",
            )
        if abs(q[2] - expected["q2_min"]) > POS_TOL * max(1.0, float(expected["scale"])):
            return Verdict(
                f"this reaches T, but with q2 = {q[2]:.4g}; Porter's rule takes the smallest stroke "
                f"(q2 = {expected['q2_min']:.4g})",
                "not_minimal",
            )
        return Verdict(None)

    return judge
