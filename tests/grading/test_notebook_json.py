"""Notebooks read and written without nbformat (:mod:`puma_course.grading.publish.notebook_json`), checked
against nbformat.

* on every notebook of the course, reading gives what ``nbformat.reads(..., as_version=4)`` gives and writing
  gives ``nbformat.writes``'s exact text;
* every notebook ``release`` writes is valid under nbformat's schema (the check the release no longer pays for);
* ``release --check`` and ``check`` import neither nbformat nor jsonschema (whose format checkers take seconds).
"""

from __future__ import annotations

import copy
import json
import subprocess
import sys

import nbformat
import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.publish import notebook_json as nbjson
from puma_course.grading.publish.release import notebook_text, release_notebook
from tests.support import ROOT

NOTEBOOKS = sorted([*ROOT.glob("solutions/*.ipynb"), *ROOT.glob("exercises/*.ipynb"), *ROOT.glob("notebooks/*.ipynb")])


def test_the_course_has_notebooks_of_every_kind():
    assert {p.parent.name for p in NOTEBOOKS} == {"solutions", "exercises", "notebooks"} and len(NOTEBOOKS) >= 30


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_reading_and_writing_give_what_nbformat_gives(path):
    text = path.read_text(encoding="utf-8")
    theirs = nbformat.reads(text, as_version=4)
    mine = nbjson.reads(text)
    assert mine == theirs
    assert nbjson.writes(mine) == nbformat.writes(theirs)
    if path.parent.name == "exercises":  # what release writes, byte for byte
        assert nbjson.writes(mine) + "\n" == text
    assert mine.cells[0].cell_type == theirs.cells[0].cell_type  # attribute access, as NotebookNode's


def test_reading_drops_what_nbformat_drops_and_joins_split_strings():
    nb = {
        "cells": [
            {
                "cell_type": "code",
                "execution_count": 1,
                "id": "a1",
                "metadata": {"trusted": True, "tags": ["x"]},
                "outputs": [
                    {"output_type": "stream", "name": "stdout", "text": ["1\n", "2\n"]},
                    {
                        "output_type": "display_data",
                        "metadata": {},
                        "data": {"text/plain": ["a\n", "b"], "application/json": ["kept", "as a list"]},
                    },
                ],
                "source": ["x = 1\n", "print(x)"],
            },
            {"cell_type": "markdown", "id": "m1", "metadata": {}, "source": "one\ntwo", "attachments": {
                "p.png": {"image/png": "iVBOR"}, "s.svg": {"image/svg+xml": ["<svg>\n", "</svg>"]}}},
        ],
        "metadata": {"signature": "sha256:00", "orig_nbformat": 3, "kernelspec": {"name": "python3"}},
        "nbformat": 4,
        "nbformat_minor": 5,
    }  # fmt: skip
    text = json.dumps(nb)
    mine, theirs = nbjson.reads(text), nbformat.reads(text, as_version=4)
    assert mine == theirs
    assert mine.cells[0].outputs[0].text == "1\n2\n" and mine.cells[0].source == "x = 1\nprint(x)"
    assert "signature" not in mine.metadata and "trusted" not in mine.cells[0].metadata
    assert nbjson.writes(mine) == nbformat.writes(theirs)
    before = copy.deepcopy(mine)
    nbjson.writes(mine)
    assert mine == before  # writing leaves the notebook as it was


def test_an_older_format_is_converted_by_nbformat_itself():
    v3 = {
        "metadata": {"name": ""},
        "nbformat": 3,
        "nbformat_minor": 0,
        "worksheets": [{"cells": [{"cell_type": "code", "input": "x = 1", "language": "python", "outputs": [],
                                   "metadata": {}, "collapsed": False}], "metadata": {}}],
    }  # fmt: skip
    nb = nbjson.reads(json.dumps(v3))
    assert nb.nbformat == 4 and nb.cells[0].source == "x = 1"


def test_new_cells_and_notebooks_are_nbformats():
    for mine, theirs in [
        (nbjson.new_code_cell("x", metadata={"tags": ["t"]}), nbformat.v4.new_code_cell("x", metadata={"tags": ["t"]})),
        (nbjson.new_markdown_cell("# A"), nbformat.v4.new_markdown_cell("# A")),
        (nbjson.new_raw_cell("r"), nbformat.v4.new_raw_cell("r")),
    ]:
        assert len(mine.id) == 8 and mine.id != nbjson.new_raw_cell().id  # random, as nbformat's
        assert {**mine, "id": "-"} == {**theirs, "id": "-"}
        nbformat.validate(mine, ref=f"{mine.cell_type}_cell", version=4, version_minor=5)
    assert nbjson.new_notebook() == nbformat.v4.new_notebook()
    nbformat.validate(nbjson.new_notebook(cells=[nbjson.new_code_cell("x")]))


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_every_released_notebook_is_valid_under_nbformats_schema(name):
    generated = release_notebook(nbjson.read(ROOT / "solutions" / f"{name}.ipynb"), EXERCISES[name])
    nbformat.validate(generated)
    nbformat.validate(nbformat.reads(notebook_text(generated), as_version=4))
    assert notebook_text(generated) == (ROOT / "exercises" / f"{name}.ipynb").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    "args", [["release", "--check"], ["check", "exercises/ex01_rotations.ipynb"]], ids=lambda a: a[0]
)
def test_a_command_that_reads_notebooks_imports_no_validator(args):
    code = (
        "import sys\nfrom puma_course.cli import main\n"
        f"code = main({[*args, '--course', str(ROOT)]!r})\n"
        "print(code, sorted(m for m in ('nbformat', 'jsonschema', 'rfc3987_syntax') if m in sys.modules))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert done.stdout.strip().splitlines()[-1] in ("0 []", "1 []"), done.stdout + done.stderr
