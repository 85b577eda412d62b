"""The marker's marks merged into the grades: ``puma-course grade SUBMISSIONS -o grades.csv --marks FILE``.

:func:`read_marks` reads one or more filled-in marks files (the templates of :mod:`.marking`, or any CSV
with the columns ``student, exercise, question`` and ``points`` and/or rubric columns, ``comment``
optional) and checks every row before anything is graded: an unknown student (a name or an anonymous
code of a student in SUBMISSIONS), an exercise not graded in this run, a question that is not one of its
written questions, a rubric column the question does not have, a number that is not one, negative, or
above the points of its criterion or question, ``points`` that differ from the sum of the filled rubric
columns, or the same (student, question) marked twice: each is a ``ValueError`` naming the file, the row
(as a spreadsheet numbers it, the header being row 1) and the column. A row with neither points nor rubric
columns is "not marked yet": it counts nothing, its cells stay empty and its student's total is provisional
(:mod:`.totals`); an answer of a notebook not handed in scores 0 (:func:`answer_points`). A file saved by a
spreadsheet set to a decimal comma reads the same: the separator (comma, semicolon or tab) is read off the
header row (:func:`separator`), and a number may have a decimal comma (``1,5``).

Once grading is done the marks go into

* the grades CSV: one column ``written:<qid>`` per written question id, then ``written`` (the row's written
  points) and ``written_max``; ``score`` and ``max_score`` stay the auto-graded ones;
* each gradebook (``--gradebook``): one column ``<exercise> written`` per exercise with written questions,
  with its points possible, counted in the total (:func:`puma_course.grading.output.gradebook.gradebook_rows`);
* each student's feedback file: the total counts the written points (as the gradebooks do), and a section
  "Written questions" with, per question, the points, the rubric
  criteria by name with the points awarded on each (never their texts, which are the marker's key), and the
  marker's comment.
"""

from __future__ import annotations

import csv
import io
import math
import os
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..results import NotebookResult
from ..written import WrittenQuestion, written_questions
from .marking import student_code
from .text import csv_safe, one_line, plural
from .totals import WrittenScore

__all__ = [
    "Mark",
    "Marks",
    "read_marks",
    "separator",
    "answer_points",
    "exercise_written",
    "written_by_student",
    "written_totals",
    "written_columns",
    "feedback_section",
]


@dataclass(frozen=True)
class Mark:
    """One marked answer: the points (None: not marked yet), the comment, the points per rubric line."""

    points: float | None
    comment: str = ""
    criteria: tuple[tuple[str, float], ...] = ()


@dataclass
class Marks:
    """Every mark read, by (student as graded, exercise, question id)."""

    marks: dict[tuple[str, str, str], Mark] = field(default_factory=dict)

    def get(self, student: str, exercise: str, qid: str) -> Mark | None:
        """The mark of the student's answer, or None when no file has a row for it."""
        return self.marks.get((student, exercise, qid))


def _number(text: str, where: str, most: float) -> float:
    try:
        value = float(text.strip().replace(",", "."))
    except ValueError:
        raise ValueError(f"{where}: expected a number of points, got {text!r}") from None
    if not math.isfinite(value) or value < 0:
        raise ValueError(f"{where}: expected a number of points from 0 to {most:g}, got {text!r}")
    if value > most + 1e-9:
        raise ValueError(f"{where}: expected at most {plural(most, 'point')}, got {text!r}")
    return value


def _student(raw: str, known: Mapping[str, str], where: str) -> str:
    name = raw.strip()
    for candidate in (name, name[1:] if name.startswith("'") else None):
        if candidate is not None and candidate in known:
            return known[candidate]
    shown = ", ".join(sorted(set(known.values()))[:6])
    raise ValueError(f"{where}: expected a student of this run (or their code), got {raw!r}; students: {shown}")


def _text(data: bytes) -> str:
    """A marks file's text: UTF-8 (a byte-order mark dropped), or UTF-16 with its mark (Excel's "Unicode text")."""
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return data.decode("utf-16")
    return data.decode("utf-8-sig")


def separator(text: str) -> str:
    r"""The separator of a marks file, read off its header row: ``,``, ``;`` or a tab.

    A spreadsheet set to a decimal comma (Excel or LibreOffice in much of Europe) saves CSV with semicolons,
    and "text" exports use tabs. The header's own separator is the one that splits it into the columns
    ``student``, ``exercise`` and ``question`` (no column name holds any of the three); a header split by none
    of them is read with commas, so the column check names what it found.

    >>> separator("student;exercise;question;points\nann;ex02_dh_frames;q4;1,5\n")
    ';'
    >>> separator("student\texercise\tquestion\tpoints\n"), separator("student,exercise,question,points\n")
    ('\t', ',')
    """
    first = text.split("\n", 1)[0]
    for sep in (",", ";", "\t"):
        try:
            head = {h.strip() for h in next(csv.reader([first], delimiter=sep), [])}
        except csv.Error:
            continue
        if {"student", "exercise", "question"} <= head:
            return sep
    return ","


def read_marks(paths: Sequence[str | os.PathLike[str]], students: Collection[str], exercises: Collection[str]) -> Marks:
    """Read and check the marks files ``paths`` against the run's ``students`` and graded ``exercises``."""
    known = {s: s for s in students} | {student_code(s): s for s in students}
    questions = {(w.exercise, w.qid): w for name in exercises for w in written_questions(name)}
    out = Marks()
    for path in paths:
        try:
            text = _text(Path(path).read_bytes())
            rows = list(csv.reader(io.StringIO(text, newline=""), delimiter=separator(text)))
        except (OSError, UnicodeDecodeError, csv.Error) as exc:
            raise ValueError(f"marks: expected a readable UTF-8 CSV file, got {str(path)!r} ({exc})") from None
        head = [h.strip() for h in rows[0]] if rows else []
        missing = [c for c in ("student", "exercise", "question") if c not in head]
        if missing or not ({"points"} & set(head) or len(head) > 3):
            raise ValueError(f"marks: expected the columns student, exercise, question, points in {str(path)!r}, "
                             f"got {head}")  # fmt: skip
        for number, row in enumerate(rows[1:], start=2):
            if not any(cell.strip() for cell in row):
                continue
            cells = dict(zip(head, row + [""] * (len(head) - len(row)), strict=False))
            where = f"marks {str(path)!r} row {number}"
            student = _student(cells["student"], known, f"{where}, column 'student'")
            exercise, qid = cells["exercise"].strip(), cells["question"].strip()
            if exercise not in exercises:
                raise ValueError(f"{where}, column 'exercise': expected an exercise graded in this run "
                                 f"({', '.join(sorted(exercises))}), got {exercise!r}")  # fmt: skip
            w = questions.get((exercise, qid))
            if w is None:
                ids = [k[1] for k in questions if k[0] == exercise]
                raise ValueError(f"{where}, column 'question': expected a written question of {exercise} {ids}, "
                                 f"got {qid!r}")  # fmt: skip
            out.marks[student, exercise, qid] = _row(w, cells, where, out.get(student, exercise, qid))
    return out


def _row(w: WrittenQuestion, cells: dict[str, str], where: str, before: Mark | None) -> Mark:
    if before is not None:
        raise ValueError(f"{where}: expected one row per student and question, got a second one for {w.qid}")
    criteria = []
    for column, text in cells.items():
        if column in ("student", "exercise", "question", "points", "comment") or not text.strip():
            continue
        names = [c.name for c in w.spec.criteria]
        if column not in names:
            raise ValueError(f"{where}, column {column!r}: expected a rubric line of {w.exercise} {w.qid} "
                             f"({', '.join(names)}), got a value {text!r}")  # fmt: skip
        criteria.append((column, _number(text, f"{where}, column {column!r}", w.criterion(column).points)))
    points_text = cells.get("points", "").strip()
    points = _number(points_text, f"{where}, column 'points'", w.points) if points_text else None
    if criteria:
        total = round(sum(v for _, v in criteria), 6)
        if points is not None and abs(points - total) > 1e-6:
            raise ValueError(f"{where}, column 'points': expected the sum of the rubric columns ({total:g}) or "
                             f"nothing, got {points_text!r}")  # fmt: skip
        points = total
    return Mark(points, cells.get("comment", "").strip(), tuple(criteria))


def answer_points(marks: Marks, result: NotebookResult, w: WrittenQuestion) -> float | None:
    """The points of the answer to ``w`` in ``result``'s notebook: its mark; 0 when no mark is given and the
    notebook was not handed in (there is nothing to mark); None when it is not marked yet."""
    m = marks.get(result.student, result.exercise, w.qid)
    if m is not None and m.points is not None:
        return m.points
    return 0.0 if result.status == "missing" else None


def exercise_written(marks: Marks, result: NotebookResult) -> WrittenScore:
    """The written points of ``result``'s exercise (:func:`answer_points` of each of its written questions)."""
    questions = written_questions(result.exercise)
    got = [answer_points(marks, result, w) for w in questions]
    known = [p for p in got if p is not None]
    possible = float(sum(w.points for w in questions))
    return WrittenScore(round(sum(known), 2) if known else None, possible, got.count(None))


def written_by_student(marks: Marks, results: Sequence[NotebookResult]) -> dict[str, dict[str, WrittenScore]]:
    """student -> exercise -> written points, for the gradebooks (the exercises with written questions)."""
    out: dict[str, dict[str, WrittenScore]] = {}
    for r in results:
        if written_questions(r.exercise):
            out.setdefault(r.student, {})[r.exercise] = exercise_written(marks, r)
    return out


def written_totals(
    written: Mapping[str, Mapping[str, WrittenScore]], results: Sequence[NotebookResult]
) -> dict[str, WrittenScore]:
    """student -> written points over the exercises graded for them (every student of ``results``).

    ``written`` is :func:`written_by_student`'s: the same numbers the gradebooks add to the total.
    """
    students = dict.fromkeys(r.student for r in results)
    return {s: WrittenScore.add((written.get(s) or {}).values()) for s in students}


def written_columns(rows: list[list[str]], marks: Marks, results: Sequence[NotebookResult]) -> list[list[str]]:
    """The grades CSV's ``rows`` (header first, as :func:`.report.csv_rows` makes them) with the written columns
    added (see the module docstring; an answer not marked yet is an empty cell); the rows are extended in place and
    returned."""
    head, body = rows[0], rows[1:]
    col = {name: i for i, name in enumerate(head)}
    graded = {(csv_safe(r.student), r.exercise): r for r in results}
    qids: list[str] = []
    for row in body:
        qids += [w.qid for w in written_questions(row[col["exercise"]]) if w.qid not in qids]
    qids.sort(key=lambda q: int(q[1:]) if q[1:].isdigit() else 0)
    head += [f"written:{q}" for q in qids] + ["written", "written_max"]
    for row in body:
        r = graded[row[col["student"]], row[col["exercise"]]]
        mine = {w.qid: w for w in written_questions(r.exercise)}
        cells = [_cell(answer_points(marks, r, mine[q])) if q in mine else "" for q in qids]
        score = exercise_written(marks, r) if mine else None
        row += cells + [_cell(score.points if score else None), f"{score.possible:g}" if score else ""]
    return [head, *body]


def _cell(points: float | None) -> str:
    return "" if points is None else f"{points:g}"


def feedback_section(marks: Marks, results: Sequence[NotebookResult]) -> str:
    """The "Written questions" section of a student's feedback (``results``: the student's notebooks; "" when no
    exercise of them has written questions)."""
    lines: list[str] = []
    for r in results:
        for w in written_questions(r.exercise):
            m = marks.get(r.student, r.exercise, w.qid)
            head = f"### {r.exercise} {w.qid}: {w.spec.title}"
            if m is None or m.points is None:
                if answer_points(marks, r, w) is None:
                    lines += [head, "", f"Not marked yet ({plural(w.points, 'point')}).", ""]
                else:
                    lines += [head, "", f"Not handed in: **0 / {w.points:g}** points.", ""]
                continue
            lines += [head, "", f"**{m.points:g} / {w.points:g}** points.", ""]
            given = dict(m.criteria)
            # the criterion's name and points only: its text is the marker's key and may hold the answer of an
            # auto-graded question (ex02's frames give away q3's table), read by a classmate who hands in late
            for c in w.spec.criteria:
                if given:
                    lines.append(f"- {given.get(c.name, 0):g} / {c.points:g} · {c.name}")
                else:
                    lines.append(f"- ({c.points:g}) {c.name}")
            if m.comment:
                lines += ["", "Comment:", ""] + [f"> {one_line(line, 2000)}" for line in m.comment.splitlines()]
            lines.append("")
    if not lines:
        return ""
    score = WrittenScore.add(exercise_written(marks, r) for r in results if written_questions(r.exercise))
    if score.provisional:
        said = f"Written: {score.text()}; the total above counts only what is marked, until the rest is."
    else:
        said = f"Written: **{score.points:g} / {score.possible:g}** points, counted in the total above."
    return "\n".join(["## Written questions (marked by your instructor)", "", said, "", *lines])
