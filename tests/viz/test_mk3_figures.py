"""Lecture 04's figure of the nearest attainable pose: what it draws, checked against projections worked here."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from puma_course import MK3  # noqa: E402
from puma_course.transforms import homogeneous, rotx, roty, rotz  # noqa: E402
from puma_course.viz.mk3_figures import ARROW, plot_nearest_attainable  # noqa: E402

ARM = MK3()
BETA = np.arctan2(200.0, 300.0)
SIDEWAYS = homogeneous(rotz(BETA + np.radians(25.0)) @ roty(np.radians(120.0)), [300.0, 200.0, 250.0])
ACROSS = homogeneous(rotx(-np.pi / 2), [400.0, 0.0, 300.0])


def test_the_arrows_are_the_goals_approach_and_its_projection_onto_the_arm_plane():
    fig = plot_nearest_attainable(ARM, [SIDEWAYS, ACROSS], ["sideways", "across"])
    top, side = fig.axes
    tips = {tuple(np.round(a.xy, 6)) for a in top.texts}
    p, z = SIDEWAYS[:3, 3], SIDEWAYS[:3, 2]
    m = np.array([-np.sin(BETA), np.cos(BETA), 0.0])
    zn = (z - (m @ z) * m) / np.linalg.norm(z - (m @ z) * m)  # the projection, worked here
    assert tuple(np.round(p[:2] + ARROW * z[:2], 6)) in tips  # the goal's approach
    assert tuple(np.round(p[:2] + ARROW * zn[:2], 6)) in tips  # the nearest, along the plane
    assert tuple(np.round(ACROSS[:2, 3] + ARROW * ACROSS[:2, 2], 6)) in tips
    assert len(top.texts) == 3  # the across goal's nearest points straight down: a cross, no arrow
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
