"""Animations play offline: no CDN link, every player icon drawn by inline CSS."""

from __future__ import annotations

import re

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from matplotlib.animation import FuncAnimation  # noqa: E402

from puma_course.viz.animation import ICON_CSS, jshtml, offline_player  # noqa: E402


def _anim():
    fig, ax = plt.subplots()
    (line,) = ax.plot([0, 1], [0, 1])
    anim = FuncAnimation(fig, lambda i: (line.set_data([0, 1], [0, i]),), frames=3)
    return fig, anim


def test_no_external_url_and_every_icon_has_a_glyph():
    fig, anim = _anim()
    raw = anim.to_jshtml()
    html = jshtml(anim).data
    plt.close(fig)
    assert "bootstrapcdn" in raw  # what matplotlib writes: the reason for this module
    assert not re.search(r"https?://", html.split("data:image", 1)[0])  # nothing fetched before the frames
    icons = set(re.findall(r'class="fa (fa-[a-z-]+)', raw))
    assert icons and all(f".animation i.{icon}:before" in ICON_CSS for icon in icons)
    assert html.count("<style>") >= 1 and html.count("data:image/png") == raw.count("data:image/png")


def test_bad_input():
    with pytest.raises(ValueError, match="^html: expected the text"):
        offline_player(None)
    with pytest.raises(ValueError, match="^anim: expected a matplotlib animation"):
        jshtml("not an animation")


def test_frames_are_drawn_at_the_figures_dpi_even_under_the_course_style():
    """The course style sets savefig.dpi = 110; an animation's frames keep the size its figure asks for."""
    import base64

    from puma_course.viz.style import COURSE_STYLE

    with matplotlib.rc_context(COURSE_STYLE):
        fig, ax = plt.subplots(figsize=(4, 3), dpi=50)
        anim = FuncAnimation(fig, lambda i: [], frames=2)
        html = jshtml(anim).data
        plt.close(fig)
    frame = re.search(r"data:image/png;base64,([^\"']+)", html).group(1).replace("\\n", "")
    png = base64.b64decode(frame)
    assert (int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")) == (200, 150)  # 4 x 3 in at 50 dpi
