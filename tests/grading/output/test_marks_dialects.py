"""Marks files as spreadsheets save them (puma_course/grading/output/marks.py): every dialect, the same marks.

A marker fills in the marks template of ``collect-written`` in a spreadsheet and saves it as CSV. Excel or
LibreOffice set to a decimal comma (much of Europe) save it with semicolons and write ``0,5``; a "text"
export uses tabs (Excel's "Unicode text" in UTF-16). ``grade --marks`` reads the separator off the header
row, so each of these files gives exactly the marks the comma file gives, and a bad value in any of them
is still refused naming its row and column (exit code 2 from ``grade``, as ``test_written`` checks for
commas). Before the separator was read, every file here but the comma one was refused: its header is one
column.
"""

from __future__ import annotations

import csv
import io
import shutil
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading.output.marks import read_marks, separator
from puma_course.grading.written import written_questions
from tests.support import ROOT

EX = "ex02_dh_frames"
QID = written_questions(EX)[0].qid
STUDENTS = ["ann", "bob", "cy", "Dora Díaz"]
HEAD = ["student", "exercise", "question", "points", "comment", "z axes", "origin 1", "origin 2", "x axes"]
#: ann by rubric line (halves), bob by points only (a half), cy not marked yet, Dora with a comment holding
#: every separator and a quote
ROWS = [
    ["ann", EX, QID, "", "Good sketch, x2 is missing.", "1", "1", "0.5", "0"],
    ["bob", EX, QID, "1.5", "Only frame {1}; but right.", "", "", "", ""],
    ["cy", EX, QID, "", "", "", "", "", ""],
    ["Dora Díaz", EX, QID, "3", 'Said "z2 = -y0",\tin words; fine.', "", "", "", ""],
]


def _save(rows: list[list[str]], sep: str, decimal: str) -> str:
    """The file a spreadsheet writes: ``sep`` between cells, ``decimal`` in numbers, quotes where needed."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, delimiter=sep, lineterminator="\r\n")
    for row in rows:
        writer.writerow([c.replace(".", decimal) if c.replace(".", "", 1).isdigit() else c for c in row])
    return buffer.getvalue()


DIALECTS = {
    "comma": (",", ".", "utf-8"),
    "comma, BOM": (",", ".", "utf-8-sig"),
    "semicolon, decimal comma": (";", ",", "utf-8"),
    "semicolon, decimal comma, BOM": (";", ",", "utf-8-sig"),
    "semicolon, decimal point": (";", ".", "utf-8"),
    "tab, decimal comma": ("\t", ",", "utf-8"),
    "tab, decimal point": ("\t", ".", "utf-8"),
    "tab, UTF-16 (Excel's Unicode text)": ("\t", ",", "utf-16"),
}


def _write(tmp_path: Path, name: str, rows: list[list[str]]) -> Path:
    sep, decimal, encoding = DIALECTS[name]
    path = tmp_path / (name.replace(" ", "_").replace(",", "").replace("'", "")[:30] + ".csv")
    path.write_bytes(_save(rows, sep, decimal).encode(encoding))
    return path


def _marks(path: Path):
    return read_marks([path], STUDENTS, [EX]).marks


@pytest.mark.parametrize("name", list(DIALECTS))
def test_every_dialect_gives_the_marks_of_the_comma_file(tmp_path, name):
    expected = _marks(_write(tmp_path, "comma", [HEAD, *ROWS]))
    assert expected["ann", EX, QID].points == 2.5 and expected["bob", EX, QID].points == 1.5
    assert expected["ann", EX, QID].criteria == (("z axes", 1.0), ("origin 1", 1.0), ("origin 2", 0.5), ("x axes", 0.0))
    assert expected["cy", EX, QID].points is None
    assert expected["Dora Díaz", EX, QID].comment == 'Said "z2 = -y0",\tin words; fine.'
    path = _write(tmp_path, name, [HEAD, *ROWS])
    if DIALECTS[name][1] == ",":
        assert b"0,5" in path.read_bytes() or "0,5".encode("utf-16-le") in path.read_bytes()
    assert _marks(path) == expected


def test_the_separator_is_the_one_that_splits_the_header():
    assert separator("student;exercise;question;points;comment\r\nann;ex;q4;1,5;a, b\r\n") == ";"
    assert separator('"student"\t"exercise"\t"question"\t"points"\n') == "\t"
    assert separator("student,exercise,question,comment;x\n") == ","
    assert separator("name;ex;q\n") == ","  # not a marks header: read with commas, the column check names it


@pytest.mark.parametrize("name", ["semicolon, decimal comma", "tab, decimal comma"])
@pytest.mark.parametrize(
    ("row", "said"),
    [
        (["dora", EX, QID, "1", "", "", "", "", ""], "row 3, column 'student'"),
        (["bob", EX, "q9", "1", "", "", "", "", ""], "row 3, column 'question'"),
        (["bob", EX, QID, "4.5", "", "", "", "", ""], "row 3, column 'points': expected at most 4"),
        (["bob", EX, QID, "1.5.1", "", "", "", "", ""], "row 3, column 'points': expected a number"),
        (["bob", EX, QID, "", "", "1.5", "", "", ""], "row 3, column 'z axes': expected at most 1"),
        (["bob", EX, QID, "3.5", "", "1", "0.5", "", ""], "row 3, column 'points': expected the sum"),
    ],
)
def test_a_bad_value_in_another_dialect_is_named_by_row_and_column(tmp_path, name, row, said):
    path = _write(tmp_path, name, [HEAD, ROWS[0], row])
    with pytest.raises(ValueError, match="marks ") as exc:
        _marks(path)
    assert said in str(exc.value) and str(path) in str(exc.value)


def test_grade_merges_a_semicolon_file_and_stops_on_a_bad_one(tmp_path, capsys):
    """The command a marker runs: the European file merges; a bad row in it exits 2, nothing graded."""
    handed_in = tmp_path / "hand-in"
    for student in ("ann", "bob", "cy"):  # the exercise as released, handed in blank
        (handed_in / student).mkdir(parents=True)
        shutil.copy(ROOT / "exercises" / f"{EX}.ipynb", handed_in / student)
    good = _write(tmp_path, "semicolon, decimal comma", [HEAD, *ROWS[:3]])
    out = tmp_path / "g" / "grades.csv"
    args = ["grade", str(handed_in), "-o", str(out), "--course", str(ROOT), "--exercise", EX, "--seed", "1"]
    assert main([*args, "--marks", str(good), "--quiet", "--sandbox", "none"]) == 0
    with open(out, newline="", encoding="utf-8") as fh:
        grades = {r["student"]: r for r in csv.DictReader(fh)}
    assert [grades[s][f"written:{QID}"] for s in ("ann", "bob", "cy")] == ["2.5", "1.5", ""]
    capsys.readouterr()
    bad = _write(tmp_path, "tab, decimal comma", [HEAD, ["ann", EX, QID, "4,5", "", "", "", "", ""]])
    other = tmp_path / "other.csv"
    assert main([*args[:3], str(other), *args[4:], "--marks", str(bad), "--quiet", "--sandbox", "none"]) == 2
    err = capsys.readouterr().err
    assert "row 2, column 'points': expected at most 4" in err and str(bad) in err
    assert not other.exists()
