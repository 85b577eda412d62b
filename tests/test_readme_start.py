"""README's first commands, run as written in a fresh clone, up to a working lab (issue 20).

The commands are read from README.md: the fenced blocks marked ``<!-- first-commands: linux-macos -->``
and ``<!-- first-commands: windows -->``. The Linux ones run in ``bash`` in a ``git clone`` of this
repository's HEAD: make the virtual environment, activate it, install what a student needs, and
start ``puma-course lab`` the way README says, with the options README documents for a server
without a browser (``--no-browser --port P --IdentityProvider.token=T``, ``--allow-root`` when the
test runs as root), on 127.0.0.1. The test polls JupyterLab's ``/api/status`` and stops the server
by its process id. pip's own cache is used (nothing here turns it off), so a warm machine installs
from it.
"""

from __future__ import annotations

import http.client
import json
import os
import re
import secrets
import signal
import socket
import subprocess
import time

import pytest

from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: README's text, a clone, pip, a venv and a server's
# start and stop; nothing a BLAS kernel computes is checked (the lectures' numbers are nbval's, in the first pass).
pytestmark = pytest.mark.no_numerics

MARK = re.compile(r"<!-- first-commands: ([\w-]+) -->\s*```([\w-]*)\n(.*?)```", re.S)


def first_commands() -> dict[str, list[str]]:
    """README's marked blocks: {"linux-macos": [line, ...], "windows": [...]}."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    return {key: [s for s in body.strip().splitlines() if s.strip()] for key, _, body in MARK.findall(text)}


def test_readme_shows_a_venv_then_a_student_install_then_the_lab_on_every_system():
    blocks = first_commands()
    assert set(blocks) == {"linux-macos", "windows"}, blocks
    unix, windows = blocks["linux-macos"], blocks["windows"]
    assert unix[:2] == ["python3 -m venv .venv", "source .venv/bin/activate"]
    assert windows[:2] == ["py -m venv .venv", r".venv\Scripts\activate"]
    for lines in (unix, windows):
        assert lines[2] == 'python -m pip install -e ".[lab]"', (
            "a student installs the lab, not the maintainers' .[dev]"
        )
        assert lines[-1] == "puma-course lab" and len(lines) == 4


def test_readme_names_the_token_option_that_puma_course_lab_help_prints(capsys):
    from puma_course.cli import main

    with pytest.raises(SystemExit):
        main(["lab", "--help"])
    helped = set(re.findall(r"--\w+\.token", capsys.readouterr().out))
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    start = readme[readme.index("## Start") :].split("\n## ", 1)[0]
    written = set(re.findall(r"--\w+\.token", start))
    assert helped and written == helped, (written, helped)


def _free_port() -> int:
    for port in range(8850, 8900):
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
            except OSError:
                continue
            return port
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _get(port: int, path: str, token: str) -> tuple[int, bytes]:
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
    try:
        conn.request("GET", f"{path}?token={token}")
        resp = conn.getresponse()
        return resp.status, resp.read()
    finally:
        conn.close()


@pytest.mark.slow
def test_readme_first_commands_in_a_fresh_clone_reach_a_working_lab(tmp_path):
    unix = first_commands()["linux-macos"]
    clone = tmp_path / "course"
    subprocess.run(["git", "clone", "-q", "--no-hardlinks", str(ROOT), str(clone)], check=True, timeout=120)
    port, token = _free_port(), secrets.token_hex(16)
    lab = f"{unix[-1]} --no-browser --port {port} --port-retries 0 --IdentityProvider.token={token}"
    lab += " --ServerApp.ip=127.0.0.1" + (" --allow-root" if os.geteuid() == 0 else "")
    script = "set -euo pipefail\n" + "\n".join(unix[:-1]) + f"\nexec {lab}\n"
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH", "PYTHONHOME")}
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep) if ".venv" not in p)
    log = tmp_path / "lab.log"
    with open(log, "wb") as out:
        proc = subprocess.Popen(["bash", "-c", script], cwd=clone, env=env, stdout=out, stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 900  # a cold pip cache on a slow machine
        answer = None
        while time.monotonic() < deadline and proc.poll() is None:
            try:
                answer = _get(port, "/api/status", token)
                if answer[0] == 200:
                    break
            except OSError:
                pass
            time.sleep(1)
        said = log.read_text(encoding="utf-8", errors="replace")[-3000:]
        assert proc.poll() is None, f"the commands stopped with code {proc.returncode}:\n{said}"
        assert answer is not None and answer[0] == 200, f"no lab answered on port {port}:\n{said}"
        assert "started" in json.loads(answer[1])
        assert (clone / ".venv" / "bin" / "puma-course").is_file()
        status, listing = _get(port, "/api/contents", token)  # the lab serves the clone, its index in it
        assert status == 200 and "START_HERE.ipynb" in [c["name"] for c in json.loads(listing)["content"]]
    finally:
        if proc.poll() is None:
            os.kill(proc.pid, signal.SIGTERM)  # `exec` made the shell's process JupyterLab itself
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.kill(proc.pid, signal.SIGKILL)
                proc.wait(timeout=30)
