"""Helpers shared by the reference modules: quiet calls, elementary transforms, the judges' dicts."""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any

import numpy as np

from puma_course import transforms

from .._formulas import case_rng, hidden_q


def _quiet(fn: Callable[..., Any], *args: Any, **kw: Any) -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args, **kw)


def tz(d: float) -> np.ndarray:
    """Trans(Z, d) as a 4x4 transform."""
    return transforms.transz(d)


def pose(R: Any, p: Any) -> np.ndarray:
    """The 4x4 transform [[R, p], [0, 1]]."""
    return transforms.homogeneous(R, p)


def _table_expected(
    fk: Callable[[np.ndarray], np.ndarray],
    revolute: Any,
    scale: float,
    *args: Any,
    stroke: tuple[float, float] = (0.2, 1.5),
) -> dict[str, Any]:
    return {
        "fk": fk,
        "Q": hidden_q(case_rng(*args), revolute, stroke=stroke),
        "revolute": np.asarray(revolute),
        "scale": scale,
    }


def _set_expected(
    robot: Any, T: Any, fk: Callable[[np.ndarray], np.ndarray] | None = None, **extra: Any
) -> dict[str, Any]:
    sol = _quiet(robot.ik, T)
    return {
        "T": np.asarray(T, dtype=float),
        "solutions": np.asarray(sol.q),
        "labels": sol.labels,
        "fk": fk or robot.fk,
        "revolute": robot.revolute,
        "scale": 1.0 + float(np.max(np.abs(T[:3, 3]))),
        **extra,
    }
