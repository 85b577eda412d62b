"""References of exercises 8 to 10: the three-step procedure, PUMA-560 inverse kinematics, paths."""

from __future__ import annotations

import dataclasses
import math
import threading
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from puma_course import euler, transforms
from puma_course.kinematics import DHChain, MountedFk, Puma560, ThreeStepArm
from puma_course.kinematics import joint_distance as _joint_distance
from puma_course.kinematics import trajectories as tr

from ._common import _quiet, _set_expected, pose, tz
from .chains import PUMA_ZERO, random_rotations


# ---------------------------------------------------------------- exercise 8: the three-step procedure
def three_step(w: Any, F: Any, l1: float, l2: float, elbow: str, theta_bar: Any, F_bar: Any) -> Any:
    """The procedure from the start {θ̄0, θ̄1, θ̄2, F̄}."""
    start = (*(float(t) for t in np.asarray(theta_bar, dtype=float)), np.asarray(F_bar, dtype=float))
    return _quiet(ThreeStepArm(l1, l2).three_step, np.asarray(w, dtype=float), np.asarray(F, dtype=float), elbow, start)


#: Exercise 8's arm (issue 22, so that lecture 08's printed formulas do not answer it): its controller counts the
#: base angle θ0 from e_y (the lecture's θ0 is this one plus π/2), and a parallelogram drives the forearm, so θ2
#: is the forearm's elevation above the horizontal (the lecture's θ2 is this one minus θ1).
BASE_ZERO = np.pi / 2


def lecture_angles(theta_bar: Any, base_zero: bool = True, parallel: bool = True) -> np.ndarray:
    """Exercise 8's joint readings (θ0, θ1, θ2) as lecture 08's angles (base from e_x, elbow from the upper arm)."""
    t0, t1, t2 = (float(t) for t in np.asarray(theta_bar, dtype=float))
    return np.array([t0 + (BASE_ZERO if base_zero else 0.0), t1, t2 - t1 if parallel else t2])


def pallet_three_step(
    w: Any,
    F: Any,
    l1: float,
    l2: float,
    elbow: str,
    theta_bar: Any,
    F_bar: Any,
    *,
    base_zero: bool = True,
    parallel: bool = True,
) -> Any:
    """The procedure for exercise 8's arm, its start given in its own readings (``base_zero``/``parallel``
    False: the lecture's reading of that joint, the mistake)."""
    return three_step(w, F, l1, l2, elbow, lecture_angles(theta_bar, base_zero, parallel), F_bar)


def three_step_cases(rng: np.random.Generator, n: int, reach: Callable[..., Any]) -> list[tuple[Any, ...]]:
    """Cases (w, F, l1, l2, elbow, θ̄, F̄): reachable w, random target and bent start, either elbow."""
    out = []
    for (w, l1, l2), F, F_bar in zip(reach(rng, n), random_rotations(rng, n), random_rotations(rng, n), strict=True):
        out.append((w, F, l1, l2, "up" if rng.uniform() < 0.5 else "down", rng.uniform(-2.5, 2.5, 3), F_bar))
    return out


def zyz_expected(w: Any, F: Any, l1: float, l2: float, elbow: str, theta_bar: Any, F_bar: Any) -> dict[str, Any]:
    """The wrist's rotation F2^T F (about its own moving axes) for the rotation judge, with the usual mix-ups."""
    sol = pallet_three_step(w, F, l1, l2, elbow, theta_bar, F_bar)
    F2, F = sol.frame_step2, np.asarray(F, dtype=float)
    lecture = [
        pallet_three_step(w, F, l1, l2, elbow, theta_bar, F_bar, base_zero=b, parallel=p).frame_step2
        for b, p in ((False, False), (True, False), (False, True))
    ]
    msg = (
        "your angles give F F2ᵀ, the rotation seen from the base (fixed axes); the wrist turns about its own "
        "moving axes: F = F2 Rz(φ) Ry(ϑ) Rz(ψ)"
    )
    return {
        "R": F2.T @ F,
        "alternatives": [
            ("order", msg, F @ F2.T),
            (
                "transposed",
                "your angles give the transpose of the rotation asked for (Fᵀ F2 instead of F2ᵀ F)",
                F.T @ F2,
            ),
            *(("lecture_mechanism", LECTURE_ARM, G.T @ F) for G in lecture),
        ],
    }


LECTURE_ARM = (
    "this is what lecture 08's arm gives from this start; this arm counts θ0 from e_y and its θ2 is the forearm's "
    "elevation above the horizontal (a parallelogram), so read the start's angles as this arm's before you turn"
)

#: Rz(φ) Ry(ϑ) Rz(ψ): the package's own (the judge of a student's angles needs it, so the edition has it)
rotation_from_zyz = euler.rotation_from_zyz


# ---------------------------------------------------------------- exercise 9: PUMA-560 inverse kinematics
def puma_fk(q: Any, a2: float = 0.4318, a3: float = 0.0203, d3: float = 0.15005, d4: float = 0.4318) -> np.ndarray:
    """^0T_6 of the PUMA-560 with the given lengths (metres)."""
    return Puma560(a2, a3, d3, d4).fk(np.asarray(q, dtype=float))


def joint_distance(q: Any, q_ref: Any, weights: Any = None) -> float:
    """The course's distance between two configurations of revolute joints (angle differences wrapped); with
    ``weights``, a controller's weighted distance sqrt(Σ w_i wrap(q_i - q_ref_i)²) (exercise 10, question 1)."""
    if weights is None:
        return float(_joint_distance(q, q_ref))
    d = np.asarray(transforms.wrap_angle(np.asarray(q, dtype=float) - np.asarray(q_ref, dtype=float)))
    return float(np.sqrt(np.sum(np.asarray(weights, dtype=float) * d * d)))


def puma_cases(rng: np.random.Generator, n: int, near_singular: bool = True) -> list[tuple[Any, ...]]:
    """Cases (T, a2, a3, d3, d4): lengths around the lecture's; with ``near_singular`` the first three poses sit
    1e-5 from the wrist singularity, 1e-4 rad from the stretched elbow and 1e-5 from the shoulder cylinder."""
    out = []
    for k in range(n):
        L = np.array(list(Puma560().lengths.values())) * rng.uniform(0.7, 1.3, 4)
        arm, q = Puma560(*L), rng.uniform(-np.pi, np.pi, 6)
        if near_singular and k == 0:
            q[4] = 1e-5 * rng.choice([-1.0, 1.0])
        elif near_singular and k == 1:
            q[2] = math.atan2(-L[3], L[1]) + 1e-4
        elif near_singular and k == 2:
            q[1] = _shoulder_theta2(q[2], *L) + 1e-5
        out.append((arm.fk(q), *(float(v) for v in L)))
    return out


def _shoulder_theta2(t3: float, a2: float, a3: float, d3: float, d4: float) -> float:
    """θ2 that puts the wrist centre straight beside the shoulder (reach X = 0: the shoulder singularity)."""
    vx, vy = a2 + a3 * math.cos(t3) - d4 * math.sin(t3), a3 * math.sin(t3) + d4 * math.cos(t3)
    return math.atan2(vx, vy)


def puma_ik_expected(
    T: Any, a2: float = 0.4318, a3: float = 0.0203, d3: float = 0.15005, d4: float = 0.4318
) -> dict[str, Any]:
    """Every configuration reaching T, for the set judge."""
    return _set_expected(Puma560(a2, a3, d3, d4), T)


def puma_arm_expected(p: Any, a2: float, a3: float, d3: float, d4: float) -> dict[str, Any]:
    """The four (θ1, θ2, θ3) putting the wrist centre at p, for the set judge (poses: the wrist centre's)."""
    arm = Puma560(a2, a3, d3, d4)
    T = pose(np.eye(3), p)
    sol = _quiet(arm.ik, T)
    keep = [i for i, lab in enumerate(sol.labels) if lab.endswith("noflip")]

    fk = MountedFk(arm.fk, pad=3, position_only=True)  # the wrist centre of (θ1, θ2, θ3)

    return {
        "T": T,
        "solutions": np.asarray(sol.q)[keep, :3],
        "labels": tuple(sol.labels[i].rsplit("/", 1)[0] for i in keep),
        "fk": fk,
        "revolute": np.ones(3, bool),
        "scale": 1.0,
    }


# The controller's joint values (ex03 q2): θ2 and θ3 counted from the arm straight up, so the lecture's joint
# vector is q + PUMA_ZERO. Exercise 9 asks every question in them: the lecture's printed formulas give the
# lecture's joint values, which put the arm elsewhere.
def upright_fk(q: Any, a2: float = 0.4318, a3: float = 0.0203, d3: float = 0.15005, d4: float = 0.4318) -> np.ndarray:
    """^0T_6 of the PUMA-560 at the controller's joint values q (arm straight up at q = 0)."""
    return Puma560(a2, a3, d3, d4).fk(np.asarray(q, dtype=float) + PUMA_ZERO)


def upright_chain(a2: float = 0.4318, a3: float = 0.0203, d3: float = 0.15005, d4: float = 0.4318) -> DHChain:
    """The PUMA-560's chain with the controller's zero (θ offsets -π/2 on joints 2, 3): a package object, so the
    judge's forward kinematics travels into a student edition whole (no bank code)."""
    arm = Puma560(a2, a3, d3, d4)
    links = [dataclasses.replace(lk, theta=lk.theta + z) for lk, z in zip(arm.links, PUMA_ZERO, strict=True)]
    return DHChain(links, name="PUMA-560, upright zero")


def to_upright(rows: Any) -> np.ndarray:
    """The lecture's joint values (rows, 3 or 6 columns) in the controller's, wrapped to (-π, π]."""
    R = np.asarray(rows, dtype=float)
    return np.asarray(transforms.wrap_angle(R - PUMA_ZERO[: R.shape[-1]])) if R.size else R.reshape(-1, R.shape[-1])


#: What rows in the lecture's joint values (θ2, θ3 counted from the arm stretched forward) are told.
LECTURE_ZERO = (
    "your rows are right in the lecture's joint values: this exercise counts θ2 and θ3 from the arm straight up "
    "(the controller's zero of ex03 q2), so θ = θ_lecture + π/2 for joints 2 and 3"
)


def _upright(expected: dict[str, Any], fk: Callable[..., Any]) -> dict[str, Any]:
    """The expected set in the controller's joint values; rows in the lecture's (q + PUMA_ZERO) are named."""
    n = np.asarray(expected["solutions"]).reshape(-1, len(expected["revolute"])).shape[1]
    offsets = [("joint_zero", LECTURE_ZERO, PUMA_ZERO[:n])]
    return {**expected, "solutions": to_upright(expected["solutions"]), "fk": fk, "offsets": offsets}


def puma_ik_upright_expected(T: Any, a2: float, a3: float, d3: float, d4: float) -> dict[str, Any]:
    """Every configuration (the controller's joint values) reaching T, for the set judge."""
    return _upright(puma_ik_expected(T, a2, a3, d3, d4), upright_chain(a2, a3, d3, d4).fk)


def puma_arm_upright_expected(p: Any, a2: float, a3: float, d3: float, d4: float) -> dict[str, Any]:
    """The four (θ1, θ2, θ3), the controller's, putting the wrist centre at p, for the set judge."""
    fk = MountedFk(upright_chain(a2, a3, d3, d4).fk, pad=3, position_only=True)
    return _upright(puma_arm_expected(p, a2, a3, d3, d4), fk)


def puma_det_j(q: Any, a2: float, a3: float, d3: float, d4: float) -> float:
    """det J of the PUMA-560 at the controller's joint values q (the geometric Jacobian, 6 x 6)."""
    q_lecture = np.asarray(q, dtype=float) + PUMA_ZERO
    return float(np.linalg.det(Puma560(a2, a3, d3, d4).jacobian(q_lecture)))


def puma_lost_direction(q: Any, a2: float, a3: float, d3: float, d4: float) -> np.ndarray:
    """At an elbow or shoulder singularity (controller's q): the unit direction in which the wrist centre cannot
    move, the left singular vector of J_w = ∂p/∂(θ1, θ2, θ3) with the smallest singular value, signed u · p > 0."""
    arm, q_lecture = Puma560(a2, a3, d3, d4), np.asarray(q, dtype=float) + PUMA_ZERO
    U, _, _ = np.linalg.svd(arm.jacobian(q_lecture)[:3, :3])
    u = U[:, -1]
    return u if float(u @ arm.fk(q_lecture)[:3, 3]) > 0 else -u


def puma_singular_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (q, a2, a3, d3, d4), q the controller's: at the stretched elbow or the shoulder singularity,
    alternately, lengths around the lecture's."""
    out = []
    for k in range(n):
        L = np.array(list(Puma560().lengths.values())) * rng.uniform(0.7, 1.3, 4)
        q = rng.uniform(-np.pi, np.pi, 6)
        stretched = math.atan2(-L[3], L[1])
        if k % 2 == 0:  # the elbow stretched: a3 s3 + d4 c3 = 0; the reach X kept away from 0
            q[2] = stretched  # (folded, the PUMA's wrist centre is 0.5 mm from the shoulder: no direction to speak of)
            while abs(_reach(q[1], q[2], *L)) < 0.1 * L[0]:
                q[1] = rng.uniform(-np.pi, np.pi)
        else:  # the shoulder: the reach X = 0, the elbow kept away from its singularity
            q[2] = stretched + rng.choice([-1.0, 1.0]) * rng.uniform(0.4, 2.7)
            q[1] = _shoulder_theta2(q[2], *L)
        out.append((to_upright(q[None])[0], *(float(v) for v in L)))
    return out


def _reach(t2: float, t3: float, a2: float, a3: float, d3: float, d4: float) -> float:
    """The reach X = a2 c2 + a3 c23 - d4 s23 (lecture 09 §1), the lecture's joint values."""
    return a2 * math.cos(t2) + a3 * math.cos(t2 + t3) - d4 * math.sin(t2 + t3)


def puma_det_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (q, a2, a3, d3, d4) for det J: random controller's q, |sin θ5| > 0.2 (a singular arm, det J = 0, is
    one public case: more would let a wrong sign or a missing factor pass them)."""
    out = []
    for _ in range(n):
        L = np.array(list(Puma560().lengths.values())) * rng.uniform(0.7, 1.3, 4)
        q = rng.uniform(-np.pi, np.pi, 6)
        q[4] = rng.choice([-1.0, 1.0]) * rng.uniform(0.2, np.pi - 0.2)
        out.append((q, *(float(v) for v in L)))
    return out


def puma_nearest_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T, q_ref, a2, a3, d3, d4) on poses near singularities (:func:`puma_cases`): q_ref near one solution
    with one joint across ±π from it, drawn until the solution nearest by the unwrapped distance is another one
    (so not wrapping fails every hidden case)."""
    out: list[tuple[Any, ...]] = []
    poses = puma_cases(rng, n, near_singular=True)
    while len(out) < n:
        T, *L = poses[len(out)]
        sol = np.atleast_2d(np.asarray(_quiet(Puma560(*L).ik, T).q, dtype=float))
        for _ in range(50):
            q_ref = sol[int(rng.integers(len(sol)))] + rng.normal(0.0, 0.05, 6)
            j = int(rng.integers(6))  # one joint just across ±π from the solution: only a wrapped distance sees it
            q_ref[j] = math.copysign(math.pi, -q_ref[j]) + math.copysign(0.05, q_ref[j]) * -1.0
            q_ref = np.asarray(transforms.wrap_angle(q_ref))
            wrapped = np.asarray(transforms.wrap_angle(sol - q_ref))
            plain = np.asarray(transforms.wrap_angle(sol)) - q_ref
            if int(np.argmin(np.sum(wrapped**2, axis=1))) != int(np.argmin(np.sum(plain**2, axis=1))):
                out.append((T, q_ref, *L))
                break
        else:  # no q_ref separates the two distances on this pose: another pose
            poses[len(out)] = puma_cases(rng, 1, near_singular=False)[0]
    return out


def puma_nearest_expected(T: Any, q_ref: Any, a2: float, a3: float, d3: float, d4: float) -> dict[str, Any]:
    """What the nearest judge needs."""
    return {**_set_expected(Puma560(a2, a3, d3, d4), T), "q_ref": np.asarray(q_ref, dtype=float)}


def puma_world_expected(T_world: Any, B: Any, d6: float) -> dict[str, Any]:
    """The lecture's PUMA-560 standing at B (world) with a tool d6 along z6: every configuration putting the tool
    at T_world, and the poses a row reaches after the usual mistakes."""
    arm, T_world, B = Puma560(), np.asarray(T_world, dtype=float), np.asarray(B, dtype=float)
    Bi = transforms.inverse_transform(B)
    alts = [
        ("base_frame", "you solved as if the robot stood at the world origin: its base frame is B", B @ T_world),
        (
            "order",
            "you composed B on the wrong side: T_world = B ⁰T₆ Tz(d6), so ⁰T₆ = B⁻¹ T_world Tz(-d6)",
            B @ T_world @ Bi @ tz(-d6) @ tz(d6),
        ),
        (
            "order",
            "you composed the tool on the wrong side: the tool is d6 along the hand's own z6, so Tz(d6) multiplies "
            "⁰T₆ on the right: ⁰T₆ = B⁻¹ T_world Tz(-d6), not B⁻¹ Tz(-d6) T_world",
            tz(-d6) @ T_world @ tz(d6),
        ),
        ("tool_frame", "your configurations put frame {6}, not the tool tip, at the pose asked for", T_world @ tz(d6)),
        (
            "offset_sign",
            "the tool is d6 beyond frame {6} along z6: ⁰T₆ = B⁻¹ T_world Tz(-d6), not Tz(+d6)",
            T_world @ tz(2 * d6),
        ),
    ]
    out = _set_expected(arm, Bi @ T_world @ tz(-d6), alternatives=alts)
    out = _upright(out, MountedFk(upright_chain().fk, base=B, tool=tz(d6)))  # the controller's joint values
    out["T"] = T_world
    # what the same mistakes give when their ⁰T₆ is out of reach: no solution (the judge names an empty answer)
    out["wrong_sets"] = [
        (key, message, to_upright(np.asarray(_quiet(arm.ik, Bi @ P @ tz(-d6)).q).reshape(-1, 6)))
        for key, message, P in alts
    ]
    return out


def puma_world_cases(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (T_world, B, d6): the robot on a random base (a pedestal turned and shifted, or hung upside down),
    drawn until every mistake of :func:`puma_world_expected` (the base forgotten or on the wrong side, the tool
    left out or added) asks for a pose the arm reaches: an answer that makes one is then named on every case,
    not only where its IK returns nothing (an IK that clips its square roots returns rows there, reaching nothing)."""
    out: list[tuple[Any, ...]] = []
    while len(out) < n:
        R = transforms.rotz(rng.uniform(-np.pi, np.pi)) @ (transforms.rotx(np.pi) if len(out) % 2 else np.eye(3))
        B, d6 = pose(R, rng.uniform(-0.4, 0.4, 3)), float(rng.uniform(0.05, 0.2))
        q = rng.uniform(-np.pi, np.pi, 6)
        T_world = B @ Puma560().fk(q) @ tz(d6)
        if all(len(rows) for _, _, rows in puma_world_expected(T_world, B, d6)["wrong_sets"]):
            out.append((T_world, B, d6))
    return out


# ---------------------------------------------------------------- exercise 10: trajectories
def puma_path_expected(path: Any, q0: Any, d_tool: float) -> dict[str, Any]:
    """What the path judge needs: the pen path, the smoothest joint path (``follow``) and the mistaken fks."""
    arm, path = Puma560(), np.asarray(path, dtype=float)
    ref = tr.follow(arm, path @ tz(-d_tool), np.asarray(q0, dtype=float)).q
    alts = [
        ("tool_frame", "your path puts frame {6} (the wrist), not the pen tip, on the path", arm.fk),
        (
            "offset_sign",
            "the pen tip is d beyond frame {6} along z6: ⁰T₆ = T_pen Tz(-d), not Tz(+d)",
            MountedFk(arm.fk, tool=tz(-d_tool)),
        ),
    ]
    return {
        "path": path,
        "fk": MountedFk(arm.fk, tool=tz(d_tool)),
        "q0": np.asarray(q0, dtype=float),
        "ref": ref,
        "revolute": arm.revolute,
        "scale": 1.0,
        "alternatives": alts,
    }


def puma_paths(rng: np.random.Generator, n: int) -> list[tuple[Any, ...]]:
    """Cases (path, q0, d_tool): lines through a wrist flip (θ5 crossing 0 between samples) and circles, each
    starting from a configuration that is not the solver's first branch."""
    arm, out = Puma560(), list[tuple[Any, ...]]()
    while len(out) < n:  # only paths where nearest-the-start jumps (see _start_nearest_jumps)
        k = len(out)
        d = float(rng.uniform(0.05, 0.15))
        q_mid = np.array(
            [
                rng.uniform(-1, 1),
                rng.uniform(-0.9, -0.3),
                rng.uniform(0.1, 0.5),
                rng.uniform(-1, 1),
                0.0,
                rng.uniform(-1, 1),
            ]
        )
        T_mid = arm.fk(q_mid)
        if k % 2 == 0:
            step = 0.15 * T_mid[:3, 2] if k % 4 == 0 else 0.15 * np.array([0.0, 0.0, 1.0])
            T0 = T_mid.copy()
            T0[:3, 3] -= step
            path06 = tr.line_path(T0, T_mid[:3, 3] + step, int(rng.integers(30, 45)) * 2)
        else:
            path06 = tr.circle_path(
                T_mid[:3, 3] + [0.0, 0.08, 0.0], 0.08, rng.normal(size=3), T_mid[:3, :3], int(rng.integers(30, 45))
            )
        sols = _quiet(arm.ik, path06[0])
        q0 = sols.q[int(rng.integers(1, len(sols)))]
        if _start_nearest_jumps(arm, path06, q0):
            out.append((path06 @ tz(d), q0, d))
    return out


class PublicPaths(Sequence[tuple[Any, ...]]):
    """The public cases ``puma_paths(default_rng(seed), n)``, drawn the first time they are used, not when the bank
    is imported: a command that loads the bank without grading ex10's q3 (release, edition of other exercises,
    every check) does not pay for the drawing. Read-only, like the tuple it stands for, and pickled as that tuple.

    >>> paths = PublicPaths(seed=10, n=2)
    >>> paths._cases is None, len(paths), paths._cases is not None
    (True, 2, True)
    """

    def __init__(self, seed: int, n: int) -> None:
        self.seed, self.n = seed, n
        self._cases: tuple[tuple[Any, ...], ...] | None = None
        self._lock = threading.Lock()  # the grader plans in several threads: the first to need them draws them

    def _drawn(self) -> tuple[tuple[Any, ...], ...]:
        if self._cases is None:
            with self._lock:
                if self._cases is None:
                    self._cases = tuple(puma_paths(np.random.default_rng(self.seed), self.n))
        return self._cases

    def __getitem__(self, index: Any) -> Any:
        return self._drawn()[index]

    def __len__(self) -> int:
        return len(self._drawn())

    def __repr__(self) -> str:  # the tuple's (an exercise's repr is the same as with the tuple itself)
        return repr(self._drawn())

    def __reduce__(self) -> tuple[Any, ...]:
        # pickled as the plain tuple it stands for: a student edition's public data names no bank code
        return (tuple, (self._drawn(),))


def _follow_rows(arm: Puma560, path06: np.ndarray, sols: Any, q0: np.ndarray) -> np.ndarray:
    """``tr.follow(arm, path06, q0).q`` from the batch ``sols`` already solved: the same rows, the same ties.

    follow takes, pose after pose, the valid branch nearest the previous choice (solving a flagged, singular
    pose again with the previous configuration as ``near``). Here the costs from each branch of one pose to each
    branch of the next are computed at once, so that the walk along the path is a loop over indices; a flagged
    pose (its rows depend on the choice before it) is taken step by step as follow takes it.
    """
    Q, valid = sols.q.copy(), sols.valid.copy()
    n = Q.shape[0]
    flagged = (np.asarray(sols.flags).reshape(n, -1) != 0).any(axis=1)

    def nearest(i: int, prev: np.ndarray) -> int:  # trajectories.nearest_index for one pose (all joints revolute)
        d = np.asarray(transforms.wrap_angle(Q[i] - prev))
        return int(np.argmin(np.where(valid[i], np.einsum("kj,kj->k", d, d), np.inf)))

    D = np.asarray(transforms.wrap_angle(Q[1:, None, :, :] - Q[:-1, :, None, :]))  # (n - 1, from, to, 6)
    best = np.argmin(np.where(valid[1:, None, :], np.einsum("...kj,...kj->...k", D, D), np.inf), axis=-1)
    prev, j, choice = np.asarray(q0, dtype=float), -1, np.empty(n, dtype=int)
    for i in range(n):
        if flagged[i]:
            again = _quiet(arm.ik, path06[i], near=prev)
            if len(again) and again.labels[0] in sols.labels:
                k = sols.labels.index(again.labels[0])
                Q[i, k], valid[i, k] = again[0], True
        j = nearest(i, prev) if i == 0 or flagged[i] or flagged[i - 1] else int(best[i - 1, j])
        choice[i], prev = j, Q[i, j]
    return Q[np.arange(n), choice]


def _follows_itself(sols: Any, pick: np.ndarray, mine: np.ndarray, q0: np.ndarray) -> bool:
    """True when follow would choose the branches ``pick`` too: at no pose flagged singular, the first nearest
    ``q0`` and each the valid branch nearest the one before (follow's rule and costs; ties to the first)."""
    if (np.asarray(sols.flags) != 0).any():
        return False
    prev = np.concatenate([np.asarray(q0, dtype=float)[None], mine[:-1]])
    D = np.asarray(transforms.wrap_angle(sols.q - prev[:, None, :]))  # (n, branch, 6)
    return bool(np.array_equal(np.argmin(np.where(sols.valid, np.einsum("...kj,...kj->...k", D, D), np.inf), axis=-1),
                               pick))  # fmt: skip


def _start_nearest_jumps(arm: Puma560, path06: np.ndarray, q0: np.ndarray, slack: float = 0.01) -> bool:
    """True when choosing, at every pose, the solution nearest the *start* q0 (not the previous pose) makes a
    step the path judge calls a jump: only such paths tell that mistake from the right method."""
    # every branch of every pose in one batched solve (the rows arm.ik gives, bit for bit: the same decisions
    # as solving pose by pose, so the same paths are drawn for the same key; tests/grading/bank/test_ex10_paths.py)
    sols = _quiet(arm.ik_batch, path06)
    d = np.asarray(transforms.wrap_angle(sols.q - q0))
    pick = np.argmin(np.where(sols.valid, np.sum(d * d, axis=2), np.inf), axis=1)
    mine = sols.q[np.arange(len(path06)), pick]
    if _follows_itself(sols, pick, mine, q0):
        return False  # nearest the start is what follow chooses at every pose: the same path, no jump to tell
    ref = _follow_rows(arm, path06, sols, q0)

    def largest(P: np.ndarray) -> float:
        d = np.asarray(transforms.wrap_angle(P[1:] - P[:-1]))
        return float(np.max(np.sqrt(np.sum(d * d, axis=1)), initial=0.0))

    return largest(mine) > 1.5 * largest(ref) + slack


def three_step_variant(
    field: str,
    *,
    zero_theta: bool = False,
    identity_frame: bool = False,
    other_elbow: bool = False,
    base_zero: bool = True,
    parallel: bool = True,
) -> Callable[..., np.ndarray]:
    """``field`` of the procedure under a mistake: the start's angles taken as 0, its frame as I, the other elbow.

    Takes the same arguments as the question asking for ``field`` (q1: w, θ̄, F̄; q3: w, l1, l2, elbow, θ̄, F̄;
    q4, q5: w, F, l1, l2, elbow, θ̄, F̄).
    """

    def wrong(*args: Any) -> np.ndarray:
        w, F, l1, l2, elbow, tb, Fb = _three_step_args(args)
        tb = np.zeros(3) if zero_theta else tb
        Fb = np.eye(3) if identity_frame else Fb
        elbow = {"up": "down", "down": "up"}[elbow] if other_elbow else elbow
        sol = pallet_three_step(w, F, l1, l2, elbow, tb, Fb, base_zero=base_zero, parallel=parallel)
        return _field(sol, field, parallel)

    return wrong


def _three_step_args(args: tuple[Any, ...]) -> tuple[Any, ...]:
    """(w, F, l1, l2, elbow, θ̄, F̄) from the arguments of any three-step question (missing ones filled in)."""
    if len(args) == 3:  # step 1 (w, θ̄, F̄): the lengths do not matter, pick ones that reach w
        r = math.hypot(*np.asarray(args[0], dtype=float).tolist())
        return args[0], np.eye(3), r, r, "up", args[1], args[2]
    if len(args) == 4:  # the arm's angles (w, l1, l2, elbow): neither the start nor the target matters
        return args[0], np.eye(3), *args[1:], np.zeros(3), np.eye(3)
    if len(args) == 6:  # step 2 (w, l1, l2, elbow, θ̄, F̄): the target does not matter
        return args[0], np.eye(3), *args[1:]
    return tuple(args)


def _field(sol: Any, field: str, parallel: bool = True) -> np.ndarray:
    if field == "arm":  # exercise 8's θ2 is the forearm's elevation (parallel), the lecture's from the upper arm
        return np.asarray([sol.theta1, sol.theta1 + sol.theta2 if parallel else sol.theta2], dtype=float)
    return np.asarray(getattr(sol, field), dtype=float)


def step_field(field: str) -> Callable[..., np.ndarray]:
    """The reference of a three-step question asking for ``field`` (arm: [θ1, θ2]), exercise 8's arm."""

    def ref(*args: Any) -> np.ndarray:
        return _field(pallet_three_step(*_three_step_args(args)), field)

    return ref


def elevations_added(w: Any, l1: float, l2: float, elbow: str, theta_bar: Any, F_bar: Any) -> np.ndarray:
    """The mistake of step 2: this arm's θ2 read as lecture 08's elbow angle *in the step*, the forearm turned by
    Δ(θ1 + θ2) = (θ1 + θ2) - (θ̄1 + θ̄2) where it turns by θ2 - θ̄2 (both readings this arm's): the right frame
    turned further by θ1 - θ̄1 about the same axis a."""
    sol = pallet_three_step(w, np.eye(3), l1, l2, elbow, theta_bar, F_bar)
    g = math.atan2(float(np.asarray(w, dtype=float)[1]), float(np.asarray(w, dtype=float)[0]))
    a = np.array([math.sin(g), -math.cos(g), 0.0])
    extra = float(sol.theta1) - float(np.asarray(theta_bar, dtype=float)[1])
    return np.asarray(transforms.rodrigues(a, extra) @ np.asarray(sol.frame_step2, dtype=float))


def moved_wrong_way(field: str) -> Callable[..., np.ndarray]:
    """The step's rotation applied on the wrong side (about the moving axes): F̄ K(e_z, δ0), F1 K(a, δ) or F2ᵀ F."""

    def wrong(*args: Any) -> np.ndarray:
        sol = pallet_three_step(*_three_step_args(args))
        if field == "frame_step1":
            return np.asarray(sol.start.frame) @ sol.K_base
        if field == "frame_step2":
            return sol.frame_step1 @ sol.K_arm
        return sol.frame_step2.T @ np.asarray(args[1], dtype=float)

    return wrong


def wrap_near_pi(q: Any) -> np.ndarray:
    """Joint values wrapped into (-π, π] (where a distance that forgets to wrap goes wrong)."""
    return np.asarray(transforms.wrap_angle(np.asarray(q, dtype=float)))


def sorted_expected(solutions: Any, q_prev: Any, weights: Any = None) -> dict[str, Any]:
    """The PUMA-560 solutions of one pose, nearest ``q_prev`` first by the weighted wrapped distance (all weights
    1 without ``weights``), for the set judge (ordered); the orders of the usual mistakes: not wrapping the angle
    differences, leaving out the weights, or not sorting at all."""
    S, q = np.asarray(solutions, dtype=float), np.asarray(q_prev, dtype=float)
    w = np.ones(S.shape[-1]) if weights is None else np.asarray(weights, dtype=float)
    arm = Puma560()
    d = np.asarray(transforms.wrap_angle(S - q))
    plain = S[np.argsort(np.sum(w * (S - q) ** 2, axis=1), kind="stable")]
    wrong = [("unwrapped_distance", "sorted without wrapping the angle differences: 179° and -179° are 2° apart, "
              "not 358° (lecture 10 §2)", plain)]  # fmt: skip
    if weights is not None:
        unweighted = S[np.argsort(np.sum(d * d, axis=1), kind="stable")]
        message = "sorted by lecture 10's unweighted distance: multiply each squared difference by its joint's weight"
        wrong.append(("lecture_mechanism", message, unweighted))
    wrong.append(("solution_order", "these are the solutions as given, not sorted by their distance to q_prev", S))
    return {"T": arm.fk(S[0]), "solutions": S[np.argsort(np.sum(w * d * d, axis=1), kind="stable")],
            "labels": tuple(f"solution {i + 1}" for i in range(len(S))), "fk": arm.fk, "revolute": arm.revolute,
            "scale": 1.0, "ordered": True, "wrong_orders": wrong}  # fmt: skip
