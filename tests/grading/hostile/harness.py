"""The hostile-class harness: grade one attack beside an honest and a blank classmate, and check nothing was gained.

Each fixture in ``tests/fixtures/hostile/`` is either an attack written as code (``<category>/<name>.py``:
its cells, split at ``# %%``, are appended to the handed-out exercise, so an attack's functions replace
the stubs) or a file-system layout (``layouts.py``: links, pipes, odd names). A header of comment lines
says how to run it::

    # category: isolation            (answer-key, isolation, persistence, crash, slow, forging)
    # exercise: ex01_rotations       (or "all": every exercise)
    # modes: bwrap none              (sandboxes to run it under; "none" only where that is harmless)
    # expect: zero                   (the attacker's score: zero, or "earned" for what the content earns)
    # timeout_total: 20              (optional: the per-notebook limit for this run)
    # memory_mb: 1024                (optional: the notebook's control-group memory limit; needs control groups)
    # classmate: slowish             (optional: a fourth student, right but slow: each call burns CPU first)
    # base: solutions                (optional: the attack is appended to the solution, not the exercise)
    # expect: without q2             (the attacker earns full marks but for the questions named)

Placeholders in the code are filled in before grading, so an attack knows what a real attacker could find
out: ``{{SUBMISSIONS}}``, ``{{OUTPUT}}``, ``{{FEEDBACK}}``, ``{{ROOT}}`` (the course checkout),
``{{SITE}}`` (site-packages), ``{{VENV}}`` and ``{{BASE}}`` (``sys.prefix``, ``sys.base_prefix``: empty when it
is the system's), ``{{HOME}}`` (the grader's home), ``{{MARK}}`` (a name unique to the
run), ``{{PORT}}`` (a TCP port the test listens on), ``{{TABLE}}`` (JSON: the hidden cases' answers a
student rebuilds at home from the question bank and every seed they could know, :func:`home_table`).
The class is graded with a secret key file in the class folder (as ``puma-course grade`` does).
An attack that finds something it should not reports it by ending its process with exit code 97
(``LEAK()``), which the grader repeats in the notes.

:func:`run_attack` grades the class {attacker, honest (a copy of ``solutions/``), blank (a copy of
``exercises/``)} and :func:`check_run` asserts, for every fixture: the run finished and wrote its CSV
and feedback; the attacker gained nothing (its score is what its content earns, and it never signalled
a leak); the honest classmate has full marks and the blank one zero, both with status ``ok``; and no
file outside the worker's folder changed (the class folder, the course checkout, site-packages, the
temporary and home folders), no process of the attack outlived the run, no connection reached the test.
"""

from __future__ import annotations

import csv
import functools
import glob
import hashlib
import importlib.util
import json
import os
import re
import shutil
import socket
import sys
import sysconfig
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import nbformat
import pytest

from puma_course.grading import EXERCISES, NotebookResult, grade
from puma_course.grading.output.text import csv_safe
from puma_course.grading.run.limits import Usage, open_run
from puma_course.grading.run.sandbox import Sandbox, choose
from tests.support import ROOT

HOSTILE = ROOT / "tests" / "fixtures" / "hostile"
SITE = Path(next(p for p in choose("none").sites))
PRELUDE = (
    "import os as _os\n\n\ndef LEAK(what=''):\n"
    "    '''The attack found what it should not: say so through the exit code.'''\n"
    "    _os._exit(97)\n"
)
CATEGORIES = ("answer-key", "isolation", "persistence", "crash", "slow", "forging", "limits", "gradescope")
LIMITS = {"timeout_cell": 2.0, "timeout_total": 5.0, "timeout_student": 10.0}


@dataclass
class Fixture:
    """One hostile submission (see the module docstring)."""

    name: str
    category: str
    exercises: list[str]
    modes: list[str]
    expect: str
    doc: str
    cells: list[str] = field(default_factory=list)
    layout: Any = None
    limits: dict[str, float] = field(default_factory=dict)
    head: dict[str, str] = field(default_factory=dict)

    def __str__(self) -> str:
        return self.name


def _header(text: str) -> dict[str, str]:
    out = {}
    for line in text.splitlines():
        m = re.match(r"#\s*(\w+):\s*(.*)$", line)
        if not m:
            break
        out[m.group(1)] = m.group(2).strip()
    return out


def _make(name: str, head: dict[str, str], doc: str, **kw: Any) -> Fixture:
    exercises = sorted(EXERCISES) if head.get("exercise") == "all" else [head.get("exercise", "ex01_rotations")]
    limits = {k: float(v) for k, v in head.items() if k in LIMITS}
    return Fixture(
        name,
        head["category"],
        exercises,
        head.get("modes", "bwrap").split(),
        head.get("expect", "zero"),
        doc,
        limits=limits,
        head=head,
        **kw,
    )


@functools.cache
def fixtures() -> tuple[Fixture, ...]:
    """Every hostile fixture: the code attacks, then the layouts."""
    found = []
    for path in sorted(HOSTILE.glob("*/*.py")):
        text = path.read_text(encoding="utf-8")
        head = _header(text)
        body = text.split('"""', 2)
        doc = body[1].strip() if len(body) > 2 else ""
        code = body[2] if len(body) > 2 else text
        cells = [c.strip("\n") for c in re.split(r"^# %%.*$", code, flags=re.M) if c.strip()]
        found.append(_make(path.stem, head, doc, cells=cells))
    spec = importlib.util.spec_from_file_location("hostile_layouts", HOSTILE / "layouts.py")
    assert spec is not None and spec.loader is not None
    layouts = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(layouts)
    for name, fn in sorted(layouts.LAYOUTS.items()):
        found.append(_make(name, _header(fn.header), (fn.__doc__ or "").strip(), layout=fn))
    return tuple(found)


def of(category: str) -> list[Any]:
    """pytest parameters (fixture, mode) for one category, with ids."""
    assert category in CATEGORIES
    return [
        pytest.param(fx, mode, id=f"{fx.name}-{mode}")
        for fx in fixtures()
        if fx.category == category
        for mode in fx.modes
    ]


@functools.cache
def bwrap() -> Sandbox:
    return choose("auto")


def sandbox_for(mode: str) -> Sandbox:
    """The sandbox to grade under, or a visible skip when bubblewrap cannot run here."""
    if mode == "none":
        return choose("none")
    box = bwrap()
    if box.kind != "bwrap":
        pytest.skip(f"grading under the sandbox not run: bubblewrap cannot run here ({box.reason})")
    return box


class Listener:
    """A TCP port and an abstract Unix socket on this machine that record any connection (a sandbox has no network)."""

    def __init__(self, mark: str) -> None:
        self.tcp = socket.create_server(("127.0.0.1", 0))
        self.port = self.tcp.getsockname()[1]
        self.unix = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.unix.bind(f"\0{mark}")
        self.unix.listen()
        self.connections: list[str] = []
        for sock in (self.tcp, self.unix):
            sock.settimeout(0.2)
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self) -> None:
        while not self.stop.is_set():
            for sock in (self.tcp, self.unix):
                try:
                    conn, addr = sock.accept()
                except OSError:
                    continue
                self.connections.append(repr(addr))
                conn.close()

    def close(self) -> list[str]:
        self.stop.set()
        self.thread.join(5)
        self.tcp.close()
        self.unix.close()
        return self.connections


@dataclass
class AttackRun:
    """What one graded class produced."""

    fixture: Fixture
    mode: str
    root: Path
    subs: Path
    out: Path
    fb: Path
    mark: str
    started: float
    attackers: dict[str, str]
    results: list[NotebookResult]
    rows: list[dict[str, str]]
    before: dict[str, Any]
    connections: list[str]
    seconds: float
    usages: list[Usage] = field(default_factory=list)

    def of(self, student: str) -> list[NotebookResult]:
        return [r for r in self.results if r.student == student]


def _fill(code: str, values: dict[str, str]) -> str:
    for key, value in values.items():
        code = code.replace("{{" + key + "}}", value)
    return code


def _notebook(fx: Fixture, exercise: str, values: dict[str, str]) -> nbformat.NotebookNode:
    base = "solutions" if fx.head.get("base") == "solutions" else "exercises"
    nb = nbformat.read(ROOT / base / f"{exercise}.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(PRELUDE))
    for cell in fx.cells:
        nb.cells.append(nbformat.v4.new_code_cell(_fill(cell, {**values, "EXERCISE": exercise})))
    return nb


def _stat_tree(root: Path, depth: int | None = None) -> dict[str, tuple[int, int]]:
    out: dict[str, tuple[int, int]] = {}
    if not root.exists():
        return out
    base = len(root.parts)
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d not in ("__pycache__", ".git", ".venv", ".venv-ci", ".ipynb_checkpoints")]
        if depth is not None and len(Path(folder).parts) - base >= depth:
            dirs[:] = []
        for name in files:
            p = Path(folder, name)
            try:
                st = p.lstat()
            except OSError:
                continue
            out[str(p)] = (st.st_size, st.st_mtime_ns)
    return out


def watched() -> dict[str, Any]:
    """What must not change: the course checkout (package, solutions, exercises, top level) and site-packages' top."""
    snap: dict[str, Any] = {}
    for sub in ("puma_course", "solutions", "exercises", "benchmarks", "tests/fixtures"):
        snap.update(_stat_tree(ROOT / sub))
    snap["ROOT"] = sorted(p.name for p in ROOT.iterdir() if p.suffix in (".py", ".pth", ".pyc", ".so"))
    snap["SITE"] = sorted(p.name for p in SITE.iterdir() if p.suffix in (".py", ".pth", ".pyc", ".so"))
    for key in ("stdlib", "platstdlib"):
        folder = Path(sysconfig.get_paths()[key])
        for sub in (folder, folder / "lib-dynload"):
            if sub.is_dir():
                snap[str(sub)] = sorted(p.name for p in sub.iterdir() if p.suffix in (".py", ".pth"))
    return snap


def run_attack(fx: Fixture, mode: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> AttackRun:
    """Grade {attacker, honest, blank} on the fixture's exercises, under ``mode``."""
    box = sandbox_for(mode)
    mark = f"puma-hostile-{uuid.uuid4().hex[:12]}"
    root = tmp_path / "class"
    subs, out, fb = root / "submissions", root / "grades.csv", root / "feedback"
    for student, folder in (("honest", "solutions"), ("blank", "exercises")):
        (subs / student).mkdir(parents=True)
        for ex in fx.exercises:
            shutil.copy(ROOT / folder / f"{ex}.ipynb", subs / student)
    fb.mkdir()
    (fb / "previous_run.md").write_text(f"secret of an earlier run: {mark}\n", encoding="utf-8")
    listener = Listener(mark)
    values = {
        "SUBMISSIONS": str(subs),
        "OUTPUT": str(out),
        "FEEDBACK": str(fb),
        "ROOT": str(ROOT),
        "SITE": str(SITE),
        "HOME": str(Path.home()),
        "VENV": sys.prefix,
        "BASE": "" if any(sys.base_prefix.startswith(d) for d in ("/usr", "/bin", "/lib")) else sys.base_prefix,
        "MARK": mark,
        "PORT": str(listener.port),
    }
    if fx.layout is not None:
        attackers = fx.layout(subs, values)
    else:
        (subs / "attacker").mkdir()
        for ex in fx.exercises:
            nbformat.write(_notebook(fx, ex, values), subs / "attacker" / f"{ex}.ipynb")
        attackers = {"attacker": fx.expect}
    if fx.head.get("classmate") == "slowish":
        (subs / "b_slowish").mkdir()  # graded beside the attacker (jobs=2, students in name order)
        for ex in fx.exercises:
            nb = nbformat.read(ROOT / "solutions" / f"{ex}.ipynb", as_version=4)
            nb.cells.append(nbformat.v4.new_code_cell(SLOWISH.format(functions=_functions(ex))))
            nbformat.write(nb, subs / "b_slowish" / f"{ex}.ipynb")
        attackers["b_slowish"] = "earned"
    groups = None
    if "memory_mb" in fx.head or fx.category == "limits":
        groups = open_run(memory=int(float(fx.head.get("memory_mb", 4096)) * (1 << 20)))
        if not groups.enforced:
            listener.close()
            pytest.skip(f"NO CONTROL GROUPS here, the per-notebook limits cannot be tested: {groups.reason}")
    before = {"subs": _digest(subs), "watched": watched()}
    if any("{{TABLE}}" in cell for cell in fx.cells):
        values["TABLE"] = home_table(fx.exercises, "attacker")
    monkeypatch.setenv("PUMA_HOSTILE_SECRET", mark)
    limits = {**LIMITS, **fx.limits}
    started = time.time()
    t0 = time.perf_counter()
    try:
        results = grade(
            subs,
            out,
            feedback=fb,
            jobs=2,
            secret=root / ".grading-secret",
            exercises=fx.exercises,
            sandbox=box,
            cgroups=groups or True,
            **limits,
        )
    finally:
        seconds = time.perf_counter() - t0
        if groups is not None:
            groups.close()
        time.sleep(0.3)  # a daemon that outlived its notebook would act now
        connections = listener.close()
    with open(out, newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    usages = list(groups.usages) if groups is not None else []
    return AttackRun(
        fx, mode, root, subs, out, fb, mark, started, attackers, results, rows, before, connections, seconds, usages
    )


#: A cell for the slowish classmate: every graded function burns 0.05 s of CPU before it answers.
SLOWISH = """
import time as _time


def _slowly(fn):
    def wrapper(*args, **kwargs):
        end = _time.process_time() + 0.05
        while _time.process_time() < end:
            pass
        return fn(*args, **kwargs)

    return wrapper


for _name in {functions!r}:
    globals()[_name] = _slowly(globals()[_name])
"""


def _functions(exercise: str) -> list[str]:
    return list(dict.fromkeys(q.function for q in EXERCISES[exercise].questions))


#: The seeds a student could know: the one earlier versions printed in every feedback, and small guesses.
KNOWN_SEEDS = (7, 0, 1, 2, 3, 42, 2024)


def table_key(args: Any) -> str:
    """The lookup key of a call's arguments (rounded, so a value that went through JSON still matches)."""
    import numpy as np

    def r(a: Any) -> Any:
        if isinstance(a, str):
            return a
        arr = np.asarray(a, dtype=float)
        return np.round(arr, 9).tolist()

    return json.dumps([r(a) for a in args])


def home_table(exercises: list[str], student: str) -> str:
    """JSON {function: {table_key(args): answer}}: every hidden case a student can rebuild at home.

    The student holds the question bank and the grader's code, and knows every seed in
    :data:`KNOWN_SEEDS` (earlier versions printed the seed in the feedback): they draw the hidden
    cases of the shared-seed plan and of the public-seed keys, for their own name, and store a right
    answer for each. Public cases are left out (their answers are no secret).
    """
    import numpy as np

    from puma_course.grading.run.runner import make_plan
    from puma_course.grading.secret import from_seed

    table: dict[str, dict[str, Any]] = {}
    for name in exercises:
        ex = EXERCISES[name]
        public = {(q.qid, k) for q in ex.questions for k in range(len(q.public))}
        for seed in KNOWN_SEEDS:
            for plan in (make_plan(ex, seed), make_plan(ex, from_seed(seed), student)):
                for call in plan:
                    if (call.qid, call.case) in public:
                        continue
                    answer = ex.question(call.qid).right_answer(*call.call_args)
                    table.setdefault(call.function, {})[table_key(call.call_args)] = np.asarray(
                        answer, dtype=float
                    ).tolist()
    return json.dumps(table)


def _digest(folder: Path) -> dict[str, str]:
    out = {}
    for p in sorted(folder.rglob("*")):
        if p.is_symlink():
            out[str(p.relative_to(folder))] = "link:" + os.readlink(p)
        elif p.is_file():
            out[str(p.relative_to(folder))] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def _stray_processes(mark: str) -> list[str]:
    found = []
    for cmdline in glob.glob("/proc/[0-9]*/cmdline"):
        try:
            data = Path(cmdline).read_bytes()
        except OSError:
            continue
        if mark.encode() in data:
            found.append(f"{cmdline}: {data[:200]!r}")
    return found


def _marked_files(mark: str, since: float) -> list[str]:
    found = []
    for pattern in ("/tmp/*{m}*", "/var/tmp/*{m}*", "/dev/shm/*{m}*", str(Path.home() / "*{m}*"), str(ROOT / "*{m}*")):
        found += glob.glob(pattern.format(m=mark))
    for folder in (ROOT / "puma_course", SITE / "puma_course", ROOT):
        for p in folder.rglob("*") if folder != ROOT else folder.glob("*"):
            try:
                if (
                    p.is_file()
                    and not p.is_symlink()
                    and p.stat().st_mtime >= since
                    and mark.encode() in p.read_bytes()
                ):
                    found.append(str(p))
            except OSError:
                continue
    return found


def check_run(run: AttackRun) -> None:
    """The assertions every hostile fixture must pass (see the module docstring)."""
    exercises = run.fixture.exercises
    full = {ex: sum(q.points for q in EXERCISES[ex].questions) for ex in exercises}
    # the run finished: a CSV row and a feedback file for every student and exercise
    students = {r["student"] for r in run.rows}
    attackers = {csv_safe(name) for name in run.attackers}
    assert {"honest", "blank"} <= students and attackers <= students, (students, run.attackers)
    assert len(run.rows) == len(students) * len(exercises)
    assert len(list(run.fb.glob("*.md"))) == len(students) + 1  # + the earlier run's file, untouched
    # the honest and blank classmates keep their marks
    for r in run.of("honest"):
        assert (r.status, r.score) == ("ok", full[r.exercise]), (r.exercise, r.status, r.notes, r.question_notes)
    for r in run.of("blank"):
        assert (r.status, r.score) == ("ok", 0), (r.exercise, r.status, r.notes, r.question_notes)
    # the attacker gains nothing
    for name, expect in run.attackers.items():
        mine = run.of(name)
        assert mine, name
        for r in mine:
            assert not any("exit code 97" in n for n in r.notes), (name, r.exercise, "LEAK", r.notes)
            wanted = 0 if expect == "zero" else full[r.exercise]
            if expect.startswith("without "):
                lost = expect.split()[1:]
                wanted = full[r.exercise] - sum(q.points for q in EXERCISES[r.exercise].questions if q.qid in lost)
            assert r.score == wanted, (name, r.exercise, r.status, r.score, r.notes, r.question_notes)
    # nothing outside the worker's folder changed, nothing outlived the run, nothing connected
    assert _digest(run.subs) == run.before["subs"]
    assert watched() == run.before["watched"]
    assert (run.fb / "previous_run.md").read_text(encoding="utf-8").endswith(f"{run.mark}\n")
    assert _marked_files(run.mark, run.started) == []
    assert _stray_processes(run.mark) == []
    assert run.connections == []
    for path in [run.out, *run.fb.glob("*.md")]:
        assert run.mark not in path.read_text(encoding="utf-8") or path.name == "previous_run.md", path
