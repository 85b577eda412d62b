"""Fixtures shared by the grading tests: notebook builders, a small exercise, a JupyterLab-like save."""

from __future__ import annotations

import nbformat
import numpy as np
import pytest

from puma_course.grading import Exercise, Question, load_bank
from tests.support import ROOT

# the course's question bank (ROOT/bank), imported as puma_course_bank before any test module needs it
load_bank(ROOT)


def _make_notebook(*cells: tuple[str, str, list[str] | None]) -> nbformat.NotebookNode:
    nb = nbformat.v4.new_notebook()
    for kind, src, tags in cells:
        make = nbformat.v4.new_code_cell if kind == "code" else nbformat.v4.new_markdown_cell
        nb.cells.append(make(src, metadata={"tags": tags} if tags else {}))
    return nb


@pytest.fixture
def make_notebook():
    """``make_notebook((kind, source, tags or None), ...)``: a notebook of code/markdown cells."""
    return _make_notebook


def _right_rotation(axis, angle):
    t = -angle if axis.startswith("-") else angle  # a turn about -e is a turn about e the other way
    c, s = np.cos(t), np.sin(t)
    return {
        "x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
        "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
        "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
    }[axis[-1]]


@pytest.fixture
def right_rotation():
    """A correct answer to ex01_rotations:q1, written out by hand."""
    return _right_rotation


@pytest.fixture
def small_exercise():
    """An exercise of two questions (``double``, 2 points; ``half``, a 1-point bonus), not registered."""
    public, no_hidden = ((1.0,),), lambda rng: []
    double = Question("q1", "double", 2, "twice x", public, no_hidden, reference=lambda x: 2 * x)
    half = Question("q2", "half", 1, "half x", public, no_hidden, reference=lambda x: x / 2, bonus=True)
    return Exercise("ex99_small", "A small exercise", (double, half))


def _jupyterlab_save(path, python_version: str = "3.12.4", run: bool = True) -> None:
    """Open ``path`` as JupyterLab 4 does, optionally run it, and save it (nbformat.write).

    JupyterLab fills in the kernel's full ``language_info`` (with the student's Python version),
    may add cell metadata (collapsed headings, scrolling), widget state, and, once cells ran,
    execution counts and outputs. None of that changes what the exercise asks.
    """
    nb = nbformat.read(path, as_version=4)
    nb.metadata["kernelspec"] = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
    nb.metadata["language_info"] = {
        "codemirror_mode": {"name": "ipython", "version": 3},
        "file_extension": ".py",
        "mimetype": "text/x-python",
        "name": "python",
        "nbconvert_exporter": "python",
        "pygments_lexer": "ipython3",
        "version": python_version,
    }
    nb.metadata["widgets"] = {"application/vnd.jupyter.widget-state+json": {"state": {}, "version_major": 2}}
    for count, cell in enumerate(nb.cells, start=1):
        if cell.cell_type == "markdown" and cell.source.startswith("## "):
            cell.metadata["jp-MarkdownHeadingCollapsed"] = True
        if run and cell.cell_type == "code":
            cell.metadata["scrolled"] = True
            cell.execution_count = count
            cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text="q1 ...: not attempted yet\n")]
    nbformat.write(nb, path)


@pytest.fixture
def jupyterlab_save():
    """``jupyterlab_save(path, python_version=..., run=True)``: what opening and saving in JupyterLab does."""
    return _jupyterlab_save
