"""Grading a class on several machines: a stable split by student, and the shard files that merge back.

Each student's hidden cases depend only on the key, the student and the exercise (:mod:`.secret`), so a class
graded in N parts under one key gives, part by part, exactly what one run over the whole class gives. This module
decides which part grades which student (:class:`Shard`), writes what a part graded to a shard file
(:func:`write_shard`: the results, with the key's fingerprint, the course version and the split, never the key),
and reads a set of shard files back as one class (:func:`read_shards`), refusing, by name, shards graded under
different keys or course versions, split differently, overlapping, or missing.

The split hashes the student's name (SHA-256), not its place in a sorted list: a student handed in late, or a
folder that gained a student, moves no one else to another shard.

>>> s = Shard.parse("2/3")
>>> (s.index, s.count, str(s))
(2, 3, '2/3')
>>> sorted(n for n in ("ann", "bob", "cy", "dee", "eve") if Shard.parse("1/2").owns(n))
['ann', 'bob', 'cy']
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .results import NotebookResult

__all__ = [
    "FORMAT",
    "Shard",
    "ShardFile",
    "ShardError",
    "shard_path",
    "run_facts",
    "write_shard",
    "read_shard",
    "read_shards",
]

#: The shard file's format name and version (the file's ``format`` field).
FORMAT = "puma-course-shard/1"


class ShardError(ValueError):
    """Shard files that do not make one class (the message names the files and what differs)."""


@dataclass(frozen=True)
class Shard:
    """Part ``index`` of ``count`` (1-based): the students whose name hashes to it."""

    index: int
    count: int

    def __post_init__(self) -> None:
        if not (isinstance(self.count, int) and isinstance(self.index, int)) or isinstance(self.count, bool):
            raise ValueError(f"shard: expected whole numbers K/N, got {self.index!r}/{self.count!r}")
        if self.count < 1 or not 1 <= self.index <= self.count:
            raise ValueError(f"shard: expected K/N with 1 <= K <= N, got {self.index}/{self.count}")

    @classmethod
    def parse(cls, text: str) -> Shard:
        """``"K/N"`` (as ``--shard`` takes it) as a :class:`Shard`; ValueError naming what came otherwise."""
        parts = str(text).strip().split("/")
        if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
            raise ValueError(f"shard: expected K/N (e.g. 2/8: the second of eight parts), got {text!r}")
        return cls(int(parts[0]), int(parts[1]))

    def owns(self, student: str) -> bool:
        """Whether this part grades ``student`` (the same answer on any machine, for any class it is in)."""
        digest = hashlib.sha256(student.encode("utf-8", "surrogatepass")).digest()
        return int.from_bytes(digest[:8], "big") % self.count == self.index - 1

    def select(self, students: Iterable[str]) -> list[str]:
        """The students of ``students`` this part grades, in their order."""
        return [s for s in students if self.owns(s)]

    def __str__(self) -> str:
        return f"{self.index}/{self.count}"


@dataclass(frozen=True)
class ShardFile:
    """What one part of a class graded: who, under which key and course version, and the results."""

    shard: Shard
    key: str  # the key's fingerprint, never the key
    course_version: str
    exercises: tuple[str, ...]
    students: tuple[str, ...]
    results: tuple[NotebookResult, ...]
    #: what the run's files report besides the results: the public seed (or None), the sandbox's kind and reason,
    #: the limits' label and the hand-in layout (``merge`` refuses parts that differ in any of them)
    facts: dict[str, Any] = dataclasses.field(default_factory=dict)
    #: each notebook's own code, for the copy report over the whole class (:class:`.output.copies.Handed` fields)
    handed: tuple[dict[str, Any], ...] = ()
    path: Path | None = None

    def to_json(self) -> dict[str, Any]:
        return {
            "format": FORMAT,
            "shard": str(self.shard),
            "key": self.key,
            "course_version": self.course_version,
            "exercises": list(self.exercises),
            "students": list(self.students),
            "results": [dataclasses.asdict(r) for r in self.results],
            "facts": self.facts,
            "handed": list(self.handed),
        }


def _result(raw: Any, where: str) -> NotebookResult:
    names = {f.name for f in dataclasses.fields(NotebookResult)}
    if not isinstance(raw, dict) or not {"student", "exercise", "status", "max_score"} <= set(raw) <= names:
        raise ShardError(f"{where}: expected a result with the fields {sorted(names)}, got {str(raw)[:200]}")
    for key in ("scores",):
        values = raw.get(key, {})
        if not isinstance(values, dict) or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values.values()
        ):
            raise ShardError(f"{where}: expected finite numbers in {key}, got {values!r}")
    return NotebookResult(**raw)


def shard_path(output: str | os.PathLike[str]) -> Path:
    """Where ``grade --shard K/N -o FILE`` writes its shard file by default: ``<FILE's stem>.shard.json`` beside it.

    >>> shard_path("out/part-2.csv").as_posix()
    'out/part-2.shard.json'
    """
    out = Path(output)
    return out.with_name(f"{out.stem}.shard.json")


def run_facts(key: Any, box: Any, limits: str, layout: str) -> dict[str, Any]:
    """What a part's files report besides its results (the key's public seed, the sandbox, the limits, the
    layout), as the shard file keeps them: parts that differ in any of them do not merge."""
    return {"seed": key.seed, "sandbox": box.kind, "sandbox_reason": box.reason, "limits": limits, "layout": layout}


def write_shard(path: str | os.PathLike[str], shard_file: ShardFile) -> Path:
    """Write ``shard_file`` as JSON at ``path`` (atomically: a temporary file renamed over it)."""
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(f".{out.name}.tmp")
    tmp.write_text(json.dumps(shard_file.to_json(), indent=1, allow_nan=False) + "\n", encoding="utf-8")
    os.replace(tmp, out)
    return out


def read_shard(path: str | os.PathLike[str]) -> ShardFile:
    """One shard file; :class:`ShardError` naming the file when it is not one."""
    p = Path(path)
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ShardError(f"{p}: expected a shard file written by `puma-course grade --shard K/N`, got {exc}") from exc
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        got = data.get("format") if isinstance(data, dict) else type(data).__name__
        raise ShardError(f"{p}: expected a shard file of format {FORMAT!r}, got {got!r}")
    try:
        shard = Shard.parse(data["shard"])
        key, version = str(data["key"]), str(data["course_version"])
        exercises, students = tuple(map(str, data["exercises"])), tuple(map(str, data["students"]))
        raw, facts, handed = data["results"], data.get("facts", {}), data.get("handed", [])
    except (KeyError, TypeError, ValueError) as exc:
        raise ShardError(f"{p}: a shard file with a missing or bad field: {exc}") from exc
    if not isinstance(raw, list):
        raise ShardError(f"{p}: expected a list of results, got {type(raw).__name__}")
    if not isinstance(facts, dict) or not isinstance(handed, list) or not all(isinstance(h, dict) for h in handed):
        raise ShardError(f"{p}: expected facts as a mapping and handed as a list of mappings")
    results = tuple(_result(r, f"{p}, result {i + 1}") for i, r in enumerate(raw))
    strays = sorted({r.student for r in results} - set(students))
    if strays:
        raise ShardError(f"{p}: results for students the shard does not list: {', '.join(strays)}")
    return ShardFile(shard, key, version, exercises, students, results, facts, tuple(handed), p)


def _one(files: Sequence[ShardFile], what: str, value: Any) -> None:
    seen: dict[Any, list[str]] = {}
    for f in files:
        seen.setdefault(value(f), []).append(str(f.path))
    if len(seen) > 1:
        told = "; ".join(f"{v!r}: {', '.join(paths)}" for v, paths in seen.items())
        raise ShardError(f"shards graded under different {what}: {told}")


def read_shards(paths: Sequence[str | os.PathLike[str]]) -> tuple[list[ShardFile], list[NotebookResult]]:
    """The shard files at ``paths`` as one class: the files, and every result sorted by (student, exercise).

    Refuses (:class:`ShardError`, naming the files) shards graded under different keys, course versions,
    exercises or splits (N), a part given twice or missing, and a student graded in two parts.
    """
    if not paths:
        raise ShardError("merge: expected the shard files of a class (one per part), got none")
    files = [read_shard(p) for p in paths]
    _one(files, "keys (fingerprints)", lambda f: f.key)
    _one(files, "course versions", lambda f: f.course_version)
    _one(files, "splits (N in --shard K/N)", lambda f: f.shard.count)
    _one(files, "exercise lists", lambda f: f.exercises)
    for fact in ("seed", "sandbox", "sandbox_reason", "limits", "layout"):
        _one(files, f"settings ({fact})", lambda f, fact=fact: f.facts.get(fact))
    count = files[0].shard.count
    by_index: dict[int, list[str]] = {}
    for f in files:
        by_index.setdefault(f.shard.index, []).append(str(f.path))
    twice = {k: v for k, v in by_index.items() if len(v) > 1}
    if twice:
        told = "; ".join(f"part {k}/{count}: {', '.join(v)}" for k, v in sorted(twice.items()))
        raise ShardError(f"overlapping shards, the same part given more than once: {told}")
    missing = [f"{k}/{count}" for k in range(1, count + 1) if k not in by_index]
    if missing:
        raise ShardError(f"missing shards: part(s) {', '.join(missing)} of {count} not given")
    owner: dict[str, str] = {}
    for f in files:
        for s in f.students:
            if s in owner:
                raise ShardError(f"student {s!r} graded in two shards: {owner[s]} and {f.path}")
            owner[s] = str(f.path)
    for f in files:
        for s in f.students:
            if not f.shard.owns(s):
                raise ShardError(f"{f.path}: student {s!r} does not belong to part {f.shard} (the split is by name)")
    results = sorted((r for f in files for r in f.results), key=lambda r: (r.student, r.exercise))
    return files, results
