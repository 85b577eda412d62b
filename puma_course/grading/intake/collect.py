"""Collecting notebooks from what a learning platform downloads: one student, many exercises, their identifiers.

``puma-course grade SUBMISSIONS --layout folders|canvas|moodle`` reads one of three layouts:

* ``folders`` (the default): ``SUBMISSIONS/<student>/<exercise>.ipynb``, read by :mod:`.submissions`.
* ``canvas``: the flat folder of Canvas's "Download Submissions" zip. Canvas names each uploaded file
  ``<name>[_LATE]_<user id>_<file id>_<file name as uploaded>`` (canvas-lms ``lib/content_zipper.rb``:
  ``get_filename`` and ``add_upload_submission``), where ``<name>`` is the student's sortable name,
  lower-cased with every non-word character removed (``smithjohn``), ``LATE`` marks a late submission,
  and an anonymously graded assignment gives ``anon_<id>`` in place of name and user id. A file the
  student uploaded again under the same name comes back as ``ex01_rotations-1.ipynb``,
  ``ex01_rotations-2.ipynb``: the highest number (then the highest file id) counts, the others are listed.
* ``moodle``: Moodle's "Download all submissions", with or without "Download submissions in folders":
  a folder ``<Full Name>_<participant id>_assignsubmission_file_`` per student holding the files as
  uploaded, or flat files ``<Full Name>_<participant id>_assignsubmission_file_<file name>`` (Moodle's
  ``mod/assign``: "StudentName_StudentID_PluginType_Plugin_FilePathAndName").

Each notebook is matched to an exercise by its file name (``<exercise>.ipynb``, any ``-N`` re-upload
suffix removed). Files that match no exercise, files of an unrecognised name, and the older copies
of a re-uploaded notebook are returned as :attr:`Collected.problems`: the command prints them and
the class summary lists them. Nothing is opened here: the notebooks are read later, without following
links, by :func:`~.submissions.read_path`.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..output.text import display_name, quoted
from .submissions import Notebook, StudentFiles, StudentFolder, read_path

__all__ = ["LAYOUTS", "Submitter", "Collected", "collect", "parse_canvas_name", "parse_moodle_name"]

LAYOUTS = ("folders", "canvas", "moodle")

_CANVAS = re.compile(
    r"^(?:(?P<name>.*?)_)??(?P<late>LATE_)?(?P<uid>anon_[A-Za-z0-9]+|\d+)_(?P<fid>\d+)_(?P<file>.+)$", re.DOTALL
)
_MOODLE = re.compile(r"^(?P<name>.+)_(?P<pid>\d+)_assignsubmission_file_(?P<file>.*)$", re.DOTALL)
_REUPLOAD = re.compile(r"^(?P<stem>.+?)-(?P<n>\d+)$")


@dataclass
class Submitter:
    """One student of a download: ``key`` names them in the grades (unique); ``name``, ``user_id`` as the platform
    gave them; ``late``: the exercises it marked late; ``files``: the notebook kept per exercise."""

    key: str
    name: str
    user_id: str = ""
    late: set[str] = field(default_factory=set)
    files: dict[str, Path] = field(default_factory=dict)
    #: exercise -> (re-upload number, file id) of the file kept, to compare with the next one found
    rank: dict[str, tuple[int, int]] = field(default_factory=dict)


@dataclass
class Collected:
    """What :func:`collect` found: the students, and every file it did not grade (with why)."""

    layout: str
    folder: Path
    students: list[Submitter] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)
    seen: list[str] = field(default_factory=list)
    #: exercises of the course left out on purpose, with why (a file of one is "not collected: why", not "no exercise")
    others: dict[str, str] = field(default_factory=dict)

    def notebooks(self) -> int:
        """How many notebooks will be graded."""
        return sum(len(s.files) for s in self.students)

    def folders(self) -> list[StudentFolder]:
        """The students as :func:`~.submissions.scan` would list them (``raw`` and ``name``: the key)."""
        return [StudentFolder(s.key, s.key) for s in self.students]

    def read(self, student: StudentFolder, exercises: list[str]) -> StudentFiles:
        """The student's notebooks, read without following links (see :func:`~.submissions.read_path`)."""
        me = next(s for s in self.students if s.key == student.raw)
        out = StudentFiles()
        for name in exercises:
            path = me.files.get(name)
            out.notebooks[name] = (
                read_path(path) if path is not None else Notebook("missing", note=f"no file {name}.ipynb was submitted")
            )
        return out

    def late(self) -> set[tuple[str, str]]:
        """(student key, exercise) of every late submission."""
        return {(s.key, ex) for s in self.students for ex in s.late}

    def by_key(self) -> dict[str, Submitter]:
        """The students by key."""
        return {s.key: s for s in self.students}


def parse_canvas_name(filename: str) -> dict[str, str] | None:
    """The parts of a Canvas bulk-download file name, or None when it is not one.

    >>> p = parse_canvas_name("smithjohn_LATE_12345_67890_ex01_rotations-1.ipynb")
    >>> p["name"], p["late"], p["uid"], p["fid"], p["file"]
    ('smithjohn', 'LATE_', '12345', '67890', 'ex01_rotations-1.ipynb')
    >>> parse_canvas_name("LATE_anon_xY12_555_ex01_rotations.ipynb")["uid"]
    'anon_xY12'
    >>> parse_canvas_name("notes.ipynb") is None
    True
    """
    m = _CANVAS.match(filename)
    return None if m is None else {k: v or "" for k, v in m.groupdict().items()}


def parse_moodle_name(name: str) -> dict[str, str] | None:
    """The parts of a Moodle download entry (``Full Name_123_assignsubmission_file_[file]``), or None.

    >>> parse_moodle_name("Ann O'Neil, Jr_42_assignsubmission_file_")
    {'name': "Ann O'Neil, Jr", 'pid': '42', 'file': ''}
    """
    m = _MOODLE.match(name)
    return None if m is None else m.groupdict()


def _exercise_of(filename: str, exercises: list[str]) -> tuple[str, int] | None:
    """The exercise a file name belongs to and its re-upload number (0 for the first upload)."""
    if not filename.lower().endswith(".ipynb"):
        return None
    stem = filename[: -len(".ipynb")]
    if stem in exercises:
        return stem, 0
    m = _REUPLOAD.match(stem)
    if m is not None and m["stem"] in exercises:
        return m["stem"], int(m["n"])
    return None


def _entries(folder: Path) -> list[os.DirEntry[str]]:
    with os.scandir(folder) as it:
        return sorted((e for e in it if not e.name.startswith(".")), key=lambda e: e.name)


def _kind(entry: os.DirEntry[str]) -> str:
    try:
        if entry.is_symlink():
            return "link"
        return "dir" if entry.is_dir(follow_symlinks=False) else "file"
    except OSError:
        return "file"


def _add(
    c: Collected, s: Submitter, path: Path, shown: str, exercises: list[str], filename: str, fid: int = 0
) -> str | None:
    """File ``path`` (uploaded as ``filename``) for ``s``; returns its exercise if it is the one kept so far."""
    found = _exercise_of(filename, exercises)
    if found is None:
        other = _exercise_of(filename, list(c.others))
        if other is not None:
            c.problems.append(f"{shown}: not collected: {other[0]} {c.others[other[0]]}")
            return None
        c.problems.append(
            f"{shown}: matches no exercise (expected one of {', '.join(e + '.ipynb' for e in exercises)})"
        )
        return None
    ex, n = found
    rank = (n, fid)
    if ex in s.files:
        keep_old = rank < s.rank[ex]
        older, newer = (path, s.files[ex]) if keep_old else (s.files[ex], path)
        c.problems.append(
            f"{quoted(s.key, 120)}: {quoted(display_name(older.name), 120)} not graded: "
            f"{quoted(display_name(newer.name), 120)} is a later upload of {ex}"
        )
        if keep_old:
            return None
    s.files[ex], s.rank[ex] = path, rank
    return ex


def _collect_canvas(c: Collected, exercises: list[str]) -> None:
    students: dict[str, Submitter] = {}
    for entry in _entries(c.folder):
        shown = quoted(display_name(entry.name), 120)
        c.seen.append(display_name(entry.name))
        kind = _kind(entry)
        if kind != "file":
            c.problems.append(
                f"{shown}: a {'symbolic link' if kind == 'link' else 'folder'}; Canvas's download is flat"
            )
            continue
        parts = parse_canvas_name(entry.name)
        if parts is None:
            c.problems.append(f"{shown}: not a Canvas submission file name (<name>_<user id>_<file id>_<file>)")
            continue
        uid = parts["uid"]
        key = f"{parts['name']}_{uid}" if parts["name"] else uid
        s = students.setdefault(uid, Submitter(key, parts["name"] or uid, "" if uid.startswith("anon_") else uid))
        ex = _add(c, s, Path(entry.path), shown, exercises, parts["file"], int(parts["fid"]))
        if ex is not None:
            (s.late.add if parts["late"] else s.late.discard)(ex)
    c.students = sorted(students.values(), key=lambda s: s.key)


def _walk_files(folder: Path, c: Collected, shown_root: str) -> list[Path]:
    out: list[Path] = []
    for entry in _entries(folder):
        kind = _kind(entry)
        if kind == "file":
            out.append(Path(entry.path))
        elif kind == "dir":
            out += _walk_files(Path(entry.path), c, f"{shown_root}/{entry.name}")
        else:
            c.problems.append(
                f"{quoted(display_name(shown_root + '/' + entry.name), 160)}: a symbolic link; not followed"
            )
    return out


def _collect_moodle(c: Collected, exercises: list[str]) -> None:
    students: dict[str, Submitter] = {}
    for entry in _entries(c.folder):
        shown = quoted(display_name(entry.name), 120)
        c.seen.append(display_name(entry.name))
        kind = _kind(entry)
        parts = parse_moodle_name(entry.name)
        if kind == "link" or parts is None or (kind == "dir") == bool(parts["file"]):
            why = "a symbolic link" if kind == "link" else "not a Moodle file submission"
            c.problems.append(f"{shown}: {why} (<Full Name>_<participant id>_assignsubmission_file_...)")
            continue
        pid = parts["pid"]
        key = f"{display_name(parts['name'])}_{pid}"
        s = students.setdefault(pid, Submitter(key, parts["name"], pid))
        if kind == "dir":
            for path in _walk_files(Path(entry.path), c, entry.name):
                where = quoted(display_name(f"{entry.name}/{path.relative_to(entry.path)}"), 160)
                _add(c, s, path, where, exercises, path.name)
        else:
            _add(c, s, Path(entry.path), shown, exercises, parts["file"])
    c.students = sorted(students.values(), key=lambda s: s.key)


def collect(
    folder: str | os.PathLike[str], layout: str, exercises: list[str], others: dict[str, str] | None = None
) -> Collected:
    """The students and notebooks of a ``canvas`` or ``moodle`` download in ``folder`` (see the module docstring).

    ``others``: exercises of the course not collected this time, each with why (e.g. "has no written question");
    their files are listed as not collected, with that reason. ValueError when ``layout`` is unknown or the
    folder cannot be read.
    """
    if layout not in ("canvas", "moodle"):
        raise ValueError(f"layout: expected 'canvas' or 'moodle' to collect, got {layout!r}")
    c = Collected(layout, Path(folder), others=dict(others or {}))
    try:
        (_collect_canvas if layout == "canvas" else _collect_moodle)(c, list(exercises))
    except OSError as exc:
        raise ValueError(f"submissions: expected a readable folder, got {str(folder)!r} ({exc.strerror})") from None
    c.students = [s for s in c.students if s.files]
    return c
