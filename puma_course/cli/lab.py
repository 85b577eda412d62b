"""``puma-course lab``: JupyterLab on the course, its index first; root handled as a student would expect.

JupyterLab refuses to start as root unless given ``--allow-root``. Root in a container (Docker, Podman,
Kubernetes: often the only user there) is not a mistake, so ``lab`` passes ``--allow-root`` itself and says so;
root on a machine of its own is usually ``sudo`` by mistake, so ``lab`` stops with a message saying what to do
(run it as yourself, or add ``--allow-root`` on purpose) instead of JupyterLab's bare refusal.
JupyterLab is given the course's file manager (:mod:`puma_course.cli.lab_contents`) by its dotted path.
"""

from __future__ import annotations

import argparse
import os
import shlex
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..course import INDEX
from .options import course

__all__ = ["lab_command", "add_parser", "run", "CONTENTS_MANAGER", "running_as_root", "in_container"]

#: notebooks open unmodified whatever the student's Python (see :mod:`puma_course.cli.lab_contents`)
CONTENTS_MANAGER = "--ServerApp.contents_manager_class=puma_course.cli.lab_contents.CourseContentsManager"

#: where the first process's control groups are listed (a container's runtime names itself there)
PROC1_CGROUP = "/proc/1/cgroup"

ROOT_REFUSED = """\
puma-course lab: you are running it as root (the administrator), and JupyterLab refuses to start as root:
a notebook run as root can change anything on this machine.
  - On your own computer: run it as your own user, without sudo:  puma-course lab
  - In a container or virtual machine where root is the only user, say so:  puma-course lab --allow-root"""


def lab_command(
    root: str | os.PathLike[str], jupyter_args: Sequence[str] = (), no_browser: bool = False, allow_root: bool = False
) -> list[str]:
    """The command line that opens JupyterLab at the course folder ``root``, its index first.

    JupyterLab serves ``root`` (lectures in ``notebooks/`` and exercises in ``exercises/`` are
    both in its file browser); when ``root`` holds the index ``START_HERE.ipynb``, JupyterLab's
    default page (the URL it opens and prints) is that notebook. ``jupyter_args`` come last, so
    an option given there overrides the ones chosen here.

    >>> cmd = lab_command("/srv/course", ["--port", "8899"], no_browser=True)
    >>> cmd[1:4], cmd[5:], cmd[0] == sys.executable
    (['-m', 'jupyterlab', '--ServerApp.root_dir=/srv/course'], ['--no-browser', '--port', '8899'], True)
    >>> cmd[4] == CONTENTS_MANAGER
    True
    >>> lab_command("/srv/course", allow_root=True)[-1]
    '--allow-root'
    """
    folder = Path(root)
    cmd = [sys.executable, "-m", "jupyterlab", f"--ServerApp.root_dir={folder}", CONTENTS_MANAGER]
    if (folder / INDEX).is_file():
        cmd.append(f"--LabApp.default_url=/lab/tree/{INDEX}")
    if allow_root:
        cmd.append("--allow-root")
    if no_browser:
        cmd.append("--no-browser")
    cmd.extend(jupyter_args)
    return cmd


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``lab`` sub-command (``common``: the shared ``--course`` option)."""
    lab_parser = sub.add_parser(
        "lab",
        parents=[common],
        allow_abbrev=False,  # an abbreviation of a JupyterLab option must reach JupyterLab, not match ours
        usage="puma-course lab [-h] [--course DIR] [--no-browser] [--print-command] [JUPYTER-OPTIONS ...]",
        help="open JupyterLab on the course (lectures and exercises), START_HERE.ipynb first",
        description="Open JupyterLab at the course folder, with the index START_HERE.ipynb as its first page. "
        "As root, in a container it adds --allow-root itself (and says so); elsewhere it stops and says what to do.",
        epilog="Every other option goes to JupyterLab unchanged, e.g. --port 8899, --allow-root, "
        "--IdentityProvider.token=TOKEN, --LabApp.default_url=/lab.",
    )
    lab_parser.add_argument("--no-browser", action="store_true", help="start the server without opening a browser")
    lab_parser.add_argument(
        "--print-command", action="store_true", help="print the JupyterLab command instead of running it"
    )


def running_as_root() -> bool:
    """True when this process runs as root (POSIX; never on Windows)."""
    geteuid = getattr(os, "geteuid", None)
    return geteuid is not None and geteuid() == 0


def in_container() -> bool:
    """True inside a Docker, Podman, LXC or Kubernetes container (the marks they leave; False when unsure)."""
    if os.environ.get("container") or os.environ.get("KUBERNETES_SERVICE_HOST"):
        return True
    if any(os.path.exists(mark) for mark in ("/.dockerenv", "/run/.containerenv")):
        return True
    try:
        with open(PROC1_CGROUP, encoding="utf-8") as fh:
            groups = fh.read()
    except OSError:
        return False
    return any(word in groups for word in ("docker", "kubepods", "containerd", "libpod", "lxc"))


def _allows_root(jupyter_args: Sequence[str]) -> bool:
    """Whether the options for JupyterLab already allow root (``--allow-root``, ``--ServerApp.allow_root=True``)."""
    said = {a.replace("-", "_").lower() for a in jupyter_args}
    return bool(said & {"__allow_root", "__serverapp.allow_root=true", "__notebookapp.allow_root=true"})


def _exec(cmd: list[str]) -> int:
    """Run ``cmd`` in place of this process (POSIX), else as a child whose exit code is returned."""
    sys.stdout.flush()
    sys.stderr.flush()
    if os.name == "posix":
        # Like `jupyter lab` itself: Ctrl-C, SIGTERM and the exit code belong to JupyterLab,
        # which asks before shutting down and stops its kernels (a waiting parent would not).
        os.execv(cmd[0], cmd)
    with subprocess.Popen(cmd) as proc:  # pragma: no cover - Windows
        while True:
            try:
                return proc.wait()
            except KeyboardInterrupt:
                continue  # JupyterLab got the Ctrl-C as well and handles it


def run(args: argparse.Namespace) -> int:
    """``puma-course lab``: exit code 2 (with what to do) as root outside a container without ``--allow-root``.

    ``--print-command`` prints the command (with ``--allow-root`` added as running it would add it) and refuses
    nothing.
    """
    root = running_as_root() and not _allows_root(args.jupyter_args)
    add_root = root and in_container()
    cmd = lab_command(course(args), args.jupyter_args, no_browser=args.no_browser, allow_root=add_root)
    if args.print_command:  # only shown: never refused
        print(shlex.join(cmd))
        return 0
    if root and not add_root:
        print(ROOT_REFUSED, file=sys.stderr)
        return 2
    if add_root:
        print("puma-course lab: running as root in a container, so JupyterLab is given --allow-root", file=sys.stderr)
    return _exec(cmd)
