"""Slider panels (puma_course.viz.widgets): built without a display (Agg); the kinematics must receive radians.

Truths used here: degrees converted to radians by hand-worked numbers, poses worked by hand
(the PUMA-560 at θ = 0, the MK3 at θ1 = 90°, an RP arm), the robots' own points for what is
drawn, and Craig's link matrix worked by hand for the one-link panel.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

from puma_course import MK3, DHChain, Link, Porter, Puma560
from puma_course.viz import Panel, dh_link_panel, joint_sliders, robot_panel


def _xyz(line):
    return np.transpose(line.get_data_3d())


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
    assert joint_sliders(["q2"], 0.0, 2.0, degrees=False, units="")[0].description == "q2 []"
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


def test_robot_panel_passes_radians_to_the_robot():
    arm = SpyPuma()
    panel = robot_panel(arm, readout="pose")
    assert isinstance(panel, Panel)
    assert [s.description for s in panel.sliders] == [f"θ{i} [deg]" for i in range(1, 7)]
    assert panel.sliders[0].min == pytest.approx(-180.0) and panel.sliders[0].max == pytest.approx(180.0)
    # initial draw at q = 0: hand-worked p = (a2 + a3, d3, -d4)
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [0.4318 + 0.0203, 0.15005, -0.4318], atol=1e-12)
    panel.sliders[1].value = 90.0  # the student sees degrees ...
    q = np.array([0.0, np.pi / 2, 0.0, 0.0, 0.0, 0.0])  # ... the kinematics sees radians
    np.testing.assert_allclose(arm.seen[-1], q, atol=1e-12)
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk(q), atol=1e-12)
    # θ2 = 90° turns the arm down: p = (a3 c23 - d4 s23 + a2 c2, d3, -a3 s23 - a2 s2 - d4 c23) = (-d4, d3, -a2 - a3)
    np.testing.assert_allclose(arm.fk(q)[:3, 3], [-0.4318, 0.15005, -0.4521], atol=1e-12)
    assert "p = " in panel.last_readout and "R =" in panel.last_readout
    assert panel.last_readout.splitlines()[0] == "p = [-0.4318  0.15   -0.4521] m"
    # what is drawn is the robot's polyline (the offset d3 visible), not the frame origins
    np.testing.assert_allclose(_xyz(panel.last_axes.lines[0]), Puma560().points(q), atol=1e-12)
    assert panel.last_axes.get_title() == "PUMA-560 (m)"
    assert [t.get_text() for t in panel.last_axes.texts] == ["{0}", "{6}"]  # the base and the hand are named
    assert plt.get_fignums() == []  # every redraw closes its figure


def test_robot_panel_custom_readout_and_limits():
    arm = MK3()
    panel = robot_panel(arm, readout=lambda q: f"sum={np.degrees(q).sum():.1f}", limits=(-800, 800))
    panel.set_radians([np.pi / 2, 0, 0, 0, -np.pi / 4])
    assert panel.last_readout == "sum=45.0"
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk([np.pi / 2, 0, 0, 0, -np.pi / 4]), atol=1e-9)
    # at θ1 = 90° the MK3 reaches along +y: p = (0, a1 + a2 + a3, d1 - d5) worked by hand
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [0.0, 600.0, 260.0], atol=1e-9)
    assert panel.last_axes.get_xlim3d() == pytest.approx((-800, 800))
    with pytest.raises(ValueError, match="limits"):
        robot_panel(arm, limits=(1, 0))
    with pytest.raises(ValueError, match="readout"):
        robot_panel(arm, readout="nonsense")
    with pytest.raises(ValueError, match="robot"):
        robot_panel(arm.frames)
    with pytest.raises(ValueError, match="q"):
        robot_panel(arm, q=np.zeros((2, 5)))


def test_robot_panel_starts_at_a_named_configuration():
    panel = robot_panel(MK3(), q="qr", readout=None)
    assert [s.value for s in panel.sliders] == [0.0, 90.0, -90.0, 0.0, 0.0]  # qr = (0, 90°, -90°, 0, 0)
    assert panel.last_readout is None
    np.testing.assert_allclose(panel.last_q, [0.0, np.pi / 2, -np.pi / 2, 0.0, 0.0], atol=1e-12)


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
    np.testing.assert_allclose(_xyz(panel.last_axes.lines[0]), arm.points([np.pi / 2, 1.5]), atol=1e-12)


def test_robot_panel_porter_labels_units_and_stroke():
    arm = Porter(1.0, 0.5, 0.3)
    panel = robot_panel(arm, q=[0.5, -0.4, 1.2, 0.9, 0.6, -0.3])
    assert [s.description for s in panel.sliders] == [
        "α1 [deg]", "α2 [deg]", "q2 []", "α3 [deg]", "α4 [deg]", "α5 [deg]",
    ]  # fmt: skip
    assert panel.sliders[2].max == pytest.approx(2 * (1.0 + 0.5 + 0.3))  # the default stroke 2 (l1 + l3 + l4)
    assert panel.sliders[2].value == 1.2 and panel.sliders[0].value == pytest.approx(np.degrees(0.5))
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk([0.5, -0.4, 1.2, 0.9, 0.6, -0.3]), atol=1e-12)
    assert panel.last_readout.splitlines()[0].startswith("p = [") and panel.last_readout.splitlines()[0][-1] == "]"
    # the automatic view is a cube holding the base origin and the arm as drawn
    ax = panel.last_axes
    lims = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()])
    np.testing.assert_allclose(np.ptp(lims, axis=1), np.ptp(lims[0]))
    P = np.vstack([arm.points(panel.last_q), np.zeros((1, 3))])
    assert np.all(lims[:, 0] <= P.min(axis=0)) and np.all(lims[:, 1] >= P.max(axis=0))


# ---- dh_link_panel, the kernel route -------------------------------------------------------------


def test_dh_link_panel_matrix_matches_hand_worked_cases():
    panel = dh_link_panel()
    s = panel.sliders
    assert [x.description for x in s] == ["α_{i-1} [deg]", "a_{i-1}", "θ_i [deg]", "d_i"]
    # α = 90°, a = 1, θ = 0, d = 0.5: Z_i = -Y_{i-1}... origin at (a, -d, 0) by hand
    s[0].value, s[1].value, s[2].value, s[3].value = 90.0, 1.0, 0.0, 0.5
    T = panel.last_frames[-1]
    np.testing.assert_allclose(T[:3, 3], [1.0, -0.5, 0.0], atol=1e-12)
    np.testing.assert_allclose(T[:3, 2], [0.0, -1.0, 0.0], atol=1e-12)
    assert "^(i-1)T_i" in panel.last_readout
    np.testing.assert_allclose(panel.last_frames[0], np.eye(4))
    # the path drawn through the four elementary steps: Rot(X, α) stays at the origin, Trans(X, a) moves
    # to (a, 0, 0), Rot(Z, θ) stays, Trans(Z, d) moves d along Z_i = -Y_{i-1}
    path = _xyz(panel.last_axes.lines[0])
    np.testing.assert_allclose(path, [[0, 0, 0], [0, 0, 0], [1, 0, 0], [1, 0, 0], [1, -0.5, 0]], atol=1e-12)
    # after Rot(X, 90°) the intermediate frame's z axis is -y0 (first faint triad, its blue line)
    z1 = _xyz(panel.last_axes.lines[3])
    np.testing.assert_allclose((z1[1] - z1[0]) / np.linalg.norm(z1[1] - z1[0]), [0.0, -1.0, 0.0], atol=1e-12)


def test_kernel_route_uses_interactive_output(monkeypatch):
    # pretend to be inside a kernel: the panel then goes through ipywidgets.interactive_output
    import ipywidgets

    import puma_course.viz.widgets as W

    calls = []
    real = ipywidgets.interactive_output

    def spy(f, controls):
        calls.append(sorted(controls))
        return real(f, controls)

    shown = []
    monkeypatch.setattr(W, "get_ipython", lambda: object())
    monkeypatch.setattr(W.widgets, "interactive_output", spy)
    monkeypatch.setattr(W, "display", lambda fig: shown.append(fig))
    arm = MK3()
    panel = W.robot_panel(arm, readout="pose")
    assert calls == [["s0", "s1", "s2", "s3", "s4"]]
    panel.sliders[2].value = -90.0
    q = np.array([0.0, 0.0, -np.pi / 2, 0.0, 0.0])
    np.testing.assert_allclose(panel.last_q, q, atol=1e-12)
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk(q), atol=1e-9)
    assert shown and shown[-1] is panel.last_axes.figure  # each redraw shows a fresh figure ...
    assert len({id(f) for f in shown}) == len(shown)
    assert plt.get_fignums() == []  # ... and closes it
