"""Finding and reading ``SUBMISSIONS/<student>/<exercise>.ipynb`` without trusting what is there.

Whatever a folder of submissions holds, :func:`scan` lists its students and :func:`read_student`
reads their notebooks without ever stopping the run:

* a **symbolic link** is never followed: a linked student folder or notebook is reported as
  ``refused`` (and scores 0), and nothing it points at is opened;
* only **regular files** are read: a FIFO, a device or a folder in place of a notebook is
  ``refused`` before it is opened (a FIFO could block, a device could be endless);
* a notebook larger than :data:`MAX_NOTEBOOK_BYTES` is not read (``malformed``); an unreadable
  folder or file is ``unreadable``; a missing one ``missing``;
* **any name** works: names that are not UTF-8, that start with dashes, or that are as long as
  the file system allows are shown through :func:`~puma_course.grading.output.text.display_name`,
  which also keeps two names apart when they would display alike.

Files are opened relative to their folder's descriptor with ``O_NOFOLLOW``, so a name swapped for
a link between the check and the read is refused too. Nothing read here is parsed here: the
bytes go to the worker, which parses them under its own limits.
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..output.text import display_name, quoted

__all__ = [
    "StudentFolder",
    "Notebook",
    "scan",
    "read_student",
    "read_path",
    "handed_in",
    "exercises_to_grade",
    "MAX_NOTEBOOK_BYTES",
]

MAX_NOTEBOOK_BYTES = 20_000_000
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_FLAGS = os.O_RDONLY | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_NONBLOCK", 0)
_DIR_FD = os.open in os.supports_dir_fd and os.scandir in os.supports_fd


@dataclass
class StudentFolder:
    """One entry of the submissions folder: ``raw`` is its name on disk, ``name`` how the grader shows it."""

    raw: str
    name: str
    refused: str | None = None


@dataclass
class Notebook:
    """One (student, exercise) file: its ``state`` (read, missing, refused, unreadable, malformed), bytes, a note."""

    state: str
    data: bytes | None = None
    note: str | None = None


@dataclass
class StudentFiles:
    """What :func:`read_student` found in a student's folder."""

    notebooks: dict[str, Notebook] = field(default_factory=dict)
    others: list[str] = field(default_factory=list)


def scan(folder: Path) -> list[StudentFolder]:
    """The student folders of ``folder`` (names starting with '.' skipped), sorted, shown names made unique.

    An entry that is a symbolic link is listed with ``refused`` set; plain files are not students.
    """
    found: list[StudentFolder] = []
    with os.scandir(folder) as entries:
        for entry in entries:
            if entry.name.startswith("."):
                continue
            try:
                link = entry.is_symlink()
                is_dir = entry.is_dir(follow_symlinks=False)
            except OSError:
                link, is_dir = False, True
            if link:
                why = "the student's folder is a symbolic link; links are not followed, so nothing in it was graded"
                found.append(StudentFolder(entry.name, "", why))
            elif is_dir:
                found.append(StudentFolder(entry.name, ""))
    found.sort(key=lambda s: os.fsencode(s.raw))
    used: set[str] = set()
    for student in found:
        shown = base = display_name(student.raw)
        k = 2
        while shown in used:
            shown, k = f"{base}~{k}", k + 1
        used.add(shown)
        student.name = shown
    return found


def handed_in(folder: Path, exercises: Sequence[str]) -> list[str]:
    """The exercises of ``exercises`` (in their order) that some student's folder holds an entry for.

    An entry named ``<exercise>.ipynb`` counts whatever it is (a link or a folder is refused when
    graded, but it was handed in); student folders that are links, or that cannot be listed, are
    not looked into. Nothing is opened but the folders.
    """
    found: set[str] = set()
    wanted = {f"{name}.ipynb": name for name in exercises}
    for student in scan(folder):
        if student.refused is not None:
            continue
        try:
            names = os.listdir(folder / student.raw)
        except OSError:
            continue
        found.update(wanted[n] for n in names if n in wanted)
    return [name for name in exercises if name in found]


def exercises_to_grade(folder: Path, submissions: Path, known: Sequence[str]) -> tuple[list[str], list[str], list[str]]:
    """What ``puma-course grade`` grades by default: the exercises ``folder/*.ipynb`` (the course's
    ``exercises/``) that the grader knows (``known``) and some student handed in.

    Returns (graded, unknown to the grader, handed in by nobody). Raises ``ValueError`` when that
    leaves nothing to grade. A ``submissions`` that is not a folder is left for the grader to refuse.
    """
    names = sorted(p.stem for p in folder.glob("*.ipynb"))
    if not names:
        raise ValueError(
            f"exercise: expected --exercise NAME or a course that hands out exercises, got none in {str(folder)!r}"
        )
    unknown = [name for name in names if name not in known]
    names = [name for name in names if name in known]
    if not names:
        raise ValueError(
            f"exercise: expected exercises the grader knows ({', '.join(sorted(known))}) in {str(folder)!r}, "
            f"got only {', '.join(unknown)}"
        )
    if not submissions.is_dir():
        return names, unknown, []
    try:
        graded = handed_in(submissions, names)
    except OSError as exc:
        raise ValueError(
            f"submissions: expected a readable folder, got {str(submissions)!r} ({exc.strerror})"
        ) from None
    if not graded:
        raise ValueError(
            f"submissions: expected <student>/<exercise>.ipynb files named after the course's exercises "
            f"({', '.join(names)}), got none in {str(submissions)!r}"
        )
    return graded, unknown, [name for name in names if name not in graded]


def _refusal(mode: int) -> str | None:
    if stat.S_ISLNK(mode):
        return "is a symbolic link; links are not followed"
    if stat.S_ISDIR(mode):
        return "is a folder, not a notebook file"
    if not stat.S_ISREG(mode):
        return "is not a regular file (a pipe, socket or device)"
    return None


def _read_fd(fd: int, shown: str) -> Notebook:
    info = os.fstat(fd)
    why = _refusal(info.st_mode)
    if why is not None:
        return Notebook("refused", note=f"{shown} {why}")
    if info.st_size > MAX_NOTEBOOK_BYTES:
        return Notebook("malformed", note=f"{shown} is {info.st_size} bytes, more than {MAX_NOTEBOOK_BYTES}: not read")
    chunks, total = [], 0
    while True:
        try:
            chunk = os.read(fd, 1 << 20)
        except BlockingIOError:  # pragma: no cover - regular files do not block
            continue
        if not chunk:
            break
        total += len(chunk)
        if total > MAX_NOTEBOOK_BYTES:
            return Notebook("malformed", note=f"{shown} grew past {MAX_NOTEBOOK_BYTES} bytes while read: not read")
        chunks.append(chunk)
    return Notebook("read", b"".join(chunks))


def _open_error(exc: OSError, shown: str, what: str) -> Notebook:
    if exc.errno == errno.ENOENT:
        return Notebook("missing", note=f"no file {shown} was submitted")
    if exc.errno in (errno.ELOOP, errno.EMLINK):
        return Notebook("refused", note=f"{shown} is a symbolic link; links are not followed")
    if exc.errno == errno.ENOTDIR:
        return Notebook("refused", note=f"the {what} is not a folder")
    reason = os.strerror(exc.errno) if exc.errno else type(exc).__name__
    return Notebook("unreadable", note=f"{shown} could not be read ({reason})")


def read_student(folder: Path, student: StudentFolder, exercises: Sequence[str]) -> StudentFiles:
    """Read ``<exercise>.ipynb`` for each exercise in the student's folder (see the module docstring)."""
    out = StudentFiles()
    if student.refused is not None:
        out.notebooks = {name: Notebook("refused", note=student.refused) for name in exercises}
        return out
    path = folder / student.raw
    try:
        dir_fd = os.open(path, os.O_RDONLY | _NOFOLLOW | getattr(os, "O_DIRECTORY", 0)) if _DIR_FD else -1
    except OSError as exc:
        nb = _open_error(exc, "the student's folder", "student's folder")
        if nb.state == "missing":
            nb = Notebook("unreadable", note="the student's folder disappeared while grading")
        elif nb.state == "unreadable":
            nb.note = f"the student's folder could not be read ({os.strerror(exc.errno) if exc.errno else exc})"
        out.notebooks = {name: nb for name in exercises}
        return out
    try:
        for name in exercises:
            out.notebooks[name] = _read_one(path, dir_fd, f"{name}.ipynb")
        try:
            listing = os.listdir(dir_fd if dir_fd >= 0 else path)
        except OSError:
            listing = []
        others = sorted(n for n in listing if n.endswith(".ipynb") and n[: -len(".ipynb")] not in exercises)
        out.others = [quoted(display_name(n), 120) for n in others[:5]] + (["…"] if len(others) > 5 else [])
    finally:
        if dir_fd >= 0:
            os.close(dir_fd)
    return out


def _read_one(path: Path, dir_fd: int, filename: str) -> Notebook:
    shown = filename
    try:
        if dir_fd >= 0:
            mode = os.stat(filename, dir_fd=dir_fd, follow_symlinks=False).st_mode
        else:  # pragma: no cover - platforms without dir_fd
            mode = os.lstat(path / filename).st_mode
    except OSError as exc:
        return _open_error(exc, shown, "student's folder")
    why = _refusal(mode)
    if why is not None:
        return Notebook("refused", note=f"{shown} {why}")
    try:
        fd = os.open(filename, _FLAGS | _NOFOLLOW, dir_fd=dir_fd) if dir_fd >= 0 else os.open(path / filename, _FLAGS)
    except OSError as exc:
        return _open_error(exc, shown, "student's folder")
    try:
        return _read_fd(fd, shown)
    except OSError as exc:
        return _open_error(exc, shown, "student's folder")
    finally:
        os.close(fd)


def read_path(path: str | os.PathLike[str]) -> Notebook:
    """Read one notebook file by path, by the same rules (a link as the last part of the path is refused)."""
    path = Path(path)
    return _read_one(path.parent, -1, path.name) if not _DIR_FD else _read_in(path)


def _read_in(path: Path) -> Notebook:
    try:
        dir_fd = os.open(path.parent, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError as exc:
        return _open_error(exc, quoted(path.name), "folder")
    try:
        return _read_one(path.parent, dir_fd, path.name)
    finally:
        os.close(dir_fd)
