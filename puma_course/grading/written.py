"""Written questions: answered in words, formulas and sketches, marked by a person with a rubric.

The course folder's ``bank/written.py`` declares them, keyed by exercise (a separate file, so the
exercise banks ``bank/exNN_*.py`` stay as they are)::

    WRITTEN = {"ex02_dh_frames": (Written(points=4, title=..., prompt=..., criteria=(Criterion(...), ...),
                                          full_answer=..., worked=...),), ...}

A written question's id continues the exercise's numbering: after the auto-graded ``q1`` … ``q3`` the first
written question is ``q4`` (:func:`written_questions`), so adding an auto-graded question renumbers the
written ones rather than clashing with them. ``puma-course release`` puts two Markdown cells into each
exercise notebook, before its closing cell: the prompt (tagged ``written-prompt:qN``, with the points) and
the answer cell (tagged ``written:qN``) where the student writes, LaTeX allowed, a drawing dropped in as an
attachment. The rubric (``criteria``), ``full_answer`` and ``worked`` never leave the course folder: they are
for the marking files of ``puma-course collect-written`` (:mod:`.output.marking`) and the feedback.

Written points are not auto-graded: they stay out of an exercise's ``max_score`` and its auto-graded total,
and reach the grades only through ``puma-course grade --marks FILE`` (:mod:`.output.marks`).
"""

from __future__ import annotations

import base64
import binascii
import importlib
import json
import re
from dataclasses import dataclass, field
from typing import Any

from .bank_loader import BANK_MODULE, EXERCISES
from .output.text import plural
from .spec import Exercise

__all__ = [
    "Criterion",
    "Written",
    "WrittenQuestion",
    "Answer",
    "ANSWER_TAG",
    "PROMPT_TAG",
    "PLACEHOLDER",
    "written_questions",
    "written_exercises",
    "prompt_source",
    "written_summary",
    "read_answers",
    "Release",
    "release_of",
]

ANSWER_TAG, PROMPT_TAG = "written:", "written-prompt:"
PLACEHOLDER = (
    "*Write your answer here, in this cell (Markdown: formulas between `$…$`; a sketch can be a photo or a "
    "drawing dragged into this cell).*"
)
#: Attachments kept per answer, and the largest one (bytes, decoded); a notebook is at most 20 MB anyway.
MAX_ATTACHMENTS, MAX_ATTACHMENT_BYTES = 8, 8_000_000
IMAGE_TYPES = {"image/png": "png", "image/jpeg": "jpg", "image/gif": "gif", "image/webp": "webp"}


@dataclass(frozen=True)
class Criterion:
    """One line of a rubric: a short ``name`` (a column of the marks file), its ``points``, what earns them."""

    name: str
    points: float
    text: str

    def __post_init__(self) -> None:
        if not re.fullmatch(r"[a-z0-9][a-z0-9 _-]{0,40}", self.name):
            raise ValueError(f"name: expected a short lower-case criterion name, got {self.name!r}")
        if not (isinstance(self.points, (int, float)) and 0 < self.points < 1e6):
            raise ValueError(f"points: expected a positive number for criterion {self.name!r}, got {self.points!r}")


@dataclass(frozen=True)
class Written:
    """A written question as the bank declares it (its id comes from :func:`written_questions`)."""

    points: float
    title: str
    prompt: str
    criteria: tuple[Criterion, ...]
    full_answer: str
    worked: str

    def __post_init__(self) -> None:
        total = sum(c.points for c in self.criteria)
        if not self.criteria or abs(total - self.points) > 1e-9:
            raise ValueError(
                f"criteria: expected rubric lines whose points add up to the question's {self.points:g}, "
                f"got {total:g} for {self.title!r}"
            )
        names = [c.name for c in self.criteria]
        if len(set(names)) != len(names):
            raise ValueError(f"criteria: expected distinct names for {self.title!r}, got {names}")


@dataclass(frozen=True)
class WrittenQuestion:
    """A written question of an exercise, with its id (``q4``)."""

    exercise: str
    qid: str
    spec: Written

    @property
    def points(self) -> float:
        """The question's points (the rubric's total)."""
        return self.spec.points

    def criterion(self, name: str) -> Criterion:
        """The rubric line called ``name`` (ValueError naming the lines if there is none)."""
        for c in self.spec.criteria:
            if c.name == name:
                return c
        raise ValueError(f"criterion: expected one of {[c.name for c in self.spec.criteria]}, got {name!r}")


def _declared() -> dict[str, tuple[Written, ...]]:
    """``WRITTEN`` of the loaded bank's ``written.py`` (empty when the course has none)."""
    len(EXERCISES)  # loads the bank of the course found from here, when none is loaded yet
    try:
        module = importlib.import_module(f"{BANK_MODULE}.written")
    except ModuleNotFoundError as exc:
        if exc.name != f"{BANK_MODULE}.written":
            raise
        return {}
    declared: dict[str, tuple[Written, ...]] = dict(getattr(module, "WRITTEN", {}))
    for name, items in declared.items():
        if name not in EXERCISES:
            raise ValueError(f"bank/written.py: expected exercises of the bank {sorted(EXERCISES)}, got {name!r}")
        if not all(isinstance(w, Written) for w in items):
            raise ValueError(f"bank/written.py: expected Written(...) entries for {name}, got {items!r}")
    return declared


def written_questions(exercise: str | Exercise) -> tuple[WrittenQuestion, ...]:
    """The written questions of ``exercise`` (a name or the exercise), numbered after its auto-graded ones.

    >>> (w,) = written_questions("ex02_dh_frames")
    >>> w.points, int(w.qid[1:]) == len(EXERCISES["ex02_dh_frames"].questions) + 1
    (4, True)
    """
    name = exercise if isinstance(exercise, str) else exercise.name
    items = _declared().get(name, ())
    if not items:
        return ()
    taken = [q.qid for q in (EXERCISES[name] if isinstance(exercise, str) else exercise).questions]
    numbers = [int(m[1]) for m in (re.fullmatch(r"q(\d+)", t) for t in taken) if m]
    first = max(numbers, default=0) + 1
    return tuple(WrittenQuestion(name, f"q{first + k}", w) for k, w in enumerate(items))


def written_exercises() -> list[str]:
    """The exercises that have written questions, sorted."""
    return sorted(name for name, items in _declared().items() if items)


def _points(points: float) -> str:
    return plural(points, "point")


def prompt_source(w: WrittenQuestion) -> str:
    """The Markdown of the prompt cell the release puts above the answer cell."""
    return (
        f"**{w.qid}** · written · {_points(w.points)}, marked by your instructor (not by the self-check, and "
        f"not in the auto-graded total) · {w.spec.title}\n\n{w.spec.prompt.strip()}"
    )


def written_summary(exercise: str | Exercise) -> str:
    """What the points summary adds for the exercise's written questions ("" when it has none).

    >>> written_summary("ex02_dh_frames").replace(written_questions("ex02_dh_frames")[0].qid, "qN")
    ' Written, marked by your instructor: qN 4.'
    """
    items = written_questions(exercise)
    if not items:
        return ""
    return " Written, marked by your instructor: " + " · ".join(f"{w.qid} {w.points:g}" for w in items) + "."


@dataclass
class Answer:
    """A student's answer to one written question: the Markdown, the images attached, and what was odd."""

    text: str = ""
    images: list[tuple[str, str, bytes]] = field(default_factory=list)  # (name as attached, extension, bytes)
    notes: list[str] = field(default_factory=list)

    @property
    def empty(self) -> bool:
        """True when nothing was written and nothing attached."""
        return not self.text.strip() and not self.images


def _source(cell: dict[str, Any]) -> str:
    src = cell.get("source", "")
    return "".join(str(s) for s in src) if isinstance(src, list) else str(src)


def _tags(cell: dict[str, Any]) -> list[str]:
    meta = cell.get("metadata")
    tags = meta.get("tags", []) if isinstance(meta, dict) else []
    return [str(t) for t in tags] if isinstance(tags, list) else []


def _images(cell: dict[str, Any], answer: Answer) -> None:
    found = cell.get("attachments")
    if not isinstance(found, dict):
        return
    for name, bundle in list(found.items())[: MAX_ATTACHMENTS + 1]:
        if len(answer.images) >= MAX_ATTACHMENTS:
            answer.notes.append(f"more than {MAX_ATTACHMENTS} attachments: the others are not shown")
            break
        kind = next((m for m in IMAGE_TYPES if isinstance(bundle, dict) and isinstance(bundle.get(m), str)), None)
        if kind is None:
            answer.notes.append(f"attachment {str(name)[:80]!r} is not a PNG, JPEG, GIF or WebP image: not shown")
            continue
        data = bundle[kind]
        if len(data) > MAX_ATTACHMENT_BYTES * 4 // 3 + 8:
            answer.notes.append(f"attachment {str(name)[:80]!r} is larger than {MAX_ATTACHMENT_BYTES} bytes: not shown")
            continue
        try:
            raw = base64.b64decode(data.replace("\n", ""), validate=True)
        except (binascii.Error, ValueError):
            answer.notes.append(f"attachment {str(name)[:80]!r} is not valid base64: not shown")
            continue
        answer.images.append((str(name), IMAGE_TYPES[kind], raw))


@dataclass(frozen=True)
class Release:
    """The cells of an exercise as released: their ids and their texts (to tell the student's own cells)."""

    ids: frozenset[str]
    sources: frozenset[str]

    def holds(self, cell: dict[str, Any]) -> bool:
        """True when ``cell`` is one of the release's (by its id, or by its text when it has one)."""
        ident, source = cell.get("id"), _source(cell).strip()
        return isinstance(ident, str) and ident in self.ids or bool(source) and source in self.sources


def release_of(exercise: str) -> Release | None:
    """The released cells of ``exercise``, read from the loaded course's ``exercises/`` (None when absent)."""
    len(EXERCISES)  # loads the bank of the course found from here, when none is loaded yet
    course = EXERCISES.course
    if course is None:
        return None
    try:
        nb = json.loads((course / "exercises" / f"{exercise}.ipynb").read_text(encoding="utf-8"))
        cells = [c for c in nb["cells"] if isinstance(c, dict)]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    ids = frozenset(str(c["id"]) for c in cells if isinstance(c.get("id"), str))
    return Release(ids, frozenset(t for t in (_source(c).strip() for c in cells) if t))


def _added_below(cells: list[dict[str, Any]], start: int, release: Release) -> list[int]:
    """The cells the student added below the answer cell at ``start``: Markdown (or raw) cells, up to the
    first code cell, cell tagged ``written…`` or cell of the release."""
    out = []
    for i in range(start + 1, len(cells)):
        cell = cells[i]
        written = any(t.startswith((ANSWER_TAG, PROMPT_TAG)) for t in _tags(cell))
        if cell.get("cell_type") not in ("markdown", "raw") or written or release.holds(cell):
            break
        out.append(i)
    return out


_UNSET: Any = object()


def read_answers(data: bytes, exercise: str, release: Release | None = _UNSET) -> dict[str, Answer]:
    """The written answers in a handed-in notebook (its bytes), by question id.

    The answer is the Markdown cell tagged ``written:qN``; when the tag was lost, the cell just below the
    prompt ``written-prompt:qN``. A student who went on writing in new Markdown cells below it is read on:
    the cells they added, up to the first code cell, cell tagged ``written…`` or cell of the ``release``
    (default: :func:`release_of` the exercise; its cells are known by id, or by text), are part of the
    answer, and a note says so. Without the release these cells cannot be told from the exercise's own, and
    a note says how many were left unread. The released placeholder counts as no answer. Nothing is run or
    trusted: the JSON is read as data, and a notebook that is not one gives empty answers with a note.
    """
    if release is _UNSET:
        release = release_of(exercise)
    questions = written_questions(exercise)
    out = {w.qid: Answer() for w in questions}
    try:
        nb = json.loads(data.decode("utf-8"))
        cells = nb.get("cells", []) if isinstance(nb, dict) else []
        cells = [c for c in cells if isinstance(c, dict)] if isinstance(cells, list) else []
    except (UnicodeDecodeError, ValueError, RecursionError):
        for answer in out.values():
            answer.notes.append("the notebook is not valid JSON: no answer could be read")
        return out
    for w in questions:
        answer = out[w.qid]
        tagged = [i for i, c in enumerate(cells) if ANSWER_TAG + w.qid in _tags(c)]
        if not tagged:
            prompt = [i for i, c in enumerate(cells) if PROMPT_TAG + w.qid in _tags(c)]
            tagged = [prompt[0] + 1] if prompt and prompt[0] + 1 < len(cells) else []
            if tagged:
                answer.notes.append("the answer cell lost its tag: the cell below the question was taken")
        if not tagged:
            answer.notes.append(f"no answer cell (tagged {ANSWER_TAG}{w.qid}) in the notebook")
            continue
        if len(tagged) > 1:
            answer.notes.append(f"{len(tagged)} cells tagged {ANSWER_TAG}{w.qid}: all are shown, in order")
        for i in tagged:
            cell = cells[i]
            text = _source(cell).replace(PLACEHOLDER, "").strip()
            if cell.get("cell_type") != "markdown" and text:
                answer.notes.append(f"the answer cell is a {str(cell.get('cell_type'))[:20]} cell, not Markdown")
            answer.text = "\n\n".join(t for t in (answer.text, text) if t)
            _images(cell, answer)
            _read_on(cells, i, release, answer)
    return out


def _read_on(cells: list[dict[str, Any]], start: int, release: Release | None, answer: Answer) -> None:
    """Add to ``answer`` what the student wrote in cells of their own below the answer cell at ``start``."""
    if release is None:
        below = _added_below(cells, start, Release(frozenset(), frozenset()))
        if any(_source(cells[i]).strip() for i in below):
            were, they = ("was", "it") if len(below) == 1 else ("were", "they")
            answer.notes.append(
                f"{plural(len(below), 'Markdown cell')} below the answer cell {were} not read: without the released "
                f"exercise {they} cannot be told from its own cells"
            )
        return
    added = [i for i in _added_below(cells, start, release) if _source(cells[i]).strip() or cells[i].get("attachments")]
    if not added:
        return
    for i in added:
        answer.text = "\n\n".join(t for t in (answer.text, _source(cells[i]).replace(PLACEHOLDER, "").strip()) if t)
        _images(cells[i], answer)
    answer.notes.append(
        f"the answer goes on in {plural(len(added), 'cell')} the student added below the answer cell: shown after "
        "it, in order"
    )
