"""Judging configurations: sets of solutions, the nearest one, a joint path, angles by their rotation."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ....transforms import wrap_angle
from ...remake import made
from ..mistake import close
from ..verdict import Judge, Verdict
from .poses import POS_TOL, as_floats, joint_distance, offset_text, pose_ok, revolute_to_radians, wrap_joints


# ------------------------------------------------------------------------------------------ solution sets
def _rows(got: Any, n: int) -> np.ndarray | str:
    arr = as_floats(got)
    if arr is None:
        return "did not return numbers"
    if arr.size == 0:  # an empty list: no configuration (an unreachable pose has none)
        return arr.reshape(0, n)
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
    i = int(np.flatnonzero(~ok)[0])
    label = f"row {i + 1}" if arr.shape[0] > 1 else "your configuration"
    plain = f"{label} does not reach the pose: off by {offset_text(reached[i : i + 1], np.asarray(target))}"
    if np.all(pose_ok(fk(revolute_to_radians(arr, rev)), target, scale)):
        return Verdict("your angles are in degrees: the course works in radians", "degrees", None, plain)
    for key, message, offset in expected.get("offsets", ()):  # joint values counted from another zero
        if np.all(pose_ok(fk(arr - np.asarray(offset, dtype=float)), target, scale)):
            return Verdict(message, key, None, plain)
    for key, message, alt in expected.get("alternatives", ()):
        if np.all(pose_ok(reached, alt, scale)):
            return Verdict(message, key, None, plain)
    return Verdict(plain, "not_a_solution")


def solution_set_judge(match_tol: float = 1e-6) -> Judge:
    """Judge a set of configurations: each reaches the pose, none twice, none of the reference's missing.

    The reference gives ``{"T", "solutions" (k, n), "labels", "fk", "revolute", "scale"}`` and may
    add ``"offsets"`` (``(key, message, offset)``: rows that reach the pose once ``offset`` is taken off them count
    the joints from another zero), ``"alternatives"`` (``(key, message, pose)``: rows that all reach that pose made that
    mistake; ``"wrong_sets"``, ``(key, message, rows)``: the solutions a mistaken pose has, so that an empty
    answer is that mistake where the mistaken pose is out of reach), ``"stroke"`` (a column that must not be
    negative) and ``"ordered"`` (True: the rows
    must come in the reference's order; ``"wrong_orders"``, ``(key, message, rows)``, name the
    mistakes that produce another order).
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        sols, labels = np.asarray(expected["solutions"], dtype=float), tuple(expected["labels"])
        rev = np.asarray(expected["revolute"], dtype=bool)
        k, n = sols.shape
        arr = _rows(got, n)
        if isinstance(arr, str):
            return Verdict(arr)
        q2_max = expected.get("q2_max")  # a stroke limit (column "stroke"): rows beyond it are out of reach
        if k == 0 and len(arr) == 0:
            return Verdict(None)
        if len(arr) == 0:
            message = f"returned no configuration; the pose has {k}"
            # a mistaken pose out of reach: its (empty) set of solutions is the mistaken answer
            named = [(key, why) for key, why, rows in expected.get("wrong_sets", ()) if len(rows) == 0]
            return Verdict(message, "missing_solutions", (*named, ("missing_solutions", message)), message)
        if len(arr) > 4 * max(k, 1):  # far more rows than solutions: said before any other work (a bounded cost)
            return Verdict(
                f"returned {len(arr)} configurations; the pose has {k} solutions: list each solution once",
                "duplicates",
            )
        why = _not_reaching(arr, expected, expected["T"])
        if why is not None:
            return why
        stroke = expected.get("stroke")
        if stroke is not None and np.any(arr[:, stroke] < -1e-9):
            i = int(np.flatnonzero(arr[:, stroke] < -1e-9)[0])
            why = expected.get("stroke_reason")  # the question's own reason (a rod with a fixed part)
            return Verdict(
                why.format(i=i + 1, v=arr[i, stroke])
                if why
                else f"row {i + 1} has q2 = {arr[i, stroke]:.4g} < 0: a stroke cannot be negative; that value "
                "belongs to the other arctan solution of eq. (14) (lecture 06 (d))",
                "negative_stroke",
            )
        if stroke is not None and q2_max is not None and np.any(arr[:, stroke] > q2_max + 1e-9):
            i = int(np.flatnonzero(arr[:, stroke] > q2_max + 1e-9)[0])
            left = f"{k} configurations are left" if k else "no configuration is left: the pose is out of reach"
            return Verdict(
                f"row {i + 1} reaches the pose with q2 = {arr[i, stroke]:.4g}, beyond the stroke limit "
                f"q2_max = {q2_max:.4g} (lecture 06 §5): drop it; {left}",
                "stroke_limit",
            )
        D = joint_distance(arr[:, None, :], arr[None, :, :], rev)
        twice = np.argwhere(np.triu(D < match_tol, k=1))  # the same tolerance as a match: one solution, once
        if twice.size:
            i, j = (int(v) + 1 for v in twice[0])
            return Verdict(
                f"rows {i} and {j} are the same configuration: list each solution once (there are {k} here)",
                "duplicates",
            )
        if len(arr) > k:  # more rows than solutions, none two within the match tolerance (reference rows that close)
            return Verdict(
                f"returned {len(arr)} configurations; the pose has {k} solutions: list each solution once",
                "duplicates",
            )
        M = joint_distance(sols[:, None, :], arr[None, :, :], rev) < match_tol
        missing = [labels[i] for i in np.flatnonzero(~M.any(axis=1))]
        if missing:
            return Verdict(f"misses {len(missing)} of the {k} solutions: {', '.join(missing)}", "missing_solutions")
        extra = np.flatnonzero(~M.any(axis=0))
        if extra.size:
            return Verdict(
                f"row {extra[0] + 1} reaches the pose but matches none of the {k} solutions to 1e-6 "
                "(is it accurate enough?)"
            )
        if expected.get("ordered") and not np.all(np.diag(M)):
            for key, message, rows in expected.get("wrong_orders", ()):
                if np.all(joint_distance(np.asarray(rows, dtype=float), arr, rev) < match_tol):
                    return Verdict(message, key)
            return Verdict("the right solutions, in another order: sort them as the question asks", "solution_order")
        return Verdict(None)

    return made(judge, solution_set_judge, match_tol)


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
        d, ds = float(joint_distance(arr[0], q_ref, rev)), joint_distance(sols, q_ref, rev)
        best = int(np.argmin(ds))
        if d <= ds[best] + 1e-6:
            return Verdict(None)
        mine = joint_distance(sols, arr[0], rev)
        label = labels[int(np.argmin(mine))] if np.min(mine) < 1e-6 else "yours"
        not_nearest = (
            f"a solution ({label}), but not the nearest: it is {d:.3g} from q_ref, {labels[best]} is {ds[best]:.3g}"
        )
        candidates = [("not_nearest", not_nearest)]
        # the mistake "angle differences not wrapped" is named only when the answer IS the solution nearest by
        # the unwrapped distance (computed on the solutions, angles in (-π, π]), not guessed from a symptom
        plain = np.sqrt(np.sum((np.where(rev, wrap_angle(sols), sols) - q_ref) ** 2, axis=-1))
        if np.min(mine) < 1e-6 and int(np.argmin(plain)) == int(np.argmin(mine)):
            candidates.insert(
                0,
                (
                    "unwrapped_distance",
                    f"you chose {label}, the nearest if angle differences are not wrapped; wrapped to (-π, π] "
                    f"(179° and -179° are 2° apart) the nearest is {labels[best]}, {ds[best]:.3g} away against your "
                    f"{d:.3g}",
                ),
            )
        key, message = candidates[0]
        return Verdict(message, key, tuple(candidates), not_nearest)

    return made(judge, nearest_judge)


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
            i = int(np.flatnonzero(~ok)[0])
            plain = (
                f"the configuration for pose {i + 1} does not reach it: off by "
                f"{offset_text(fk(arr[i : i + 1]), path[i : i + 1])}"
            )
            if np.all(pose_ok(fk(revolute_to_radians(arr, rev)), path, scale)):
                return Verdict("your angles are in degrees: the course works in radians", "degrees", None, plain)
            for key, message, other_fk in expected.get("alternatives", ()):
                if np.all(pose_ok(other_fk(arr), path, scale)):
                    return Verdict(message, key, None, plain)
            return Verdict(plain, "not_a_solution")
        start, ref_start = float(joint_distance(arr[0], q0, rev)), float(joint_distance(ref[0], q0, rev))
        if start > ref_start + slack:
            return Verdict(
                f"your path starts {start:.3g} (joint distance) away from q0, where the arm stands: its "
                "first configuration must be the solution nearest q0",
                "start_jump",
            )
        steps, ref_steps = joint_distance(arr[1:], arr[:-1], rev), joint_distance(ref[1:], ref[:-1], rev)
        limit = 1.5 * float(np.max(ref_steps, initial=0.0)) + slack
        if np.max(steps, initial=0.0) > limit:
            k = int(np.argmax(steps))
            moved = np.abs(wrap_joints(arr[k + 1] - arr[k], rev))
            joints = ", ".join(str(j + 1) for j in np.flatnonzero(moved > 0.1)) or "several"
            return Verdict(
                f"between poses {k + 1} and {k + 2} joint(s) {joints} jump by up to {np.max(moved):.3g} (a step of "
                f"{steps[k]:.3g}; a smooth path never needs more than {limit:.3g}): pick, at every pose, the solution "
                "nearest the previous configuration",
                "jump",
            )
        return Verdict(None)

    return made(judge, path_judge, slack)


def rotation_judge(from_angles: Callable[..., np.ndarray]) -> Judge:
    """Judge angles by the rotation ``from_angles(*angles)`` they give (any equivalent triple passes).

    The reference gives ``{"R": the rotation asked for}`` and may add ``"alternatives"``
    (``(key, message, rotation)``).
    """

    def judge(got: Any, expected: Any, args: tuple[Any, ...]) -> Verdict:
        R = np.asarray(expected["R"], dtype=float)
        arr = as_floats(got)
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

    return made(judge, rotation_judge, from_angles)


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

    return made(judge, stroke_judge)
