"""Hostile fixtures against the limits (issue 21): per notebook, not per process; the grader's own work bounded.

Each runs beside an honest and a blank classmate (tests/grading/hostile/harness.py); those needing control groups are
skipped, saying so, where the machine does not allow them (CI runs as root on a hybrid cgroup machine, where
they run). In addition to what every run must satisfy:

* forked_memory: no group's peak memory passed its limit, and the kernel stopped a process of that notebook;
* setsid_busy_children: the slowish classmate graded beside it kept every point (check_run) and the attacker's
  group used at most one CPU;
* forged_results: the attacker's notebook took no longer than its limit (the judging is bounded) and its forged
  cases failed as too large;
* duplicate_solutions: q2 failed ("each solution once"), the rest of the solution kept its points.
"""

from __future__ import annotations

import pytest

from puma_course.grading.run.limits import CPUS
from tests.grading.hostile.harness import LIMITS, check_run, of, run_attack

pytestmark = pytest.mark.hostile


@pytest.mark.parametrize(("fx", "mode"), of("limits"))
def test_limits_hold_per_notebook(fx, mode, tmp_path, monkeypatch):
    run = run_attack(fx, mode, tmp_path, monkeypatch)
    check_run(run)
    limit = int(float(fx.head.get("memory_mb", 4096))) << 20
    assert run.usages, "no control group was used"
    assert all(u.peak_memory <= limit + (1 << 20) for u in run.usages), [u.peak_memory for u in run.usages]
    attacker = run.of("attacker")
    if fx.name == "forked_memory":
        assert max(u.oom_kills for u in run.usages) >= 1, run.usages
    if fx.name == "setsid_busy_children":
        busy = max(run.usages, key=lambda u: u.cpu_seconds)
        wall = {**LIMITS, **fx.limits}["timeout_total"] + 3
        assert busy.cpu_seconds <= CPUS * wall, busy
    if fx.name == "forged_results":
        r = attacker[0]
        assert r.seconds < {**LIMITS, **fx.limits}["timeout_total"], r.seconds
        notes = " ".join(n for q in ("q1", "q2") for n in r.question_notes[q])
        assert "more numbers than the answer can have" in notes, r.question_notes
    if fx.name == "duplicate_solutions":
        assert any("list each solution once" in n for n in attacker[0].question_notes["q2"]), attacker[0].question_notes
