"""Lectures 03 and 08 from the keyboard alone, in JupyterLab as ``puma-course lab`` starts it (issue 34).

The notebook is opened; from then on only keys are pressed: Shift+Enter runs every cell in turn, the
arrow keys of command mode walk back up to the panel's cell, Tab moves into its output. There a
joint slider (lecture 03) takes ArrowRight and the arm moves (the viewer redraws a new pose, the
readout changes); Tab reaches the 3-D view, whose arrow keys turn it and "+" zooms, and whose live
region then says where the tool is; in lecture 08 Tab reaches the viewer's animation-step slider, whose
arrow keys step the animation. No arrow key may move JupyterLab's active cell. The Tab stops of each
panel are counted (few stops per panel). Screenshots: tests/artifacts/kbd_NN_*.png.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from .lab import Lab, open_notebook, viewers, wait_idle

pytestmark = pytest.mark.browser

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


def _run_by_keyboard(page: Any, lab: Lab, name: str) -> int:
    """Shift+Enter on every cell from the first; returns the number of cells."""
    n = len(json.loads((lab.root / name).read_text(encoding="utf-8"))["cells"])
    page.locator(".jp-Notebook").focus()  # the notebook has the keyboard focus, as after opening it
    page.keyboard.press("Escape")
    page.keyboard.press("Control+Home")
    for _ in range(n):
        page.keyboard.press("Shift+Enter")
        page.wait_for_timeout(40)
    page.wait_for_function(
        """() => [...document.querySelectorAll('.jp-Notebook .jp-CodeCell .jp-InputPrompt')]
            .every((p) => !/\\[\\*\\]/.test(p.textContent))""",
        timeout=300_000,
    )
    wait_idle(page, 300_000)
    return n


def _walk_to_cell(page: Any, index: int) -> None:
    """Command mode, then ArrowUp until cell ``index`` is the active one."""
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


def test_lecture_03_by_keyboard_alone(lab: Lab, page: Any, artifacts: Path) -> None:
    name = "03_puma560_forward_kinematics.ipynb"
    open_notebook(page, lab, name)
    _run_by_keyboard(page, lab, name)
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


def test_lecture_08_by_keyboard_alone(lab: Lab, page: Any, artifacts: Path) -> None:
    name = "08_three_step_wrist_frame.ipynb"
    open_notebook(page, lab, name)
    _run_by_keyboard(page, lab, name)
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
