"""Helpers of the command line's tests (the fixtures are in conftest.py)."""

from __future__ import annotations

import os
import shlex
from pathlib import Path

from puma_course.cli import main
from tests.support import ROOT


def grade_argv(subs: Path, out: Path, *extra: str, exercise: str = "ex01_rotations") -> list[str]:
    """``puma-course grade SUBS -o OUT/g.csv --feedback OUT/fb --exercise EXERCISE EXTRA...``: one exercise of a
    small class graded into files under ``out``, as the command-line tests run it."""
    return ["grade", str(subs), "-o", str(out / "g.csv"), "--feedback", str(out / "fb"), "--exercise", exercise, *extra]


def lab_argv(capsys, *args: str) -> list[str]:
    """``puma-course lab --print-command ARGS``: the JupyterLab command line it prints, split."""
    assert main(["lab", "--print-command", *args]) == 0
    return shlex.split(capsys.readouterr().out)


def edit_a_cell(path) -> None:
    """Change one cell's source (what release --check compares; the file's layout it ignores)."""
    import nbformat

    nb = nbformat.read(path, as_version=4)
    nb.cells[-1].source += "\n# edited by hand"
    nbformat.write(nb, path)


def clean_env(**extra: str) -> dict[str, str]:
    """This environment without PYTHONPATH and PYTHONHOME (a subprocess sees what an install sees), plus ``extra``."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(extra)
    return env


def _tags(cell) -> list[str]:
    return list(cell.get("metadata", {}).get("tags", []))


def hand_in_written(folder: Path, exercise: str, solved: bool, answer: str | None) -> Path:
    """``folder/<exercise>.ipynb`` as a student hands it in: the solution (``solved``) or the exercise as released,
    with ``answer`` written into the first written question's answer cell (None: left as released)."""
    import nbformat

    from puma_course.grading.written import ANSWER_TAG, written_questions

    released = nbformat.read(ROOT / "exercises" / f"{exercise}.ipynb", as_version=4)
    nb = nbformat.read(ROOT / "solutions" / f"{exercise}.ipynb", as_version=4) if solved else released
    if solved:  # the solution has no written cells: the released ones go before its closing cell
        nb.cells[-1:-1] = [c for c in released.cells if any(t.startswith("written") for t in _tags(c))]
    if answer is not None:
        qid = written_questions(exercise)[0].qid
        next(c for c in nb.cells if ANSWER_TAG + qid in _tags(c)).source = answer
    folder.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, folder / f"{exercise}.ipynb")
    return folder / f"{exercise}.ipynb"
