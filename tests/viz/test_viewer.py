"""The WebGL viewer's kernel side (puma_course.viz.viewer): what it sends, checked against the robot API and by hand.

The browser side is checked by node (js/test, run from test_viewer_js.py) and in Chromium (tests/browser).
"""

from __future__ import annotations

import base64
import html
import re

import numpy as np
import pytest

from puma_course import MK3, Porter, Puma560
from puma_course.viz import RobotViewer, Viewer
from puma_course.viz.viewer import view_box


def test_scene_is_sent_once_with_the_frame_styles():
    arm = Puma560()
    v = RobotViewer(arm, "qn")
    sc = v.scene
    assert [f["label"] for f in sc["frames"]] == [f"{{{i}}}" for i in range(7)]
    assert [f["priority"] for f in sc["frames"]] == [2, 1, 1, 1, 1, 1, 2]  # the base and the tool label first
    assert sc["frames"][0]["length"] == pytest.approx(1.3 * sc["frames"][1]["length"])  # base and tool stand out
    assert sc["points"] == len(arm.points(arm.q("qn"))) and sc["units"] == "m" and sc["title"] == "PUMA-560"
    # the grid lies where the arm stands (its first link point) and spans its reach
    assert sc["grid"]["z"] == pytest.approx(arm.points(arm.q("qn"))[0, 2])
    assert sc["grid"]["size"] > 1.5  # the PUMA reaches about 0.9 m from its shoulder
    assert RobotViewer(arm, labels="ends").scene["frames"][3]["label"] == ""
    assert [f["label"] for f in RobotViewer(arm, labels="none").scene["frames"]] == [""] * 7


def test_pose_is_the_robots_frames_and_points():
    arm = MK3()
    v = RobotViewer(arm)
    q = np.radians([30.0, 45.0, -60.0, 10.0, 90.0])
    v.set_q(q)
    np.testing.assert_allclose(np.reshape(v.pose["frames"], (-1, 4, 4)), arm.frames(q), atol=1e-7)
    np.testing.assert_allclose(np.reshape(v.pose["points"], (-1, 3)), arm.points(q), atol=1e-7)
    seq = v.pose["seq"]
    v.set_q(q)
    assert v.pose["seq"] == seq + 1  # every update is a new message, even to the same pose
    with pytest.raises(ValueError, match="q"):
        v.set_q(np.zeros(4))
    with pytest.raises(ValueError, match="frames"):
        v.show(np.eye(4)[None])  # 1 frame for a viewer of 6


def test_camera_frames_the_first_pose_and_the_triads():
    arm = Porter(1.0, 0.5, 0.3)
    q = np.array([0.5, -0.4, 1.2, 0.9, 0.6, -0.3])
    v = RobotViewer(arm, q)
    c, r = np.array(v.scene["center"]), v.scene["radius"]
    shown = np.vstack([arm.points(q), arm.frames(q)[:, :3, 3], np.zeros((1, 3))])
    assert np.all(np.linalg.norm(shown - c, axis=1) <= r)
    assert r < 1.5  # the pose, not the whole reach (a stroke of 3.6 would give more than 2)


def test_view_box_by_hand():
    c, r = view_box([[0, 0, 0], [2, 0, 0], [1, 1, 0]], margin=0.0)
    np.testing.assert_allclose(c, [1.0, 0.5, 0.0])
    assert r == pytest.approx(np.hypot(1.0, 0.5))


def test_targets_ghosts_and_animation():
    arm = Puma560()
    v = RobotViewer(arm, "qz")
    q_end = np.radians([10.0, -30.0, 20.0, 10.0, 40.0, 10.0])  # not singular: eight solutions
    T = arm.fk(q_end)
    v.set_targets(T)
    assert v.targets == [{"frame": [float(x) for x in np.round(T.ravel(), 7) + 0.0], "label": "target"}]
    v.set_targets(np.stack([T, T]), labels=["A", "B"])
    assert [t["label"] for t in v.targets] == ["A", "B"]
    with pytest.raises(ValueError, match="labels"):
        v.set_targets(T, labels=["A", "B"])
    sol = arm.ik(T)
    v.show_ik(sol, selected=2)
    assert len(v.ghosts["arms"]) == len(sol) and v.ghosts["selected"] == 2
    for g, qk in zip(v.ghosts["arms"], sol.q, strict=True):
        np.testing.assert_allclose(np.reshape(g["points"], (-1, 3)), arm.points(qk), atol=1e-7)
    v.show_ik(np.zeros((0, 6)))
    assert v.ghosts == {"arms": [], "selected": -1}
    with pytest.raises(ValueError, match="selected"):
        v.show_ik(sol, selected=99)
    path = np.linspace(arm.q("qz"), q_end, 5)
    v.animate(path, fps=10)
    anim = v.animation
    assert len(anim["poses"]) == 5 and anim["fps"] == 10.0 and anim["loop"] is False
    np.testing.assert_allclose(np.reshape(anim["poses"][-1]["frames"], (-1, 4, 4))[-1], T, atol=1e-7)
    # the animation's view holds every pose of the path
    c, r = np.array(anim["view"]["center"]), anim["view"]["radius"]
    assert np.all(np.linalg.norm(arm.points(path).reshape(-1, 3) - c, axis=1) <= r)
    with pytest.raises(ValueError, match="fps"):
        v.animate(path, fps=0)


def test_a_chain_viewer_checks_its_styles():
    F = np.stack([np.eye(4)] * 3)
    v = Viewer(F, faint=[False, True, False], axes=False, units="mm", lengths=0.5)
    assert [f["faint"] for f in v.scene["frames"]] == [False, True, False]
    assert [f["length"] for f in v.scene["frames"]] == [0.5] * 3
    with pytest.raises(ValueError, match="labels"):
        Viewer(F, labels=["a"])
    with pytest.raises(ValueError, match="faint"):
        Viewer(F, faint=[True])
    with pytest.raises(ValueError, match="robot"):
        RobotViewer("PUMA")


def test_static_png_shows_the_pose_and_closes_its_figure():
    import matplotlib.pyplot as plt

    v = RobotViewer(MK3(), "qr")
    png = v.static_png()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and plt.get_fignums() == []
    data = v._repr_mimebundle_()
    data = data[0] if isinstance(data, tuple) else data
    # the still picture is an <img alt> in text/html (JupyterLab gives a bare image/png no alt): one copy, no PNG
    assert "image/png" not in data and "application/vnd.jupyter.widget-view+json" in data
    m = re.fullmatch(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)" alt="([^"]+)">', data["text/html"])
    assert m and base64.b64decode(m.group(1))[:8] == b"\x89PNG\r\n\x1a\n"
    assert html.unescape(m.group(2)) == v.still_alt()
    assert "Motoman MK3" in v.still_alt() and "6 frames" in v.still_alt()


def test_the_picture_kept_for_a_live_viewer_says_it_is_still(monkeypatch):
    from matplotlib.figure import Figure

    from puma_course.viz.viewer import STILL_NOTE

    seen, savefig = [], Figure.savefig

    def spy(fig, *args, **kwargs):
        seen.append([t.get_text() for t in fig.texts])
        return savefig(fig, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", spy)
    v = RobotViewer(MK3(), "qr")
    v.static_png()  # asked for directly: no note
    v._repr_mimebundle_()  # the picture a saved notebook keeps in place of the widget
    assert seen == [[], [STILL_NOTE]]


def test_the_text_repr_names_the_viewer_and_holds_no_memory_address():
    v = RobotViewer(MK3(), "qr")
    data = v._repr_mimebundle_()
    data = data[0] if isinstance(data, tuple) else data
    assert data["text/plain"] == repr(v) == "RobotViewer('Motoman MK3', 6 frames)"
    assert "0x" not in data["text/plain"]


def test_the_stills_note_sits_under_the_axes_numbers_and_labels():
    _check_the_stills_note()


def test_the_stills_note_sits_under_the_axes_labels_in_the_course_style(course_style):
    # the lectures' style lays figures out with constrained layout, which undid the note's room (issue 25: the
    # stills of lectures 02, 03, 05, 09 and 10 printed their note over the x label)
    _check_the_stills_note()


def _check_the_stills_note():
    import matplotlib.pyplot as plt

    from puma_course.viz.frames import new_axes, note_below, set_equal
    from puma_course.viz.viewer import STILL_NOTE

    fig, ax = new_axes(figsize=(5.6, 4.2), title="PUMA-560", dpi=110)
    try:
        set_equal(ax, np.array([[-0.6, -0.6, -0.4], [0.6, 0.6, 1.0]]))
        ax.set(xlabel="x [m]", ylabel="y [m]", zlabel="z [m]")
        size = fig.get_size_inches().copy()
        note_below(fig, ax, STILL_NOTE)
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        note = fig.texts[-1].get_window_extent(r)
        drawn = [a.label.get_window_extent(r) for a in (ax.xaxis, ax.yaxis, ax.zaxis)]
        ticks = [t.get_window_extent(r) for a in (ax.xaxis, ax.yaxis, ax.zaxis) for t in a.get_ticklabels()
                 if t.get_text() and t.get_visible()]  # fmt: skip
        W = fig.get_size_inches()[0] * fig.dpi
        drawn += [b for b in ticks if 0 <= b.x0 and b.x1 <= W]  # the numbers drawn (not those of ticks out of view)
        assert len(drawn) >= 6  # three axis labels and their numbers
        for b in drawn:
            assert not note.overlaps(b), f"the note {note} overlaps {b}"
        assert note.y1 < min(b.y0 for b in drawn)  # under all of it
        assert note.y0 >= 0 and fig.get_size_inches()[1] >= size[1]  # inside the picture, which grew to hold it
    finally:
        plt.close(fig)
