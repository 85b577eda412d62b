"""The figures of lectures 05-07 (puma_course.viz.porter_figures) on the Agg backend.

Truths used here: matplotlib's own projection of a drawn 3-D line at draw time (where a label's
anchor must be), the rendered window extents of labels and tick numbers (nothing overlaps), Porter's
points at a straight configuration worked out by hand, and the geometric properties the
construction must have whatever computes it (|p3 - p4| = l3, p3 - p4 normal to x5, p3 in the
plane through z0 and p4, the two candidates symmetric about p4; the circle of the parallel planes
at distance l3 from p4 in the plane normal to x5, through the elbow point of every configuration
reaching the pose).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from puma_course import Porter, Puma560, SingularityWarning
from puma_course.viz import labels as L
from puma_course.viz import porter_figures as PF
from puma_course.viz.labels import tick_label_boxes
from tests.support import assert_no_overlap

ARM = Porter(1.0, 0.5, 0.3)
Q_GENERAL = np.array([0.6, -0.5, 1.2, 0.8, 0.7, -0.4])
Q_PARALLEL = np.array([0.7, 0.3, 1.2, 0.4, math.pi / 2, 0.5])
Q_AXIS = np.array([0.7, -0.5, 0.5 / math.cos(0.5), math.pi / 2 + 0.5, 0.4, 0.5])


pytestmark = pytest.mark.usefixtures("course_style")  # the lectures' style, restored afterwards


def _labels(ax):
    return [t for t in ax.texts if t.get_text()]


def _check_readable(fig):
    """No tick numbers collide, no two labels overlap, every axis label and label lies inside the figure."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    inside = fig.bbox.padded(1.0)
    for ax in fig.axes:
        boxes = tick_label_boxes(ax)
        for name, bs in boxes.items():
            assert bs, f"the {name} axis has no tick numbers"
        assert_no_overlap([b for bs in boxes.values() for b in bs])
        label_boxes = [t.get_window_extent(renderer) for t in _labels(ax)]
        assert_no_overlap(label_boxes)
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            box = axis.label.get_window_extent(renderer)
            assert inside.contains(box.x0, box.y0) and inside.contains(box.x1, box.y1), axis.label.get_text()
        for box in label_boxes:
            assert inside.contains(box.x0, box.y0) and inside.contains(box.x1, box.y1)
        legend = ax.get_legend()
        if legend is not None:
            assert min(t.get_fontsize() for t in legend.get_texts()) >= 9
    assert fig.dpi >= 100


# ---- the points ----------------------------------------------------------------------------------


def test_plot_frames_labels_the_frames_where_they_are_by_hand():
    # angles 0, stroke 0.8: up l1 = 1, out 0.8, down l3 = 0.5, out l4 = 0.3
    fig = PF.plot_frames(ARM, [[0.0, 0.0, 0.8, 0.0, 0.0, 0.0]])
    ax = fig.axes[0]
    hand = np.array([[0, 0, 0], [0, 0, 1], [0.8, 0, 1], [0.8, 0, 0.5], [1.1, 0, 0.5]], dtype=float)
    anchors = {t.get_text(): t.xy for t in _labels(ax)}
    assert list(anchors) == ["x", "y", "z"] + [n for n in PF.FRAME_NAMES if n]  # F0's letters first (issue 25)
    np.testing.assert_allclose(list(anchors.values())[3:], L._screen(ax, hand), atol=1e-12)
    tips = 0.14 * 1.1 * np.eye(3)  # F0 = the base frame; triads 0.14 of the widest extent, 1.1 (out 0.8 + l4)
    np.testing.assert_allclose(list(anchors.values())[:3], L._screen(ax, tips), atol=1e-12)
    with pytest.raises(ValueError, match="^arm"):
        PF.plot_frames(Puma560(), np.zeros(6))


@pytest.mark.parametrize("seed", range(5))
def test_ver2_points_have_the_properties_of_the_construction(seed):
    rng = np.random.default_rng(seed)
    q = np.r_[rng.uniform(-3, 3, 2), rng.uniform(0.2, 2.0), rng.uniform(-3, 3, 3)]
    T = ARM.fk(q)
    V = PF.ver2_points(ARM, T, near=q)
    l1, l3, l4 = 1.0, 0.5, 0.3
    np.testing.assert_allclose(V["p4"], T[:3, 3] - l4 * T[:3, 0], atol=1e-12)  # eq. 17
    np.testing.assert_allclose(V["p2"], [0, 0, l1], atol=1e-15)
    assert np.linalg.norm(V["n"]) == pytest.approx(1.0)
    assert abs(V["n"] @ [0, 0, 1]) < 1e-12 and abs(V["n"] @ V["p4"]) < 1e-12  # normal to z0 and to p4
    assert len(V["p3"]) == 2
    for p3 in V["p3"]:
        assert np.linalg.norm(p3 - V["p4"]) == pytest.approx(l3, abs=1e-12)
        assert abs((p3 - V["p4"]) @ V["x5"]) < 1e-12
        assert abs((p3 - V["p0"]) @ V["n"]) < 1e-12
    np.testing.assert_allclose(V["p3"].sum(axis=0), 2 * V["p4"], atol=1e-12)  # ± l3 z4
    # the arm that made T has one of the two elbow points (both arm planes share the points)
    assert np.linalg.norm(V["p3"] - ARM.points(q)[3], axis=1).min() < 1e-9


def test_ver2_points_refuse_a_free_plane_and_bad_input():
    with pytest.raises(ValueError, match="^T: expected a pose whose wrist point p4 is off the z0 axis"):
        PF.ver2_points(ARM, ARM.fk(Q_AXIS))
    with pytest.raises(ValueError, match="^T"):
        PF.ver2_points(ARM, np.eye(3))
    with pytest.raises(ValueError, match="^T: expected a pose the arm reaches"):
        PF.ver2_points(Porter(1.0, 0.5, 0.3, q2_max=1.0), ARM.fk([0.3, 0.2, 5.0, 0.4, 0.5, 0.6]))


def test_parallel_circle_is_every_elbow_point_of_the_family():
    T = ARM.fk(Q_PARALLEL)
    C = PF.parallel_circle(ARM, T, samples=73)
    p4, x5 = T[:3, 3] - 0.3 * T[:3, 0], T[:3, 0]
    np.testing.assert_allclose(np.linalg.norm(C - p4, axis=1), 0.5, atol=1e-12)
    np.testing.assert_allclose((C - p4) @ x5, 0.0, atol=1e-12)
    np.testing.assert_allclose(C[0], C[-1], atol=1e-12)  # closed
    # members of the family (found with near= at different α3) have their p3 on the circle
    for a3 in (0.0, 0.4, 1.5):
        ref = Q_PARALLEL.copy()
        ref[3] = a3
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SingularityWarning)
            s = ARM.ik(T, near=ref)[0]
        p3 = ARM.points(s)[3]
        assert np.linalg.norm(p3 - p4) == pytest.approx(0.5) and abs((p3 - p4) @ x5) < 1e-9
    with pytest.raises(ValueError, match="^T: expected a pose with parallel planes"):
        PF.parallel_circle(ARM, ARM.fk(Q_GENERAL))
    with pytest.raises(ValueError, match="^samples"):
        PF.parallel_circle(ARM, T, samples=2)


# ---- the figures ---------------------------------------------------------------------------------


def test_plot_frames_is_readable_and_shows_every_frame():
    fig = PF.plot_frames(ARM, [[0, 0, 0.8, 0, 0, 0], Q_GENERAL], ["straight", "general"])
    _check_readable(fig)
    for ax in fig.axes:
        assert sorted(t.get_text() for t in _labels(ax)) == sorted([n for n in PF.FRAME_NAMES if n] + ["x", "y", "z"])
    with pytest.raises(ValueError, match="^titles"):
        PF.plot_frames(ARM, np.zeros((2, 6)), ["one"])
    with pytest.raises(ValueError, match="^Q"):
        PF.plot_frames(ARM, np.zeros((2, 5)))


def test_plot_solutions_groups_the_four_by_arm_plane():
    sol = ARM.ik(ARM.fk(Q_GENERAL), near=Q_GENERAL)
    fig = PF.plot_solutions(ARM, sol)
    _check_readable(fig)
    assert len(fig.axes) == 2
    for ax in fig.axes:
        assert sum(t.get_text().startswith("$p_3$") for t in _labels(ax)) == 2
    with pytest.raises(ValueError, match="^solutions"):
        PF.plot_solutions(ARM, np.zeros((0, 6)))


def test_plot_construction_and_parallel_planes_are_readable():
    _check_readable(PF.plot_construction(ARM, ARM.fk(Q_GENERAL), near=Q_GENERAL))
    fig = PF.plot_parallel_planes(ARM, ARM.fk(Q_PARALLEL), Q_PARALLEL)
    _check_readable(fig)
    assert len(fig.axes[0].get_legend().get_texts()) == 3
    with pytest.raises(ValueError, match="^q_ref"):
        PF.plot_parallel_planes(ARM, ARM.fk(Q_PARALLEL), np.zeros((2, 6)))


def test_the_dashed_lines_are_the_joint_axes_each_joint_moves_the_chain_about():
    """Independent truth: moving one joint turns every later point about its line (or slides it along it)."""
    rng = np.random.default_rng(7)
    q = rng.uniform(-1.0, 1.0, 6)
    q[2] = 0.9
    lines = PF.joint_axis_lines(ARM.frames(q))
    assert lines.shape == (6, 2, 3)
    np.testing.assert_allclose(np.linalg.norm(lines[:, 1], axis=1), 1.0)
    for j, (o, u) in enumerate(lines):
        moved = q.copy()
        moved[j] += 0.37
        # every frame's origin and the tips of its three axes, before and after the joint moves
        F0, F1 = ARM.frames(q), ARM.frames(moved)
        before = np.concatenate(
            [F0[:, :3, 3], (F0[:, :3, 3][:, :, None] + F0[:, :3, :3]).transpose(0, 2, 1).reshape(-1, 3)]
        )
        after = np.concatenate(
            [F1[:, :3, 3], (F1[:, :3, 3][:, :, None] + F1[:, :3, :3]).transpose(0, 2, 1).reshape(-1, 3)]
        )
        assert np.abs(after - before).max() > 0.05 or j == 5  # the joint moves something (α5: only the hand's axes)
        if j == 2:  # the stroke: every point from p3 on slides along u by the change, the others stay
            shift = after - before
            moved_rows = np.abs(shift).max(axis=1) > 1e-12
            np.testing.assert_allclose(
                shift[moved_rows], np.broadcast_to(0.37 * u, shift[moved_rows].shape), atol=1e-12
            )
            continue
        # a rotation about the line (o, u): the component along u and the distance to the line are kept
        for b, a in zip(before, after, strict=True):
            assert abs(np.dot(a - o, u) - np.dot(b - o, u)) < 1e-12
            assert abs(np.linalg.norm(np.cross(a - o, u)) - np.linalg.norm(np.cross(b - o, u))) < 1e-12
    fig = PF.plot_frames(ARM, [q])
    dashed = [ln for ln in fig.axes[0].lines if ln.get_linestyle() == "--"]
    assert len(dashed) == 6
    for ln, (o, u) in zip(dashed, lines, strict=True):
        a, b = np.transpose(ln.get_data_3d())
        np.testing.assert_allclose(np.cross(b - a, u), 0.0, atol=1e-12)  # along the joint's axis
        np.testing.assert_allclose((a + b) / 2, o, atol=1e-12)  # through the joint
