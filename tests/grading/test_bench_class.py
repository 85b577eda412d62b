"""benchmarks/bench_class.py runs: a class of 2 students x 2 exercises, graded in 2 parts, then resumed; and the
blank ex10/ex01 comparison on one notebook each. Only that it runs and what it counts are checked, never a time."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tests.support import ROOT

pytestmark = pytest.mark.no_numerics

SCRIPT = ROOT / "benchmarks" / "bench_class.py"
NAMES = ["ex01_rotations", "ex02_dh_frames"]


def _run(*args: str) -> str:
    done = subprocess.run([sys.executable, str(SCRIPT), *args], cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_bench_class_grades_a_small_class_in_parts_and_resumes(tmp_path):
    work, out = tmp_path / "work", tmp_path / "figures.json"
    args = ["--students", "2", "--small", "1", "--parts", "2", "--kernel-sample", "0", "--workdir", str(work)]
    args += ["--exercises", *NAMES, "--json", str(out)]
    first = _run(*args)
    figures = json.loads(out.read_text(encoding="utf-8"))
    # notebook i of student k: honest, wrong, blank by (k + i) % 3, i the exercise's place among all ten
    assert figures["counts"] == {"honest": 1, "wrong": 2, "blank": 1}
    whole, small = figures["whole"], figures["small"]
    assert whole["notebooks"] == 4 and small["notebooks"] == 2
    assert whole["plan_calls"] == 4 and small["plan_calls"] == 2  # every notebook planned once, in the grader
    assert sum(whole["statuses"].values()) == 4
    assert whole["cpu_grader"] > 0 and whole["cpu_children"] > 0 and whole["grader_rss_mib"] > 0
    assert any("class of 1,000 x 2 on 50 shard(s)" in line for line in figures["table"])
    assert "read back" not in first
    again = _run(*args)  # every part measured already: read back, nothing graded again
    assert again.count("read back from") == 3  # the small class (one part) and both parts of the class
    assert json.loads(out.read_text(encoding="utf-8"))["whole"] == whole


def test_bench_class_compares_blank_ex10_with_blank_ex01(tmp_path):
    out = tmp_path / "figures.json"
    printed = _run("--compare-blank", "1", "--rounds", "1", "--json", str(out))
    got = json.loads(out.read_text(encoding="utf-8"))["compare_blank"]
    assert got["count"] == 1 and set(got["best"]) == {"ex01_rotations", "ex10_trajectories"}
    assert got["ratio"] == pytest.approx(got["best"]["ex10_trajectories"] / got["best"]["ex01_rotations"])
    assert got["cpu_ratio"] == pytest.approx(got["cpu"]["ex10_trajectories"] / got["cpu"]["ex01_rotations"])
    assert "ex10/ex01 =" in printed
