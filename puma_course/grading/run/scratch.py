"""The sandbox's own file system: a per-run copy of what a worker reads, so its mount table names no host folder.

A bind mount shows, in ``/proc/self/mountinfo`` (field 4, "root"), the bound folder's path inside the file
system it comes from: binding ``/root/.pyenv/versions/3.11.7`` at ``/python/0`` still prints the host path.
Only a folder that is the root of a file system of its own prints nothing but ``/``. So each run copies what a
worker needs into a :class:`Scratch`, in memory:

* as root, a fresh tmpfs mounted for the run (``mountinfo`` then shows ``/python/0``, ``/puma/bin``, ...: the
  sandbox's own names, nothing of the host);
* otherwise, a private folder of ``/dev/shm`` (no mount is allowed; ``mountinfo`` then shows the run folder's
  name inside ``/dev/shm``, ``/puma-run-<random>/python/0``, and nothing of the host's layout).

What is copied (:func:`copy_python`): the Python executable, its shared library, its standard library without
the parts a notebook cannot use here (tests, IDLE, Tk, ensurepip, lib2to3, the build configuration), and from
site-packages the course's runtime dependencies and theirs (``numpy``, ``matplotlib``, ``sympy``, ...), read
from the installed distribution's metadata; never the course package itself. Only folders outside the system's
(``/usr`` and the like, bound as they are) are copied. The stage (:mod:`.stage`) is built inside the same
scratch. ``benchmarks/bench_sandbox.py`` prints what this costs.
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import errno
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import weakref
from collections.abc import Iterable
from pathlib import Path

__all__ = ["Scratch", "copy_python", "runtime_tops", "SKIP_STDLIB", "ROOTS"]

#: Standard-library folders a graded notebook has no use for (not copied).
SKIP_STDLIB = frozenset(
    {"test", "idlelib", "tkinter", "turtledemo", "ensurepip", "lib2to3", "site-packages", "dist-packages"}
)
#: What a graded notebook may import besides the standard library and the student-side package: these
#: distributions and what they need (the course's computational dependencies; its widget libraries, which
#: need a browser, stay out).
ROOTS = ("numpy", "matplotlib", "sympy")
COURSE = "puma-course"
_MNT_DETACH = 2


def _libc() -> ctypes.CDLL | None:
    name = ctypes.util.find_library("c")
    try:
        return ctypes.CDLL(name or "libc.so.6", use_errno=True)
    except OSError:  # pragma: no cover - not glibc/musl
        return None


def _mount_tmpfs(folder: str) -> bool:
    """Mount a fresh tmpfs on ``folder`` (root only); False where that is not allowed."""
    if os.geteuid() != 0 or not sys.platform.startswith("linux"):
        return False
    libc = _libc()
    if libc is None:
        return False
    flags = 0x2 | 0x4  # MS_NOSUID | MS_NODEV
    return libc.mount(b"tmpfs", folder.encode(), b"tmpfs", flags, b"mode=0755") == 0


def _umount(folder: str) -> None:
    libc = _libc()
    if libc is not None:
        libc.umount2(folder.encode(), _MNT_DETACH)


def _remove(folder: str, mounted: bool) -> None:
    if mounted:
        _umount(folder)  # the tmpfs and everything in it are gone
    for root, dirs, _ in os.walk(folder):
        for d in dirs:  # the stage is made read-only
            with contextlib.suppress(OSError):
                os.chmod(os.path.join(root, d), 0o755)
    shutil.rmtree(folder, ignore_errors=True)


class Scratch:
    """A run's in-memory folder (see the module docstring); removed by :meth:`close` or when garbage collected."""

    def __init__(self, base: str | None = None) -> None:
        if base is None:
            base = "/dev/shm" if os.path.isdir("/dev/shm") and os.access("/dev/shm", os.W_OK) else None
        self.path = tempfile.mkdtemp(prefix="puma-run-", dir=base)
        self.mounted = _mount_tmpfs(self.path)
        self._finalizer = weakref.finalize(self, _remove, self.path, self.mounted)

    @property
    def kind(self) -> str:
        """ "tmpfs" (a file system of its own) or "folder" (a folder of a shared one)."""
        return "tmpfs" if self.mounted else "folder"

    def close(self) -> None:
        self._finalizer()


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _closure(roots: Iterable[str]) -> list[object]:
    """The installed distributions ``roots`` need (without extras), themselves included."""
    import importlib.metadata as md

    seen: dict[str, object] = {}
    todo = list(roots)
    while todo:
        name = todo.pop()
        if _norm(name) in seen:
            continue
        try:
            dist = md.distribution(name)
        except md.PackageNotFoundError:
            continue
        seen[_norm(name)] = dist
        for req in dist.requires or []:
            head, _, marker = req.partition(";")
            if "extra" in marker:
                continue
            if marker.strip():
                try:
                    from packaging.markers import Marker

                    if not Marker(marker.strip()).evaluate():
                        continue
                except Exception:  # noqa: BLE001 - packaging missing or an odd marker: take it
                    pass
            m = re.match(r"\s*([A-Za-z0-9][A-Za-z0-9._-]*)", head)
            if m:
                todo.append(m.group(1))
    return list(seen.values())


def runtime_tops(roots: Iterable[str] = ROOTS) -> list[tuple[str, str]]:
    """(folder, top-level name) of every file or folder that the distributions ``roots`` need install."""
    tops: set[tuple[str, str]] = set()
    for dist in _closure(roots):
        if _norm(getattr(dist, "metadata", {}).get("Name", "") or "") == _norm(COURSE):
            continue  # never the course package
        base = str(dist.locate_file(""))  # type: ignore[attr-defined]
        for f in getattr(dist, "files", None) or []:
            parts = Path(str(f)).parts
            # not site-packages' shared __pycache__ (it also holds other packages' files: an editable install's
            # finder names the course's folder), nor .pth files (the worker runs with -S)
            if parts and parts[0] not in ("..", "/", "__pycache__") and not parts[0].endswith(".pth"):
                tops.add((os.path.realpath(base), parts[0]))
    return sorted(tops)


def _inside(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip("/") + "/")


def _copy(host: str, names: list[str], out: str) -> None:
    """Copy ``host/<name>`` (files or whole folders, links kept) to ``out/<name>`` for each name."""
    names = [n for n in dict.fromkeys(names) if os.path.lexists(os.path.join(host, n))]
    if not names:
        return
    os.makedirs(out, exist_ok=True)
    tar = shutil.which("tar")
    if tar:
        listing = b"".join(n.encode() + b"\0" for n in names)
        pack = subprocess.Popen(
            [tar, "-C", host, "--null", "-T", "-", "-cf", "-"], stdin=subprocess.PIPE, stdout=subprocess.PIPE
        )
        unpack = subprocess.Popen([tar, "-C", out, "-xf", "-"], stdin=pack.stdout)
        assert pack.stdin is not None and pack.stdout is not None
        pack.stdout.close()
        pack.stdin.write(listing)
        pack.stdin.close()
        if unpack.wait() == 0 and pack.wait() == 0:
            return
        raise OSError(errno.EIO, "tar could not copy the Python install")
    for n in names:  # pragma: no cover - a system without tar
        src, dst = os.path.join(host, n), os.path.join(out, n)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if os.path.isdir(src) and not os.path.islink(src):
            shutil.copytree(src, dst, symlinks=True, dirs_exist_ok=True)
        else:
            shutil.copy2(src, dst, follow_symlinks=False)


def copy_python(views: Iterable[tuple[str, str]], dest: str, python: str, sites: Iterable[str]) -> None:
    """Copy into ``dest/<i>`` what a worker needs of each (host folder, view ``/python/<i>``) in ``views``."""
    sites = [os.path.realpath(s) for s in sites]
    tops = [(base, name) for base, name in runtime_tops() if any(_inside(base, s) for s in sites)]
    std = {os.path.realpath(sysconfig.get_paths()[k]) for k in ("stdlib", "platstdlib")}
    for host, view in views:
        out = os.path.join(dest, view.rstrip("/").rsplit("/", 1)[-1])
        os.makedirs(out, exist_ok=True)
        names = [os.path.relpath(python, host)] if _inside(python, host) else []
        lib = os.path.join(host, "lib")
        names += (
            [f"lib/{n}" for n in sorted(os.listdir(lib)) if n.startswith("libpython")] if os.path.isdir(lib) else []
        )
        for folder in sorted(std):
            if _inside(folder, host) and os.path.isdir(folder):
                rel = os.path.relpath(folder, host)
                names += [
                    f"{rel}/{n}"
                    for n in sorted(os.listdir(folder))
                    if n not in SKIP_STDLIB and not n.startswith("config-")
                ]
        for base, name in tops:
            if _inside(base, host):
                names.append(os.path.relpath(os.path.join(base, name), host))
        _copy(host, names, out)
