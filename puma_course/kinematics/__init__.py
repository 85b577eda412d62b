"""Kinematics layer: every arm of the course as a robot with the same API, and one IK result type."""

from __future__ import annotations

from .dh import DHChain, Link, mdh
from .ik import IKBatch, IKSolutions, KinematicsWarning, SingularityWarning, joint_distance
from .mk3 import MK3
from .porter import Porter
from .puma560 import Puma560
from .robot import MountedFk, Robot
from .three_step import ThreeStepArm

__all__ = [
    "DHChain",
    "IKBatch",
    "IKSolutions",
    "KinematicsWarning",
    "Link",
    "MK3",
    "MountedFk",
    "Porter",
    "Puma560",
    "Robot",
    "SingularityWarning",
    "ThreeStepArm",
    "joint_distance",
    "mdh",
]
