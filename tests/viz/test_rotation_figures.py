"""Lecture 01's figures (puma_course.viz.rotation_figures): what is drawn is the geometry, checked independently.

The truths here do not come from the module: matrices worked out by hand, Euler turns rebuilt as
turns about the *current* axes written in the scene (Rodrigues about the moved axis, multiplied
on the left), and the gimbal-lock gain measured by finite differences of zyz_from_rotation.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

from puma_course import rodrigues, rotation_from_rpy, rotation_from_zyz, wrap_angle, zyz_from_rotation
from puma_course.transforms import homogeneous, rotx, rotz
from puma_course.viz import rotation_figures as RF

EX, EY, EZ = np.eye(3)


def _triad(ax) -> np.ndarray:
    """The drawn triad of a frame axes: its three lines' far ends, as columns (x, y, z)."""
    return np.stack([np.array(line.get_data_3d())[:, 1] for line in ax.lines[:3]], axis=1)


def _turn_line(ax) -> np.ndarray:
    """The unit direction of the dashed turn axis drawn in ``ax`` (checked to pass through the origin)."""
    (dashed,) = [line for line in ax.lines if line.get_linestyle() == "--"]
    a, b = np.array(dashed.get_data_3d()).T
    np.testing.assert_allclose((a + b) / 2, 0.0, atol=1e-12)
    return (b - a) / np.linalg.norm(b - a)


def _parallel(u, v) -> bool:
    u, v = np.asarray(u, float), np.asarray(v, float)
    return bool(np.linalg.norm(np.cross(u, v)) < 1e-9 and np.linalg.norm(u) > 0)


def test_triad_lines_are_the_columns_and_tips_are_named():
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    arts = RF.draw_triad(ax, rotz(np.pi / 2), turn_axis=[0, 0, 2.0])
    # by hand: Rz(90°) sends x to y, y to -x, z stays
    np.testing.assert_allclose(_triad(ax), [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-12)
    tips = [t for t in arts if hasattr(t, "get_position_3d")]
    assert [t.get_text() for t in tips] == ["x", "y", "z"]
    np.testing.assert_allclose(np.array(tips[0].get_position_3d()) / np.linalg.norm(tips[0].get_position_3d()),
                               [0, 1, 0], atol=1e-12)  # fmt: skip
    assert _parallel(_turn_line(ax), EZ)
    assert ax.get_xticks().size == 0 and ax.get_xlabel() == "scene x"
    # a transform is drawn by its rotation; equal limits hold the unit ball
    RF.draw_triad(ax, homogeneous(rotx(0.3), [5.0, 0, 0]))
    lims = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()])
    np.testing.assert_allclose(lims[:, 1] - lims[:, 0], lims[0, 1] - lims[0, 0])
    assert lims[0, 1] > 1.0


def test_triad_refuses_what_is_not_a_rotation_or_an_axis():
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    with pytest.raises(ValueError, match="rotation"):
        RF.draw_triad(ax, np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="turn_axis"):
        RF.draw_triad(ax, np.eye(3), turn_axis=[0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="length"):
        RF.draw_triad(ax, np.eye(3), length=-1.0)


def test_frame_sequence_grid_titles_and_checks():
    fig, axes = RF.plot_frame_sequence([np.eye(3)] * 5, list("abcde"), ncols=3, row_titles=["one", "two"])
    assert axes.shape == (2, 3)
    assert [ax.get_title() for ax in axes.flat[:5]] == list("abcde")
    assert not axes[1, 2].axison  # the sixth place is left empty
    assert axes[0, 0].texts[-1].get_text() == "one"
    with pytest.raises(ValueError, match="titles"):
        RF.plot_frame_sequence([np.eye(3)] * 2, ["a"])
    with pytest.raises(ValueError, match="turn_axes"):
        RF.plot_frame_sequence([np.eye(3)] * 2, ["a", "b"], turn_axes=[None])
    with pytest.raises(ValueError, match="row_titles"):
        RF.plot_frame_sequence([np.eye(3)] * 2, ["a", "b"], row_titles=["x", "y"])
    with pytest.raises(ValueError, match="rotations"):
        RF.plot_frame_sequence([], [])


def test_fixed_versus_moving_by_hand():
    """A = Rz(90°), B = Rx(90°): A B and B A worked out by hand, and the axis B turns about in each case."""
    fig, axes = RF.plot_fixed_vs_moving(rotz(np.pi / 2), rotx(np.pi / 2))
    AB = np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]])  # x -> y, y -> z, z -> x
    BA = np.array([[0, -1, 0], [0, 0, -1], [1, 0, 0]])  # x -> z, y -> -x, z -> -y
    np.testing.assert_allclose(_triad(axes[0, 2]), AB, atol=1e-12)
    np.testing.assert_allclose(_triad(axes[1, 2]), BA, atol=1e-12)
    # moving axes: B turns about the x axis A has carried onto the scene's y; fixed axes: about the scene's x
    assert _parallel(_turn_line(axes[0, 2]), EY)
    assert _parallel(_turn_line(axes[1, 2]), EX)
    assert _parallel(_turn_line(axes[0, 1]), EZ) and _parallel(_turn_line(axes[1, 1]), EZ)
    assert axes[0, 2].get_title() == r"after $B$: $A\,B$" and axes[1, 2].get_title() == r"after $B$: $B\,A$"


def _turns_about_current_axes(a, b, c):
    """ZYZ rebuilt without the module: each turn about the frame's *current* axis, written in the scene."""
    R1 = rodrigues(EZ, a)
    R2 = rodrigues(R1[:, 1], b) @ R1
    R3 = rodrigues(R2[:, 2], c) @ R2
    return [np.eye(3), R1, R2, R3], [EZ, R1[:, 1], R2[:, 2]]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_zyz_steps_are_turns_about_the_moving_axes(seed):
    a, b, c = np.random.default_rng(seed).uniform(-np.pi, np.pi, 3)
    fig, axes = RF.plot_euler_steps([a, b, c], "zyz")
    frames, turn_axes = _turns_about_current_axes(a, b, c)
    for k in range(4):
        np.testing.assert_allclose(_triad(axes[0, k]), frames[k], atol=1e-12)
    for k in range(3):
        assert _parallel(_turn_line(axes[0, k + 1]), turn_axes[k])
    np.testing.assert_allclose(frames[3], rotation_from_zyz(a, b, c), atol=1e-12)
    assert "29°" in RF.plot_euler_steps([0.5, 0.7, 0.3])[1][0, 1].get_title()  # φ = 0.5 rad shown in degrees


@pytest.mark.parametrize("seed", [3, 4])
def test_rpy_steps_are_turns_about_the_fixed_axes(seed):
    roll, pitch, yaw = np.random.default_rng(seed).uniform(-np.pi, np.pi, 3)
    fig, axes = RF.plot_euler_steps([roll, pitch, yaw], "rpy", elev=30, azim=-15)
    expected = [np.eye(3)]
    for axis, angle in zip((EX, EY, EZ), (roll, pitch, yaw), strict=True):
        expected.append(rodrigues(axis, angle) @ expected[-1])  # a turn about a fixed axis multiplies on the left
    for k in range(4):
        np.testing.assert_allclose(_triad(axes[0, k]), expected[k], atol=1e-12)
    for k, axis in enumerate((EX, EY, EZ)):
        assert _parallel(_turn_line(axes[0, k + 1]), axis)
    np.testing.assert_allclose(expected[3], rotation_from_rpy(roll, pitch, yaw), atol=1e-12)
    assert (axes[0, 0].elev, axes[0, 0].azim) == (30, -15)


def test_euler_steps_refuse_unknown_conventions_and_bad_angles():
    with pytest.raises(ValueError, match="convention"):
        RF.plot_euler_steps([0.1, 0.2, 0.3], "xyz")
    with pytest.raises(ValueError, match="angles"):
        RF.plot_euler_steps([0.1, 0.2])
    with pytest.raises(ValueError, match="angles"):
        RF.plot_euler_steps([0.1, np.nan, 0.3])


def test_angle_sweep_is_in_degrees_and_broken_only_where_an_angle_wraps():
    fig, ax = plt.subplots()
    x = np.linspace(0.0, 1.0, 50)
    turning = wrap_angle(np.linspace(0.0, 3.0 * np.pi, 50))  # wraps once, at 180°
    smooth = np.linspace(-np.pi / 2, np.pi / 2, 50)
    wrapped_line, smooth_line = RF.draw_angle_sweep(ax, x, np.c_[turning, smooth], ["a", "b"], xlabel="s [1]")
    y = wrapped_line.get_ydata()
    assert np.isnan(y).sum() == 1
    finite = y[~np.isnan(y)]
    np.testing.assert_allclose(finite, np.degrees(turning))
    pieces = np.split(y, np.flatnonzero(np.isnan(y)))
    assert all(np.all(np.abs(np.diff(p[~np.isnan(p)])) < 180.0) for p in pieces)
    assert not np.isnan(smooth_line.get_ydata()).any()
    np.testing.assert_allclose(smooth_line.get_ydata()[[0, -1]], [-90.0, 90.0])
    assert ax.get_ylabel() == "angle [deg]" and ax.get_xlabel() == "s [1]"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["a", "b"]
    with pytest.raises(ValueError, match="labels"):
        RF.draw_angle_sweep(ax, x, turning, ["a", "b"], xlabel="s")
    with pytest.raises(ValueError, match="angles"):
        RF.draw_angle_sweep(ax, x, turning[:10], ["a"], xlabel="s")
    with pytest.raises(ValueError, match="styles"):
        RF.draw_angle_sweep(ax, x, turning, ["a"], xlabel="s", styles=["-", "--"])


def test_lock_gain_references_match_finite_differences_of_the_euler_angles():
    """cot ϑ and 1/sin ϑ (drawn) against φ and ψ measured from zyz_from_rotation after a turn of 1e-7 rad."""
    theta = np.array([1e-3, 1e-2, 0.1, 0.5, 1.2])
    phi0, psi0, delta = 0.5, 0.2, 1e-7
    R0 = rotation_from_zyz(phi0, theta, psi0)
    R1 = rodrigues([np.cos(phi0), np.sin(phi0), 0.0], delta) @ R0  # about the horizontal axis along (r13, r23)
    measured = np.abs(wrap_angle(zyz_from_rotation(R1) - zyz_from_rotation(R0))) / delta
    fig, ax = plt.subplots()
    lines = RF.draw_lock_gain(ax, theta, measured[:, [0, 2]], ["φ", "ψ"])
    cot, inv_sin = lines[2].get_ydata(), lines[3].get_ydata()
    np.testing.assert_allclose(measured[:, 0], cot, rtol=1e-4)
    np.testing.assert_allclose(measured[:, 2], inv_sin, rtol=1e-4)
    np.testing.assert_allclose(lines[0].get_xdata(), np.degrees(theta))
    assert ax.get_xscale() == ax.get_yscale() == "log" and "[deg]" in ax.get_xlabel()
    with pytest.raises(ValueError, match="theta"):
        RF.draw_lock_gain(ax, [0.0, 0.1], [1.0, 1.0], ["φ"])
    with pytest.raises(ValueError, match="gains"):
        RF.draw_lock_gain(ax, [0.1, 0.2], [1.0, -1.0], ["φ"])
    with pytest.raises(ValueError, match="labels"):
        RF.draw_lock_gain(ax, [0.1, 0.2], [1.0, 2.0], ["φ", "ψ"])
