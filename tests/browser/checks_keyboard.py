"""Lectures 03 and 08 from the keyboard alone, in JupyterLab as ``puma-course lab`` starts it (issue 34).

The notebook is opened; from then on only keys are pressed: Shift+Enter runs every cell in turn, the
arrow keys of command mode walk back up to the panel's cell, Tab moves into its output. There a
joint slider (lecture 03) takes ArrowRight and the arm moves (the viewer redraws a new pose, the
readout changes); Tab reaches the 3-D view, whose arrow keys turn it and "+" zooms, and whose live
region then says where the tool is; in lecture 08 Tab reaches the viewer's animation-step slider, whose
arrow keys step the animation. No arrow key may move JupyterLab's active cell. The Tab stops of each
panel are counted (few stops per panel). Lecture 08's matplotlib player: Tab reaches its "frame" slider,
whose arrow keys step the frames, and its Play button, which Enter starts and Space pauses. Lecture 09's IK
selector: Tab reaches it, ArrowDown picks another of the eight solutions (the viewer highlights that ghost),
Tab reaches "move the arm there", Enter moves the arm there (new slider values, the same hand pose).
Screenshots: tests/artifacts/kbd_NN_*.png. Made on the one page per lecture of ``lab.Tab``, run with
Shift+Enter (``lab.run_by_keyboard``), after the lecture's read-only checks (collected by
``test_lectures_01_to_05.py`` and ``test_lectures_06_to_10.py``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from .checks_lectures import _readout
from .lab import Lab, Tab, viewers

ACTIVE = """() => [...document.querySelectorAll('.jp-Notebook .jp-Cell')]
    .indexOf(document.querySelector('.jp-Notebook .jp-Cell.jp-mod-active'))"""

FOCUS = """() => { const a = document.activeElement; if (!a) return {};
    const cell = a.closest('.jp-Cell');
    return {tag: a.tagName, role: a.getAttribute('role') || '', label: a.getAttribute('aria-label') || '',
            cls: a.className && a.className.baseVal === undefined ? a.className : '',
            cell: cell ? [...document.querySelectorAll('.jp-Notebook .jp-Cell')].indexOf(cell) : -1,
            output: !!a.closest('.jp-OutputArea')}; }"""


def _panel_index(lab: Lab, name: str) -> int:
    cells = json.loads((lab.root / name).read_text(encoding="utf-8"))["cells"]
    return next(
        i
        for i, c in enumerate(cells)
        if any("application/vnd.jupyter.widget-view+json" in o.get("data", {}) for o in c.get("outputs", []))
    )


def _walk_to_cell(page: Any, index: int) -> None:
    """The notebook focused (as after running it by keys), command mode, then ArrowUp until cell ``index`` is active."""
    page.locator(".jp-Notebook").focus()
    page.keyboard.press("Escape")
    for _ in range(200):
        now = page.evaluate(ACTIVE)
        if now == index:
            return
        page.keyboard.press("ArrowUp" if now > index else "ArrowDown")
        page.wait_for_timeout(30)
    raise AssertionError(f"the arrow keys did not reach cell {index}")


def _tab_until(page: Any, test: str, limit: int = 80) -> tuple[dict[str, Any], int]:
    """Press Tab until the focused element passes ``test`` (a JS predicate on FOCUS's dict); (focus, presses)."""
    for k in range(1, limit + 1):
        page.keyboard.press("Tab")
        f = page.evaluate(FOCUS)
        if page.evaluate(f"(f) => {test}", f):
            return f, k
    raise AssertionError(f"{limit} Tab presses did not reach {test}; last focus {page.evaluate(FOCUS)}")


def _turn_the_view(page: Any, box: Any, artifacts: Path, stem: str) -> None:
    eye = box.evaluate("b => b.__puma.eye")
    turns = box.evaluate("b => b.__puma.keyTurns")
    page.keyboard.press("ArrowRight")
    page.keyboard.press("ArrowUp")
    page.keyboard.press("+")
    page.wait_for_function("([b, n]) => b.__puma.keyTurns >= n + 3", arg=[box.element_handle(), turns])
    page.wait_for_timeout(600)  # the live region speaks once the view has settled
    now = box.evaluate("b => b.__puma.eye")
    assert max(abs(a - b) for a, b in zip(eye, now, strict=True)) > 0.05, f"{stem}: the arrow keys did not turn: {eye}"
    status = box.locator("[role=status]")
    assert status.get_attribute("aria-live") == "polite"
    text = status.inner_text()
    assert " at x " in text and "azimuth" in text, f"{stem}: the live region says {text!r}"
    box.screenshot(path=str(artifacts / f"kbd_{stem}_view_turned.png"))


def test_lecture_03_by_keyboard_alone(tab: Tab, artifacts: Path) -> None:
    name, lab = tab.name, tab.lab
    assert name == "03_puma560_forward_kinematics.ipynb" and tab.by_keyboard
    page = tab.executed()
    panel = _panel_index(lab, name)
    _walk_to_cell(page, panel)
    box = viewers(page).first
    page.wait_for_function("b => b.__puma && b.__puma.poseRenders > 0", arg=box.element_handle())

    # Tab into the panel: the first joint slider, named by its visible label
    f, before = _tab_until(page, f"f.role === 'slider' && f.cell === {panel}")
    assert f["label"] == "θ1 [deg]", f
    active = page.evaluate(ACTIVE)
    renders = box.evaluate("b => b.__puma.poseRenders")
    readout = page.locator(".jp-Notebook pre.puma-readout").first.inner_text()
    for _ in range(5):
        page.keyboard.press("ArrowRight")
    page.wait_for_function("([b, n]) => b.__puma.poseRenders > n", arg=[box.element_handle(), renders])
    page.wait_for_timeout(500)
    assert page.locator(".jp-Notebook pre.puma-readout").first.inner_text() != readout, "the readout did not change"
    assert page.evaluate(ACTIVE) == active, "an arrow key moved JupyterLab's active cell"
    page.locator(".jp-Notebook .jp-Cell").nth(panel).screenshot(path=str(artifacts / "kbd_03_slider_moved.png"))

    # on to the 3-D view: a few stops, then the arrow keys turn it
    f, stops = _tab_until(page, "f.tag === 'CANVAS'")
    assert f["role"] == "application" and "arrow keys turn" in f["label"], f
    assert stops <= 16, f"{stops} Tab stops from the first slider to the 3-D view"
    assert box.evaluate("b => document.activeElement === b.querySelector('canvas')")
    _turn_the_view(page, box, artifacts, "03")
    assert page.evaluate(ACTIVE) == active
    page.screenshot(path=str(artifacts / "kbd_03_page.png"))
    assert not page.errors, page.errors


def test_lecture_08_by_keyboard_alone(tab: Tab, artifacts: Path) -> None:
    name, lab = tab.name, tab.lab
    assert name == "08_three_step_wrist_frame.ipynb" and tab.by_keyboard
    page = tab.executed()
    panel = _panel_index(lab, name)
    _walk_to_cell(page, panel)
    box = viewers(page).first
    page.wait_for_function("b => b.__puma && b.__puma.animSteps > 1", arg=box.element_handle())

    f, _ = _tab_until(page, f"f.tag === 'CANVAS' && f.cell === {panel}")
    active = page.evaluate(ACTIVE)
    _turn_the_view(page, box, artifacts, "08")

    f, stops = _tab_until(page, "f.label === 'animation step'")
    assert stops <= 6, f"{stops} Tab stops from the view to its animation slider"
    step = box.evaluate("b => b.__puma.animStep")
    for _ in range(3):
        page.keyboard.press("ArrowRight")
    page.wait_for_timeout(300)
    assert box.evaluate("b => b.__puma.animStep") == step + 3, "the arrow keys did not step the animation"
    assert page.evaluate(ACTIVE) == active, "an arrow key moved JupyterLab's active cell"
    page.locator(".jp-Notebook .jp-Cell").nth(panel).screenshot(path=str(artifacts / "kbd_08_animation_stepped.png"))
    assert not page.errors, page.errors


def _cell_index(lab: Lab, name: str, marker: str) -> int:
    """The first cell whose saved output holds ``marker``."""
    cells = json.loads((lab.root / name).read_text(encoding="utf-8"))["cells"]
    return next(i for i, c in enumerate(cells) if any(marker in json.dumps(o) for o in c.get("outputs", [])))


def test_lecture_08_matplotlib_player_by_keyboard_alone(tab: Tab, artifacts: Path) -> None:
    name, lab = tab.name, tab.lab
    assert name == "08_three_step_wrist_frame.ipynb"
    page = tab.executed()
    cell = _cell_index(lab, name, "_anim_img")
    _walk_to_cell(page, cell)
    player = page.locator(".jp-Notebook .jp-Cell").nth(cell).locator(".animation")
    img = player.locator("img").first
    active = page.evaluate(ACTIVE)

    # Tab reaches the player's frame slider (named "frame"); its arrow keys step the frames, not JupyterLab's cells
    f, stops = _tab_until(page, f"f.tag === 'INPUT' && f.cell === {cell} && f.output")
    assert stops <= 20, f"{stops} Tab stops from the cell to its player"
    slider = player.get_by_role("slider", name="frame")
    assert slider.evaluate("s => document.activeElement === s"), f"the first stop in the player is not its slider: {f}"
    start, picture = int(slider.input_value()), img.get_attribute("src")
    key = "ArrowLeft" if start > 0 else "ArrowRight"
    for _ in range(2):
        page.keyboard.press(key)
    page.wait_for_timeout(200)
    assert int(slider.input_value()) == start + (2 if key == "ArrowRight" else -2), "the arrow keys did not step it"
    assert img.get_attribute("src") != picture, "the arrow keys did not change the frame shown"
    assert page.evaluate(ACTIVE) == active, "an arrow key moved JupyterLab's active cell"

    # on to Play by Tab: Enter starts it (the frames change), Space on Pause stops it
    f, stops = _tab_until(page, "f.label === 'Play'")
    assert stops <= 8, f"{stops} Tab stops from the slider to Play"
    picture = img.get_attribute("src")
    page.keyboard.press("Enter")
    page.wait_for_function(
        "([i, f]) => i.getAttribute('src') !== f", arg=[img.element_handle(), picture], timeout=10_000
    )
    page.keyboard.press("Shift+Tab")  # Pause sits just before Play
    assert page.evaluate(FOCUS)["label"] == "Pause", page.evaluate(FOCUS)
    page.keyboard.press("Space")
    page.wait_for_timeout(400)
    held = img.get_attribute("src")
    page.wait_for_timeout(600)
    assert img.get_attribute("src") == held, "Space on Pause did not stop the animation"
    assert page.evaluate(ACTIVE) == active, "a key moved JupyterLab's active cell"
    player.screenshot(path=str(artifacts / "kbd_08_player_stepped.png"))
    assert not page.errors, page.errors


def test_lecture_09_ik_selector_by_keyboard_alone(tab: Tab, artifacts: Path) -> None:
    name, lab = tab.name, tab.lab
    assert name == "09_puma560_inverse_kinematics.ipynb"
    page = tab.executed()
    panel = _panel_index(lab, name)
    _walk_to_cell(page, panel)
    box = viewers(page).first
    page.wait_for_function("b => b.__puma && b.__puma.ghosts === 8", arg=box.element_handle())
    active = page.evaluate(ACTIVE)

    # Tab reaches the selector (a <select> named by its visible label); ArrowDown picks another solution
    f, stops = _tab_until(page, f"f.tag === 'SELECT' && f.cell === {panel}")
    assert stops <= 24, f"{stops} Tab stops from the cell to its IK selector"
    select = page.locator(".jp-Notebook .jp-Cell").nth(panel).locator(".widget-dropdown select").first
    assert select.evaluate("s => document.activeElement === s")
    chosen = box.evaluate("b => b.__puma.selected")
    readouts = page.locator(".jp-Notebook .jp-Cell").nth(panel).locator(".widget-slider .widget-readout")
    q_before = readouts.all_inner_texts()[:6]
    hand = _readout(page)
    page.keyboard.press("ArrowDown" if chosen < 7 else "ArrowUp")
    page.wait_for_function("([b, n]) => b.__puma.selected !== n", arg=[box.element_handle(), chosen])
    picked = box.evaluate("b => b.__puma.selected")
    assert picked != chosen and 0 <= picked < 8
    assert page.evaluate(ACTIVE) == active, "an arrow key moved JupyterLab's active cell"

    # Tab on to "move the arm there"; Enter moves the arm to the picked solution: new joints, the same hand
    f, stops = _tab_until(page, "f.tag === 'BUTTON' && f.cell === " + str(panel))
    assert stops <= 3, f"{stops} Tab stops from the selector to its button: {f}"
    assert page.evaluate("() => document.activeElement.textContent.trim()") == "move the arm there"
    renders = box.evaluate("b => b.__puma.poseRenders")
    page.keyboard.press("Enter")
    page.wait_for_function("([b, n]) => b.__puma.poseRenders > n", arg=[box.element_handle(), renders])
    page.wait_for_timeout(500)
    assert readouts.all_inner_texts()[:6] != q_before, "Enter on 'move the arm there' did not move the joints"
    np.testing.assert_allclose(_readout(page), hand, atol=2e-4, err_msg="the hand pose changed")
    assert page.evaluate(ACTIVE) == active, "a key moved JupyterLab's active cell"
    page.locator(".jp-Notebook .jp-Cell").nth(panel).screenshot(path=str(artifacts / "kbd_09_ik_selected.png"))
    assert not page.errors, page.errors
