"""Lecture 09's figures and the computations behind them, against independent truths.

The branch gaps are checked against the two roots of the θ1 and θ3 equations written out by hand
(not through the solver) and the flip identity; the labels against the drawn arm's geometry; the
sweeps against det J of the numeric Jacobian; the figures for what a reader sees (legends off the
data, tick labels apart, the flip pair's frame {4} turned over, the panel's picture at 110 dpi).
"""

from __future__ import annotations

import math
import struct
import warnings

import numpy as np
import pytest

from puma_course import MK3, Puma560
from puma_course.transforms import wrap_angle
from puma_course.viz import ik_figures as F
from puma_course.viz import new_axes, robot_panel

ARM = Puma560()
L = ARM.lengths
Q_TRUE = np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0])


def _random_q(n: int, seed: int = 3) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))


def _measured_label(q: np.ndarray) -> str:
    """The branch read off the drawn arm (lecture 09): sign of the reach X, the elbow above or below the line
    from the shoulder to the wrist centre (the arm's plane is vertical), the sign of θ5."""
    P = ARM.points(q)
    shoulder, elbow, wrist = P[2], P[3], P[5]
    reach = math.cos(q[0]) * wrist[0] + math.sin(q[0]) * wrist[1]
    line = (wrist - shoulder) / np.linalg.norm(wrist - shoulder)
    off = (elbow - shoulder) - ((elbow - shoulder) @ line) * line
    return "/".join(["left" if reach >= 0 else "right", "up" if off[2] > 0 else "down",
                     "noflip" if q[4] >= 0 else "flip"])  # fmt: skip


# ------------------------------------------------------------------------------------------------ branch gaps
def test_gaps_are_the_distances_to_the_other_root_of_each_equation():
    """θ1' = 2φ - π - θ1 (ρ sin(φ - θ1) = d3), θ3' = -θ3 - 2 atan2(d4, a3) (r cos(θ3 + ψ) = κ), θ5' = -θ5."""
    Q = _random_q(200)
    _, gaps = F.branch_gaps(ARM, Q)
    w = ARM.fk(Q)[:, :3, 3]
    phi = np.arctan2(w[:, 1], w[:, 0])
    t1_other = 2 * phi - np.pi - Q[:, 0]
    t3_other = -Q[:, 2] - 2 * math.atan2(L["d4"], L["a3"])
    np.testing.assert_allclose(gaps["shoulder"], np.abs(wrap_angle(Q[:, 0] - t1_other)), atol=1e-9)
    np.testing.assert_allclose(gaps["elbow"], np.abs(wrap_angle(Q[:, 2] - t3_other)), atol=1e-9)
    np.testing.assert_allclose(gaps["wrist"], np.abs(wrap_angle(2 * Q[:, 4])), atol=1e-9)


def test_labels_agree_with_the_drawn_arm():
    Q = _random_q(300, seed=11)
    labels, _ = F.branch_gaps(ARM, Q)
    assert labels == [_measured_label(q) for q in Q]
    assert len(set(labels)) == 8


def test_the_sign_of_det_j_is_minus_the_product_of_the_elbow_and_wrist_words():
    """det J = -a2 (a3 s3 + d4 c3) X s5; "up" is sign(X (a3 s3 + d4 c3)), "noflip" sign(s5)."""
    Q = _random_q(300, seed=5)
    labels, _ = F.branch_gaps(ARM, Q)
    det = np.linalg.det(ARM.jacobian(Q))
    for lab, d in zip(labels, det, strict=True):
        _, elbow, wrist = lab.split("/")
        assert np.sign(d) == -(1 if elbow == "up" else -1) * (1 if wrist == "noflip" else -1)


def _singular_poses() -> dict[str, np.ndarray]:
    c3, s3 = math.cos(0.4), math.sin(0.4)
    vx, vy = L["a2"] + L["a3"] * c3 - L["d4"] * s3, L["a3"] * s3 + L["d4"] * c3
    return {
        "elbow": np.array([0.5, -0.3, -math.atan2(L["d4"], L["a3"]), 0.2, 1.0, 0.1]),
        "shoulder": np.array([0.2, math.atan2(vx, vy), 0.4, 0.5, 0.7, -0.3]),
        "wrist": np.array([0.3, -0.6, 0.2, 0.9, 0.0, 0.4]),
    }


@pytest.mark.parametrize("word", ["shoulder", "elbow", "wrist"])
def test_the_gap_closes_exactly_at_the_singularity_and_only_its_own(word):
    q = _singular_poses()[word]
    _, gaps = F.branch_gaps(ARM, q[None])
    assert gaps[word][0] < 1e-6
    assert all(gaps[k][0] > 0.1 for k in gaps if k != word)


def test_at_the_shoulder_left_up_meets_right_down():
    """Near X = 0 the nearest other solution is right/down (θ3 equal), not right/up."""
    q = _singular_poses()["shoulder"].copy()
    q[1] += 1e-3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = ARM.ik(ARM.fk(q), near=q)
    own = sol.labels[0]
    s, e, w = own.split("/")
    other = {"left": "right", "right": "left"}[s] + "/" + {"up": "down", "down": "up"}[e] + "/" + w
    same_elbow = {"left": "right", "right": "left"}[s] + "/" + e + "/" + w
    d = {lab: float(np.linalg.norm(wrap_angle(qq - q))) for lab, qq in zip(sol.labels, sol.q, strict=True)}
    assert d[other] < 0.05 < d[same_elbow]


# ------------------------------------------------------------------------------------------------ sweeps
@pytest.mark.parametrize("word", ["shoulder", "elbow", "wrist"])
def test_a_sweep_crosses_one_zero_of_det_j_where_the_label_changes(word):
    s = F.singularity_sweep(ARM, Q_TRUE, word, n=120)  # no sample exactly on the zero
    q = Q_TRUE.copy()
    q[s["joint"]] = s["zero"]
    assert abs(np.linalg.det(ARM.jacobian(q))) < 1e-12  # the zero is a zero of det J
    sign = np.sign(s["det"])
    assert sign[0] == -sign[-1] and np.count_nonzero(np.diff(sign)) == 1  # one crossing
    part = {"shoulder": 0, "elbow": 1, "wrist": 2}[word]
    words = [lab.split("/")[part] for lab in s["labels"]]
    change = int(np.flatnonzero(np.diff(sign))[0])
    assert words[change] != words[change + 1] and len(set(words[: change + 1])) == len(set(words[change + 1 :])) == 1
    assert np.argmin(s["gap"]) in (change, change + 1) and s["gap"].min() < 0.05 * s["gap"].max()


def test_sweep_and_figure_refuse_what_they_cannot_draw():
    with pytest.raises(ValueError, match="word"):
        F.singularity_sweep(ARM, Q_TRUE, "knee")
    with pytest.raises(ValueError, match="arm"):
        F.singularity_sweep(MK3(), np.zeros(5), "wrist")
    with pytest.raises(ValueError, match="q0"):
        F.singularity_sweep(ARM, np.zeros(5), "wrist")
    with pytest.raises(ValueError, match="n"):
        F.singularity_sweep(ARM, Q_TRUE, "wrist", n=2.5)
    with pytest.raises(ValueError, match="frames"):
        F.draw_wrist(new_axes()[1], ARM, Q_TRUE, frames=(3,))
    far = np.eye(4)
    far[:3, 3] = [2.0, 0.0, 0.0]
    with pytest.raises(ValueError, match="T"):
        F.plot_shoulder_top_view(ARM, far)


# ------------------------------------------------------------------------------------------------ figures
def _tick_labels_apart(ax) -> bool:
    r = ax.figure.canvas.get_renderer()
    for labels in (ax.get_xticklabels(), ax.get_yticklabels()):
        boxes = [t.get_window_extent(r) for t in labels if t.get_text() and t.get_visible()]
        if any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1 :]):
            return False
    return True


def test_the_flip_pair_has_the_same_links_and_a_turned_over_frame_4():
    sol = ARM.ik(ARM.fk(Q_TRUE))
    fig, ax = new_axes()
    a = F.draw_wrist(ax, ARM, sol.q[0], frames=(4,), axes=False, labels=False)
    b = F.draw_wrist(ax, ARM, sol.q[1], frames=(4,), axes=False, labels=False)
    data = [np.array(x.get_data_3d()).T for x in (a + b)]  # forearm, flange, x4, y4, z4 per arm
    for k in (0, 1, 4):  # the forearm, the flange and z4: the same
        np.testing.assert_allclose(data[k], data[5 + k], atol=1e-12)
    for k in (2, 3):  # x4 and y4: reversed about the same origin
        np.testing.assert_allclose(data[k][1] - data[k][0], -(data[5 + k][1] - data[5 + k][0]), atol=1e-12)


def test_solutions_flip_pair_and_top_view_say_what_they_show():
    sol = ARM.ik(ARM.fk(Q_TRUE))
    fig = F.plot_solutions(ARM, sol)
    assert [ax.get_title() for ax in fig.axes] == list(sol.labels)
    fig = F.plot_wrist_flip(ARM, sol.q[0], sol.q[1], titles=sol.labels[:2])
    assert "θ4 = -140°" in fig.axes[1].get_title() and "θ5 = -60°" in fig.axes[1].get_title()
    fig = F.plot_shoulder_top_view(ARM, ARM.fk(Q_TRUE))
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "shoulder left: θ1 = 30.0°" in texts and "shoulder right: θ1 = -117.3°" in texts
    fig.canvas.draw()
    assert _tick_labels_apart(fig.axes[0])


def test_the_sweep_figure_has_readable_ticks():
    fig = F.plot_singularity_sweeps(ARM, Q_TRUE, n=61)
    fig.canvas.draw()
    assert all(_tick_labels_apart(ax) for ax in fig.axes)
    assert [ax.get_title() for ax in fig.axes[:3]] == ["shoulder: turn θ2", "elbow: turn θ3", "wrist: turn θ5"]


def test_the_workspace_legend_names_each_bound_once_and_covers_no_data():
    rng = np.random.default_rng(0)
    P = ARM.fk(rng.uniform(-np.pi, np.pi, (2000, 6)))[:, :3, 3]
    red = (L["d3"], "ρ = d3", "tab:red")
    fig = F.plot_workspace(P, units="m", title="PUMA-560", top_circles=[((0, 0), L["d3"], "ρ = d3", "tab:red")],
                           side_lines=[red], side_circles=[((0, 0), 0.877, "outer sphere", "k")])  # fmt: skip
    fig.canvas.draw()
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    assert texts == ["ρ = d3", "outer sphere"]
    r = fig.canvas.get_renderer()
    box = fig.legends[0].get_window_extent(r)
    assert not any(box.overlaps(ax.get_window_extent(r)) for ax in fig.axes)
    assert all(_tick_labels_apart(ax) for ax in fig.axes)
    assert fig.legends[0].get_texts()[0].get_fontsize() >= 9


def _png_dpi(png: bytes) -> float:
    i = png.find(b"pHYs")
    return struct.unpack(">I", png[i + 4 : i + 8])[0] * 0.0254


def test_the_ik_panels_picture_is_drawn_at_110_dpi_with_its_ghosts():
    panel = robot_panel(ARM, ik=True, q=Q_TRUE)
    assert round(_png_dpi(panel.viewer.static_png())) == 110
    assert len(panel.viewer.ghosts["arms"]) == 8  # the picture shows the solutions as ghosts


def test_top_view_and_workspace_dash_nothing_since_dashed_lines_mean_joint_axes():
    # issue 25: one meaning for a dashed line in every lecture; the arm plane and the bounds are not joint axes
    from puma_course.viz import ik_figures as ikf

    arm = Puma560()
    top = ikf.plot_shoulder_top_view(arm, arm.fk(np.radians([30, -50, 20, 40, 60, -30])))
    P = arm.fk(np.random.default_rng(0).uniform(-np.pi, np.pi, (300, 6)))[:, :3, 3]
    ws = ikf.plot_workspace(P, units="m", title="t", top_circles=[((0, 0), 0.15, "c", "k")],
                            side_circles=[((0, 0), 0.8, "r", "k")], side_lines=[(0.15, "l", "tab:red")])
    for fig in (top, ws):
        styles = {ln.get_linestyle() for ax in fig.axes for ln in ax.lines}
        assert "--" not in styles, styles


def test_workspace_floor_is_a_legend_entry_with_room_below_it():
    from puma_course.viz import ik_figures as ikf

    P = np.random.default_rng(1).uniform(-1.0, 1.0, (200, 3))
    fig = ikf.plot_workspace(P, units="m", title="t", side_floor=(-1.0, "floor, z = -1.00 m"))
    side = fig.axes[1]
    assert side.get_ylim()[0] < -1.0  # the floor line is not on the view's edge
    assert "floor, z = -1.00 m" in [t.get_text() for t in fig.legends[0].get_texts()]
    assert [t.get_text() for t in side.texts] == []  # no label at an edge of the view


def test_the_wrist_triads_are_lettered_and_their_letters_keep_apart():
    """Issue 25: the flip pair names each axis with its frame (x4 ... z6), the eight panels {4}'s x, y, z."""
    sol = ARM.ik(ARM.fk(Q_TRUE))
    fig = F.plot_wrist_flip(ARM, sol.q[0], sol.q[1], titles=sol.labels[:2])
    for ax in fig.axes:
        texts = [t for t in ax.texts if t.get_text()]
        assert sorted(t.get_text() for t in texts) == sorted(f"${a}_{j}$" for a in "xyz" for j in (4, 5, 6))
        assert _no_overlap(texts)
    fig = F.plot_solutions(ARM, sol)
    for ax in fig.axes:
        texts = [t for t in ax.texts if t.get_text()]
        assert [t.get_text() for t in texts] == ["x", "y", "z"] and _no_overlap(texts)


def _no_overlap(texts) -> bool:
    fig = texts[0].figure
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(r) for t in texts]
    inside = all(fig.bbox.contains(b.x0, b.y0) and fig.bbox.contains(b.x1, b.y1) for b in boxes)
    return inside and not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1 :])
