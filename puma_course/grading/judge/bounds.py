"""The grader's own work, bounded: a worker's answer is measured before anything is built from it.

Everything a worker sends comes through a pipe the student's code can write to directly, past the
worker's own 10,000-number cap. Before an answer reaches a judge (where it becomes numpy arrays and,
for sets of solutions, pairwise distances), :func:`check_answer` walks it once, in pure Python and in
time linear in its size, and refuses it, in words for the student, when it is not a rectangular
array of numbers or holds more numbers than the question's expected value allows
(:func:`number_bound`). A refused answer fails its case in well under a millisecond per kilobyte,
and no judge ever sees more than :data:`MAX_NUMBERS` numbers.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["MAX_NUMBERS", "MAX_DEPTH", "number_bound", "shape_of", "check_answer"]

#: The most numbers any answer may hold (the worker's own cap on what a function returns).
MAX_NUMBERS = 10_000
#: The most nested levels an answer may have (the deepest expected value is a (n, 4, 4) path: 3).
MAX_DEPTH = 4


def number_bound(expected: Any) -> int:
    """How many numbers a right answer to a call whose reference gave ``expected`` can hold, with slack.

    An array reference allows twice its size (a transposed or flattened answer is still worded by
    the comparison); a judge's reference (a dict) allows the size of its largest array of numbers
    (the reference solutions, the path's poses, the hidden joint values) twice over, and at least 64.

    >>> number_bound(np.zeros((4, 4))), number_bound({"solutions": np.zeros((8, 6)), "fk": len})
    (64, 96)
    """
    if isinstance(expected, dict):
        biggest = max((_size(v) for v in expected.values()), default=0)
    else:
        try:
            biggest = int(np.size(expected))
        except Exception:  # noqa: BLE001 - an odd reference: the worker's cap is the bound
            return MAX_NUMBERS
    return int(min(MAX_NUMBERS, max(64, 2 * biggest)))


def _size(value: Any) -> int:
    """The number of numbers in an array-like entry of a judge's reference (0 for anything else)."""
    if isinstance(value, np.ndarray):
        return int(value.size)
    if isinstance(value, (list, tuple)):
        try:
            return int(np.asarray(value, dtype=float).size)
        except (TypeError, ValueError):
            return sum(_size(v) for v in value)
    return 1 if isinstance(value, (int, float)) and not isinstance(value, bool) else 0


def shape_of(value: Any, limit: int) -> tuple[int, ...] | str:
    """The shape of ``value`` as a nested list of numbers, or why it is not one (more than ``limit`` numbers,
    ragged, too deep, not numbers). Never builds an array; stops as soon as ``limit`` is passed.

    >>> shape_of([[1, 2], [3, 4.5]], 100), shape_of([[1, 2], [3]], 100), shape_of([1] * 101, 100)
    ((2, 2), 'a ragged list (rows of different lengths)', 'more than 100 numbers')
    """
    if isinstance(value, bool) or value is None:
        return "not numbers"
    if isinstance(value, (int, float)):
        return ()
    if not isinstance(value, list):
        return "not numbers"
    shape: list[int] = []
    level: list[Any] = [value]
    while level and isinstance(level[0], list):
        if len(shape) >= MAX_DEPTH:
            return f"nested more than {MAX_DEPTH} levels deep"
        width = len(level[0])
        if any(not isinstance(item, list) or len(item) != width for item in level):
            return "a ragged list (rows of different lengths)"
        shape.append(width)
        if len(level) * width > limit:
            return f"more than {limit} numbers"
        level = [x for item in level for x in item]
    for x in level:
        if isinstance(x, bool) or not isinstance(x, (int, float)):
            return "a ragged list (rows of different lengths)" if isinstance(x, list) else "not numbers"
    return tuple(shape)


def check_answer(value: Any, expected: Any) -> str | None:
    """None when ``value`` (a JSON value from the worker) may be judged against ``expected``; else why not.

    >>> check_answer([[0.0] * 6] * 8, {"solutions": np.zeros((8, 6))}) is None
    True
    >>> check_answer([[0.0] * 6] * 4000, {"solutions": np.zeros((8, 6))})
    'returned more numbers than the answer can have (more than 96 numbers): not judged'
    """
    found = shape_of(value, number_bound(expected))
    if isinstance(found, tuple):
        return None
    if found.startswith("more than"):
        return f"returned more numbers than the answer can have ({found}): not judged"
    if found.startswith("not numbers"):
        return None  # the judge words it (a string, a dict, ...): nothing costly is built from it
    return f"returned {found}, which is not an array of numbers"
