"""Smoke tests of the drawing helpers on the Agg backend (no display)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from puma_course import mk3, puma560  # noqa: E402
from puma_course import plotting as P  # noqa: E402
from puma_course.transforms import homogeneous, rotz  # noqa: E402


@pytest.fixture(autouse=True)
def _close_all():
    yield
    plt.close("all")


def _ranges(ax):
    return np.array([np.ptp(ax.get_xlim3d()), np.ptp(ax.get_ylim3d()), np.ptp(ax.get_zlim3d())])


def test_set_equal_gives_equal_ranges_and_frames_the_points():
    fig, ax = P.new_axes(title="t")
    pts = np.array([[0.0, 0.0, 0.0], [4.0, 1.0, 0.5], [-1.0, 2.0, 0.2]])
    P.set_equal(ax, pts)
    r = _ranges(ax)
    np.testing.assert_allclose(r, r[0])
    assert r[0] >= 5.0  # the x extent (-1..4) fits
    for k, lim in enumerate([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]):
        assert lim[0] <= pts[:, k].min() and lim[1] >= pts[:, k].max()
    # without points: uses what the axes currently show, still equal
    ax.set_xlim3d(0, 10)
    P.set_equal(ax)
    r = _ranges(ax)
    np.testing.assert_allclose(r, r[0])


def test_draw_frame_axes_point_along_rotation_columns():
    fig, ax = P.new_axes()
    T = homogeneous(rotz(np.pi / 2), [1.0, 2.0, 3.0])
    arts = P.draw_frame(ax, T, label="{1}", length=0.5)
    assert len(arts) == 4  # three axes + a label
    x_line = arts[0]
    xs, ys, zs = x_line.get_data_3d()
    np.testing.assert_allclose([xs[1] - xs[0], ys[1] - ys[0], zs[1] - zs[0]], [0.0, 0.5, 0.0], atol=1e-12)
    assert x_line.get_color() == "tab:red"


def test_draw_chain_and_plot_chain_for_both_robots():
    for arm in (puma560(), mk3()):
        F = arm.frames(arm.q("qz"))
        fig, ax = P.plot_chain(F, title=arm.name)
        r = _ranges(ax)
        np.testing.assert_allclose(r, r[0])
        assert ax.get_title() == arm.name
        fig.canvas.draw()  # renders without error
    with pytest.raises(ValueError, match="frames"):
        P.draw_chain(ax, np.zeros((3, 3)))


def test_draw_points_and_frames():
    fig, ax = P.new_axes()
    P.draw_points(ax, np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.0]]))
    arts = P.draw_frames(ax, np.stack([np.eye(4)] * 3))
    assert len(arts) == 3 * 4


def test_animate_frames_to_jshtml():
    arm = puma560()
    Q = np.linspace(arm.q("qz"), arm.q("qr"), 3)
    seq = arm.frames(Q)
    calls = []

    def extra(ax, t):
        calls.append(t)
        return P.draw_points(ax, np.array([[0.3, 0.0, 0.2]]), color="k")

    anim = P.animate_frames(seq, extra=extra, title="qz to qr", dpi=40, figsize=(3, 3))
    html = anim.to_jshtml()
    assert "<img" in html and html.count("data:image/png;base64") >= 3
    assert set(calls) >= {0, 1, 2}
