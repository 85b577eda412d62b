"""Rendering results: one per-question line, the ``puma-course check`` report, feedback Markdown, the CSV.

:func:`format_question` is the only place a question's result is worded. The self-check
(:func:`puma_course.grading.check`), the feedback files written by :func:`~puma_course.grading.grade`
and ``puma-course check`` (:func:`format_check_report`) all print through it, so a student reads
the same verdicts, scores and hints everywhere:

* ``passed``: every case passed (full points);
* ``partly``: some cases passed (points in proportion);
* ``not attempted yet``: no case passed and every failure is the released stub's ``NotImplementedError``;
* ``FAILED``: anything else, with the first distinct reasons.

A question's hint follows ``partly`` and ``FAILED`` only: after an attempt, never beside "not attempted yet".
"""

from __future__ import annotations

import contextlib
import csv
import io
import os
import re
import tempfile
from collections.abc import Collection, Mapping, Sequence
from pathlib import Path

from ..bank_loader import EXERCISES
from ..results import NotebookResult
from ..run.worker import NOT_ATTEMPTED
from ..secret import Secret
from ..spec import Exercise, Question
from .text import csv_safe, file_stem, one_line, quoted
from .totals import WrittenScore

__all__ = [
    "verdict",
    "format_question",
    "format_check_report",
    "feedback_markdown",
    "hidden_inputs_note",
    "write_feedback",
    "feedback_paths",
    "write_csv",
    "csv_rows",
    "safe_name",
    "replace_atomically",
]

_COUNT_LINE = re.compile(r"^\d+/\d+ cases pass$")


def verdict(q: Question, earned: float, notes: Sequence[str]) -> str:
    """``passed``, ``partly``, ``not attempted yet`` or ``FAILED`` for ``earned`` points and the case notes.

    >>> from puma_course.grading import EXERCISES
    >>> q = EXERCISES["ex01_rotations"].question("q1")
    >>> verdict(q, 2, ["3/3 cases pass"]), verdict(q, 1.33, ["2/3 cases pass", "case 3: wrong sign"])
    ('passed', 'partly')
    >>> verdict(q, 0, ["0/3 cases pass", "case 1: not attempted yet (NotImplementedError)"])
    'not attempted yet'
    """
    if earned >= q.points:
        return "passed"
    if earned > 0:
        return "partly"
    reasons = [n for n in notes if not _COUNT_LINE.match(n)]
    if reasons and all(NOT_ATTEMPTED in r for r in reasons):
        return NOT_ATTEMPTED
    return "FAILED"


def _wants_hint(q: Question, earned: float, notes: Sequence[str]) -> bool:
    """A hint follows an attempt that fell short (``partly`` or ``FAILED``), never "not attempted yet": shown
    before the student has tried, a hint gives away the step the question asks them to find."""
    return bool(q.hint) and verdict(q, earned, notes) in ("partly", "FAILED")


def format_question(
    q: Question, earned: float, notes: Sequence[str], *, markdown: bool = False, scope: str = ""
) -> str:
    """The result of one question as a text line (plus an indented ``Hint:`` line), or with ``markdown`` a table row.

    ``notes`` are the question's notes ("k/n cases pass", then reasons); a not-attempted question
    shows its verdict only, without the hint (a hint comes after an attempt that fell short). The
    Markdown row has the columns question | points | result. ``scope`` says which cases the points count
    (the self-check: "on the public cases", the grader's points come from more).

    >>> from puma_course.grading import EXERCISES
    >>> q = EXERCISES["ex01_rotations"].question("q4")
    >>> print(format_question(q, 2, ["4/4 cases pass"]))
    q4 relative_pose: 2 / 2 points - passed (4/4 cases pass)
    >>> print(format_question(q, 0, ["0/4 cases pass", "public case 1: returned shape (3,)"]))  # doctest: +ELLIPSIS
    q4 relative_pose: 0 / 2 points - FAILED (0/4 cases pass; public case 1: returned shape (3,))
      Hint: Write the chain {A} → {0} → {B} as a product of two transforms, ...
    >>> format_question(q, 2, ["4/4 cases pass"], markdown=True)
    '| q4 `relative_pose` | 2 / 2 | passed: 4/4 cases pass |'
    """
    word = verdict(q, earned, notes)
    bonus = " (bonus)" if q.bonus else ""
    detail = "; ".join(notes) if word != NOT_ATTEMPTED else ""
    if markdown:
        result = (f"{word}: {detail}" if detail else word).replace("|", r"\|")
        return f"| {q.qid} `{q.function}`{bonus} | {earned:g} / {q.points:g} | {result} |"
    on = f" {scope}" if scope else ""
    line = f"{q.qid} {q.function}{bonus}: {earned:g} / {q.points:g} points{on} - {word}"
    if detail:
        line += f" ({detail})"
    if _wants_hint(q, earned, notes):
        line += f"\n  Hint: {q.hint}"
    return line


def format_check_report(result: NotebookResult, exercise: Exercise) -> str:
    """What ``puma-course check`` prints: the score on the public cases, notes, one line per question.

    >>> from puma_course.grading import EXERCISES, NotebookResult
    >>> ex = EXERCISES["ex01_rotations"]
    >>> r = NotebookResult("me", ex.name, "missing", ex.max_score, scores={q.qid: 0.0 for q in ex.questions})
    >>> print(format_check_report(r, ex).splitlines()[0])
    ex01_rotations: 0 / 15 on the public cases (status missing)
    """
    lines = [f"{exercise.name}: {result.score:g} / {result.max_score:g} on the public cases (status {result.status})"]
    lines += [f"  {note}" for note in result.notes]
    for q in exercise.questions:
        text = format_question(q, result.scores.get(q.qid, 0.0), result.question_notes.get(q.qid, []))
        lines += [f"  {line}" for line in text.splitlines()]
    return "\n".join(lines)


def feedback_markdown(
    student: str,
    results: Sequence[NotebookResult],
    seed: int | None = None,
    unsandboxed: str | None = None,
    key: Secret | None = None,
    as_user: str | None = None,
    written: WrittenScore | None = None,
    section: str = "",
) -> str:
    """One student's feedback file: per exercise the status, the score, one table row per question, hints.

    The student's folder name and every text of the student's that a note repeats are quoted as
    code, so the file shows them literally (no headings, links or table rows of the student's
    making). ``unsandboxed`` is the reason the notebooks ran without the operating-system sandbox,
    if they did: the file then says so first. ``key`` is the grading run's key: the file ends by
    saying where the hidden inputs came from (:func:`hidden_inputs_note`). ``written`` is the student's
    written points (``grade --marks``): the total then counts those marked, as the gradebooks do, says how it is
    made up, and is called provisional while an answer waits for a mark; ``section`` (the written questions'
    marks, :func:`.marks.feedback_section`) follows the exercises.

    >>> feedback_markdown("x\\n# Total: 56 / 56", [], seed=1).splitlines()[0]
    '# Feedback for `x\\\\x0a# Total: 56 / 56`'
    """
    lines = [f"# Feedback for {quoted(student, 120)}", ""]
    del seed  # accepted for compatibility, never printed: a printed seed let a student rebuild the hidden inputs
    if unsandboxed is not None and as_user is not None:  # Gradescope: no bubblewrap, but a user of its own, alone
        lines += [
            f"> Graded without bubblewrap ({one_line(unsandboxed, 300)}): the notebook ran alone in its container, "
            f"as the unprivileged user {quoted(as_user, 60)}, which could not open the grader's files.",
            "",
        ]
    elif unsandboxed is not None:
        lines += [
            "> **Warning: graded without the operating-system sandbox** "
            f"({one_line(unsandboxed, 300)}). The grades may not be reliable if a classmate's "
            "notebook interfered with the grading.",
            "",
        ]
    total = round(sum(r.score for r in results), 2)
    top = round(sum(r.max_score for r in results), 2)
    if written is None:
        lines += [f"Total: **{total:g} / {top:g}** points.", ""]
    else:
        both = f"**{round(total + (written.points or 0.0), 2):g} / {round(top + written.possible, 2):g}** points"
        if written.provisional:  # the same total as the gradebooks', said to leave out what is not marked yet
            lines.append(f"Total: {both}, provisional (auto-graded {total:g} / {top:g}; written questions: "
                         f"{written.text()}).")  # fmt: skip
        else:
            lines.append(f"Total: {both} (auto-graded {total:g} / {top:g}, written questions {written.text()}).")
        lines.append("")
    for r in results:
        ex = EXERCISES[r.exercise]
        lines += [
            f"## {r.exercise}: {ex.title}",
            "",
            f"Status: `{r.status}`. Score: **{r.score:g} / {r.max_score:g}**."
            + (f" Run id: `{r.run_id}`." if r.run_id else ""),
            "",
        ]
        for note in r.notes:
            lines.append(f"- {one_line(note, 600)}")
        if r.notes:
            lines.append("")
        if r.status in ("missing", "malformed", "refused", "unreadable"):
            continue
        lines += ["| question | points | result |", "| --- | --- | --- |"]
        for q in ex.questions:
            lines.append(format_question(q, r.scores[q.qid], r.question_notes.get(q.qid, []), markdown=True))
        if any(q.bonus for q in ex.questions):
            lines += ["", "Bonus points count in your score, not in the maximum."]
        failing = [q for q in ex.questions if _wants_hint(q, r.scores[q.qid], r.question_notes.get(q.qid, []))]
        if failing:
            lines += ["", "Hints:"] + [f"- {q.qid}: {q.hint}" for q in failing]
        lines.append("")
    if section:
        lines += [section.rstrip("\n"), ""]
    note = hidden_inputs_note(key)
    lines += ["", note] if note else []
    return "\n".join(lines) + "\n"


def hidden_inputs_note(key: Secret | None) -> str:
    """The feedback's last line: where the hidden inputs came from, said only as far as it is true.

    A key file (the instructor's secret): drawn for this student alone, and repeatable. A public seed
    (``--seed N``): a seed the class shares, from which anyone can rebuild them. A one-off key: for
    this run only. No key known: nothing.

    >>> from puma_course.grading.secret import from_seed
    >>> hidden_inputs_note(from_seed(3)).split(";")[0]
    'Your hidden inputs came from a seed shared by the whole class, not from a secret key'
    >>> hidden_inputs_note(None)
    ''
    """
    if key is None:
        return ""
    if key.seed is not None:
        return (
            "Your hidden inputs came from a seed shared by the whole class, not from a secret key; anyone who knows "
            "the seed can draw them again."
        )
    if key.source == "one-off":
        return "Your hidden inputs were drawn for you alone, from a key made for this grading run only."
    return (
        "Your hidden inputs were drawn for you alone, from a key your instructor keeps; the run id names them, "
        "so your instructor can repeat your grading exactly."
    )


def safe_name(name: str) -> str:
    """A file-name-safe form of a student's folder name (bounded in length, never hidden or empty).

    >>> safe_name("../Ann Lee")
    'Ann_Lee'
    """
    return file_stem(name)


def replace_atomically(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a fresh temporary file and a rename: whole or not at all, and a
    link planted at ``path`` is replaced, never followed."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name[:50]}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", newline="", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def write_feedback(
    folder: str | os.PathLike[str],
    results: Sequence[NotebookResult],
    seed: int | None = None,
    unsandboxed: str | None = None,
    reserved: Sequence[str] = (),
    key: Secret | None = None,
    as_user: str | None = None,
    written: Mapping[str, WrittenScore] | None = None,
    sections: Mapping[str, str] | None = None,
) -> dict[str, Path]:
    """One Markdown file per student in ``folder`` (created); returns the file of each student.

    ``reserved`` are file stems no student gets (the grades file's and the class summary's, when they are
    written into the same folder): a student whose folder has such a name gets ``NAME_2.md``. ``written`` and
    ``sections`` give each student's written points and marks (see :func:`feedback_markdown`).
    """
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    by_student: dict[str, list[NotebookResult]] = {}
    for r in results:
        by_student.setdefault(r.student, []).append(r)
    files = feedback_paths(out, list(by_student), reserved)
    for student, mine in by_student.items():
        text = feedback_markdown(
            student,
            mine,
            seed,
            unsandboxed,
            key,
            as_user,
            written=None if written is None else written.get(student, WrittenScore(0.0, 0.0)),
            section=(sections or {}).get(student, ""),
        )
        replace_atomically(files[student], text)
    return files


def feedback_paths(
    folder: str | os.PathLike[str], students: Sequence[str], reserved: Sequence[str] = ()
) -> dict[str, Path]:
    """The feedback file of each student (in the order given) in ``folder``, as :func:`write_feedback` names them.

    >>> {s: p.name for s, p in feedback_paths("fb", ["Ann Lee", "Ann_Lee", "grades"], ["grades"]).items()}
    {'Ann Lee': 'Ann_Lee.md', 'Ann_Lee': 'Ann_Lee_2.md', 'grades': 'grades_2.md'}
    """
    used: set[str] = {r.lower() for r in reserved}
    files = {}
    for student in students:
        stem = base = file_stem(student)
        k = 2
        while stem.lower() in used:  # two names that make the same file name (also on case-insensitive disks)
            stem, k = f"{base}_{k}", k + 1
        used.add(stem.lower())
        files[student] = Path(folder) / f"{stem}.md"
    return files


def csv_rows(
    results: Sequence[NotebookResult],
    names: Sequence[str],
    seed: int | None = None,
    sandbox: str = "",
    secret: str = "",
    late: Collection[tuple[str, str]] | None = None,
    limits: str = "",
) -> list[list[str]]:
    """The CSV's rows, header first (see :func:`write_csv`)."""
    qids: list[str] = []
    for name in names:
        for q in EXERCISES[name].questions:
            if q.qid not in qids:
                qids.append(q.qid)
    head = ["student", "exercise", "score", "max_score", "bonus", *qids, "status", "sandbox", "limits", "seed"]
    rows = [[*head, "secret", "run", "notes"]]
    if late is not None:
        rows[0].append("late")
    for r in results:
        ex = EXERCISES.get(r.exercise)
        bonus = sum(r.scores.get(q.qid, 0.0) for q in ex.questions if q.bonus) if ex is not None else 0.0
        row = [csv_safe(r.student), r.exercise, f"{r.score:g}", f"{r.max_score:g}", f"{round(bonus, 2):g}"]
        row += [f"{r.scores[q]:g}" if q in r.scores else "" for q in qids]
        row += [r.status, sandbox, limits, "" if seed is None else str(seed), secret, r.run_id]
        row.append(csv_safe(one_line(" | ".join(r.notes), 500)))
        if late is not None:
            row.append("late" if (r.student, r.exercise) in late else "")
        rows.append(row)
    return rows


def write_csv(
    output: str | os.PathLike[str],
    results: Sequence[NotebookResult],
    names: Sequence[str],
    *,
    seed: int | None = None,
    sandbox: str = "",
    secret: str = "",
    late: Collection[tuple[str, str]] | None = None,
    limits: str = "",
) -> None:
    """Write the grades: student, exercise, score, max_score, bonus, one column per question id, status,
    sandbox, limits, seed, secret, run, notes.

    ``bonus`` is the part of the score that bonus questions earned (it counts in ``score``, not in
    ``max_score``); ``sandbox`` says how the notebooks ran ("bwrap" or "none"); ``limits`` how the
    notebook's memory, processes and CPU were limited (per notebook by a control group, or per process
    only, and why); ``secret`` is the fingerprint of the key the hidden inputs were drawn from, ``run``
    each notebook's run id, and ``seed`` the public seed when one stood for the key (empty otherwise):
    with the same key file, ``grade`` draws the same inputs again. With ``late`` (the (student, exercise)
    pairs a platform marked late), a last column ``late`` says "late" for those. A text cell that a
    spreadsheet would read as a formula starts with ``'``. The file is written under a fresh temporary
    name and moved into place, so it appears whole or not at all.
    """
    out = Path(output)
    if out.parent and not out.parent.exists():
        out.parent.mkdir(parents=True, exist_ok=True)
    buffer = io.StringIO()
    csv.writer(buffer).writerows(csv_rows(results, names, seed, sandbox, secret, late, limits=limits))
    replace_atomically(out, buffer.getvalue())
