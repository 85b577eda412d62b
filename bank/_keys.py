"""The answer keys of the question bank: package functions (``"module:attr"``) that answer a question.

Calling one of a question's keys while that question is graded fails the case (the worker's
tripwires, :mod:`puma_course.grading.run.worker`); the self-check flags it the same way. Names only,
no imports: a test checks that every key still names a function of the package.
"""

from __future__ import annotations

_T, _DH, _P560 = "puma_course.transforms", "puma_course.kinematics.dh", "puma_course.kinematics.puma560"
_IK, _PORTER, _TS = "puma_course.kinematics.ik", "puma_course.kinematics.porter", "puma_course.kinematics.three_step"
_BANK = "puma_course_bank._reference.chains"
KEY_ROT = tuple(f"{_T}:{name}" for name in ("rotx", "roty", "rotz", "trotx", "troty", "trotz"))
KEY_RODRIGUES = (f"{_T}:rodrigues", f"{_T}:trot")
KEY_AXIS_ANGLE = (f"{_T}:axis_angle",)
KEY_EULER = tuple(f"puma_course.euler:{name}" for name in ("zyz_from_rotation", "rpy_from_rotation"))
KEY_INVERSE = (f"{_T}:inverse_transform",)
#: numpy's general inverses and solvers: a question that asks for a rigid inverse (Rᵀ, -Rᵀp) or for motions undone
#: forbids them all, since ``solve(T_a, T_b)`` or ``pinv(T)`` is ``inv`` by another name (the tripwire catches the
#: call; a name outside the package is never left out of the student side: ``Exercise.answer_keys`` keeps to the
#: package). Their compiled routes too: the ufuncs of ``numpy.linalg._umath_linalg`` that invert or solve, and
#: ``lapack_lite``'s least-squares solvers (its QR routines, like ``svd``, ``eig`` and ``det``, are decompositions,
#: not watched: an inverse built from one by hand is judged by the question's words)
KEY_GENERAL_INVERSE = (
    *(f"numpy.linalg:{name}" for name in ("inv", "pinv", "solve", "lstsq", "tensorinv", "tensorsolve")),
    *(f"numpy.linalg._umath_linalg:{name}" for name in ("inv", "solve", "solve1", "lstsq")),
    *(f"numpy.linalg.lapack_lite:{name}" for name in ("dgelsd", "zgelsd")),
)
KEY_MDH = (f"{_DH}:mdh", f"{_DH}:DHChain.link_matrices", f"{_BANK}:mdh")
KEY_LINK_PARAMETERS = (
    "puma_course_bank._formulas:link_parameters",
    "puma_course_bank._formulas:link_parameters_between",
    f"{_T}:inverse_transform",
)
KEY_MDH_INVERSE = (*KEY_MDH, f"{_T}:inverse_transform", f"{_BANK}:mdh_inverse")
KEY_CHAIN = (
    f"{_DH}:DHChain.fk",
    f"{_DH}:DHChain.frames",
    f"{_DH}:DHChain.link_matrices",
    f"{_DH}:_walk",
    f"{_BANK}:table_fk",
    f"{_BANK}:table_chain",
    f"{_P560}:Puma560.fk",
    f"{_P560}:_fk_entries",
)
KEY_TABLES = (
    f"{_DH}:DHChain.table",
    f"{_DH}:DHChain.parameters",
    f"{_P560}:Puma560.__init__",
    "puma_course.kinematics.mk3:MK3.__init__",
    f"{_BANK}:rrp_fk",
    f"{_BANK}:puma_pedestal_fk",
    f"{_BANK}:mk3_rail_fk",
    f"{_BANK}:mk3_table",
    "puma_course_bank._reference.porter_chain:porter_tool_fk",
)
KEY_PORTER_FK = (
    f"{_PORTER}:Porter.fk",
    f"{_PORTER}:Porter.frames",
    "puma_course.kinematics.robot:Robot.points",
    f"{_PORTER}.fk:fk_entries",
    f"{_PORTER}.fk:frames_array",
)
KEY_PORTER_IK = (
    f"{_PORTER}:Porter.ik",
    f"{_PORTER}:Porter.ik_batch",
    f"{_PORTER}.explicit:branch",
    f"{_PORTER}.explicit:pose_terms",
    f"{_PORTER}.geometric:construct",
    f"{_PORTER}.geometric:angle",
)
KEY_THREE_STEP = (
    f"{_TS}.arm:ThreeStepArm.three_step",
    f"{_TS}.arm:ThreeStepArm.ik",
    f"{_TS}.procedure:solve_three_steps",
    f"{_TS}.procedure:motion",
    f"{_TS}.geometry:arm_axis",
    f"{_TS}.geometry:triangle",
    f"{_TS}.geometry:base_angle",
    "puma_course.euler:zyz_from_rotation",
)
KEY_PUMA_IK = (
    f"{_P560}:Puma560.ik",
    f"{_P560}:Puma560.ik_batch",
    f"{_P560}:_arm",
    f"{_P560}:_wrist",
    f"{_P560}:_reach",
)
KEY_JACOBIAN = (
    "puma_course.kinematics.dh:DHChain.jacobian",
    "puma_course.kinematics.jacobian:geometric_jacobian",
    "puma_course.kinematics.jacobian:jacobian_from_axes",
    "puma_course.symbolic.jacobian:puma560_jacobian_determinant",
)
KEY_NEAREST = (
    f"{_IK}:IKSolutions.nearest",
    f"{_IK}:IKSolutions.sorted_by",
    f"{_IK}:IKSolutions._sorted",
    f"{_IK}:nearest_index",
    f"{_IK}:joint_distance",
    "puma_course.kinematics.trajectories:follow",
    "puma_course.kinematics.trajectories:naive",
)
