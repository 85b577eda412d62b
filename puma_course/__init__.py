"""puma-course: the helper package behind the manipulator-kinematics course.

Import stays light: numpy only. sympy (``puma_course.symbolic``), matplotlib
(``puma_course.plotting``) and ipywidgets (``puma_course.widgets``) load only
when those modules are imported.
"""

from __future__ import annotations

from . import dh, porter, puma_ik, robots, three_step, trajectories, transforms
from .dh import DHChain, Link, mdh
from .robots import mk3, puma560
from .transforms import (
    axis_angle,
    homogeneous,
    rodrigues,
    rotx,
    roty,
    rotz,
)

__version__ = "0.1.0"

__all__ = [
    "DHChain",
    "Link",
    "axis_angle",
    "dh",
    "porter",
    "puma_ik",
    "robots",
    "three_step",
    "trajectories",
    "transforms",
    "homogeneous",
    "mdh",
    "mk3",
    "puma560",
    "rodrigues",
    "rotx",
    "roty",
    "rotz",
]
