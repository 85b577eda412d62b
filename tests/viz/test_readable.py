"""Figures readable without colour and with contrast (issue 34; WCAG 2.1 1.4.1 use of colour, 1.4.3 contrast).

Every figure function of the package is drawn on a typical input; then no two lines of one axes may be told apart by
colour alone (:func:`~puma_course.viz.style.colour_only_lines`: same style, marker and width, colours of the same
lightness, no text in their colour), and every text keeps 4.5:1 on its ground
(:func:`~puma_course.viz.style.low_contrast_texts`). The checks themselves are tested on figures that must fail.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

from puma_course import MK3, Porter, Puma560, ThreeStepArm
from puma_course.kinematics.frame_assignment import frame_steps
from puma_course.transforms import homogeneous, rotx, roty, rotz
from puma_course.viz import (
    arms,
    dh_figures,
    ik_figures,
    ik_sweeps,
    mk3_figures,
    path_figures,
    porter_figures,
    rotation_figures,
    three_step,
)
from puma_course.viz.frames import AXIS_COLORS, new_axes
from puma_course.viz.style import (
    JOINT_COLOR,
    NORMAL_COLOR,
    colour_only_lines,
    contrast_ratio,
    low_contrast_texts,
    text_color,
)
from puma_course.viz.viewer import RobotViewer

PUMA, MK, PORTER = Puma560(), MK3(), Porter(1.0, 0.5, 0.3)
Q_PUMA = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])
Q_PORTER = np.array([0.6, -0.5, 1.2, 0.8, 0.7, -0.4])
Q_PARALLEL = np.array([0.7, 0.3, 1.2, 0.4, math.pi / 2, 0.5])


SIDEWAYS = homogeneous(
    rotz(np.arctan2(200.0, 300.0) + np.radians(25.0)) @ roty(np.radians(120.0)), [300.0, 200.0, 250.0]
)
ACROSS = homogeneous(rotx(-np.pi / 2), [400.0, 0.0, 300.0])


def _issue_31_goal() -> np.ndarray:
    """Issue 31's goal (as tests/viz/test_mk3_figures.py builds it): the wrist circle partly out of reach."""
    p = np.array([134.71, 191.34, -107.83])
    er = np.array([p[0], p[1], 0.0]) / np.hypot(p[0], p[1])
    m = np.array([-er[1], er[0], 0.0])
    t, b = np.radians(9.85), np.radians(7.07)
    z = np.cos(t) * (np.cos(b) * er + np.sin(b) * np.array([0.0, 0.0, 1.0])) + np.sin(t) * m
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    return homogeneous(np.column_stack([x, np.cross(z, x), z]), p)


def _puma_walk():
    a2, a3, d3, d4 = PUMA.lengths.values()
    W = [a2 + a3, d3, -d4]
    P = [[0, 0, 0], [0, 0, 0], [a2, 0, 0], [a2 + a3, d3, 0], W, W]
    U = [[0, 0, 1], [0, 1, 0], [0, 1, 0], [0, 0, -1], [0, 1, 0], [0, 0, -1]]
    return frame_steps(P, U)


def _viewer_still():
    v = RobotViewer(PUMA, "qn")
    v.show_ik(PUMA.ik(PUMA.fk(PUMA.q("qn"))), selected=0)
    fig, ax = new_axes()
    v._draw_static(ax)
    return fig


def _first(x):
    return x[0] if isinstance(x, tuple) else x


FIGURES = {
    "arms.plot_robot": lambda: arms.plot_robot(PUMA, PUMA.q("qn"))[0],
    "dh.plot_step_dimensions": lambda: dh_figures.plot_step_dimensions(_puma_walk(), 3),
    "ik.plot_solutions": lambda: ik_figures.plot_solutions(PUMA, PUMA.ik(PUMA.fk(Q_PUMA))),
    "ik.plot_wrist_flip": lambda: ik_figures.plot_wrist_flip(PUMA, *PUMA.ik(PUMA.fk(Q_PUMA)).q[:2]),
    "ik.plot_shoulder_top_view": lambda: ik_figures.plot_shoulder_top_view(PUMA, PUMA.fk(Q_PUMA)),
    "ik.plot_workspace": lambda: ik_figures.plot_workspace(
        PUMA.fk(np.random.default_rng(0).uniform(-np.pi, np.pi, (300, 6)))[:, :3, 3],
        units="m",
        title="t",
        top_circles=[((0, 0), 0.15, "ρ = d3", "tab:red")],
        side_lines=[(0.15, "ρ = d3", "tab:red")],
        side_floor=(-0.35, "floor"),
    ),
    "ik.plot_singularity_sweeps": lambda: ik_sweeps.plot_singularity_sweeps(PUMA, Q_PUMA, n=61),
    "mk3.plot_nearest_attainable": lambda: mk3_figures.plot_nearest_attainable(
        MK, [SIDEWAYS, ACROSS], ["sideways", "across"]
    ),
    "mk3.plot_wrist_circle": lambda: mk3_figures.plot_wrist_circle(MK, _issue_31_goal(), "issue 31"),
    "path.joint_path_figure": lambda: path_figures.joint_path_figure(
        [np.linspace(0, 1, 20)[:, None] * [1.0, -0.5, 0.3]] * 2, titles=["nearest", "naive"]
    )[0],
    "porter.plot_frames": lambda: porter_figures.plot_frames(PORTER, [Q_PORTER]),
    "porter.plot_solutions": lambda: porter_figures.plot_solutions(PORTER, PORTER.ik(PORTER.fk(Q_PORTER))),
    "porter.plot_construction": lambda: porter_figures.plot_construction(PORTER, PORTER.fk(Q_PORTER), near=Q_PORTER),
    "porter.plot_parallel_planes": lambda: porter_figures.plot_parallel_planes(
        PORTER, PORTER.fk(Q_PARALLEL), Q_PARALLEL
    ),
    "rotation.plot_fixed_vs_moving": lambda: rotation_figures.plot_fixed_vs_moving(rotz(np.pi / 2), rotx(np.pi / 2))[0],
    "rotation.plot_frame_sequence": lambda: rotation_figures.plot_frame_sequence(
        [rotz(0.3 * k) for k in range(3)], ["a", "b", "c"]
    )[0],
    "rotation.plot_euler_steps": lambda: rotation_figures.plot_euler_steps([0.5, 0.7, 0.3])[0],
    "three_step.plot_steps": lambda: three_step.plot_steps(
        ThreeStepArm(1.5, 1.0).three_step(np.array([0.5, 0.5, 2.0]), np.diag([-1.0, 1.0, -1.0]))
    ),
    "three_step.plot_triangle": lambda: three_step.plot_triangle(ThreeStepArm(1.5, 1.0), np.array([0.5, 0.5, 2.0])),
    "viewer still (with IK ghosts)": _viewer_still,
}


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_no_lines_told_apart_by_colour_alone(name, course_style):
    fig = _first(FIGURES[name]())
    assert colour_only_lines(fig) == [], name


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_every_text_keeps_4_5_to_1(name, course_style):
    fig = _first(FIGURES[name]())
    assert low_contrast_texts(fig) == [], name


def test_the_course_colours_for_text_have_4_5_to_1_on_white():
    # hand-worked: tab:green #2ca02c has relative luminance 0.2582, so (1.05) / (0.3082) = 3.41 < 4.5
    assert contrast_ratio("tab:green") == pytest.approx(3.41, abs=0.01)
    for colour in [*AXIS_COLORS, NORMAL_COLOR, JOINT_COLOR, "tab:orange", "tab:olive", "0.55", "0.6"]:
        darker = text_color(colour)
        assert contrast_ratio(darker) >= 4.5, colour
        if contrast_ratio(colour) >= 4.5:
            assert darker == colour  # a readable colour is kept as it is
    assert contrast_ratio("black", "white") == pytest.approx(21.0)
    assert contrast_ratio("#777777", "#fbfbfb") == pytest.approx(4.33, abs=0.01)  # the issue's faint labels


def test_the_colour_check_fails_on_lines_told_apart_by_colour_alone():
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1], color="tab:blue", label="nearest")
    ax.plot([0, 1], [1, 0], color="tab:orange", label="naive")
    (found,) = colour_only_lines(fig)
    assert "'nearest' and 'naive'" in found
    ax.lines[1].set_linestyle("--")  # a second cue: passes
    assert colour_only_lines(fig) == []
    ax.lines[1].set_linestyle("-")
    ax.lines[1].set_linewidth(4.0)  # twice as wide: passes
    assert colour_only_lines(fig) == []
    ax.lines[1].set_linewidth(2.0)
    ax.text(1, 0, "naive", color=text_color("tab:orange"))  # a direct label in its colour: passes
    assert colour_only_lines(fig) == []
    fig2, ax2 = plt.subplots()
    ax2.plot([0, 1], [0, 1], "o", color="tab:red")
    ax2.plot([0, 1], [1, 0], "o", color="tab:green")  # red and green dots: the classic failure
    assert len(colour_only_lines(fig2)) == 1
    ax2.lines[1].set_color("0.1")  # dark grey against red: 3:1 lightness, passes
    assert colour_only_lines(fig2) == []


def test_the_contrast_check_fails_on_faint_text():
    fig, ax = plt.subplots()
    ax.set_title("title")
    ax.text(0.5, 0.5, "faint", color="0.6")
    ax.set_xlabel("x", color="tab:green")
    found = low_contrast_texts(fig)
    assert len(found) == 2 and any("'faint'" in f for f in found) and any("'x'" in f for f in found)
    ax.set_facecolor("black")
    assert any("'title'" not in f and "'x'" in f for f in low_contrast_texts(fig))  # the label is on the figure
