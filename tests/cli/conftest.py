"""The fixtures of the command line's tests: an instructor's small course, and a folder outside any course."""

from __future__ import annotations

import shutil

import pytest

from puma_course.course import INDEX, is_course
from tests.support import ROOT


@pytest.fixture
def course_copy(tmp_path):
    """An instructor's own small course: one solution, its exercise, a lecture folder and the index."""
    root = tmp_path / "my-course"
    for sub in ("solutions", "exercises"):
        (root / sub).mkdir(parents=True)
        shutil.copy(ROOT / sub / "ex01_rotations.ipynb", root / sub)
    (root / "notebooks").mkdir()
    shutil.copy(ROOT / INDEX, root)
    shutil.copytree(ROOT / "bank", root / "bank", ignore=shutil.ignore_patterns("__pycache__"))  # its questions
    return root.resolve()


@pytest.fixture
def outside(tmp_path):
    """A folder with no course at or above it."""
    here = (tmp_path / "elsewhere").resolve()
    here.mkdir()
    if any(is_course(f) for f in (here, *here.parents)):
        pytest.skip(f"not run: the test needs a folder outside any course, and a folder above {here} is a course")
    return here
