"""Slider panels: built without a display (Agg); callbacks must receive radians."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from puma_course import mk3, puma560  # noqa: E402
from puma_course.widgets import Panel, chain_panel, dh_link_panel, joint_sliders  # noqa: E402


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


def test_joint_sliders_bad_input():
    with pytest.raises(ValueError, match="highs"):
        joint_sliders(["θ1"], [1.0], [0.0])
    with pytest.raises(ValueError, match="lows"):
        joint_sliders(["θ1", "θ2"], [0.0, 0.0, 0.0], 1.0)


def test_chain_panel_passes_radians_to_fk():
    arm = puma560()
    seen = []

    def frames_fn(q):
        seen.append(np.array(q))
        return arm.frames(q)

    panel = chain_panel(frames_fn, 6, readout="pose", title="PUMA-560")
    assert isinstance(panel, Panel)
    assert [s.description for s in panel.sliders][0] == "θ1 [deg]"
    # initial draw at q = 0: hand-worked p = (a2 + a3, d3, -d4)
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [0.4318 + 0.0203, 0.15005, -0.4318], atol=1e-12)
    panel.sliders[1].value = 90.0  # the student sees degrees ...
    q = np.array([0.0, np.pi / 2, 0.0, 0.0, 0.0, 0.0])  # ... the kinematics sees radians
    np.testing.assert_allclose(seen[-1], q, atol=1e-12)
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk(q), atol=1e-12)
    assert "p = " in panel.last_readout and "R =" in panel.last_readout
    assert plt.get_fignums() == []  # every redraw closes its figure


def test_chain_panel_custom_readout_and_limits():
    arm = mk3()
    panel = chain_panel(arm.frames, 5, readout=lambda q: f"sum={np.degrees(q).sum():.1f}", limits=(-800, 800))
    panel.set_radians([np.pi / 2, 0, 0, 0, -np.pi / 4])
    assert panel.last_readout == "sum=45.0"
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk([np.pi / 2, 0, 0, 0, -np.pi / 4]), atol=1e-9)
    # at θ1 = 90° the MK3 reaches along +y: p = (0, a1 + a2 + a3, d1 - d5) worked by hand
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [0.0, 600.0, 260.0], atol=1e-9)
    with pytest.raises(ValueError, match="limits"):
        chain_panel(arm.frames, 5, limits=(1, 0))
    with pytest.raises(ValueError, match="readout"):
        chain_panel(arm.frames, 5, readout="nonsense")


def test_chain_panel_porter_like_lambda_with_prismatic_joint():
    # a toy chain with one prismatic joint: slide along x by d, then turn about z
    def frames(q, length):
        th, d = q
        T1 = np.eye(4)
        T1[0, 3] = d
        T2 = T1.copy()
        T2[:2, :2] = [[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]]
        T2[:3, 3] += T2[:3, 0] * length
        return np.stack([np.eye(4), T1, T2])

    panel = chain_panel(lambda q: frames(q, 1.0), ["θ", "d"], [-np.pi, 0.0], [np.pi, 2.0], degrees=[True, False])
    assert [s.description for s in panel.sliders] == ["θ [deg]", "d"]
    panel.sliders[0].value = 90.0
    panel.sliders[1].value = 1.5
    np.testing.assert_allclose(panel.last_frames[-1][:3, 3], [1.5, 1.0, 0.0], atol=1e-12)


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


def test_kernel_route_uses_interactive_output(monkeypatch):
    # pretend to be inside a kernel: the panel then goes through ipywidgets.interactive_output
    import ipywidgets

    import puma_course.widgets as W

    calls = []
    real = ipywidgets.interactive_output

    def spy(f, controls):
        calls.append(sorted(controls))
        return real(f, controls)

    monkeypatch.setattr(W, "get_ipython", lambda: object())
    monkeypatch.setattr(W.widgets, "interactive_output", spy)
    arm = mk3()
    panel = W.chain_panel(arm.frames, 5, readout="pose")
    assert calls == [["s0", "s1", "s2", "s3", "s4"]]
    panel.sliders[2].value = -90.0
    q = np.array([0.0, 0.0, -np.pi / 2, 0.0, 0.0])
    np.testing.assert_allclose(panel.last_q, q, atol=1e-12)
    np.testing.assert_allclose(panel.last_frames[-1], arm.fk(q), atol=1e-9)
    assert plt.get_fignums() == []
