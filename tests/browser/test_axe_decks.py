"""axe-core's WCAG 2.1 A/AA rules over every slide deck and every instructor key (issue 34).

The test and its fixtures are test_axe.py's (see there); the kinds are split across two files so that two
pytest workers (``--dist loadfile``) share the work: the site there, the slides and the keys here.
"""

from __future__ import annotations

import pytest

from tests.browser.test_axe import axe, built, check_every_page, served  # noqa: F401 - the fixtures

pytestmark = pytest.mark.browser


@pytest.mark.parametrize("kind", ["slides", "keys"])
def test_every_page_meets_wcag21_aa_under_axe(kind, axe, built, served, chromium, artifacts, tmp_path_factory):  # noqa: F811
    check_every_page(kind, axe, built, served, chromium, artifacts, tmp_path_factory)
