"""Worst pose error of the kinematics near each threshold of issue 21 ("No wrong answer at any edge").

Prints, per threshold, how many poses were solved, the worst pose error of any returned solution (in
units of the robot's size), how many poses lost the start configuration with ``near=q0`` (beyond the
conditioning bound stated per line), and how many disagreed between ``ik`` and ``ik_batch``. The truth is
the generic product of link matrices (:meth:`DHChain.fk`), not the closed forms.

Run: ``python benchmarks/bench_edges.py [N]`` (N poses per threshold, default 2000).
"""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np

from puma_course.kinematics import MK3, DHChain, Puma560
from puma_course.kinematics.frame_assignment import common_normal
from puma_course.transforms import axis_angle, rodrigues


def _wrapped(a: np.ndarray) -> np.ndarray:
    return np.abs(np.arctan2(np.sin(a), np.cos(a)))


def _puma_case(arm: Puma560, Q: np.ndarray, tol: float, start_tol: float) -> tuple[float, int, int]:
    a2, a3, d3, d4 = arm.lengths.values()
    size = a2 + math.hypot(a3, d4) + abs(d3)
    worst, lost, mismatch = 0.0, 0, 0
    for q in Q:
        T = arm.fk(q)
        sol = arm.ik(T, near=q, tol=tol)
        b = arm.ik_batch(T[None], near=q[None], tol=tol)
        rows = np.array(list(sol))
        worst = max(worst, float(np.abs(DHChain.fk(arm, rows) - T).max()) / size)
        lost += int(_wrapped(rows - q).max(axis=1).min() > start_tol)
        mismatch += int(b.valid.sum() != len(rows))
    return worst, lost, mismatch


def main(n: int) -> None:
    warnings.simplefilter("ignore")
    rng = np.random.default_rng(21)
    arm = Puma560()
    print(f"{'threshold':58s} {'poses':>6s} {'worst err/size':>15s} {'start lost':>10s} {'ik!=batch':>9s}")
    for t5 in (0.0, 1e-12, 1e-9, 5e-8, -1e-7, 1e-7, 2e-7):
        for tol in (1e-7, 1e-12):
            Q = rng.uniform(-3, 3, (n, 6))
            Q[:, 4] = t5
            w, lost, mm = _puma_case(arm, Q, tol, 1e-6 if abs(t5) != 1e-12 else 1e-3)
            print(f"PUMA wrist θ5 = {t5:<8g} tol = {tol:<6g}{'':27s} {n:6d} {w:15.3g} {lost:10d} {mm:9d}")
    a2, a3, d3, d4 = arm.lengths.values()
    for dt3 in (0.0, 1e-9, 5e-8, 2e-7):
        Q = rng.uniform(-3, 3, (n, 6))
        Q[:, 2] = math.atan2(a3, d4) - math.pi / 2 + dt3
        Q[:, 4] = np.where(np.abs(Q[:, 4]) < 0.01, 0.01, Q[:, 4])
        w, lost, mm = _puma_case(arm, Q, 1e-7, 1e-6 + 4e-7 / 0.01)
        print(f"PUMA elbow stretched + {dt3:<8g}{'':34s} {n:6d} {w:15.3g} {lost:10d} {mm:9d}")
    # MK3 with the wrist point microns from the base axis
    sys.path.insert(0, "tests/kinematics")
    from test_edges import _mk3_wrist_near_axis_configs  # noqa: E402  (the test's generator)

    mk3 = MK3()
    size = sum(abs(v) for v in mk3.lengths.values())
    Q = _mk3_wrist_near_axis_configs(min(n, 500), seed=22)
    refused, worst = 0, 0.0
    for q in Q:
        T = mk3.fk(q)
        sol = mk3.ik(T, near=q)
        if not sol.success:
            refused += 1
            continue
        worst = max(worst, max(float(np.abs(DHChain.fk(mk3, r) - T).max()) for r in sol) / size)
    print(f"MK3 wrist point 1e-7..1e-4 mm from the base axis (refused {refused}){'':11s} {len(Q):6d} {worst:15.3g}")
    # common normal, nearly parallel lines
    for delta in (5e-9, 1.2e-8, 1e-7):
        err = 0.0
        for _ in range(200):
            R = rodrigues(rng.normal(size=3), rng.uniform(0, 3))
            u2 = np.array([math.sin(delta), 0.0, math.cos(delta)])
            cn = common_normal(R @ [0.0, 0.0, 1.0], R[:, 2], R @ ([0.0, 1.0, 0.0] + 2.0 * u2), R @ u2)
            err = max(err, abs(cn.a - 1.0), abs(cn.alpha - delta))
        print(f"common_normal δ = {delta:<8g} (worst |a - 1|, |α - δ|){'':20s} {200:6d} {err:15.3g}")
    for delta in (1e-7, 1e-6, 1e-5):
        err = 0.0
        for _ in range(200):
            k = rng.normal(size=3)
            Rk = rodrigues(k, math.pi - delta)
            ax, ang = axis_angle(Rk)
            err = max(err, float(np.abs(rodrigues(ax, ang) - Rk).max()))
        print(f"axis_angle θ = π - {delta:<8g} (round trip){'':25s} {200:6d} {err:15.3g}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)
