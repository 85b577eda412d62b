"""``puma-course merge``: the shards of a class (``grade --shard K/N``) written as one run over the class would be.

:func:`merge_shards` reads the shard files (:func:`.shards.read_shards`, which refuses parts that do not make
one class), checks that the key given is the one they were graded under, and hands every result, and every
notebook's code for the copy report, to the one writer (:func:`.output.writer.write_run`): the grades CSV, the
feedback, the class summary and the gradebooks come out as one run over the whole class writes them, with the
written marks merged first.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

from .intake.collect import Collected, collect
from .output.copies import Handed, find_copies
from .output.gradebook import read_roster
from .output.marks import read_marks
from .output.writer import RunFacts, Written, write_run
from .results import NotebookResult
from .run.sandbox import Sandbox
from .secret import Secret
from .shards import ShardError, read_shards

__all__ = ["merge_shards"]

PathLike = str | os.PathLike[str]


def _handed(raw: dict[str, object]) -> Handed:
    hidden = raw.get("hidden_code", [])
    return Handed(
        str(raw["student"]),
        str(raw["exercise"]),
        dict(raw.get("code", {})),  # type: ignore[call-overload]
        list(raw.get("carried", [])),  # type: ignore[call-overload]
        [(str(w), str(c)) for w, c in hidden],  # type: ignore[attr-defined]
    )


def merge_shards(
    shards: Sequence[PathLike],
    output: PathLike,
    key: Secret,
    *,
    feedback: PathLike | None = None,
    marks: Sequence[PathLike] = (),
    gradebooks: Sequence[str] = (),
    roster: PathLike | None = None,
    submissions: PathLike | None = None,
) -> tuple[list[NotebookResult], Written]:
    """Write the CSV ``output`` (and the feedback, summary and ``gradebooks``) of the class the ``shards`` graded.

    ``key`` must be the key they were graded under (its fingerprint is checked); shards graded from a platform's
    download (``--layout canvas|moodle``) need that download (``submissions``), read again for its names and
    late hand-ins. Raises :class:`~.shards.ShardError` (a ValueError) naming what does not fit, before writing.
    """
    files, results = read_shards(shards)
    first = files[0]
    if key.fingerprint != first.key:
        raise ShardError(
            f"key: expected the key the shards were graded under (fingerprint {first.key}), got one with fingerprint "
            f"{key.fingerprint}: give merge the same --secret FILE (or --seed N) as grade"
        )
    layout = str(first.facts.get("layout", "folders"))
    names = list(first.exercises)
    collected: Collected | None = None
    if layout != "folders":
        if submissions is None:
            raise ShardError(
                f"submissions: the shards were graded from a {layout} download; give merge the same download "
                "(--submissions DIR) for its names and late hand-ins"
            )
        collected = collect(Path(submissions), layout, names)
    students = sorted(s for f in files for s in f.students)
    checked = read_marks(marks, students, names) if marks else None
    people = read_roster(roster) if roster is not None else None
    box = Sandbox(str(first.facts.get("sandbox", "none")), reason=str(first.facts.get("sandbox_reason", "")))
    handed = [_handed(h) for f in files for h in f.handed]
    facts = RunFacts(tuple(names), key, box, str(first.facts.get("limits", "")), collected, find_copies(handed))
    written = write_run(
        results, Path(output), facts, feedback=feedback, marks=checked, gradebooks=gradebooks, roster=people
    )
    return results, written
