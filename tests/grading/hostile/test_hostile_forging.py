"""Hostile fixtures, forging the output: the feedback and the CSV show a student's text literally, short and inert.

See tests/grading/hostile/harness.py for what every run must satisfy; here, in addition, every feedback file is read
as Markdown would render it (code spans removed) and every CSV cell as a spreadsheet would.
"""

from __future__ import annotations

import csv
import re

import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.output.text import quoted
from tests.grading.hostile.harness import check_run, of, run_attack

pytestmark = pytest.mark.hostile

CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)*?\1")
INERT = ("\x1b", "\u202e", "\u2028", "\u2029", "\x85", "\x00", "\u200b")


def outside_code(text: str) -> str:
    """What of a Markdown text is not inside a code span (where Markdown, links and HTML would act)."""
    return "\n".join(CODE_SPAN.sub("", line) for line in text.splitlines())


@pytest.mark.parametrize(("fx", "mode"), of("forging"))
def test_forged_output_stays_literal(fx, mode, tmp_path, monkeypatch):
    run = run_attack(fx, mode, tmp_path, monkeypatch)
    check_run(run)
    files = write_feedback_names(run)
    for path in files.values():
        text = path.read_text(encoding="utf-8")
        assert len(text) < 60_000, (path, len(text))
        assert not any(ch in text for ch in INERT), path
        plain = outside_code(text)
        lines = plain.splitlines()
        # the structure is the grader's: one title, one total, one heading and one table per exercise
        assert [ln for ln in lines if ln.startswith("# ")] == ["# Feedback for "], (path, lines[:3])
        assert plain.count("Total: **") == 1, path
        headings = [ln for ln in lines if ln.startswith("#")]
        assert len(headings) == 1 + len(fx.exercises), (path, headings)
        rows = [ln for ln in lines if ln.startswith("| q") and not ln.startswith("| question")]
        assert len(rows) in (0, sum(len(EXERCISES[e].questions) for e in fx.exercises)), (path, rows)
        for bad in ("<script", "<img", "](", "56 / 56", "56 of 56", "10 / 10 | passed"):
            assert bad not in plain, (path, bad)
    with open(run.out, newline="", encoding="utf-8") as fh:
        for row in csv.reader(fh):
            for cell in row:
                assert not cell.startswith(("=", "+", "-", "@")), cell
                assert not any(ch in cell for ch in INERT), cell
                assert "\n" not in cell and len(cell) < 2000


def write_feedback_names(run):
    """The feedback file of each attacker (by the title inside it: names may collide as file names)."""
    found = {}
    for path in run.fb.glob("*.md"):
        first = path.read_text(encoding="utf-8").splitlines()[0]
        for name in run.attackers:
            if first == f"# Feedback for {quoted(name, 120)}":
                found[name] = path
    assert set(found) == set(run.attackers), (sorted(found), sorted(run.attackers))
    return found
