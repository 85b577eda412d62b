"""The lectures with joint panels (02-05) as saved: a picture for every panel, no widget state, small files.

A reader who opens a lecture without running it (JupyterLab before Run All, or a static page
built from the committed notebooks) must see each panel's picture, not a text repr. The
browser side of this is checked in tests/browser; here the saved files themselves.
"""

from __future__ import annotations

import base64
import html
import re
from pathlib import Path

import nbformat
import pytest

NOTEBOOKS = Path(__file__).resolve().parents[2] / "notebooks"
LECTURES = ["02_dh_frame_attachment", "03_puma560_forward_kinematics", "04_mk3_forward_kinematics",
            "05_porter_direct_problem"]  # fmt: skip
WIDGET = "application/vnd.jupyter.widget-view+json"


def _panel_cells(nb):
    return [c for c in nb.cells if c.cell_type == "code" and "_panel(" in c.source]


IMG = re.compile(r'^<img src="data:image/png;base64,([A-Za-z0-9+/=]+)" alt="([^"]*)">$')


def _picture(bundle) -> tuple[str, str]:
    """The base64 PNG and the alt of a panel's saved picture (``<img alt>`` in text/html)."""
    text = bundle["text/html"]
    m = IMG.match(("".join(text) if isinstance(text, list) else text).strip())
    assert m, f"the panel's picture is not one <img alt>: {str(text)[:200]}"
    return m.group(1), html.unescape(m.group(2))


@pytest.mark.parametrize("name", LECTURES)
def test_every_panel_leaves_a_picture(name):
    nb = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
    cells = _panel_cells(nb)
    assert cells, f"{name} has no panel"
    for cell in cells:
        # widget output differs run to run: nbval skips it by the cell's tag, no pragma in what a student reads
        assert "nbval-ignore-output" in cell.metadata.get("tags", []) and "NBVAL" not in cell.source
        bundles = [o["data"] for o in cell.outputs if o.get("output_type") in ("execute_result", "display_data")]
        assert len(bundles) == 1 and WIDGET in bundles[0], "the panel is not the cell's result"
        # the picture is an <img alt> in text/html, its one copy (JupyterLab gives a bare image/png no alt)
        assert "image/png" not in bundles[0]
        png = base64.b64decode(_picture(bundles[0])[0])
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and 10_000 < len(png) < 150_000
        # its alt is the cell's own (the one the site gives it), a sentence
        alt = cell.metadata["mystnb"]["image"]["alt"]
        assert _picture(bundles[0])[1] == alt and len(alt) > 40


@pytest.mark.parametrize("name", LECTURES)
def test_no_widget_state_and_under_1_5_mb(name):
    path = NOTEBOOKS / f"{name}.ipynb"
    nb = nbformat.read(path, as_version=4)
    # a saved widget state would carry the viewer's whole module and make static pages try (and fail)
    # to run the widget instead of showing the picture: execute with --ExecutePreprocessor.store_widget_state=False
    assert "widgets" not in nb.metadata
    assert path.stat().st_size < 1_500_000


def test_static_html_shows_the_panel_picture():
    from nbconvert import HTMLExporter

    nb = nbformat.read(NOTEBOOKS / "03_puma560_forward_kinematics.ipynb", as_version=4)
    (cell,) = _panel_cells(nb)
    png, alt = _picture(next(o["data"] for o in cell.outputs if "data" in o))
    page, _ = HTMLExporter().from_notebook_node(nb)
    assert f"data:image/png;base64,{png[:200]}" in page.replace("\n", "")
    # the page's <img> of the picture carries the cell's alt (nbconvert may re-escape it)
    img = re.search(r'<img [^>]*src="data:image/png;base64,' + re.escape(png[:200]) + r"[^>]*>", page.replace("\n", ""))
    assert img and html.unescape(re.search(r'alt="([^"]*)"', img.group(0)).group(1)) == alt
    assert "Panel(children" not in page


ALL = sorted(NOTEBOOKS.glob("[0-9][0-9]_*.ipynb"))


@pytest.mark.parametrize("path", ALL, ids=lambda p: p.stem[:2])
def test_no_test_machinery_and_stored_as_jupyterlab_4_writes_it(path):
    """No nbval pragma in a cell; the metadata JupyterLab 4 writes, so opening the lecture changes nothing."""
    nb = nbformat.read(path, as_version=4)
    assert not [c.id for c in nb.cells if "NBVAL" in c.source], "an nbval pragma in a cell: use the cell tag"
    assert (nb.nbformat, nb.nbformat_minor) == (4, 5) and all("id" in c for c in nb.cells)
    assert nb.metadata.kernelspec == {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}


WITH_WIDGETS = [p for p in ALL if "application/vnd.jupyter.widget-view+json" in p.read_text(encoding="utf-8")]


@pytest.mark.parametrize("path", WITH_WIDGETS, ids=lambda p: p.stem[:2])
def test_every_saved_still_is_an_img_with_its_cells_alt(path):
    """Issue 34: a panel's or viewer's saved picture reaches JupyterLab with alt text (no bare image/png beside it)."""
    nb = nbformat.read(path, as_version=4)
    stills = 0
    for k, cell in enumerate(nb.cells):
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if WIDGET not in data:
                continue
            stills += 1
            assert "image/png" not in data, f"{path.name} cell {k}: a bare PNG beside the widget"
            png, alt = _picture(data)
            assert base64.b64decode(png)[:8] == b"\x89PNG\r\n\x1a\n"
            assert alt == cell.metadata["mystnb"]["image"]["alt"], f"{path.name} cell {k}: not the site's alt"
            assert not cell.metadata["mystnb"]["image"].get("alt_auto"), f"{path.name} cell {k}: a generated alt"
    assert stills > 0
