"""The few functions the closed forms need, for plain floats (one pose) or numpy arrays (a batch).

Each solver writes its formulas ONCE, as functions of an ``ops`` argument: the one-pose path
calls them with :data:`SCALAR` (Python floats and :mod:`math`: a few µs per pose), the batch
path with :data:`ARRAY` (numpy arrays broadcasting over poses and branches: one vectorised pass).
Only arithmetic operators and these functions appear in the formulas, so both paths compute the
same expressions in the same order, with the same rounding (``atan2`` and ``hypot`` are numpy's in both).

>>> SCALAR.where(True, 1.0, 2.0), ARRAY.where(np.array([True, False]), 1.0, 2.0).tolist()
(1.0, [1.0, 2.0])
"""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any

import numpy as np

__all__ = ["SCALAR", "ARRAY"]


def _where(cond: Any, a: Any, b: Any) -> Any:
    return a if cond else b


def _maximum(a: Any, b: Any) -> Any:
    return a if a > b else b


def _atan2(y: float, x: float) -> float:
    # numpy's arctan2 and hypot round differently from math's (77k and 6k of 1M random pairs differ in the
    # last bit here): the one-pose path calls numpy's on plain floats so that a threshold decided on the
    # result (a singular wrist, a reach limit) falls the same way in ``ik`` and ``ik_batch``
    return float(np.arctan2(y, x))


def _hypot(x: float, y: float) -> float:
    return float(np.hypot(x, y))


SCALAR = SimpleNamespace(
    sin=math.sin,
    cos=math.cos,
    atan2=_atan2,
    sqrt=math.sqrt,
    hypot=_hypot,
    where=_where,
    maximum=_maximum,
    abs=abs,
    any=bool,
    pi=math.pi,
)

ARRAY = SimpleNamespace(
    sin=np.sin,
    cos=np.cos,
    atan2=np.arctan2,
    sqrt=np.sqrt,
    hypot=np.hypot,
    where=np.where,
    maximum=np.maximum,
    abs=np.abs,
    any=np.any,
    pi=math.pi,
)
