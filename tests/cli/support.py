"""Helpers of the command line's tests (the fixtures are in conftest.py)."""

from __future__ import annotations

import os
import shlex

from puma_course.cli import main


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
