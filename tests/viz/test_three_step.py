"""Pictures and the animation of the three-step procedure (puma_course.viz.three_step)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from puma_course import ThreeStepArm
from puma_course.kinematics.three_step import motion
from puma_course.viz import three_step as tsp
from puma_course.viz.animation import jshtml
from puma_course.viz.style import use_course_style
from tests.support import jshtml_png_sizes

L1, L2 = 1.5, 1.0
W_EX = np.array([0.5, 0.5, 2.0])
TARGET_EX = np.column_stack([[-1.0, 0, 0], [0, 1.0, 0], [0, 0, -1.0]])  # (f1, f2, f3) = (-e_x, e_y, -e_z)


def test_plot_steps_and_animation_smoke():
    sol = ThreeStepArm(L1, L2).three_step(W_EX, TARGET_EX)
    fig = tsp.plot_steps(sol)
    assert len(fig.axes) == 4
    assert [ax.get_title() for ax in fig.axes] == list(tsp.PHASE_TITLES)
    plt.close(fig)
    anim = tsp.animate(sol, steps_per_phase=3, dpi=40, figsize=(4.0, 3.0))
    # as the lectures show it (jshtml), and under the course style, whose savefig.dpi (110) a bare to_jshtml()
    # would use: another test in the same worker may have switched the style on
    use_course_style()
    html = jshtml(anim).data
    sizes = jshtml_png_sizes(html)
    assert len(sizes) == 10  # 3 * 3 + 1
    assert sizes[0] == (160, 120)  # 4 x 3 inches at 40 dpi: the dpi was kept


def test_plot_steps_draws_the_arm_at_the_start_and_after_each_step():
    sol = ThreeStepArm(L1, L2).three_step(W_EX, TARGET_EX)
    fig = tsp.plot_steps(sol)
    # the last panel's arm ends at w; the straight start (first panel) reaches (l1 + l2, 0, 0)
    last = [ln for ln in fig.axes[3].lines if ln.get_marker() == "o"]
    first = [ln for ln in fig.axes[0].lines if ln.get_marker() == "o"]
    np.testing.assert_allclose(np.transpose(last[0].get_data_3d())[-1], W_EX, atol=1e-12)
    np.testing.assert_allclose(np.transpose(first[0].get_data_3d()), [[0, 0, 0], [L1, 0, 0], [L1 + L2, 0, 0]])
    # the wrist frame drawn at the end is the target: f1 = -e_x (length 0.5)
    f1 = np.transpose(fig.axes[3].lines[-3].get_data_3d())
    np.testing.assert_allclose(f1[1] - f1[0], [-0.5, 0.0, 0.0], atol=1e-12)
    assert len(motion(sol, steps_per_phase=12).phase) == 37


def test_draw_triad_and_state():
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    R = np.column_stack([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # Rz(90°)
    arts = tsp.draw_triad(ax, [1.0, 0.0, 0.0], R, length=2.0, color="k")
    np.testing.assert_allclose(np.transpose(arts[0].get_data_3d()), [[1.0, 0.0, 0.0], [1.0, 2.0, 0.0]])
    assert [a.get_text() for a in arts if hasattr(a, "get_text")] == ["f1", "f2", "f3"]
    arts = tsp.draw_state(ax, [[0, 0, 0], [0, 0, 1.5], [1.0, 0, 1.5]], np.eye(3), length=0.5)
    np.testing.assert_allclose(np.transpose(arts[0].get_data_3d())[-1], [1.0, 0.0, 1.5])
    assert len(arts) == 7


def test_plot_triangle_draws_the_law_of_cosines_triangle_in_the_arm_plane():
    import math

    import pytest

    from puma_course.viz.labels import overlapping_labels

    fig = tsp.plot_triangle(ThreeStepArm(L1, L2), W_EX)
    ax = fig.axes[0]
    up = next(ln for ln in ax.lines if ln.get_label() == "elbow up").get_xydata()
    down = next(ln for ln in ax.lines if ln.get_label() == "elbow down").get_xydata()
    # truth by hand: w lies at horizontal distance |(0.5, 0.5)| and height 2 from the shoulder
    r, z = math.hypot(0.5, 0.5), 2.0
    for s, e, w in (up, down):
        assert np.allclose(s, 0.0) and np.allclose(w, [r, z])
        assert math.dist(s, e) == pytest.approx(L1) and math.dist(e, w) == pytest.approx(L2)
    cross = [(w - s)[0] * (e - s)[1] - (w - s)[1] * (e - s)[0] for s, e, w in (up, down)]  # 2-D cross product
    assert cross[0] > 0 > cross[1]  # the up elbow lies above the line s-w, the down elbow below it
    # the β arc: its radius from the up elbow, its angle the law of cosines' angle at the elbow
    l3 = math.hypot(r, z)
    beta = math.acos((L1**2 + L2**2 - l3**2) / (2 * L1 * L2))
    arc = next(ln for ln in ax.lines if ln.get_color() == "tab:red").get_xydata() - up[1]
    a0, a1 = (math.atan2(p[1], p[0]) for p in (arc[0], arc[-1]))
    assert abs((a1 - a0 + math.pi) % (2 * math.pi) - math.pi) == pytest.approx(beta)
    texts = [t for t in ax.texts if t.get_text()]
    assert {t.get_text() for t in texts} >= {"$s$", "$w$", "$\\beta$", "$\\gamma$", "$\\theta$"}
    assert overlapping_labels(texts) == []
    plt.close(fig)
    with pytest.raises(ValueError, match="^arm: expected ThreeStepArm"):
        tsp.plot_triangle(object(), W_EX)
