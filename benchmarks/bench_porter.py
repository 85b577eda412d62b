"""Benchmark of Porter's chain (puma_course.porter): fk, ik_explicit, ik_geometric.

Run:  /work/venv/bin/python benchmarks/bench_porter.py
Prints fk ns/pose on a 100k batch, the scalar ik_explicit / ik_geometric µs/pose, the batched
Ver.1 (ik_explicit_batch) µs/pose, and the max round-trip error |fk(ik(T)) - T| over 10,000
seeded random poses (q2 > 0). Targets: ik_explicit <= 200 µs/pose, round trip <= 1e-12.
Timings are not asserted anywhere (shared, noisy machines): read them as orders of magnitude.
"""

from __future__ import annotations

import time

import numpy as np

from puma_course import porter as P

L1, L3, L4 = 1.0, 0.5, 0.3


def best_of(fn, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    rng = np.random.default_rng(2024)
    Q = rng.uniform(0.0, 2 * np.pi, (100_000, 6))
    Q[:, 2] = rng.uniform(0.05, 2.0, len(Q))
    t = best_of(lambda: P.fk(Q, L1, L3, L4))
    print(f"fk (batch of {len(Q)}):            {t / len(Q) * 1e9:8.1f} ns/pose")

    Qs = Q[:10_000]
    T = P.fk(Qs, L1, L3, L4)
    n = 2000
    t = best_of(lambda: [P.ik_explicit(T[i], L1, L3, L4) for i in range(n)], repeat=2)
    print(f"ik_explicit (scalar, all 4):       {t / n * 1e6:8.1f} µs/pose")
    t = best_of(lambda: [P.ik_explicit(T[i], L1, L3, L4, near=Qs[i]) for i in range(n)], repeat=2)
    print(f"ik_explicit (scalar, near=):       {t / n * 1e6:8.1f} µs/pose")
    t = best_of(lambda: [P.ik_geometric(T[i], L1, L3, L4) for i in range(n)], repeat=2)
    print(f"ik_geometric (scalar, 2):          {t / n * 1e6:8.1f} µs/pose")
    t = best_of(lambda: P.ik_explicit_batch(T, L1, L3, L4))
    print(f"ik_explicit_batch ({len(T)}):       {t / len(T) * 1e6:8.2f} µs/pose")

    S, _ = P.ik_explicit_batch(T, L1, L3, L4)
    back = P.fk(S.reshape(-1, 6), L1, L3, L4).reshape(len(T), 4, 4, 4)
    print(f"round trip, batch Ver.1, {len(T)} poses x 4: max error {np.abs(back - T[:, None]).max():.2e}")
    e1 = e2 = 0.0
    for i in range(len(T)):
        e1 = max(e1, float(np.abs(P.fk(P.ik_explicit(T[i], L1, L3, L4), L1, L3, L4) - T[i]).max()))
        e2 = max(e2, float(np.abs(P.fk(P.ik_geometric(T[i], L1, L3, L4), L1, L3, L4) - T[i]).max()))
    print(f"round trip, scalar ik_explicit, {len(T)} poses:  max error {e1:.2e}")
    print(f"round trip, scalar ik_geometric, {len(T)} poses: max error {e2:.2e}")


if __name__ == "__main__":
    main()
