"""A delegated control-group subtree: per-notebook limits for a grader that is not root.

Without root, the grader cannot make control groups (:mod:`.limits`), and a notebook's limits hold per
process only. Root can hand a grading user a folder of its own in each hierarchy, once
(``puma-course limits delegate --user NAME``, :func:`delegate`); the grader, run by that user, finds it
(:func:`find_delegated`, called by :func:`.limits.open_run` when not root) and makes its run's and its
notebooks' groups under it, with the same limits as root's; the terminal and the CSV say
``per notebook (cgroup v1, delegated)``. ``--undo`` removes the folders (:func:`undelegate`).

The delegated parent is ``puma-grading-<user>`` at the top of each hierarchy (found at the top or below it,
in a folder above the grader's own group):

* **cgroup v1** (the hybrid hierarchy of these machines): one folder per controller (``memory``, ``pids``,
  ``cpu``, ``cpuacct``), whose *directory only* is given to the user. That is all the user needs: it may
  make and remove groups in it, and the files of a group it makes are its own (the kernel gives a new
  group's files to their maker), so it sets their limits and moves its own processes into them (v1 asks
  for write access to the destination's ``cgroup.procs`` and, of a writer who is not root, the same user
  id as the process moved: the grader's launcher writes its own process id, :data:`.limits.JOIN`). The
  parent's own ``cgroup.procs``/``tasks`` stay root's, so no process of the user can move into the parent,
  above its notebook's limits. A notebook runs as the grader's user: inside the bubblewrap sandbox it sees no
  ``/sys/fs/cgroup`` (and cannot mount a v1 hierarchy in its user namespace); without the sandbox
  (``--sandbox none``) it could move itself into a group of its own making: the limits then hold only
  against honest mistakes.
* **cgroup v2** (a unified hierarchy with the ``memory``, ``pids`` and ``cpu`` controllers), following the
  kernel's rules (Documentation/admin-guide/cgroup-v2.rst, "Delegation"): the folder, its
  ``cgroup.procs``, ``cgroup.threads`` and ``cgroup.subtree_control`` are given to the user, the
  controllers are enabled for its children, and a leaf ``grader`` is made for the grader's own processes
  (a v2 group with enabled controllers holds no process). A process may be moved only by a writer of the
  ``cgroup.procs`` of the common ancestor of its old and new group, so the grader must *start* inside the
  subtree: root moves the grading shell there (``echo $$ > .../puma-grading-NAME/grader/cgroup.procs``),
  or the grading user's systemd does it (``systemd-run --user --scope -p Delegate=yes``, which
  :func:`.limits.open_run` uses without this module). Not tested on these machines (no v2 controllers).
"""

from __future__ import annotations

import errno
import os
import pwd
import re
from pathlib import Path

from .cgroupfs import remove_group, v2_mount, write_setting
from .groups import ROOT, Run

__all__ = ["parent_name", "delegate", "undelegate", "find_delegated", "V1_CONTROLLERS", "V2_CONTROLLERS"]

#: The v1 controllers a delegated subtree has (``cpuacct`` only for the CPU time counter: optional).
V1_CONTROLLERS = ("memory", "pids", "cpu", "cpuacct")
#: The v2 controllers a delegated subtree enables.
V2_CONTROLLERS = ("memory", "pids", "cpu")
_USER = re.compile(r"^[A-Za-z_][A-Za-z0-9_.-]{0,31}\$?$")


def parent_name(user: str) -> str:
    """The delegated parent's folder name for ``user``.

    >>> parent_name("grader")
    'puma-grading-grader'
    """
    if not isinstance(user, str) or not _USER.match(user):
        raise ValueError(f"user: expected a user name (letters, digits, _ . -; up to 32), got {user!r}")
    return f"puma-grading-{user}"


def _v1_mount(root: Path, controller: str) -> Path | None:
    for m in (controller, "cpu,cpuacct", "cpuacct,cpu"):
        if controller in m.split(",") and (root / m).is_dir() and (root / m / "cgroup.procs").exists():
            return root / m
    return None


def _v2_ready(root: Path) -> Path | None:
    mount = v2_mount(root)
    if mount is None:
        return None
    try:
        available = set((mount / "cgroup.controllers").read_text().split())
    except OSError:
        return None
    return mount if set(V2_CONTROLLERS) <= available else None


def _user(user: str) -> tuple[int, int]:
    parent_name(user)
    try:
        entry = pwd.getpwnam(user)
    except KeyError:
        raise ValueError(f"user: expected an existing user name, got {user!r}") from None
    if entry.pw_uid == 0:
        raise ValueError(f"user: expected a user other than root (root needs no delegation), got {user!r}")
    return entry.pw_uid, entry.pw_gid


def delegate(user: str, *, root: str | os.PathLike[str] = ROOT) -> list[str]:
    """Make (or re-own) ``user``'s delegated parent in every hierarchy; returns what was done, line by line.

    Needs root. v2 where the unified hierarchy has the controllers, else v1 (see the module docstring).
    """
    uid, gid = _user(user)
    base, name = Path(root), parent_name(user)
    done: list[str] = []
    mount = _v2_ready(base)
    if mount is not None:
        folder = mount / name
        write_setting(mount / "cgroup.subtree_control", " ".join(f"+{c}" for c in V2_CONTROLLERS))
        folder.mkdir(exist_ok=True)
        write_setting(folder / "cgroup.subtree_control", " ".join(f"+{c}" for c in V2_CONTROLLERS))
        leaf = folder / "grader"
        leaf.mkdir(exist_ok=True)
        for path in (folder, leaf):
            for f in ("", "cgroup.procs", "cgroup.threads", "cgroup.subtree_control"):
                os.chown(path / f if f else path, uid, gid)
        done.append(
            f"cgroup v2: {folder} ({', '.join(V2_CONTROLLERS)}) given to {user} (folder, cgroup.procs, "
            "cgroup.threads, cgroup.subtree_control), and its leaf grader/"
        )
        done.append(
            f"start the grader inside it, as root: echo $$ > {leaf}/cgroup.procs; runuser -u {user} -- "
            "puma-course grade ..."
        )
        return done
    made: dict[Path, list[str]] = {}
    for controller in V1_CONTROLLERS:
        m = _v1_mount(base, controller)
        if m is None:
            if controller == "cpuacct":
                continue
            raise ValueError(
                f"root: expected a cgroup v1 {controller} controller (or v2 with it) under {base}, found none"
            )
        made.setdefault(m / name, []).append(controller)
    for folder, controllers in made.items():
        folder.mkdir(exist_ok=True)
        os.chown(folder, uid, gid)
        os.chmod(folder, 0o755)
        done.append(f"cgroup v1 {','.join(controllers)}: {folder}/ given to {user} (the folder only)")
    done.append(f"the grader, run by {user}, now limits each notebook in a group of its own under these")
    return done


def undelegate(user: str, *, root: str | os.PathLike[str] = ROOT) -> list[str]:
    """Remove ``user``'s delegated parents and every group under them (none may still hold a process)."""
    name = parent_name(user)
    base = Path(root)
    folders = [p for p in {base / name, base / "unified" / name} if p.is_dir()]
    folders += [m / name for c in V1_CONTROLLERS if (m := _v1_mount(base, c)) is not None and (m / name).is_dir()]
    done: list[str] = []
    for folder in dict.fromkeys(folders):
        busy = []
        for dirpath, _dirs, _files in sorted(os.walk(folder), key=lambda w: -len(Path(w[0]).parts)):
            try:
                os.rmdir(dirpath)
            except OSError as exc:
                busy.append(f"{dirpath} ({exc.strerror})")
        if busy:
            raise ValueError(f"user: {user}'s groups could not all be removed (processes left?): {'; '.join(busy)}")
        done.append(f"removed {folder}")
    if not done:
        done.append(f"nothing to undo: no {name} under {base}")
    return done


def _ancestors(group: str) -> list[str]:
    """``/a/b`` -> ``/a/b``, ``/a``, ``/`` (deepest first)."""
    parts = [p for p in group.split("/") if p]
    return ["/" + "/".join(parts[:i]) for i in range(len(parts), -1, -1)]


def _find(mount: Path, own: str, name: str) -> Path | None:
    for anc in _ancestors(own):
        cand = mount / anc.lstrip("/") / name
        if cand.is_dir():
            return cand
    return None


def find_delegated(root: Path, own: dict[str, str], run_name: str, user: str | None = None) -> Run | str | None:
    """The run's groups under this user's delegated parent (:class:`~.limits.Run` with ``delegated`` True),
    why they cannot be made there (a string), or None where there is no delegated parent, or for root."""
    if user is None and (not hasattr(os, "geteuid") or os.geteuid() == 0):
        return None
    if user is None:
        try:
            user = pwd.getpwuid(os.geteuid()).pw_name
        except KeyError:
            return None
    try:
        name = parent_name(user)
    except ValueError:
        return None
    mount = _v2_ready(root)
    if mount is not None:
        folder = _find(mount, own.get("", "/"), name)
        if folder is not None:
            inside = Path(mount / own.get("", "/").lstrip("/"))
            if folder != inside and folder not in inside.parents:
                return (
                    f"the delegated subtree {folder} is not above the grader's own group ({inside}): start the "
                    f"grader inside it (as root: echo $$ > {folder}/grader/cgroup.procs)"
                )
            return _make(2, {c: folder for c in V2_CONTROLLERS}, run_name)
    parents: dict[str, Path] = {}
    for controller in V1_CONTROLLERS:
        m = _v1_mount(root, controller)
        found = _find(m, own.get(controller, "/"), name) if m is not None else None
        if found is not None:
            parents[controller] = found
    if not parents:
        return None
    missing = [c for c in V1_CONTROLLERS[:3] if c not in parents]
    if missing:
        return f"the delegated subtree {name} has no {', '.join(missing)} folder (puma-course limits delegate)"
    return _make(1, parents, run_name)


def _make(version: int, parents: dict[str, Path], run_name: str) -> Run | str:
    folders: dict[str, Path] = {}
    made: list[Path] = []
    for controller, parent in parents.items():
        run = parent / run_name
        try:
            if run not in made:
                run.mkdir()
                made.append(run)
                if version == 2:
                    write_setting(run / "cgroup.subtree_control", " ".join(f"+{c}" for c in V2_CONTROLLERS))
        except OSError as exc:
            for folder in reversed(made):
                remove_group(folder)
            why = "not this user's" if exc.errno in (errno.EACCES, errno.EPERM) else exc.strerror
            return f"cannot make a group in the delegated subtree {parent} ({why})"
        folders[controller] = run
    return Run(version, folders, delegated=True)
