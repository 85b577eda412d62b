"""puma_course.grading.runner: the plan stays in the grader, hidden inputs are seeded, the child is this package."""

from __future__ import annotations

import json
import subprocess
import sys

import nbformat

from puma_course.grading import EXERCISES, grade_notebook, runner
from puma_course.grading.runner import PACKAGE_PARENT, make_plan


def test_hidden_inputs_depend_on_the_seed_and_are_reproducible():
    ex = EXERCISES["ex01_rotations"]
    a, b, c = make_plan(ex, 1), make_plan(ex, 1), make_plan(ex, 2)
    assert [x["args"] for x in a] == [x["args"] for x in b]
    assert [x["args"] for x in a] != [x["args"] for x in c]


def test_the_child_never_receives_expected_values(monkeypatch, tmp_path):
    seen = {}

    def fake_run_child(cells, calls, workdir, timeout_cell, timeout_total, forbidden=None):
        seen["calls"] = calls
        return [], False, 0, False

    monkeypatch.setattr(runner, "_run_child", fake_run_child)
    sub = tmp_path / "ex01_rotations.ipynb"
    nbformat.write(nbformat.v4.new_notebook(), sub)
    result = grade_notebook(sub, EXERCISES["ex01_rotations"], "s", seed=1)
    assert result.status == "crashed" and result.score == 0
    assert seen["calls"] and all(set(c) == {"qid", "case", "function", "args"} for c in seen["calls"])


def test_the_child_runs_the_worker_of_this_package(tmp_path):
    # python -I ignores PYTHONPATH and the current folder: the bootstrap itself puts the folder
    # holding puma_course first on sys.path, so the child imports this very package
    init = str(PACKAGE_PARENT / "puma_course" / "__init__.py")
    job = {
        "cells": ["import puma_course", "def same_file(path):\n    return [float(puma_course.__file__ == path)]"],
        "calls": [{"qid": "q1", "case": 0, "function": "same_file", "args": [init]}],
        "timeout_cell": 10,
    }
    out = subprocess.run(
        [sys.executable, "-I", "-c", runner.CHILD_BOOTSTRAP],
        input=json.dumps(job),
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=60,
    )
    events = [json.loads(line) for line in out.stdout.splitlines()]
    assert [e["kind"] for e in events] == ["cell", "cell", "call", "done"], events
    assert events[2]["value"] == [1.0]
    assert "puma_course.grading.worker" in runner.CHILD_BOOTSTRAP


def test_the_tamper_check_covers_every_module_of_the_package():
    digest = runner._package_digest()
    modules = {"__init__.py", "grading/runner.py", "grading/worker.py", "grading/bank/_reference/__init__.py"}
    assert modules <= set(digest)
    assert all(not key.startswith("/") for key in digest)
