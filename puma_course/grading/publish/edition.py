"""The student edition: the course a student clones, written from the instructor's course folder.

``puma-course edition DIR`` (:func:`write_edition`) writes into DIR everything a student works
with, and nothing of the answer key:

* a student README (make a virtual environment, install, open, work, self-check, hand in);
* ``START_HERE.ipynb``, ``notebooks/`` (the lectures, with their outputs), ``exercises/`` (the
  student versions) and the figures the exercises show (``figures/*.png``);
* the package source (``puma_course/``, ``pyproject.toml``, ``LICENSE``, and a ``setup.py`` that builds in a
  temporary folder, so installing leaves no ``build/`` or ``*.egg-info`` behind), so ``pip install .`` in
  DIR gives the kinematics, the viewer and the grading engine, and the self-check's data for the
  public cases only (``puma_course/grading/publish/public_data/exercises.pickle``,
  :mod:`puma_course.grading.publish.public`): inputs, expected values, the mistaken answers it recognises
  on those inputs, hints.

Not written: ``solutions/``, the question bank (``bank/``: reference answers, hidden-case
generators), hidden tests, a grading secret or seed, tests, benchmarks, the website's and the
maintainers' tools. Writing again updates DIR in place: the entries it writes are replaced, and
anything else in DIR (a ``.git``, say) is left untouched.
"""

from __future__ import annotations

import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

from ...course import INDEX
from ...hub import write_binder_files
from ..bank_loader import load_bank
from .public import DATA_FILE, dumps, public_exercise

__all__ = ["Edition", "write_edition", "STUDENT_README", "SETUP_PY", "MANAGED"]

#: What an edition holds at its top level (replaced on every write; anything else in DIR is kept).
MANAGED = (
    "README.md",
    "binder",
    "LICENSE",
    "pyproject.toml",
    "setup.py",
    ".gitignore",
    INDEX,
    "notebooks",
    "exercises",
    "figures",
    "puma_course",
)

_IGNORE = shutil.ignore_patterns("__pycache__", "*.pyc", ".ipynb_checkpoints", "*.egg-info", "public_data")

STUDENT_README = """\
# {title}: the student edition

A Jupyter workbook on the kinematics of robot manipulators: ten lectures (`notebooks/`), ten
exercises (`exercises/`), and the small package `puma_course` the lectures use. Start at
[START_HERE.ipynb](START_HERE.ipynb).

## Install (once)

You need Python 3.10 or newer. In a terminal, in this folder, make a virtual environment,
activate it and install the course with JupyterLab:

Linux and macOS:

```bash
python3 -m venv .venv
source .venv/bin/activate
python -m pip install ".[lab]"
```

Windows (a Command Prompt):

```bat
py -m venv .venv
.venv\\Scripts\\activate.bat
python -m pip install ".[lab]"
```

(In PowerShell the second line is `.venv\\Scripts\\Activate.ps1`; if PowerShell refuses to run it because
running scripts is disabled, use a Command Prompt, or allow your own scripts once with
`Set-ExecutionPolicy -Scope CurrentUser RemoteSigned`.)

The install builds in a temporary folder (`setup.py`), so this folder gets no `build/` or `*.egg-info`.

(Already have JupyterLab, on a university hub say? `python -m pip install .` installs only what the
lectures and the self-checks need, and leaves your JupyterLab as it is.)

## Open

With the environment active (`source .venv/bin/activate`, or `.venv\\Scripts\\activate.bat` on Windows):

```bash
puma-course lab
```

JupyterLab opens at this folder with `START_HERE.ipynb`, the index of every lecture and exercise.
`puma-course --help` lists your commands (`lab`, `check`) first; the others are your instructor's.

JupyterLab will not run as root (the administrator). In a container (Docker, Podman) where you are root,
`puma-course lab` gives JupyterLab `--allow-root` itself and says so. Anywhere else it stops and tells you
to run it as your own user, without `sudo`; if root really is the only user there, run
`puma-course lab --allow-root`.

## Work

Read a lecture top to bottom and run it (Run > Run All Cells); change the numbers and run again.
Each exercise in `exercises/` asks for functions: write each answer where the notebook says so.
Some also ask a **written** question: write it in the Markdown cell below the question (formulas between
`$…$`; a sketch is a photo or drawing dragged into that cell). Your instructor marks it by hand.

## Self-check

Below each answer, the cell `check("q1", my_function)` runs your function on the question's public
cases and prints whether it passes, what is wrong and a hint. From a terminal in this folder,

```bash
puma-course check ex01_rotations
```

checks a whole notebook the same way. The grader uses other, hidden inputs too: an answer that only
fits the public cases will not earn the points.

## Hand in

Save the notebook (File > Save) and hand in the file `exercises/NAME.ipynb` itself, keeping its
name, the way your instructor says. Do not rename the functions the questions ask for.
"""

GITIGNORE = """\
.venv/
__pycache__/
*.egg-info/
.ipynb_checkpoints/
build/
"""


#: The edition's ``setup.py``: setuptools builds in a temporary folder, so ``pip install .`` (or ``-e .``) leaves
#: no ``build/`` or ``*.egg-info`` in the student's folder (everything else comes from ``pyproject.toml``).
SETUP_PY = """\
\"\"\"Build the course's package in a temporary folder, so the install leaves this folder as it was.

Everything else about the package is in pyproject.toml.
\"\"\"

import atexit
import shutil
import tempfile

from setuptools import setup

scratch = tempfile.mkdtemp(prefix="puma-course-build-")
atexit.register(shutil.rmtree, scratch, ignore_errors=True)
setup(options={"build": {"build_base": scratch}, "egg_info": {"egg_base": scratch}})
"""


@dataclass
class Edition:
    """What :func:`write_edition` wrote: the folder and the files, by path inside it."""

    root: Path
    files: list[str] = field(default_factory=list)
    exercises: list[str] = field(default_factory=list)


def _title(course: Path) -> str:
    readme = course / "README.md"
    if readme.is_file():
        first = readme.read_text(encoding="utf-8").splitlines()[:1]
        if first and first[0].startswith("# "):
            return first[0][2:].strip()
    return course.name


def _figures(course: Path) -> list[Path]:
    """The figures the notebooks and exercises show (``../figures/NAME.png``), that exist."""
    shown: set[str] = set()
    for nb in [*course.glob("notebooks/*.ipynb"), *course.glob("exercises/*.ipynb"), course / INDEX]:
        if nb.is_file():
            shown.update(re.findall(r"figures/([\w.-]+\.(?:png|svg|jpg|gif))", nb.read_text(encoding="utf-8")))
    return sorted(course / "figures" / name for name in shown if (course / "figures" / name).is_file())


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    elif path.exists() or path.is_symlink():
        path.unlink()


def write_edition(out: str | Path, course: str | Path | None = None) -> Edition:
    """Write the student edition of ``course`` (default: the course found from here) into ``out``.

    ``out`` must not be the course itself or lie inside its ``solutions/`` or ``bank/``.
    """
    bank = load_bank(course)
    root = bank.course
    assert root is not None  # load_bank sets it
    dest = Path(out).resolve()
    if dest == root or any(dest == root / d or root / d in dest.parents for d in ("solutions", "bank", "puma_course")):
        raise ValueError(f"out: expected a folder outside the course's own files, got {str(out)!r}")
    dest.mkdir(parents=True, exist_ok=True)
    for name in MANAGED:
        _remove(dest / name)

    (dest / "README.md").write_text(STUDENT_README.format(title=_title(root)), encoding="utf-8")
    (dest / ".gitignore").write_text(GITIGNORE, encoding="utf-8")
    (dest / "setup.py").write_text(SETUP_PY, encoding="utf-8")
    for name in ("LICENSE", "pyproject.toml", INDEX):
        if (root / name).is_file():
            shutil.copy2(root / name, dest / name)
    for folder in ("notebooks", "exercises"):
        if (root / folder).is_dir():
            shutil.copytree(root / folder, dest / folder, ignore=_IGNORE)
    figures = _figures(root)
    if figures:
        (dest / "figures").mkdir()
        for fig in figures:
            shutil.copy2(fig, dest / "figures" / fig.name)
    package = Path(__file__).resolve().parents[2]
    shutil.copytree(package, dest / "puma_course", ignore=_IGNORE)
    write_binder_files(dest)  # repo2docker/Binder's environment, and the .gitignore nbgitpuller needs

    names = sorted(bank)
    data = dest / "puma_course" / DATA_FILE.relative_to(package)
    data.parent.mkdir(parents=True, exist_ok=True)
    data.write_bytes(dumps({name: public_exercise(bank[name]) for name in names}))

    files = sorted(p.relative_to(dest).as_posix() for name in MANAGED for p in _walk(dest / name))
    return Edition(dest, files, names)


def _walk(path: Path) -> list[Path]:
    if path.is_dir():
        return [p for p in path.rglob("*") if p.is_file()]
    return [path] if path.is_file() else []
