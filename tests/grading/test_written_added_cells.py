"""A written answer continued in cells the student added below the answer cell (puma_course/grading/written.py).

A student who runs out of room in the answer cell (or wants a second sketch) presses B and writes on in a
new Markdown cell. ``collect-written`` read only the cell tagged ``written:qN``, so that text was lost to
the marker. It now reads on: the Markdown cells the student added below the answer cell, up to the first
code cell, cell tagged ``written…`` or cell of the release (``exercises/``, known by cell id, or by text
when a copy has a new id), are part of the answer, and the marking document says so. Checked here on
ex02's written question, handed in as the release with cells added around it, and end to end through
``puma-course collect-written``.
"""

from __future__ import annotations

import base64

import nbformat
import pytest

from puma_course.cli import main
from puma_course.grading.bank_loader import load_bank
from puma_course.grading.written import ANSWER_TAG, PROMPT_TAG, Release, read_answers, release_of, written_questions
from tests.support import ROOT

EX = "ex02_dh_frames"
QID = written_questions(EX)[0].qid
PNG = b"\x89PNG\r\n\x1a\n" + bytes(range(30))
FIRST = "Frame {1}: $z_1$ up the column, origin at the shoulder."
MORE = "Frame {2}: $z_2 = -y_0$, the tip raised; $x_2$ along the common normal."
LAST = "So $d_2$ is the only variable of joint 2."


@pytest.fixture(autouse=True)
def _this_course():
    """The release is read from the loaded course's ``exercises/``: load this repository's bank, whatever another
    test run before in the same process loaded (a course copy without ``exercises/`` gives no release)."""
    load_bank(ROOT)


def _released() -> nbformat.NotebookNode:
    return nbformat.read(ROOT / "exercises" / f"{EX}.ipynb", as_version=4)


def _answer_index(nb) -> int:
    return next(i for i, c in enumerate(nb.cells) if ANSWER_TAG + QID in c.metadata.get("tags", []))


def _hand_in(*added, answer: str = FIRST) -> bytes:
    """The release with ``answer`` in the answer cell and ``added`` cells inserted just below it."""
    nb = _released()
    i = _answer_index(nb)
    nb.cells[i].source = answer
    nb.cells[i + 1 : i + 1] = list(added)
    return nbformat.writes(nb).encode()


def md(text: str, **kw) -> nbformat.NotebookNode:
    return nbformat.v4.new_markdown_cell(text, **kw)  # a new cell: a fresh random id, as JupyterLab gives


def test_markdown_cells_added_below_the_answer_are_part_of_it():
    sketch = md("![second sketch](attachment:s2.png)")
    sketch["attachments"] = {"s2.png": {"image/png": base64.b64encode(PNG).decode()}}
    answer = read_answers(_hand_in(md(MORE), md(""), sketch, md(LAST)), EX)[QID]
    assert answer.text == "\n\n".join([FIRST, MORE, sketch.source, LAST])  # in order; the empty cell adds nothing
    assert answer.images == [("s2.png", "png", PNG)]
    assert answer.notes == [
        "the answer goes on in 3 cells the student added below the answer cell: shown after it, in order"
    ]
    # the release's closing cell, just below them, is not part of the answer
    closing = _released().cells[_answer_index(_released()) + 1].source
    assert closing.strip() and closing.strip() not in answer.text


def test_nothing_added_reads_as_before():
    answer = read_answers(_hand_in(), EX)[QID]
    assert answer.text == FIRST and not answer.notes and not answer.images


def test_a_code_cell_ends_the_answer():
    code = nbformat.v4.new_code_cell("import numpy as np  # trying something out")
    answer = read_answers(_hand_in(md(MORE), code, md(LAST)), EX)[QID]
    assert answer.text == f"{FIRST}\n\n{MORE}" and LAST not in answer.text


def test_a_cell_of_the_release_ends_the_answer_by_id_or_by_text():
    nb = _released()
    i = _answer_index(nb)
    closing = nb.cells[i + 1]
    nb.cells[i].source = FIRST
    closing.source = "I have read this."  # the student edited the closing cell: it keeps the release's id
    nb.cells[i + 1 : i + 1] = [md(MORE)]
    nb.cells.insert(i + 3, md(LAST))
    data = nbformat.writes(nb).encode()
    assert b"I have read this." in data and f'"id": "{closing.id}"'.encode() in data
    assert read_answers(data, EX)[QID].text == f"{FIRST}\n\n{MORE}"
    closing = _released().cells[i + 1]
    copied = md(closing.source)  # a copy of a release cell (a new id): known by its text
    assert read_answers(_hand_in(md(MORE), copied, md(LAST)), EX)[QID].text == f"{FIRST}\n\n{MORE}"


def test_a_written_tag_ends_the_answer():
    for tag in (ANSWER_TAG + "q9", PROMPT_TAG + "q9"):
        tagged = md("another question's cell", metadata={"tags": [tag]})
        assert read_answers(_hand_in(md(MORE), tagged, md(LAST)), EX)[QID].text == f"{FIRST}\n\n{MORE}"


def test_an_answer_cell_that_lost_its_tag_is_read_on_too():
    nb = _released()
    i = _answer_index(nb)
    nb.cells[i].source, nb.cells[i].metadata["tags"] = FIRST, []
    nb.cells[i + 1 : i + 1] = [md(MORE)]
    answer = read_answers(nbformat.writes(nb).encode(), EX)[QID]
    assert answer.text == f"{FIRST}\n\n{MORE}"
    assert answer.notes[0].startswith("the answer cell lost its tag") and "goes on in 1 cell" in answer.notes[1]


def test_without_the_release_the_cells_below_are_left_unread_and_the_marker_told():
    answer = read_answers(_hand_in(md(MORE)), EX, None)[QID]
    assert answer.text == FIRST
    assert answer.notes == [
        "2 Markdown cells below the answer cell were not read: without the released exercise they cannot be "
        "told from its own cells"
    ]


def test_the_release_is_read_from_the_course_exercises():
    release = release_of(EX)
    assert isinstance(release, Release)
    nb = _released()
    assert all(release.holds(c) for c in nb.cells)
    assert not release.holds(md(MORE)) and not release.holds({"id": ["not", "a", "string"], "source": 3})
    assert release_of("no_such_exercise") is None


def test_collect_written_shows_the_added_cells_in_the_marking_document(tmp_path, capsys):
    sub = tmp_path / "hand-in"
    (sub / "ann").mkdir(parents=True)
    (sub / "ann" / f"{EX}.ipynb").write_bytes(_hand_in(md(MORE), md(LAST)))
    out = tmp_path / "marking"
    assert main(["collect-written", str(sub), "-o", str(out), "--course", str(ROOT), "--exercise", EX]) == 0
    capsys.readouterr()
    doc = (out / f"{EX}-{QID}.md").read_text(encoding="utf-8")
    answer = doc.split("### `ann`")[1]
    assert "*the answer goes on in 2 cells the student added below the answer cell: shown after it, in order*" in (
        answer
    )
    quoted = [line[2:] for line in answer.splitlines() if line.startswith("> ")]
    assert quoted == [FIRST, MORE, LAST]


@pytest.mark.parametrize("name", sorted({"ex03_puma_fk", "ex06_porter_explicit"}))
def test_every_written_exercise_release_is_known(name):
    release = release_of(name)
    assert release is not None and release.ids
