"""The instructor's view of a graded class: per question, who passed and which mistakes were common.

:func:`class_summary` reads the graded results (:class:`~puma_course.grading.results.NotebookResult`,
one per student and exercise) and counts, for every question, how many students passed it, partly
passed it, failed it or did not attempt it, their mean points, and the mistakes the grader diagnosed
(:mod:`puma_course.grading.judge.diagnose`), each counted once per student who made it. :func:`write_summary`
writes it as Markdown next to the grades CSV (``grades.csv`` -> ``grades-summary.md``) and returns a few
lines for the terminal: the questions the class found hardest and their commonest mistake.
``puma-course grade`` calls it after grading.
"""

from __future__ import annotations

import os
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..bank_loader import EXERCISES
from ..judge.diagnose import TITLES
from ..results import NotebookResult
from ..spec import Question
from .copies import CopyReport, copies_section
from .report import replace_atomically, verdict
from .text import one_line, plural, quoted
from .totals import StudentTotal

__all__ = [
    "QuestionSummary",
    "question_summaries",
    "class_summary",
    "write_summary",
    "summary_note",
    "summary_path",
    "run_outcome",
    "totals_section",
]

#: Statuses of notebooks that were not graded at all (they count as "not submitted").
UNGRADED = ("missing", "malformed")


@dataclass
class QuestionSummary:
    """What the class did on one question."""

    exercise: str
    question: Question
    submitted: int = 0
    passed: int = 0
    partly: int = 0
    failed: int = 0
    not_attempted: int = 0
    points: float = 0.0
    mistakes: Counter[str] = field(default_factory=Counter)

    @property
    def mean(self) -> float:
        """Mean points over the students who submitted the exercise."""
        return self.points / self.submitted if self.submitted else 0.0

    def common(self, k: int = 3) -> list[tuple[str, int]]:
        """The ``k`` mistakes made by most students, as (key, students), most common first."""
        return sorted(self.mistakes.items(), key=lambda kv: (-kv[1], kv[0]))[:k]


def question_summaries(results: Sequence[NotebookResult]) -> list[QuestionSummary]:
    """One :class:`QuestionSummary` per question of every exercise that appears in ``results``.

    >>> from puma_course.grading import EXERCISES
    >>> ex = EXERCISES["ex01_rotations"]
    >>> r = NotebookResult.blank("ann", ex)
    >>> r.scores["q1"], r.question_notes["q1"] = 2.0, ["9/9 cases pass"]
    >>> r.mistakes["q2"] = ["transposed", "transposed"]
    >>> s = question_summaries([r])
    >>> s[0].passed, s[1].failed, s[1].mistakes["transposed"]
    (1, 1, 1)
    """
    order = [name for name in EXERCISES if any(r.exercise == name for r in results)]
    out: list[QuestionSummary] = []
    for name in order:
        mine = [r for r in results if r.exercise == name]
        for q in EXERCISES[name].questions:
            s = QuestionSummary(name, q)
            for r in mine:
                if r.status in UNGRADED:
                    continue
                s.submitted += 1
                earned = r.scores.get(q.qid, 0.0)
                s.points += earned
                word = verdict(q, earned, r.question_notes.get(q.qid, []))
                if word == "passed":
                    s.passed += 1
                elif word == "partly":
                    s.partly += 1
                elif word == "FAILED":
                    s.failed += 1
                else:
                    s.not_attempted += 1
                s.mistakes.update(set(r.mistakes.get(q.qid, [])))
            out.append(s)
    return out


def _mistakes_cell(s: QuestionSummary) -> str:
    return "; ".join(f"{TITLES.get(key, key)} (`{key}`): {n}" for key, n in s.common()) or "–"


def class_summary(
    results: Sequence[NotebookResult],
    unmatched: Sequence[str] = (),
    copies: CopyReport | None = None,
    totals: Mapping[str, StudentTotal] | None = None,
) -> str:
    """The class summary as Markdown: one table per exercise, one row per question; then each student's total
    (``totals``, :func:`~.totals.student_totals`: auto-graded, written, total, as the feedback and the gradebooks
    give it), when given; then the copy report (:func:`~.copies.copies_section`), when one was made.

    >>> from puma_course.grading import EXERCISES
    >>> r = NotebookResult.blank("ann", EXERCISES["ex01_rotations"])
    >>> print(class_summary([r]).splitlines()[0])
    # Class summary: 1 student, 1 exercise
    """
    students = sorted({r.student for r in results})
    summaries = question_summaries(results)
    names = list(dict.fromkeys(s.exercise for s in summaries))
    lines = [f"# Class summary: {plural(len(students), 'student')}, {plural(len(names), 'exercise')}", ""]
    lines += [
        "Per question: how many of the students who handed the exercise in passed it (full points), passed it "
        "partly, failed it or did not attempt it; their mean points; and the mistakes the grader recognised, each "
        "counted once per student who made it in at least one case.",
        "",
    ]
    for name in names:
        mine = [s for s in summaries if s.exercise == name]
        handed = mine[0].submitted
        lines += [
            f"## {name}: {EXERCISES[name].title}",
            "",
            f"Handed in by {handed} of {plural(len(students), 'student')}.",
            "",
        ]
        lines += [
            "| question | points | passed | partly | failed | not attempted | mean | most common mistakes (students) |",
            "| --- | --- | --- | --- | --- | --- | --- | --- |",
        ]
        for s in mine:
            bonus = " (bonus)" if s.question.bonus else ""
            lines.append(
                f"| {s.question.qid} `{s.question.function}`{bonus} | {s.question.points:g} | {s.passed} | {s.partly} "
                f"| {s.failed} | {s.not_attempted} | {s.mean:.2f} | {_mistakes_cell(s)} |"
            )
        lines.append("")
    if totals:
        lines += totals_section(totals)
    if unmatched:
        lines += [f"## Files not graded ({len(unmatched)})", ""]
        lines += [f"- {one_line(u, 400)}" for u in unmatched]
        lines.append("")
    lines += copies_section(copies)
    return "\n".join(lines) + "\n"


def totals_section(totals: Mapping[str, StudentTotal]) -> list[str]:
    """The summary's table of students: auto-graded points, written points (– without marks), total (called
    provisional while a written answer waits for a mark).

    >>> from puma_course.grading.output.totals import WrittenScore
    >>> print("\\n".join(totals_section({"ann": StudentTotal(27, 27, WrittenScore(2.5, 4))})[4:]))
    | `ann` | 27 / 27 | 2.5 / 4 | **29.5 / 31** |
    >>> print("\\n".join(totals_section({"cy": StudentTotal(12, 27, WrittenScore(None, 4, 1))})[4:]))
    | `cy` | 12 / 27 | not marked yet (4 points) | **12 / 31** provisional |
    """
    lines = [
        "## Totals per student",
        "",
        "| student | auto-graded | written | total |",
        "| --- | --- | --- | --- |",
    ]
    for student in sorted(totals):
        t = totals[student]
        written = "–" if t.written is None else t.written.text()
        total = f"**{t.total:g} / {t.top:g}**" + (" provisional" if t.provisional else "")
        lines.append(f"| {quoted(student, 120)} | {t.auto:g} / {t.auto_max:g} | {written} | {total} |")
    return [*lines, ""]


def summary_path(output: str | os.PathLike[str]) -> Path:
    """Where the summary of the grades file ``output`` goes: next to it, ``NAME-summary.md``.

    >>> summary_path("out/grades.csv").as_posix()
    'out/grades-summary.md'
    """
    out = Path(output)
    return out.with_name(f"{out.stem}-summary.md")


def write_summary(
    results: Sequence[NotebookResult],
    output: str | os.PathLike[str],
    lines: int = 8,
    unmatched: Sequence[str] = (),
    copies: CopyReport | None = None,
    totals: Mapping[str, StudentTotal] | None = None,
) -> tuple[Path, str]:
    """Write :func:`class_summary` next to the grades file ``output``; return its path and a short text.

    The text names the file and the ``lines`` questions with the lowest share of students passing,
    each with its commonest diagnosed mistake. ``unmatched`` lists the files of a platform's download
    that were not graded (see :mod:`.collect`); the summary ends with them. The file is written like the
    CSV and the feedback (a fresh temporary name moved into place), and :func:`~puma_course.grading.grade`
    keeps its name free of any student's feedback file. ``copies`` (:func:`~.copies.find_copies`) adds the
    copy report: near-copies of the package, a lecture or a classmate, and hidden code; it changes no mark.
    """
    path = summary_path(output)
    text = class_summary(results, unmatched, copies, totals)
    replace_atomically(path, text)  # whole or not at all; a planted link is replaced
    return path, summary_note(results, output, lines)


def summary_note(results: Sequence[NotebookResult], output: str | os.PathLike[str], lines: int = 8) -> str:
    """The short text :func:`write_summary` returns: the summary's file and the hardest ``lines`` questions."""
    path = summary_path(output)
    hard = sorted((s for s in question_summaries(results) if s.submitted), key=lambda s: s.passed / s.submitted)
    text = [f"class summary: {path}"]
    for s in hard[:lines]:
        if s.passed == s.submitted:
            break
        common = s.common(1)
        why = f"; commonest mistake: {TITLES.get(common[0][0], common[0][0])} ({common[0][1]})" if common else ""
        text.append(f"  {s.exercise} {s.question.qid} {s.question.function}: {s.passed}/{s.submitted} passed{why}")
    return "\n".join(text)


def run_outcome(results: Sequence[Any], submissions: Path, names: Sequence[str]) -> tuple[int, str]:
    """The exit code of a grading run and what went wrong: (0, ""), or 4 when no student folder holds any
    notebook (the message says where it looked and in which layout: a flat download of notebooks is named),
    or 5 when every notebook found crashed."""
    found = [r for r in results if r.status != "missing"]
    elsewhere = submissions.is_dir() and any(submissions.glob("*/*.ipynb"))  # misnamed: the feedback names them
    if not found and not elsewhere:
        flat = sorted(p.name for p in submissions.glob("*.ipynb")) if submissions.is_dir() else []
        layout = (
            f"; it holds notebooks directly ({', '.join(flat[:3])}{', ...' if len(flat) > 3 else ''}): a flat "
            "download, give each student a folder"
            if flat
            else ""
        )
        return 4, (
            f"no notebook found: looked for {str(submissions)!r}/<student>/<exercise>.ipynb with exercise "
            f"in {', '.join(names)} (one folder per student){layout}"
        )
    if found and all(r.status == "crashed" for r in found):
        return 5, (
            f"every one of the {plural(len(found), 'notebook')} found crashed: the grader or its sandbox is broken "
            "here, not the students (see the CSV's notes)"
        )
    return 0, ""
