"""The marker's files for the written questions: ``puma-course collect-written SUBMISSIONS -o DIR``.

Reads the handed-in notebooks (any layout ``grade`` reads: ``folders``, ``canvas``, ``moodle``; read by the
same code, links never followed, nothing run) and writes into DIR, per written question of each exercise:

* ``<exercise>-<qid>.md``: one Markdown document, the question and its rubric (each criterion with its
  points, what a full answer contains, the worked answer) above every student's answer, each under its own
  heading, with the images the student attached (saved beside it in ``attachments/``); an answer the student
  went on writing in cells of their own below the answer cell is shown whole, with a note saying so
  (:func:`~puma_course.grading.written.read_answers`). It renders with its
  formulas in JupyterLab (``puma-course lab``, then open it with the Markdown preview), offline. A student's
  text is shown inside a quote, made inert (:func:`_inert`: no image, link, HTML or heading of its own), so it
  cannot change the document around it, pose as another student's section or fetch anything; attachments
  are saved under a file name no other student's shares;
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

from ..bank_loader import EXERCISES
from ..intake.collect import collect
from ..intake.submissions import StudentFolder, read_student, scan
from ..written import Answer, WrittenQuestion, read_answers, release_of, written_exercises, written_questions
from .report import replace_atomically
from .text import csv_safe, file_stem, plural, quoted

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
    """What :func:`collect_written` wrote: the files, and per (exercise, question) the answers written (not blank)
    and the rows of its marks template (one per student who handed the exercise in, blank answers included)."""

    folder: Path
    files: list[Path] = field(default_factory=list)
    answers: dict[tuple[str, str], int] = field(default_factory=dict)
    rows: dict[tuple[str, str], int] = field(default_factory=dict)  # rows of each marks template: one per student
    problems: list[str] = field(default_factory=list)


#: A formula in a student's Markdown: ``$$...$$`` or ``$...$`` (``\$`` is no delimiter), kept apart so it still renders.
_MATH = re.compile(r"(\$\$(?:\\.|[^\\])+?\$\$|\$(?:\\.|[^\\$])+?\$)", re.DOTALL)
#: What opens a link in text or a formula: URL schemes and ``www.`` (autolinked by GFM renderers), e-mail's ``@``,
#: and the formula commands that make links or load code (MathJax's ``\href``, ``\url``, ``\require``, ...).
_LINKY = re.compile(r"(?i)(?<=[a-z0-9+.-])(:)(?=//)|\b(www)(\.)|(@)|\\(href|url|require|class|cssId|style|html\w*)\b")
#: A line that could underline the line above into a heading or draw a rule (after quote and list markers).
_RULE = re.compile(r"^((?:[ \t]*(?:>|[*+-](?=[ \t])|\d{1,9}[.)](?=[ \t])))*[ \t]*)([-=*_][-=*_ \t]*)$")
_IN_TEXT = {"&": "&amp;", "<": "&lt;", "[": "&#91;", "]": "&#93;", "#": "&#35;", "`": "&#96;"}
_IN_MATH = {"<": r"\lt{}", ">": r"\gt{}", "[": r"\lbrack{}", "]": r"\rbrack{}", "#": r"\#"}


def _unlink(match: re.Match[str]) -> str:
    colon, www, dot, at, command = match.groups()
    if command:
        return rf"\mathrm{{{command}}}"
    if www:
        return f"{www}\u200b{dot}"
    return f"{colon or at}\u200b"  # a zero-width space: the text reads the same, no renderer links it


def _inert(text: str) -> str:
    r"""A student's Markdown made inert: shown as written, but with no link, image, HTML, heading or rule of its own.

    Attached images become words (they are shown below the answer, from the marker's own copy). Outside formulas
    every character that opens Markdown or HTML structure (``[ ] < # ` &``) becomes a character reference, so no
    inline or reference-style image or link, ``[ref]: url`` definition, HTML tag (``<img>``, ``<a>``,
    ``<iframe>``, ``srcset``), autolink ``<http://...>``, code span or heading can form, whatever the renderer;
    inside ``$...$`` the same characters become their LaTeX names (``\lbrack``, ``\lt``), so formulas still
    render. URLs and ``www.`` get a zero-width space after the scheme's colon so that no renderer links them
    bare, MathJax's ``\href`` and kin are spelled out, and a line of ``-``, ``=``, ``*`` or ``_`` (a setext
    heading's underline or a rule) is shown as characters.

    >>> print(_inert("![x](http://e.org/a.png) [r]: www.e.org <img src=x> $[0, \\pi]$").replace("\u200b", "|"))
    !&#91;x&#93;(http:|//e.org/a.png) &#91;r&#93;: www|.e.org &lt;img src=x> $\lbrack{}0, \pi\rbrack{}$
    """
    text = re.sub(r"!\[([^\]]*)\]\(\s*<?attachment:[^)]*\)", r"(attached image “\1”: shown below)", text)
    parts = _MATH.split(text)
    out = []
    for k, part in enumerate(parts):
        table = _IN_MATH if k % 2 else _IN_TEXT
        out.append(_LINKY.sub(_unlink, "".join(table.get(ch, ch) for ch in part)))
    lines = "".join(out).split("\n")
    for i, line in enumerate(lines):
        m = _RULE.match(line)
        if m:
            lines[i] = m.group(1) + "".join(f"&#{ord(ch)};" if ch in "-=*_" else ch for ch in m.group(2))
    return "\n".join(lines)


def _quote(text: str) -> list[str]:
    return [f"> {line}" if line.strip() else ">" for line in re.split(r"\r\n|\r|\n", text)] or [">"]


def marking_markdown(w: WrittenQuestion, answers: list[tuple[str, Answer, list[str]]]) -> str:
    """The marking document of ``w``: question, rubric, worked answer, then (shown name, answer, image paths)."""
    spec = w.spec
    lines = [f"# {w.exercise} {w.qid}: {spec.title} ({plural(w.points, 'point')})", "", "## The question", ""]
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
        lines += [f"*{_inert(note)}*" for note in answer.notes] + ([""] if answer.notes else [])
        if answer.empty:
            lines.append("*(no answer written)*")
            continue
        if answer.text.strip():
            lines += _quote(_inert(answer.text))
        for k, path in enumerate(images, start=1):
            lines += ["", f"![attachment {k} of the answer above]({path})"]
    return "\n".join(lines) + "\n"


def _own_stem(shown: str, taken: set[str]) -> str:
    """A file-name stem for ``shown`` that no other student of ``taken`` has (compared without case), then taken.

    The stem is :func:`file_stem` of the name where that keeps it whole, else (``Ann Lee`` becomes ``Ann_Lee``,
    a long name is cut) followed by a hash of the name, longer until it is free: ``Ann Lee`` and ``Ann_Lee``,
    or ``ann`` and ``Ann`` on a file system that ignores case, never share an attachment.

    >>> taken = set()
    >>> _own_stem("Ann_Lee", taken), _own_stem("Ann Lee", taken), _own_stem("ann_lee", taken)[:8]
    ('Ann_Lee', 'Ann_Lee-a36e143c', 'ann_lee-')
    """
    stem = file_stem(shown, 60)
    digest = hashlib.sha256(shown.encode("utf-8", "surrogateescape")).hexdigest()
    candidates = ([stem] if stem == shown else []) + [f"{stem}-{digest[:n]}" for n in (8, 16, 64)]
    candidates.append(f"{stem}-{digest}-{len(taken)}")  # the same name twice (codes that collide): still apart
    candidate = next(c for c in candidates if c.lower() not in taken)
    taken.add(candidate.lower())
    return candidate


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
            taken: set[str] = set()
            for student, answers in handed:
                shown = student_code(student) if anonymise else student
                stem = _own_stem(shown, taken)
                images = []
                for k, (_, ext, raw) in enumerate(answers[w.qid].images, start=1):
                    path = folder / "attachments" / f"{name}-{w.qid}-{stem}-{k}.{ext}"
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
            result.rows[name, w.qid] = len(listed)
    return result
