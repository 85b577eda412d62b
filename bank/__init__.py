"""The question bank: one module per exercise, each declaring its ``EXERCISE``; importing this registers them.

Each ``exNN_*.py`` holds only declarations (function names, points, public inputs, hidden-input
generators, references, judges, the mistakes it recognises, hints, the package names a student may
use). Every call into the kinematics layer goes through :mod:`._reference`; numbers that need numpy
alone are in :mod:`._formulas` and :mod:`._inputs`, the answer keys in :mod:`._keys`.

>>> from puma_course.grading.bank_loader import EXERCISES
>>> sorted(EXERCISES)[:2]
['ex01_rotations', 'ex02_dh_frames']
"""

from __future__ import annotations

from puma_course.grading.bank_loader import register

from . import (
    ex01_rotations,
    ex02_dh_frames,
    ex03_puma_fk,
    ex04_mk3_fk,
    ex05_porter_fk,
    ex06_porter_explicit,
    ex07_porter_geometric,
    ex08_three_step,
    ex09_puma_ik,
    ex10_trajectories,
)

MODULES = (
    ex01_rotations,
    ex02_dh_frames,
    ex03_puma_fk,
    ex04_mk3_fk,
    ex05_porter_fk,
    ex06_porter_explicit,
    ex07_porter_geometric,
    ex08_three_step,
    ex09_puma_ik,
    ex10_trajectories,
)

for _module in MODULES:
    register(_module.EXERCISE)
