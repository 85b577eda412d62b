"""Labels beside points and the tick numbers of 3-D axes (puma_course.viz.labels) on the Agg backend.

Truths used here: matplotlib's own projection of a drawn 3-D line at draw time (where a label's
anchor must be), the rendered window extents of labels and tick numbers (nothing overlaps; the
overlap check itself finds an overlap), and a line drawn through a label's preferred side (the label
moves off it).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

from puma_course.viz import labels as L
from puma_course.viz.frames import new_axes, set_equal
from tests.support import assert_no_overlap

pytestmark = pytest.mark.usefixtures("course_style")  # the lectures' style, restored afterwards


# ---- tidy_axes, fit_ticks ------------------------------------------------------------------------


def test_tidy_axes_labels_units_and_few_ticks():
    fig = plt.figure()
    ax = L.tidy_axes(fig.add_subplot(projection="3d"), units="mm")
    ax.set_xlim3d(-1000, 1000)
    fig.canvas.draw()
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x [mm]", "y [mm]", "z [mm]")
    assert len(L.tick_label_boxes(ax)["x"]) <= 5


def test_tidy_axes_and_fit_ticks_refuse_a_2d_axes():
    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match="^ax: expected a 3-D axes"):
        L.tidy_axes(ax)
    with pytest.raises(ValueError, match="^ax: expected a 3-D axes"):
        L.fit_ticks(ax)
    with pytest.raises(ValueError, match="^max_bins"):
        L.fit_ticks(plt.figure().add_subplot(projection="3d"), max_bins=1)


@pytest.mark.parametrize("azim", [-90.0, -60.0, -30.0, -3.0, 20.0, 87.0])
def test_fit_ticks_leaves_no_colliding_tick_numbers(azim):
    fig = plt.figure(figsize=(4.0, 3.6))
    ax = L.tidy_axes(fig.add_subplot(projection="3d"))
    ax.view_init(elev=12, azim=azim)
    set_equal(ax, [[-0.6, -0.6, -0.2], [1.4, 1.4, 1.8]])
    L.fit_ticks(ax)
    fig.canvas.draw()
    boxes = L.tick_label_boxes(ax)
    assert_no_overlap([b for bs in boxes.values() for b in bs], pad=1.0)
    assert all(len(bs) >= 2 for bs in boxes.values())


def test_fit_ticks_thins_an_axis_seen_end_on():
    fig = plt.figure(figsize=(4.0, 3.6))
    ax = L.tidy_axes(fig.add_subplot(projection="3d"))
    ax.view_init(elev=5, azim=-2)  # x points almost at the viewer
    set_equal(ax, [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]])
    L.fit_ticks(ax)
    fig.canvas.draw()
    boxes = L.tick_label_boxes(ax)
    assert len(boxes["x"]) < len(boxes["y"])


# ---- label_points --------------------------------------------------------------------------------


def test_labels_are_anchored_where_matplotlib_draws_the_points():
    fig, ax = new_axes()
    P = np.array([[0.0, 0.0, 0.0], [1.0, 0.2, 0.5], [0.3, 1.0, 1.0]])
    (line,) = ax.plot(*P.T, "o")
    set_equal(ax, P)
    anns = L.label_points(ax, P, ["a", "b", "c"])
    fig.canvas.draw()  # Line3D projects its points at draw time: its 2-D data is the truth
    np.testing.assert_allclose([a.xy for a in anns], line.get_xydata(), atol=1e-12)


def test_labels_of_crowded_points_do_not_overlap_and_leave_the_points_free():
    fig, ax = new_axes(figsize=(4.0, 4.0))
    rng = np.random.default_rng(3)
    P = np.vstack([rng.normal(0.0, 0.03, (5, 3)), [[1.0, 1.0, 1.0], [-1.0, -1.0, -1.0]]])
    (line,) = ax.plot(*P.T, "o", ms=4)
    set_equal(ax, P)
    anns = L.label_points(ax, P, [f"$p_{i}$" for i in range(len(P))])
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = [a.get_window_extent(renderer) for a in anns]
    assert_no_overlap(boxes)
    disp = ax.transData.transform(line.get_xydata())  # where matplotlib drew the points
    for box in boxes:  # no label covers the centre of any labelled point
        assert not any(box.contains(x, y) for x, y in disp)


def test_label_points_skips_empty_names_and_checks_its_input():
    fig, ax = new_axes()
    P = np.zeros((3, 3)) + [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    set_equal(ax, P)
    assert [a.get_text() for a in L.label_points(ax, P, ["", "b", ""])] == ["b"]
    with pytest.raises(ValueError, match="^names: expected one text per point"):
        L.label_points(ax, P, ["a", "b"])
    with pytest.raises(ValueError, match="^names"):
        L.label_points(ax, P, "abc")
    with pytest.raises(ValueError, match="^points"):
        L.label_points(ax, np.zeros((3, 2)), ["a", "b", "c"])
    with pytest.raises(ValueError, match="^color"):
        L.label_points(ax, P, ["a", "b", "c"], color=["k", "r"])
    with pytest.raises(ValueError, match="^avoid"):
        L.label_points(ax, P, ["a", "b", "c"], avoid=[np.zeros((2, 2))])


def test_place_labels_separates_labels_on_one_point_and_the_check_is_not_vacuous():
    fig, ax = new_axes()
    texts = L.place_labels(ax, [L.Label([0.0, 0.0, 0.0], f"label {k}") for k in range(8)])
    assert len(texts) == 8 and L.overlapping_labels(texts) == []
    same = [ax.text2D(0.5, 0.5, "one", transform=ax.transAxes), ax.text2D(0.5, 0.5, "two", transform=ax.transAxes)]
    assert L.overlapping_labels(same) == [("one", "two")]
    assert L.overlapping_labels([]) == []


def test_a_label_moves_off_a_line_drawn_through_its_preferred_side():
    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    ax.set(xlim=(0, 1), ylim=(0, 1))
    line = np.array([[0.0, 0.5], [1.0, 0.5]])
    ax.plot(*line.T)
    (free,) = L.place_labels(ax, [L.Label([0.5, 0.5], "label", prefer=0)])
    (moved,) = L.place_labels(ax, [L.Label([0.5, 0.5], "moved", prefer=0)], lines=[line])
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    y = ax.transData.transform([[0.5, 0.5]])[0, 1]  # after the drawing: the layout has settled
    assert free.get_window_extent(r).y0 < y < free.get_window_extent(r).y1  # the preferred side crosses the line
    box = moved.get_window_extent(r)
    assert not box.y0 < y < box.y1
    plt.close(fig)


def test_a_label_keeps_off_the_tick_numbers(monkeypatch):
    def place():
        fig, ax = plt.subplots(figsize=(4.0, 3.0))
        ax.set(xlim=(0, 1), ylim=(0, 1), xticks=[0.25, 0.5, 0.75])
        ax.tick_params(axis="x", direction="in", pad=-14)  # tick numbers drawn inside the axes
        (text,) = L.place_labels(ax, [L.Label([0.5, 0.12], "label", prefer=-90)])
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        numbers = [t.get_window_extent(r) for t in ax.get_xticklabels() if t.get_text()]
        hit = any(text.get_window_extent(r).overlaps(b) for b in numbers)
        plt.close(fig)
        return hit

    assert not place()
    monkeypatch.setattr(L, "_axis_texts", lambda ax, renderer: [])  # the rule switched off: the check can fail
    assert place()
