"""Fixtures of the viz tests: every test draws off-screen (Agg, set in tests/conftest.py) and leaves no figure open."""

from __future__ import annotations

from collections.abc import Iterator

import matplotlib as mpl
import matplotlib.pyplot as plt
import pytest


@pytest.fixture(autouse=True)
def _close_figures() -> Iterator[None]:
    """Close every figure a test left open, so figures do not pile up across tests."""
    yield
    plt.close("all")


@pytest.fixture
def course_style() -> Iterator[None]:
    """The lectures' style (110 dpi, 10-11 pt) for a test, restored afterwards for the other tests."""
    from puma_course.viz import use_course_style

    with mpl.rc_context():
        use_course_style()
        yield
