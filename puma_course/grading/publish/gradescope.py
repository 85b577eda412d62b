"""A Gradescope autograder: the zip ``puma-course gradescope`` builds, and the run inside Gradescope's container.

The zip follows Gradescope's autograder specification (gradescope-autograders.readthedocs.io, "Autograder
Specifications"): ``setup.sh`` and ``run_autograder`` at its root; Gradescope unpacks it into
``/autograder/source``, runs ``setup.sh`` once when it builds the image, copies ``run_autograder`` to
``/autograder/run_autograder`` and runs it, in ``/autograder``, for each submission, which it puts in
``/autograder/submission``; ``run_autograder`` must write ``/autograder/results/results.json``.

* ``setup.sh`` makes a virtual environment ``/autograder/puma-venv`` and installs into it the wheel of
  this package that the zip carries (``dist/puma_course-<version>-py3-none-any.whl``: the version that
  built the zip, so the grader is pinned to it), with its dependencies from the package index the
  image's pip uses; nothing else is downloaded. ``PUMA_PIP_OPTIONS`` adds pip options and
  ``PUMA_VENV_OPTIONS`` venv options (the tests install offline). It makes the system user
  ``puma-student`` (:data:`~.run.asuser.STUDENT_USER`; ``PUMA_STUDENT_UID`` fixes its uid) and makes the
  installed package, its record and ``/autograder/source`` root's alone.
* ``run_autograder`` runs ``python -m puma_course.grading.publish.gradescope``: :func:`run` locks the grader's
  folders and checks the student's user (:func:`~.gradescope_run.isolate`), grades the submitted notebook
  (``<exercise>.ipynb``, or the only notebook submitted) as ``puma-course grade`` does, as that user
  (:mod:`.run.asuser`), with the zip's question bank, ends every process of the user and writes
  ``results.json`` (:func:`~.gradescope_run.finish`): the score; one test per question (name, score,
  max_score, visible, its result worded as in the feedback file with the hidden cases' details left out),
  and for a question that failed a hidden case one more test, unscored, ``after_due_date``, with those
  details; the whole feedback file as an ``after_due_date`` test; the run's notes, which say what held, as
  the top-level output.
* The zip carries the bank of its own exercise only (:func:`_bank_files`), loaded from ``/autograder/source``.
"""

from __future__ import annotations

import ast
import base64
import csv
import hashlib
import importlib.metadata
import io
import json
import os
import secrets
import stat
import sys
import tempfile
import time
import zipfile
from pathlib import Path
from typing import Any

from ... import __version__
from ..bank_loader import EXERCISES, load_bank
from ..intake.submissions import read_path
from ..output.report import format_question
from ..output.text import quoted
from ..results import NotebookResult
from ..run.asuser import STUDENT_USER
from ..spec import Exercise
from .gradescope_run import finish, isolate, write_results

__all__ = ["build_autograder", "run", "results_json", "wheel_name", "SETUP_SH", "RUN_AUTOGRADER"]

_PACKAGE_DIR = Path(__file__).resolve().parents[2]
_EPOCH = (1980, 1, 1, 0, 0, 0)
HIDDEN_MARK = "hidden case"

SETUP_SH = """#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (puma-course {version}).
set -euo pipefail
cd "$(dirname "$0")"
python3 -m venv ${{PUMA_VENV_OPTIONS:-}} /autograder/puma-venv || {{
    apt-get update && apt-get install -y python3-venv && python3 -m venv ${{PUMA_VENV_OPTIONS:-}} /autograder/puma-venv
}}
/autograder/puma-venv/bin/python -m pip install --disable-pip-version-check --no-cache-dir ${{PUMA_PIP_OPTIONS:-}} \\
    "./dist/{wheel}"
/autograder/puma-venv/bin/python -c \\
    "import importlib.metadata as m; v = m.version('puma-course'); assert v == '{version}', v"
# the user every notebook runs as, never root (PUMA_STUDENT_UID: its uid, if the image needs a fixed one)
id -u {user} >/dev/null 2>&1 || useradd --system --user-group --no-create-home --shell /usr/sbin/nologin \\
    ${{PUMA_STUDENT_UID:+--uid "$PUMA_STUDENT_UID"}} {user}
# the grader's full package, its record and this folder (the wheel, the bank): root's alone
PKG=$(/autograder/puma-venv/bin/python -I -c \\
    "import importlib.util as u; print(u.find_spec('puma_course').submodule_search_locations[0])")
chmod -R go-rwx "$PKG" "$(dirname "$PKG")"/puma_course-*.dist-info /autograder/source
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for every submission, in /autograder (puma-course {version}, exercise {exercise}).
PY=python3
if [ -x /autograder/puma-venv/bin/python ]; then PY=/autograder/puma-venv/bin/python; fi
exec "$PY" -m puma_course.grading.publish.gradescope /autograder
"""


def wheel_name(version: str = __version__) -> str:
    """The wheel's file name (PEP 427).

    >>> wheel_name("0.2.0")
    'puma_course-0.2.0-py3-none-any.whl'
    """
    return f"puma_course-{version}-py3-none-any.whl"


#: The bank/__init__.py of an autograder: it registers the zip's own exercise only.
BANK_INIT = '''"""The question bank of this autograder: {exercise} alone (puma-course {version} built it)."""

from puma_course.grading.bank_loader import register

from . import {exercise} as _exercise

register(_exercise.EXERCISE)
'''


def _bank_files(course: Path, exercise: str | None = None) -> dict[str, bytes]:
    """The course's question bank, as zip paths -> bytes, shipped under ``bank/``.

    With ``exercise``: that exercise's module (``bank/<exercise>.py``), the bank's modules it imports, and theirs
    (its private helpers: ``_keys``, ``_reference``, ...), with a ``bank/__init__.py`` registering it alone (the
    bank's own is left out); without, or when the bank has no ``<exercise>.py``, the whole bank. The bank lives
    in the course folder (``bank/``, beside ``solutions/``), never in the package; ``run_autograder`` loads it
    from ``/autograder/source/bank``, which only root can read (``setup.sh``).
    """
    folder = Path(course) / "bank"
    if not folder.is_dir():
        return {}
    if exercise is not None and (folder / f"{exercise}.py").is_file():
        mine = sorted(_imported(folder, exercise))
        files = {f"bank/{p.relative_to(folder).as_posix()}": p.read_bytes() for p in mine}
        files["bank/__init__.py"] = BANK_INIT.format(exercise=exercise, version=__version__).encode()
        return files
    return {
        f"bank/{p.relative_to(folder).as_posix()}": p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and "__pycache__" not in p.parts and not p.name.endswith(".pyc")
    }


def _imported(folder: Path, exercise: str) -> set[Path]:
    """The files of the bank at ``folder`` that ``<exercise>.py`` imports, and those they import (relative imports,
    or absolute ones of the bank's package name), with the ``__init__.py`` of every package between them."""
    from ..bank_loader import BANK_MODULE

    seen: set[Path] = set()
    todo = [folder / f"{exercise}.py"]
    while todo:
        path = todo.pop()
        if path in seen or not path.is_file() or folder not in path.parents or path == folder / "__init__.py":
            continue  # the bank's own __init__ imports every exercise: the zip has one of its own
        seen.add(path)
        todo += [p / "__init__.py" for p in path.parents if folder in p.parents]
        for node in ast.walk(ast.parse(path.read_bytes(), str(path))):
            if isinstance(node, ast.ImportFrom):
                parts, names = (node.module or "").split("."), [a.name for a in node.names]
                if node.level:
                    todo += _candidates(path.parents[node.level - 1].joinpath(*filter(None, parts)), names)
                elif parts[0] == BANK_MODULE:
                    todo += _candidates(folder.joinpath(*parts[1:]), names)
            elif isinstance(node, ast.Import):
                for parts in (a.name.split(".") for a in node.names):
                    if parts[0] == BANK_MODULE:
                        todo += _candidates(folder.joinpath(*parts[1:]), [])
    return seen


def _candidates(target: Path, names: list[str]) -> list[Path]:
    """The files ``from <target> import <names>`` may read: the module, the package, and submodules of that name."""
    found = [target.with_suffix(".py"), target / "__init__.py"]
    return found + [target / f"{n}.py" for n in names] + [target / n / "__init__.py" for n in names]


def _record_hash(data: bytes) -> str:
    return "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()


def _wheel_bytes(version: str) -> bytes:
    """A wheel of the installed package: every file of ``puma_course/`` (no caches), its metadata, RECORD."""
    files: dict[str, bytes] = {}
    for p in sorted(_PACKAGE_DIR.rglob("*")):
        if p.is_file() and "__pycache__" not in p.parts and p.suffix not in (".pyc", ".pyo"):
            files[f"puma_course/{p.relative_to(_PACKAGE_DIR).as_posix()}"] = p.read_bytes()
    try:
        requires = importlib.metadata.requires("puma-course") or []
    except importlib.metadata.PackageNotFoundError:  # pragma: no cover - run from a plain checkout
        requires = []
    info = f"puma_course-{version}.dist-info"
    meta = ["Metadata-Version: 2.1", "Name: puma-course", f"Version: {version}", "Requires-Python: >=3.10"]
    meta += [f"Requires-Dist: {r}" for r in requires if "extra ==" not in r]
    files[f"{info}/METADATA"] = ("\n".join(meta) + "\n").encode()
    files[f"{info}/WHEEL"] = b"Wheel-Version: 1.0\nGenerator: puma-course\nRoot-Is-Purelib: true\nTag: py3-none-any\n"
    files[f"{info}/entry_points.txt"] = b"[console_scripts]\npuma-course = puma_course.cli:main\n"
    record = io.StringIO()
    writer = csv.writer(record, lineterminator="\n")
    for name, data in files.items():
        writer.writerow([name, _record_hash(data), len(data)])
    writer.writerow([f"{info}/RECORD", "", ""])
    files[f"{info}/RECORD"] = record.getvalue().encode()
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for name, data in files.items():
            _put(zf, name, data)
    return buf.getvalue()


def _put(zf: zipfile.ZipFile, name: str, data: bytes, executable: bool = False) -> None:
    info = zipfile.ZipInfo(name, _EPOCH)
    info.external_attr = ((0o755 if executable else 0o644) | stat.S_IFREG) << 16
    info.compress_type = zipfile.ZIP_DEFLATED
    zf.writestr(info, data)


def build_autograder(course: str | os.PathLike[str], exercise: str, output: str | os.PathLike[str]) -> str:
    """Write the autograder zip of ``exercise`` to ``output``; return a few lines saying what is in it."""
    if exercise not in EXERCISES:
        raise ValueError(f"exercise: expected one of {sorted(EXERCISES)}, got {exercise!r}")
    version = __version__
    wheel = wheel_name(version)
    config = {"exercise": exercise, "version": version, "wheel": wheel}
    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    bank = _bank_files(Path(course), exercise)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        _put(zf, "setup.sh", SETUP_SH.format(version=version, wheel=wheel, user=STUDENT_USER).encode(), executable=True)
        _put(zf, "run_autograder", RUN_AUTOGRADER.format(version=version, exercise=exercise).encode(), True)
        _put(zf, "autograder.json", (json.dumps(config, indent=1) + "\n").encode())
        _put(zf, f"dist/{wheel}", _wheel_bytes(version))
        for name, data in bank.items():
            _put(zf, name, data)
    size = out.stat().st_size
    return (
        f"wrote {out} ({size / 1e6:.1f} MB): setup.sh, run_autograder, dist/{wheel}"
        + (f", bank/ ({len(bank)} files)" if bank else "")
        + f"\nupload it as the autograder of the Gradescope assignment for {exercise} "
        "(Ubuntu base image; students submit "
        f"{exercise}.ipynb)"
    )


def _find_notebook(folder: Path, exercise: str) -> tuple[Path | None, str]:
    found = sorted(
        p for p in folder.rglob("*") if p.name.lower().endswith(".ipynb") and ".ipynb_checkpoints" not in p.parts
    )
    exact = [p for p in found if p.name == f"{exercise}.ipynb"]
    if exact:
        return exact[0], ""
    if len(found) == 1:
        return found[0], f"graded {quoted(found[0].name, 80)} as {exercise}.ipynb"
    if not found:
        return None, f"no notebook was submitted: upload {exercise}.ipynb"
    names = ", ".join(quoted(p.name, 80) for p in found[:5])  # the student's names: one line each, bounded
    return None, f"{len(found)} notebooks were submitted ({names}) and none is named {exercise}.ipynb: upload that one"


def _public_text(q: Any, earned: float, notes: list[str]) -> tuple[str, list[str]]:
    hidden = [n for n in notes if n.startswith(HIDDEN_MARK)]
    shown = [n for n in notes if not n.startswith(HIDDEN_MARK)]
    if hidden:
        shown.append(f"{len(hidden)} hidden-case failure(s): the inputs are shown after the due date")
    return format_question(q, earned, shown), hidden


def results_json(
    result: NotebookResult, exercise: Exercise, notes: list[str], feedback: str, seconds: float, extra: dict[str, Any]
) -> dict[str, Any]:
    """The results.json of one graded submission (see the module docstring)."""
    tests: list[dict[str, Any]] = []
    for i, q in enumerate(exercise.questions, 1):
        earned = result.scores.get(q.qid, 0.0)
        qnotes = result.question_notes.get(q.qid, [])
        text, hidden = _public_text(q, earned, qnotes)
        name = f"{q.qid} {q.function}" + (" (bonus)" if q.bonus else "")
        tests.append(
            {
                "name": name,
                "number": str(i),
                "score": earned,
                "max_score": 0.0 if q.bonus else float(q.points),
                "output": text,
                "visibility": "visible",
            }
        )
        if hidden:
            tests.append(
                {
                    "name": f"{name}: hidden cases",
                    "number": f"{i}.h",
                    "output": format_question(q, earned, qnotes),
                    "visibility": "after_due_date",
                }
            )
    tests.append({"name": "Feedback file", "output": feedback, "output_format": "md", "visibility": "after_due_date"})
    return {
        "score": result.score,
        "execution_time": max(0, round(seconds)),
        "output": "\n".join(notes),
        "visibility": "visible",
        "stdout_visibility": "hidden",
        "extra_data": extra,
        "tests": tests,
    }


def run(root: str | os.PathLike[str] = "/autograder") -> dict[str, Any]:
    """Grade ``<root>/submission`` as ``<root>/source/autograder.json`` says; write and return results.json.

    Should the grader itself fail, results.json still appears: score 0 and the error, for the instructor.
    """
    try:
        return _run(Path(root))
    except Exception as exc:  # noqa: BLE001 - Gradescope must get a results.json whatever happens
        out = {"score": 0.0, "output": f"the autograder failed ({type(exc).__name__}: {exc}); ask your instructor"}
        out["tests"] = []
        write_results(Path(root), out)
        raise


def _forget_bank(source: Path) -> None:
    """Import every module of the bank at ``source/bank`` (already loaded), then delete its files: nothing needs them
    any more (Gradescope runs each submission in a fresh container), and a file gone cannot be read."""
    import importlib
    import pkgutil
    import shutil

    from ..bank_loader import BANK_MODULE

    for info in pkgutil.walk_packages([str(source / "bank")], prefix=BANK_MODULE + "."):
        importlib.import_module(info.name)
    shutil.rmtree(source / "bank", ignore_errors=True)


def _run(base: Path) -> dict[str, Any]:
    from ..run.runner import grade

    start = time.perf_counter()
    iso = isolate(base)  # before anything else: the grader's files root's alone, the student's user checked
    config = json.loads((base / "source" / "autograder.json").read_text(encoding="utf-8"))
    name = config["exercise"]
    load_bank(base / "source")  # the zip's bank: this exercise's module and its helpers (root's alone)
    exercise = EXERCISES[name]
    notes: list[str] = []
    if iso.refused:
        out = {"score": 0.0, "output": f"not graded: {iso.refused}. Ask your instructor.", "tests": []}
        write_results(base, out)
        return out
    if config.get("version") != __version__:
        notes.append(f"WARNING: the zip was built by puma-course {config.get('version')}, this is {__version__}")
    path, said = _find_notebook(base / "submission", name)
    if said:
        notes.append(said)
    box = iso.box
    notes += iso.notes
    _forget_bank(base / "source")
    seed = secrets.randbits(31)
    with tempfile.TemporaryDirectory(prefix="puma-gradescope-") as tmp:
        sub = Path(tmp) / "submissions" / "submission"
        sub.mkdir(parents=True)
        if path is not None:
            nb = read_path(path)
            if nb.data is not None:
                (sub / f"{name}.ipynb").write_bytes(nb.data)
            elif nb.note:
                notes.append(nb.note)
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            results = grade(
                sub.parent,
                Path(tmp) / "grades.csv",
                feedback=Path(tmp) / "feedback",
                jobs=1,
                seed=seed,
                exercises=[name],
                sandbox=box,
                private=[base / "source", base / "submission", base / "results"],
            )
        result = results[0]
        feedback = next((Path(tmp) / "feedback").glob("*.md")).read_text(encoding="utf-8")
    notes += [f"status: {result.status}", *result.notes]
    notes.append(f"{name}: {result.score:g} / {result.max_score:g} points")
    extra = {"exercise": name, "status": result.status, "version": __version__, "seed": seed}
    extra["sandbox"] = box.kind
    out = finish(iso, base, results_json(result, exercise, notes, feedback, time.perf_counter() - start, extra))
    print(out["output"])
    return out


if __name__ == "__main__":  # pragma: no cover - what run_autograder runs
    run(sys.argv[1] if len(sys.argv) > 1 else "/autograder")
