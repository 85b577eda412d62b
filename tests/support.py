"""Plain helpers shared by the test modules (fixtures live in conftest.py).

Import as ``from tests.support import ROOT, random_q``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: The repository root (the course folder).
ROOT = Path(__file__).resolve().parents[1]


def random_q(n: int, seed: int, N: int | None = None, low: float = -np.pi, high: float = np.pi) -> np.ndarray:
    """Joint angles drawn uniformly from [low, high): shape (n,) or (N, n), reproducible by ``seed``."""
    rng = np.random.default_rng(seed)
    return rng.uniform(low, high, n if N is None else (N, n))
