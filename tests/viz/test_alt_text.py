"""Figures carry their alt text into JupyterLab (issue 34): ``figure_alt`` in an IPython shell, and every lecture."""

from __future__ import annotations

import base64
import html
import json
import re
from pathlib import Path

import pytest

from puma_course.viz.alt_text import img_html

ROOT = Path(__file__).resolve().parents[2]
LECTURES = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
WIDGET = "application/vnd.jupyter.widget-view+json"
IMG = re.compile(r'^<img src="data:image/png;base64,([A-Za-z0-9+/=]+)" alt="([^"]*)">$')


@pytest.fixture
def shell():
    pytest.importorskip("matplotlib_inline")
    from IPython.core.interactiveshell import InteractiveShell

    sh = InteractiveShell.instance()
    sh.run_cell("%matplotlib inline", silent=True)
    yield sh
    InteractiveShell.clear_instance()


def _figures(shell, code: str, key: str = "") -> list[dict]:
    """The display bundles of the figures a cell shows (a PNG, bare or in an ``<img>``)."""
    from IPython.utils.capture import capture_output

    with capture_output() as cap:
        result = shell.run_cell(code)
    assert result.success, result.error_in_exec
    return [o.data for o in cap.outputs if "image/png" in o.data or "<img" in o.data.get("text/html", "")]


def test_a_cells_figures_carry_its_alt_as_html_beside_the_png_and_the_next_cell_does_not(shell):
    alt = 'Two lines: "up" & "down", crossing at x = 0.5.'
    code = "import matplotlib.pyplot as plt\nplt.plot([0, 1]); plt.plot([1, 0]); plt.show()\n"
    shown = _figures(shell, f"from puma_course.viz import figure_alt\nfigure_alt({alt!r})\n" + code + code)
    assert len(shown) == 2  # both figures of the cell
    for data in shown:
        m = IMG.match(data["text/html"])
        assert m, data["text/html"][:120]
        assert html.unescape(m.group(2)) == alt
        assert "image/png" not in data  # one copy of the picture, the one with the alt
        assert base64.b64decode(m.group(1))[:8] == b"\x89PNG\r\n\x1a\n"
    later = _figures(shell, code)
    assert len(later) == 1 and "text/html" not in later[0]  # the alt ended with its cell: a bare PNG again
    # the very PNG the inline backend draws (same figure, same size): the HTML's equals a bare one's
    again = _figures(shell, f"figure_alt({alt!r})\n" + code, key="text/html")
    assert IMG.match(again[0]["text/html"]).group(1) == later[0]["image/png"]


def test_img_html_escapes_the_alt_and_wraps_bytes():
    assert img_html(b"\x89PNG", "a < b") == '<img src="data:image/png;base64,iVBORw==" alt="a &lt; b">'


@pytest.mark.parametrize("alt", ["", "   ", None, 3])
def test_figure_alt_refuses_an_empty_alt(alt):
    from puma_course.viz import figure_alt

    with pytest.raises(ValueError, match="alt: expected"):
        figure_alt(alt)


@pytest.mark.parametrize("path", LECTURES, ids=lambda p: p.stem[:2])
def test_every_lecture_figure_carries_the_alt_of_its_cell_for_jupyterlab(path: Path):
    """Every figure a lecture keeps is an ``<img alt>`` (no bare PNG), its alt the site's (the cell's metadata)."""
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    figures = 0
    for k, cell in enumerate(cells):
        alt = cell.get("metadata", {}).get("mystnb", {}).get("image", {}).get("alt")
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            text = data.get("text/html", "")
            text = "".join(text) if isinstance(text, list) else text
            if WIDGET in data or not ("image/png" in data or text.startswith("<img")):
                continue
            figures += 1
            assert "image/png" not in data, f"{path.name} cell {k}: a bare PNG, without alt in JupyterLab"
            m = IMG.match(text.strip())
            assert m, f"{path.name} cell {k}: {text[:120]}"
            assert alt and html.unescape(m.group(2)) == alt, f"{path.name} cell {k}: the alt differs from the site's"
    assert figures > 0
