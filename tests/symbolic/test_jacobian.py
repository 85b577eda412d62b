"""The PUMA-560 Jacobian determinant derived with sympy, against the numeric Jacobian and the IK's singularities."""

from __future__ import annotations

import warnings

import numpy as np
import sympy as sp

from puma_course.kinematics import Puma560
from puma_course.symbolic import jacobian as J
from puma_course.symbolic.notation import PUMA560_LENGTHS, theta_symbols

ARM = Puma560()
LENGTHS = dict(zip(PUMA560_LENGTHS, (0.4318, 0.0203, 0.15005, 0.4318), strict=True))


def _det(q):
    return float(J.puma560_jacobian_determinant().subs(LENGTHS).subs(dict(zip(theta_symbols(6), q, strict=True))))


def test_the_determinant_factors_into_the_three_singularities():
    d = J.puma560_jacobian_determinant()
    f = J.SINGULARITY_FACTORS
    assert sp.simplify(d + PUMA560_LENGTHS[0] * f["elbow"] * f["shoulder"] * f["wrist"]) == 0
    assert J.puma560_wrist_axes_determinant() == -sp.sin(theta_symbols(6)[4])


def test_the_sympy_determinant_equals_the_numeric_jacobian():
    """Second, independent computation: det of DHChain.jacobian (cross products of frames) at random q."""
    rng = np.random.default_rng(7)
    for q in rng.uniform(-np.pi, np.pi, (15, 6)):
        assert np.isclose(np.linalg.det(ARM.jacobian(q)), _det(q), atol=1e-10)


def test_each_factor_vanishes_where_the_ik_flags_its_singularity():
    a2, a3, d4 = 0.4318, 0.0203, 0.4318
    t3 = np.arctan2(-d4, a3)  # elbow factor a3 s3 + d4 c3 = 0
    vx, vy = a2 + a3 * np.cos(0.4) - d4 * np.sin(0.4), a3 * np.sin(0.4) + d4 * np.cos(0.4)
    cases = {
        "elbow": np.array([0.5, -0.3, t3, 0.2, 1.0, 0.1]),
        "shoulder": np.array([0.2, np.arctan2(vx, vy), 0.4, 0.5, 0.7, -0.3]),  # the reach X is 0
        "wrist": np.array([0.3, -0.6, 0.2, 0.9, 0.0, 0.4]),
    }
    for key, q in cases.items():
        value = float(J.SINGULARITY_FACTORS[key].subs(LENGTHS).subs(dict(zip(theta_symbols(6), q, strict=True))))
        assert abs(value) < 1e-12
        assert abs(np.linalg.det(ARM.jacobian(q))) < 1e-12
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            sol = ARM.ik(ARM.fk(q), near=q)
        assert key in sol.flags[0], (key, sol.flags[0])
        assert caught
