"""Checks of lectures 01-10 in a real browser, made on one opened and run page per lecture (``lab.Tab``).

Collected by ``test_lectures_01_to_05.py`` and ``test_lectures_06_to_10.py``, which choose the lectures
each check runs on. The panels of lectures 02-05: opened from disk (no kernel output yet), every panel
cell shows its static picture (an <img>), never a text repr; after the run every panel is a WebGL
canvas, no cell shows "Error displaying widget" or a repr, the frame labels do not overlap; typing a
value into a slider's readout moves the drawn arm (the origins the viewer drew, and the pixels) and the
readout matrix to the value worked out by hand here; the mouse turns the view and "reset view" frames
the arm where it is. Every lecture as a student gets it: opened unmodified; after the run every output
image is drawn at its size, every animation plays on one click.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np

from .lab import VIEWER_STATE, Tab, output_texts, viewers

REPR = re.compile(r"\b(Robot)?Panel\(children=|\bViewer\(|HBox\(children=")


def _panel_cells(page: Any) -> Any:
    return page.locator(".jp-Notebook .jp-CodeCell").filter(has_text="_panel(")


def _readout(page: Any) -> np.ndarray:
    """The numbers of the panel's readout matrix (4 x 4)."""
    text = page.locator(".jp-Notebook pre.puma-readout").first.inner_text()
    rows = re.findall(r"\[\s*([-\d.e\s]+?)\s*\]", text.split("=", 1)[1])
    return np.array([[float(x) for x in r.split()] for r in rows])


def _set_slider(page: Any, box: Any, index: int, value: float) -> None:
    """Type ``value`` into slider ``index``'s readout (display units) and wait for the viewer to redraw."""
    before = box.evaluate("b => b.__puma.poseRenders")
    readout = page.locator(".jp-Notebook .widget-slider .widget-readout").nth(index)
    readout.click()
    page.keyboard.press("Control+A")
    page.keyboard.type(f"{value:g}")
    page.keyboard.press("Enter")
    page.wait_for_function("([b, n]) => b.__puma.poseRenders > n", arg=[box.element_handle(), before], timeout=10_000)


def _no_overlap(labels: list[dict[str, float]]) -> None:
    for i, a in enumerate(labels):
        for b in labels[i + 1 :]:
            apart = a["x"] + a["w"] <= b["x"] or b["x"] + b["w"] <= a["x"] or a["y"] + a["h"] <= b["y"] or \
                b["y"] + b["h"] <= a["y"]  # fmt: skip
            assert apart, f"labels {a['text']} and {b['text']} overlap: {a} {b}"


def _hand_dh() -> tuple[list[tuple[int, float]], np.ndarray, np.ndarray]:
    # α = 90°, a = 1, θ = 30° (start), d = 0.5 (start); Craig's link matrix by hand
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    T = np.array([[c, -s, 0, 1.0], [0, 0, -1, -0.5], [s, c, 0, 0], [0, 0, 0, 1]])
    return [(0, 90.0)], T, T[:3, 3]


def _hand_puma() -> tuple[list[tuple[int, float]], np.ndarray, np.ndarray]:
    # θ2 = 90° turns the arm at q = 0 about +y0 (the shoulder axis):
    # p = (-d4, d3, -(a2 + a3)), R = Ry(90°) diag(1, -1, -1)
    T = np.array([[0, 0, -1, -0.4318], [0, -1, 0, 0.15005], [-1, 0, 0, -0.4521], [0, 0, 0, 1]])
    return [(1, 90.0)], T, T[:3, 3]


def _hand_mk3() -> tuple[list[tuple[int, float]], np.ndarray, np.ndarray]:
    # θ1 = 90°: the outstretched arm (a1 + a2 + a3 = 600 mm along x at q = 0, hand d1 - d5 = 260 mm high) turns onto +y
    p = np.array([0.0, 600.0, 260.0])
    return [(0, 90.0)], np.array([]), p


def _hand_porter() -> tuple[list[tuple[int, float]], np.ndarray, np.ndarray]:
    # every joint at 0 (the lecture's check by hand): F05 = identity rotation, p5 = (l4, 0, l1 - l3) = (0.3, 0, 0.5)
    T = np.eye(4)
    T[:3, 3] = [0.3, 0.0, 0.5]
    return [(k, 0.0) for k in range(6)], T, T[:3, 3]


PANELS = {
    "02_dh_frame_attachment.ipynb": _hand_dh,
    "03_puma560_forward_kinematics.ipynb": _hand_puma,
    "04_mk3_forward_kinematics.ipynb": _hand_mk3,
    "05_porter_direct_problem.ipynb": _hand_porter,
}


def test_lecture_panels_show_their_picture_before_the_kernel_runs(name: str, tab: Tab, artifacts: Path) -> None:
    stem = name.split("_")[0]
    page = tab.opened()

    # 1. before the kernel runs: each panel cell shows its saved picture, not a text repr
    cells = _panel_cells(page)
    assert cells.count() >= 1
    for k in range(cells.count()):
        out = cells.nth(k).locator(".jp-OutputArea")
        img = out.locator("img")
        assert img.count() == 1, f"{name}: panel {k} shows no picture before the kernel runs"
        img.scroll_into_view_if_needed()
        assert img.evaluate("i => i.complete && i.naturalWidth > 200 && i.naturalHeight > 200")
        assert not REPR.search(out.text_content() or ""), f"{name}: a text repr is shown: {out.text_content()!r}"
        out.screenshot(path=str(artifacts / f"{stem}_before_run_{k}.png"))


def test_lecture_panels_in_chromium(name: str, tab: Tab, artifacts: Path) -> None:
    stem = name.split("_")[0]
    page = tab.executed()
    cells = _panel_cells(page)

    # 2. Run All: every panel is a live WebGL view; no cell shows an error or a repr
    boxes = viewers(page)
    boxes.first.wait_for(timeout=30_000)
    assert boxes.count() == cells.count()
    for text in output_texts(page):
        assert "Error displaying widget" not in text
        assert not REPR.search(text), f"{name}: a text repr is shown: {text[:200]!r}"
    box = boxes.first
    box.scroll_into_view_if_needed()
    page.wait_for_function("b => b.__puma.poseRenders >= 1 && b.__puma.labels.length > 0", arg=box.element_handle())
    state = box.evaluate(VIEWER_STATE)
    assert state["hasWebGL"], f"{name}: the panel has no WebGL canvas"
    assert state["width"] > 300 and state["height"] > 300
    _no_overlap(state["labels"])
    panel = cells.first.locator(".jp-OutputArea")
    panel.screenshot(path=str(artifacts / f"{stem}_panel.png"))
    pixels = box.locator("canvas").screenshot()

    # 3. a slider move: the drawn arm and the readout reach the values worked out by hand
    moves, T_hand, p_hand = PANELS[name]()
    R_before = _readout(page)[:3, :3]
    for index, value in moves:
        _set_slider(page, box, index, value)
    state = box.evaluate(VIEWER_STATE)
    origins = np.array(box.evaluate("b => b.__puma.origins"))
    np.testing.assert_allclose(origins[-1], p_hand, atol=1e-4 * max(1.0, np.abs(p_hand).max()))
    T_read = _readout(page)
    np.testing.assert_allclose(T_read[:3, 3], p_hand, atol=1e-3 * max(1.0, np.abs(p_hand).max()))
    if T_hand.size:
        np.testing.assert_allclose(T_read, T_hand, atol=1e-3 * max(1.0, np.abs(p_hand).max()))
    else:  # MK3: θ1 = 90° turns the hand's rotation by Rz(90°) too
        np.testing.assert_allclose(T_read[:3, :3], np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]) @ R_before, atol=2e-3)
    assert box.locator("canvas").screenshot() != pixels, f"{name}: the picture did not change"
    _no_overlap(state["labels"])
    panel.screenshot(path=str(artifacts / f"{stem}_panel_moved.png"))

    # 4. the mouse turns the view (the labels move on the screen), "reset view" frames the arm again
    canvas = box.locator("canvas")
    bb = canvas.bounding_box()
    start = [(lab_["x"], lab_["y"]) for lab_ in state["labels"]]
    page.mouse.move(bb["x"] + bb["width"] / 2, bb["y"] + bb["height"] / 2)
    page.mouse.down()
    page.mouse.move(bb["x"] + bb["width"] / 2 + 120, bb["y"] + bb["height"] / 2 + 30, steps=8)
    page.mouse.up()
    page.wait_for_timeout(200)
    turned = [(lab_["x"], lab_["y"]) for lab_ in box.evaluate("b => b.__puma.labels")]
    assert turned != start, f"{name}: dragging did not turn the view"
    panel.screenshot(path=str(artifacts / f"{stem}_panel_turned.png"))
    # "reset view" frames the arm where it is now: every labelled frame's origin inside the picture
    box.get_by_role("button", name="reset view").click()
    page.wait_for_timeout(200)
    back = box.evaluate("b => b.__puma.labels")
    assert [(lab_["x"], lab_["y"]) for lab_ in back] != turned
    assert all(0 <= lab_["ax"] <= bb["width"] and 0 <= lab_["ay"] <= bb["height"] for lab_ in back), back
    _no_overlap(back)
    panel.screenshot(path=str(artifacts / f"{stem}_panel_reset.png"))

    # 5. the user's turn of the view is kept while the arm moves, and the arm stays in the picture
    page.mouse.move(bb["x"] + bb["width"] / 2, bb["y"] + bb["height"] / 2)
    page.mouse.down()
    page.mouse.move(bb["x"] + bb["width"] / 2 - 90, bb["y"] + bb["height"] / 2 - 20, steps=6)
    page.mouse.up()
    page.wait_for_timeout(200)
    eye = np.array(box.evaluate("b => b.__puma.eye"))
    index, value = moves[0]
    _set_slider(page, box, index, value - 90.0)
    page.wait_for_timeout(200)
    np.testing.assert_allclose(box.evaluate("b => b.__puma.eye"), eye, atol=1e-6)
    moved = box.evaluate("b => b.__puma.labels")
    assert all(0 <= lab_["ax"] <= bb["width"] and 0 <= lab_["ay"] <= bb["height"] for lab_ in moved), moved
    panel.screenshot(path=str(artifacts / f"{stem}_panel_turned_moved.png"))
    assert not page.errors, f"{name}: errors on the page: {page.errors}"


# ---- every lecture as a student gets it (JupyterLab's default, windowed notebook) ----------------------

# the room is the width the renderer gives the image: its parent's content box (JupyterLab's image renderer adds no
# padding; its HTML renderer, which shows a figure with its alt text as an <img>, keeps 20 px on the right)
IMAGE_SIZE = """(img) => {
    const r = img.getBoundingClientRect();
    const box = img.parentElement || img.closest('.jp-OutputArea-output');
    const cs = getComputedStyle(box);
    const room = box.getBoundingClientRect().width - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight)
        - parseFloat(cs.borderLeftWidth) - parseFloat(cs.borderRightWidth);
    return {w: r.width, h: r.height, nw: img.naturalWidth, nh: img.naturalHeight, complete: img.complete,
            room: room, src: (img.getAttribute('src') || '').slice(0, 40)};
}"""


def _drawn_at_natural_size(img: Any, where: str) -> None:
    """The image, scrolled into view, is drawn at its natural size (or scaled down to the output's width)."""
    # a reader scrolls the output into view (the image itself may have no box to scroll to until then)
    out = img.evaluate_handle("i => i.closest('.jp-OutputArea-output')")
    out.evaluate("o => o.scrollIntoView({block: 'center'})")
    try:  # the output's image, looked up afresh (the player may replace its element once it is in view)
        img.page.wait_for_function(
            "o => [...o.querySelectorAll('img')].every(i => i.complete && i.naturalWidth > 0"
            " && i.getBoundingClientRect().width > 0)",
            arg=out, timeout=5_000,
        )  # fmt: skip
    except Exception:
        pass  # measured below: the message says what was drawn
    s = img.evaluate(IMAGE_SIZE)
    want_w = min(s["nw"], s["room"])
    assert abs(s["w"] - want_w) <= 1.5, f"{where}: drawn {s['w']:.0f} x {s['h']:.0f}, natural {s['nw']} x {s['nh']}"
    assert abs(s["h"] - s["nh"] * want_w / s["nw"]) <= 1.5, f"{where}: drawn {s['w']:.0f} x {s['h']:.0f}, natural {s}"


def test_lecture_as_a_student_gets_it(name: str, tab: Tab, artifacts: Path) -> None:
    """Opened unmodified; after Run All every output image is drawn at its size, every animation plays on one click."""
    stem = name.split("_")[0]
    tab.opened()  # the notebook as opened: its tab counted half a second after opening (lab.Tab)
    assert tab.dirty_after_open == 0, f"{name}: JupyterLab marks the notebook modified right after opening it"
    page = tab.executed()
    outputs = page.locator(".jp-Notebook .jp-CodeCell .jp-OutputArea-output")
    images = page.locator(".jp-Notebook .jp-CodeCell .jp-OutputArea-output img")
    for k in range(images.count()):
        _drawn_at_natural_size(images.nth(k), f"{name}: output image {k}")
    players = page.locator(".jp-Notebook .jp-OutputArea-output .animation")
    for k in range(players.count()):
        player = players.nth(k)
        img = player.locator("img").first
        _drawn_at_natural_size(img, f"{name}: animation {k}'s picture")
        play = player.get_by_role("button", name="Play", exact=True)
        before = play.bounding_box()
        first = img.get_attribute("src")
        slider = player.locator("input.anim-slider")
        start = int(slider.input_value())
        play.click()
        page.wait_for_function(
            "([s, v]) => parseInt(s.value) !== v", arg=[slider.element_handle(), start], timeout=5_000
        )
        after = play.bounding_box()
        assert before is not None and after is not None
        assert abs(after["y"] - before["y"]) < 1 and abs(after["x"] - before["x"]) < 1, (
            f"{name}: animation {k}'s play button moved under the pointer: {before} -> {after}"
        )
        try:  # a player may show its first picture for a few frames (lecture 10 holds the start)
            page.wait_for_function(
                "([p, f]) => p.querySelector('img').getAttribute('src') !== f", arg=[player.element_handle(), first],
                timeout=10_000,
            )  # fmt: skip
        except Exception:
            pass
        assert img.get_attribute("src") != first, f"{name}: animation {k} did not change its picture"
        _drawn_at_natural_size(img, f"{name}: animation {k}'s picture while it plays")
        player.get_by_role("button", name="Pause", exact=True).click()
        player.screenshot(path=str(artifacts / f"{stem}_animation_{k}.png"))
    assert outputs.count() > 0
    for text in output_texts(page):
        assert "Error displaying widget" not in text
        assert "NBVAL" not in text
    sources = page.locator(".jp-Notebook .jp-CodeCell .jp-InputArea").all_inner_texts()
    assert not any("NBVAL" in s for s in sources), f"{name}: an nbval pragma is shown in a cell"
    assert not page.errors, f"{name}: errors on the page: {page.errors}"
