"""A Gradescope autograder: the zip ``puma-course gradescope`` builds, and the run inside Gradescope's container.

The zip follows Gradescope's autograder specification (gradescope-autograders.readthedocs.io, "Autograder
Specifications"): ``setup.sh`` and ``run_autograder`` at its root; Gradescope unpacks it into
``/autograder/source``, runs ``setup.sh`` once when it builds the image, copies ``run_autograder`` to
``/autograder/run_autograder`` and runs it, in ``/autograder``, for each submission, which it puts in
``/autograder/submission``; ``run_autograder`` must write ``/autograder/results/results.json``.

* ``setup.sh`` makes a virtual environment ``/autograder/puma-venv`` and installs into it the wheel of
  this package that the zip carries (``dist/puma_course-<version>-py3-none-any.whl``: the version that
  built the zip, so the grader is pinned to it), with its dependencies from the package index the
  image's pip uses; nothing else is downloaded. ``PUMA_PIP_OPTIONS`` adds pip options (the tests
  install offline with ``--no-index``).
* ``run_autograder`` runs ``python -m puma_course.grading.gradescope``: :func:`run` grades the
  submitted notebook (``<exercise>.ipynb``, or the only notebook submitted) as ``puma-course grade``
  does, with the course's question bank, and writes ``results.json``: the score; one test per
  question (name, score, max_score, visible, its result worded as in the feedback file with the
  hidden cases' details left out), and for a question that failed a hidden case one more test, unscored,
  ``after_due_date``, with those details; the whole feedback file as an ``after_due_date`` test; the
  run's notes as the top-level output.
* The course's bank goes in the zip through :func:`_bank_files` and is loaded from ``/autograder/source``.

Gradescope's container may not allow the user namespaces bubblewrap needs: the run then grades without
the operating-system sandbox, and says so in the output everyone sees. The answer key stays out of the
student's process as in every grading run: the worker imports only the student-side package.
"""

from __future__ import annotations

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

from .. import _version
from .model import EXERCISES, Exercise, NotebookResult, load_bank
from .output.report import format_question
from .run.submissions import read_path

__all__ = ["build_autograder", "run", "results_json", "wheel_name", "SETUP_SH", "RUN_AUTOGRADER"]

_PACKAGE_DIR = Path(__file__).resolve().parents[1]
_EPOCH = (1980, 1, 1, 0, 0, 0)
HIDDEN_MARK = "hidden case"

SETUP_SH = """#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (puma-course {version}).
set -euo pipefail
cd "$(dirname "$0")"
python3 -m venv /autograder/puma-venv || {{
    apt-get update && apt-get install -y python3-venv && python3 -m venv /autograder/puma-venv
}}
/autograder/puma-venv/bin/python -m pip install --disable-pip-version-check --no-cache-dir ${{PUMA_PIP_OPTIONS:-}} \\
    "./dist/{wheel}"
/autograder/puma-venv/bin/python -c \\
    "import importlib.metadata as m; v = m.version('puma-course'); assert v == '{version}', v"
"""

RUN_AUTOGRADER = """#!/usr/bin/env bash
# Gradescope runs this for every submission, in /autograder (puma-course {version}, exercise {exercise}).
PY=python3
if [ -x /autograder/puma-venv/bin/python ]; then PY=/autograder/puma-venv/bin/python; fi
exec "$PY" -m puma_course.grading.gradescope /autograder
"""


def wheel_name(version: str = _version.__version__) -> str:
    """The wheel's file name (PEP 427).

    >>> wheel_name("0.2.0")
    'puma_course-0.2.0-py3-none-any.whl'
    """
    return f"puma_course-{version}-py3-none-any.whl"


def _bank_files(course: Path) -> dict[str, bytes]:
    """The course's question bank, as zip paths -> bytes, shipped under ``bank/``.

    The bank lives in the course folder (``bank/``, beside ``solutions/``), never in the package, so it is
    shipped whole; ``run_autograder`` loads it from ``/autograder/source/bank``. The zip is made by the
    instructor, so the key may be in it; the student's process never sees it (hidden by the OS sandbox,
    or taken off the container's disk before any student code runs where there is none).
    """
    folder = Path(course) / "bank"
    if not folder.is_dir():
        return {}
    return {
        f"bank/{p.relative_to(folder).as_posix()}": p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and "__pycache__" not in p.parts and not p.name.endswith(".pyc")
    }


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
    version = _version.__version__
    wheel = wheel_name(version)
    config = {"exercise": exercise, "version": version, "wheel": wheel}
    out = Path(output)
    out.parent.mkdir(parents=True, exist_ok=True)
    bank = _bank_files(Path(course))
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        _put(zf, "setup.sh", SETUP_SH.format(version=version, wheel=wheel).encode(), executable=True)
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
        return found[0], f"graded {found[0].name} as {exercise}.ipynb"
    if not found:
        return None, f"no notebook was submitted: upload {exercise}.ipynb"
    names = ", ".join(p.name for p in found[:5])
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
        _write(Path(root), out)
        raise


def _write(base: Path, out: dict[str, Any]) -> None:
    results_dir = base / "results"
    results_dir.mkdir(parents=True, exist_ok=True)
    tmp = results_dir / ".results.json.tmp"
    tmp.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    os.replace(tmp, results_dir / "results.json")


def _forget_bank(source: Path) -> None:
    """Import every module of the bank at ``source/bank`` (already loaded), then delete its files: without the
    OS sandbox, a student's process could otherwise read the answer key from the container's disk. Gradescope
    runs each submission in a fresh container, so nothing else needs them."""
    import importlib
    import pkgutil
    import shutil

    from .model import BANK_MODULE

    for info in pkgutil.walk_packages([str(source / "bank")], prefix=BANK_MODULE + "."):
        importlib.import_module(info.name)
    shutil.rmtree(source / "bank", ignore_errors=True)


def _run(base: Path) -> dict[str, Any]:
    from .run.runner import grade
    from .run.sandbox import choose

    start = time.perf_counter()
    config = json.loads((base / "source" / "autograder.json").read_text(encoding="utf-8"))
    name = config["exercise"]
    load_bank(base / "source")  # the course's bank, shipped in the zip (never in the student's process)
    exercise = EXERCISES[name]
    notes: list[str] = []
    if config.get("version") != _version.__version__:
        notes.append(
            f"WARNING: the zip was built by puma-course {config.get('version')}, this is {_version.__version__}"
        )
    path, said = _find_notebook(base / "submission", name)
    if said:
        notes.append(said)
    box = choose("auto")
    if box.kind != "bwrap":
        notes.append(
            f"Graded WITHOUT the operating-system sandbox ({box.reason}): this container does not allow it. "
            "Your code ran in its own process, with time and memory limits, against a package without the answer key."
        )
        _forget_bank(base / "source")  # nothing hides the folder from the student's process: take it off the disk
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
    extra = {"exercise": name, "status": result.status, "version": _version.__version__, "seed": seed}
    extra["sandbox"] = box.kind
    out = results_json(result, exercise, notes, feedback, time.perf_counter() - start, extra)
    _write(base, out)
    print("\n".join(notes))
    return out


if __name__ == "__main__":  # pragma: no cover - what run_autograder runs
    run(sys.argv[1] if len(sys.argv) > 1 else "/autograder")
