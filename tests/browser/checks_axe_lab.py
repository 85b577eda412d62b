"""axe-core's WCAG 2.1 A/AA rules over the lectures' outputs as JupyterLab shows them (issue 34).

JupyterLab is started as ``puma-course lab`` starts it (:class:`tests.browser.lab.Lab`: default settings,
127.0.0.1, stopped by PID). Each lecture is opened as a student first opens it (the committed outputs, the
notebook untrusted); the lectures with a joint panel are also run (Run All) so that their live widgets and
viewers are checked. axe is scoped to the notebook's output areas (``.jp-OutputArea``): JupyterLab's own
interface is not the course's. JupyterLab's default windowed notebook attaches only the cells in view, so each
code cell is scrolled into view and its output area checked in turn. The test fails on any violation and
lists, per lecture, each rule with its node count. Both checks are made on the one page per lecture of
``lab.Tab`` (collected by ``test_lectures_01_to_05.py`` and ``test_lectures_06_to_10.py``); the counts of the
last run are written to ``tests/artifacts/axe_lab.json``. No exception: a joint panel's saved picture, shown
before its cell runs, is an ``<img alt>`` too (``viz.viewer.with_picture``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from .lab import NOTEBOOKS, Tab
from .test_axe import TAGS, axe_script

LECTURES = sorted(p.name for p in NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"))


def _has_widgets(name: str) -> bool:
    cells = json.loads((NOTEBOOKS / name).read_text(encoding="utf-8"))["cells"]
    return any(
        "application/vnd.jupyter.widget-view+json" in out.get("data", {})
        for cell in cells
        for out in cell.get("outputs", [])
    )


RUN = [n for n in LECTURES if _has_widgets(n)]

_CELL_AXE = """async ([cell, tags]) => {
    const area = cell.querySelector('.jp-OutputArea');
    if (!area || !area.querySelector('.jp-OutputArea-output')) return [];
    const r = await axe.run(area, {runOnly: {type: 'tag', values: tags}, resultTypes: ['violations']});
    return r.violations.map(v => ({id: v.id, impact: v.impact, nodes: v.nodes.map(n => n.target.join(' ')),
                                   html: v.nodes[0] ? v.nodes[0].html.slice(0, 160) : ''}));
}"""


@pytest.fixture(scope="module")
def axe() -> str:
    script = axe_script()
    if script is None:
        pytest.skip("!!! axe-core is missing: npm install --prefix .ci axe-core@4; the JupyterLab checks SKIPPED !!!")
    return script.read_text(encoding="utf-8")


def audit_outputs(page: Any, script: str) -> dict[str, dict[str, Any]]:
    """{rule: {impact, nodes (count), cells, html}} over every code cell's output area, each scrolled into view."""
    page.add_script_tag(content=script)
    cells = page.locator(".jp-Notebook .jp-CodeCell")
    found: dict[str, dict[str, Any]] = {}
    for i in range(cells.count()):
        cell = cells.nth(i)
        cell.scroll_into_view_if_needed()
        page.wait_for_timeout(150)  # the windowed notebook attaches and lays the cell out
        for v in page.evaluate(_CELL_AXE, [cell.element_handle(), TAGS]):
            rule = found.setdefault(v["id"], {"impact": v["impact"], "nodes": 0, "cells": [], "html": v["html"]})
            rule["nodes"] += len(v["nodes"])
            rule["cells"].append(i)
    return found


def _record(artifacts: Path, key: str, found: dict[str, dict[str, Any]]) -> None:
    path = artifacts / "axe_lab.json"
    data = json.loads(path.read_text(encoding="utf-8")) if path.exists() else {}
    data[key] = found
    path.write_text(json.dumps(data, indent=1, sort_keys=True), encoding="utf-8")


def _check(key: str, found: dict[str, dict[str, Any]]) -> None:
    """No violation of any rule."""
    assert not found, f"{key}: WCAG 2.1 A/AA violations in the outputs: " + "; ".join(
        f"{rule} x{v['nodes']} (cells {v['cells']}: {v['html']})" for rule, v in found.items()
    )


def test_saved_outputs_meet_wcag21_aa_in_jupyterlab(name: str, tab: Tab, axe: str, artifacts: Path) -> None:
    page = tab.opened()
    found = audit_outputs(page, axe)
    _record(artifacts, f"opened/{name}", found)
    _check(f"{name} (opened)", found)


def test_live_panels_meet_wcag21_aa_in_jupyterlab(name: str, tab: Tab, axe: str, artifacts: Path) -> None:
    page = tab.executed()
    found = audit_outputs(page, axe)
    _record(artifacts, f"run/{name}", found)
    _check(f"{name} (after Run All)", found)
