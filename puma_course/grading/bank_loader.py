"""The question bank's loader: the registry :data:`EXERCISES` of exercises by name, filled from a course folder.

The registry maps an exercise's name (the file stem of ``solutions/NAME.ipynb``) to its
:class:`~puma_course.grading.spec.Exercise`; the course's question bank (``COURSE/bank/``, beside ``solutions/``,
imported from the course folder as :data:`BANK_MODULE`) fills it, one exercise each, through :func:`register`.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from collections.abc import Iterator, MutableMapping
from pathlib import Path

from .spec import Exercise

__all__ = ["EXERCISES", "register", "Bank", "BankNotFoundError", "BANK_MODULE", "load_bank"]


#: The name the course's bank is imported under (its ``bank/`` folder is a package of this name).
BANK_MODULE = "puma_course_bank"


class BankNotFoundError(ValueError):
    """The course has no question bank (``bank/`` beside ``solutions/``), e.g. a student edition."""


class Bank(MutableMapping[str, Exercise]):
    """The registry of exercises by name, filled from the question bank of a course folder.

    The bank is content, not engine: it lives in the course folder (``COURSE/bank/``, one file per
    exercise, beside ``solutions/``) and is imported from there, so editing a question needs no
    reinstall. The first lookup loads the bank of the course found from the current directory
    (:func:`puma_course.course.find_course`); :meth:`load` loads another course's bank.
    """

    def __init__(self) -> None:
        self._data: dict[str, Exercise] = {}
        self._course: Path | None = None
        self._loading = False

    @property
    def course(self) -> Path | None:
        """The course folder whose bank is loaded (None before the first lookup)."""
        return self._course

    def load(self, course: str | os.PathLike[str] | None = None) -> Bank:
        """Load the question bank of ``course`` (default: the course found from the current directory).

        Raises :class:`BankNotFoundError` naming the folder it looked in when the course has no ``bank/``.
        """
        from ..course import course_root

        given = Path(course).resolve() if course is not None else None
        # a course folder, or any folder holding a bank/ (an autograder's source folder: .gradescope)
        root = given if given is not None and (given / "bank" / "__init__.py").is_file() else course_root(course)
        init = root / "bank" / "__init__.py"
        if not init.is_file():
            raise BankNotFoundError(
                f"course: expected a question bank at {str(init.parent)!r} (the instructor's course folder holds "
                f"bank/ beside solutions/; a student edition has none), got {str(root)!r} without one"
            )
        if root == self._course and self._data:
            return self
        for name in [m for m in sys.modules if m == BANK_MODULE or m.startswith(BANK_MODULE + ".")]:
            del sys.modules[name]
        self._data.clear()
        self._course = root
        spec = importlib.util.spec_from_file_location(BANK_MODULE, init, submodule_search_locations=[str(init.parent)])
        if spec is None or spec.loader is None:  # pragma: no cover - a file that exists always gives a spec
            raise BankNotFoundError(f"course: could not import the question bank at {str(init)!r}")
        module = importlib.util.module_from_spec(spec)
        sys.modules[BANK_MODULE] = module
        self._loading = True
        try:
            spec.loader.exec_module(module)
        except BaseException:
            sys.modules.pop(BANK_MODULE, None)
            self._data.clear()
            self._course = None
            raise
        finally:
            self._loading = False
        return self

    def _loaded(self) -> dict[str, Exercise]:
        if self._course is None and not self._loading:
            self.load()
        return self._data

    def __getitem__(self, name: str) -> Exercise:
        return self._loaded()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._loaded())

    def __len__(self) -> int:
        return len(self._loaded())

    def __setitem__(self, name: str, exercise: Exercise) -> None:
        self._loaded()[name] = exercise

    def __delitem__(self, name: str) -> None:
        del self._loaded()[name]

    def register(self, exercise: Exercise) -> Exercise:
        """Add ``exercise`` (ValueError if the name or a question id is taken twice)."""
        if exercise.name in self._data and self._data[exercise.name] is not exercise:
            raise ValueError(f"exercise: expected a new name, got {exercise.name!r}, which is registered already")
        qids = [q.qid for q in exercise.questions]
        if len(set(qids)) != len(qids) or not qids:
            raise ValueError(f"exercise: expected distinct question ids in {exercise.name}, got {qids}")
        self._data[exercise.name] = exercise
        return exercise


#: Every exercise by name, from the question bank of the course (``COURSE/bank/``, one file per exercise).
EXERCISES: Bank = Bank()


def load_bank(course: str | os.PathLike[str] | None = None) -> Bank:
    """Load the question bank of ``course`` into :data:`EXERCISES` (default: the course found from here)."""
    return EXERCISES.load(course)


def register(exercise: Exercise) -> Exercise:
    """Add ``exercise`` to :data:`EXERCISES` (ValueError if the name or a question id is taken twice)."""
    return EXERCISES.register(exercise)
