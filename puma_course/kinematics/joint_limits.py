"""Published joint limits: the PUMA-560's ranges with their source, moved into this course's joint angles.

A table of joint limits means something only with the zeros and senses of the model it was written for, so
the published numbers are kept as published (:data:`PUBLISHED_QLIM_DEG`, in the source model's angles), the
offset between the two models is stated (:data:`FROM_CORKE_DEG`, checked in the tests against an independent
product of the source's DH table), and :data:`JOINT_LIMITS` is what the course's
:class:`~puma_course.kinematics.puma560.Puma560` uses (``arm.joint_limits``, for
:meth:`~puma_course.kinematics.ik.IKSolutions.within_limits`). No source the course has gives the Motoman
MK3's limits, so it has none.

>>> np.degrees(JOINT_LIMITS[1]).tolist()  # θ2: the arm straight up (-90°) is the middle of the range
[-225.0, 45.0]
"""

from __future__ import annotations

import numpy as np

__all__ = ["PUBLISHED_QLIM_DEG", "FROM_CORKE_DEG", "JOINT_LIMITS"]

#: The PUMA-560's joint ranges as published, in degrees (lower, upper) for joints 1 to 6, in the joint
#: coordinates of the model they are published with: P. Corke's Robotics Toolbox, ``mdl_puma560`` (MATLAB,
#: standard DH, ``qlim``), taken there from Wang & Chen, "A combined optimization method for solving the
#: inverse kinematics problem of mechanical manipulators", IEEE Trans. Robotics and Automation 7(4), 1991,
#: p. 489. Robotics Toolbox for Python's ``models.DH.Puma560`` uses the same set as its ``qlim`` in release 1.5.0
#: (releases 1.0 to 1.3 kept these numbers as comments beside symmetric limits of their own for joints 2 to 4).
#: The ranges are 320°, 270°, 270°, 280°, 200° and 532°.
PUBLISHED_QLIM_DEG: tuple[tuple[float, float], ...] = (
    (-160.0, 160.0), (-45.0, 225.0), (-225.0, 45.0), (-110.0, 170.0), (-100.0, 100.0), (-266.0, 266.0),
)  # fmt: skip
#: This model's joint angles minus Corke's for the same arm (degrees). Both models put θ1 = 0 where the
#: controller does (this model's base frame is Corke's turned by 180° about the base axis, as each names
#: its x0 after its own θ1 = 0); Corke's upper arm points along x1 at θ2 = 0 and this model's the other
#: way, so θ2 differs by 180° (written -180°: the range then holds this model's zero); θ3 to θ6 agree.
#: The tests check it against an independent standard-DH product of Corke's table.
FROM_CORKE_DEG: tuple[float, ...] = (0.0, -180.0, 0.0, 0.0, 0.0, 0.0)


def _joint_limits() -> np.ndarray:
    lim = np.radians(np.array(PUBLISHED_QLIM_DEG) + np.array(FROM_CORKE_DEG)[:, None])
    lim.setflags(write=False)
    return lim


#: The published ranges in this model's joint angles (radians, (6, 2)): θ1 ±160°, θ2 and θ3 from -225°
#: to 45° (the arm straight up at -90° is the middle of both), θ4 -110° to 170°, θ5 ±100°, θ6 ±266°.
JOINT_LIMITS: np.ndarray = _joint_limits()
