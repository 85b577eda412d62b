"""Written questions: released as prompt and answer cells, collected for a marker, marks merged into the grades.

* ``puma-course release`` puts each written question's prompt (with its points) and a Markdown answer cell
  tagged ``written:qN`` into the exercise, before its closing cell; the rubric and the worked answer stay in
  the bank (no exercise holds them; the edition's leak search, in test_edition, looks for them too);
* the worked answers are right: the entry p_z of 0T6 worked out for the pedestal PUMA agrees with the
  robot's forward kinematics built from lecture 03's model, not from the formula;
* the round trip, as an instructor runs it: three students hand in (one with a sketch attached),
  ``collect-written`` writes a marking document and a marks template (anonymised), the marks are filled in
  as a marker would, ``grade --marks`` merges them; the grades CSV, the Canvas, Moodle and wide gradebooks
  and the feedback files are parsed back, totals and comments checked;
* a bad marks file (unknown student, question or rubric line, too many points, not a number, NaN, points
  that are not the rubric's sum, a row twice) stops ``grade`` with exit code 2 before anything is graded,
  naming the row and the column.
"""

from __future__ import annotations

import base64
import csv
import shutil
import warnings
from pathlib import Path

import nbformat
import numpy as np
import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES, release_notebook
from puma_course.grading.output.marking import student_code
from puma_course.grading.output.marks import read_marks
from puma_course.grading.written import (
    ANSWER_TAG,
    PLACEHOLDER,
    PROMPT_TAG,
    Criterion,
    Written,
    read_answers,
    written_exercises,
    written_questions,
)
from puma_course.kinematics.porter import Porter
from puma_course.kinematics.puma560 import Puma560
from puma_course_bank._reference.porter_chain import porter_rod_fk
from tests.support import ROOT

EX = "ex02_dh_frames"
AUTO = int(EXERCISES[EX].max_score)  # the auto-graded points of EX (12 since ex02 q4 was added)
QID = written_questions(EX)[0].qid  # q4 while the exercise has three auto-graded questions
PNG = b"\x89PNG\r\n\x1a\n" + bytes(range(40))


def _tags(cell) -> list[str]:
    return list(cell.get("metadata", {}).get("tags", []))


def _secrets() -> list[str]:
    """The marker's texts of every written question: rubric lines, what a full answer holds, the worked answer."""
    out = []
    for name in written_exercises():
        for w in written_questions(name):
            out += [c.text for c in w.spec.criteria]
            out += [line.strip() for line in (w.spec.full_answer + "\n" + w.spec.worked).splitlines()]
    return [s for s in out if len(s) > 25]


def test_the_course_has_the_three_written_questions_and_their_rubrics_add_up():
    assert written_exercises() == ["ex02_dh_frames", "ex03_puma_fk", "ex06_porter_explicit"]
    for name in written_exercises():
        graded = [q.qid for q in EXERCISES[name].questions]
        for w in written_questions(name):
            assert w.qid not in graded and int(w.qid[1:]) == len(graded) + 1  # numbered after the graded ones
            assert sum(c.points for c in w.spec.criteria) == w.points
    with pytest.raises(ValueError, match="add up"):
        Written(3, "t", "p", (Criterion("a", 1, "x"),), "f", "w")
    with pytest.raises(ValueError, match="criterion name"):
        Criterion("Bad|Name", 1, "x")


@pytest.mark.parametrize("name", ["ex02_dh_frames", "ex03_puma_fk", "ex06_porter_explicit"])
def test_release_puts_the_prompt_and_answer_cell_before_the_closing_cell(name):
    nb = nbformat.read(ROOT / "exercises" / f"{name}.ipynb", as_version=4)
    (w,) = written_questions(name)
    tags = [_tags(c) for c in nb.cells]
    prompt, answer = tags.index([PROMPT_TAG + w.qid]), tags.index([ANSWER_TAG + w.qid])
    assert answer == prompt + 1 == len(nb.cells) - 2 and "hand it in" in nb.cells[-1].source
    assert nb.cells[answer].cell_type == "markdown" and nb.cells[answer].source == PLACEHOLDER
    assert f"{w.points:g} points" in nb.cells[prompt].source and w.spec.prompt.strip() in nb.cells[prompt].source
    summary = next(c.source for c in nb.cells if "points-summary" in _tags(c))
    assert f"Written, marked by your instructor: {w.qid} {w.points:g}." in summary
    # the auto-graded total is untouched
    assert f"{EXERCISES[name].max_score:g} in all" in summary


def test_no_rubric_or_worked_answer_reaches_an_exercise():
    secrets = _secrets()
    assert len(secrets) > 20
    text = "\n".join(p.read_text(encoding="utf-8") for p in (ROOT / "exercises").glob("*.ipynb"))
    text += "\n".join(line.strip() for line in text.splitlines())
    assert [s for s in secrets if s in text] == []


def test_a_solution_carrying_a_written_tag_is_refused():
    nb = nbformat.read(ROOT / "solutions" / f"{EX}.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_markdown_cell("mine", metadata={"tags": [ANSWER_TAG + QID]}))
    with pytest.raises(ValueError, match="generates"):
        release_notebook(nb, EXERCISES[EX])


def test_the_worked_entry_of_0t6_is_the_pedestal_robots():
    """p_z = h + a2 c2 + a3 s23 + d4 c23 + d6 (c23 c5 - s23 c4 s5), against lecture 03's robot lifted by h, counted
    from the controller's zero (theta2 = q2 - 90 deg, theta3 = q3 - 90 deg) and holding the tool d6 along z6."""
    (w,) = written_questions("ex03_puma_fk")
    assert r"p_z = h + a_2 c_2 + a_3 s_{23} + d_4 c_{23} + d_6\,(c_{23} c_5 - s_{23} c_4 s_5)" in w.spec.worked
    rng = np.random.default_rng(7)
    for _ in range(50):
        a2, a3, d3, d4, h, d6 = rng.uniform(0.05, 1.0, 6)
        q = rng.uniform(-np.pi, np.pi, 6)
        arm = Puma560(a2, a3, d3, d4)
        T = arm.fk(q + np.radians([0, -90, -90, 0, 0, 0]))
        tip = h + T[2, 3] + d6 * T[2, 2]
        c, s = np.cos, np.sin
        q23 = q[1] + q[2]
        formula = h + a2 * c(q[1]) + a3 * s(q23) + d4 * c(q23) + d6 * (c(q23) * c(q[4]) - s(q23) * c(q[3]) * s(q[4]))
        assert tip == pytest.approx(formula, abs=1e-12)
    # the check at q = 0 of the worked answer: arm and tool straight up
    T0 = Puma560(0.4, 0.02, 0.15, 0.43).fk(np.radians([0, -90, -90, 0, 0, 0]))
    assert 1.0 + T0[2, 3] + 0.05 * T0[2, 2] == pytest.approx(1.0 + 0.4 + 0.43 + 0.05)
    assert "h + a_2 + d_4 + d_6" in w.spec.worked


def test_the_worked_count_of_the_telescopic_rod_is_the_chains():
    """ex06's written question: the rod lengths, the pairs, the count for each l2 and the stroke's end, worked out
    from Porter's chain's configurations and frames (the points p2, p3), and the telescopic chain's own fk."""
    (w,) = written_questions("ex06_porter_explicit")
    text = " ".join((w.spec.prompt + w.spec.worked + w.spec.full_answer).split())
    q_pub, L = np.array([0.3, 0.7, 1.3, -0.4, 0.9, 0.6]), (1.0, 0.5, 0.3)
    arm = Porter(*L)
    T = arm.fk(q_pub)
    T_case, l1, l2, l3, l4 = EXERCISES["ex06_porter_explicit"].question("q2").public[0]  # the prompt's case
    assert np.allclose(T_case, T) and (l1, l3, l4) == L and l2 == 1.6 and "l_2 = 1.6" in text
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = arm.ik(T)
    frames = arm.frames(sol.q)
    rods = np.linalg.norm(frames[:, 3, :3, 3] - frames[:, 2, :3, 3], axis=1)  # |p3 - p2| from the points
    assert np.allclose(rods, sol.q[:, 2])
    short, long = np.sort(np.unique(np.round(rods, 9)))
    assert f"{short:.3f}" == "1.300" and f"{long:.3f}" == "1.924" and "1.924" in text and "1.300" in text
    assert f"{short - 1.6:.3f}" == "-0.300" and f"{long - 1.6:.3f}" == "0.324" and "0.324" in text
    # the pairs: the same points, one per side of the arm plane, opposite signs of c4
    by_label = dict(zip(sol.labels, range(len(sol.labels)), strict=True))
    for front, back, rod in (("front/c4+", "back/c4-", short), ("front/c4-", "back/c4+", long)):
        i, j = by_label[front], by_label[back]
        assert np.allclose(frames[i, :, :3, 3], frames[j, :, :3, 3]) and np.isclose(rods[i], rod)
    assert "(front, $c_4 > 0$) pairs with (back, $c_4 < 0$) at $1.300$" in text
    # the count for l2: the configurations whose stroke |p3 - p2| - l2 is >= 0, each reaching T on the rod chain
    for l2, count in ((1.0, 4), (short, 4), (1.6, 2), (long, 2), (2.0, 0)):
        keep = rods - l2 >= -1e-8
        assert int(np.sum(keep)) == count
        for q in sol.q[keep]:
            stroke = max(q[2] - l2, 0.0)
            rod_q = np.r_[q[:2], stroke, q[3:]]
            assert np.allclose(porter_rod_fk(rod_q, L[0], l2, L[1], L[2]), T, atol=1e-9)
            assert q[2] > 0.5  # never a zero-length rod: alpha2 fixed by the rod's direction
    assert "front/$c_4 < 0$ and back/$c_4 > 0$ remain" in text


def _hand_in(base: Path, answer: str | None, attach: bool = False, honest: bool = True) -> nbformat.NotebookNode:
    """A student's ex02: the solutions' code (or the blank exercise) with the released written cells, answered."""
    exercise = nbformat.read(ROOT / "exercises" / f"{EX}.ipynb", as_version=4)
    nb = nbformat.read(ROOT / "solutions" / f"{EX}.ipynb", as_version=4) if honest else exercise
    if honest:
        nb.cells[-1:-1] = [c for c in exercise.cells if any(t.startswith("written") for t in _tags(c))]
    cell = next(c for c in nb.cells if ANSWER_TAG + QID in _tags(c))
    if answer is not None:
        cell.source = answer
    if attach:
        cell["attachments"] = {"frames.png": {"image/png": base64.b64encode(PNG).decode()}}
    base.mkdir(parents=True)
    nbformat.write(nb, base / f"{EX}.ipynb")
    return nb


ANN = r"$z_1$ up the column, $z_2 = -y_0$ (raising the tip). ![my sketch](attachment:frames.png) <b>bold</b>"
BOB = "The origin of {1} is where the column and the shoulder axes cross, at height $h$."


@pytest.fixture
def handed_in(tmp_path: Path) -> Path:
    sub = tmp_path / "hand-in"
    _hand_in(sub / "ann", ANN, attach=True)
    _hand_in(sub / "bob", BOB, honest=False)
    _hand_in(sub / "cy", None)  # left the placeholder: no answer
    return sub


def _dicts(path: Path) -> list[dict[str, str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def _rows(path: Path) -> list[list[str]]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.reader(fh))


def test_answers_are_read_from_the_tagged_cell_with_their_attachments(handed_in):
    ann = read_answers((handed_in / "ann" / f"{EX}.ipynb").read_bytes(), EX)[QID]
    assert ann.text == ANN and ann.images == [("frames.png", "png", PNG)] and not ann.notes
    assert read_answers((handed_in / "cy" / f"{EX}.ipynb").read_bytes(), EX)[QID].empty
    assert "not valid JSON" in read_answers(b"{", EX)[QID].notes[0]


def test_the_round_trip_collect_mark_merge(handed_in, tmp_path, capsys):
    marking = tmp_path / "marking"
    args = ["collect-written", str(handed_in), "-o", str(marking), "--course", str(ROOT), "--anonymise"]
    assert main(args) == 0
    doc = (marking / f"{EX}-{QID}.md").read_text(encoding="utf-8")
    (w,) = written_questions(EX)
    assert all(c.text.replace("|", "/") in doc for c in w.spec.criteria) and w.spec.worked.strip() in doc
    codes = {who: student_code(who) for who in ("ann", "bob", "cy")}
    for who, code in codes.items():
        assert f"### `{code}`" in doc and f"`{who}`" not in doc  # anonymised
    assert "z_2 = -y_0" in doc and BOB in doc and "*(no answer written)*" in doc
    assert "&lt;b>bold&lt;/b>" in doc and "<b>" not in doc  # the student's HTML is shown, not rendered
    image = marking / "attachments" / f"{EX}-{QID}-{codes['ann']}-1.png"
    assert image.read_bytes() == PNG and f"](attachments/{image.name})" in doc

    sheet = marking / f"{EX}-{QID}-marks.csv"
    rows = _rows(sheet)
    assert rows[0] == ["student", "exercise", "question", "points", "comment", "z axes", "origin 1", "origin 2",
                       "x axes"]  # fmt: skip
    assert sorted(r[0] for r in rows[1:]) == sorted(codes.values())
    # the marker fills it in: ann by rubric line, bob by points only, cy left unmarked
    filled = [rows[0]]
    for row in rows[1:]:
        if row[0] == codes["ann"]:
            row[4], row[5:9] = "Good sketch; x2 is missing.", ["1", "1", "0.5", "0"]
        elif row[0] == codes["bob"]:
            row[3], row[4] = "1", "Only frame {1}, but right."
        filled.append(row)
    with open(sheet, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh).writerows(filled)

    out = tmp_path / "out" / "grades.csv"
    feedback = tmp_path / "feedback"
    args = ["grade", str(handed_in), "-o", str(out), "--course", str(ROOT), "--exercise", EX, "--seed", "3"]
    args += ["--feedback", str(feedback), "--marks", str(sheet), "--sandbox", "none"]
    args += ["--gradebook", "canvas", "--gradebook", "moodle", "--gradebook", "wide"]
    assert main(args) == 0
    assert "written marks: 2 answers marked" in capsys.readouterr().out

    grades = {r["student"]: r for r in _dicts(out)}
    assert [float(grades[s]["score"]) for s in ("ann", "bob", "cy")] == [AUTO, 0, AUTO]  # the auto-graded part as is
    assert {grades[s]["max_score"] for s in grades} == {str(AUTO)}
    assert [grades[s][f"written:{QID}"] for s in ("ann", "bob", "cy")] == ["2.5", "1", ""]
    assert [grades[s]["written"] for s in ("ann", "bob", "cy")] == ["2.5", "1", ""]
    assert {grades[s]["written_max"] for s in grades} == {"4"}

    canvas = _rows(out.parent / "grades-canvas.csv")
    assert canvas[0][5:] == [EX, f"{EX} written", "Final Points"]
    assert [float(x) for x in canvas[1][5:7]] == [AUTO, 4]
    body = {r[0]: [float(x) if x else None for x in r[5:]] for r in canvas[2:]}
    # cy's answer is not marked yet: an empty cell, which Canvas's import leaves ungraded (a 0 would grade it)
    assert body == {"ann": [AUTO, 2.5, AUTO + 2.5], "bob": [0, 1, 1], "cy": [AUTO, None, AUTO]}
    moodle = {r["Full name"]: r for r in _dicts(out.parent / "grades-moodle.csv")}
    assert [float(moodle["ann"][k]) for k in (EX, f"{EX} written", "Total")] == [AUTO, 2.5, AUTO + 2.5]
    wide = {r["student"]: r for r in _dicts(out.parent / "grades-wide.csv")}
    assert float(wide["bob"][f"{EX} written"]) == 1 and float(wide["bob"]["total"]) == 1

    ann = (feedback / "ann.md").read_text(encoding="utf-8")
    # the total counts the written points, as the gradebooks do (it said the auto-graded total alone: issue 32);
    # the auto-graded part is still said, as before
    assert (
        f"Total: **{AUTO + 2.5:g} / {AUTO + 4}** points (auto-graded {AUTO} / {AUTO}, written questions 2.5 / 4)."
        in ann
    )
    assert "## Written questions (marked by your instructor)" in ann and "Written: **2.5 / 4** points" in ann
    assert "**2.5 / 4** points." in ann and "> Good sketch; x2 is missing." in ann
    assert "- 0.5 / 1 · origin 2\n" in ann and "- 0 / 1 · x axes\n" in ann
    # the criteria's texts are the marker's key (ex02's give away q3's table): never in a student's feedback
    bob = (feedback / "bob.md").read_text(encoding="utf-8")
    everyone = [(feedback / f"{s}.md").read_text(encoding="utf-8") for s in ("ann", "bob", "cy")]
    assert not any(c.text in text for c in w.spec.criteria for text in everyone)
    assert "**1 / 4** points." in bob and "> Only frame {1}, but right." in bob
    assert "Not marked yet (4 points)." in (feedback / "cy.md").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("layout", "where", "key"),
    [
        ("canvas", f"smithjohn_101_1001_{EX}.ipynb", "smithjohn_101"),
        ("moodle", f"Ann O'Neil_42_assignsubmission_file_/{EX}.ipynb", "Ann O'Neil_42"),
    ],
)
def test_collect_written_reads_the_platforms_downloads_too(tmp_path, layout, where, key):
    download = tmp_path / layout
    _hand_in(tmp_path / "tmp", ANN, attach=True)
    (download / where).parent.mkdir(parents=True, exist_ok=True)
    shutil.copy(tmp_path / "tmp" / f"{EX}.ipynb", download / where)
    args = ["collect-written", str(download), "-o", str(tmp_path / "m"), "--course", str(ROOT), "--layout", layout]
    assert main(args) == 0
    assert _rows(tmp_path / "m" / f"{EX}-{QID}-marks.csv")[1][:3] == [key, EX, QID]
    doc = (tmp_path / "m" / f"{EX}-{QID}.md").read_text(encoding="utf-8")
    assert f"### `{key}`" in doc and "z_2 = -y_0" in doc
    assert len(list((tmp_path / "m" / "attachments").glob("*.png"))) == 1


def test_collect_written_says_an_exercise_has_no_written_question_not_that_it_matches_none(tmp_path, capsys):
    download = tmp_path / "canvas"
    _hand_in(tmp_path / "tmp", ANN, attach=True)
    download.mkdir()
    shutil.copy(tmp_path / "tmp" / f"{EX}.ipynb", download / f"smithjohn_101_1001_{EX}.ipynb")
    shutil.copy(ROOT / "exercises" / "ex01_rotations.ipynb", download / "smithjohn_101_1002_ex01_rotations.ipynb")
    (download / "smithjohn_101_1003_notes.ipynb").write_text("{}", encoding="utf-8")
    args = ["collect-written", str(download), "-o", str(tmp_path / "m"), "--course", str(ROOT), "--layout", "canvas"]
    assert main(args) == 0
    err = capsys.readouterr().err
    assert "ex01_rotations.ipynb" in err and "not collected: ex01_rotations has no written question" in err
    ex01 = next(line for line in err.splitlines() if "ex01_rotations" in line)
    assert "matches no exercise" not in ex01
    notes = next(line for line in err.splitlines() if "notes.ipynb" in line)
    assert "matches no exercise" in notes  # a file of no exercise at all is still said to be one


HEAD = ["student", "exercise", "question", "points", "comment", "z axes", "origin 1", "origin 2", "x axes"]


@pytest.mark.parametrize(
    ("row", "said"),
    [
        (["dora", EX, QID, "1", "", "", "", "", ""], "row 2, column 'student'"),
        (["ann", EX, "q9", "1", "", "", "", "", ""], "row 2, column 'question'"),
        (["ann", "ex01_rotations", "q1", "1", "", "", "", "", ""], "row 2, column 'exercise'"),
        (["ann", EX, QID, "5", "", "", "", "", ""], "row 2, column 'points': expected at most 4"),
        (["ann", EX, QID, "four", "", "", "", "", ""], "row 2, column 'points': expected a number"),
        (["ann", EX, QID, "nan", "", "", "", "", ""], "row 2, column 'points'"),
        (["ann", EX, QID, "-1", "", "", "", "", ""], "row 2, column 'points'"),
        (["ann", EX, QID, "", "", "2", "", "", ""], "row 2, column 'z axes': expected at most 1"),
        (["ann", EX, QID, "3", "", "1", "1", "", ""], "row 2, column 'points': expected the sum"),
    ],
)
def test_a_bad_marks_file_stops_grade_naming_row_and_column(handed_in, tmp_path, capsys, row, said):
    bad = tmp_path / "marks.csv"
    with open(bad, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh).writerows([HEAD, row])
    args = ["grade", str(handed_in), "-o", str(tmp_path / "g.csv"), "--course", str(ROOT), "--exercise", EX]
    assert main([*args, "--marks", str(bad), "--quiet", "--seed", "1"]) == 2
    err = capsys.readouterr().err
    assert said in err and str(bad) in err
    assert not (tmp_path / "g.csv").exists()  # nothing was graded


def test_more_bad_marks_files(tmp_path):
    students, exercises = ["ann", "bob"], [EX]

    def read(*rows: list[str], head: list[str] = HEAD):
        path = tmp_path / "m.csv"
        with open(path, "w", newline="", encoding="utf-8") as fh:
            csv.writer(fh).writerows([head, *rows])
        return read_marks([path], students, exercises)

    with pytest.raises(ValueError, match="row 3: expected one row per student and question"):
        read(["ann", EX, QID, "1"], ["ann", EX, QID, "2"])
    with pytest.raises(ValueError, match=r"row 2, column 'neatness': expected a rubric line"):
        read(["ann", EX, QID, "", "x"], head=["student", "exercise", "question", "points", "neatness"])
    with pytest.raises(ValueError, match="expected the columns student, exercise, question"):
        read(["ann", QID, "1"], head=["student", "question", "points"])
    # a code stands for its student, a formula-safe name for the name; an empty row is skipped
    marks = read([student_code("bob"), EX, QID, "2", "ok"], [], ["'ann", EX, QID, "", "", "1", "1", "1", "1"])
    assert marks.get("bob", EX, QID).points == 2 and marks.get("ann", EX, QID).points == 4
