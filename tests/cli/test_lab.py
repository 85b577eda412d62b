"""``puma-course lab``: the JupyterLab command it runs on the course, root as a student would expect it handled
(one test starts a real JupyterLab)."""

from __future__ import annotations

import http.client
import json
import os
import re
import secrets
import shlex
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from puma_course.cli import lab as cli_lab
from puma_course.cli import main
from puma_course.course import INDEX
from tests.cli.support import clean_env, lab_argv
from tests.support import ROOT


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
    argv = lab_argv(capsys, *mine)
    assert argv[-len(mine) :] == mine  # in order, last: JupyterLab lets a later option win
    assert "--print-command" not in argv and "--no-browser" not in argv


def test_lab_opens_the_folder_of_a_course_without_an_index(course_copy, capsys, monkeypatch):
    (course_copy / INDEX).unlink()
    monkeypatch.chdir(course_copy)
    argv = lab_argv(capsys)
    assert f"--ServerApp.root_dir={course_copy}" in argv
    assert not any(a.startswith("--LabApp.default_url") for a in argv)


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
    env = clean_env(
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


# --------------------------------------------------------------------------- root (issue 31)
@pytest.fixture
def no_exec(monkeypatch):
    """``lab`` records the command it would replace this process with, instead of starting JupyterLab."""
    started: list[list[str]] = []

    def fake_execv(path, argv):
        started.append(list(argv))
        raise SystemExit(0)

    monkeypatch.setattr(cli_lab.os, "execv", fake_execv)
    return started


def test_lab_as_root_outside_a_container_says_what_to_do_and_starts_nothing(monkeypatch, capsys, no_exec):
    monkeypatch.setattr(cli_lab, "running_as_root", lambda: True)
    monkeypatch.setattr(cli_lab, "in_container", lambda: False)
    assert main(["lab", "--course", str(ROOT)]) == 2
    err = capsys.readouterr().err
    assert "as root" in err and "without sudo" in err and "puma-course lab --allow-root" in err
    assert no_exec == []
    with pytest.raises(SystemExit):  # asked for on purpose: JupyterLab is started, given the option once
        main(["lab", "--course", str(ROOT), "--allow-root"])
    assert no_exec[-1].count("--allow-root") == 1


def test_lab_as_root_in_a_container_allows_root_and_says_so(monkeypatch, capsys, no_exec):
    monkeypatch.setattr(cli_lab, "running_as_root", lambda: True)
    monkeypatch.setattr(cli_lab, "in_container", lambda: True)
    with pytest.raises(SystemExit):
        main(["lab", "--course", str(ROOT), "--port", "8898"])
    (argv,) = no_exec
    assert argv.count("--allow-root") == 1 and argv[-2:] == ["--port", "8898"]
    assert "running as root in a container" in capsys.readouterr().err
    for given in ("--allow-root", "--ServerApp.allow_root=True"):
        with pytest.raises(SystemExit):
            main(["lab", "--course", str(ROOT), given])
        assert "--allow-root" not in no_exec[-1][:-1]  # not added when the student gave it
    assert main(["lab", "--course", str(ROOT), "--print-command"]) == 0
    assert "--allow-root" in capsys.readouterr().out  # the command shown is the one run


def test_lab_as_a_user_is_given_no_allow_root(monkeypatch, capsys, no_exec):
    monkeypatch.setattr(cli_lab, "running_as_root", lambda: False)
    monkeypatch.setattr(cli_lab, "in_container", lambda: pytest.fail("no need to ask"))
    with pytest.raises(SystemExit):
        main(["lab", "--course", str(ROOT)])
    assert "--allow-root" not in no_exec[0] and capsys.readouterr().err == ""


def test_a_container_is_told_by_the_marks_its_runtime_leaves(monkeypatch, tmp_path):
    for name in ("container", "KUBERNETES_SERVICE_HOST"):
        monkeypatch.delenv(name, raising=False)
    real_exists = os.path.exists
    monkeypatch.setattr(
        cli_lab.os.path, "exists", lambda p: False if p.startswith(("/.dockerenv", "/run/")) else real_exists(p)
    )
    groups = tmp_path / "cgroup"
    monkeypatch.setattr(cli_lab, "PROC1_CGROUP", str(groups))
    assert not cli_lab.in_container()  # no file: not known to be one
    groups.write_text("12:pids:/init.scope\n1:name=systemd:/init.scope\n", encoding="utf-8")
    assert not cli_lab.in_container()  # a machine's own
    groups.write_text("12:pids:/docker/0123abcd\n", encoding="utf-8")
    assert cli_lab.in_container()
    groups.write_text("0::/kubepods/besteffort/pod1\n", encoding="utf-8")
    assert cli_lab.in_container()
    groups.unlink()
    monkeypatch.setenv("container", "podman")
    assert cli_lab.in_container()
