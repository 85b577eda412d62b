"""Reading a submitted notebook in the worker: its code cells, IPython magics commented out, hidden tests removed.

The grader never parses a submission itself: the worker does it here, under the child's time and
memory limits, and reports only a reason code (and a JSON position) when the file is not a
readable notebook, never the file's contents.
"""

from __future__ import annotations

import json

__all__ = ["NotebookError", "strip_magics", "strip_hidden", "notebook_cells", "BEGIN_HIDDEN", "END_HIDDEN"]

BEGIN_HIDDEN, END_HIDDEN = "### BEGIN HIDDEN TESTS", "### END HIDDEN TESTS"
#: At most this many characters of code are run from one notebook.
MAX_CODE_CHARS = 5_000_000


class NotebookError(ValueError):
    """The notebook cannot be read: ``code`` says why (the grader words it), with a position for JSON errors."""

    def __init__(self, code: str, line: int = 0, column: int = 0) -> None:
        super().__init__(code)
        self.code, self.line, self.column = code, line, column


def strip_magics(source: str) -> str:
    """Comment out IPython-only lines (``%magic``, ``!shell``) so plain Python can run a cell.

    >>> strip_magics("%matplotlib inline\\nx = 1")
    '# %matplotlib inline\\nx = 1'
    """
    out = []
    for line in source.splitlines():
        stripped = line.lstrip()
        if stripped.startswith(("%", "!")):
            indent = line[: len(line) - len(stripped)]
            out.append(f"{indent}# {stripped}")
        else:
            out.append(line)
    return "\n".join(out)


def strip_hidden(source: str) -> str:
    """The cell without its ``### BEGIN HIDDEN TESTS`` ... ``### END HIDDEN TESTS`` blocks.

    An open block runs to the end of the cell.

    >>> strip_hidden("x = 1\\n### BEGIN HIDDEN TESTS\\nassert x == 2\\n### END HIDDEN TESTS\\ny = 2")
    'x = 1\\ny = 2'
    """
    if BEGIN_HIDDEN not in source:
        return source
    out, hidden = [], False
    for line in source.splitlines():
        stripped = line.strip()
        if stripped == BEGIN_HIDDEN:
            hidden = True
        elif stripped == END_HIDDEN:
            hidden = False
        elif not hidden:
            out.append(line)
    return "\n".join(out)


def notebook_cells(data: bytes) -> list[str]:
    """The code cells of a notebook file's bytes (nbformat 4, or 3's worksheets), hidden tests removed.

    >>> notebook_cells(b'{"cells": [{"cell_type": "code", "source": ["x = ", "1"]}, {"cell_type": "markdown"}]}')
    ['x = 1']
    >>> notebook_cells(b'{"cells": 3}')
    Traceback (most recent call last):
    ...
    puma_course.grading.run.worker.notebook.NotebookError: no-cells
    """
    try:
        nb = json.loads(data)
    except UnicodeDecodeError:
        raise NotebookError("encoding") from None
    except json.JSONDecodeError as exc:
        raise NotebookError("json", exc.lineno, exc.colno) from None
    except (RecursionError, MemoryError):
        raise NotebookError("nesting") from None
    if not isinstance(nb, dict):
        raise NotebookError("no-cells")
    cells, key = nb.get("cells"), "source"
    if cells is None and isinstance(nb.get("worksheets"), list) and nb["worksheets"]:
        cells, key = nb["worksheets"][0].get("cells") if isinstance(nb["worksheets"][0], dict) else None, "input"
    if not isinstance(cells, list):
        raise NotebookError("no-cells")
    sources, total = [], 0
    for cell in cells:
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        src = cell.get(key, "")
        if isinstance(src, list) and all(isinstance(s, str) for s in src):
            src = "".join(src)
        if not isinstance(src, str):
            raise NotebookError("cell")
        total += len(src)
        if total > MAX_CODE_CHARS:
            raise NotebookError("too-much-code")
        sources.append(strip_hidden(src))
    return sources
