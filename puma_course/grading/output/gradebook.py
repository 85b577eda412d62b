"""A gradebook a learning platform imports: one row per student, one column per exercise, a total.

``puma-course grade ... --gradebook canvas|moodle|wide`` writes, next to the grades CSV
(``grades.csv`` -> ``grades-canvas.csv``, ``grades-moodle.csv``, ``grades-wide.csv``):

* ``canvas``: Canvas's gradebook import (Canvas Instructor Guide, "How do I import grades in the
  Gradebook?"; canvas-lms ``app/models/gradebook_importer.rb``, which reads the file): the identifier
  columns ``Student``, ``ID``, ``SIS User ID``, ``SIS Login ID``, ``Section`` first (the importer
  requires ``Student`` and ``ID`` first and ``Section`` last of them), one column per assignment (a
  header equal to an assignment's title, or ``Title (1234)``, fills that assignment; any other becomes
  a new assignment), a second row whose first cell holds ``Points Possible`` (the new assignments'
  points), and the total as ``Final Points``, a trailing column the importer drops as read-only. ``ID``
  is the Canvas user id read from the download's file names; the importer matches students by it.
* ``moodle``: Moodle's CSV grade import (MoodleDocs, "Grade import", Moodle 3.11 to 4.5): any column
  can be mapped to a grade item, and one column identifies the user, mapped to its ID number,
  email address, username or user id. The download names students by full name and a per-assignment
  participant number, neither of which the import maps, so ``--roster`` takes Moodle's own grade
  export (``First name``, ``Last name``, ``ID number``, ``Email address``) and fills ``ID number`` and
  ``Email address`` for each student by full name; without a roster those columns stay empty and the
  command says so.
* ``wide``: the same numbers for a spreadsheet: ``student``, ``name``, ``user id``, one column per
  exercise, ``total``, ``late``.

Scores are plain decimal numbers (``12.5``, never ``1.25e+01``, at most two decimals); a missing or
ungraded notebook scores 0. A written column (``grade --marks``) of an exercise none of whose written answers
is marked yet is an empty cell, never 0: both importers read an empty cell as "no grade" (canvas-lms's
``GradebookImporter`` treats a blank score as no score, so an ungraded submission stays ungraded; Moodle's
``gradeimport_csv_load_data::update_grade_item`` maps ``''`` and ``-`` to no grade), and the total, which counts
only the marks given, is then provisional; the wide gradebook counts the answers not marked yet per student
(``written not marked``). Text cells are written by the csv module (quoted when they hold a
comma, quote or line break) and a cell a spreadsheet would read as a formula starts with ``'``.
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from ..bank_loader import EXERCISES
from ..intake.collect import Submitter
from ..results import NotebookResult
from ..written import written_questions
from .report import replace_atomically
from .text import csv_safe, plural
from .totals import WrittenScore

__all__ = ["FORMATS", "gradebook_path", "gradebook_rows", "write_gradebook", "read_roster", "number"]

FORMATS = ("canvas", "moodle", "wide")
CANVAS_IDS = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]


@dataclass(frozen=True)
class RosterEntry:
    """A student of a Moodle grade export: the identifiers its import can map."""

    id_number: str
    email: str


def number(value: float) -> str:
    """A score as a plain decimal number, at most two decimals.

    >>> number(12.0), number(12.5), number(1 / 3), number(1e-7), number(123456789.0)
    ('12', '12.5', '0.33', '0', '123456789')
    """
    text = f"{round(float(value), 2):.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def gradebook_path(output: str | os.PathLike[str], fmt: str) -> Path:
    """Where the gradebook of the grades file ``output`` goes.

    >>> gradebook_path("out/grades.csv", "canvas").as_posix()
    'out/grades-canvas.csv'
    """
    out = Path(output)
    return out.with_name(f"{out.stem}-{fmt}.csv")


def read_roster(path: str | os.PathLike[str]) -> dict[str, RosterEntry]:
    """Moodle's grade export (CSV) as full name -> identifiers (ValueError when its columns are missing)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            rows = list(csv.DictReader(fh))
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise ValueError(f"roster: expected a readable UTF-8 CSV file, got {str(path)!r} ({exc})") from None
    need = {"First name", "Last name"}
    if not rows or not need <= set(rows[0]) or not ({"ID number", "Email address"} & set(rows[0])):
        have = sorted(rows[0]) if rows else []
        raise ValueError(
            f"roster: expected Moodle's grade export with columns First name, Last name and ID number or Email "
            f"address, got {have} in {str(path)!r}"
        )
    return {
        f"{r['First name'].strip()} {r['Last name'].strip()}".strip(): RosterEntry(
            (r.get("ID number") or "").strip(), (r.get("Email address") or "").strip()
        )
        for r in rows
    }


def _totals(results: Sequence[NotebookResult], names: Sequence[str]) -> dict[str, dict[str, float | None]]:
    scores: dict[str, dict[str, float | None]] = {}
    for r in results:
        scores.setdefault(r.student, {n: 0.0 for n in names})[r.exercise] = r.score
    return scores


def _students(names: Sequence[str], shown: int = 5) -> str:
    """``3 students: ann, bob, cy`` (the first ``shown`` names, then ``…``).

    >>> _students(["ann"]), _students(list("abcdefg"))
    ('1 student: ann', '7 students: a, b, c, d, e …')
    """
    return f"{plural(len(names), 'student')}: " + ", ".join(names[:shown]) + (" …" if len(names) > shown else "")


def _cell(value: float | None) -> str:
    return "" if value is None else number(value)


def _sum(scores: Mapping[str, float | None]) -> str:
    return number(sum(v for v in scores.values() if v is not None))


def gradebook_rows(
    fmt: str,
    results: Sequence[NotebookResult],
    names: Sequence[str],
    people: Mapping[str, Submitter] | None = None,
    roster: Mapping[str, RosterEntry] | None = None,
    written: Mapping[str, Mapping[str, WrittenScore]] | None = None,
) -> tuple[list[list[str]], list[str]]:
    """The gradebook's rows (header first) and what the instructor must know about them.

    ``people`` maps a graded student (the ``student`` of the results) to the identifiers collected
    from the download; ``roster`` (Moodle) maps a full name to the identifiers Moodle's import maps.
    ``written`` (``grade --marks``, :func:`.marks.written_by_student`) maps a student to the written points per
    exercise: each exercise with written questions then has a column ``<exercise> written`` after the exercises
    (with its points possible; empty while none of its answers is marked), counted in the total.
    """
    if fmt not in FORMATS:
        raise ValueError(f"gradebook: expected one of {', '.join(FORMATS)}, got {fmt!r}")
    people = people or {}
    scores = _totals(results, names)
    points = [number(EXERCISES[n].max_score) for n in names]
    unmarked: dict[str, int] = {}
    if written is not None:
        marked = [n for n in names if written_questions(n)]
        for student, mine in scores.items():
            got = written.get(student) or {}
            unmarked[student] = sum(w.unmarked for w in got.values())
            mine.update({f"{n} written": got[n].points if n in got else 0.0 for n in marked})
        points += [number(sum(w.points for w in written_questions(n))) for n in marked]
        names = [*names, *(f"{n} written" for n in marked)]
    notes: list[str] = []
    rows: list[list[str]]
    if fmt == "canvas":
        rows = [[*CANVAS_IDS, *names, "Final Points"], ["    Points Possible", "", "", "", "", *points, ""]]
        no_id = []
        for student, mine in scores.items():
            who = people.get(student)
            uid = who.user_id if who is not None else ""
            if not uid:
                no_id.append(student)
            shown = who.name if who is not None else student
            rows.append([csv_safe(shown), uid, "", "", "", *(_cell(mine[n]) for n in names), _sum(mine)])
        if no_id:
            why = "not from a Canvas download" if not people else "graded anonymously, or not in the download"
            notes.append(f"no Canvas user id (the ID Canvas's import matches a row by) for {_students(no_id)} ({why})")
    elif fmt == "moodle":
        rows = [["Full name", "ID number", "Email address", *names, "Total"]]
        missing = []
        for student, mine in scores.items():
            who = people.get(student)
            full = who.name if who is not None else student
            entry = (roster or {}).get(full)
            if entry is None:
                missing.append(full)
            rows.append(
                [
                    csv_safe(full),
                    csv_safe(entry.id_number) if entry else "",
                    csv_safe(entry.email) if entry else "",
                    *(_cell(mine[n]) for n in names),
                    _sum(mine),
                ]
            )
        if missing:
            why = "no --roster given" if roster is None else "not in the roster"
            by = "what Moodle's import matches a row by"
            notes.append(f"no ID number or email ({by}) for {_students(missing)} ({why})")
    else:
        late = {(s, ex) for s, p in people.items() for ex in p.late}
        rows = [
            ["student", "name", "user id", *names, "total", "late", *(["written not marked"] * (written is not None))]
        ]
        for student, mine in scores.items():
            who = people.get(student)
            lates = " ".join(n for n in names if (student, n) in late)
            rows.append(
                [
                    csv_safe(student),
                    csv_safe(who.name) if who else "",
                    who.user_id if who else "",
                    *(_cell(mine[n]) for n in names),
                    _sum(mine),
                    lates,
                    *([str(unmarked.get(student, 0))] * (written is not None)),
                ]
            )
    return rows, notes


def write_gradebook(
    fmt: str,
    output: str | os.PathLike[str],
    results: Sequence[NotebookResult],
    names: Sequence[str],
    people: Mapping[str, Submitter] | None = None,
    roster: Mapping[str, RosterEntry] | None = None,
    written: Mapping[str, Mapping[str, WrittenScore]] | None = None,
) -> tuple[Path, list[str]]:
    """Write the gradebook next to the grades file ``output`` (UTF-8, CRLF rows as the csv module writes them)."""
    rows, notes = gradebook_rows(fmt, results, names, people, roster, written)
    path = gradebook_path(output, fmt)
    buffer = io.StringIO()
    csv.writer(buffer).writerows(rows)
    replace_atomically(path, buffer.getvalue())
    return path, notes
