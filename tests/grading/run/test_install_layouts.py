"""Every supported install grades correctly under bubblewrap, and never shows a worker the course.

Each layout is installed into a fresh virtual environment: editable (``pip install -e .``),
non-editable (``pip install .``), from a built wheel, and ``pip install -e git+file://...`` (the
course cloned into ``<venv>/src``, its ``.git`` inside the Python install). In each, ``puma-course
grade`` grades an honest student full marks, a blank one 0, and a snoop 0: the snoop's answer is
right only when it can read the course's solution, its bank or its ``.git`` from inside the sandbox.

The environments take their dependencies (numpy, ...) from this one through a ``.pth`` line, so
only the course itself is installed (``--no-deps``, no network); pip builds in its usual isolated
build environment, as an instructor's install does.
"""

from __future__ import annotations

import csv
import json
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import nbformat
import pytest

from puma_course.grading.run.sandbox import choose
from tests.support import ROOT

pytestmark = [
    # CI's second pass (another OpenBLAS kernel) leaves this out: each install layout under bubblewrap:
    # packaging; an honest answer's numerics under this kernel are test_exercises' full marks.
    pytest.mark.no_numerics,
    pytest.mark.slow,
    pytest.mark.skipif(os.name != "posix", reason="venv layout (bin/) of POSIX"),
]

LAYOUTS = ("editable", "non-editable", "wheel", "git-editable")


def _env() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}


def _course(where: Path) -> Path:
    """A small course checkout: the package, its pyproject, ex01's solution, exercise and bank, a git history."""
    where.mkdir(parents=True)
    shutil.copytree(ROOT / "puma_course", where / "puma_course", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(ROOT / "bank", where / "bank", ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(ROOT / name, where)
    for sub in ("solutions", "exercises"):
        (where / sub).mkdir()
        shutil.copy(ROOT / sub / "ex01_rotations.ipynb", where / sub)
    git = ["git", "-C", str(where), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run([*git, "init", "-q"], check=True)
    subprocess.run([*git, "add", "-A"], check=True)
    subprocess.run([*git, "commit", "-qm", "course"], check=True)
    return where


def _snoop(paths: list[str]) -> nbformat.NotebookNode:
    """The blank exercise, with q1 answered right only if one of ``paths`` can be read (the key)."""
    nb = nbformat.read(ROOT / "exercises" / "ex01_rotations.ipynb", as_version=4)
    code = (
        "import os, numpy as np\n"
        f"SEEN = [p for p in {paths!r} if os.path.exists(p)]\n"
        "def elementary_rotation(axis, angle):\n"
        "    if not SEEN:\n"
        "        raise NotImplementedError\n"
        "    c, s = np.cos(-angle if axis[0] == '-' else angle), np.sin(-angle if axis[0] == '-' else angle)\n"
        "    return {'x': np.array([[1, 0, 0], [0, c, -s], [0, s, c]]), 'y': np.array([[c, 0, s], [0, 1, 0], "
        "[-s, 0, c]]), 'z': np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis[-1]]\n"
    )
    for cell in nb.cells:
        if "question:q1" in cell.metadata.get("tags", []):
            cell.source = code
    return nb


def _install(layout: str, course: Path, tmp: Path) -> tuple[Path, Path]:
    """(the environment's bin folder, the course folder to grade) for ``layout``."""
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    site = subprocess.run(
        [python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True, text=True, check=True,
    ).stdout.strip()  # fmt: skip
    outer = sorted({sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]})
    Path(site, "outer_environment.pth").write_text("\n".join(outer) + "\n", encoding="utf-8")
    pip = [str(python), "-m", "pip", "install", "--quiet", "--no-deps"]
    if layout == "editable":
        cmd, graded = [*pip, "-e", str(course)], course
    elif layout == "non-editable":
        cmd, graded = [*pip, str(course)], course
    elif layout == "wheel":
        dist = tmp / "dist"
        built = subprocess.run(
            [str(python), "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", str(dist), str(course)],
            capture_output=True, text=True, env=_env(), cwd=tmp,
        )  # fmt: skip
        assert built.returncode == 0, built.stderr
        cmd, graded = [*pip, str(next(dist.glob("*.whl")))], course
    else:  # pip clones the course into <venv>/src/puma-course, .git and all
        cmd, graded = [*pip, "-e", f"git+file://{course}#egg=puma-course"], venv / "src" / "puma-course"
    done = subprocess.run(cmd, capture_output=True, text=True, env=_env(), cwd=tmp)
    assert done.returncode == 0, done.stdout + done.stderr
    return venv / "bin", graded


@pytest.mark.parametrize("layout", LAYOUTS)
def test_every_install_grades_honest_blank_and_snoop_students_under_bubblewrap(tmp_path, layout):
    if choose("auto").kind != "bwrap":
        pytest.skip("bubblewrap cannot run here")
    course = _course(tmp_path / "course")
    bin_dir, graded = _install(layout, course, tmp_path)
    where = subprocess.run(
        [bin_dir / "python", "-c", "import puma_course; print(puma_course.__file__)"],
        capture_output=True, text=True, check=True, env=_env(), cwd=tmp_path,
    ).stdout.strip()  # fmt: skip
    package_parent = Path(where).resolve().parents[1]
    if layout in ("non-editable", "wheel"):
        assert "site-packages" in where, where
    elif layout == "git-editable":
        assert Path(where).resolve().is_relative_to((tmp_path / "venv" / "src").resolve()), where
    subs = tmp_path / "subs"
    for student in ("honest", "blank", "snoop"):
        (subs / student).mkdir(parents=True)
    shutil.copy(graded / "solutions" / "ex01_rotations.ipynb", subs / "honest")
    shutil.copy(graded / "exercises" / "ex01_rotations.ipynb", subs / "blank")
    keys = [str(graded / "solutions" / "ex01_rotations.ipynb"), str(graded / "bank" / "ex01_rotations.py"),
            str(graded / ".git" / "HEAD"), str(package_parent / "solutions"), str(package_parent / ".git")]  # fmt: skip
    nbformat.write(_snoop(keys), subs / "snoop" / "ex01_rotations.ipynb")
    out = tmp_path / "g.csv"
    done = subprocess.run(
        [bin_dir / "puma-course", "grade", str(subs), "-o", str(out), "--course", str(graded),
         "--exercise", "ex01_rotations", "--sandbox", "bwrap", "--quiet", "--seed", "3"],
        capture_output=True, text=True, env=_env(), cwd=tmp_path, timeout=600,
    )  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    with open(out, newline="", encoding="utf-8") as fh:
        rows = {r["student"]: r for r in csv.DictReader(fh)}
    assert {s: rows[s]["sandbox"] for s in rows} == {"honest": "bwrap", "blank": "bwrap", "snoop": "bwrap"}
    assert float(rows["honest"]["score"]) == float(rows["honest"]["max_score"]) == 15.0, json.dumps(rows["honest"])
    assert float(rows["blank"]["score"]) == 0.0 and rows["blank"]["status"] == "ok", json.dumps(rows["blank"])
    assert float(rows["snoop"]["score"]) == 0.0, json.dumps(rows["snoop"])


def test_grade_exits_non_zero_when_every_notebook_crashed_or_none_was_found(tmp_path):
    from puma_course.cli import main

    flat = tmp_path / "flat"
    flat.mkdir()
    shutil.copy(ROOT / "exercises" / "ex01_rotations.ipynb", flat / "ann_ex01_rotations.ipynb")  # a flat download
    code = main(["grade", str(flat), "-o", str(tmp_path / "g.csv"), "--exercise", "ex01_rotations", "--quiet"])
    assert code == 2  # no student folder at all: said before grading, naming the layout (issue 24's exit code)
    (tmp_path / "empty" / "ann").mkdir(parents=True)  # a student folder with no notebook in it
    code = main(["grade", str(tmp_path / "empty"), "-o", str(tmp_path / "g.csv"), "--exercise", "ex01_rotations"])
    assert code == 4
    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    (subs / "ann" / "ex01_rotations.ipynb").write_text(
        json.dumps({"cells": [{"cell_type": "code", "source": "import os\nos._exit(9)", "metadata": {},
                               "outputs": [], "execution_count": None}],
                    "metadata": {}, "nbformat": 4, "nbformat_minor": 5}),
        encoding="utf-8",
    )  # fmt: skip
    code = main(["grade", str(subs), "-o", str(tmp_path / "g.csv"), "--exercise", "ex01_rotations", "--quiet"])
    assert code == 5
