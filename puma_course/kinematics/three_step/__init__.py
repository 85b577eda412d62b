"""The three-step wrist-frame inverse kinematics of a 6R PUMA with a spherical wrist (source "2.3 Kinematics").

* :class:`ThreeStepArm`: the arm as a robot (fk, frames, ik with all eight branches, ik_batch);
* :meth:`ThreeStepArm.three_step`: the source's three-step procedure for one target, with every
  intermediate quantity (:class:`ThreeStepSolution`), and :func:`motion` to animate it;
* :func:`motion_joints`: the motion as joint vectors of the six-joint arm, the wrist step on the geodesic
  (the source's) or jointly interpolated.

>>> sol = ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]))
>>> round(float(np.degrees(sol.theta0)), 6), round(float(np.degrees(sol.theta1)), 4)
(45.0, 95.9034)
>>> np.allclose(ThreeStepArm(1.5, 1.0).wrist_position(sol.theta0, sol.theta1, sol.theta2), [0.5, 0.5, 2.0])
True
"""

from __future__ import annotations

import numpy as np  # noqa: F401  (the doctest above uses it)

from .arm import ThreeStepArm
from .geometry import arm_axis
from .procedure import ArmState, Motion, ThreeStepSolution, ThreeStepWarning, as_state, motion
from .wrist_paths import WRIST_MOTIONS, forearm_frames, motion_joints, wrist_goal

__all__ = ["ThreeStepArm", "ArmState", "Motion", "ThreeStepSolution", "ThreeStepWarning", "arm_axis", "as_state",
           "motion", "motion_joints", "wrist_goal", "forearm_frames", "WRIST_MOTIONS"]  # fmt: skip
