"""A student's and an instructor's first steps with ``puma-course`` (issue 31): the help, a closed pipe."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys

import pytest

from puma_course.cli import build_parser, main
from puma_course.cli.help import BROKEN_PIPE, STUDENT_COMMANDS
from tests.support import ROOT


def _commands() -> list[str]:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if a.dest == "command"]
    return list(sub.choices)


def test_help_lists_a_students_commands_first_then_the_instructors(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: puma-course [-h] COMMAND ...")
    students, instructors = out.index("Commands for students:"), out.index("Commands for instructors:")
    assert students < instructors < out.index("options:")
    listed = {m[1]: m.start() for m in re.finditer(r"^  ([a-z][a-z-]+)  ", out, re.MULTILINE)}
    assert sorted(listed) == sorted(_commands())  # every command, once, each under one heading
    for name, at in listed.items():
        assert (students < at < instructors) == (name in STUDENT_COMMANDS), name
    assert set(STUDENT_COMMANDS) == {"lab", "check"}
    assert "open JupyterLab on the course" in out  # with each command's own help


def test_a_command_line_with_no_command_still_names_what_is_missing(capsys):
    with pytest.raises(SystemExit) as info:
        main([])
    assert info.value.code == 2 and "required: COMMAND" in capsys.readouterr().err


def test_no_command_lists_the_commands_and_each_command_names_itself_in_its_usage(capsys):
    with pytest.raises(SystemExit):
        main([])
    assert "Commands for students:" in capsys.readouterr().err
    for name in ("check", "grade", "collect-written"):
        with pytest.raises(SystemExit) as info:
            main([name, "--help"])
        assert info.value.code == 0
        assert capsys.readouterr().out.startswith(f"usage: puma-course {name} [-h]")
    with pytest.raises(SystemExit):
        main(["check"])
    assert "puma-course check: error:" in capsys.readouterr().err


def _closed_pipe(*args: str, cwd=ROOT) -> subprocess.CompletedProcess[str]:
    """Run ``puma-course ARGS`` with its output read by nobody (as ``| head`` leaves it once it has its lines)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    proc = subprocess.Popen(
        [sys.executable, "-m", "puma_course.cli", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        env=env,
    )
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # the reader is gone before the first line is written
    err = proc.stderr.read()
    return subprocess.CompletedProcess(proc.args, proc.wait(), "", err)


@pytest.mark.parametrize(
    "args",
    [
        ("check", "exercises/ex01_rotations.ipynb"),
        ("release", "--check"),
        ("limits", "show"),
        ("--help",),
        ("check", "--help"),
    ],
)
def test_output_into_a_closed_pipe_ends_quietly(args):
    done = _closed_pipe(*args)
    assert "Traceback" not in done.stderr and "BrokenPipeError" not in done.stderr, done.stderr
    assert done.returncode in (0, BROKEN_PIPE), done.stderr  # argparse's help swallows the error itself: 0
    if args[0] == "check" and len(args) == 2 and args[1] != "--help":
        assert done.returncode == BROKEN_PIPE


def test_grade_into_a_closed_pipe_grades_the_class_all_the_same(tmp_path):
    (tmp_path / "subs" / "ann").mkdir(parents=True)
    shutil.copy(ROOT / "exercises" / "ex01_rotations.ipynb", tmp_path / "subs" / "ann")
    out = tmp_path / "grades.csv"
    done = _closed_pipe("grade", str(tmp_path / "subs"), "-o", str(out), "--seed", "1", "--sandbox", "none")
    assert "Traceback" not in done.stderr and "BrokenPipeError" not in done.stderr, done.stderr
    assert done.returncode in (0, BROKEN_PIPE), done.stderr
    assert "ann" in out.read_text(encoding="utf-8")  # graded and written: the progress lines went nowhere
