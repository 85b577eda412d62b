"""Judging modelling questions for what is right, not against one answer.

Each factory returns a ``judge(got, expected, args) -> Verdict`` for :attr:`Question.judge_with
<puma_course.grading.spec.Question.judge_with>`. ``expected`` is what the question's reference computed
in the grader's process: a dict holding the hidden joint values, the reference poses and the
reference robot's forward kinematics as a callable (``"fk"``), so a judge can test a student's answer
by what it *does*:

* :func:`table_judge`: a DH table is right when its chain reaches the reference poses over hidden
  random joint values (any valid frame assignment passes); otherwise it says whether the table is
  standard DH, right only at q = 0, has a joint turning the wrong way, the wrong joint type, degrees,
  or is off by a constant base or tool transform;
* :func:`solution_set_judge`: every row reaches the pose, no row twice, no solution missing (named by
  its branch), in any order unless the question asks for one;
* :func:`nearest_judge`: a solution, and the nearest one in wrapped joint distance;
* :func:`path_judge`: a joint path reaches every pose of a Cartesian path, starts at the given
  configuration and never jumps (largest step against the smoothest path's);
* :func:`rotation_judge`: angles judged by the rotation they produce (any equivalent triple passes);
* :func:`stroke_judge`: Porter's parallel-planes representative (front plane, minimal stroke).

The judges need no kinematics of their own: the bank passes in what they evaluate (the chain of a
student's table, the robot's forward kinematics) from the course's bank (``bank/_reference/``).
"""

from __future__ import annotations

from .poses import pose_errors, pose_ok
from .solutions import nearest_judge, path_judge, rotation_judge, solution_set_judge, stroke_judge
from .tables import table_judge

__all__ = [
    "pose_errors",
    "pose_ok",
    "table_judge",
    "solution_set_judge",
    "nearest_judge",
    "path_judge",
    "rotation_judge",
    "stroke_judge",
]
