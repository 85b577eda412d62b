"""The frame-assignment figures (puma_course.viz.dh_figures) on the Agg backend.

Truths used here: joint axes built from known DH parameters with Craig's link matrix (the picture
must read the same a, α, d, θ back off the lines), the drawn lines' data against the feet of the
common normal, a 3-4-5 triangle for the piston, the clipping of a segment worked by hand, and the
label boxes measured on the rendered figure (no two overlap; the check itself finds an overlap).
"""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.kinematics import Puma560, mdh
from puma_course.kinematics.frame_assignment import frame_steps
from puma_course.viz import dh_figures as D
from puma_course.viz import labels as L
from puma_course.viz.frames import new_axes


def _axes_from_params(al0, a0, th, d, al1, a1):
    """Three joint axes whose DH parameters are known: axis i-1 is z, axes i and i+1 from Craig's link matrix."""
    Fi = mdh(al0, a0, th, d)
    Fn = Fi @ mdh(al1, a1, 0.0, 0.0)
    P = np.array([[0, 0, 0.2], Fi[:3, 3] - 0.4 * Fi[:3, 2], Fn[:3, 3] + 0.3 * Fn[:3, 2]])  # not at the feet
    U = np.array([[0, 0, 1.0], Fi[:3, 2], Fn[:3, 2]])
    return P, U, Fi


def _texts(labels):
    return sorted(t.get_text() for t in labels)


@pytest.mark.parametrize("seed", range(6))
def test_the_dh_picture_reads_back_the_parameters_the_axes_were_built_from(seed):
    rng = np.random.default_rng(seed)
    al0, th, al1 = rng.uniform(-1.2, 1.2, 3)
    a0, d, a1 = rng.uniform(0.5, 2.0, 3)
    P, U, Fi = _axes_from_params(al0, a0, th, d, al1, a1)
    fig, ax = new_axes(figsize=(8, 6))
    pic = D.draw_dh_picture(ax, P, U)
    got = [pic.params[k] for k in ("alpha_prev", "a_prev", "theta", "d", "alpha", "a")]
    assert np.allclose(got, [al0, a0, th, d, al1, a1])
    assert np.allclose(pic.frames[1], Fi)  # frame {i} where Craig's link matrix puts it
    assert L.overlapping_labels(pic.labels) == []
    assert _texts(pic.labels) == sorted(
        ["axis $i-1$", "axis $i$", "axis $i+1$", "$a_{i-1}$", r"$\alpha_{i-1}$", "$a_{i}$", "$d_{i}$",
         r"$\theta_{i}$", "$X_{i-1}$", "$X_{i}$", "$Z_{i-1}$", "$Z_{i}$"]
    )  # fmt: skip


def test_the_lectures_picture_has_its_labels_inside_the_axes_and_apart():
    P = np.array([[0, 0, -0.5], [1.5, 0.6, -0.8], [2.5, 0.5, 1.0]])
    U = np.array([[0, 0, 1.0], [0, -0.6, 0.8], [-0.6, 0, 0.8]])
    fig, ax = new_axes(figsize=(8, 6))
    pic = D.draw_dh_picture(ax, P, U, elev=16, azim=-70)
    assert pic.params["a_prev"] == pytest.approx(1.5) and pic.params["alpha_prev"] == pytest.approx(np.arctan2(3, 4))
    r = fig.canvas.get_renderer()
    frame = ax.get_window_extent(r)
    for t in pic.labels:
        bb = t.get_window_extent(r)
        assert frame.x0 <= bb.x0 and bb.x1 <= frame.x1 and frame.y0 <= bb.y0 and bb.y1 <= frame.y1, t.get_text()
    assert L.overlapping_labels(pic.labels) == []


def test_draw_common_normal_draws_the_normal_between_its_feet():
    fig, ax = new_axes()
    cn, labels = D.draw_common_normal(ax, [0, 0, 0], [0, 0, 1], [1, 0, 5], [0, 1, 0], place=False)
    assert cn.kind == "skew" and cn.a == 1.0 and cn.alpha == -np.pi / 2
    normal = [ln for ln in ax.lines if ln.get_color() == D.NORMAL_COLOR and ln.get_linewidth() == 3.5]
    assert len(normal) == 1 and np.allclose(np.transpose(normal[0].get_data_3d()), [[0, 0, 5], [1, 0, 5]])
    assert [lb.text for lb in labels] == ["axis $i-1$", "axis $i$", "$a_{i-1}$", r"$\alpha_{i-1}$"]
    set_ax = L.place_labels(ax, labels)
    assert L.overlapping_labels(set_ax) == []


PUMA = Puma560()


def _puma_walk():
    a2, a3, d3, d4 = PUMA.lengths.values()
    W = [a2 + a3, d3, -d4]
    P = [[0, 0, 0], [0, 0, 0], [a2, 0, 0], [a2 + a3, d3, 0], W, W]
    U = [[0, 0, 1], [0, 1, 0], [0, 1, 0], [0, 0, -1], [0, 1, 0], [0, 0, -1]]
    return frame_steps(P, U)


@pytest.mark.parametrize("k", [0, 1, 2, 3, 4, 5, 6, None])
def test_frame_walk_highlights_the_step_and_keeps_labels_apart(k):
    walk = _puma_walk()
    fig, ax = new_axes(figsize=(6.4, 5.2))
    texts = D.draw_frame_walk(ax, walk, k, points=PUMA.points(np.zeros(6)), units="m")
    names = [t.get_text() for t in texts]
    first = "$\\{0\\}, \\{1\\}$"  # {0} = {1} at q = 0: one label for both
    if k == 0:  # the axes alone: their numbers, no frame
        assert sorted(names) == [str(i) for i in range(1, 7)]
    elif k is None:
        assert first in names and all(f"$\\{{{i}\\}}$" in names for i in range(2, 7))
    else:
        mine, nxt = (first if k == 1 else f"$\\{{{k}\\}}$"), f"$\\{{{k % 6 + 1}\\}}$"
        assert mine in names and nxt not in names
        assert ("$a_{2}$" in names) == (k == 2) and ("$d_{3}$" in names) == (k == 3)
    assert L.overlapping_labels(texts) == []
    assert ax.get_xlabel() == "x [m]"
    # issue 25: the bold triads' axes are lettered x, y, z, each letter anchored at its axis' tip
    bold = [] if k == 0 else walk.steps if k is None else [walk.steps[k - 1]]
    letters = [t for t in texts if t.get_text() in "xyz"]
    assert [t.get_text() for t in letters] == ["x", "y", "z"] * len(bold)
    lo, hi = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]).T  # a tip outside the view: its cut
    tips = [D._clip(st.origin, st.origin + 0.08 * st.frame[:3, c], lo, hi)[1] for st in bold for c in range(3)]
    if bold:  # draw_frame_walk's length 0.08
        np.testing.assert_allclose([t.xy for t in letters], L._screen(ax, np.array(tips)), atol=1e-12)


def test_frame_walk_clips_what_lies_outside_a_zoomed_view():
    walk = _puma_walk()
    fig, ax = new_axes()
    box = np.array([[0.35, -0.05, -0.1], [0.55, 0.2, 0.1]])  # the elbow only
    D.draw_frame_walk(ax, walk, 3, points=PUMA.points(np.zeros(6)), view_points=box)
    lo, hi = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]).T
    for ln in ax.lines:
        P = np.transpose(ln.get_data_3d())
        assert np.all(P >= lo - 1e-9) and np.all(P <= hi + 1e-9)
    with pytest.raises(ValueError, match="^upto: expected a step from 0 to 6"):
        D.draw_frame_walk(ax, walk, 7)


def test_clip_by_hand():
    lo, hi = np.zeros(3), np.ones(3)
    a, b = D._clip(np.array([-1.0, 0.5, 0.5]), np.array([3.0, 0.5, 0.5]), lo, hi)
    assert np.allclose(a, [0, 0.5, 0.5]) and np.allclose(b, [1, 0.5, 0.5])
    assert D._clip(np.array([2.0, 2, 2]), np.array([3.0, 3, 3]), lo, hi) is None
    assert D._clip(np.array([0.5, 2.0, 0.5]), np.array([0.7, 2.0, 0.5]), lo, hi) is None


def test_piston_by_hand():
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    s = D.draw_piston_joint(ax, np.pi / 2, 3.0, 4.0)  # a right angle between arms 3 and 4
    assert s == pytest.approx(5.0)
    rod = [ln for ln in ax.lines if ln.get_color() == "tab:blue" and ln.get_linewidth() == 3.5][0]
    assert np.allclose(np.transpose(rod.get_data()), [[3, 0], [0, 4]], atol=1e-12)
    texts = [c for c in ax.texts]
    assert sorted(t.get_text() for t in texts) == ["$\\gamma$", "$b$", "$c$", "$s$"]
    assert L.overlapping_labels(texts) == []


def test_bad_input():
    fig, ax = new_axes()
    with pytest.raises(ValueError, match="^points: expected three points"):
        D.draw_dh_picture(ax, np.zeros((2, 3)), np.eye(3))
    with pytest.raises(ValueError, match="^half: expected"):
        D.draw_common_normal(ax, [0, 0, 0], [0, 0, 1], [1, 0, 5], [0, 1, 0], half=-1.0)
    with pytest.raises(ValueError, match="^u1: expected a non-zero direction"):
        D.draw_common_normal(ax, [0, 0, 0], [0, 0, 0], [1, 0, 5], [0, 1, 0])
    with pytest.raises(ValueError, match="^b: expected"):
        D.draw_piston_joint(ax, 0.3, -1.0, 2.0)


# ---- issue 25: lecture 03's step 3 as a dimensioned view ---------------------------------------------------------


def test_step_dimensions_print_the_arms_lengths_and_twist_and_keep_their_texts_apart_and_inside():
    fig = D.plot_step_dimensions(_puma_walk(), 3)
    plan, along = fig.axes
    texts = [t.get_text() for t in plan.texts]
    assert "d3 = 0.15005 m" in texts and "a3 = 0.0203 m" in texts  # the lecture's table (Craig's PUMA-560)
    assert "α3 = -90°" in [t.get_text() for t in along.texts]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    for ax in (plan, along):
        shown = [t for t in ax.texts if t.get_text().strip()]
        assert L.overlapping_labels(shown) == []
        for t in shown:  # every text inside the figure, none cut by its edge
            b = t.get_window_extent(renderer)
            assert b.x0 >= box.x0 and b.x1 <= box.x1 and b.y0 >= box.y0 and b.y1 <= box.y1, t.get_text()


def test_step_dimensions_draw_the_dimension_lines_where_the_lengths_are():
    # in the plane of X3 and Z3 (origin of {3} at 0): the foot of X2 lies d3 below it on axis 3, axis 4 a3 across
    walk = _puma_walk()
    a2, a3, d3, d4 = PUMA.lengths.values()
    fig = D.plot_step_dimensions(walk, 3)
    plan = fig.axes[0]
    normal = [ln for ln in plan.lines if ln.get_color() == D.NORMAL_COLOR and ln.get_linewidth() == 4]
    assert len(normal) == 1 and np.allclose(normal[0].get_xydata(), [[0, 0], [a3, 0]])
    foot = [ln for ln in plan.lines if ln.get_marker() == "o" and np.allclose(ln.get_xydata(), [[0, -d3]])]
    assert foot  # where X2 meets axis 3


@pytest.mark.parametrize("k", [0, 1, 6, 2.0, True])
def test_step_dimensions_refuse_a_frame_without_neighbours(k):
    with pytest.raises(ValueError, match="k: expected a frame 2 .. 5"):
        D.plot_step_dimensions(_puma_walk(), k)
