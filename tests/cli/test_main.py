"""The ``puma-course`` command as a whole: its parser, its one dispatch, the course it works on, an install."""

from __future__ import annotations

import argparse
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from puma_course import cli
from puma_course.cli import COMMANDS, build_parser, main
from tests.cli.support import clean_env, edit_a_cell, lab_argv
from tests.support import ROOT


def test_other_commands_refuse_unknown_options(capsys):
    with pytest.raises(SystemExit) as info:
        main(["release", "--check", "--port", "8898"])
    assert info.value.code == 2
    assert "unrecognized arguments: --port 8898" in capsys.readouterr().err


def _actions(parser: argparse.ArgumentParser, prefix: str = "puma-course"):
    for action in parser._actions:
        yield prefix, action
        if isinstance(action, argparse._SubParsersAction):
            for choice in action._choices_actions:  # the sub-command list of `puma-course -h`
                yield prefix, choice
            for name, sub in action.choices.items():
                yield from _actions(sub, f"{prefix} {name}")


def test_every_option_of_every_subcommand_has_help():
    seen, missing = set(), []
    for where, action in _actions(build_parser()):
        if isinstance(action, argparse._HelpAction):
            continue
        name = "/".join(action.option_strings) or action.dest or action.metavar
        seen.add(f"{where} {name}")
        if not (action.help or "").strip():
            missing.append(f"{where} {name}")
    assert not missing, f"options without help: {missing}"
    for expected in ("puma-course lab --course", "puma-course grade --course", "puma-course check notebook"):
        assert expected in seen  # the walk reached the sub-commands


def _commands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


def test_every_command_is_dispatched_by_the_one_table(monkeypatch, capsys):
    """Each command the parser knows is run by its entry of COMMANDS, and by nothing else."""
    parser = build_parser()
    assert list(_commands(parser)) == list(COMMANDS)  # the same commands, in the same order
    assert list(COMMANDS)[:2] == ["lab", "check"]  # a student's commands first, the instructor's after
    for name, sub in _commands(parser).items():
        assert sub.get_default("run") is None, name  # no second way in (a set_defaults(run=...))
    minimal = {
        "lab": ["lab"],
        "check": ["check", "nb.ipynb"],
        "release": ["release"],
        "grade": ["grade", "subs", "-o", "g.csv"],
        "merge": ["merge", "part-1.shard.json", "-o", "g.csv"],
        "collect-written": ["collect-written", "subs", "-o", "out"],
        "limits": ["limits", "show"],
        "gradescope": ["gradescope", "ex01_rotations", "-o", "a.zip"],
        "site": ["site"],
        "edition": ["edition", "out"],
        "slides": ["slides"],
        "keys": ["keys"],
    }
    assert sorted(minimal) == sorted(COMMANDS)
    ran: list[tuple[str, str]] = []
    for name in COMMANDS:
        monkeypatch.setitem(COMMANDS, name, lambda args, name=name: ran.append((name, args.command)) or 40 + len(ran))
    monkeypatch.setattr(cli, "require_extra", lambda command: None)  # the extras are not what is tested here
    for i, (name, argv) in enumerate(minimal.items()):
        assert main(argv) == 41 + i, name  # the table's function's own exit code
    assert ran == [(name, name) for name in minimal]


def test_commands_work_on_the_course_they_are_run_in(course_copy, capsys, monkeypatch):
    stale = course_copy / "exercises" / "ex01_rotations.ipynb"
    edit_a_cell(stale)
    monkeypatch.chdir(course_copy / "notebooks")  # anywhere inside the course
    assert main(["release", "--check"]) == 1, "release --check must inspect this course, not the installed one"
    assert "ex01_rotations" in capsys.readouterr().err
    assert f"--ServerApp.root_dir={course_copy}" in lab_argv(capsys)
    assert main(["release"]) == 0
    assert str(course_copy / "exercises") in capsys.readouterr().out
    assert stale.read_bytes() == (ROOT / "exercises" / "ex01_rotations.ipynb").read_bytes()
    assert main(["release", "--check"]) == 0


def test_course_option_names_the_course_from_anywhere(course_copy, outside, capsys, monkeypatch):
    monkeypatch.chdir(outside)
    assert main(["release", "--check", "--course", str(course_copy)]) == 0
    assert str(course_copy / "exercises") in capsys.readouterr().out
    assert f"--ServerApp.root_dir={course_copy}" in lab_argv(capsys, "--course", str(course_copy))


@pytest.mark.parametrize(
    "argv",
    [["lab", "--print-command"], ["release", "--check"], ["grade", "subs", "-o", "g.csv"]],
    ids=["lab", "release", "grade"],
)
def test_outside_a_course_a_command_says_where_it_looked_and_exits_2(outside, capsys, monkeypatch, argv):
    monkeypatch.chdir(outside)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "no course found" in err and "solutions/" in err and "notebooks/" in err
    assert repr(str(outside)) in err and repr(str(outside.parent)) in err and "--course DIR" in err
    assert not (outside / "g.csv").exists()


def test_a_named_folder_that_is_not_a_course_exits_2(outside, capsys):
    assert main(["release", "--check", "--course", str(outside)]) == 2
    err = capsys.readouterr().err
    assert "course: expected a course folder" in err and repr(str(outside)) in err


def test_unknown_subcommand_exits_with_usage():
    with pytest.raises(SystemExit):
        main(["frobnicate"])


# --------------------------------------------------------------------------- real installs and servers


@pytest.mark.slow
@pytest.mark.skipif(
    os.name != "posix", reason="not run: the install test calls the venv's bin/ programs, a POSIX layout"
)
def test_a_non_editable_install_works_on_an_instructors_course(tmp_path, course_copy):
    src = tmp_path / "src"  # a copy, so building leaves no build/ or egg-info in the checkout
    shutil.copytree(ROOT / "puma_course", src / "puma_course", ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    # The new environment sees this one's packages (numpy, nbformat, pip) after its own, as
    # --system-site-packages would for a venv made from a system Python, so --no-deps is enough;
    # this environment's editable hook is not loaded (a .pth line adds a folder, not its .pth files).
    # pip builds the wheel in its usual isolated build environment, as an instructor's install does.
    site = subprocess.run(
        [python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    outer = sorted({sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]})
    Path(site, "outer_environment.pth").write_text("\n".join(outer) + "\n", encoding="utf-8")
    env = clean_env()
    pip = subprocess.run(
        [python, "-m", "pip", "install", "--quiet", "--no-deps", str(src)],
        capture_output=True,
        text=True,
        env=env,
    )
    assert pip.returncode == 0, pip.stdout + pip.stderr

    def run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [str(venv / "bin" / "puma-course"), *args], capture_output=True, text=True, cwd=cwd, env=env
        )

    where = subprocess.run(
        [python, "-c", "import puma_course; print(puma_course.__file__)"],
        capture_output=True,
        text=True,
        cwd=course_copy,
        env=env,
        check=True,
    ).stdout.strip()
    assert Path(where).resolve().is_relative_to(Path(site).resolve()), f"not the installed copy: {where}"

    done = run("release", "--check", cwd=course_copy / "notebooks")
    assert done.returncode == 0, done.stdout + done.stderr
    assert f"up to date ({course_copy / 'exercises'})" in done.stdout
    edit_a_cell(course_copy / "exercises" / "ex01_rotations.ipynb")
    done = run("release", "--check", cwd=course_copy)
    assert done.returncode == 1 and "ex01_rotations" in done.stderr
    done = run("lab", "--print-command", "--port", "8898", cwd=course_copy)
    assert done.returncode == 0, done.stderr
    argv = shlex.split(done.stdout)
    assert argv[0] == str(python) and f"--ServerApp.root_dir={course_copy}" in argv and argv[-2:] == ["--port", "8898"]
    done = run("release", "--check", cwd=tmp_path)
    assert done.returncode == 2 and "no course found" in done.stderr and repr(str(tmp_path.resolve())) in done.stderr


def test_a_command_whose_extra_is_missing_says_which_to_install(monkeypatch, capsys):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "jupyterlab" else real(name, *a))
    assert main(["lab", "--print-command", "--course", str(ROOT)]) == 2
    err = capsys.readouterr().err
    assert "jupyterlab" in err and "'lab' extra" in err and "pip install '.[lab]'" in err
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "nbformat" else real(name, *a))
    assert main(["release", "--check", "--course", str(ROOT)]) == 2
    assert "'grader' extra" in capsys.readouterr().err
