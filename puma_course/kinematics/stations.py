"""Base, tool and station frames: the transform equation world = base · arm · tool (Craig §3.7).

An arm's ``fk(q)`` gives the pose of its last frame {N} (the wrist, the flange) in its base frame {B}.
A cell places the base in the world (or station) frame {W} by ``base`` = ^W T_B, and the tool's point
of interest {T} on the flange by ``tool`` = ^N T_T. Then

    ^W T_T = ^W T_B · ^B T_N(q) · ^N T_T                      (:func:`world_pose`)
    ^B T_N = (^W T_B)^-1 · ^W T_T · (^N T_T)^-1                (:func:`arm_target`)

the second is what the inverse kinematics must be given when a task names the tool's goal in the
world. ``None`` stands for the identity (no base offset, no tool).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._validate import as_transform
from ..transforms import inverse_transform

__all__ = ["world_pose", "arm_target"]


def _frame(T: Any, name: str) -> np.ndarray:
    return np.eye(4) if T is None else as_transform(T, name)


def world_pose(base: Any, arm_pose: Any, tool: Any = None) -> np.ndarray:
    """^W T_T = base · arm_pose · tool: the tool frame in the world, (4, 4) or (N, 4, 4) for N arm poses.

    >>> from puma_course.transforms import transl
    >>> world_pose(transl([1.0, 0.0, 0.5]), np.eye(4), transl([0.0, 0.0, 0.1]))[:3, 3]
    array([1. , 0. , 0.6])
    """
    B, Tl = _frame(base, "base"), _frame(tool, "tool")
    A = as_transform(arm_pose, "arm_pose", batch=True)
    return B @ A @ Tl


def arm_target(world_T: Any, base: Any = None, tool: Any = None) -> np.ndarray:
    """^B T_N = base⁻¹ · world_T · tool⁻¹: the pose the arm's last frame must reach, (4, 4) or (N, 4, 4).

    >>> from puma_course.transforms import transl
    >>> np.round(arm_target(transl([1.0, 0.0, 0.6]), transl([1.0, 0.0, 0.5]), transl([0.0, 0.0, 0.1]))[:3, 3], 12) + 0.0
    array([0., 0., 0.])
    """
    B, Tl = _frame(base, "base"), _frame(tool, "tool")
    W = as_transform(world_T, "world_T", batch=True)
    return inverse_transform(B) @ W @ inverse_transform(Tl)
