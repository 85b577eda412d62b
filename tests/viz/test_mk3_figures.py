"""Lecture 04's figures of the nearest attainable pose: what they draw, checked against projections and distances
worked here."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from puma_course import MK3  # noqa: E402
from puma_course.transforms import homogeneous, rotx, roty, rotz  # noqa: E402
from puma_course.viz.mk3_figures import ARROW, plot_nearest_attainable, plot_wrist_circle  # noqa: E402

ARM = MK3()
BETA = np.arctan2(200.0, 300.0)
SIDEWAYS = homogeneous(rotz(BETA + np.radians(25.0)) @ roty(np.radians(120.0)), [300.0, 200.0, 250.0])
ACROSS = homogeneous(rotx(-np.pi / 2), [400.0, 0.0, 300.0])


def test_the_arrows_are_the_goals_approach_and_its_projection_onto_the_arm_plane():
    fig = plot_nearest_attainable(ARM, [SIDEWAYS, ACROSS], ["sideways", "across"])
    top, side = fig.axes
    arrows = [a for a in top.texts if not a.get_text()]  # the arrows (annotations without text)
    tips = {tuple(np.round(a.xy, 6)) for a in arrows}
    p, z = SIDEWAYS[:3, 3], SIDEWAYS[:3, 2]
    m = np.array([-np.sin(BETA), np.cos(BETA), 0.0])
    zn = (z - (m @ z) * m) / np.linalg.norm(z - (m @ z) * m)  # the projection, worked here
    assert tuple(np.round(p[:2] + ARROW * z[:2], 6)) in tips  # the goal's approach
    assert tuple(np.round(p[:2] + ARROW * zn[:2], 6)) in tips  # the nearest, along the plane
    assert tuple(np.round(ACROSS[:2, 3] + ARROW * ACROSS[:2, 2], 6)) in tips
    assert len(arrows) == 3  # the across goal's nearest points straight down: a cross, no arrow
    # each goal is also named beside its tool point (issue 34: not told apart by colour alone)
    names = {a.get_text(): tuple(np.round(a.xy, 6)) for a in top.texts if a.get_text()}
    assert names == {"sideways": tuple(np.round(p[:2], 6)), "across": tuple(np.round(ACROSS[:2, 3], 6))}
    assert any(line.get_marker() == "x" for line in top.lines)
    # face on: both arms end at the tool point, and the arrow follows the projection
    h = np.array([np.cos(BETA), np.sin(BETA), 0.0])
    arms = [line for line in side.lines if line.get_label() in ("front/up", "front/down")]
    assert len(arms) == 2
    for line in arms:
        assert np.allclose([line.get_xdata()[-1], line.get_ydata()[-1]], [p @ h, p[2]], atol=1e-6)
    (arrow,) = side.texts
    assert np.allclose(arrow.xy, [p @ h + ARROW * (zn @ h), p[2] + ARROW * zn[2]], atol=1e-6)
    plt.close(fig)


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: plot_nearest_attainable("MK3", [ACROSS], ["a"]), "arm: expected an MK3"),
        (lambda: plot_nearest_attainable(ARM, [np.eye(3)], ["a"]), "goals[0]: expected"),
        (lambda: plot_nearest_attainable(ARM, [], []), "goals: expected 1 to 4"),
        (lambda: plot_nearest_attainable(ARM, [ACROSS], "a"), "names: expected 1 strings"),
        (lambda: plot_nearest_attainable(ARM, [ACROSS], ["a", "b"]), "names: expected 1 strings"),
        (lambda: plot_nearest_attainable(ARM, [ACROSS], ["a"], face_on=1), "face_on"),
        (lambda: plot_nearest_attainable(ARM, [homogeneous(rotx(0.5), [2000.0, 0.0, 0.0])], ["far"]), "out of reach"),
        (lambda: plot_nearest_attainable(ARM, [homogeneous(rotx(0.5), [0.0, 0.0, 600.0])], ["up"]), "base axis"),
    ],
)
def test_bad_input(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)
    plt.close("all")


def issue_goal() -> np.ndarray:
    """Issue 31's goal: p = (134.71, 191.34, -107.83) mm, the approach 9.85° off the arm plane, its projection
    7.07° above the horizontal (its wrist point out of reach)."""
    p = np.array([134.71, 191.34, -107.83])
    er = np.array([p[0], p[1], 0.0]) / np.hypot(p[0], p[1])
    m = np.array([-er[1], er[0], 0.0])
    t, b = np.radians(9.85), np.radians(7.07)
    z = np.cos(t) * (np.cos(b) * er + np.sin(b) * np.array([0.0, 0.0, 1.0])) + np.sin(t) * m
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    return homogeneous(np.column_stack([x, np.cross(z, x), z]), p)


def test_the_wrist_circle_is_solid_exactly_where_joint_2_reaches_it():
    T = issue_goal()
    fig = plot_wrist_circle(ARM, T, "issue 31")
    d1, a1, a2, a3, d5 = ARM.lengths.values()
    p = np.array([np.hypot(T[0, 3], T[1, 3]), T[2, 3]])
    for ax in fig.axes:
        by_label = {line.get_label(): line for line in ax.lines}
        solid = by_label["wrist points it reaches"].get_xydata()
        dotted = by_label["wrist points p − d5 z′ the arm does not reach"].get_xydata()
        assert np.allclose(np.linalg.norm(dotted - p, axis=1), d5)  # the circle of radius d5 about p
        solid = solid[~np.isnan(solid).any(axis=1)]
        assert len(solid) > 100
        dist = np.stack([np.linalg.norm(solid - (j, d1), axis=1) for j in (a1, -a1)])
        within = ((dist >= abs(a2 - a3) - 1e-6) & (dist <= a2 + a3 + 1e-6)).any(axis=0)
        assert within.all()  # every solid point is in an annulus, worked here by distance
        # the two wrist points: the projection's out of reach, the nearest attainable one on the annulus's edge
        (cross,) = [ln for ln in ax.lines if ln.get_marker() == "X"]
        (dot,) = [ln for ln in ax.lines if ln.get_marker() == "o" and ln.get_color() == "tab:red"]
        assert np.hypot(cross.get_xdata()[0] - a1, cross.get_ydata()[0] - d1) > a2 + a3 + 10.0
        assert abs(np.hypot(dot.get_xdata()[0] - a1, dot.get_ydata()[0] - d1) - (a2 + a3)) < 1e-3
    assert "13.11°" in fig.legends[0].texts[-1].get_text()
    plt.close(fig)


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: plot_wrist_circle("MK3", issue_goal()), "arm: expected an MK3"),
        (lambda: plot_wrist_circle(ARM, np.eye(3)), "goal: expected"),
        (lambda: plot_wrist_circle(ARM, issue_goal(), 3), "name: expected a string"),
        (lambda: plot_wrist_circle(ARM, homogeneous(rotx(0.5), [0.0, 0.0, 600.0])), "goal: expected a tool point off"),
    ],
)
def test_wrist_circle_bad_input(call, fragment):
    with pytest.raises(ValueError) as err:
        call()
    assert fragment in str(err.value)
