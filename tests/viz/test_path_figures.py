"""Joint-path and joint-speed figures (puma_course.viz.path_figures): units on their own axes, readable legends."""

from __future__ import annotations

import matplotlib as mpl
import numpy as np
import pytest

from puma_course import Porter, Puma560
from puma_course.kinematics import trajectories as tr
from puma_course.viz import use_course_style
from puma_course.viz.path_figures import (
    JOINT_COLORS,
    JOINT_LINESTYLES,
    JOINT_MARKERS,
    MIN_LEGEND_SIZE,
    joint_axis_labels,
    joint_path_figure,
)


@pytest.fixture
def course_style():
    """The course's figure style for one test, undone afterwards (other tests check their own dpi)."""
    with mpl.rc_context():
        use_course_style()
        yield


def _ydata(ax) -> list[np.ndarray]:
    return [np.asarray(line.get_ydata(), dtype=float) for line in ax.lines]


def _overlap(a, b) -> bool:
    """Do two display-space boxes overlap (by more than a pixel)?"""
    return a.x0 < b.x1 - 1 and b.x0 < a.x1 - 1 and a.y0 < b.y1 - 1 and b.y0 < a.y1 - 1


def test_porter_stroke_gets_its_own_axis_in_its_units():
    """Porter's q2 is a length: it is drawn as it is on the second row, the angles in degrees on the first."""
    arm = Porter(1.0, 0.5, 0.3)
    q = np.array([[0.1, 0.2, 1.0, 0.3, 0.4, 0.5], [0.2, 0.3, 1.5, 0.4, 0.5, 0.6]])
    names = ["α1", "α2", "q2", "α3", "α4", "α5"]
    fig, axes = joint_path_figure(q, revolute=arm.revolute, names=names, units="")
    assert axes.shape == (2, 1)
    angles, lengths = axes[:, 0]
    assert angles.get_ylabel() == "joint angle [deg]" and lengths.get_ylabel() == "joint length (unitless)"
    # the top row holds the five angles in degrees (hand-converted), the bottom row the stroke unchanged
    expected = np.degrees(q[:, [0, 1, 3, 4, 5]]).T
    np.testing.assert_allclose(np.array(_ydata(angles)), expected, atol=1e-12)
    np.testing.assert_allclose(_ydata(lengths)[0], [1.0, 1.5])
    assert [line.get_label() for line in lengths.lines] == ["q2"]
    assert lengths.lines[0].get_color() == JOINT_COLORS[2]  # the joint's colour is its index's, in every panel


def test_angles_are_unwrapped_for_positions_but_not_for_speeds():
    """A joint crossing ±180° is drawn continuously (179° then 181°, not -179°); speeds are only converted."""
    q = np.array([[np.radians(179.0)], [np.radians(-179.0)]])
    fig, axes = joint_path_figure(q)
    np.testing.assert_allclose(_ydata(axes[0, 0])[0], [179.0, 181.0], atol=1e-9)
    qd = np.array([[1.0], [-2.0]])  # rad/s
    fig, axes = joint_path_figure(qd, speed=True, x=[0.0, 0.5])
    np.testing.assert_allclose(_ydata(axes[0, 0])[0], np.degrees([1.0, -2.0]))
    np.testing.assert_allclose(axes[0, 0].lines[0].get_xdata(), [0.0, 0.5])
    assert axes[0, 0].get_ylabel() == "joint speed [deg/s]" and axes[0, 0].get_xlabel() == "time t [s]"


def test_columns_share_their_scale_and_the_legend_lists_each_joint_once():
    q1 = np.column_stack([np.linspace(0, 1, 5), np.zeros(5)])
    q2 = np.column_stack([np.linspace(0, 3, 5), np.ones(5)])
    fig, axes = joint_path_figure([q1, q2], titles=["nearest", "naive"], names=["θ1", "θ2"])
    assert axes.shape == (1, 2)
    assert axes[0, 0].get_ylim() == axes[0, 1].get_ylim()  # same degrees on both
    assert axes[0, 0].get_ylim()[1] >= np.degrees(3.0)
    assert len(fig.legends) == 1 and [t.get_text() for t in fig.legends[0].get_texts()] == ["θ1", "θ2"]


def test_joints_selects_curves_and_drops_an_empty_row():
    """Only θ4 and θ6 of a PUMA path: one row (no length joints), two curves in the joints' own colours."""
    q = np.zeros((3, 6))
    fig, axes = joint_path_figure(q, joints=[3, 5], revolute=Puma560().revolute)
    assert axes.shape == (1, 1)
    assert [line.get_label() for line in axes[0, 0].lines] == ["θ4", "θ6"]
    assert [line.get_color() for line in axes[0, 0].lines] == [JOINT_COLORS[3], JOINT_COLORS[5]]


@pytest.mark.parametrize(("legend_size", "columns"), [(7.0, 1), (10.0, 1), (10.0, 2)])
def test_legend_is_large_enough_and_never_covers_a_curve(course_style, legend_size, columns):
    """The legend is at least 9 pt (even if the style asks for less) and lies outside every axes and the title."""
    with mpl.rc_context({"legend.fontsize": legend_size}):
        arm = Puma560()
        q0 = arm.q("qn")
        path = tr.line_path(arm.fk(q0), arm.fk(q0)[:3, 3] + [0.0, 0.1, -0.1], 30)
        jp = tr.follow(arm, path, q0)
        title = "PUMA-560 on the circle, nearest solution at every step"  # wider than one column's axes
        fig, axes = joint_path_figure([jp.q] * columns, suptitle=title)
        fig.canvas.draw()
        leg = fig.legends[0]
        assert min(t.get_fontsize() for t in leg.get_texts()) >= max(MIN_LEGEND_SIZE, legend_size) - 1e-9
        box = leg.get_window_extent()
        for ax in axes.ravel():
            assert not _overlap(box, ax.get_window_extent())
        assert not _overlap(box, fig._suptitle.get_window_extent())  # nor the title above the panels
        # nothing is clipped: the legend sits inside the figure
        fbox = fig.bbox
        assert box.x1 <= fbox.x1 + 1 and box.y0 >= fbox.y0 - 1


def test_tick_labels_do_not_overlap(course_style):
    """The y tick labels of a figure with both rows, drawn at the course style, do not collide."""
    q = np.column_stack([np.linspace(-3, 3, 50), np.linspace(0, 2, 50), np.linspace(1, -1, 50)])
    fig, axes = joint_path_figure(q, revolute=[True, False, True], units="m")
    fig.canvas.draw()
    for ax in axes.ravel():
        labels = [t for t in ax.get_yticklabels() if t.get_visible() and t.get_text()]
        boxes = [t.get_window_extent() for t in labels]
        assert len(boxes) >= 2
        for a, b in zip(boxes, boxes[1:], strict=False):
            assert not _overlap(a, b)


def test_pose_indices_get_whole_number_ticks():
    fig, axes = joint_path_figure(np.zeros((19, 2)))
    ticks = [v for v in axes[0, 0].get_xticks() if 0 <= v <= 18]
    assert len(ticks) >= 3 and all(float(v).is_integer() for v in ticks)


def test_axis_labels_with_units():
    assert joint_axis_labels("mm", speed=True) == ("joint speed [deg/s]", "joint speed [mm/s]")
    with pytest.raises(ValueError, match="units"):
        joint_axis_labels(3)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"paths": np.zeros(3)}, "paths"),
        ({"paths": "q"}, "paths"),
        ({"paths": [np.zeros((3, 2)), np.zeros((3, 3))]}, r"paths\[1\]"),
        ({"paths": np.full((2, 2), np.nan)}, "paths"),
        ({"paths": np.zeros((3, 2)), "revolute": [1, 0]}, "revolute"),
        ({"paths": np.zeros((3, 2)), "names": ["a"]}, "names"),
        ({"paths": np.zeros((3, 2)), "joints": [2]}, "joints"),
        ({"paths": np.zeros((3, 2)), "joints": [0, 0]}, "joints"),
        ({"paths": np.zeros((3, 2)), "x": [0.0, 1.0]}, "x"),
        ({"paths": np.zeros((3, 2)), "titles": ["a", "b"]}, "titles"),
        ({"paths": np.zeros((3, 2)), "units": None}, "units"),
    ],
)
def test_bad_input_is_refused_naming_the_argument(kwargs, match):
    paths = kwargs.pop("paths")
    with pytest.raises(ValueError, match=match):
        joint_path_figure(paths, **kwargs)


def test_every_joint_has_its_own_line_style_and_marker_besides_its_colour():
    """θ4 and θ6 on top of each other stay apart by style and marker positions; nothing is dashed (issue 25)."""
    q = np.zeros((40, 6))  # all six curves coincide
    fig, axes = joint_path_figure(q, revolute=Puma560().revolute)
    lines = axes[0, 0].lines
    styles = [(line.get_linestyle(), line.get_marker()) for line in lines]
    assert len(set(styles)) == 6, styles
    assert "--" not in [line.get_linestyle() for line in lines]  # a dashed line means a joint axis
    t4, t6 = lines[3], lines[5]
    assert (t4.get_linestyle(), t4.get_marker()) != (t6.get_linestyle(), t6.get_marker())
    m4, m6 = (set(range(line.get_markevery()[0], 40, line.get_markevery()[1])) for line in (t4, t6))
    assert m4 and m6 and not m4 & m6, (m4, m6)  # their markers do not coincide
    assert [line.get_linestyle() for line in lines] == [
        {"-": "-", "-.": "-.", ":": ":"}[ls] for ls in JOINT_LINESTYLES[:6]
    ]
    assert [line.get_marker() for line in lines] == list(JOINT_MARKERS[:6])
    import matplotlib.pyplot as plt

    plt.close(fig)
