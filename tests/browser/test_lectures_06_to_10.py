"""Lectures 06-10 in JupyterLab: every browser check of a lecture on one page, opened once and run once.

The checks live in ``checks_*.py`` (by subject); here each is given its lectures. pytest runs a lecture's
checks one after another in this order: those of the notebook as opened (saved outputs, untrusted), then
those of the run page that only read it, then those that play the animations, then the keyboard walks
(lecture 08's viewer and matplotlib player, lecture 09's IK selector). ``test_lectures_01_to_05.py`` holds
the other half, so that two pytest workers share the load.
"""

from __future__ import annotations

from typing import Any

import pytest

from .checks_animations import LECTURES as ANIMATED
from .checks_animations import test_animations_play_on_one_click_after_run_all, test_animations_show_a_picture_untrusted
from .checks_axe_lab import (  # noqa: F401 - axe is the fixture
    RUN,
    axe,
    test_live_panels_meet_wcag21_aa_in_jupyterlab,
    test_saved_outputs_meet_wcag21_aa_in_jupyterlab,
)
from .checks_keyboard import (
    test_lecture_08_by_keyboard_alone,
    test_lecture_08_matplotlib_player_by_keyboard_alone,
    test_lecture_09_ik_selector_by_keyboard_alone,
)
from .checks_lectures import test_lecture_as_a_student_gets_it
from .lab import NOTEBOOKS

pytestmark = pytest.mark.browser

LECTURES = sorted(p.name for p in NOTEBOOKS.glob("[0-9][0-9]_*.ipynb") if p.name[:2] >= "06")

#: each check and its lectures, in the order pytest runs them on a lecture's page
CHECKS = {
    test_saved_outputs_meet_wcag21_aa_in_jupyterlab: LECTURES,
    test_animations_show_a_picture_untrusted: list(ANIMATED),
    test_live_panels_meet_wcag21_aa_in_jupyterlab: [n for n in LECTURES if n in RUN],
    test_lecture_as_a_student_gets_it: LECTURES,
    test_animations_play_on_one_click_after_run_all: list(ANIMATED),
    test_lecture_08_by_keyboard_alone: ["08_three_step_wrist_frame.ipynb"],
    test_lecture_08_matplotlib_player_by_keyboard_alone: ["08_three_step_wrist_frame.ipynb"],
    test_lecture_09_ik_selector_by_keyboard_alone: ["09_puma560_inverse_kinematics.ipynb"],
}


def pytest_generate_tests(metafunc: Any) -> None:
    """Each check on its lectures; scope "module" groups a lecture's checks on its one page (conftest's ``tab``)."""
    if "name" in metafunc.fixturenames:
        metafunc.parametrize("name", CHECKS[metafunc.function], scope="module")
