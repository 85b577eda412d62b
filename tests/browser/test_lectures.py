"""The IK ghosts, their selector and the animation's play button on a scratch notebook; START_HERE and an exercise
open unmodified. The lectures' own checks: ``checks_lectures.py`` (run by ``test_lectures_01_to_05.py`` and
``test_lectures_06_to_10.py`` on one page per lecture).
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path
from typing import Any

import nbformat
import numpy as np
import pytest

from .checks_lectures import _panel_cells, _readout
from .lab import Lab, open_notebook, run_all, viewers

pytestmark = pytest.mark.browser


SCRATCH = """\
import numpy as np
from puma_course import Puma560
from puma_course.viz import robot_panel, RobotViewer
arm = Puma560()
q = np.radians([10.0, -30.0, 20.0, 10.0, 40.0, 10.0])
panel = robot_panel(arm, q=q, ik=True)
panel"""

SCRATCH_ANIM = """\
v = RobotViewer(arm, "qz", labels="ends")
v.set_targets(arm.fk(arm.q("qr")))
v.animate(np.linspace(arm.q("qz"), arm.q("qr"), 12), fps=30)
v"""


def test_ik_ghosts_and_animation_in_chromium(lab: Lab, page: Any, artifacts: Path) -> None:
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(SCRATCH), nbformat.v4.new_code_cell(SCRATCH_ANIM)]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"}
    nbformat.write(nb, lab.root / "scratch_viewer.ipynb")
    open_notebook(page, lab, "scratch_viewer.ipynb")
    run_all(page)
    boxes = viewers(page)
    boxes.nth(1).wait_for(timeout=30_000)
    panel_box, anim_box = boxes.nth(0), boxes.nth(1)
    page.wait_for_function("b => b.__puma.ghosts === 8 && b.__puma.selected === 0", arg=panel_box.element_handle())
    arm_q = np.radians([10.0, -30.0, 20.0, 10.0, 40.0, 10.0])
    T0 = _readout(page)

    # the selector highlights another ghost; the button moves the arm there, the hand pose stays
    select = page.locator(".jp-Notebook .widget-dropdown select").first
    options = select.locator("option").all_inner_texts()
    assert len(options) == 8 and all(re.match(r"\d:\s(left|right)/(up|down)/(no)?flip", o) for o in options)
    select.select_option(index=3)
    page.wait_for_function("b => b.__puma.selected === 3", arg=panel_box.element_handle())
    before = panel_box.evaluate("b => b.__puma.poseRenders")
    page.get_by_role("button", name="move the arm there").click()
    page.wait_for_function("([b, n]) => b.__puma.poseRenders > n", arg=[panel_box.element_handle(), before])
    page.wait_for_timeout(300)
    np.testing.assert_allclose(_readout(page), T0, atol=2e-4)
    moved = np.radians(
        [
            float(x.replace("\u2212", "-"))
            for x in page.locator(".jp-Notebook .widget-slider .widget-readout").all_inner_texts()[:6]
        ]
    )
    assert np.abs(moved - arm_q).max() > 0.1  # another configuration ...
    panel_box.scroll_into_view_if_needed()
    _panel_cells(page).first.locator(".jp-OutputArea").screenshot(path=str(artifacts / "ik_ghosts.png"))

    # the animation plays in the browser: the step counter runs to the end
    anim_box.scroll_into_view_if_needed()
    assert anim_box.evaluate("b => b.__puma.animSteps") == 12
    anim_box.get_by_role("button", name=re.compile("play")).click()
    page.wait_for_function("b => b.__puma.animStep === 11", arg=anim_box.element_handle(), timeout=10_000)
    origins = np.array(anim_box.evaluate("b => b.__puma.origins"))
    from puma_course import Puma560

    np.testing.assert_allclose(origins[-1], Puma560().fk(Puma560().q("qr"))[:3, 3], atol=1e-4)
    anim_box.screenshot(path=str(artifacts / "animation_end.png"))
    assert not page.errors, f"errors on the page: {page.errors}"


def test_start_here_and_an_exercise_open_unmodified(lab: Lab, page: Any) -> None:
    """START_HERE and an exercise (saved without language_info.version) open with no ● on their tab."""
    from tests.support import ROOT

    folder = lab.root / "course"  # a course folder in the worker's server (lab.Lab serves a copy of notebooks/)
    (folder / "exercises").mkdir(parents=True, exist_ok=True)
    (folder / "START_HERE.ipynb").write_bytes((ROOT / "START_HERE.ipynb").read_bytes())
    exercise = sorted((ROOT / "exercises").glob("*.ipynb"))[0]
    (folder / "exercises" / exercise.name).write_bytes(exercise.read_bytes())
    try:
        for name in ("course/START_HERE.ipynb", f"course/exercises/{exercise.name}"):
            open_notebook(page, lab, name)
            page.wait_for_timeout(1500)  # the kernel's language_info has arrived (idle) and been written
            dirty = page.locator(".lm-DockPanel-tabBar .lm-TabBar-tab.jp-mod-dirty")
            assert dirty.count() == 0, f"{name}: JupyterLab marks the notebook modified right after opening it"
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        lab.shutdown_kernels()
