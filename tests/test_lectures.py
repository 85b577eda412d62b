"""What every lecture promises its reader, checked on the committed notebooks.

* **Typeset mathematics**: no caret or underscore notation (``x^2``, ``T_i``, ``^{i-1}T``, ``α_{i-1}``)
  in the Markdown outside math delimiters (``$…$``, ``$$…$$``), code spans, code blocks and link
  targets.
* **Structure**: the first cell links to the notation page and states what the student will be able
  to do ("## What you will be able to do"); at least one predict-then-run prompt ("**Predict.**");
  a closing "## You can now" list; errata of the sources, if any, in one section headed "## Errata"
  placed after the main line (after "## You can now").
* **Figures**: every PNG (bare, or in the ``<img alt>`` of ``figure_alt``) drawn at 100 dpi or more (the pHYs
  chunk matplotlib writes) and at least 480 px wide; every notebook under 1.5 MB.
"""

from __future__ import annotations

import re
import struct
from base64 import b64decode
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
LECTURES = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))

_MATH_OR_CODE = re.compile(
    r"\$\$.*?\$\$"  # display math
    r"|(?<!\\)\$[^$\n]+?(?<!\\)\$"  # inline math
    r"|```.*?```"  # code blocks
    r"|`[^`\n]*`"  # code spans
    r"|\]\([^)]*\)"  # link targets
    r"|<[^>\n]*>"  # HTML tags and autolinks
    r"|https?://\S+",
    re.S,
)
#: caret or underscore notation: x^2, ^{i-1}T, T_i, a_{i-1}, x_5,1 (a word character or brace around it)
_UNTYPESET = re.compile(r"[\w)}\]]\^|\^[\w{(]|(?<![\\\w])[A-Za-zα-ωΑ-Ω]_[\w{]")


def _markdown(nb) -> list[tuple[int, str]]:
    return [(i, c.source) for i, c in enumerate(nb.cells) if c.cell_type == "markdown"]


def _untypeset(text: str) -> list[str]:
    bare = _MATH_OR_CODE.sub(" ", text)
    return [bare[max(0, m.start() - 15) : m.end() + 15].replace("\n", " ") for m in _UNTYPESET.finditer(bare)]


def test_the_scanner_finds_what_it_should():
    """The math scan is not vacuous: it flags raw notation and passes typeset or code text."""
    assert _untypeset("the link matrix ^{i-1}T_i") and _untypeset("x^2 + y^2") and _untypeset("α_{i-1} is a twist")
    assert _untypeset("the point x_5 of Porter")
    assert not _untypeset("the link matrix ${}^{i-1}T_i$ and $$x^2$$, `ex01_rotations`, [a](b_c.ipynb)")
    assert not _untypeset("snake_case words in prose such as file_name are not maths")


@pytest.mark.parametrize("path", LECTURES, ids=lambda p: p.stem[:2])
def test_no_untypeset_mathematics(path):
    nb = nbformat.read(path, as_version=4)
    found = [(i, hit) for i, text in _markdown(nb) for hit in _untypeset(text)]
    assert not found, f"{path.name}: untypeset notation in markdown cells: {found[:8]}"


def _headings(nb) -> list[tuple[int, str]]:
    return [(i, line.strip()) for i, text in _markdown(nb) for line in text.splitlines() if line.startswith("#")]


@pytest.mark.parametrize("path", LECTURES, ids=lambda p: p.stem[:2])
def test_structure_outcomes_predict_closing_errata(path):
    nb = nbformat.read(path, as_version=4)
    first = nb.cells[0].source
    assert "notation" in first.lower() and "01_rotations_and_transforms.ipynb#notation" in first, (
        f"{path.name}: the first cell must link to the notation page (01_rotations_and_transforms.ipynb#notation)"
    )
    heads = _headings(nb)
    names = [h.lower() for _, h in heads]
    assert any("what you will be able to do" in h for h in names[:3]), f"{path.name}: no outcomes at the top"
    assert any("**predict.**" in text.lower() for _, text in _markdown(nb)), f"{path.name}: no predict prompt"
    closing = [i for i, h in heads if "you can now" in h.lower()]
    assert closing, f"{path.name}: no closing 'You can now' list"
    errata = [i for i, h in heads if h.lower().startswith("## errata")]
    assert len(errata) <= 1, f"{path.name}: errata must sit in one section"
    if errata:
        assert errata[0] > closing[0], f"{path.name}: the errata section belongs after the main line"


def _png_dpi_and_width(data: bytes) -> tuple[float | None, int]:
    width = struct.unpack(">I", data[16:20])[0]
    i = data.find(b"pHYs")
    if i < 0:
        return None, width
    ppu_x, _, unit = struct.unpack(">IIB", data[i + 4 : i + 13])
    return (ppu_x * 0.0254 if unit == 1 else None), width


@pytest.mark.parametrize("path", LECTURES, ids=lambda p: p.stem[:2])
def test_figures_readable_on_a_projector_and_notebook_small(path):
    assert path.stat().st_size < 1.5e6, f"{path.name} is {path.stat().st_size / 1e6:.2f} MB (limit 1.5 MB)"
    nb = nbformat.read(path, as_version=4)
    for i, cell in enumerate(nb.cells):
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            html = "".join(data.get("text/html", ""))
            # a figure with its alt is its PNG in an <img> (puma_course.viz.figure_alt), else a bare image/png
            inline = re.match(r'<img src="data:image/png;base64,([A-Za-z0-9+/=]+)"', html)
            png = data.get("image/png") or (inline.group(1) if inline else None)
            if not png:
                continue
            dpi, width = _png_dpi_and_width(b64decode(png))
            assert dpi is None or dpi >= 99.5, f"{path.name} cell {i}: figure at {dpi:.0f} dpi (at least 100)"
            assert width >= 480, f"{path.name} cell {i}: figure {width} px wide (at least 480)"


# ---- references into the lectures ---------------------------------------------------------------------
_SECTION = re.compile(r"^## (\d+) · ", re.M)
_REFERENCE = re.compile(r"lecture (\d\d) §(\d+(?:\.\d+)?)(?:-(\d+))?")


def _sections() -> dict[str, set[str]]:
    out = {}
    for path in LECTURES:
        nb = nbformat.read(path, as_version=4)
        out[path.stem[:2]] = {m.group(1) for _, src in _markdown(nb) for m in _SECTION.finditer(src)}
    return out


def _references(text: str) -> list[tuple[str, str]]:
    refs = []
    for m in _REFERENCE.finditer(text):
        refs.append((m.group(1), m.group(2)))
        if m.group(3):  # a range "§2-4" names its last section too
            refs.append((m.group(1), m.group(3)))
    return refs


def test_the_reference_scanner_reads_sections_and_ranges():
    assert _references("see lecture 08 §3.3 and lecture 09 §2-4.") == [("08", "3.3"), ("09", "2"), ("09", "4")]


def test_every_lecture_section_a_hint_or_an_exercise_names_exists():
    """Hints, mistake messages and exercises send the student to "lecture NN §N": that section must exist
    (the lectures' rewrite renumbered them once; a stale number sends a student to the wrong page)."""
    sections = _sections()
    files = [*(ROOT / "puma_course" / "grading").rglob("*.py"), *(ROOT / "solutions").glob("*.ipynb"),
             *(ROOT / "exercises").glob("*.ipynb"), *LECTURES, ROOT / "README.md",
             *(ROOT / "docs").glob("*.md")]  # fmt: skip
    bad = [
        f"{path.relative_to(ROOT)}: lecture {n} §{sec}"
        for path in files
        for n, sec in _references(path.read_text(encoding="utf-8"))
        if sec not in sections.get(n, set())
    ]
    assert sections["08"] >= {"1", "2", "3", "4", "5"}  # the scan itself found the sections
    assert not bad, bad
