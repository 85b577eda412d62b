"""Moved to :mod:`puma_course.grading.judge.judges`; this name stays importable for courses' banks (``bank/``)."""

from typing import Any

from .judge import judges as _moved


def __getattr__(name: str) -> Any:
    return getattr(_moved, name)
