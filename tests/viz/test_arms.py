"""Drawing arms (puma_course.viz.arms) on the Agg backend.

Truths used here: the drawn lines' data against the robot's own points and frames (the robot
API is the one source of what is drawn), the PUMA-560's points at θ = 0 worked by hand from
the position formula of lecture 09, the link lengths and right angles of Craig's figure, and
the pixel size of the animation frames (inches x dpi).
"""

from __future__ import annotations

import numpy as np
import pytest

from puma_course import MK3, DHChain, Link, Porter, Puma560, ThreeStepArm
from puma_course.viz import arms as A
from puma_course.viz.animation import jshtml
from puma_course.viz.frames import new_axes
from puma_course.viz.style import use_course_style
from tests.support import jshtml_png_sizes, random_q

ARM = Puma560()
L = ARM.lengths
ROBOTS = [
    Puma560(),
    MK3(),
    Porter(1.0, 0.5, 0.3),
    ThreeStepArm(1.5, 1.0),
    DHChain([Link(0, 0), Link(-np.pi / 2, 0, kind="P"), Link(0, 0.5)], name="RPR", units="m"),
]


def _ranges(ax):
    return np.array([np.ptp(ax.get_xlim3d()), np.ptp(ax.get_ylim3d()), np.ptp(ax.get_zlim3d())])


def _xyz(line):
    return np.transpose(line.get_data_3d())


# ---- the PUMA-560's points (what draw_robot draws for it) --------------------------------------


def test_puma_points_at_qz_match_the_hand_worked_positions():
    # At θ = 0 the position formula of lecture 09 gives p = (a2 + a3, d3, -d4); the shoulder offset
    # d3 points along z2 = +y0, the upper arm a2 along x0, the forearm d4 down along -z0.
    a2, a3, d3, d4 = L["a2"], L["a3"], L["d3"], L["d4"]
    arm = Puma560()
    arm.pedestal = 0.2  # the foot is drawn this far below the base origin
    expected = np.array(
        [[0, 0, -0.2], [0, 0, 0], [0, d3, 0], [a2, d3, 0], [a2 + a3, d3, 0], [a2 + a3, d3, -d4]], dtype=float
    )
    np.testing.assert_allclose(arm.points(np.zeros(6)), expected, atol=1e-12)
    np.testing.assert_allclose(ARM.points(np.zeros(6))[0], [0.0, 0.0, -0.35], atol=1e-12)  # the default pedestal


def test_puma_points_segments_have_the_link_lengths_and_end_at_the_wrist():
    Q = random_q(6, seed=9, N=50)
    pts = ARM.points(Q)  # batch (50, 6) -> (50, 6, 3)
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
    np.testing.assert_allclose(pts[7], ARM.points(Q[7]))


# ---- draw_robot ----------------------------------------------------------------------------------


def test_draw_robot_artists_and_bad_input():
    fig, ax = new_axes()
    q = ARM.q("qn")
    arts = A.draw_robot(ax, ARM, q, color="tab:blue", alpha=0.3, label="ghost")
    assert len(arts) == 4  # links and the hand triad's 3 lines (no texts unless asked)
    links = arts[0]
    assert links.get_color() == "tab:blue" and links.get_alpha() == 0.3 and links.get_label() == "ghost"
    np.testing.assert_array_equal(_xyz(links), ARM.points(q))  # exactly the robot's polyline: offset d3 visible
    np.testing.assert_allclose(_xyz(links)[-1], ARM.fk(q)[:3, 3])  # ... ending at the wrist centre
    arts = A.draw_robot(ax, ARM, q, triads=[0, -1], labels=["{0}", "", "", "", "", "", "{6}"])
    # a labelled triad has its axes lettered x, y, z too (issue 25)
    assert [a.get_text() for a in arts if hasattr(a, "get_text")] == ["{0}", "x", "y", "z", "{6}", "x", "y", "z"]
    assert len(arts) == 1 + 2 * (4 + 3)
    assert len(A.draw_robot(ax, ARM, q, triads="none")) == 1
    fig.canvas.draw()
    with pytest.raises(ValueError, match="q"):
        A.draw_robot(ax, ARM, q[:4])
    with pytest.raises(ValueError, match="q"):
        A.draw_robot(ax, ARM, np.zeros((7, 3, 3)))
    with pytest.raises(ValueError, match="robot"):
        A.draw_robot(ax, ARM.frames(q), q)
    with pytest.raises(ValueError, match="triads"):
        A.draw_robot(ax, ARM, q, triads="hand")
    with pytest.raises(ValueError, match="triads"):
        A.draw_robot(ax, ARM, q, triads=[7])
    with pytest.raises(ValueError, match="labels"):
        A.draw_robot(ax, ARM, q, labels=["{0}"])


@pytest.mark.parametrize("robot", ROBOTS, ids=lambda r: r.name)
def test_draw_robot_draws_the_robot_points_and_frames(robot):
    fig, ax = new_axes()
    q = random_q(robot.n, seed=3)
    q = np.clip(q, robot.qlim[:, 0], robot.qlim[:, 1])
    arts = A.draw_robot(ax, robot, q, triads="all", length=0.25)
    np.testing.assert_array_equal(_xyz(arts[0]), robot.points(q))
    F = robot.frames(q)
    lines = arts[1:]
    assert len(lines) == 3 * len(F)  # no texts: every label empty
    for i, T in enumerate(F):  # triad i: the columns of frame i's rotation, 0.25 long, from its origin
        for k in range(3):
            np.testing.assert_allclose(_xyz(lines[3 * i + k]), [T[:3, 3], T[:3, 3] + 0.25 * T[:3, k]], atol=1e-12)
    # the last frame is the end effector: its pose is fk(q)
    np.testing.assert_allclose(F[-1], robot.fk(q), atol=1e-9)


def test_draw_robot_default_triad_length_is_a_fixed_share_of_the_link_length():
    fig, ax = new_axes()
    arm = ThreeStepArm(1.5, 1.0)  # links 1.5 and 1.0: the triads are 0.08 * 2.5 = 0.2 long in every pose
    for q in (np.zeros(6), random_q(6, seed=1)):
        arts = A.draw_robot(ax, arm, q)
        x = _xyz(arts[1])
        assert np.linalg.norm(x[1] - x[0]) == pytest.approx(0.2)


def test_draw_robot_ghosts_of_every_ik_solution():
    fig, ax = new_axes()
    sol = ARM.ik(ARM.fk(ARM.q("qn")))
    arts = A.draw_robot(ax, ARM, sol.q, alpha=0.4, triads="none", axes=True, label="ik")
    links = [a for a in arts if a.get_marker() == "o"]
    assert len(links) == len(sol) == 8
    for line, q in zip(links, sol.q, strict=True):
        np.testing.assert_array_equal(_xyz(line), ARM.points(q))
        np.testing.assert_allclose(_xyz(line)[-1], ARM.fk(ARM.q("qn"))[:3, 3], atol=1e-9)  # one wrist centre
    assert [ln.get_label() for ln in links].count("ik") == 1  # one legend entry
    assert len(arts) == 8 * (1 + 7)  # links and 7 dashed joint axes per arm


def test_plot_robot_frames_every_point_with_equal_scaling():
    q = MK3().q("qr")
    fig, ax = A.plot_robot(MK3(), q, triads="all")
    assert ax.get_title() == "Motoman MK3"
    r = _ranges(ax)
    np.testing.assert_allclose(r, r[0])
    P = np.vstack([MK3().points(q), np.zeros((1, 3))])
    for k, lim in enumerate([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]):
        assert lim[0] <= P[:, k].min() and lim[1] >= P[:, k].max()
    np.testing.assert_array_equal(_xyz(ax.lines[0]), MK3().points(q))


# ---- chains from frames, animations --------------------------------------------------------------


def test_draw_chain_and_plot_chain_for_both_robots():
    for arm in (Puma560(), MK3()):
        F = arm.frames(arm.q("qz"))
        fig, ax = A.plot_chain(F, title=arm.name)
        r = _ranges(ax)
        np.testing.assert_allclose(r, r[0])
        assert ax.get_title() == arm.name
        np.testing.assert_array_equal(_xyz(ax.lines[0]), F[:, :3, 3])  # links through the frame origins
        fig.canvas.draw()  # renders without error
    with pytest.raises(ValueError, match="frames"):
        A.draw_chain(ax, np.zeros((3, 3)))


def test_animate_frames_to_jshtml():
    arm = Puma560()
    Q = np.linspace(arm.q("qz"), arm.q("qr"), 3)
    seq = arm.frames(Q)
    calls = []

    def extra(ax, t):
        calls.append(t)
        return A.draw_points(ax, np.array([[0.3, 0.0, 0.2]]), color="k")

    anim = A.animate_frames(seq, extra=extra, title="qz to qr", dpi=40, figsize=(3, 3))
    html = anim.to_jshtml()
    assert "<img" in html and html.count("data:image/png;base64") >= 3
    assert set(calls) >= {0, 1, 2}
    assert set(jshtml_png_sizes(html)) == {(120, 120)}  # 3 x 3 inches at 40 dpi: the dpi was kept


def test_animate_robot_draws_each_pose_and_keeps_the_dpi():
    arm = Porter(1.0, 0.5, 0.3)
    Q = np.linspace([0.0, 0.0, 0.5, 0.0, 0.0, 0.0], [1.0, -0.5, 1.5, 0.5, 0.5, 0.5], 4)
    seen = {}

    def extra(ax, t):
        seen[t] = _xyz(ax.lines[0]).copy()  # the links drawn for pose t
        return []

    anim = A.animate_robot(arm, Q, extra=extra, triads="none", dpi=30, figsize=(4.0, 2.0))
    use_course_style()  # its savefig.dpi (110) must not leak into the frames shown through jshtml
    sizes = jshtml_png_sizes(jshtml(anim).data)
    assert sizes == [(120, 60)] * 4
    for t in range(4):
        np.testing.assert_array_equal(seen[t], arm.points(Q[t]))
    with pytest.raises(ValueError, match="q"):
        A.animate_robot(arm, Q[:, :5])
