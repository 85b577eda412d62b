"""Benchmark: grade a simulated class with the sandbox, as an instructor would; print its cost and a sizing table.

    python benchmarks/bench_class.py [--students 1000] [--jobs 2] [--exercises ex01_rotations ...]
                                     [--small M] [--parts P] [--workdir DIR] [--shard K/N]
                                     [--kernel-sample 3] [--json out.json]
    python benchmarks/bench_class.py --compare-blank 24   # 24 blank ex10 notebooks against 24 blank ex01

The class: ``--students`` folders, each handing in every exercise. Notebook ``i`` of student ``k`` is, by
``(k + i) % 3``: 0 honest (the exercise's solution from ``solutions/``), 1 wrong (the solution with one answer
broken: the first ``+`` of its first answer cell turned into ``-``, as ``bench_grading.py`` does), 2 blank (the
released exercise from ``exercises/``, its stubs untouched); the counts are printed. Every notebook of one kind
is a hard link to one file, so a class of 1,000 takes a few megabytes of disk.

Grading goes through the command an instructor runs, ``puma-course grade SUBMISSIONS -o CSV --feedback DIR
--secret KEY --jobs J`` (the sandbox and control-group limits it chooses: bubblewrap where it runs), in a
process of its own whose only addition is a timer around ``make_plan`` (planning's share). Measured:

- wall time, and CPU time of the grader and of all its children (the ``cpuacct`` control group the grader is
  started in, so every worker, sandbox and notebook process counts; where no group can be made, ``os.wait4``'s
  rusage, which misses the processes killed with their worker's process group);
- peak memory: the grader's resident high-water mark (``VmHWM``, read while it runs) and the largest
  resident set of any other process of its tree (sampled every 0.2 s; short-lived peaks can be missed);
- the marginal cost per notebook, from two class sizes: the first ``--small`` students (default a fifth) graded
  as a class of their own, then the whole class; the line ``T = fixed + notebooks x marginal`` through them (with
  ``--parts``, fitted to every part's run, each of which pays the fixed cost once);
- planning: seconds of the grader's threads' CPU spent in ``make_plan``, against the grader's and the total.

From these the sizing table: notebooks per core-hour (3,600 CPU-s over the CPU-s per notebook), memory per
worker, and the time for a class of 1,000 x the exercises on one 2-core machine and on N = 1, 4, 10, 50 shards
(each a 2-core machine running ``--jobs 2``: the fixed cost once per shard, plus its share of notebooks at the
measured marginal wall time; the merge is not counted). Beside it, nbclient's cost per notebook (a solution run
in a fresh Jupyter kernel, no sandbox, no grading: ``bench_grading.time_kernel``), the lower bound of
nbgrader-style execution.

Long runs: ``--workdir DIR`` keeps the class, the key and each part's figures; ``--parts P`` grades the class as
P shards one after the other (``--shard k/P``), so that a run stopped part-way resumes where it stopped (parts
already measured are read back, not graded again); ``--shard K/N`` grades one part only (another machine's
figures are combined by hand). The estimated time is printed before grading starts. Figures are printed,
never asserted (tests/benchmarks/test_bench_class.py runs it on 2 students so that it cannot rot).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import secrets
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ALL = sorted(p.stem for p in (ROOT / "solutions").glob("ex*.ipynb"))
KINDS = ("honest", "wrong", "blank")
#: a priori seconds of wall time per notebook with 2 jobs on 2 idle cores (refined after the small class)
GUESS_PER_NOTEBOOK = 0.35

# the grader, as `puma-course grade` runs it, with a timer around make_plan; the timer's totals go to argv[1]
_TIMED_CLI = """
import atexit, json, resource, sys, threading, time
from puma_course.grading.run import runner
real, lock, tot = runner.make_plan, threading.Lock(), {"calls": 0, "cpu": 0.0, "wall": 0.0}
def timed(*a, **k):
    c, w = time.thread_time(), time.perf_counter()
    try:
        return real(*a, **k)
    finally:
        with lock:
            tot["calls"] += 1; tot["cpu"] += time.thread_time() - c; tot["wall"] += time.perf_counter() - w
runner.make_plan = timed
out = sys.argv.pop(1)
def save():
    me = resource.getrusage(resource.RUSAGE_SELF)
    tot["self_cpu"] = me.ru_utime + me.ru_stime
    with open(out, "w") as f:
        f.write(json.dumps(tot))
atexit.register(save)
from puma_course.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _broken(nb: dict) -> dict:
    """The solution with its first answer cell's first ``+`` turned into ``-`` (one function broken)."""
    for cell in nb["cells"]:
        src = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
        if cell["cell_type"] == "code" and "### BEGIN SOLUTION" in src:
            lines = src.splitlines(keepends=True)
            for i, line in enumerate(lines):
                if " + " in line and "BEGIN" not in line:
                    lines[i] = line.replace(" + ", " - ", 1)
                    cell["source"] = "".join(lines)
                    return nb
    return nb


def kind(student: int, exercise: int) -> str:
    return KINDS[(student + exercise) % 3]


def build_class(folder: Path, students: int, names: list[str]) -> dict[str, int]:
    """Write (or complete) the class in ``folder/submissions``; the number of notebooks of each kind."""
    src = folder / "sources"
    for name in names:
        for k in KINDS:
            target = src / k / f"{name}.ipynb"
            if target.exists():
                continue
            target.parent.mkdir(parents=True, exist_ok=True)
            if k == "blank":
                shutil.copy(ROOT / "exercises" / f"{name}.ipynb", target)
            else:
                nb = json.loads((ROOT / "solutions" / f"{name}.ipynb").read_text(encoding="utf-8"))
                target.write_text(json.dumps(_broken(nb) if k == "wrong" else nb, indent=1), encoding="utf-8")
    counts = dict.fromkeys(KINDS, 0)
    for s in range(students):
        home = folder / "submissions" / f"s{s:04d}"
        home.mkdir(parents=True, exist_ok=True)
        for i, name in enumerate(names):
            k = kind(s, ALL.index(name) if name in ALL else i)
            counts[k] += 1
            if not (home / f"{name}.ipynb").exists():
                os.link(src / k / f"{name}.ipynb", home / f"{name}.ipynb")
    return counts


def _subset(folder: Path, students: int) -> Path:
    """A class of the first ``students`` students (hard links to their notebooks)."""
    sub = folder / f"first{students}"
    for s in range(students):
        home = folder / "submissions" / f"s{s:04d}"
        (sub / home.name).mkdir(parents=True, exist_ok=True)
        for nb in home.iterdir():
            if not (sub / home.name / nb.name).exists():
                os.link(nb, sub / home.name / nb.name)
    return sub


@dataclass
class Run:
    """One grading's figures."""

    label: str
    notebooks: int
    wall: float
    cpu_grader: float
    cpu_children: float
    grader_rss_mib: float
    worker_rss_mib: float
    tree_rss_mib: float
    plan_calls: int
    plan_cpu: float
    plan_wall: float
    statuses: dict[str, int] = field(default_factory=dict)
    load: tuple[float, float, float] = (0.0, 0.0, 0.0)
    points: list[list[float]] = field(default_factory=list)  # (notebooks, wall, CPU) of each grading run in it

    @property
    def cpu(self) -> float:
        return self.cpu_grader + self.cpu_children


def _descendants(pid: int) -> list[int]:
    """Every process below ``pid`` (the children of each of its threads: the grader starts workers from several)."""
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        kids = []
        for task in Path(f"/proc/{p}/task").glob("*"):
            try:
                kids += [int(k) for k in (task / "children").read_text().split()]
            except (OSError, ValueError):
                continue
        out += kids
        todo += kids
    return out


def _kib(pid: int, field_name: str) -> int:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith(field_name + ":"):
                return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return 0


class Meter:
    """A control group of the grader's own (cgroup v1 ``cpuacct`` and ``memory``, under this process's groups):
    the CPU time and the peak memory of the grader's whole tree, the workers whose process group the grader
    kills at the end among them (``os.wait4`` misses those). None of it where the groups cannot be made."""

    def __init__(self, tag: str) -> None:
        self.groups: dict[str, Path] = {}
        own = dict(
            (line.split(":", 2)[1], line.split(":", 2)[2])
            for line in Path("/proc/self/cgroup").read_text().splitlines()
            if line.count(":") >= 2
        )
        for ctl in ("cpuacct", "memory"):
            mount = next((Path("/sys/fs/cgroup") / m for m in (ctl, "cpu,cpuacct") if ctl in m.split(",")
                          and (Path("/sys/fs/cgroup") / m / "cgroup.procs").exists()), None)  # fmt: skip
            key = next((k for k in own if ctl in k.split(",")), None)
            if mount is None or key is None:
                continue
            group = mount / own[key].lstrip("/") / f"bench-class-{os.getpid()}-{tag}"
            try:
                group.mkdir()
            except OSError:
                continue
            self.groups[ctl] = group

    def enter(self) -> None:  # in the grader's process, before it runs anything (Popen's preexec_fn)
        for group in self.groups.values():
            (group / "cgroup.procs").write_text(str(os.getpid()))

    def cpu(self) -> float | None:
        g = self.groups.get("cpuacct")
        return int((g / "cpuacct.usage").read_text()) / 1e9 if g else None

    def memory_mib(self) -> float | None:
        g = self.groups.get("memory")
        return int((g / "memory.max_usage_in_bytes").read_text()) / 2**20 if g else None

    def close(self) -> None:
        for group in self.groups.values():
            for _ in range(50):
                try:
                    group.rmdir()
                    break
                except OSError:
                    time.sleep(0.1)


def grade_class(subs: Path, out: Path, key: Path, jobs: int, names: list[str], label: str, extra: list[str]) -> Run:
    """Grade ``subs`` with ``puma-course grade`` in a process of its own; its figures."""
    out.mkdir(parents=True, exist_ok=True)
    timer = out / "plan-timer.json"
    args = [sys.executable, "-c", _TIMED_CLI, str(timer), "grade", str(subs), "-o", str(out / "grades.csv")]
    args += ["--feedback", str(out / "feedback"), "--secret", str(key), "--jobs", str(jobs), "--quiet"]
    args += ["--course", str(ROOT), *[a for n in names for a in ("--exercise", n)], *extra]
    peak = {"grader": 0, "worker": 0, "tree": 0}
    start = time.perf_counter()
    meter = Meter(re.sub(r"\W", "-", label))
    with open(out / "stdout.txt", "wb") as so, open(out / "stderr.txt", "wb") as se:
        proc = subprocess.Popen(
            args, cwd=ROOT, stdout=so, stderr=se, stdin=subprocess.DEVNULL, preexec_fn=meter.enter if meter.groups
            else None
        )  # fmt: skip
    done = threading.Event()

    def sample() -> None:
        while not done.wait(0.2):
            peak["grader"] = max(peak["grader"], _kib(proc.pid, "VmHWM"))
            kids = _descendants(proc.pid)
            rss = [_kib(p, "VmRSS") for p in kids]
            peak["worker"] = max([peak["worker"], *(_kib(p, "VmHWM") for p in kids)])
            peak["tree"] = max(peak["tree"], _kib(proc.pid, "VmRSS") + sum(rss))

    watcher = threading.Thread(target=sample, daemon=True)
    watcher.start()
    _, status, usage = os.wait4(proc.pid, 0)  # the grader's and its waited-for descendants' resource usage
    wall = time.perf_counter() - start
    code = proc.returncode = os.waitstatus_to_exitcode(status)
    done.set()
    watcher.join()
    tree_cpu, tree_mib = meter.cpu(), meter.memory_mib()
    meter.close()
    if code not in (0, 1) or not (out / "grades.csv").exists():
        said = (out / "stderr.txt").read_text(encoding="utf-8", errors="replace")[-3000:]
        raise SystemExit(f"grading {label} failed (exit code {code}):\n{said}")
    rows = (out / "grades.csv").read_text(encoding="utf-8").splitlines()
    header = rows[0].split(",")
    col = header.index("status") if "status" in header else None
    statuses: dict[str, int] = {}
    for line in rows[1:]:
        if col is not None:
            st = line.split(",")[col]
            statuses[st] = statuses.get(st, 0) + 1
    timed = json.loads(timer.read_text())
    grader_cpu = timed["self_cpu"]
    total_cpu = usage.ru_utime + usage.ru_stime if tree_cpu is None else tree_cpu
    return Run(
        label,
        len(rows) - 1,
        wall,
        grader_cpu,
        total_cpu - grader_cpu,
        peak["grader"] / 1024,
        max(peak["worker"], 0) / 1024,
        peak["tree"] / 1024 if tree_mib is None else tree_mib,
        timed["calls"],
        timed["cpu"],
        timed["wall"],
        statuses,
        os.getloadavg(),
        [[len(rows) - 1, wall, total_cpu]],
    )


def estimate(notebooks: int, jobs: int, per: float | None = None) -> str:
    per = GUESS_PER_NOTEBOOK * 2 / max(1, min(jobs, os.cpu_count() or 1)) if per is None else per
    s = notebooks * per
    return f"{s / 60:.0f} min" if s >= 120 else f"{s:.0f} s"


def sizing(small: Run | None, whole: Run, jobs: int, exercises: int, kernel: float | None) -> list[str]:
    """The sizing table, as Markdown lines."""
    n = whole.notebooks
    cpu_per, marginal = whole.cpu / n, 0.0
    # every grading run is a point (notebooks, wall, CPU): wall = fixed + notebooks x marginal, fitted (each
    # part of a class graded in parts pays the fixed cost once)
    pts = [p for p in (small.points if small else []) + whole.points if p[0] > 0]
    if len({p[0] for p in pts}) >= 2:
        xs = [p[0] for p in pts]
        mx = sum(xs) / len(xs)
        sxx = sum((x - mx) ** 2 for x in xs)

        def slope(i: int) -> tuple[float, float]:
            my = sum(p[i] for p in pts) / len(pts)
            b = sum((p[0] - mx) * (p[i] - my) for p in pts) / sxx
            return b, my - b * mx

        marginal, fixed = slope(1)
        cpu_marginal = slope(2)[0]
        cpu_per = cpu_marginal if cpu_marginal > 0 else cpu_per
        fixed = max(0.0, fixed)
        how = f"fitted to {len(pts)} runs of {min(xs):.0f} to {max(xs):.0f} notebooks"
    if marginal <= 0:  # no second size, or sizes too close for the machine's noise: the average, fixed cost in it
        marginal, fixed, how = whole.wall / n, 0.0, f"average of {n} notebooks, no usable second class size"
    lines = [
        f"| figure | value ({how}; {jobs} job(s) on {os.cpu_count()} cores, load {whole.load[0]:.1f}) |",
        "| --- | --- |",
        f"| wall time per notebook, marginal | {marginal:.3f} s (fixed cost per run {fixed:.1f} s) |",
        f"| CPU per notebook (grader + children; marginal where two sizes give one) | {cpu_per:.3f} s "
        f"(all of the class: {whole.cpu / n:.3f} s) |",
        f"| notebooks per core-hour | {3600 / cpu_per:,.0f} |",
        f"| the grader's own CPU per notebook (planning, judging: one interpreter, so one process grades at most "
        f"{n / max(whole.cpu_grader, 1e-9):.1f} notebooks/s, whatever its cores) | {whole.cpu_grader / n:.3f} s |",
        f"| memory: grader peak RSS | {whole.grader_rss_mib:.0f} MiB |",
        f"| memory: per worker (largest process of the tree besides the grader) | {whole.worker_rss_mib:.0f} MiB |",
        f"| memory: the whole tree at its largest (control group peak, tmpfs and cache in it) | "
        f"{whole.tree_rss_mib:.0f} MiB |",
        f"| planning's share | {whole.plan_cpu:.1f} CPU-s in {whole.plan_calls} plans: "
        f"{100 * whole.plan_cpu / max(whole.cpu, 1e-9):.1f} % of all CPU |",
    ]
    total = 1000 * exercises
    # on a 2-core machine with --jobs 2: the marginal wall time scaled from this run's parallelism
    per2 = marginal * min(jobs, os.cpu_count() or 1) / 2
    for shards in (1, 4, 10, 50):
        t = fixed + total / shards * per2
        lines.append(
            f"| a class of 1,000 x {exercises} on {shards} shard(s) of 2 cores | "
            f"{t / 60:.1f} min ({total // shards:,} notebooks per shard) |"
        )
    if kernel is not None:
        lines.append(
            f"| nbclient, one solution in a fresh kernel, no sandbox (lower bound of nbgrader-style execution) | "
            f"{kernel:.2f} s per notebook, {kernel / marginal:.1f}x the marginal wall time here |"
        )
    return lines


def _run_parts(work: Path, subs: Path, key: Path, jobs: int, names: list[str], parts: int, label: str) -> Run:
    """Grade ``subs`` as ``parts`` shards in turn (each part's figures saved; saved ones are not graded again)."""
    runs = []
    for k in range(1, parts + 1):
        saved = work / f"{label}-part{k}of{parts}.json"
        if saved.exists():
            runs.append(Run(**json.loads(saved.read_text())))
            print(f"  part {k}/{parts}: read back from {saved}")
            continue
        extra = ["--shard", f"{k}/{parts}"] if parts > 1 else []
        r = grade_class(subs, work / f"out-{label}-{k}of{parts}", key, jobs, names, f"{label} {k}/{parts}", extra)
        saved.write_text(json.dumps(asdict(r)))
        print(f"  part {k}/{parts}: {r.notebooks} notebooks in {r.wall:.1f} s, {r.cpu:.1f} CPU-s")
        runs.append(r)
    if len(runs) == 1:
        return runs[0]
    statuses: dict[str, int] = {}
    for r in runs:
        for st, c in r.statuses.items():
            statuses[st] = statuses.get(st, 0) + c
    return Run(
        label,
        sum(r.notebooks for r in runs),
        sum(r.wall for r in runs),
        sum(r.cpu_grader for r in runs),
        sum(r.cpu_children for r in runs),
        max(r.grader_rss_mib for r in runs),
        max(r.worker_rss_mib for r in runs),
        max(r.tree_rss_mib for r in runs),
        sum(r.plan_calls for r in runs),
        sum(r.plan_cpu for r in runs),
        sum(r.plan_wall for r in runs),
        statuses,
        runs[-1].load,
        [p for r in runs for p in r.points],
    )


def _print_run(r: Run) -> None:
    print(
        f"{r.label}: {r.notebooks} notebooks in {r.wall:.1f} s wall; CPU {r.cpu:.1f} s "
        f"(grader {r.cpu_grader:.1f}, children {r.cpu_children:.1f}); peak RSS grader {r.grader_rss_mib:.0f} MiB, "
        f"largest other process {r.worker_rss_mib:.0f} MiB, tree {r.tree_rss_mib:.0f} MiB; "
        f"plans {r.plan_calls} in {r.plan_cpu:.2f} CPU-s ({r.plan_wall:.2f} s wall); statuses {r.statuses}; "
        f"load {r.load[0]:.1f} {r.load[1]:.1f} {r.load[2]:.1f}"
    )


def compare_blank(count: int, jobs: int, rounds: int, work: Path, key: Path) -> dict[str, object]:
    """Grade ``count`` blank ex10 notebooks and ``count`` blank ex01 ones, alternating, best of ``rounds``."""
    best: dict[str, float] = {}
    cpu: dict[str, float] = {}
    for name in ("ex01_rotations", "ex10_trajectories"):
        subs = work / f"blank-{name}"
        for s in range(count):
            (subs / f"s{s:04d}").mkdir(parents=True, exist_ok=True)
            target = subs / f"s{s:04d}" / f"{name}.ipynb"
            if not target.exists():
                shutil.copy(ROOT / "exercises" / f"{name}.ipynb", target)
    loads = []
    for rnd in range(rounds):
        for name in ("ex01_rotations", "ex10_trajectories"):
            r = grade_class(work / f"blank-{name}", work / f"out-blank-{name}-{rnd}", key, jobs, [name], name, [])
            loads.append(r.load[0])
            _print_run(r)
            best[name] = min(best.get(name, float("inf")), r.wall)
            cpu[name] = min(cpu.get(name, float("inf")), r.cpu)
    ratio = best["ex10_trajectories"] / best["ex01_rotations"]
    cpu_ratio = cpu["ex10_trajectories"] / cpu["ex01_rotations"]
    print(
        f"{count} blank notebooks, {jobs} job(s), best of {rounds}: ex01 {best['ex01_rotations']:.1f} s, "
        f"ex10 {best['ex10_trajectories']:.1f} s: ex10/ex01 = {ratio:.2f} (done when <= 2); CPU (grader + "
        f"children) {cpu['ex01_rotations']:.1f} and {cpu['ex10_trajectories']:.1f} s, ex10/ex01 = {cpu_ratio:.2f}; "
        f"load average during the rounds {min(loads):.1f}-{max(loads):.1f} on {os.cpu_count()} cores"
    )
    return {"count": count, "jobs": jobs, "best": best, "ratio": ratio, "cpu": cpu, "cpu_ratio": cpu_ratio,
            "load": [min(loads), max(loads)]}  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=1000)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--exercises", nargs="+", default=ALL, choices=ALL, metavar="NAME")
    parser.add_argument("--small", type=int, default=None, help="students of the smaller class (default N/5; 0: none)")
    parser.add_argument("--parts", type=int, default=1, help="grade the class as P shards in turn (resumable)")
    parser.add_argument("--shard", default=None, metavar="K/N", help="grade only part K of N (no small class)")
    parser.add_argument("--workdir", type=Path, default=None, help="keep the class and figures here (resumable)")
    parser.add_argument("--kernel-sample", type=int, default=3, help="notebooks run with nbclient (0: skip)")
    parser.add_argument("--compare-blank", type=int, default=0, metavar="N", help="N blank ex10 against N blank ex01")
    parser.add_argument("--rounds", type=int, default=2, help="rounds of --compare-blank (the best counts)")
    parser.add_argument("--json", type=Path, default=None, help="write the figures here")
    args = parser.parse_args()
    if args.students < 1 or args.jobs < 1 or args.parts < 1:
        raise SystemExit("--students, --jobs and --parts: expected at least 1")
    work = args.workdir or Path(tempfile.mkdtemp(prefix="bench-class-"))
    work.mkdir(parents=True, exist_ok=True)
    key = work / "key"
    if not key.exists():
        key.write_text(secrets.token_hex(32) + "\n")
        key.chmod(0o600)
    figures: dict[str, object] = {"python": sys.version.split()[0], "cores": os.cpu_count()}
    try:
        if args.compare_blank:
            figures["compare_blank"] = compare_blank(args.compare_blank, args.jobs, args.rounds, work, key)
        else:
            figures.update(_bench(args, work, key))
    finally:
        if args.workdir is None:
            shutil.rmtree(work, ignore_errors=True)
    if args.json is not None:
        args.json.write_text(json.dumps(figures, indent=1, default=str) + "\n", encoding="utf-8")
        print(f"figures written to {args.json}")


def _bench(args: argparse.Namespace, work: Path, key: Path) -> dict[str, object]:
    names = list(args.exercises)
    counts = build_class(work, args.students, names)
    notebooks = args.students * len(names)
    print(
        f"class: {args.students} students x {len(names)} exercises = {notebooks} notebooks "
        f"({', '.join(f'{c} {k}' for k, c in counts.items())}) in {work}; {args.jobs} job(s), "
        f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}"
    )
    free = shutil.disk_usage(work).free / 2**30
    print(f"disk: {free:.1f} GiB free in {work} (the class is hard links: 4.4 MiB for 1,000 students, "
          "plus each run's CSV and feedback)")  # fmt: skip
    small_n = args.students // 5 if args.small is None else args.small
    small_n = 0 if args.shard or small_n >= args.students else small_n
    share = 1 / int(args.shard.split("/")[1]) if args.shard else 1.0
    print(f"estimate (a priori, {GUESS_PER_NOTEBOOK} s per notebook at 2 jobs on 2 idle cores): "
          f"{estimate(round(notebooks * share) + small_n * len(names), args.jobs)}")  # fmt: skip
    small = None
    if small_n:
        small = _run_parts(work, _subset(work, small_n), key, args.jobs, names, 1, f"first{small_n}")
        _print_run(small)
        per = small.wall / small.notebooks
        print(f"estimate for the whole class from it: {estimate(notebooks, args.jobs, per)}")
    subs = work / "submissions"
    if args.shard:
        k, n = args.shard.split("/")
        whole = grade_class(subs, work / f"out-shard-{k}of{n}", key, args.jobs, names, f"shard {args.shard}",
                            ["--shard", args.shard])  # fmt: skip
    else:
        whole = _run_parts(work, subs, key, args.jobs, names, args.parts, f"class{args.students}")
    _print_run(whole)
    kernel = None
    if args.kernel_sample:
        sys.path.insert(0, str(Path(__file__).parent))
        from bench_grading import time_kernel  # noqa: PLC0415 - a sibling script, only when asked

        kernel = time_kernel(args.kernel_sample)
    table = sizing(small, whole, args.jobs, len(names), kernel)
    print("\n".join(table))
    return {"counts": counts, "small": asdict(small) if small else None, "whole": asdict(whole), "table": table,
            "nbclient_per_notebook": kernel}  # fmt: skip


if __name__ == "__main__":
    main()
