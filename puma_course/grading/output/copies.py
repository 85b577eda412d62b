"""The copy report: answers that are near-copies of the package's source, of a lecture cell or of a classmate's.

While grading, :func:`handed` keeps, from each handed-in notebook, the student's own code per question (the
cell tagged ``question:qN`` and the code cells the student added below it, up to the next question; the code
above the first question is the region ``setup``) without the exercise's own cells (:func:`~..written.release_of`),
and what the notebook carries hidden (:mod:`.payloads`). :func:`find_copies` then fingerprints every answer
(:mod:`.fingerprints`: renaming and reformatting are invisible; runs that are also in the released exercise
are left out, so blank notebooks never match) and compares it with

* the package's own source (``puma_course/**/*.py``), the functions of one module together,
* the code cells of the lectures (``notebooks/*.ipynb`` of the course folder), one lecture's together,
* every classmate's answer to the same question,

and with the package, the Python source found inside a notebook's blobs. A match is listed when at least
:data:`MIN_TOKENS` of the student's tokens lie in runs shared with one function, cell or classmate's answer and the
runs shared with its file make at least :data:`LEVEL` of the answer (for a pair of classmates: of either answer);
runs common to more than :data:`IDIOM_FILES` files of the package or of the lectures are left out.
:func:`copies_section` writes the list for the class summary. The report is for the instructor to judge: it never
changes a mark.
"""

from __future__ import annotations

import ast
import importlib.util
import json
import re
from collections import Counter, defaultdict
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from itertools import combinations
from pathlib import Path

from ..bank_loader import EXERCISES
from ..publish.release import HEADING_TAG, QUESTION_TAG
from ..spec import Exercise
from ..written import Release, release_of
from .fingerprints import Print, fingerprint, shared_tokens, similarity, tokens
from .payloads import payloads
from .text import one_line, quoted

__all__ = ["MIN_TOKENS", "LEVEL", "Handed", "Match", "CopyReport", "handed", "find_copies", "copies_section"]

#: A match needs this many of the student's tokens in shared runs (about four lines of code) ...
MIN_TOKENS = 40
#: ... making at least this share of the answer (of either answer, for two classmates).
LEVEL = 0.5
#: A run found in more than half the answers to a question (of ten or more) is how the question is answered.
COMMON_SHARE, COMMON_FROM = 0.5, 10
#: A run found in more files than this (package modules, lectures) is an idiom of the course's code.
IDIOM_FILES = 3
#: At most this many matches are listed per question (the strongest).
SHOWN = 30
PACKAGE = Path(__file__).resolve().parents[2]
SETUP = "setup"
#: At most this many of the Python sources hidden in one notebook are listed.
HIDDEN_SHOWN = 3


@dataclass
class Handed:
    """What the copy report keeps of one handed-in notebook: the student's own code per region, and its payloads."""

    student: str
    exercise: str
    code: dict[str, str] = field(default_factory=dict)
    carried: list[str] = field(default_factory=list)
    hidden_code: list[tuple[str, str]] = field(default_factory=list)


@dataclass(frozen=True)
class Match:
    """An answer (``student``, ``exercise``, ``region``) that is a near-copy of ``other`` (of kind ``source``).

    ``share`` is the part of the student's answer in runs shared with ``other``; ``other_share`` the part of
    the classmate's answer (None for the package and the lectures); ``size`` the student's tokens in them.
    """

    exercise: str
    region: str
    student: str
    source: str  # "package", "lecture", "classmate"
    other: str
    share: float
    size: int
    other_share: float | None = None


@dataclass
class CopyReport:
    """The matches, the payloads (student, exercise, note) and what could not be compared."""

    matches: list[Match] = field(default_factory=list)
    carried: list[tuple[str, str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def pairs(self, source: str = "classmate") -> set[tuple[str, str, str]]:
        """The matches of kind ``source`` as (exercise:region, student, other) (two classmates: sorted)."""
        out = set()
        for m in self.matches:
            if m.source == source:
                a, b = sorted((m.student, m.other)) if source == "classmate" else (m.student, m.other)
                out.add((f"{m.exercise}:{m.region}", a, b))
        return out


def _source(cell: dict[str, object]) -> str:
    src = cell.get("source", "")
    return "".join(str(s) for s in src) if isinstance(src, list) else str(src)


def _tags(cell: dict[str, object]) -> list[str]:
    meta = cell.get("metadata")
    tags = meta.get("tags", []) if isinstance(meta, dict) else []
    return [str(t) for t in tags] if isinstance(tags, list) else []


def _region_starts(cells: list[dict[str, object]], ex: Exercise) -> dict[int, str]:
    """Cell index -> the question whose region starts there (by tag; by ``def function(`` where the tag was lost)."""
    starts: dict[int, str] = {}
    for q in ex.questions:
        tagged = [i for i, c in enumerate(cells) if {QUESTION_TAG + q.qid, HEADING_TAG + q.qid} & set(_tags(c))]
        if not tagged:
            pattern = re.compile(rf"^\s*def\s+{re.escape(q.function)}\s*\(", re.M)
            tagged = [i for i, c in enumerate(cells) if c.get("cell_type") == "code" and pattern.search(_source(c))]
        if tagged:
            starts.setdefault(min(tagged), q.qid)
    return starts


def handed(data: bytes, exercise: Exercise, student: str, release: Release | None = None) -> Handed:
    """What the copy report needs of a handed-in notebook (its bytes); never raises (a bad notebook: nothing)."""
    try:
        return _handed(data, exercise, student, release)
    except Exception as exc:  # noqa: BLE001 - a hostile notebook must not stop grading
        return Handed(student, exercise.name, carried=[f"the notebook could not be read ({type(exc).__name__})"])


def _handed(data: bytes, exercise: Exercise, student: str, release: Release | None) -> Handed:
    out = Handed(student, exercise.name)
    try:
        nb = json.loads(data.decode("utf-8"))
        cells = [c for c in nb.get("cells", []) if isinstance(c, dict)]
    except (UnicodeDecodeError, ValueError, RecursionError, AttributeError, TypeError):
        return out
    given = release if release is not None else _release(exercise.name)
    starts = _region_starts(cells, exercise)
    region = SETUP
    parts: dict[str, list[str]] = defaultdict(list)
    for i, cell in enumerate(cells):
        region = starts.get(i, region)
        if cell.get("cell_type") != "code" or given is not None and _source(cell).strip() in given.sources:
            continue
        parts[region].append(_source(cell))
    out.code = {r: "\n".join(p) for r, p in parts.items() if any(s.strip() for s in p)}
    try:
        out.carried, out.hidden_code = payloads(nb, given.sources if given is not None else frozenset())
    except Exception as exc:  # noqa: BLE001 - a hostile notebook must not stop grading
        out.carried = [f"the notebook could not be scanned ({type(exc).__name__})"]
    return out


@lru_cache(maxsize=32)
def _release(exercise: str) -> Release | None:
    return release_of(exercise)


@lru_cache(maxsize=32)
def _given(exercise: str) -> frozenset[int]:
    """The fingerprints of every cell of the released exercise: what no student wrote."""
    given = _release(exercise)
    out: set[int] = set()
    for text in given.sources if given is not None else ():
        out |= fingerprint(tokens(text)).hashes
    return frozenset(out)


class Library:
    """Reference codes, each labelled ``file: name`` (a function) or ``file: cell i`` (a lecture cell), with an index
    from each fingerprint to the codes holding it. A match is judged against one file at a time: an answer pasting
    several functions of one module, or several cells of one lecture, is measured against all of them. A run found
    in more than :data:`IDIOM_FILES` files is an idiom of the course's code (``np.array([[c, -s, 0], ...``), not a
    sign of copying, and is left out."""

    def __init__(self, units: Iterable[tuple[str, str, str]]):
        self.labels: list[str] = []
        self.files: list[str] = []
        self.hashes: list[set[int]] = []
        index: dict[int, list[int]] = defaultdict(list)
        for file, label, code in units:
            p = fingerprint(tokens(code))
            for h in p.where:
                index[h].append(len(self.labels))
            self.labels.append(label)
            self.files.append(file)
            self.hashes.append(p.hashes)
        self.index = {h: us for h, us in index.items() if len({self.files[u] for u in us}) <= IDIOM_FILES}

    def match(self, p: Print, files: int = 3, top: int = 3) -> tuple[float, int, str, int]:
        """The share of ``p`` in runs shared with the one file that shares most, its size in tokens, that file with
        its ``top`` codes holding most of them (of the ``files`` files holding most fingerprints of ``p``), and the
        tokens shared with the one code of them that shares most."""
        shared = p.hashes & self.index.keys()
        cover = p.coverage
        if not shared or not cover:
            return 0.0, 0, "", 0
        by_file: dict[str, set[int]] = defaultdict(set)
        for h in shared:
            for u in self.index[h]:
                by_file[self.files[u]].add(h)
        candidates = sorted(by_file, key=lambda f: (-len(by_file[f]), f))[:files]
        size, best = max((shared_tokens(p, by_file[f]), f) for f in candidates)
        counts = Counter(u for h in by_file[best] for u in self.index[h] if self.files[u] == best)
        named = sorted(counts, key=lambda u: (-counts[u], self.labels[u]))[:top]
        one = max(shared_tokens(p, by_file[best] & self.hashes[u]) for u in named)
        return size / cover, size, f"{best}: " + ", ".join(self.labels[u] for u in named), one


def _functions(path: Path, rel: str) -> list[tuple[str, str, str]]:
    """Every function and method of a source file, as (``rel``, ``Class.name``, its source)."""
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines(True)
    out: list[tuple[str, str, str]] = []

    def walk(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                name = f"{prefix}{child.name}"
                if not isinstance(child, ast.ClassDef):
                    out.append((rel, name, "".join(lines[child.lineno - 1 : child.end_lineno])))
                walk(child, name + ".")

    walk(ast.parse(text), "")
    return out


def package_library(root: Path = PACKAGE) -> Library:
    """Every function of the package's source (``puma_course/**/*.py``) as a reference (read once per process)."""
    return _package_library(root.resolve())


@lru_cache(maxsize=4)
def _package_library(root: Path) -> Library:
    units = []
    for path in sorted(root.rglob("*.py")):
        units += _functions(path, path.relative_to(root.parent).as_posix())
    return Library(units)


def lecture_library(folder: Path) -> Library:
    """Every code cell of the lectures (``folder/*.ipynb``) as a reference, labelled ``notebooks/NAME.ipynb cell i``
    (read once per process)."""
    return _lecture_library(folder.resolve())


@lru_cache(maxsize=4)
def _lecture_library(folder: Path) -> Library:
    units = []
    for path in sorted(folder.glob("*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8")).get("cells", [])
        name = f"{folder.name}/{path.name}"
        units += [(name, f"cell {i}", _source(c)) for i, c in enumerate(cells) if c["cell_type"] == "code"]
    return Library(units)


def find_copies(
    answers: Iterable[Handed], course: Path | None = None, package: Path = PACKAGE, lectures: bool = True
) -> CopyReport:
    """Compare every answer with the package, the lectures (``course/notebooks``; default: the loaded course's)
    and the classmates' answers to the same question; returns the :class:`CopyReport` (one that says why,
    if the comparison failed: grading goes on, and no mark depends on it)."""
    try:
        return _find(list(answers), course, package, lectures)
    except Exception as exc:  # noqa: BLE001 - the report must never stop grading
        return CopyReport(notes=[f"no copy report: {type(exc).__name__}: {str(exc)[:200]}"])


def _find(answers: list[Handed], course: Path | None, package: Path, lectures: bool) -> CopyReport:
    report = CopyReport()
    if importlib.util.find_spec("copydetect") is None:  # the winnowing, from the grader extra
        report.notes.append("no copy report: copydetect is missing (pip install 'puma-course[grader]')")
        return report
    course = EXERCISES.course if course is None else course
    lib_package = package_library(package)
    lib_lectures = lecture_library(course / "notebooks") if lectures and course is not None else None
    if lectures and lib_lectures is None:
        report.notes.append("the lectures were not compared: no course folder")
    groups: dict[tuple[str, str], list[tuple[str, Print]]] = defaultdict(list)
    for a in sorted(answers, key=lambda h: (h.exercise, h.student)):
        report.carried += [(a.student, a.exercise, note) for note in a.carried]
        ignore = _given(a.exercise)
        for region, code in sorted(a.code.items()):
            p = fingerprint(tokens(code), ignore)
            groups[a.exercise, region].append((a.student, p))
            for kind, lib in (("package", lib_package), ("lecture", lib_lectures)):
                if lib is not None:
                    _against(report, lib, kind, a, region, p)
        hidden = sorted(a.hidden_code, key=lambda wc: -len(wc[1]))  # the Python found in its blobs: the 3 largest
        found = 0
        for where, code in hidden:
            found += _against(report, lib_package, "package", a, f"hidden in {where}", fingerprint(tokens(code)))
            if found == HIDDEN_SHOWN:
                break
    for (exercise, region), prints in groups.items():
        report.matches += _classmates(exercise, region, prints)
    return report


def _against(report: CopyReport, lib: Library, kind: str, a: Handed, region: str, p: Print) -> bool:
    share, size, label, one = lib.match(p)
    if one >= MIN_TOKENS and share >= LEVEL:
        report.matches.append(Match(a.exercise, region, a.student, kind, label, share, size))
        return True
    return False


def _classmates(exercise: str, region: str, prints: Sequence[tuple[str, Print]]) -> list[Match]:
    """The pairs of near-copies among the answers to one question.

    Answers with the same fingerprints (the same code once renamed and reformatted) are compared once, as one
    form; the forms sharing at least two fingerprints are then measured pair by pair."""
    index: dict[tuple[tuple[int, tuple[int, ...]], ...], int] = {}
    forms: list[Print] = []
    members: list[list[str]] = []
    for student, p in prints:
        key = tuple(sorted((h, tuple(w)) for h, w in p.where.items()))
        if key not in index:
            index[key] = len(forms)
            forms.append(p)
            members.append([])
        members[index[key]].append(student)
    students: Counter[int] = Counter()
    for i, p in enumerate(forms):
        for h in p.where:
            students[h] += len(members[i])
    n = len(prints)
    dropped = {h for h, c in students.items() if n >= COMMON_FROM and c > COMMON_SHARE * n}
    kept = [_without(p, dropped) for p in forms]
    holders: dict[int, list[int]] = defaultdict(list)
    for i, p in enumerate(kept):
        for h in p.where:
            holders[h].append(i)
    pair_counts: Counter[tuple[int, int]] = Counter()
    for holding in holders.values():
        for x, i in enumerate(holding):
            for j in holding[x + 1 :]:
                pair_counts[i, j] += 1
    out: list[Match] = []
    for i, same in enumerate(members):
        share, size = similarity(kept[i], kept[i])
        if len(same) > 1 and size >= MIN_TOKENS and share >= LEVEL:
            pairs = combinations(sorted(same), 2)
            out += [Match(exercise, region, a, "classmate", b, share, size, share) for a, b in pairs]
    for (i, j), count in pair_counts.items():
        if count < 2:
            continue
        share_i, size_i = similarity(kept[i], kept[j])
        share_j, size_j = similarity(kept[j], kept[i])
        if max(size_i, size_j) < MIN_TOKENS or max(share_i, share_j) < LEVEL:
            continue
        for a in members[i]:
            for b in members[j]:
                if a <= b:
                    out.append(Match(exercise, region, a, "classmate", b, share_i, size_i, share_j))
                else:
                    out.append(Match(exercise, region, b, "classmate", a, share_j, size_j, share_i))
    return out


def _without(p: Print, dropped: set[int]) -> Print:
    return p if not dropped else Print(p.length, {h: w for h, w in p.where.items() if h not in dropped})


_KIND_WORDS = {"package": "the package's source", "lecture": "a lecture cell", "classmate": "a classmate's answer"}


def _cell(text: object, limit: int = 160) -> str:
    """Text a student controls (names, a zip's member names) as a code span a Markdown table cell keeps whole."""
    return quoted(text, limit).replace("|", "\\|")


def copies_section(report: CopyReport | None) -> list[str]:
    """The class summary's section on copies (Markdown lines; none without a report)."""
    if report is None:
        return []
    lines = [f"## Possible copies ({len(report.matches)}) and hidden code ({len(report.carried)}): marks unchanged", ""]
    lines += [
        f"Answers of which at least {LEVEL:.0%} (and {MIN_TOKENS} tokens or more) lie in runs of code shared with the "
        "package's source, a lecture or a classmate's answer to the same question, once names, numbers, strings, "
        "comments and layout are set aside and the exercise's own cells left out (MOSS-style winnowing). The share is "
        "of the student's answer (for two classmates, of each one's). Similar is not copied: read both, then decide.",
        "",
    ]
    lines += [f"- {one_line(n, 300)}" for n in report.notes]
    by_question: dict[tuple[str, str], list[Match]] = defaultdict(list)
    for m in report.matches:
        by_question[m.exercise, m.region].append(m)
    if by_question:
        lines += ["| exercise | question | student | a near-copy of | which | share | tokens |", "| --- " * 7 + "|"]
    for (exercise, region), found in sorted(by_question.items()):
        found.sort(key=lambda m: (-max(m.share, m.other_share or 0.0), m.student, m.other))
        for m in found[:SHOWN]:
            share = f"{m.share:.2f}" + (f" / {m.other_share:.2f}" if m.other_share is not None else "")
            who, what, other = _cell(m.student), _KIND_WORDS[m.source], _cell(m.other, 240)
            lines.append(f"| {exercise} | {_cell(region)} | {who} | {what} | {other} | {share} | {m.size} |")
        if len(found) > SHOWN:
            lines.append(f"| {exercise} | {_cell(region)} | {len(found) - SHOWN} more, weaker | | | | |")
    if report.carried:
        lines += ["", "Hidden code: large encoded data, or calls that decode or run code (read, never run):", ""]
        lines += [f"- {_cell(s)} {e}: {_cell(note, 300)}" for s, e, note in sorted(report.carried)]
    lines.append("")
    return lines
