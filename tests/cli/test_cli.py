"""The puma-course command line, on the course it is run in (one test starts a real JupyterLab)."""

from __future__ import annotations

import argparse
import csv
import http.client
import json
import os
import re
import secrets
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import sysconfig
import time
from pathlib import Path

import pytest

from puma_course.cli import build_parser, main
from puma_course.course import INDEX, is_course
from tests.support import ROOT


@pytest.fixture
def course_copy(tmp_path):
    """An instructor's own small course: one solution, its exercise, a lecture folder and the index."""
    root = tmp_path / "my-course"
    for sub in ("solutions", "exercises"):
        (root / sub).mkdir(parents=True)
        shutil.copy(ROOT / sub / "ex01_rotations.ipynb", root / sub)
    (root / "notebooks").mkdir()
    shutil.copy(ROOT / INDEX, root)
    shutil.copytree(ROOT / "bank", root / "bank", ignore=shutil.ignore_patterns("__pycache__"))  # its questions
    return root.resolve()


@pytest.fixture
def outside(tmp_path):
    """A folder with no course at or above it."""
    here = (tmp_path / "elsewhere").resolve()
    here.mkdir()
    if any(is_course(f) for f in (here, *here.parents)):
        pytest.skip(f"not run: the test needs a folder outside any course, and a folder above {here} is a course")
    return here


def _lab_argv(capsys, *args: str) -> list[str]:
    assert main(["lab", "--print-command", *args]) == 0
    return shlex.split(capsys.readouterr().out)


def test_lab_prints_the_command_without_running_it(capsys, monkeypatch):
    # It serves the course root (notebooks/ only, before: exercises/ were out of reach) and opens the index.
    monkeypatch.chdir(ROOT)
    assert main(["lab", "--no-browser", "--print-command"]) == 0
    out = capsys.readouterr().out.strip()
    assert out.startswith(sys.executable) or out.startswith("'" + sys.executable)
    assert "-m jupyterlab" in out and out.endswith("--no-browser")
    argv = shlex.split(out)
    assert argv[:3] == [sys.executable, "-m", "jupyterlab"]
    assert f"--ServerApp.root_dir={ROOT}" in argv
    assert f"--LabApp.default_url=/lab/tree/{INDEX}" in argv


def test_lab_passes_every_other_option_to_jupyterlab_after_its_own(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    mine = ["--port", "8898", "--allow-root", "--ServerApp.token=abc", "-y", "--LabApp.default_url=/lab", "--pr"]
    argv = _lab_argv(capsys, *mine)
    assert argv[-len(mine) :] == mine  # in order, last: JupyterLab lets a later option win
    assert "--print-command" not in argv and "--no-browser" not in argv


def test_lab_opens_the_folder_of_a_course_without_an_index(course_copy, capsys, monkeypatch):
    (course_copy / INDEX).unlink()
    monkeypatch.chdir(course_copy)
    argv = _lab_argv(capsys)
    assert f"--ServerApp.root_dir={course_copy}" in argv
    assert not any(a.startswith("--LabApp.default_url") for a in argv)


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


def _edit_a_cell(path) -> None:
    """Change one cell's source (what release --check compares; the file's layout it ignores)."""
    import nbformat

    nb = nbformat.read(path, as_version=4)
    nb.cells[-1].source += "\n# edited by hand"
    nbformat.write(nb, path)


def test_commands_work_on_the_course_they_are_run_in(course_copy, capsys, monkeypatch):
    stale = course_copy / "exercises" / "ex01_rotations.ipynb"
    _edit_a_cell(stale)
    monkeypatch.chdir(course_copy / "notebooks")  # anywhere inside the course
    assert main(["release", "--check"]) == 1, "release --check must inspect this course, not the installed one"
    assert "ex01_rotations" in capsys.readouterr().err
    assert f"--ServerApp.root_dir={course_copy}" in _lab_argv(capsys)
    assert main(["release"]) == 0
    assert str(course_copy / "exercises") in capsys.readouterr().out
    assert stale.read_bytes() == (ROOT / "exercises" / "ex01_rotations.ipynb").read_bytes()
    assert main(["release", "--check"]) == 0


def test_course_option_names_the_course_from_anywhere(course_copy, outside, capsys, monkeypatch):
    monkeypatch.chdir(outside)
    assert main(["release", "--check", "--course", str(course_copy)]) == 0
    assert str(course_copy / "exercises") in capsys.readouterr().out
    assert f"--ServerApp.root_dir={course_copy}" in _lab_argv(capsys, "--course", str(course_copy))


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


def test_release_in_a_course_without_solutions_exits_2(tmp_path, capsys, monkeypatch):
    (tmp_path / "lectures-only" / "notebooks").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "lectures-only")
    assert main(["release", "--check"]) == 2
    err = capsys.readouterr().err
    assert "solutions: expected a folder" in err and "does not exist" in err


def test_check_finds_an_exercise_of_the_course_by_name(course_copy, capsys, monkeypatch):
    # the course's own ex01 is a full answer, so 15 / 15 shows it was checked, not the repository's
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", course_copy / "exercises")
    monkeypatch.chdir(course_copy / "notebooks")
    for name in ("ex01_rotations", "ex01_rotations.ipynb"):
        assert main(["check", name]) == 0
        assert "15 / 15 on the public cases" in capsys.readouterr().out
    assert main(["check", "ex99_nothing"]) == 2
    err = capsys.readouterr().err
    assert "notebook: expected" in err and str(course_copy / "exercises" / "ex99_nothing.ipynb") in err


def test_check_of_a_missing_file_outside_a_course_exits_2(outside, capsys, monkeypatch):
    monkeypatch.chdir(outside)
    assert main(["check", "ex01_rotations"]) == 2
    err = capsys.readouterr().err
    assert "no such file here, and no course" in err and repr(str(outside)) in err
    assert main(["check", str(outside / "sub" / "ex01_rotations.ipynb")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_grade_grades_the_exercises_the_course_hands_out(course_copy, capsys, monkeypatch):
    (course_copy / "exercises" / "ex99_mine.ipynb").write_text("{}", encoding="utf-8")
    (course_copy / "subs" / "ann").mkdir(parents=True)
    (course_copy / "subs" / "ben").mkdir(parents=True)
    (course_copy / "subs" / "ben" / "ex01_rotations.ipynb").write_text("{}", encoding="utf-8")
    monkeypatch.chdir(course_copy)
    # ann's folder is empty: graded (the CSV says missing); ben handed ex01 in, so only ex01 is graded
    assert main(["grade", "subs", "-o", "g.csv", "--quiet", "--seed", "1"]) == 0
    with open(course_copy / "g.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [(r["student"], r["exercise"], r["status"]) for r in rows] == [
        ("ann", "ex01_rotations", "missing"),
        ("ben", "ex01_rotations", "malformed"),
    ]
    err = capsys.readouterr().err
    assert "not graded" in err and "ex99_mine" in err


def test_grade_of_a_class_that_handed_in_no_exercise_exits_2(course_copy, capsys, monkeypatch):
    (course_copy / "subs" / "ann").mkdir(parents=True)
    (course_copy / "subs" / "ann" / "ex1.ipynb").write_text("{}", encoding="utf-8")
    monkeypatch.chdir(course_copy)
    assert main(["grade", "subs", "-o", "g.csv", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "named after the course's exercises" in err and "ex01_rotations" in err
    assert not (course_copy / "g.csv").exists()


def test_release_check_passes_on_the_committed_exercises(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    assert main(["release", "--check"]) == 0
    assert "up to date" in capsys.readouterr().out


def test_release_writes_and_check_detects_a_stale_exercise(tmp_path, capsys):
    sol, ex = tmp_path / "solutions", tmp_path / "exercises"
    sol.mkdir()
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", sol)
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex)]) == 0
    assert (ex / "ex01_rotations.ipynb").read_bytes() == (ROOT / "exercises" / "ex01_rotations.ipynb").read_bytes()
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    with open(ex / "ex01_rotations.ipynb", "a", encoding="utf-8") as fh:
        fh.write(" ")
    # the file's layout is not what the check compares (JupyterLab rewrites it on every save) ...
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    # ... a cell's source is
    path = ex / "ex01_rotations.ipynb"
    path.write_text(path.read_text(encoding="utf-8").replace("(axis, angle):", "(axis, angle=0):", 1), encoding="utf-8")
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert "ex01_rotations" in capsys.readouterr().err


def test_grade_writes_csv_and_feedback(tmp_path, capsys):
    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    (subs / "ben").mkdir()
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "ann")
    out, fb = tmp_path / "grades.csv", tmp_path / "fb"
    code = main(
        [
            "grade",
            str(subs),
            "-o",
            str(out),
            "--feedback",
            str(fb),
            "--jobs",
            "2",
            "--timeout-cell",
            "10",
            "--timeout-total",
            "30",
            "--seed",
            "5",
            "--exercise",
            "ex01_rotations",
            "--quiet",
        ]
    )
    assert code == 0
    with open(out, newline="", encoding="utf-8") as fh:
        rows = {r["student"]: r for r in csv.DictReader(fh)}
    assert rows["ann"]["score"] == "15" and rows["ann"]["status"] == "ok"
    assert rows["ben"]["score"] == "0" and rows["ben"]["status"] == "missing"
    assert (fb / "ann.md").exists() and (fb / "ben.md").exists()
    assert "graded 2 notebook(s)" in capsys.readouterr().out


def test_grade_rejects_a_missing_folder(tmp_path, capsys):
    assert main(["grade", str(tmp_path / "nope"), "-o", str(tmp_path / "g.csv")]) == 2
    assert "submissions" in capsys.readouterr().err


def test_check_grades_a_notebook_on_public_cases(capsys):
    assert main(["check", str(ROOT / "solutions" / "ex01_rotations.ipynb")]) == 0
    out = capsys.readouterr().out
    assert "15 / 15 on the public cases" in out
    assert main(["check", str(ROOT / "exercises" / "ex01_rotations.ipynb")]) == 0
    assert "0 / 15" in capsys.readouterr().out


def test_check_rejects_an_unknown_exercise(tmp_path, capsys):
    nb = tmp_path / "mine.ipynb"
    nb.write_text("{}", encoding="utf-8")
    assert main(["check", str(nb)]) == 2
    assert "unknown exercise" in capsys.readouterr().err


def test_unknown_subcommand_exits_with_usage():
    with pytest.raises(SystemExit):
        main(["frobnicate"])


def test_grade_warns_and_exits_3_when_the_package_changes_during_grading(tmp_path, monkeypatch, capsys):
    from puma_course.grading.run import runner

    digests = iter([{"a.py": b"1"}, {"a.py": b"2"}])
    monkeypatch.setattr(runner, "package_digest", lambda *_: next(digests))
    (tmp_path / "subs" / "ann").mkdir(parents=True)
    code = main(
        ["grade", str(tmp_path / "subs"), "-o", str(tmp_path / "g.csv"), "--exercise", "ex01_rotations", "--quiet"]
    )
    assert code == 3
    assert "changed while grading" in capsys.readouterr().err


def test_missing_notebook_feedback_names_misnamed_files(tmp_path):
    subs = tmp_path / "subs"
    (subs / "cat").mkdir(parents=True)
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", subs / "cat" / "ex01_rotations (1).ipynb")
    assert (
        main(
            [
                "grade",
                str(subs),
                "-o",
                str(tmp_path / "g.csv"),
                "--feedback",
                str(tmp_path / "fb"),
                "--exercise",
                "ex01_rotations",
                "--quiet",
            ]
        )
        == 0
    )
    text = (tmp_path / "fb" / "cat.md").read_text(encoding="utf-8")
    assert "missing" in text and "ex01_rotations (1).ipynb" in text


def test_check_keeps_bonus_and_answer_key_rules_of_the_grader(tmp_path, capsys):
    """`puma-course check` must judge the public cases exactly as grading does.

    The ex06 solution answers the bonus too: 10 points plus a 3-point bonus, not 13 / 13.
    """
    nb = tmp_path / "ex06_porter_explicit.ipynb"
    shutil.copy(ROOT / "solutions" / "ex06_porter_explicit.ipynb", nb)
    assert main(["check", str(nb)]) == 0
    out = capsys.readouterr().out
    assert "13 / 10" in out and "(bonus)" in out


# --------------------------------------------------------------------------- real installs and servers
def _clean_env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(extra)
    return env


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
    env = _clean_env()
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
    _edit_a_cell(course_copy / "exercises" / "ex01_rotations.ipynb")
    done = run("release", "--check", cwd=course_copy)
    assert done.returncode == 1 and "ex01_rotations" in done.stderr
    done = run("lab", "--print-command", "--port", "8898", cwd=course_copy)
    assert done.returncode == 0, done.stderr
    argv = shlex.split(done.stdout)
    assert argv[0] == str(python) and f"--ServerApp.root_dir={course_copy}" in argv and argv[-2:] == ["--port", "8898"]
    done = run("release", "--check", cwd=tmp_path)
    assert done.returncode == 2 and "no course found" in done.stderr and repr(str(tmp_path.resolve())) in done.stderr


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _get(port: int, path: str) -> tuple[int, dict[str, str], str]:
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    try:
        conn.request("GET", path)
        response = conn.getresponse()
        return response.status, dict(response.getheaders()), response.read().decode("utf-8")
    finally:
        conn.close()


@pytest.mark.slow
@pytest.mark.skipif(os.name != "posix", reason="not run: lab replaces its process with JupyterLab (exec) on POSIX only")
def test_lab_serves_the_course_root_and_opens_the_index_first(tmp_path):
    port, token = _free_port(), secrets.token_hex(16)
    env = _clean_env(
        JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"),
        JUPYTER_CONFIG_DIR=str(tmp_path / "config"),
        JUPYTER_DATA_DIR=str(tmp_path / "data"),
    )
    cmd = [sys.executable, "-m", "puma_course.cli", "lab", "--no-browser", "--ip", "127.0.0.1", "--port", str(port)]
    cmd += ["--port-retries", "0", f"--IdentityProvider.token={token}"]
    if os.geteuid() == 0:
        cmd.append("--allow-root")  # JupyterLab refuses root without it
    log = tmp_path / "lab.log"
    with open(log, "w", encoding="utf-8") as out:
        server = subprocess.Popen(cmd, cwd=ROOT / "notebooks", env=env, stdout=out, stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 60
        while True:
            assert server.poll() is None, "JupyterLab exited:\n" + log.read_text(encoding="utf-8")
            try:
                if _get(port, f"/api/status?token={token}")[0] == 200:
                    break
            except OSError:
                pass
            assert time.monotonic() < deadline, "JupyterLab did not start:\n" + log.read_text(encoding="utf-8")
            time.sleep(0.2)
        # the process started is JupyterLab itself, so stopping it by this PID stops the server
        assert (tmp_path / "runtime" / f"jpserver-{server.pid}.json").exists()

        status, _, body = _get(port, f"/api/contents?token={token}")
        assert status == 200
        listing = json.loads(body)
        entries = {item["name"]: item["type"] for item in listing["content"]}
        assert entries["notebooks"] == entries["exercises"] == "directory" and entries[INDEX] == "notebook"
        for folder, first in (
            ("notebooks", "01_rotations_and_transforms.ipynb"),
            ("exercises", "ex01_rotations.ipynb"),
        ):
            status, _, body = _get(port, f"/api/contents/{folder}?token={token}")
            assert status == 200 and first in {item["name"] for item in json.loads(body)["content"]}
        assert _get(port, "/api/contents")[0] == 403  # the token is required

        status, headers, _ = _get(port, f"/?token={token}")
        assert status == 302 and headers["Location"].split("?")[0] == f"/lab/tree/{INDEX}"
        status, _, page = _get(port, f"/lab/tree/{INDEX}?token={token}")
        found = re.search(r'<script id="jupyter-config-data" type="application/json">(.*?)</script>', page, re.DOTALL)
        assert status == 200 and found
        config = json.loads(found.group(1))
        assert config["treePath"] == INDEX and Path(config["serverRoot"]) == ROOT
    finally:
        server.send_signal(signal.SIGTERM)
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


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
