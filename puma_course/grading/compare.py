"""Moved to :mod:`puma_course.grading.judge.compare`; this name stays importable for courses' banks (``bank/``)."""

from typing import Any

from .judge import compare as _moved


def __getattr__(name: str) -> Any:
    return getattr(_moved, name)
