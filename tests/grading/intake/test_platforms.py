"""Platform downloads in, gradebooks out: Canvas's flat folder and Moodle's folders graded, gradebooks parsed back.

The downloads are built from the course's own ``solutions/`` (full marks) and ``exercises/`` (0 points),
named as Canvas and Moodle name them (see :mod:`puma_course.grading.intake.collect`); the gradebooks are read
back with the csv module, so columns, order, quoting and numbers are checked as an import would read them.
"""

from __future__ import annotations

import csv
import shutil
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading.intake.collect import collect, parse_canvas_name
from puma_course.grading.output.gradebook import CANVAS_IDS, number
from tests.support import ROOT

EX1, EX2 = "ex01_rotations", "ex02_dh_frames"
HONEST = {EX1: ROOT / "solutions" / f"{EX1}.ipynb", EX2: ROOT / "solutions" / f"{EX2}.ipynb"}
BLANK = {EX1: ROOT / "exercises" / f"{EX1}.ipynb", EX2: ROOT / "exercises" / f"{EX2}.ipynb"}
MAX = {EX1: 15.0, EX2: 12.0}


def _rows(path: Path) -> list[list[str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.reader(fh))


def _dicts(path: Path) -> list[dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


@pytest.fixture
def canvas_download(tmp_path: Path) -> Path:
    d = tmp_path / "canvas"
    d.mkdir()
    # smithjohn uploaded a blank notebook, then again the honest one: Canvas renamed it ex01_rotations-1
    shutil.copy(BLANK[EX1], d / f"smithjohn_101_1001_{EX1}.ipynb")
    shutil.copy(HONEST[EX1], d / f"smithjohn_101_1002_{EX1}-1.ipynb")
    shutil.copy(HONEST[EX2], d / f"smithjohn_101_1003_{EX2}.ipynb")
    # doejane handed ex01 in late, with a scratch notebook beside it
    shutil.copy(HONEST[EX1], d / f"doejane_LATE_102_2001_{EX1}.ipynb")
    shutil.copy(BLANK[EX1], d / "doejane_LATE_102_2002_scratch.ipynb")
    (d / "notes.txt").write_text("not a submission", encoding="utf-8")
    return d


@pytest.fixture
def moodle_download(tmp_path: Path) -> Path:
    d = tmp_path / "moodle"
    ann = d / "Ann O'Neil, Jr_42_assignsubmission_file_"
    bob = d / 'Bob "Bobby" Li_43_assignsubmission_file_'
    for folder in (ann, bob):
        folder.mkdir(parents=True)
    shutil.copy(HONEST[EX1], ann / f"{EX1}.ipynb")
    shutil.copy(HONEST[EX2], ann / f"{EX2}.ipynb")
    shutil.copy(BLANK[EX1], bob / f"{EX1}.ipynb")
    (d / "Cy Z_44_assignsubmission_onlinetext_").mkdir()
    return d


def test_canvas_file_names_are_parsed_as_canvas_writes_them():
    p = parse_canvas_name(f"obrienanne_LATE_3_44_{EX1}-2.ipynb")
    assert (p["name"], p["late"], p["uid"], p["fid"], p["file"]) == ("obrienanne", "LATE_", "3", "44", f"{EX1}-2.ipynb")
    # a name that keeps an underscore (Canvas keeps word characters) and an anonymously graded file
    assert parse_canvas_name(f"o_brien_3_44_{EX1}.ipynb")["name"] == "o_brien"
    anon = parse_canvas_name(f"anon_Ab12_55_{EX1}.ipynb")
    assert (anon["name"], anon["uid"]) == ("", "anon_Ab12")


def test_collect_canvas_keeps_the_latest_upload_and_lists_what_it_did_not_grade(canvas_download):
    c = collect(canvas_download, "canvas", [EX1, EX2])
    people = c.by_key()
    assert set(people) == {"smithjohn_101", "doejane_102"}
    assert people["smithjohn_101"].files[EX1].name == f"smithjohn_101_1002_{EX1}-1.ipynb"
    assert people["doejane_102"].late == {EX1} and people["smithjohn_101"].late == set()
    assert people["doejane_102"].user_id == "102"
    text = "\n".join(c.problems)
    assert f"smithjohn_101_1001_{EX1}.ipynb" in text and "later upload" in text
    assert "doejane_LATE_102_2002_scratch.ipynb" in text and "matches no exercise" in text
    assert "notes.txt" in text and len(c.problems) == 3


def test_grade_canvas_download_writes_late_column_and_both_gradebooks(canvas_download, tmp_path, capsys):
    out = tmp_path / "out" / "grades.csv"
    args = ["grade", str(canvas_download), "-o", str(out), "--course", str(ROOT), "--layout", "canvas"]
    args += ["--exercise", EX1, "--exercise", EX2, "--gradebook", "canvas", "--gradebook", "wide", "--quiet"]
    assert main(args) == 0
    said = capsys.readouterr()
    assert "not graded:" in said.err and "scratch.ipynb" in said.err
    grades = {(r["student"], r["exercise"]): r for r in _dicts(out)}
    assert float(grades["smithjohn_101", EX1]["score"]) == MAX[EX1]  # the re-upload, not the blank first one
    assert float(grades["smithjohn_101", EX2]["score"]) == MAX[EX2]
    assert grades["doejane_102", EX1]["late"] == "late" and grades["smithjohn_101", EX1]["late"] == ""
    assert grades["doejane_102", EX2]["status"] == "missing"
    summary = (out.parent / "grades-summary.md").read_text(encoding="utf-8")
    assert "## Files not graded (3)" in summary and "notes.txt" in summary

    rows = _rows(out.parent / "grades-canvas.csv")
    assert rows[0] == [*CANVAS_IDS, EX1, EX2, "Final Points"]
    assert rows[1][0].strip() == "Points Possible" and [float(x) for x in rows[1][5:7]] == [MAX[EX1], MAX[EX2]]
    body = {r[1]: r for r in rows[2:]}  # by Canvas user id, as Canvas matches them
    assert set(body) == {"101", "102"}
    assert body["101"][0] == "smithjohn"
    assert [float(x) for x in body["101"][5:]] == [MAX[EX1], MAX[EX2], MAX[EX1] + MAX[EX2]]
    assert [float(x) for x in body["102"][5:]] == [MAX[EX1], 0, MAX[EX1]]
    assert all(len(r) == len(rows[0]) for r in rows)

    wide = {r["student"]: r for r in _dicts(out.parent / "grades-wide.csv")}
    assert wide["doejane_102"]["late"] == EX1 and wide["doejane_102"]["user id"] == "102"
    assert float(wide["smithjohn_101"]["total"]) == MAX[EX1] + MAX[EX2]


def test_grade_moodle_download_and_its_gradebook_with_a_roster(moodle_download, tmp_path, capsys):
    roster = tmp_path / "export.csv"
    with open(roster, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["First name", "Last name", "ID number", "Institution", "Department", "Email address"])
        w.writerow(["Ann", "O'Neil, Jr", "S-1", "", "", "ann@example.org"])
        w.writerow(['Bob "Bobby"', "Li", "S-2", "", "", "bob@example.org"])
    out = tmp_path / "m" / "grades.csv"
    args = ["grade", str(moodle_download), "-o", str(out), "--course", str(ROOT), "--layout", "moodle"]
    args += ["--exercise", EX1, "--exercise", EX2, "--gradebook", "moodle", "--roster", str(roster), "--quiet"]
    assert main(args) == 0
    assert "assignsubmission_onlinetext" in capsys.readouterr().err
    rows = _rows(out.parent / "grades-moodle.csv")
    assert rows[0] == ["Full name", "ID number", "Email address", EX1, EX2, "Total"]
    body = {r[0]: r for r in rows[1:]}
    assert body["Ann O'Neil, Jr"][1:3] == ["S-1", "ann@example.org"]
    assert [float(x) for x in body["Ann O'Neil, Jr"][3:]] == [MAX[EX1], MAX[EX2], MAX[EX1] + MAX[EX2]]
    assert body['Bob "Bobby" Li'][1:3] == ["S-2", "bob@example.org"]
    assert [float(x) for x in body['Bob "Bobby" Li'][3:]] == [0, 0, 0]
    # the names with a comma and quotes went through the csv module's quoting, and back
    raw = (out.parent / "grades-moodle.csv").read_text(encoding="utf-8")
    assert '"Ann O\'Neil, Jr"' in raw and '"Bob ""Bobby"" Li"' in raw


def test_moodle_flat_download_is_read_too(tmp_path):
    d = tmp_path / "flat"
    d.mkdir()
    shutil.copy(HONEST[EX1], d / f"Dee Q_45_assignsubmission_file_{EX1}.ipynb")
    c = collect(d, "moodle", [EX1])
    assert [(s.name, s.user_id, sorted(s.files)) for s in c.students] == [("Dee Q", "45", [EX1])]


def test_empty_or_unrecognised_download_exits_2_saying_what_it_looked_for(moodle_download, tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    out = str(tmp_path / "g.csv")
    assert main(["grade", str(empty), "-o", out, "--course", str(ROOT), "--layout", "canvas"]) == 2
    err = capsys.readouterr().err
    assert "--layout canvas" in err and "holds: nothing" in err
    assert main(["grade", str(moodle_download), "-o", out, "--course", str(ROOT), "--layout", "canvas"]) == 2
    err = capsys.readouterr().err
    assert "--layout canvas" in err and "assignsubmission_file_" in err and "download is flat" in err
    assert not Path(out).exists()
    assert main(["grade", str(empty), "-o", out, "--course", str(ROOT)]) == 2
    assert "--layout folders" in capsys.readouterr().err


def test_canvas_download_graded_as_folders_exits_2_and_names_the_layout(canvas_download, tmp_path, capsys):
    # what the issue saw: "graded 0 notebook(s) of 0 student(s)" and exit code 0
    assert main(["grade", str(canvas_download), "-o", str(tmp_path / "g.csv"), "--course", str(ROOT)]) == 2
    err = capsys.readouterr().err
    assert "no student folder" in err and "--layout canvas" in err and "smithjohn_101_1001" in err


def test_numbers_are_plain_decimals():
    assert [number(x) for x in (0, 13, 2.5, 1 / 3, 2 / 3, 1e-9, 1e6)] == [
        "0",
        "13",
        "2.5",
        "0.33",
        "0.67",
        "0",
        "1000000",
    ]


def test_a_roster_without_moodle_columns_is_refused(tmp_path):
    from puma_course.grading.output.gradebook import read_roster

    bad = tmp_path / "r.csv"
    bad.write_text("name,mail\nAnn,a@x\n", encoding="utf-8")
    with pytest.raises(ValueError, match="roster: expected Moodle's grade export"):
        read_roster(bad)
    with pytest.raises(ValueError, match="roster: expected a readable"):
        read_roster(tmp_path / "nope.csv")


def test_a_roster_row_with_one_name_matches_its_student(tmp_path):
    """A student with no last name in Moodle ("bob", "") is the hand-in folder "bob", not "bob " (found by a
    review run as a new instructor: the gradebook left bob's identifiers empty)."""
    from puma_course.grading.output.gradebook import read_roster

    roster = tmp_path / "r.csv"
    roster.write_text(
        "First name,Last name,ID number,Email address\nbob,,7,bob@x\nAnn,Lee,8,ann@x\n,Solo,9,solo@x\n",
        encoding="utf-8",
    )
    people = read_roster(roster)
    assert set(people) == {"bob", "Ann Lee", "Solo"}
    assert (people["bob"].id_number, people["bob"].email) == ("7", "bob@x")
