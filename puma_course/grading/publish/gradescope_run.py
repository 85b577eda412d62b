"""Inside Gradescope's container: who runs the student's notebook, what it can reach, and how results.json is written.

Gradescope runs ``run_autograder`` as root, without bubblewrap. :func:`isolate` (root only) makes the
grader's files root's alone (the zip's folder with the bank, the submission, the results folder, the full
package when it is installed under ``/autograder``), then checks, by running a process as the unprivileged
user ``setup.sh`` made (:mod:`.run.asuser`), what that user can open, whether it can signal the grader, and
whether new PID and mount namespaces are allowed. Each notebook then runs as that user
(:class:`~.run.asuser.AsUser`); :func:`finish` ends every process of the user and writes ``results.json``
atomically (a fresh file beside it, renamed over it) into the folder only root can write, then reads it back.

Not root (an instructor trying the autograder as themselves): nothing can be dropped, the run says so.
"""

from __future__ import annotations

import json
import os
import secrets
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..run.asuser import STUDENT_USER, AsUser, User, end_processes, find_user, make_user, probe
from ..run.sandbox import Sandbox, choose, python_layout

__all__ = ["Isolation", "isolate", "finish", "write_results", "package_folders"]


@dataclass
class Isolation:
    """How the notebook runs here: the sandbox, the user (None: as the grader itself), what holds, in words."""

    box: Sandbox
    user: User | None
    notes: list[str] = field(default_factory=list)
    #: why grading must not go on (student code would run as root); "" when it may
    refused: str = ""


def package_folders() -> list[Path]:
    """The installed full package's folder and its ``.dist-info`` (the record of its files)."""
    import puma_course

    pkg = Path(puma_course.__file__).resolve().parent
    return [pkg, *sorted(pkg.parent.glob("puma_course-*.dist-info"))]


def _root_only(path: Path, mode: int) -> str:
    """Make ``path`` root's with ``mode`` (not following a link); "" or why not."""
    try:
        st = os.lstat(path)
        if stat.S_ISLNK(st.st_mode):
            return f"{path} is a link"
        os.chown(path, 0, 0, follow_symlinks=False)
        os.chmod(path, mode)
    except OSError as exc:
        return f"{path}: {exc.strerror}"
    return ""


def isolate(base: Path) -> Isolation:
    """Lock the grader's files and choose how the notebook runs (see the module docstring)."""
    if os.geteuid() != 0:
        box = choose("auto")
        said = "bubblewrap" if box.kind == "bwrap" else f"no sandbox: {box.reason}"
        note = f"Graded by a grader that is not root ({said}): your code ran as the grader's own user."
        return Isolation(box, None, [note])
    results = base / "results"
    results.mkdir(parents=True, exist_ok=True)
    failed = [_root_only(base / "source", 0o700), _root_only(base / "submission", 0o700)]
    failed += [_root_only(results, 0o700)]
    try:
        if os.stat(base).st_mode & 0o022:
            os.chmod(base, os.stat(base).st_mode & ~0o022)
    except OSError as exc:
        failed.append(f"{base}: {exc.strerror}")
    private = [str(base / "source"), str(base / "submission"), str(results)]
    metadata = base / "submission_metadata.json"  # Gradescope's: earlier submissions and their scores
    if os.path.lexists(metadata):
        failed.append(_root_only(metadata, 0o600))
        private.append(str(metadata))
    for folder in package_folders():
        if base in folder.parents:  # installed by setup.sh: never chmod a checkout outside /autograder
            failed.append(_root_only(folder, 0o700))
        private.append(str(folder))
    user = find_user() or make_user()
    if user is None:
        why = f"the unprivileged user {STUDENT_USER} does not exist and could not be made (run setup.sh)"
        return Isolation(choose("none"), None, refused=why)
    found = probe(user, private)
    if not found.ok:
        return Isolation(choose("none"), None, refused=f"{found.said}; your code is never run as root")
    where = (
        "in PID and mount namespaces of its own (it saw only its own processes)"
        if found.namespaces
        else "in the container's PID namespace (the container allows no new one: it could list the grader's "
        "processes, but not signal them or read their memory)"
    )
    notes = [
        f"Your code ran as the unprivileged user {user.name} (not root), {where}, with time and memory limits, "
        "against a package holding only what this exercise allows."
    ]
    if found.readable:
        why = "; ".join(filter(None, failed)) or "its permissions"
        notes.append(f"WARNING: that user could open {', '.join(found.readable)} ({why})")
    else:
        notes.append(
            "That user could not open the grader's full package, the question bank, your submission's folder or "
            "this results folder, and every process it left was ended before these results were written."
        )
    reason = "bubblewrap does not run in this container"
    box = AsUser.of(user, found.namespaces, reason, python_layout()[2])
    return Isolation(box, user, notes)


def write_results(base: Path, out: dict[str, Any]) -> None:
    """Write ``results.json`` atomically: a fresh file (never an existing one, never through a link) renamed over it;
    then read it back (ValueError if it is not what was written, or not root's when root writes it)."""
    folder = base / "results"
    folder.mkdir(parents=True, exist_ok=True)
    data = (json.dumps(out, indent=1) + "\n").encode()
    tmp = folder / f".results.{secrets.token_hex(8)}.tmp"
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o644)
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view) :]
        os.fsync(fd)
    finally:
        os.close(fd)
    os.replace(tmp, folder / "results.json")
    fd = os.open(folder / "results.json", os.O_RDONLY | os.O_NOFOLLOW)
    try:
        st = os.fstat(fd)
        with os.fdopen(os.dup(fd), "rb") as fh:
            back = fh.read()
    finally:
        os.close(fd)
    if back != data or st.st_nlink != 1 or (os.geteuid() == 0 and st.st_uid != 0):
        raise ValueError(f"results.json: expected the file just written, got {len(back)} bytes, owner {st.st_uid}")


def finish(iso: Isolation, base: Path, out: dict[str, Any]) -> dict[str, Any]:
    """End every process of the student's user, then write ``out`` as results.json; return what was written."""
    if iso.user is not None:
        left = end_processes(iso.user)
        if left:
            note = f"{left} process(es) your notebook started were still running after it ended: they were stopped"
            out["output"] = out.get("output", "") + "\n" + note
    write_results(base, out)
    return out
