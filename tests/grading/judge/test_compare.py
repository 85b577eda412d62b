"""puma_course.grading.judge.compare: each comparison accepts what is right and says what is wrong."""

from __future__ import annotations

import numpy as np

from puma_course.grading.judge.compare import compare_angles, compare_angles_at, compare_close, compare_solution_set


def test_compare_close_accepts_equal_and_reports_differences():
    ref = np.array([[1.0, 2.0], [3.0, 4.0]])
    assert compare_close(ref.tolist(), ref) is None
    assert compare_close(ref + 1e-9, ref) is None
    assert "differ" in compare_close(ref + 1e-3, ref)
    assert "shape" in compare_close(ref.ravel()[:3], ref)
    assert compare_close("a string", ref) == "did not return numbers"
    assert "NaN" in compare_close([[np.nan, 2], [3, 4]], ref)


def test_compare_close_tolerance_scales_with_the_reference():
    # millimetre-sized values (MK3): an error of 1e-5 mm on 600 mm is a rounding error, not a mistake
    ref = np.array([600.0, 0.0, 260.0])
    assert compare_close(ref + 1e-5, ref) is None
    assert compare_close(ref + 1e-2, ref) is not None


def test_compare_close_accepts_a_squeezable_shape():
    assert compare_close([[0.5]], np.array(0.5)) is None
    assert compare_close(0.5, np.array([0.5])) is None


def test_compare_angles_is_modulo_two_pi():
    assert compare_angles([0.1 - 2 * np.pi, np.pi], np.array([0.1, -np.pi])) is None
    assert compare_angles([0.2], np.array([0.1])) is not None


def test_compare_solution_set_ignores_order_and_wraps_only_angle_columns():
    cmp = compare_solution_set([0, 2])
    ref = np.array([[0.1, 1.0, 0.2], [3.0, 2.0, 6.0]])
    assert cmp(ref[::-1] + [[2 * np.pi, 0, -2 * np.pi], [0, 0, 0]], ref) is None
    # column 1 is a length: adding 2π there is wrong
    assert cmp(ref + [[0, 2 * np.pi, 0], [0, 0, 0]], ref) is not None
    assert "misses" in cmp(ref[:1], ref)
    assert "not a solution" in cmp(np.vstack([ref, [[1.0, 1.0, 1.0]]]), ref)
    assert "shape" in cmp(ref.ravel(), ref)


def test_compare_solution_set_refuses_a_row_listed_twice():
    cmp = compare_solution_set([0])
    ref = np.array([[0.1, 1.0], [3.0, 2.0]])
    assert cmp(np.vstack([ref, ref[:1]]), ref) == "returned 3 rows for the 2 expected"


def test_compare_angles_at_wraps_only_the_angle_entries():
    cmp = compare_angles_at([0, 2])
    ref = np.array([0.5, 0.2, -3.0, 0.1])
    assert cmp(ref + [2 * np.pi, 0, -2 * np.pi, 0], ref) is None
    assert "differ" in cmp(ref + [0, 2 * np.pi, 0, 0], ref)  # a length is not an angle
    assert "shape" in cmp(ref[:3], ref)
