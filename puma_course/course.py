"""Find the course folder: the one that holds ``solutions/`` or ``notebooks/``.

A course is a folder, not the installed package: an instructor's own course folder works with a
non-editable install, and every ``puma-course`` command works on the course it is run in. The
course root is the nearest folder, at or above the starting one, that holds a ``solutions/`` or a
``notebooks/`` folder; its layout is::

    START_HERE.ipynb   the index JupyterLab opens first (optional)
    notebooks/         the lectures
    exercises/         the student versions, generated from solutions/
    solutions/         the single source of every exercise

Standard library only (base layer).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from pathlib import Path

__all__ = ["MARKERS", "INDEX", "CourseNotFoundError", "is_course", "find_course", "course_root", "course_exercises"]

#: A folder is a course when it holds one of these folders.
MARKERS: tuple[str, ...] = ("solutions", "notebooks")

#: The course's index, relative to the course root: the notebook ``puma-course lab`` opens first.
INDEX = "START_HERE.ipynb"

_WHAT = " or ".join(f"{m}/" for m in MARKERS)


class CourseNotFoundError(ValueError):
    """No course folder where one was looked for; ``searched`` lists the folders that were tried.

    >>> err = CourseNotFoundError("course: expected a course folder", searched=(Path("a"), Path("b")))
    >>> isinstance(err, ValueError), [p.name for p in err.searched]
    (True, ['a', 'b'])
    """

    def __init__(self, message: str, searched: tuple[Path, ...] = ()) -> None:
        super().__init__(message)
        self.searched = searched


def is_course(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is a course root (a folder holding ``solutions/`` or ``notebooks/``).

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     before = is_course(tmp)
    ...     (Path(tmp) / "notebooks").mkdir()
    ...     before, is_course(tmp)
    (False, True)
    """
    folder = Path(path)
    return any((folder / marker).is_dir() for marker in MARKERS)


def find_course(start: str | os.PathLike[str] | None = None, fallback: bool = False) -> Path:
    """The course root at or above ``start`` (default: the current directory), as an absolute path.

    Walks up from ``start`` to the first folder holding ``solutions/`` or ``notebooks/``; raises
    :class:`CourseNotFoundError` naming every folder it searched when there is none (with ``fallback``,
    it looks from the current directory then: a notebook outside any course, checked in a course).

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     root = Path(tmp).resolve()
    ...     (root / "solutions").mkdir()
    ...     (root / "notebooks" / "figures").mkdir(parents=True)
    ...     find_course(root / "notebooks" / "figures") == root
    True
    """
    origin = Path.cwd() if start is None else Path(start)
    here = origin.resolve()
    if not here.is_dir():
        raise CourseNotFoundError(
            f"start: expected a folder inside a course (one holding {_WHAT}), got {str(origin)!r}, "
            + ("which is not a folder" if here.exists() else "which does not exist"),
            searched=(),
        )
    searched: list[Path] = []
    for folder in (here, *here.parents):
        searched.append(folder)
        if is_course(folder):
            return folder
    if fallback and start is not None:
        return find_course()
    raise CourseNotFoundError(
        f"start: expected a folder inside a course (a folder holding {_WHAT} at or above it), got {str(origin)!r}; "
        f"searched {', '.join(repr(str(f)) for f in searched)}",
        searched=tuple(searched),
    )


def course_root(course: str | os.PathLike[str] | None = None, start: str | os.PathLike[str] | None = None) -> Path:
    """The course to work on: ``course`` itself when named (it must be a course root), else :func:`find_course`.

    A named course is taken as it is, never walked up from: naming a folder that holds neither
    ``solutions/`` nor ``notebooks/`` raises :class:`CourseNotFoundError`.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     (Path(tmp) / "solutions").mkdir()
    ...     course_root(tmp) == Path(tmp).resolve()
    True
    """
    if course is None:
        return find_course(start)
    folder = Path(course)
    resolved = folder.resolve()
    if not resolved.is_dir():
        why = "which is not a folder" if resolved.exists() else "which does not exist"
    elif not is_course(resolved):
        why = f"which holds neither {' nor '.join(f'{m}/' for m in MARKERS)}"
    else:
        return resolved
    raise CourseNotFoundError(
        f"course: expected a course folder (one holding {_WHAT}), got {str(folder)!r}, {why}",
        searched=(resolved,),
    )


def course_exercises(root: Path, known: Sequence[str]) -> list[str]:
    """The exercises the course at ``root`` hands out (``exercises/*.ipynb``) that the grader knows.

    Names the ones it does not know on stderr; raises ValueError when none is left.
    """
    folder = root / "exercises"
    names = sorted(p.stem for p in folder.glob("*.ipynb"))
    if not names:
        raise ValueError(
            f"exercise: expected --exercise NAME or a course that hands out exercises, got none in {str(folder)!r}"
        )
    unknown = [name for name in names if name not in known]
    if unknown:
        print(f"not graded (the grader has no questions for them): {', '.join(unknown)}", file=sys.stderr)
    graded = [name for name in names if name in known]
    if not graded:
        raise ValueError(
            f"exercise: expected exercises the grader knows ({', '.join(sorted(known))}) in {str(folder)!r}, "
            f"got only {', '.join(unknown)}"
        )
    return graded
