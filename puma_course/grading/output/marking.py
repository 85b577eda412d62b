"""The marker's files for the written questions: ``puma-course collect-written SUBMISSIONS -o DIR``.

Reads the handed-in notebooks (any layout ``grade`` reads: ``folders``, ``canvas``, ``moodle``; read by the
same code, links never followed, nothing run) and writes into DIR, per written question of each exercise:

* ``<exercise>-<qid>.md``: one Markdown document, the question and its rubric (each criterion with its
  points, what a full answer contains, the worked answer) above every student's answer, each under its own
  heading, with the images the student attached (saved beside it in ``attachments/``); an answer the student
  went on writing in cells of their own below the answer cell is shown whole, with a note saying so
  (:func:`~puma_course.grading.written.read_answers`). It renders with its
  formulas in JupyterLab (``puma-course lab``, then open it with the Markdown preview), offline. A student's
  text is shown inside a quote, with its HTML and links to images elsewhere made inert, so it cannot change
  the document around it or fetch anything;
* ``<exercise>-<qid>-marks.csv``: the marks template, one row per student who handed the notebook in, the
  columns ``student, exercise, question, points, comment`` and one per rubric line (its name). Fill in either
  ``points`` or the rubric columns (then ``points`` is their sum), or both (they must agree), and a comment;
  ``puma-course grade ... --marks FILE`` merges it (:mod:`.marks`).

With ``anonymise``, a student is named by a stable code (:func:`student_code`: the same student has the same
code in every file and every run), so marking is blind; ``--marks`` accepts codes and names alike.
"""

from __future__ import annotations

import csv
import hashlib
import io
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..model import EXERCISES
from ..run.collect import collect
from ..run.submissions import StudentFolder, read_student, scan
from ..written import Answer, WrittenQuestion, read_answers, release_of, written_exercises, written_questions
from .report import replace_atomically
from .text import csv_safe, file_stem, quoted

__all__ = ["student_code", "Marking", "collect_written", "marking_markdown", "template_rows", "FIXED_COLUMNS"]

FIXED_COLUMNS = ["student", "exercise", "question", "points", "comment"]


def student_code(student: str) -> str:
    """The stable code that stands for ``student`` in anonymised marking files.

    >>> student_code("Ann Lee"), student_code("Ann Lee") == student_code("Ann Lee"), len(student_code("x"))
    ('S-a36e143c', True, 10)
    """
    return "S-" + hashlib.sha256(student.encode("utf-8", "surrogateescape")).hexdigest()[:8]


@dataclass
class Marking:
    """What :func:`collect_written` wrote: the files, and the answers read per (exercise, question)."""

    folder: Path
    files: list[Path] = field(default_factory=list)
    answers: dict[tuple[str, str], int] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)


def _inert(text: str) -> str:
    """A student's Markdown with its HTML shown as text and its images made into words (attachments are shown
    below the answer; an image elsewhere would be fetched when the document is viewed)."""
    text = re.sub(r"!\[([^\]]*)\]\(\s*attachment:[^)]*\)", r"*[attached image \1: shown below]*", text)
    text = re.sub(r"!\[([^\]]*)\]\([^)]*\)", r"*[image \1: not shown]*", text)
    return text.replace("&", "&amp;").replace("<", "&lt;")


def _quote(text: str) -> list[str]:
    return [f"> {line}" if line.strip() else ">" for line in text.splitlines()] or [">"]


def marking_markdown(w: WrittenQuestion, answers: list[tuple[str, Answer, list[str]]]) -> str:
    """The marking document of ``w``: question, rubric, worked answer, then (shown name, answer, image paths)."""
    spec = w.spec
    lines = [f"# {w.exercise} {w.qid}: {spec.title} ({w.points:g} points)", "", "## The question", ""]
    lines += _quote(spec.prompt.strip())
    lines += ["", "## Rubric", "", "| criterion | points | earns them |", "| --- | --- | --- |"]
    lines += [f"| {c.name} | {c.points:g} | {c.text.replace('|', '/')} |" for c in spec.criteria]
    lines += ["", "**A full answer contains:**", "", spec.full_answer.strip(), "", "**Worked answer:**", ""]
    lines += [spec.worked.strip(), "", f"## Answers ({len(answers)})", ""]
    lines.append(
        f"Mark each answer in `{w.exercise}-{w.qid}-marks.csv` (its row for the student): the rubric columns "
        f"({', '.join(c.name for c in spec.criteria)}) or `points`, and a `comment` the student will read."
    )
    for shown, answer, images in answers:
        lines += ["", "---", "", f"### {quoted(shown, 120)}", ""]
        lines += [f"*{note}*" for note in answer.notes] + ([""] if answer.notes else [])
        if answer.empty:
            lines.append("*(no answer written)*")
            continue
        if answer.text.strip():
            lines += _quote(_inert(answer.text))
        for k, path in enumerate(images, start=1):
            lines += ["", f"![{shown}, attachment {k}]({path})"]
    return "\n".join(lines) + "\n"


def template_rows(w: WrittenQuestion, students: list[str]) -> list[list[str]]:
    """The marks template of ``w`` for ``students`` (as they are to be named), header first."""
    names = [c.name for c in w.spec.criteria]
    blank = ["" for _ in names]
    return [[*FIXED_COLUMNS, *names]] + [[csv_safe(s), w.exercise, w.qid, "", "", *blank] for s in students]


def _read_all(
    submissions: Path, layout: str, names: list[str], others: dict[str, str]
) -> tuple[list[tuple[str, dict[str, bytes]]], list[str]]:
    """(student as graded, exercise -> notebook bytes) for every student, and the files not read, with why."""
    problems: list[str] = []
    found: list[tuple[str, dict[str, bytes]]] = []
    if layout == "folders":
        try:
            students = scan(submissions)
        except OSError as exc:
            raise ValueError(f"submissions: expected a readable folder, got {str(submissions)!r} ({exc})") from None
        read = [(s.name, read_student(submissions, s, names)) for s in students]
    else:
        c = collect(submissions, layout, names, others)
        problems += c.problems
        read = [(s.key, c.read(StudentFolder(s.key, s.key), names)) for s in c.students]
    for student, files in read:
        mine = {}
        for name, nb in files.notebooks.items():
            if nb.state == "read" and nb.data is not None:
                mine[name] = nb.data
            elif nb.state != "missing":
                problems.append(f"{student}: {name}: {nb.state} ({nb.note})")
        found.append((student, mine))
    return found, problems


def collect_written(
    submissions: str | os.PathLike[str],
    out: str | os.PathLike[str],
    layout: str = "folders",
    exercises: list[str] | None = None,
    anonymise: bool = False,
) -> Marking:
    """Write the marking documents and marks templates of every written question (see the module docstring).

    ``exercises`` names the exercises (default: every exercise with written questions that someone handed
    in). ValueError when one has no written question, or the submissions folder cannot be read or holds none.
    """
    have = written_exercises()
    names = have if not exercises else list(exercises)
    unknown = [n for n in names if n not in have]
    if unknown or not names:
        raise ValueError(f"exercise: expected exercises with written questions ({', '.join(have)}), got {unknown}")
    sub = Path(submissions)
    if not sub.is_dir():
        raise ValueError(f"submissions: expected a folder, got {str(sub)!r}")
    # a file of another exercise is "not collected: has no written question", not "matches no exercise"
    others = {n: "has no written question" for n in EXERCISES if n not in have}
    others.update({n: "was not asked for (--exercise)" for n in have if n not in names})
    people, problems = _read_all(sub, layout, names, others)
    if not exercises:  # by default, the exercises someone handed in
        names = [n for n in names if any(n in files for _, files in people)]
        if not names:
            raise ValueError(
                f"submissions: expected notebooks of {', '.join(have)} (they have written questions) read as "
                f"--layout {layout}, got none in {str(sub)!r}"
            )
    folder = Path(out)
    (folder / "attachments").mkdir(parents=True, exist_ok=True)
    result = Marking(folder, problems=problems)
    for name in names:
        release = release_of(name)  # the exercise's own cells, to tell the cells a student added below an answer
        handed = [(student, read_answers(files[name], name, release)) for student, files in people if name in files]
        for w in written_questions(name):
            shown_rows, listed = [], []
            for student, answers in handed:
                shown = student_code(student) if anonymise else student
                images = []
                for k, (_, ext, raw) in enumerate(answers[w.qid].images, start=1):
                    path = folder / "attachments" / f"{name}-{w.qid}-{file_stem(shown, 60)}-{k}.{ext}"
                    path.write_bytes(raw)
                    images.append(f"attachments/{path.name}")
                shown_rows.append((shown, answers[w.qid], images))
                listed.append(shown)
            doc = folder / f"{name}-{w.qid}.md"
            replace_atomically(doc, marking_markdown(w, shown_rows))
            buffer = io.StringIO()
            csv.writer(buffer).writerows(template_rows(w, listed))
            sheet = folder / f"{name}-{w.qid}-marks.csv"
            replace_atomically(sheet, buffer.getvalue())
            result.files += [doc, sheet]
            result.answers[name, w.qid] = sum(1 for _, a, _ in shown_rows if not a.empty)
    return result
