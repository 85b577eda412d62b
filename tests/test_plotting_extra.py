"""Tests of the PUMA-560 drawing helpers (puma_points, draw_puma) on the Agg backend."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from puma_course import plotting as P  # noqa: E402
from puma_course.robots import puma560  # noqa: E402


@pytest.fixture(autouse=True)
def _close_all():
    yield
    plt.close("all")


ARM = puma560()
L = ARM.lengths


def test_puma_points_at_qz_match_the_hand_worked_positions():
    # At θ = 0 the position formula of lecture 09 gives p = (a2 + a3, d3, -d4); the shoulder offset
    # d3 points along z2 = +y0, the upper arm a2 along x0, the forearm d4 down along -z0.
    a2, a3, d3, d4 = L["a2"], L["a3"], L["d3"], L["d4"]
    expected = np.array(
        [[0, 0, -0.2], [0, 0, 0], [0, d3, 0], [a2, d3, 0], [a2 + a3, d3, 0], [a2 + a3, d3, -d4]], dtype=float
    )
    got = P.puma_points(ARM.frames(np.zeros(6)), d3, a3, pedestal=0.2)
    np.testing.assert_allclose(got, expected, atol=1e-12)


def test_puma_points_segments_have_the_link_lengths_and_end_at_the_wrist():
    rng = np.random.default_rng(9)
    Q = rng.uniform(-np.pi, np.pi, (50, 6))
    pts = P.puma_points(ARM.frames(Q), L["d3"], L["a3"])  # batch (50, 7, 4, 4) -> (50, 6, 3)
    assert pts.shape == (50, 6, 3)
    seg = np.diff(pts, axis=1)
    lengths = np.linalg.norm(seg, axis=-1)
    np.testing.assert_allclose(lengths, np.broadcast_to([0.35, L["d3"], L["a2"], L["a3"], L["d4"]], (50, 5)))
    # offset ⊥ upper arm, a3 ⊥ forearm: the right angles of Craig's figure
    np.testing.assert_allclose(np.einsum("ni,ni->n", seg[:, 1], seg[:, 2]), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.einsum("ni,ni->n", seg[:, 3], seg[:, 4]), 0.0, atol=1e-12)
    # the last point is the wrist centre: the position column of the pose
    np.testing.assert_allclose(pts[:, -1], ARM.fk(Q)[:, :3, 3], atol=1e-12)
    # the batch equals point-by-point
    np.testing.assert_allclose(pts[7], P.puma_points(ARM.frames(Q[7]), L["d3"], L["a3"]))


def test_draw_puma_artists_and_bad_input():
    fig, ax = P.new_axes()
    F = ARM.frames(ARM.q("qn"))
    arts = P.draw_puma(ax, F, L["d3"], L["a3"], color="tab:blue", alpha=0.3, label="ghost")
    assert len(arts) == 5  # pedestal, links, triad
    assert arts[1].get_color() == "tab:blue" and arts[1].get_alpha() == 0.3 and arts[1].get_label() == "ghost"
    xs, ys, zs = arts[1].get_data_3d()
    np.testing.assert_allclose([xs[-1], ys[-1], zs[-1]], ARM.fk(ARM.q("qn"))[:3, 3])
    assert len(P.draw_puma(ax, F, L["d3"], L["a3"], wrist_frame=False)) == 2
    fig.canvas.draw()
    with pytest.raises(ValueError, match="frames"):
        P.draw_puma(ax, F[:4], L["d3"], L["a3"])
    with pytest.raises(ValueError, match="frames"):
        P.puma_points(np.zeros((7, 3, 3)), L["d3"], L["a3"])
