"""The grader's side: plan the calls, run each notebook in a fresh child process, score what comes back.

:func:`grade` grades ``SUBMISSIONS/<student>/<exercise>.ipynb`` for a class: it computes every
expected value first (:func:`make_plan`, in this process), reads every submitted file into memory
before any student code runs, then grades each notebook with :func:`grade_notebook`: a fresh
``python -I`` child (:mod:`puma_course.grading.worker`) in a temporary folder, with a time limit
per cell, per call and per notebook, gets the code cells and the calls (never the expected
values) through a pipe and sends back only the numbers the student's functions return. The
comparison happens here. Results go to a CSV and feedback files (:mod:`puma_course.grading.report`).
"""

from __future__ import annotations

import concurrent.futures
import copy
import json
import os
import secrets
import subprocess
import sys
import tempfile
import threading
import time
import warnings
import zlib
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .model import EXERCISES, Exercise, NotebookResult, Question, Verdict, score_question
from .report import feedback_markdown, safe_name, write_csv

__all__ = ["GradingIntegrityWarning", "make_plan", "grade_notebook", "grade", "MAX_NOTEBOOK_BYTES", "PACKAGE_PARENT"]

MAX_NOTEBOOK_BYTES = 20_000_000
MAX_OUTPUT_BYTES = 8_000_000

#: The folder that holds the ``puma_course`` package (not the course's folder): put first on the
#: child's ``sys.path`` so that the child imports this very package, installed or not.
PACKAGE_PARENT = Path(__file__).resolve().parents[2]
_PACKAGE_DIR = PACKAGE_PARENT / "puma_course"
#: The child's whole program (run with ``python -I -c``): this package first on the path, then the worker.
CHILD_BOOTSTRAP = (
    f"import sys; sys.path.insert(0, {str(PACKAGE_PARENT)!r}); from puma_course.grading.worker import main; main()"
)


class GradingIntegrityWarning(UserWarning):
    """The course package's files changed while grading: a submission may have tampered with them."""


def _package_digest() -> dict[str, bytes]:
    """The bytes of every module of the package, by path inside it."""
    return {p.relative_to(_PACKAGE_DIR).as_posix(): p.read_bytes() for p in sorted(_PACKAGE_DIR.rglob("*.py"))}


def _jsonable(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def make_plan(exercise: Exercise, seed: int) -> list[dict[str, Any]]:
    """Every call to make (public + hidden cases) with its expected value, computed here.

    Each question draws its hidden inputs from its own generator, seeded by ``seed`` and the
    question's name, so adding a question does not change the others' inputs.

    >>> from puma_course.grading import EXERCISES
    >>> calls = make_plan(EXERCISES["ex01_rotations"], seed=1)
    >>> calls[0]["qid"], calls[0]["function"], calls[0]["args"], calls[0]["expected"].shape
    ('q1', 'elementary_rotation', ['x', 0.3], (3, 3))

    ``expected`` is whatever the question's reference returns (an array for most questions; a
    question judged by equivalence may return what its judge needs) and ``call_args`` keeps the
    original arguments for the judge; neither ever reaches the student's process.
    """
    calls = []
    for q in exercise.questions:
        rng = np.random.default_rng([seed, zlib.crc32(f"{exercise.name}:{q.qid}".encode())])
        for case, args in enumerate(q.cases(rng)):
            expected = q.reference(*copy.deepcopy(args))
            if not callable(expected):
                expected = np.asarray(expected, dtype=float) if not isinstance(expected, dict) else expected
            calls.append(
                {
                    "qid": q.qid,
                    "case": case,
                    "function": q.function,
                    "args": [_jsonable(a) for a in args],
                    "expected": expected,
                    "call_args": tuple(args),
                }
            )
    return calls


def _load(path: Path) -> bytes:
    size = path.stat().st_size
    if size > MAX_NOTEBOOK_BYTES:
        raise ValueError(f"the file is {size} bytes, more than {MAX_NOTEBOOK_BYTES}")
    return path.read_bytes()


def _parse_cells(data: bytes) -> list[str]:
    """The code cells of a notebook's bytes, or ValueError saying why they cannot be read."""
    import nbformat

    try:
        nb = nbformat.reads(data.decode("utf-8", errors="replace"), as_version=4)
    except Exception as exc:  # noqa: BLE001 - nbformat raises many kinds
        raise ValueError(f"not a readable notebook ({type(exc).__name__}: {str(exc)[:150]})") from None
    cells = nb.get("cells")
    if not isinstance(cells, list):
        raise ValueError("the notebook has no list of cells")
    sources = []
    for cell in cells:
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        src = cell.get("source", "")
        if isinstance(src, list):
            src = "".join(str(s) for s in src)
        if not isinstance(src, str):
            raise ValueError("a code cell's source is not text")
        sources.append(src)
    return sources


def _child_env(workdir: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k in ("PATH", "LANG", "LC_ALL", "SYSTEMROOT", "TMPDIR")}
    env.update(
        HOME=workdir,
        MPLBACKEND="Agg",
        MPLCONFIGDIR=workdir,
        PYTHONHASHSEED="0",
        OMP_NUM_THREADS="1",
        OPENBLAS_NUM_THREADS="1",
        MKL_NUM_THREADS="1",
        PYTHONDONTWRITEBYTECODE="1",
    )
    return env


def _drain(stream: Any, cap: int, sink: list[bytes], overflow: list[bool]) -> None:
    kept = 0
    while True:
        chunk = stream.read(65536)
        if not chunk:
            return
        if kept < cap:
            sink.append(chunk[: cap - kept])
            kept += len(sink[-1])
        if kept >= cap:
            overflow[0] = True


def _run_child(
    cells: list[str],
    calls: list[dict[str, Any]],
    workdir: str,
    timeout_cell: float,
    timeout_total: float,
    forbidden: dict[str, list[str]] | None = None,
) -> tuple[list[dict[str, Any]], bool, int | None, bool]:
    """Run the worker; return (events, timed_out, returncode, output_overflow)."""
    job = json.dumps(
        {"cells": cells, "calls": calls, "timeout_cell": timeout_cell, "max_size": 10_000, "forbidden": forbidden or {}}
    )
    kwargs: dict[str, Any] = {}
    if os.name == "posix":
        kwargs.update(start_new_session=True)  # its own process group, killed as a whole
    proc = subprocess.Popen(
        [sys.executable, "-I", "-c", CHILD_BOOTSTRAP],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        cwd=workdir,
        env=_child_env(workdir),
        **kwargs,
    )
    sink: list[bytes] = []
    overflow = [False]
    reader = threading.Thread(target=_drain, args=(proc.stdout, MAX_OUTPUT_BYTES, sink, overflow), daemon=True)
    reader.start()
    try:
        assert proc.stdin is not None
        proc.stdin.write(job.encode())
        proc.stdin.close()
    except (BrokenPipeError, OSError):
        pass
    timed_out = False
    try:
        proc.wait(timeout=timeout_total)
    except subprocess.TimeoutExpired:
        timed_out = True
    if timed_out or os.name == "posix":
        # kill the whole session: a student's code may have started children of its own
        try:
            os.killpg(proc.pid, 9) if os.name == "posix" else proc.kill()
        except (ProcessLookupError, PermissionError, OSError):
            pass
        if timed_out:
            proc.wait()
    reader.join(timeout=5)
    if not reader.is_alive() and proc.stdout is not None:
        proc.stdout.close()
    events = []
    for line in b"".join(sink).splitlines():
        try:
            event = json.loads(line)
        except (ValueError, UnicodeDecodeError):
            continue
        if isinstance(event, dict):
            events.append(event)
    return events, timed_out, proc.returncode, overflow[0]


def _judge(q: Question, event: dict[str, Any] | None, expected: Any, args: tuple[Any, ...]) -> Verdict:
    """The verdict on the child's answer to one call (its event): right, or the reason for the student."""
    if event is None:
        return Verdict("no answer came back (the notebook stopped before this call)")
    if "error" in event:
        return Verdict(str(event["error"])[:300])
    if "value" not in event:
        return Verdict("no value came back")
    try:
        return q.judge(event["value"], expected, args)
    except Exception as exc:  # noqa: BLE001 - a bizarre value must not stop the grading
        return Verdict(f"could not compare the value ({type(exc).__name__})")


def grade_notebook(
    path: str | os.PathLike[str] | None,
    exercise: Exercise,
    student: str = "",
    seed: int = 0,
    timeout_cell: float = 10.0,
    timeout_total: float = 60.0,
    plan: list[dict[str, Any]] | None = None,
    data: bytes | None = None,
) -> NotebookResult:
    """Grade one submitted notebook (``path`` None or absent: status "missing").

    ``plan`` is the exercise's :func:`make_plan` for ``seed`` (computed here when None). The file is
    read once (or ``data`` holds its bytes, read earlier); the child gets its code cells through
    a pipe and runs in a fresh temporary directory holding a copy, so the submission is never
    modified and nothing written to disk while grading can change what is graded.
    """
    start = time.perf_counter()
    if path is None or (data is None and not Path(path).is_file()):
        return NotebookResult.blank(student, exercise, "missing", f"no file {exercise.name}.ipynb was submitted")
    path = Path(path)
    try:
        if data is None:
            data = _load(path)
        cells = _parse_cells(data)
    except (ValueError, OSError) as exc:
        return NotebookResult.blank(student, exercise, "malformed", str(exc))
    result = NotebookResult.blank(student, exercise)
    calls_plan = make_plan(exercise, seed) if plan is None else plan
    # the child gets what to call, never what is expected
    child_calls = [{k: v for k, v in item.items() if k not in ("expected", "call_args")} for item in calls_plan]
    with tempfile.TemporaryDirectory(prefix="puma-grade-") as workdir:
        (Path(workdir) / path.name).write_bytes(data)
        forbidden = {q.qid: list(q.forbidden) for q in exercise.questions if q.forbidden}
        events, timed_out, returncode, overflow = _run_child(
            cells, child_calls, workdir, timeout_cell, timeout_total, forbidden
        )
    done = any(e.get("kind") == "done" for e in events)
    for e in events:
        if e.get("kind") == "cell" and e.get("status") in ("error", "timeout"):
            result.notes.append(f"code cell {int(e.get('index', -1)) + 1}: {str(e.get('error', ''))[:300]}")
    got: dict[tuple[str, Any], dict[str, Any]] = {}
    for e in events:
        if e.get("kind") == "call":
            got.setdefault((str(e.get("qid")), e.get("case")), e)
    outcomes: dict[str, list[tuple[str, str | None]]] = {q.qid: [] for q in exercise.questions}
    for item in calls_plan:
        q = exercise.question(item["qid"])
        kind = "public case" if item["case"] < len(q.public) else "hidden case"
        verdict = _judge(q, got.get((q.qid, item["case"])), item["expected"], item.get("call_args", ()))
        outcomes[q.qid].append((f"{kind} {item['case'] + 1}", verdict.reason))
        if verdict.mistake is not None:
            result.mistakes.setdefault(q.qid, []).append(verdict.mistake)
    for q in exercise.questions:
        result.scores[q.qid], result.question_notes[q.qid] = score_question(q.points, outcomes[q.qid])
    if timed_out:
        result.status = "timeout"
        result.notes.append(
            f"the notebook ran longer than {timeout_total:g} s in total and was stopped; "
            "answers that came back before that were graded"
        )
    elif not done:
        result.status = "crashed"
        result.notes.append(
            f"the notebook's process ended early (exit code {returncode}); "
            "answers that came back before that were graded"
        )
    elif any(e.get("kind") == "cell" and e.get("status") != "ok" for e in events):
        result.status = "cell-error"
    if overflow:
        result.notes.append("the notebook wrote too much output; the rest was discarded")
    result.seconds = time.perf_counter() - start
    return result


def grade(
    submissions: str | os.PathLike[str],
    output: str | os.PathLike[str],
    feedback: str | os.PathLike[str] | None = None,
    jobs: int = 2,
    timeout_cell: float = 10.0,
    timeout_total: float = 60.0,
    seed: int | None = None,
    exercises: Sequence[str] | None = None,
    progress: Callable[[NotebookResult], None] | None = None,
) -> list[NotebookResult]:
    """Grade ``submissions/<student>/<exercise>.ipynb`` for every student folder and exercise.

    Writes ``output`` (CSV: student, exercise, score, max_score, one column per
    question id, status, notes) and, if ``feedback`` is given, one Markdown file
    per student. Returns the results (sorted by student, exercise).
    """
    sub_dir = Path(submissions)
    if not sub_dir.is_dir():
        raise ValueError(f"submissions: expected a folder with one sub-folder per student, got {str(sub_dir)!r}")
    names = list(exercises) if exercises else list(EXERCISES)
    for name in names:
        if name not in EXERCISES:
            raise ValueError(f"exercises: expected names among {sorted(EXERCISES)}, got {name!r}")
    seed = secrets.randbits(31) if seed is None else int(seed)
    students = sorted(p.name for p in sub_dir.iterdir() if p.is_dir() and not p.name.startswith("."))
    plans = {name: make_plan(EXERCISES[name], seed) for name in names}  # every expected value, before any child runs
    package_before = _package_digest()
    # read every file into memory before any student code runs: a student's process
    # cannot alter what is graded for anyone, itself included
    tasks = []
    for student in students:
        for name in names:
            path = sub_dir / student / f"{name}.ipynb"
            data: bytes | Exception | None = None
            if path.is_file():
                try:
                    data = _load(path)
                except (ValueError, OSError) as exc:
                    data = exc
            tasks.append((student, name, path, data))

    def work(task: tuple[str, str, Path, bytes | Exception | None]) -> NotebookResult:
        student, name, path, data = task
        ex = EXERCISES[name]
        try:
            if isinstance(data, Exception):
                res = NotebookResult.blank(student, ex, "malformed", str(data))
            else:
                res = grade_notebook(
                    path if data is not None else None,
                    ex,
                    student,
                    seed,
                    timeout_cell,
                    timeout_total,
                    plans[name],
                    data=data,
                )
        except Exception as exc:  # noqa: BLE001 - one broken submission must not stop the class
            res = NotebookResult.blank(
                student, ex, "grader-error", f"the grader failed on this notebook: {type(exc).__name__}: {exc}"
            )
        if progress is not None:
            progress(res)
        return res

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, int(jobs))) as pool:
        results = list(pool.map(work, tasks))
    results.sort(key=lambda r: (r.student, r.exercise))
    package_after = _package_digest()
    changed = sorted(
        k for k in set(package_before) | set(package_after) if package_before.get(k) != package_after.get(k)
    )
    if changed:
        warnings.warn(
            f"the puma_course package files changed while grading ({', '.join(changed)}); a submission "
            "may have tampered with them, so the grades of notebooks graded afterwards are not reliable. "
            "Grade in a container or as a user who cannot write the package.",
            GradingIntegrityWarning,
            stacklevel=2,
        )
    write_csv(output, results, names)
    for r in results:
        if r.status == "missing":
            others = sorted(p.name for p in (sub_dir / r.student).glob("*.ipynb") if p.stem not in EXERCISES)
            if others:
                r.notes.append(
                    f"notebooks found under other names: {', '.join(others)} (name the file exactly {r.exercise}.ipynb)"
                )
    if feedback is not None:
        fb_dir = Path(feedback)
        fb_dir.mkdir(parents=True, exist_ok=True)
        used: set[str] = set()
        for student in students:
            mine = [r for r in results if r.student == student]
            stem = safe_name(student)
            while stem in used:  # two folder names that sanitise alike
                stem += "_"
            used.add(stem)
            (fb_dir / f"{stem}.md").write_text(feedback_markdown(student, mine, seed), encoding="utf-8")
    return results
