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


# ---- the course's player: a picture and named controls before any script runs ---------------------------


def _page(frames=3, alt="a line rising"):
    fig, anim = _anim()
    page = jshtml(anim, alt=alt).data
    plt.close(fig)
    return page


def test_the_first_frame_is_the_images_own_picture_with_its_size_and_alt():
    import base64

    page = _page()
    img = re.search(r"<img [^>]*>", page).group(0)
    src = re.search(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', img)
    assert src, "the committed <img> has no picture of its own"
    png = base64.b64decode(src.group(1))
    w, h = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert f'width="{w}" height="{h}"' in img and f"aspect-ratio:{w}/{h}" in img  # laid out before any decode
    assert 'alt="a line rising"' in img
    # every frame is embedded once: the first in the <img>, the others in the script
    assert page.count("data:image/png") == 3 and page.count(src.group(1)) == 1


def test_controls_are_named_and_hidden_until_the_cell_has_run():
    page = _page()
    buttons = re.findall(r"<button [^>]*>", page)
    assert len(buttons) == 9 and all('aria-label="' in b and 'title="' in b for b in buttons)
    names = [re.search(r'title="([^"]+)"', b).group(1) for b in buttons]
    assert names[5] == "Play" and names[4] == "Pause"  # matplotlib's order, which the site's tests use
    # the slider: inside a <label> with the visible word "frame", disabled until the script runs, and kept
    # from JupyterLab's command-mode shortcuts (lumino stops at data-lm-suppress-shortcuts)
    label = re.search(r'<label class="anim-label">frame <input [^>]*class="anim-slider"[^>]*></label>', page)
    assert label and "data-lm-suppress-shortcuts" in label.group(0)
    # no script yet (an untrusted notebook): the controls are hidden, and a line says when they come
    player = re.search(r'<div class="anim-player" hidden="hidden">(.*?)<p class="anim-note">', page, re.S)
    assert player and all(b in player.group(1) for b in buttons) and label.group(0) in player.group(1)
    note = re.search(r'<p class="anim-note">(.*?)</p>', page, re.S).group(1)
    assert "once this cell has run" in note and "3 frames" in note
    script = page.split("<script>", 1)[1]
    assert "note.remove()" in script and '.querySelector(".anim-player").hidden = false' in script


def test_nothing_is_fetched_and_the_script_needs_no_global():
    page = _page()
    assert not re.search(r"https?://", page)
    assert "onclick=" not in page and "oninput=" not in page  # handlers are attached by the script itself


def test_default_alt_and_bad_alt():
    page = _page(alt=None)
    assert re.search(r'alt="An animation of 3 frames\."', page)
    with pytest.raises(ValueError, match="^alt: expected a text"):
        _page(alt="  ")


def test_player_html_checks_its_frames():
    from puma_course.viz.animation import player_html

    with pytest.raises(ValueError, match="^frames: expected at least one"):
        player_html([], alt="x")
    with pytest.raises(ValueError, match="^frames: expected PNG"):
        player_html([b"GIF89a" + bytes(30)], alt="x")
    with pytest.raises(ValueError, match="^interval: expected a positive"):
        player_html([_png()], alt="x", interval=0)


def _png():
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.new("RGB", (4, 3)).save(buf, "png")
    return buf.getvalue()
