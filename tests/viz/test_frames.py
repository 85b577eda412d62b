"""Axes and frame helpers (puma_course.viz.frames) on the Agg backend, against hand-worked geometry."""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.transforms import homogeneous, rotz
from puma_course.viz import frames as V
from puma_course.viz.style import contrast_ratio, text_color


def _ranges(ax):
    return np.array([np.ptp(ax.get_xlim3d()), np.ptp(ax.get_ylim3d()), np.ptp(ax.get_zlim3d())])


def test_new_axes_is_3d_with_labels_view_and_dpi():
    fig, ax = V.new_axes(figsize=(4.0, 3.0), title="t", elev=10, azim=30, dpi=50)
    assert ax.name == "3d" and ax.get_title() == "t"
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x", "y", "z")
    assert (ax.elev, ax.azim) == (10, 30)
    assert tuple(fig.canvas.get_width_height()) == (200, 150)  # 4 x 3 inches at 50 dpi


def test_set_equal_gives_equal_ranges_and_frames_the_points():
    fig, ax = V.new_axes(title="t")
    pts = np.array([[0.0, 0.0, 0.0], [4.0, 1.0, 0.5], [-1.0, 2.0, 0.2]])
    V.set_equal(ax, pts)
    r = _ranges(ax)
    np.testing.assert_allclose(r, r[0])
    assert r[0] >= 5.0  # the x extent (-1..4) fits
    for k, lim in enumerate([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]):
        assert lim[0] <= pts[:, k].min() and lim[1] >= pts[:, k].max()
    # without points: uses what the axes currently show, still equal
    ax.set_xlim3d(0, 10)
    V.set_equal(ax)
    r = _ranges(ax)
    np.testing.assert_allclose(r, r[0])


def test_set_equal_margin_by_hand():
    fig, ax = V.new_axes()
    V.set_equal(ax, [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], margin=0.5)  # half side 1 * 1.5 around (1, 0, 0)
    np.testing.assert_allclose(ax.get_xlim3d(), [-0.5, 2.5])
    np.testing.assert_allclose(ax.get_zlim3d(), [-1.5, 1.5])
    with pytest.raises(ValueError, match="points"):
        V.set_equal(ax, [[0.0, 1.0]])
    with pytest.raises(ValueError, match="points"):
        V.set_equal(ax, np.zeros((0, 3)))
    # any stack of points: (2, 2, 3) frames the same cube as its four points
    V.set_equal(ax, [[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]], margin=0.0)
    np.testing.assert_allclose([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()], [[0, 2], [-1, 1], [-0.5, 1.5]])


def test_draw_frame_axes_point_along_rotation_columns():
    fig, ax = V.new_axes()
    T = homogeneous(rotz(np.pi / 2), [1.0, 2.0, 3.0])
    arts = V.draw_frame(ax, T, label="{1}", length=0.5)
    assert len(arts) == 4 + 3  # three axes + a label + the letters x, y, z at the tips (issue 25)
    assert [a.get_text() for a in arts[4:]] == ["x", "y", "z"]
    # the letters in their axis' hue, darkened where needed to 4.5:1 on white (issue 34: tab:green is 3.4:1)
    assert [a.get_color() for a in arts[4:]] == [text_color(c) for c in V.AXIS_COLORS]
    assert all(contrast_ratio(a.get_color()) >= 4.5 for a in arts[4:])
    np.testing.assert_allclose(arts[4].get_position_3d(), [1.0, 2.0 + 1.18 * 0.5, 3.0], atol=1e-12)
    assert len(V.draw_frame(ax, T, label="{1}", length=0.5, letters=False)) == 4
    x_line = arts[0]
    xs, ys, zs = x_line.get_data_3d()
    np.testing.assert_allclose([xs[1] - xs[0], ys[1] - ys[0], zs[1] - zs[0]], [0.0, 0.5, 0.0], atol=1e-12)
    assert x_line.get_color() == "tab:red"
    # the y axis of Rz(90°) is -x0, from the origin (1, 2, 3)
    np.testing.assert_allclose(np.transpose(arts[1].get_data_3d()), [[1.0, 2.0, 3.0], [0.5, 2.0, 3.0]], atol=1e-12)
    assert [a.get_color() for a in arts[:3]] == list(V.AXIS_COLORS)
    with pytest.raises(ValueError, match="T"):
        V.draw_frame(ax, np.eye(3))


def test_draw_points_and_frames():
    fig, ax = V.new_axes()
    (line,) = V.draw_points(ax, np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.0]]))
    np.testing.assert_allclose(np.transpose(line.get_data_3d()), [[0, 0, 0], [1, 0, 0], [1, 1, 0]])
    arts = V.draw_frames(ax, np.stack([np.eye(4)] * 3))
    assert len(arts) == 3 * (4 + 3)  # per frame: three axes, a label, the letters x, y, z (issue 25)
    assert [a.get_text() for a in arts if hasattr(a, "get_text")] == [
        t for i in range(3) for t in (f"{{{i}}}", "x", "y", "z")
    ]
    plain = V.draw_frames(ax, np.stack([np.eye(4)] * 3), letters=False)
    assert len(plain) == 3 * 4
    assert [a.get_text() for a in plain if hasattr(a, "get_text")] == ["{0}", "{1}", "{2}"]


def test_triad_letters_sit_at_the_tips_and_face_the_way_their_axes_point():
    """Issue 25: seen from above (elev 90, azim -90) x points right on the page, y up."""
    from puma_course.viz.frames import new_axes, triad_letters

    fig, ax = new_axes(elev=90, azim=-90)
    T = np.eye(4)
    T[:3, 3] = [0.2, -0.1, 0.0]
    labels = triad_letters(ax, T, 0.5, names=["$x_1$", "$y_1$", "$z_1$"])
    assert [lb.text for lb in labels] == ["$x_1$", "$y_1$", "$z_1$"]
    np.testing.assert_allclose([lb.point for lb in labels], T[:3, 3] + 0.5 * np.eye(3), atol=1e-15)
    assert abs(labels[0].prefer - 0.0) < 1e-6 or abs(labels[0].prefer - 360.0) < 1e-6
    assert abs(labels[1].prefer - 90.0) < 1e-6
    with pytest.raises(ValueError, match="^names: expected three texts"):
        triad_letters(ax, T, 0.5, names=["x", "y"])
