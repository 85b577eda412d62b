"""Hostile fixtures, crashing the run: odd files and names, broken or enormous notebooks, dying or flooding workers.

Whatever the submission, the run ends with a CSV and feedback for everyone; see tests/grading/hostile/harness.py.
"""

from __future__ import annotations

import resource
from pathlib import Path

import pytest

from tests.grading.hostile.harness import check_run, of, run_attack

pytestmark = pytest.mark.hostile

#: The attacker's status for the fixtures where it is decided by the file alone.
STATUS = {
    "symlink_to_solution": "refused",
    "symlink_to_classmate_folder": "refused",
    "symlink_to_etc_passwd": "refused",
    "fifo_notebook": "refused",
    "folder_notebook": "refused",
    "oversize_notebook": "malformed",
    "deep_json": "malformed",
    "close_result_pipe": "crashed",
    # crashed either way: the grader stops reading past its caps, or, when the worker's CPU-clock tick cuts the
    # fixture's writes short (os.write returns a partial count on a signal), the lines the worker never sends
    # mark the results as flooded (events.tampered)
    "flood_result_pipe": "crashed",
    "segfault": "crashed",
}


@pytest.mark.parametrize(("fx", "mode"), of("crash"))
def test_crash_attack_leaves_the_run_complete(fx, mode, tmp_path, monkeypatch):
    rss_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    run = run_attack(fx, mode, tmp_path, monkeypatch)
    check_run(run)
    for name in run.attackers:
        for r in run.of(name):
            if fx.name in STATUS:
                assert r.status == STATUS[fx.name], (name, r.status, r.notes)
            if fx.name == "bad_bytes_and_shapes" and name != "attacker4":
                assert r.status == "malformed", (name, r.status, r.notes)
    if fx.name == "symlink_to_etc_passwd":
        first = Path("/etc/passwd").read_text(encoding="utf-8", errors="replace").splitlines()[0]
        for path in [run.out, *run.fb.glob("*.md")]:
            assert first[:8] not in path.read_text(encoding="utf-8"), path
    if fx.name in ("huge_notebook", "million_outputs", "oversize_notebook", "deep_json"):
        # the grader parsed nothing: its own memory did not grow by the notebook's parse (kB on Linux)
        grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - rss_before
        assert grown < 400_000, grown
