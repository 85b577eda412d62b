"""Plain helpers shared by the test modules (fixtures live in conftest.py).

Import as ``from tests.support import ROOT, random_q``.
"""

from __future__ import annotations

import base64
import re
import struct
from pathlib import Path

import numpy as np

#: The repository root (the course folder).
ROOT = Path(__file__).resolve().parents[1]


def random_q(n: int, seed: int, N: int | None = None, low: float = -np.pi, high: float = np.pi) -> np.ndarray:
    """Joint angles drawn uniformly from [low, high): shape (n,) or (N, n), reproducible by ``seed``."""
    rng = np.random.default_rng(seed)
    return rng.uniform(low, high, n if N is None else (N, n))


def jshtml_png_sizes(html: str) -> list[tuple[int, int]]:
    """(width, height) in pixels of every PNG frame embedded in an animation's ``to_jshtml()``, read from
    each PNG header (IHDR), so a test can check the figure's dpi was kept."""
    frames = re.findall(r"data:image/png;base64,((?:[A-Za-z0-9+/=]|\\\n)+)", html)
    sizes = []
    for b64 in frames:
        png = base64.b64decode(b64.replace("\\\n", ""))
        sizes.append(struct.unpack(">II", png[16:24]))
    return sizes


def assert_no_overlap(boxes: list, pad: float = 0.0) -> None:
    """No two of the matplotlib Bboxes overlap (each grown by ``pad`` pixels)."""
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not a.padded(pad).overlaps(b.padded(pad)), f"{a} overlaps {b}"
