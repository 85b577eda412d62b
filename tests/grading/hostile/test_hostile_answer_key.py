"""Hostile fixtures, answer-key access: nothing of the package beyond what the exercise allows is within reach.

Each fixture (tests/fixtures/hostile/answer_key/) is graded beside an honest and a blank classmate; see
tests/grading/hostile/harness.py for what every run must satisfy.
"""

from __future__ import annotations

import pytest

from tests.grading.hostile.harness import check_run, of, run_attack

pytestmark = pytest.mark.hostile


@pytest.mark.parametrize(("fx", "mode"), of("answer-key"))
def test_answer_key_attack_gains_nothing(fx, mode, tmp_path, monkeypatch):
    run = run_attack(fx, mode, tmp_path, monkeypatch)
    check_run(run)
    notes = " ".join(n for r in run.of("attacker") for n in r.notes)
    if "from puma_course" in "".join(fx.cells):
        # a refused import says why, in the student's words
        assert "not available in this exercise" in notes or run.of("attacker")[0].status != "cell-error", notes
