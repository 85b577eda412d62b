"""Lectures 01-05 in JupyterLab: every browser check of a lecture on one page, opened once and run once.

The checks live in ``checks_*.py`` (by subject); here each is given its lectures. pytest runs a lecture's
checks one after another in this order: those of the notebook as opened (saved outputs, untrusted), then
those of the run page that only read it, then those that move sliders or the view (the mouse, then the
keyboard walk). ``test_lectures_06_to_10.py`` holds the other half, so that two pytest workers share the load.
"""

from __future__ import annotations

from typing import Any

import pytest

from .checks_axe_lab import (  # noqa: F401 - axe is the fixture
    RUN,
    axe,
    test_live_panels_meet_wcag21_aa_in_jupyterlab,
    test_saved_outputs_meet_wcag21_aa_in_jupyterlab,
)
from .checks_keyboard import test_lecture_03_by_keyboard_alone
from .checks_lectures import (
    PANELS,
    test_lecture_as_a_student_gets_it,
    test_lecture_panels_in_chromium,
    test_lecture_panels_show_their_picture_before_the_kernel_runs,
)
from .lab import NOTEBOOKS

pytestmark = pytest.mark.browser

LECTURES = sorted(p.name for p in NOTEBOOKS.glob("0[1-5]_*.ipynb"))

#: each check and its lectures, in the order pytest runs them on a lecture's page
CHECKS = {
    test_saved_outputs_meet_wcag21_aa_in_jupyterlab: LECTURES,
    test_lecture_panels_show_their_picture_before_the_kernel_runs: sorted(PANELS),
    test_live_panels_meet_wcag21_aa_in_jupyterlab: [n for n in LECTURES if n in RUN],
    test_lecture_as_a_student_gets_it: LECTURES,
    test_lecture_panels_in_chromium: sorted(PANELS),
    test_lecture_03_by_keyboard_alone: ["03_puma560_forward_kinematics.ipynb"],
}


def pytest_generate_tests(metafunc: Any) -> None:
    """Each check on its lectures; scope "module" groups a lecture's checks on its one page (conftest's ``tab``)."""
    if "name" in metafunc.fixturenames:
        metafunc.parametrize("name", CHECKS[metafunc.function], scope="module")
