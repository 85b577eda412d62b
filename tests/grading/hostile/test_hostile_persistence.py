"""Hostile fixtures, persistence: nothing a notebook leaves behind outlives it or changes a later grade.

The honest classmate is graded after the attacker (students run in name order), so a planted module,
cache file, daemon or exit hook would show in its marks; see tests/grading/hostile/harness.py.
"""

from __future__ import annotations

import pytest

from tests.grading.hostile.harness import check_run, of, run_attack

pytestmark = pytest.mark.hostile


@pytest.mark.parametrize(("fx", "mode"), of("persistence"))
def test_persistence_attack_leaves_nothing(fx, mode, tmp_path, monkeypatch):
    run = run_attack(fx, mode, tmp_path, monkeypatch)
    check_run(run)
    # the grades file is the grader's, written last
    assert "1000" not in run.out.read_text(encoding="utf-8")
