"""Browser tests: JupyterLab on 127.0.0.1 driven by Playwright in Debian's Chromium (marker ``browser``).

Skipped, with the reason in pytest's summary, where Chromium or Playwright is missing (``.ci/run``
installs both). Screenshots go to ``tests/artifacts/`` (git-ignored): look at them.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from .lab import Lab, browser, missing

ARTIFACTS = Path(__file__).resolve().parents[1] / "artifacts"

WHY = missing()


def pytest_collection_modifyitems(config: Any, items: list[pytest.Item]) -> None:
    """Skip this folder's tests (each module is marked ``browser``) when Chromium or Playwright is missing."""
    here = Path(__file__).parent
    for item in items:
        if WHY and here in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.skip(reason=f"browser tests skipped: {WHY}"))


@pytest.fixture(scope="module")
def lab() -> Iterator[Lab]:
    with Lab() as server:
        yield server


@pytest.fixture(scope="module")
def chromium() -> Iterator[Any]:
    with browser() as b:
        yield b


@pytest.fixture
def page(chromium: Any) -> Iterator[Any]:
    context = chromium.new_context(viewport={"width": 1400, "height": 1000}, device_scale_factor=1)
    pg = context.new_page()
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.errors = errors
    try:
        yield pg
    finally:
        context.close()


@pytest.fixture(scope="session")
def artifacts() -> Path:
    ARTIFACTS.mkdir(exist_ok=True)
    return ARTIFACTS
