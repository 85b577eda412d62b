"""The hub tests (marker ``hub``): skipped, with the reason in pytest's summary, only where no hub can start.

A hub needs Linux, root (it makes system users and spawns their servers as them), configurable-http-proxy
(``.ci/run`` installs it from npm), git and a Python every user may run; the browser part needs Chromium
and Playwright as tests/browser does.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from ..browser.lab import missing as browser_missing
from .hubctl import why_not

WHY = why_not() or browser_missing()


def pytest_collection_modifyitems(config: Any, items: list[pytest.Item]) -> None:
    here = Path(__file__).parent
    for item in items:
        if WHY and here in Path(str(item.fspath)).parents:
            item.add_marker(pytest.mark.skip(reason=f"!!! hub tests SKIPPED: {WHY} !!!"))
