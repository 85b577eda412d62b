"""A class graded in two shards and merged gives, file for file, what one run over the class gives.

Seven students of the crafted fixture class (tests/fixtures/submissions: honest, raising, missing a function,
wrong types, memorising, evil values, a huge print) hand in ex01. The class is graded three ways with the same
public key and limits: once whole (``puma-course grade``), and as ``--shard 1/2`` and ``--shard 2/2`` whose
shard files ``puma-course merge`` combines. The merged CSV, class summary, gradebooks and every feedback file
must be byte for byte those of the one run; each shard grades only its own students, and together all of
them; merge refuses a missing part and a key other than the shards'.
"""

from __future__ import annotations

import csv
import json
import shutil
import warnings
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading import SandboxWarning
from puma_course.grading.shards import Shard
from tests.support import ROOT

EX = "ex01_rotations"
STUDENTS = ["good", "raises", "missing_function", "wrong_type", "memorizer", "evil_values", "huge_print"]
COMMON = ["--seed", "11", "--exercise", EX, "--timeout-cell", "5", "--timeout-total", "40", "--quiet"]
BOOKS = ["--gradebook", "wide", "--gradebook", "canvas"]

# the merge is compared with one run under the same kernel; what a kernel could change in the marks is covered
# by the grading tests that stay in CI's second pass
pytestmark = pytest.mark.no_numerics


def _grade(subs: Path, out: Path, *extra: str) -> int:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SandboxWarning)
        return main(["grade", str(subs), "-o", str(out / "grades.csv"), "--feedback", str(out / "fb"), "--course",
                     str(ROOT), *COMMON, *BOOKS, *extra])  # fmt: skip


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("shards")
    subs = base / "hand-in"
    for s in STUDENTS:
        shutil.copytree(ROOT / "tests" / "fixtures" / "submissions" / s, subs / s)
    one, p1, p2, merged = (base / n for n in ("one", "part1", "part2", "merged"))
    codes = [_grade(subs, one), _grade(subs, p1, "--shard", "1/2"), _grade(subs, p2, "--shard", "2/2")]
    shards = [str(p1 / "grades.shard.json"), str(p2 / "grades.shard.json")]
    codes.append(main(["merge", *shards, "-o", str(merged / "grades.csv"), "--feedback", str(merged / "fb"),
                       "--seed", "11", "--course", str(ROOT), *BOOKS]))  # fmt: skip
    return {"base": base, "one": one, "parts": [p1, p2], "merged": merged, "codes": codes, "shards": shards}


def _files(folder: Path) -> dict[str, bytes]:
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not p.name.endswith(".shard.json")
    }


def _students(csv_path: Path) -> list[str]:
    with open(csv_path, newline="", encoding="utf-8") as fh:
        return [row["student"] for row in csv.DictReader(fh)]


def test_each_shard_grades_its_own_students_and_together_all(runs):
    assert runs["codes"][1:3] == [runs["codes"][0]] * 2, runs["codes"]
    parts = [_students(p / "grades.csv") for p in runs["parts"]]
    assert all(parts) and not set(parts[0]) & set(parts[1])
    assert sorted(parts[0] + parts[1]) == sorted(STUDENTS)
    for k, part in enumerate(parts, start=1):
        assert part == sorted(Shard(k, 2).select(STUDENTS))
        assert json.loads(Path(runs["shards"][k - 1]).read_text())["shard"] == f"{k}/2"


def test_the_merge_writes_what_one_run_writes_byte_for_byte(runs):
    assert runs["codes"][3] == 0
    one, merged = _files(runs["one"]), _files(runs["merged"])
    assert sorted(merged) == sorted(one)
    assert {"grades.csv", "grades-summary.md", "fb/good.md"} <= set(one), sorted(one)
    assert any(name.startswith("grades") and "canvas" in name for name in one), sorted(one)
    for name in one:
        assert merged[name] == one[name], name
    scores = {r["student"]: float(r["score"]) for r in csv.DictReader(open(runs["one"] / "grades.csv", newline=""))}
    assert scores["good"] == 13 and scores["raises"] == 7  # the crafted class's known marks (test_fixtures.py)


def test_merge_refuses_a_missing_part_and_another_key(runs, capsys):
    out = runs["base"] / "refused"
    code = main(["merge", runs["shards"][0], "-o", str(out / "g.csv"), "--seed", "11", "--course", str(ROOT)])
    err = capsys.readouterr().err
    assert code == 2 and "missing shards: part(s) 2/2 of 2" in err, err
    code = main(["merge", *runs["shards"], "-o", str(out / "g.csv"), "--seed", "12", "--course", str(ROOT)])
    err = capsys.readouterr().err
    assert code == 2 and "key: expected the key the shards were graded under" in err, err
    assert not out.exists()  # nothing written when refused


def test_a_bad_shard_option_is_refused_by_name(tmp_path, capsys):
    shutil.copytree(ROOT / "tests" / "fixtures" / "submissions" / "good", tmp_path / "good")
    code = main(["grade", str(tmp_path), "-o", str(tmp_path / "g.csv"), "--shard", "3/2", "--seed", "1",
                 "--course", str(ROOT)])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 2 and "shard: expected K/N with 1 <= K <= N, got 3/2" in err, err
    assert not (tmp_path / "g.csv").exists()
