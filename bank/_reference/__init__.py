"""The question bank's one window onto the kinematics layer: reference answers, hidden inputs, mechanisms.

Every call the bank makes into the course's kinematics (``rodrigues``, ``mdh``, ``DHChain``,
``Puma560``, ``MK3``, ``Porter``, ``ThreeStepArm``, ``trajectories``, ...) is made in this package,
so a change of the kinematics API touches these modules only; the exercise files name what they ask
for and import the module of their topic:

* :mod:`.chains`: rotations, link matrices and DH tables, the mechanisms of the frame-assignment
  questions (the RRP arm, the PUMA-560 on a pedestal, the MK3 on a rail), exercises 1 to 4;
* :mod:`.porter_chain`: Porter's chain, direct and inverse (exercises 5 to 7);
* :mod:`.motion`: the three-step procedure, PUMA-560 inverse kinematics, paths (exercises 8 to 10).

References run in the grader's process; their warnings (singular poses) are silenced. A modelling
question's reference returns a dict for its judge (:mod:`puma_course.grading.judge.judges`), holding the
reference robot's forward kinematics as a callable. The answer keys (package functions a question
forbids) are named in :mod:`puma_course_bank._keys`.
"""
