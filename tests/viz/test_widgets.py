"""Joint panels (puma_course.viz.widgets): built without a browser; the kinematics must receive radians.

Truths used here: degrees converted to radians by hand-worked numbers, poses worked by hand
(the PUMA-560 at θ = 0 and θ2 = 90°, the MK3 at θ1 = 90°, an RP arm), the robots' own points
for what is sent to the viewer, and Craig's link matrix worked by hand for the one-link panel.
What the browser draws from it is checked in tests/browser.
"""

from __future__ import annotations

import base64
import re
import warnings

import numpy as np
import pytest

from puma_course import MK3, DHChain, Link, Porter, Puma560
from puma_course.viz import Panel, RobotViewer, dh_link_panel, joint_sliders, robot_panel


def _sent(panel):
    """What the last update sent to the browser: frames (m, 4, 4) and link points (p, 3)."""
    pose = panel.viewer.pose
    return np.reshape(pose["frames"], (-1, 4, 4)), np.reshape(pose["points"], (-1, 3))


class SpyPuma(Puma560):
    """A PUMA-560 that records every joint vector its frames are computed for."""

    def __init__(self) -> None:
        super().__init__()
        self.seen: list[np.ndarray] = []

    def frames(self, q):
        self.seen.append(np.array(q))
        return super().frames(q)


# ---- joint_sliders -------------------------------------------------------------------------------


def test_joint_sliders_labels_and_units():
    s = joint_sliders(
        ["θ1", "θ2", "d3"], [-np.pi, -np.pi / 2, 0.0], [np.pi, np.pi / 2, 0.5], degrees=[1, 1, 0], units="m"
    )
    assert [x.description for x in s] == ["θ1 [deg]", "θ2 [deg]", "d3 [m]"]
    assert s[0].min == pytest.approx(-180.0) and s[0].max == pytest.approx(180.0)
    assert s[1].max == pytest.approx(90.0)
    assert s[2].max == pytest.approx(0.5)  # lengths are not converted
    s[0].value = 45.0
    s[2].value = 0.25
    np.testing.assert_allclose(s.radians(), [np.pi / 4, 0.0, 0.25])


def test_joint_sliders_unitless_lengths_and_bare_names():
    assert joint_sliders(["q2"], 0.0, 2.0, degrees=False, units="")[0].description == "q2 [length]"
    assert joint_sliders(["d"], 0.0, 2.0, degrees=False)[0].description == "d"
    s = joint_sliders(["θ", "d"], [-np.pi, 1.0], [np.pi, 2.0], degrees=[True, False])
    assert [x.value for x in s] == [0.0, 1.5]  # 0 where the range allows it, else the middle
    s.set_radians([-np.pi / 2, 1.25])
    assert [x.value for x in s] == [-90.0, 1.25]


def test_joint_sliders_bad_input():
    with pytest.raises(ValueError, match="highs"):
        joint_sliders(["θ1"], [1.0], [0.0])
    with pytest.raises(ValueError, match="lows"):
        joint_sliders(["θ1", "θ2"], [0.0, 0.0, 0.0], 1.0)


# ---- robot_panel ---------------------------------------------------------------------------------


def test_robot_panel_passes_radians_to_the_robot_and_sends_its_frames():
    arm = SpyPuma()
    panel = robot_panel(arm, readout="pose")
    assert isinstance(panel, Panel) and isinstance(panel.viewer, RobotViewer)
    assert [s.description for s in panel.sliders] == [f"θ{i} [deg]" for i in range(1, 7)]
    assert panel.sliders[0].min == pytest.approx(-180.0) and panel.sliders[0].max == pytest.approx(180.0)
    assert all(s.continuous_update for s in panel.sliders)  # the arm follows a dragged slider
    # initial pose at q = 0: hand-worked p = (a2 + a3, d3, -d4)
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [0.4318 + 0.0203, 0.15005, -0.4318], atol=1e-12)
    panel.sliders[1].value = 90.0  # the student sees degrees ...
    q = np.array([0.0, np.pi / 2, 0.0, 0.0, 0.0, 0.0])  # ... the kinematics sees radians
    np.testing.assert_allclose(arm.seen[-1], q, atol=1e-12)
    # θ2 = 90° turns the arm about +y0: p = (-d4, d3, -(a2 + a3)), R = Ry(90°) diag(1, -1, -1), by hand
    T = np.array([[0, 0, -1, -0.4318], [0, -1, 0, 0.15005], [-1, 0, 0, -0.4521], [0, 0, 0, 1]])
    np.testing.assert_allclose(panel.last_frames[-1], T, atol=1e-12)
    assert panel.last_readout.splitlines() == [
        "⁰T₆ =   (lengths in m)",
        "[[ 0.      0.     -1.     -0.4318]",
        " [ 0.     -1.      0.      0.15  ]",
        " [-1.      0.      0.     -0.4521]",
        " [ 0.      0.      0.      1.    ]]",
    ]
    assert "puma-readout" in panel.readout_widget.value and "⁰T₆" in panel.readout_widget.value
    # what is sent to the browser: the robot's polyline (the offset d3 visible) and its 7 frames, rounded to 1e-7
    F, P = _sent(panel)
    np.testing.assert_allclose(P, Puma560().points(q), atol=1e-7)
    np.testing.assert_allclose(F, Puma560().frames(q), atol=1e-7)
    assert panel.viewer.scene["title"] == "PUMA-560" and panel.viewer.scene["units"] == "m"
    assert [f["label"] for f in panel.viewer.scene["frames"]] == [f"{{{i}}}" for i in range(7)]


def test_a_slider_move_sends_only_the_pose():
    panel = robot_panel(MK3())
    scene = panel.viewer.scene
    sent = []
    panel.viewer.observe(lambda change: sent.append(change["name"]), names=["scene", "pose", "ghosts", "targets"])
    panel.sliders[0].value = 30.0
    assert sent == ["pose"] and panel.viewer.scene is scene
    assert len(panel.viewer.pose["frames"]) == 6 * 16 and len(panel.viewer.pose["points"]) == 6 * 3


def test_robot_panel_custom_readout():
    arm = MK3()
    panel = robot_panel(arm, readout=lambda q: f"sum={np.degrees(q).sum():.1f}")
    panel.set_radians([np.pi / 2, 0, 0, 0, -np.pi / 4])
    assert panel.last_readout == "sum=45.0"
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk([np.pi / 2, 0, 0, 0, -np.pi / 4]), atol=1e-9)
    # at θ1 = 90° the MK3 reaches along +y: p = (0, a1 + a2 + a3, d1 - d5) worked by hand
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [0.0, 600.0, 260.0], atol=1e-9)
    with pytest.raises(ValueError, match="readout"):
        robot_panel(arm, readout="nonsense")
    with pytest.raises(ValueError, match="robot"):
        robot_panel(arm.frames)
    with pytest.raises(ValueError, match="q"):
        robot_panel(arm, q=np.zeros((2, 5)))
    with pytest.raises(ValueError, match="labels"):
        robot_panel(arm, labels=["{0}"])


def test_robot_panel_starts_at_a_named_configuration():
    panel = robot_panel(MK3(), q="qr", readout=None)
    assert [s.value for s in panel.sliders] == [0.0, 90.0, -90.0, 0.0, 0.0]  # qr = (0, 90°, -90°, 0, 0)
    assert panel.last_readout is None
    np.testing.assert_allclose(panel.last_q, [0.0, np.pi / 2, -np.pi / 2, 0.0, 0.0], atol=1e-12)


def test_set_radians_keeps_the_exact_joint_vector_when_the_browser_snaps_the_sliders():
    arm = Puma560()
    panel = robot_panel(arm)
    q = np.array([0.1234, -0.5, 0.25, 1.0, 0.7, -0.2])
    panel.set_radians(q)
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk(q), atol=1e-12)
    # the browser rounds 7.07° to the 1° step and sends 7.0 back: an echo, not a move
    panel.sliders[0].value = 7.0
    np.testing.assert_allclose(panel.last_q, q, atol=0)
    panel.sliders[0].value = 20.0  # a real move
    np.testing.assert_allclose(panel.last_q, [np.radians(20.0), *q[1:]], atol=1e-12)


def test_robot_panel_with_a_prismatic_joint():
    # an RP arm: θ1 about z0, then a slide d2 along z2 = +y1; the hand is at d2 (-sin θ1, cos θ1, 0)
    arm = DHChain([Link(0, 0), Link(-np.pi / 2, 0, kind="P")], name="RP arm", units="m",
                  qlim=[(-np.pi, np.pi), (0.0, 2.0)])  # fmt: skip
    panel = robot_panel(arm)
    assert [s.description for s in panel.sliders] == ["θ1 [deg]", "d2 [m]"]
    assert (panel.sliders[1].min, panel.sliders[1].max) == (0.0, 2.0)  # a length: not converted
    panel.sliders[0].value = 90.0
    panel.sliders[1].value = 1.5
    np.testing.assert_allclose(panel.last_q, [np.pi / 2, 1.5], atol=1e-12)
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [-1.5, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(_sent(panel)[1], arm.points([np.pi / 2, 1.5]), atol=1e-7)


def test_robot_panel_porter_labels_units_and_stroke():
    arm = Porter(1.0, 0.5, 0.3)
    labels = ["{0}", "", "{2}", "{3}", "{4}", "{5}"]
    panel = robot_panel(arm, q=[0.5, -0.4, 1.2, 0.9, 0.6, -0.3], labels=labels)
    assert [s.description for s in panel.sliders] == [
        "α1 [deg]", "α2 [deg]", "q2 [length]", "α3 [deg]", "α4 [deg]", "α5 [deg]",
    ]  # fmt: skip
    assert panel.sliders[2].max == pytest.approx(2 * (1.0 + 0.5 + 0.3))  # the default stroke 2 (l1 + l3 + l4)
    assert panel.sliders[2].value == 1.2 and panel.sliders[0].value == pytest.approx(np.degrees(0.5))
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk([0.5, -0.4, 1.2, 0.9, 0.6, -0.3]), atol=1e-12)
    assert [f["label"] for f in panel.viewer.scene["frames"]] == labels
    assert panel.last_readout.splitlines()[0] == "⁰T₅ ="  # unitless: no unit said
    # at q = 0 (the lecture's check by hand): identity rotation, p5 = (l4, 0, l1 - l3)
    panel.set_radians(np.zeros(6))
    np.testing.assert_allclose(panel.last_frames[-1], [[1, 0, 0, 0.3], [0, 1, 0, 0], [0, 0, 1, 0.5], [0, 0, 0, 1]],
                               atol=1e-12)  # fmt: skip


def test_robot_panel_ik_ghosts_selector_and_go():
    arm = Puma560()
    q = np.radians([10.0, -30.0, 20.0, 10.0, 40.0, 10.0])
    panel = robot_panel(arm, q=q, ik=True)
    sol = arm.ik(arm.fk(q))
    assert len(panel.ik_selector.options) == 8
    assert sorted(label.split(": ", 1)[1] for label, _ in panel.ik_selector.options) == sorted(sol.labels)
    ghosts = panel.viewer.ghosts
    assert len(ghosts["arms"]) == 8 and ghosts["selected"] == 0
    # every ghost reaches the same hand pose (its last frame), the first one is q itself (nearest first)
    for g in ghosts["arms"]:
        np.testing.assert_allclose(np.reshape(g["frames"], (-1, 4, 4))[-1], arm.fk(q), atol=1e-6)
    np.testing.assert_allclose(panel.solutions.q[0], q, atol=1e-9)
    panel.ik_selector.value = 5
    assert panel.viewer.ghosts["selected"] == 5
    target, branch = panel.solutions.q[5], panel.solutions.labels[5]
    panel.ik_go.click()
    np.testing.assert_allclose(panel.last_q, target, atol=1e-12)
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk(q), atol=1e-12)  # the hand stays where it was
    # the branch moved to stays selected; nearest first, it is now the first solution: the arm itself
    assert panel.ik_selector.label == f"1: {branch}" and panel.viewer.ghosts["selected"] == 0
    assert "8 configurations" in panel.ik_status.value


def test_robot_panel_ik_at_a_singular_pose_says_so_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        panel = robot_panel(Puma560(), ik=True)  # q = 0: θ5 = 0, the wrist is singular
    assert "singular" in panel.ik_status.value and "θ5" in panel.ik_status.value


# ---- dh_link_panel -------------------------------------------------------------------------------


def test_dh_link_panel_matrix_matches_hand_worked_cases():
    panel = dh_link_panel()
    s = panel.sliders
    assert [x.description for x in s] == ["αᵢ₋₁ [deg]", "aᵢ₋₁ [length]", "θᵢ [deg]", "dᵢ [length]"]
    assert not any(c in x.description for x in s for c in "_^{}\\")  # plain Unicode, no TeX
    # α = 90°, a = 1, θ = 0, d = 0.5: Z_i = -Y_{i-1}, origin at (a, -d, 0) by hand
    s[0].value, s[1].value, s[2].value, s[3].value = 90.0, 1.0, 0.0, 0.5
    T = panel.last_frames[-1]
    np.testing.assert_allclose(T[:3, 3], [1.0, -0.5, 0.0], atol=1e-12)
    np.testing.assert_allclose(T[:3, 2], [0.0, -1.0, 0.0], atol=1e-12)
    assert panel.last_readout.startswith("ⁱ⁻¹Tᵢ =")
    np.testing.assert_allclose(panel.last_frames[0], np.eye(4))
    # the path sent through the four elementary steps: Rot(X, α) stays at the origin, Trans(X, a) moves
    # to (a, 0, 0), Rot(Z, θ) stays, Trans(Z, d) moves d along Z_i = -Y_{i-1}
    F, P = _sent(panel)
    np.testing.assert_allclose(P, [[0, 0, 0], [0, 0, 0], [1, 0, 0], [1, 0, 0], [1, -0.5, 0]], atol=1e-12)
    # after Rot(X, 90°) the intermediate frame's z axis is -y0
    np.testing.assert_allclose(F[1][:3, 2], [0.0, -1.0, 0.0], atol=1e-12)
    styles = panel.viewer.scene["frames"]
    assert [f["label"] for f in styles] == ["{i-1}", "", "", "", "{i}"]
    assert [f["faint"] for f in styles] == [False, True, True, True, False]


# ---- the picture left in the notebook ------------------------------------------------------------


def test_display_bundle_has_a_png_of_the_first_pose():
    panel = robot_panel(MK3())
    data = panel._repr_mimebundle_()
    data = data[0] if isinstance(data, tuple) else data
    # the PNG is inside an <img alt> in text/html, its only copy (JupyterLab shows an image/png without alt)
    assert set(data) >= {"application/vnd.jupyter.widget-view+json", "text/html", "text/plain"}
    assert "image/png" not in data
    m = re.fullmatch(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)" alt="([^"]{40,})">', data["text/html"])
    assert m, data["text/html"][:200]
    png = base64.b64decode(m.group(1))
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert 400 <= width <= 800 and 300 <= height <= 800  # about 620 x 480 at 110 dpi
    assert len(png) < 150_000
