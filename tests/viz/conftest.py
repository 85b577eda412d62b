"""Fixtures of the viz tests: every test draws off-screen (Agg, set in tests/conftest.py) and leaves no figure open."""

from __future__ import annotations

from collections.abc import Iterator

import matplotlib.pyplot as plt
import pytest


@pytest.fixture(autouse=True)
def _close_figures() -> Iterator[None]:
    """Close every figure a test left open, so figures do not pile up across tests."""
    yield
    plt.close("all")
