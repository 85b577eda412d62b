"""Lectures 08 and 10's animations as a student meets them in JupyterLab (issues 31 and 34).

Opened from disk, a notebook is not trusted and JupyterLab runs none of its scripts: every
animation must still show its first frame (a decoded picture, with alt text) and say that its
buttons come once the cell has run (no dead control in view). After Run All (JupyterLab's default
windowed notebook), the student scrolls down with the mouse wheel to each animation and clicks
Play once: the picture must be drawn at its size and change. The slider's arrow keys step the
animation (JupyterLab's command-mode shortcuts do not take them). Screenshots in tests/artifacts/:
NN_untrusted_animation_K.png, NN_run_animation_K.png, NN_untrusted.png, NN_after_run_all.png.
Made on the one page per lecture of ``lab.Tab`` (collected by ``test_lectures_06_to_10.py``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from .lab import Lab, Tab

LECTURES = ("08_three_step_wrist_frame.ipynb", "10_trajectories.ipynb")
PLAYERS = ".jp-Notebook .jp-OutputArea-output .animation"


def _saved_animations(lab: Lab, name: str) -> int:
    """How many animation players the notebook's saved outputs hold."""
    cells = json.loads((lab.root / name).read_text(encoding="utf-8"))["cells"]
    count = 0
    for cell in cells:
        for out in cell.get("outputs", []):
            html = out.get("data", {}).get("text/html", "")
            count += "_anim_img" in ("".join(html) if isinstance(html, list) else html)
    return count


def _wheel_to(page: Any, locator: Any, limit: int = 200) -> None:
    """Scroll the notebook with the mouse wheel (as a student does) until ``locator`` is in the middle of the view."""
    view = page.viewport_size
    page.mouse.move(view["width"] * 0.55, view["height"] * 0.5)
    last, still = None, 0
    for _ in range(limit):
        box = locator.bounding_box()
        # the wheel at the end of the notebook's scroll range (JupyterLab's windowed list still sizing the cells
        # below from estimates): let the browser scroll the element itself into view, as a link to it would
        still = still + 1 if box is not None and last is not None and abs(box["y"] - last) < 1 else 0
        last = None if box is None else box["y"]
        if still >= 5:
            locator.scroll_into_view_if_needed()
            page.wait_for_timeout(300)
            box, still = locator.bounding_box(), 0
        if box is not None and 80 <= box["y"] and box["y"] + min(box["height"], 400) <= view["height"] - 80:
            page.wait_for_timeout(300)  # the windowed notebook lays the cell out
            return
        # towards y = 120 by at most 350 px a notch: a fixed 350 could step over the band and back for ever
        step = 350 if box is None else max(-350.0, min(350.0, box["y"] - 120))
        step = step if abs(step) >= 40 else (40 if step > 0 else -40)
        page.mouse.wheel(0, step)
        page.wait_for_timeout(60)
    raise AssertionError("the wheel did not bring the animation into view")


PICTURE = """(img) => ({complete: img.complete, nw: img.naturalWidth, nh: img.naturalHeight,
    w: img.getBoundingClientRect().width, h: img.getBoundingClientRect().height, alt: img.getAttribute('alt') || '',
    src: (img.getAttribute('src') || '').slice(0, 30)})"""


def test_animations_show_a_picture_untrusted(name: str, tab: Tab, artifacts: Path) -> None:
    stem = name.split("_")[0]
    expected = _saved_animations(tab.lab, name)
    assert expected >= 1, f"{name}: no saved animation"
    page = tab.opened()

    # 1. untrusted, as first opened: a picture with a text alternative, controls that say why they wait
    players = page.locator(PLAYERS)
    assert players.count() == expected, f"{name}: {players.count()} players shown, {expected} saved"
    for k in range(expected):
        player = players.nth(k)
        _wheel_to(page, player)
        img = player.locator("img").first
        img.page.wait_for_function("i => i.complete && i.naturalWidth > 0", arg=img.element_handle(), timeout=10_000)
        s = img.evaluate(PICTURE)
        assert s["nw"] > 200 and s["nh"] > 200, f"{name}: animation {k} shows no picture untrusted: {s}"
        assert s["w"] > 200 and s["h"] > 200, f"{name}: animation {k}'s picture is drawn {s['w']} x {s['h']}"
        assert len(s["alt"]) > 40, f"{name}: animation {k}'s picture has no text alternative: {s['alt']!r}"
        note = player.locator(".anim-note")
        assert note.is_visible() and "once this cell has run" in note.inner_text()
        # no control that cannot work yet: the buttons and the slider wait, hidden, for the cell's script
        assert player.get_by_role("button").count() == 0 and player.get_by_role("slider").count() == 0
        player.screenshot(path=str(artifacts / f"{stem}_untrusted_animation_{k}.png"))
    page.screenshot(path=str(artifacts / f"{stem}_untrusted.png"))


def test_animations_play_on_one_click_after_run_all(name: str, tab: Tab, artifacts: Path) -> None:
    stem = name.split("_")[0]
    expected = _saved_animations(tab.lab, name)
    # 2. Run All, then from the top: wheel down to each animation, one click on Play changes the picture
    page = tab.executed()
    page.locator(".jp-Notebook .jp-Cell").first.click()
    page.keyboard.press("Escape")
    page.keyboard.press("Control+Home")  # command mode: the notebook's first cell, the view at the top
    page.wait_for_timeout(500)
    players = page.locator(PLAYERS)
    assert players.count() == expected
    for k in range(expected):
        player = players.nth(k)
        _wheel_to(page, player)
        img = player.locator("img").first
        s = img.evaluate(PICTURE)
        assert s["complete"] and s["nw"] > 200, f"{name}: animation {k} after Run All: {s}"
        assert abs(s["w"] - min(s["nw"], player.evaluate("p => p.parentElement.clientWidth"))) <= 1.5, (
            f"{name}: animation {k} drawn {s['w']:.0f} x {s['h']:.0f} of {s['nw']} x {s['nh']}"
        )
        assert player.locator(".anim-note").count() == 0  # its script ran: the waiting line is gone
        first = img.get_attribute("src")
        play = player.get_by_role("button", name="Play", exact=True)
        assert play.is_enabled()
        box = play.bounding_box()
        page.mouse.click(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)  # one click, where it is
        page.wait_for_function(
            "([p, f]) => p.querySelector('img').getAttribute('src') !== f", arg=[player.element_handle(), first],
            timeout=10_000,
        )  # fmt: skip
        s = player.locator("img").first.evaluate(PICTURE)
        assert s["w"] > 200 and s["h"] > 200, f"{name}: animation {k} drawn {s['w']} x {s['h']} while it plays"
        player.get_by_role("button", name="Pause", exact=True).click()
        player.screenshot(path=str(artifacts / f"{stem}_run_animation_{k}.png"))

        # the slider by keyboard: the arrow key steps the animation and leaves the notebook where it is
        slider = player.get_by_role("slider", name="frame")
        player.get_by_role("button", name="First frame", exact=True).click()
        slider.focus()
        active = page.evaluate("() => document.querySelector('.jp-Notebook .jp-Cell.jp-mod-active') !== null && "
                               "[...document.querySelectorAll('.jp-Notebook .jp-Cell')]"
                               ".indexOf(document.querySelector('.jp-Notebook .jp-Cell.jp-mod-active'))")  # fmt: skip
        before = player.locator("img").first.get_attribute("src")
        for _ in range(3):  # three frames on (lecture 10's first animation holds its start for two)
            page.keyboard.press("ArrowRight")
        page.wait_for_timeout(200)
        assert slider.input_value() == "3", f"{name}: animation {k}: ArrowRight did not step the slider"
        assert player.locator(".anim-count").inner_text().startswith("4 / ")
        assert player.locator("img").first.get_attribute("src") != before
        now = page.evaluate("() => [...document.querySelectorAll('.jp-Notebook .jp-Cell')]"
                            ".indexOf(document.querySelector('.jp-Notebook .jp-Cell.jp-mod-active'))")  # fmt: skip
        assert now == active, f"{name}: the arrow key moved JupyterLab's active cell ({active} -> {now})"
    page.screenshot(path=str(artifacts / f"{stem}_after_run_all.png"))
    assert not page.errors, f"{name}: errors on the page: {page.errors}"
