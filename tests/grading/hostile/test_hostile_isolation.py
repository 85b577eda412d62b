"""Hostile fixtures, isolation: a notebook reaches neither the grader, nor its classmates, nor the network.

Every fixture here needs the operating-system sandbox (without it, the grader runs student code as its own
user and says so); see tests/grading/hostile/harness.py for what every run must satisfy.
"""

from __future__ import annotations

import pytest

from tests.grading.hostile.harness import check_run, of, run_attack

pytestmark = pytest.mark.hostile


@pytest.mark.parametrize(("fx", "mode"), of("isolation"))
def test_isolation_attack_gains_nothing(fx, mode, tmp_path, monkeypatch):
    run = run_attack(fx, mode, tmp_path, monkeypatch)
    check_run(run)
    assert [r.student for r in run.results].count("honest") == len(fx.exercises)
