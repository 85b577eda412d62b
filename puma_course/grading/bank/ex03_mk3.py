"""Exercise 3 (``solutions/ex03_mk3.ipynb``): forward kinematics of the Motoman MK3 (mm)."""

from __future__ import annotations

import numpy as np

from ..model import Exercise, Question
from . import _reference as ref
from ._inputs import angles

EXERCISE = Exercise(
    "ex03_mk3",
    "Forward kinematics of the Motoman MK3",
    (
        Question(
            "q1",
            "mk3_fk",
            3,
            "MK3 forward kinematics ^0T_5 (mm)",
            public=((np.zeros(5),), (np.array([0.0, np.pi / 2, -np.pi / 2, 0.0, 0.0]),)),
            hidden=lambda rng: angles(rng, 5, 5),
            reference=ref.mk3_fk,
            forbidden=ref.KEY_MK3,
            hint="The table: d1 = 360, a1 = 135, a2 = 250, a3 = 215, d5 = 100 mm; α1 = α4 = 90°.",
        ),
        Question(
            "q2",
            "mk3_position",
            3,
            "tool position from the closed form",
            public=((np.zeros(5),), (np.array([0.5, 0.3, -0.4, 0.2, 0.1]),)),
            hidden=lambda rng: angles(rng, 5, 5),
            reference=ref.mk3_position,
            forbidden=ref.KEY_MK3,
            hint="The horizontal reach is a1 + a2 C2 + a3 C23 + d5 S234; the height starts at d1.",
        ),
        Question(
            "q3",
            "mk3_tool_axis",
            2,
            "direction of the tool axis z5",
            public=((np.zeros(5),),),
            hidden=lambda rng: angles(rng, 4, 5),
            reference=ref.mk3_tool_axis,
            forbidden=ref.KEY_MK3,
            hint="It is the third column of the rotation part; only θ1 and θ2 + θ3 + θ4 matter.",
        ),
    ),
    allowed=(),  # the self-check only: the MK3 is the answer
)
