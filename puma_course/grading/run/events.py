"""From a worker's events to a graded notebook: the grader words every message and quotes the student's text.

The events come through a pipe the student's code can also write to, so nothing in them is
trusted: a value is only a candidate answer (judged against the reference computed here), an
error is a code from a fixed list (worded here) plus, at most, the student's own text (an
exception's message, a type's name), which goes into the feedback only through
:func:`~puma_course.grading.output.text.quoted`. A field of the wrong type is ignored, a case the plan
does not have is ignored, and only the first answer to a case counts.
"""

from __future__ import annotations

import time
from typing import Any

from ..judge.bounds import check_answer
from ..judge.verdict import Verdict, reconcile
from ..output.text import quoted
from ..plan import Plan
from ..results import NotebookResult, score_question
from ..spec import Exercise, Question, key_words
from .child import ChildResult
from .limits import WALL_FACTOR
from .worker import NOT_ATTEMPTED

__all__ = ["apply", "tampered", "malformed_note", "call_verdict", "cell_note", "JUDGING_SECONDS"]

#: The time the grader spends judging one notebook's answers, at most; cases after it are not judged.
#: (Each answer is bounded before it is judged, so an honest notebook's judging takes milliseconds.)
JUDGING_SECONDS = 10.0

_MALFORMED = {
    "json": "not a readable notebook (not valid JSON: line {line}, column {column})",
    "encoding": "not a readable notebook (not UTF-8 text)",
    "nesting": "not a readable notebook (its JSON is nested too deeply)",
    "no-cells": "not a readable notebook (no list of cells)",
    "cell": "not a readable notebook (a code cell's source is not text)",
    "too-much-code": "the notebook holds more code than the grader runs (5,000,000 characters): not run",
}


def _int(value: Any) -> int:
    return value if isinstance(value, int) and not isinstance(value, bool) and 0 <= value < 10**9 else 0


def _text(value: Any) -> str:
    return value if isinstance(value, str) else ""


def malformed_note(event: dict[str, Any]) -> str:
    """The note for a notebook the worker could not read (only its reason code and position are used).

    >>> malformed_note({"code": "json", "line": 1, "column": 87})
    'not a readable notebook (not valid JSON: line 1, column 87)'
    """
    template = _MALFORMED.get(_text(event.get("code")), "not a readable notebook")
    return template.format(line=_int(event.get("line")), column=_int(event.get("column")))


def _where(event: dict[str, Any]) -> str:
    line = _int(event.get("line"))
    return f" (line {line} of its cell)" if line else ""


def call_verdict(
    q: Question, event: dict[str, Any] | None, expected: Any, args: tuple[Any, ...], limits: str
) -> Verdict:
    """The verdict on the worker's answer to one call: right, or the reason (the student's text quoted).

    ``limits`` is the per-call time limit as the student reads it ("10 s").
    """
    if event is None:
        return Verdict("no answer came back (the notebook stopped before this call)")
    error = event.get("error")
    if error is not None:
        detail = _text(event.get("detail"))
        reasons = {
            "not-attempted": f"{NOT_ATTEMPTED} (NotImplementedError)",
            "no-function": f"no function named {q.function}() was defined",
            "not-callable": f"{q.function} is a {quoted(detail, 60)}, not a function",
            "skipped": "skipped: an earlier case of this question ran out of time",
            "timeout": f"the call ran longer than {limits}",
            "convert-timeout": f"converting the returned value to numbers took longer than {limits}",
            "raised": f"raised {quoted(detail)}{_where(event)}",
            "not-numbers": f"returned a {quoted(detail, 60)}, which is not an array of numbers",
            "too-many": f"returned {_int(event.get('size'))} numbers, more than the 10000 allowed",
        }
        if error == "timeout":
            return Verdict(timeout_words("the call", event, limits))
        if error == "answer-key" and detail.startswith("tamper:"):
            return Verdict(
                f"switched off the grader's watch on the answer key ({detail[7:]}) while being graded: the case fails"
            )
        if error == "answer-key":
            spec = detail if detail in q.forbidden else ""
            return Verdict(key_words(spec))
        return Verdict(reasons.get(_text(error), "the call failed"))
    if "value" not in event:
        return Verdict("no value came back")
    refused = check_answer(event["value"], expected)  # measured before anything is built from it
    if refused is not None:
        return Verdict(refused)
    try:
        return q.judge(event["value"], expected, args)
    except Exception as exc:  # noqa: BLE001 - a bizarre value must not stop the grading
        return Verdict(f"could not compare the value ({type(exc).__name__})")


def timeout_words(what: str, event: dict[str, Any], limits: str) -> str:
    """What ran out of time, and on which clock: the worker says "cpu" (its CPU time limit), "backstop" (timed
    on CPU time but stopped by the wall-clock backstop, :data:`.limits.WALL_FACTOR` times the limit), or
    "wall" (no CPU time counter: the wall clock). ``limits`` is the limit as the student reads it ("10 s")."""
    clock = event.get("clock")
    if clock == "cpu":
        return f"{what} used more than {limits} of CPU time".strip()
    if clock == "backstop":
        seconds = float(limits.split()[0]) * WALL_FACTOR
        return f"{what} ran longer than {seconds:g} s on the wall clock (while waiting, not computing)".strip()
    return f"{what} ran longer than {limits}".strip()


def cell_name(event: dict[str, Any]) -> str:
    """How the student finds a cell: by its first line (JupyterLab numbers no cells), else by its place.

    >>> cell_name({"index": 3, "first": "def f(x):"}), cell_name({"index": 3})
    ('the code cell starting `def f(x):`', 'code cell 4')
    """
    first = _text(event.get("first")).strip()
    return f"the code cell starting {quoted(first, 80)}" if first else f"code cell {_int(event.get('index')) + 1}"


def cell_note(event: dict[str, Any], limits: str) -> str | None:
    """The note for a code cell that raised or ran out of time (None for one that ran), naming it by its first line."""
    status = event.get("status")
    if status == "timeout":
        return f"{cell_name(event)}: " + timeout_words("", event, limits)
    if status == "error":
        return f"{cell_name(event)}: {quoted(_text(event.get('detail')))}{_where(event)}"
    return None


def tampered(child: ChildResult) -> str | None:
    """The note when the notebook's code wrote to the grader's result pipe, None when only the worker did.

    The worker writes whole event lines of its own kinds, one call event per (question, case) and one
    "ready": a line that is not such an event (:attr:`.child.ChildResult.foreign`, a flood's partial
    lines among them) or a second event where there is one is the notebook's doing.
    """
    keys = [(e.get("qid"), e.get("case")) for e in child.events if e.get("kind") == "call"]
    ready = sum(1 for e in child.events if e.get("kind") == "ready")
    extra = child.foreign + len(keys) - len(set(keys)) + max(ready - 1, 0)
    if not extra:
        return None
    return (
        f"the notebook wrote to the grader's results channel ({extra} line{'s' if extra != 1 else ''} the grader"
        " did not send): its results were flooded or forged, so none was graded"
    )


def apply(
    result: NotebookResult,
    exercise: Exercise,
    plan: Plan,
    child: ChildResult,
    *,
    timeout_cell: float,
    stop_note: str,
) -> None:
    """Score ``result`` from the worker's events (``stop_note``: why the notebook was stopped, if it timed out)."""
    limits = f"{timeout_cell:g} s"
    malformed = next((e for e in child.events if e.get("kind") == "malformed"), None)
    if malformed is not None and not any(e.get("kind") in ("cell", "call") for e in child.events):
        result.status = "malformed"
        result.notes.append(malformed_note(malformed))
        return
    cells = [e for e in child.events if e.get("kind") == "cell"]
    for e in cells[:20]:
        note = cell_note(e, limits)
        if note is not None:
            result.notes.append(note)
    bad = [e for e in cells[20:] if cell_note(e, limits) is not None]
    if bad:
        result.notes.append(f"{len(bad)} more code cells failed")
    got: dict[tuple[str, int], dict[str, Any]] = {}
    for e in child.events:
        if e.get("kind") == "call" and isinstance(e.get("qid"), str) and isinstance(e.get("case"), int):
            got.setdefault((e["qid"], e["case"]), e)
    judged: dict[str, list[tuple[str, Verdict]]] = {q.qid: [] for q in exercise.questions}
    budget = time.perf_counter() + JUDGING_SECONDS
    for item in plan:
        q = exercise.question(item.qid)
        kind = "public case" if item.case < len(q.public) else "hidden case"
        if time.perf_counter() > budget:  # a second line behind the answers' bounds (bounds.check_answer)
            verdict = Verdict(f"not judged: judging this notebook's answers took longer than {JUDGING_SECONDS:g} s")
        else:
            event = got.get((q.qid, item.case))
            verdict = call_verdict(q, event, item.expected, item.call_args, limits)
        judged[q.qid].append((f"{kind} {item.case + 1}", verdict))
    outcomes: dict[str, list[tuple[str, str | None]]] = {}
    for qid, pairs in judged.items():
        verdicts = reconcile([v for _, v in pairs])  # a mistake named only if every failing case is that mistake
        outcomes[qid] = [(label, v.reason) for (label, _), v in zip(pairs, verdicts, strict=True)]
        for v in verdicts:
            if v.mistake is not None:
                result.mistakes.setdefault(qid, []).append(v.mistake)
    for q in exercise.questions:
        result.scores[q.qid], result.question_notes[q.qid] = score_question(q.points, outcomes[q.qid])
    forged = tampered(child)
    if forged:
        result.status = "crashed"
        result.notes.append(forged)
        for q in exercise.questions:  # a written event cannot be told from the worker's: none is trusted
            # the reasons stay (what was judged, bounded as ever), the count of passing cases does not
            notes = result.question_notes[q.qid][1:]
            result.scores[q.qid] = 0.0
            result.question_notes[q.qid] = ["not graded: the results channel was written to", *notes]
        result.mistakes.clear()
    elif child.timed_out:
        result.status = "timeout"
        result.notes.append(stop_note)
    elif child.overflow:
        result.status = "crashed"
        result.notes.append("the notebook sent too much output to the grader and was stopped")
    elif not child.done:
        result.status = "crashed"
        code = child.returncode
        result.notes.append(
            "the notebook's process ended early"
            + (f" (exit code {code})" if isinstance(code, int) else "")
            + "; answers that came back before that were graded"
        )
    elif any(e.get("status") in ("error", "timeout") for e in cells):
        result.status = "cell-error"
