"""puma-course: the helper package behind the manipulator-kinematics course.

Layers (each folder imports only the ones above it in this list):

* base: :mod:`~puma_course.transforms` (rotations, K(a, θ), transforms, the one ``wrap_angle``),
  :mod:`~puma_course.euler` (ZYZ and roll-pitch-yaw angles), input checks,
  :mod:`~puma_course.course` (finding the course folder);
* :mod:`~puma_course.kinematics`: every arm as a robot with the same API (``fk``, ``frames``,
  ``ik``, ``ik_batch``) and one inverse-kinematics result type;
* :mod:`~puma_course.symbolic` (sympy), :mod:`~puma_course.viz` (figures, widgets),
  :mod:`~puma_course.grading` (exercises); :mod:`~puma_course.cli` on top.

``import puma_course`` loads numpy only: sympy, matplotlib and ipywidgets load with the
sub-packages that need them.

>>> from puma_course import Puma560
>>> arm = Puma560()
>>> sol = arm.ik(arm.fk(arm.q("qn")))
>>> len(sol), sol.success
(8, True)
"""

from __future__ import annotations

from . import euler, kinematics, transforms
from ._version import __version__
from .euler import rotation_from_rpy, rotation_from_zyz, rpy_from_rotation, zyz_from_rotation
from .kinematics import (
    MK3,
    DHChain,
    IKBatch,
    IKSolutions,
    KinematicsWarning,
    Link,
    Porter,
    Puma560,
    Robot,
    SingularityWarning,
    ThreeStepArm,
    joint_distance,
    mdh,
)
from .transforms import (
    axis_angle,
    homogeneous,
    inverse_transform,
    rodrigues,
    rotx,
    roty,
    rotz,
    wrap_angle,
)

__all__ = [
    "MK3",
    "DHChain",
    "IKBatch",
    "IKSolutions",
    "KinematicsWarning",
    "Link",
    "Porter",
    "Puma560",
    "Robot",
    "SingularityWarning",
    "ThreeStepArm",
    "__version__",
    "axis_angle",
    "euler",
    "homogeneous",
    "inverse_transform",
    "joint_distance",
    "kinematics",
    "mdh",
    "rodrigues",
    "rotation_from_rpy",
    "rotation_from_zyz",
    "rotx",
    "roty",
    "rotz",
    "rpy_from_rotation",
    "transforms",
    "wrap_angle",
    "zyz_from_rotation",
]
