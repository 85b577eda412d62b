"""The question bank: one module per exercise, each declaring its ``EXERCISE``; importing this registers them.

Each ``exNN_*.py`` holds only declarations (function names, points, public inputs, hidden-input
generators, references, hints). Every call into the kinematics layer goes through
:mod:`._reference`, so a change of the kinematics API touches that one file.

>>> from puma_course.grading.model import EXERCISES
>>> sorted(EXERCISES)[:2]
['ex01_rotations', 'ex02_dh_puma']
"""

from __future__ import annotations

from ..model import register
from . import ex01_rotations, ex02_dh_puma, ex03_mk3, ex04_porter_fk, ex05_porter_ik, ex06_three_step

MODULES = (ex01_rotations, ex02_dh_puma, ex03_mk3, ex04_porter_fk, ex05_porter_ik, ex06_three_step)

for _module in MODULES:
    register(_module.EXERCISE)
