"""Input generators of the question bank that need numpy only (no kinematics: see ``_reference``)."""

from __future__ import annotations

from typing import Any

import numpy as np


def unit_vectors(rng: np.random.Generator, n: int) -> np.ndarray:
    """``n`` random unit 3-vectors: shape (n, 3).

    >>> np.allclose(np.linalg.norm(unit_vectors(np.random.default_rng(0), 4), axis=1), 1)
    True
    """
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def angles(rng: np.random.Generator, n: int, k: int) -> list[tuple[Any, ...]]:
    """``n`` one-argument cases, each a joint vector of ``k`` angles in [-π, π)."""
    return [(q,) for q in rng.uniform(-np.pi, np.pi, (n, k))]


def reachable_wrist_points(rng: np.random.Generator, n: int) -> list[tuple[np.ndarray, float, float]]:
    """Cases (w, l1, l2) of the three-step exercise: w reachable, off both reach limits and the base axis."""
    out: list[tuple[np.ndarray, float, float]] = []
    while len(out) < n:
        l1, l2 = (float(x) for x in rng.uniform(0.5, 2.0, 2))
        r = rng.uniform(abs(l1 - l2) + 0.1, l1 + l2 - 0.1)
        if r <= 0.1:
            continue
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        if np.hypot(d[0], d[1]) < 0.2:
            continue
        out.append((r * d, l1, l2))
    return out
