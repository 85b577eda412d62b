"""The one writer of a grading run: every file from the same merged results, so every total agrees.

:func:`write_run` is called once per run, by :func:`~puma_course.grading.grade` (from the command line or from
Python alike), after the notebooks are graded. It merges the written marks (``grade --marks``, read and checked
before grading: :func:`.marks.read_marks`) into the results first, works out each student's total once
(:func:`.totals.student_totals`), and only then writes

* the grades CSV (:func:`.report.csv_rows`, with the written columns: :func:`.marks.written_columns`);
* each student's feedback file (:func:`.report.write_feedback`: the total counts the written points, and the
  written questions' section follows the exercises);
* the class summary (:func:`.summary.write_summary`, with each student's total);
* each gradebook asked for (canvas, moodle, wide: :func:`.gradebook.write_gradebook`, the written points in
  columns of their own, counted in the total).

Nothing is read back and rewritten afterwards: each file is written once, whole (a fresh temporary file moved
into place).
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..intake.collect import Collected
from ..results import NotebookResult
from ..run.sandbox import Sandbox
from ..secret import Secret
from .copies import CopyReport
from .gradebook import RosterEntry, write_gradebook
from .marks import Marks, feedback_section, written_by_student, written_columns, written_totals
from .report import csv_rows, replace_atomically, write_feedback
from .summary import summary_path, write_summary
from .totals import StudentTotal, WrittenScore, student_totals

__all__ = ["RunFacts", "Written", "write_run", "reserved_stems"]


@dataclass(frozen=True)
class RunFacts:
    """What the run found out that its files report: the exercises graded, the key, the sandbox, the limits, the
    platform download (its people, late hand-ins and files not graded) and the copy report."""

    names: tuple[str, ...]
    key: Secret
    box: Sandbox
    limits: str = ""
    collected: Collected | None = None
    copies: CopyReport | None = None


@dataclass
class Written:
    """What :func:`write_run` wrote: each student's total, the files, and what an import of a gradebook lacks."""

    totals: dict[str, StudentTotal]
    csv: Path
    summary: Path
    summary_note: str
    feedback: dict[str, Path] = field(default_factory=dict)
    gradebooks: list[tuple[str, Path, list[str]]] = field(default_factory=list)
    marked: int | None = None  # answers with marks (None: no marks given)
    unmarked: int = 0  # answers handed in and not marked yet: their students' totals are provisional
    shard: Path | None = None  # the shard file written (``grade --shard K/N``), for ``puma-course merge``


def reserved_stems(output: str | os.PathLike[str], feedback: str | os.PathLike[str]) -> list[str]:
    """The file stems in the feedback folder that belong to the grader's own files (the CSV, the class summary).

    >>> reserved_stems("fb/grades.md", "fb"), reserved_stems("grades.csv", "fb")
    (['grades', 'grades-summary'], [])
    """
    folder = os.path.realpath(feedback)
    own = [Path(output), summary_path(output)]
    return [p.stem for p in own if p.suffix.lower() == ".md" and os.path.realpath(p.parent) == folder]


def write_run(
    results: Sequence[NotebookResult],
    output: str | os.PathLike[str],
    facts: RunFacts,
    *,
    feedback: str | os.PathLike[str] | None = None,
    marks: Marks | None = None,
    gradebooks: Sequence[str] = (),
    roster: Mapping[str, RosterEntry] | None = None,
) -> Written:
    """Write the CSV, the feedback (when ``feedback`` names a folder), the summary and each of ``gradebooks``
    from ``results`` merged with ``marks``; see the module docstring. ``roster`` is Moodle's grade export, read
    (:func:`.gradebook.read_roster`) before grading."""
    names = list(facts.names)
    written = written_by_student(marks, results) if marks is not None else None
    per_student: Mapping[str, WrittenScore] | None = None
    if written is not None:
        per_student = written_totals(written, results)
    totals = student_totals(results, per_student)
    people_late = facts.collected.late() if facts.collected is not None else None
    box = facts.box

    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    rows = csv_rows(results, names, facts.key.seed, box.label, facts.key.fingerprint, people_late, limits=facts.limits)
    if marks is not None:
        rows = written_columns(rows, marks, results)
    buffer = io.StringIO()
    csv.writer(buffer).writerows(rows)
    replace_atomically(out, buffer.getvalue())

    done = Written(totals, out, summary_path(out), "")
    if feedback is not None:
        user = getattr(box, "user", None)  # AsUser (Gradescope): alone, as an unprivileged user
        sections = None
        if marks is not None:
            mine: dict[str, list[NotebookResult]] = {}
            for r in results:
                mine.setdefault(r.student, []).append(r)
            sections = {s: feedback_section(marks, own) for s, own in mine.items()}
        done.feedback = write_feedback(
            feedback,
            results,
            unsandboxed=box.reason if box.kind != "bwrap" else None,
            reserved=reserved_stems(out, feedback),
            key=facts.key,
            as_user=user.name if box.kind == "user" and user is not None else None,
            written=per_student,
            sections=sections,
        )
    unmatched = facts.collected.problems if facts.collected is not None else ()
    done.summary, done.summary_note = write_summary(
        results, out, unmatched=unmatched, copies=facts.copies, totals=totals
    )
    people = facts.collected.by_key() if facts.collected is not None else None
    for fmt in dict.fromkeys(gradebooks):
        path, notes = write_gradebook(fmt, out, results, names, people, roster, written)
        done.gradebooks.append((fmt, path, notes))
    if marks is not None:
        done.marked = sum(1 for m in marks.marks.values() if m.points is not None)
        done.unmarked = sum(t.written.unmarked for t in totals.values() if t.written is not None)
    return done
