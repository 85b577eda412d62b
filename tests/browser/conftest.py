"""Browser tests: JupyterLab on 127.0.0.1 driven by Playwright in Debian's Chromium (marker ``browser``).

Skipped, with the reason in pytest's summary, where Chromium or Playwright is missing (``.ci/run``
installs both). Screenshots go to ``tests/artifacts/`` (git-ignored): look at them.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from .lab import Lab, Tab, browser, missing, new_page

ARTIFACTS = Path(__file__).resolve().parents[1] / "artifacts"

WHY = missing()


@pytest.hookimpl(trylast=True)  # after pytest's own reordering by fixture parameter, which interleaves them
def pytest_collection_modifyitems(config: Any, items: list[pytest.Item]) -> None:
    """Skip this folder's tests (each module is marked ``browser``) when Chromium or Playwright is missing.

    In a module with ``CHECKS`` (``test_lectures_*``), run a lecture's checks together, in CHECKS's order, the
    lectures in name order: one page per lecture (the ``tab`` fixture), the read-only checks before the others.
    """
    here = Path(__file__).parent
    for item in items:
        if WHY and here in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.skip(reason=f"browser tests skipped: {WHY}"))
    # the hook sees the whole session's items: doctests and nbval's cells have no ``module``
    checked = [hasattr(getattr(item, "module", None), "CHECKS") and hasattr(item, "callspec") for item in items]
    slots = [i for i, yes in enumerate(checked) if yes]

    def key(item: Any) -> tuple[str, str, int]:
        order = list(item.module.CHECKS)
        return str(item.fspath), item.callspec.params["name"], order.index(item.function)

    for i, item in zip(slots, sorted((items[i] for i in slots), key=key), strict=True):
        items[i] = item


# Package scope, not session: Playwright's sync API keeps an asyncio loop running in the worker while it is open,
# and the worker goes on to other folders' tests (nbclient's asyncio.run, the hub test's own Playwright), which
# fail inside a running loop. Leaving this folder closes Chromium and JupyterLab; coming back starts them again.
@pytest.fixture(scope="package")
def lab() -> Iterator[Lab]:
    """One JupyterLab server per pytest worker while it runs this folder's tests, shared by all of them."""
    with Lab() as server:
        yield server


@pytest.fixture(scope="package")
def chromium() -> Iterator[Any]:
    with browser() as b:
        yield b


@pytest.fixture
def page(chromium: Any) -> Iterator[Any]:
    pg = new_page(chromium)
    try:
        yield pg
    finally:
        pg.context.close()


#: the lectures walked by keyboard alone (tests/browser/checks_keyboard.py): their one run is Shift+Enter on every cell
BY_KEYBOARD = {"03_puma560_forward_kinematics.ipynb", "08_three_step_wrist_frame.ipynb"}


@pytest.fixture(scope="module")
def tab(name: str, lab: Lab, chromium: Any) -> Iterator[Tab]:
    """Lecture ``name`` opened once and run once for every check of a ``test_lectures_*`` module (``lab.Tab``).

    ``name`` is parametrized with scope "module" by those modules, so pytest runs a lecture's checks one after
    another, in the order they are defined, and closes the page (and shuts its kernel down) before the next lecture.
    """
    t = Tab(chromium, lab, name, by_keyboard=name in BY_KEYBOARD)
    try:
        yield t
    finally:
        t.close()


@pytest.fixture(scope="session")
def artifacts() -> Path:
    ARTIFACTS.mkdir(exist_ok=True)
    return ARTIFACTS
