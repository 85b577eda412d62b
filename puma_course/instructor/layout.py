"""How a lecture notebook is cut into slides that fit a projector, and where the speaker notes go.

The lectures are written to be read in JupyterLab, not shown: a section's ``##`` heading often sits in the
middle of a Markdown cell (after the previous section's answer to its Predict prompt), and a section runs to
several screens. :func:`slide_cells` works on a copy of the notebook, before nbconvert sees it:

1. every Markdown cell is split at each ``#``, ``##`` and ``###`` heading line (not inside a code fence or a
   ``$$`` block), and the heading's cell starts a slide (``#``, ``##``) or a vertical sub-slide (``###``);
2. the content then flows: each cell's height on the 1280×700 slide is estimated (:func:`estimate`), a cell
   that would take the (sub-)slide beyond :data:`BUDGET` starts a new sub-slide, a Markdown cell taller than
   the budget is split at its paragraphs first, and a code cell with a tall output (a figure, a long table)
   gets a sub-slide of its own;
3. the instructor notes (``instructor/notes/NN.md``) become speaker notes (``<aside class="notes">``, reveal's
   speaker view, key ``s``): the whole file on the title slide, and each numbered "Predict answers" item on the
   slide of the lecture's Predict prompt with that number, when the counts agree.

Cells the author marked ``skip`` or ``notes`` keep their type. Standard library and nbformat's node type only.
"""

from __future__ import annotations

import copy
import math
import re
from typing import Any

__all__ = ["BUDGET", "estimate", "split_markdown", "slide_cells", "predict_answers"]

#: the estimated height (px, on reveal's 1280×700 slide) a (sub-)slide may fill before the next cell moves on
BUDGET = 640
#: a code cell whose estimate is above this gets a sub-slide of its own
TALL_OUTPUT = 320
#: a code cell of more lines is tagged :data:`SMALL_CODE_TAG` and shown in a smaller font (the template's CSS)
LONG_CODE, SMALL_CODE_SCALE, SMALL_CODE_TAG = 18, 0.65, "puma-slides-long-code"
_CHARS_PER_LINE = 68  # the content column at the theme's font size
_LINE, _CODE_LINE, _PARAGRAPH = 27, 23, 20

_HEADING = re.compile(r"^(#{1,3}) \S")
_FENCE = re.compile(r"^\s*(```|~~~)")


def _blocks(source: str) -> list[tuple[str, bool]]:
    """The lines of a Markdown source, each with whether it is outside code fences and ``$$`` blocks."""
    out, fence, math_block = [], False, False
    for line in source.split("\n"):
        free = not fence and not math_block
        out.append((line, free))
        if _FENCE.match(line):
            fence = not fence
        elif not fence and line.strip().count("$$") % 2 == 1:
            math_block = not math_block
    return out


def split_markdown(source: str, at_paragraphs: bool = False) -> list[str]:
    """``source`` cut before every heading line of level 1-3 (and at blank lines when ``at_paragraphs``),
    never inside a code fence or a ``$$`` block; empty pieces are dropped.

    >>> split_markdown("Answer.\\n\\n## 2 · Next\\n\\nText")
    ['Answer.', '## 2 · Next\\n\\nText']
    """
    pieces: list[list[str]] = [[]]
    for line, free in _blocks(source):
        if free and (_HEADING.match(line) or (at_paragraphs and not line.strip())) and pieces[-1]:
            pieces.append([])
        if at_paragraphs and free and not line.strip():
            continue
        pieces[-1].append(line)
    texts = ["\n".join(p).strip("\n") for p in pieces]
    return [t for t in texts if t.strip()]


def _text_lines(text: str, per_line: int) -> int:
    return sum(max(1, math.ceil(len(line) / per_line)) for line in text.splitlines() if line.strip())


def _markdown_height(source: str) -> int:
    height, fence, in_math = 0, False, False
    for line in source.split("\n"):
        stripped = line.strip()
        if _FENCE.match(line):
            fence = not fence
            height += 12
        elif fence:
            height += _CODE_LINE
        elif in_math or stripped.startswith("$$"):
            if stripped.count("$$") % 2 == 1:
                in_math = not in_math
            one_line = stripped.count("$$") == 2  # $$ … $$ on one line: its rows are its \\ (line breaks)
            rows = 1 + (stripped.count("\\\\") if one_line else 0)
            content = stripped.replace("$$", "").strip()
            height += (30 + 6 * stripped.count("\\frac")) * rows if content else 12
        elif _HEADING.match(line):
            height += 70 if line.startswith(("# ", "## ")) else 50
        elif not stripped:
            height += _PARAGRAPH // 2
        else:
            height += _LINE * max(1, math.ceil(len(stripped) / _CHARS_PER_LINE)) + 6 * stripped.count("\\frac")
    return height


def _output_height(output: dict[str, Any]) -> int:
    data = output.get("data", {})
    html = "".join(data.get("text/html", ""))  # a str or a list of lines
    if any(k.startswith("image/") for k in data) or html.startswith("<img"):  # a figure, bare or with its alt
        return 440  # the template caps an image at 60 % of the slide's height
    if output.get("output_type") == "error":
        text = "\n".join(str(line) for line in output.get("traceback", []))
        return _CODE_LINE * _text_lines(re.sub("\x1b\\[[0-9;]*m", "", text), 110) + 10
    if output.get("output_type") == "stream":
        return _CODE_LINE * _text_lines(str(output.get("text", "")), 110) + 10
    if "text/html" in data:
        html = "".join(data["text/html"]) if isinstance(data["text/html"], list) else str(data["text/html"])
        if "_anim_img" in html:
            return 480
        rows = html.count("<tr") + html.count("<br") + html.count("<li")
        return 40 + 30 * max(1, rows) if rows else 40 + _LINE * _text_lines(re.sub("<[^>]+>", "", html), 110)
    if "text/latex" in data:
        latex = "".join(data["text/latex"]) if isinstance(data["text/latex"], list) else str(data["text/latex"])
        return 30 + 34 * max(1, latex.count("\\\\") + 1)
    if "text/plain" in data:
        text = "".join(data["text/plain"]) if isinstance(data["text/plain"], list) else str(data["text/plain"])
        return _CODE_LINE * _text_lines(text, 110) + 10
    return 30


def estimate(cell: Any) -> int:
    """The estimated height (px, on the 1280×700 slide) of a cell with its outputs."""
    if cell.cell_type == "markdown":
        return _markdown_height(cell.source)
    if cell.cell_type != "code":
        return 0
    lines = len(cell.source.splitlines())
    source = 0 if cell.get("metadata", {}).get("transient", {}).get("remove_source") else lines
    scale = SMALL_CODE_SCALE if lines > LONG_CODE else 1.0
    return 24 + int(_CODE_LINE * source * scale) + sum(_output_height(o) for o in cell.get("outputs", []))


_PREDICT_ITEM = re.compile(r"^(\d+)\.\s")


def predict_answers(notes: str) -> list[str]:
    """The numbered items under the notes' ``## Predict answers`` heading, in order (continuation lines kept).

    >>> predict_answers("## Predict answers\\n\\n1. Two.\\n2. Three,\\n   or four.\\n\\n## Next")
    ['Two.', 'Three,\\nor four.']
    """
    parts = re.split(r"^## Predict answers\s*$", notes, maxsplit=1, flags=re.M)
    if len(parts) < 2:
        return []
    body = re.split(r"^#{1,2} ", parts[1], maxsplit=1, flags=re.M)[0]
    items: list[list[str]] = []
    for line in body.splitlines():
        match = _PREDICT_ITEM.match(line)
        if match:
            items.append([line[match.end() :].strip()])
        elif items and line.strip():
            items[-1].append(line.strip())
    return ["\n".join(item) for item in items]


def _slide_type(cell: Any) -> str:
    return str(cell.get("metadata", {}).get("slideshow", {}).get("slide_type", "-"))


def _set(cell: Any, slide_type: str) -> None:
    cell.setdefault("metadata", {}).setdefault("slideshow", {})["slide_type"] = slide_type


def _notes_cell(nb: Any, source: str) -> Any:
    import nbformat

    # headings as bold lines: the speaker view shows notes in a narrow pane, where an <h1> fills it
    cell = nbformat.v4.new_markdown_cell(re.sub(r"^#{1,6} +(.+?)\s*$", r"**\1**", source, flags=re.M))
    _set(cell, "notes")
    return cell


def slide_cells(nb: Any, notes: str | None = None) -> Any:
    """A copy of the notebook ``nb`` cut into slides as the module says, with ``notes`` as speaker notes."""
    import nbformat

    nb = copy.deepcopy(nb)
    cells: list[Any] = []
    for cell in nb.cells:
        if cell.cell_type != "markdown" or _slide_type(cell) in ("skip", "notes"):
            cells.append(cell)
            continue
        pieces = split_markdown(cell.source)
        for k, piece in enumerate(pieces):
            if k == 0:
                cell.source = piece
                cells.append(cell)
            else:
                new = nbformat.v4.new_markdown_cell(piece)
                new.metadata = copy.deepcopy({k: v for k, v in cell.metadata.items() if k != "tags"})
                cells.append(new)

    for cell in cells:
        if cell.cell_type == "code" and len(cell.source.splitlines()) > LONG_CODE:
            cell.setdefault("metadata", {}).setdefault("tags", []).append(SMALL_CODE_TAG)
    cells = [part for cell in cells for part in _split_outputs(cell)]
    flowed: list[Any] = []
    used = 0  # the estimated height on the current (sub-)slide
    alone = False  # the last cell asked for a sub-slide of its own
    for cell in cells:
        kind = _slide_type(cell)
        if kind in ("skip", "notes"):
            flowed.append(cell)
            continue
        heading = _HEADING.match(cell.source) if cell.cell_type == "markdown" else None
        if not flowed or (heading and len(heading[1]) <= 2):
            _set(cell, "slide")
            used = 0
        elif heading:
            _set(cell, "subslide")
            used = 0
        else:
            _set(cell, "-")
        height = estimate(cell)
        if cell.cell_type == "markdown" and height > BUDGET:
            parts = split_markdown(cell.source, at_paragraphs=True)
        else:
            parts = [cell.source]
        for k, part in enumerate(parts):
            piece = cell if k == 0 else nbformat.v4.new_markdown_cell(part)
            if k:
                _set(piece, "-")
            piece.source = part
            h = estimate(piece)
            tall = piece.cell_type == "code" and h > TALL_OUTPUT
            starts = _slide_type(piece) in ("slide", "subslide")
            if not starts and used and (alone or tall or used + h > BUDGET):
                _set(piece, "subslide")
                used = 0
            used += h
            alone = tall
            flowed.append(piece)
    nb.cells = flowed
    if notes:
        _add_notes(nb, notes)
    return nb


def _split_outputs(cell: Any) -> list[Any]:
    """A code cell taller than the budget with several outputs, as the cell with its first outputs and
    source-less copies holding the rest (nbconvert leaves out the source of ``metadata.transient.remove_source``)."""
    outputs = cell.get("outputs", []) if cell.cell_type == "code" else []
    if len(outputs) < 2 or estimate(cell) <= BUDGET:
        return [cell]
    groups: list[list[Any]] = [[]]
    used = estimate(cell) - sum(_output_height(o) for o in outputs)
    for output in outputs:
        h = _output_height(output)
        if groups[-1] and used + h > BUDGET:
            groups.append([])
            used = 0
        groups[-1].append(output)
        used += h
    parts = []
    for k, group in enumerate(groups):
        part = copy.deepcopy(cell) if k else cell
        if k:
            if "id" in cell:
                part["id"] = f"{cell['id'][:56]}-out{k}"  # ids stay unique
            part.metadata["transient"] = {"remove_source": True}
            part.metadata.pop("tags", None)
        part.outputs = group
        parts.append(part)
    return parts


def _add_notes(nb: Any, notes: str) -> None:
    """The whole ``notes`` after the title slide's first cell; each Predict answer after its prompt's cell."""
    answers = predict_answers(notes)
    prompts = [k for k, c in enumerate(nb.cells) if c.cell_type == "markdown" and "**Predict" in c.source]
    out: list[Any] = []
    for k, cell in enumerate(nb.cells):
        out.append(cell)
        if k == 0:
            out.append(_notes_cell(nb, notes))
        if answers and len(answers) == len(prompts) and k in prompts:
            number = prompts.index(k) + 1
            out.append(_notes_cell(nb, f"**Predict {number}, the answer:** {answers[number - 1]}"))
    nb.cells = out
