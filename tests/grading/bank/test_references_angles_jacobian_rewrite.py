"""The references of the questions issue 22 added (ex01 q6, ex02 q4, ex09 q1-q5) against independent truths.

X-Y-Z angles multiplied back with the package's rotations; det J against the factors of lecture 09 §9; the
lost direction against the geometry (along p stretched, horizontal on the shoulder cylinder); the standard
table's modified rewrite by the poses both chains reach; the controller's zero by the forward kinematics.
"""

from __future__ import annotations

import numpy as np

from puma_course.grading import EXERCISES
from puma_course.kinematics.puma560 import Puma560
from puma_course.kinematics.standard_dh import standard_dh
from puma_course.transforms import rotx, roty, rotz

EXERCISES["ex01_rotations"]  # loads the bank
import puma_course_bank._formulas as formulas  # noqa: E402
import puma_course_bank._reference.chains as chains  # noqa: E402
import puma_course_bank._reference.motion as motion  # noqa: E402

L = (0.4318, 0.0203, 0.15005, 0.4318)
ZERO = np.array([0.0, -np.pi / 2, -np.pi / 2, 0.0, 0.0, 0.0])


def test_xyz_angles_multiply_back_and_lie_in_range_also_at_the_lock():
    rng = np.random.default_rng(0)
    for _ in range(300):
        a, b, c = rng.uniform(-np.pi, np.pi), rng.uniform(-np.pi / 2, np.pi / 2), rng.uniform(-np.pi, np.pi)
        R = rotx(a) @ roty(b) @ rotz(c)
        x = formulas.xyz_angles(R)
        assert np.allclose(rotx(x[0]) @ roty(x[1]) @ rotz(x[2]), R, atol=1e-12) and abs(x[1]) <= np.pi / 2
    for sign in (1.0, -1.0):  # Rx(a) Ry(±π/2) Rz(c) = Rx(a ± c) Ry(±π/2): c = 0 returns a ± c
        Ry = np.array([[0.0, 0.0, sign], [0.0, 1.0, 0.0], [-sign, 0.0, 0.0]])
        R = rotx(0.4) @ Ry @ rotz(0.3)
        assert np.allclose(formulas.xyz_angles(np.round(R, 15)), [0.4 + sign * 0.3, sign * np.pi / 2, 0.0])


def test_det_j_is_the_product_of_lecture_09_s_factors_at_the_controller_s_zero():
    rng = np.random.default_rng(1)
    a2, a3, d3, d4 = L
    for q in rng.uniform(-np.pi, np.pi, (100, 6)):
        t = q + ZERO
        X = a2 * np.cos(t[1]) + a3 * np.cos(t[1] + t[2]) - d4 * np.sin(t[1] + t[2])
        factors = -a2 * (a3 * np.sin(t[2]) + d4 * np.cos(t[2])) * X * np.sin(t[4])
        assert abs(motion.puma_det_j(q, *L) - factors) < 1e-12


def test_the_lost_direction_is_along_p_stretched_and_horizontal_on_the_shoulder_cylinder():
    for k, (q, *lengths) in enumerate(motion.puma_singular_cases(np.random.default_rng(2), 20)):
        u = motion.puma_lost_direction(q, *lengths)
        p = Puma560(*lengths).fk(q + ZERO)[:3, 3]
        truth = p / np.linalg.norm(p) if k % 2 == 0 else np.r_[p[:2], 0.0] / np.hypot(p[0], p[1])
        assert np.allclose(u, truth, atol=1e-8), (k, u, truth)
        # and no joint rate of joints 1-3 moves the wrist centre along it (central differences)
        for j in range(3):
            dq = np.zeros(6)
            dq[j] = 1e-6
            dp = Puma560(*lengths).fk(q + ZERO + dq)[:3, 3] - Puma560(*lengths).fk(q + ZERO - dq)[:3, 3]
            assert abs(u @ dp) / 2e-6 < 1e-5


def test_the_modified_rewrite_of_a_standard_table_reaches_the_standard_chain_s_poses():
    rng = np.random.default_rng(3)
    for (table,) in chains.standard_tables(rng, 10):
        mod = formulas.modified_from_standard(table)
        for q in rng.uniform(-1.0, 1.0, (3, len(table))):
            T = np.eye(4)
            for (alpha, a, theta, d, sigma), qi in zip(table, q, strict=True):
                T = T @ (standard_dh(theta, d + qi, a, alpha) if sigma else standard_dh(theta + qi, d, a, alpha))
            assert np.allclose(chains.table_fk(mod, q), T)


def test_the_controller_s_zero_is_the_arm_straight_up():
    # by hand from lecture 09 §1 at θ2 = -π/2, θ3 = -π/2: X = -a3, p = (c1 X - d3 s1, s1 X + d3 c1, a2 + d4)
    p = motion.upright_chain(*L).fk(np.zeros(6))[:3, 3]
    assert np.allclose(p, [-L[1], L[2], L[0] + L[3]])
    assert np.allclose(motion.upright_chain(*L).fk(np.zeros(6)), motion.upright_fk(np.zeros(6), *L))
