"""Benchmark: the copy report (issue 30, deliverable 4) on a class of 200; prints seconds and peak memory.

    python benchmarks/bench_copies.py [--students 200] [--seed 30]

Each student hands in all ten exercises. For every question a student's answer is drawn from the pool of
that question's answers: the solution's and every answer of the corpus (``tests/fixtures/answers``: valid
ones, wrong ones and wrong methods, each renamed to the function the question asks for), then varied as
students vary their code: the names of its parameters and variables changed, comments and blank lines
added, and for one in three the layout redone (``ast.unparse``). One exercise in ten is handed in blank.
Planted on top: ten pairs of students sharing an answer, five students pasting a package function, five
pasting a lecture cell. Only the report is timed (no notebook is run): :func:`~.copies.handed` on every
notebook's bytes, as the grader calls it after grading each one, then :func:`~.copies.find_copies`.
Peak memory is Python's (tracemalloc, in a second, untimed pass) during the two steps, with what is kept of
the notebooks while grading, and the process's peak resident size.
Figures are printed, never asserted.
"""

from __future__ import annotations

import argparse
import ast
import inspect
import io
import json
import keyword
import random
import resource
import sys
import textwrap
import time
import tokenize
import tracemalloc
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from puma_course.grading import EXERCISES  # noqa: E402
from puma_course.grading.output import copies  # noqa: E402
from tests.fixtures.answers import CORPUS  # noqa: E402

NAMES = ("alpha beta gamma value out res tmp acc mat vec angle ang pos rot tr idx k_ item row col"
         " first second total part piece aux w z").split()  # fmt: skip


def _answer_cells(name: str) -> dict[str, str]:
    nb = json.loads((ROOT / "solutions" / f"{name}.ipynb").read_text(encoding="utf-8"))
    out = {}
    for cell in nb["cells"]:
        tags = cell.get("metadata", {}).get("tags", [])
        qid = next((t.split(":", 1)[1] for t in tags if t.startswith("question:")), None)
        if qid:
            src = "".join(cell["source"])
            out[qid] = "\n".join(line for line in src.splitlines() if "### " not in line)
    return out


def pools() -> dict[tuple[str, str], list[str]]:
    """Per (exercise, question): the distinct sources of the solution's answer and of the corpus's answers."""
    out: dict[tuple[str, str], list[str]] = defaultdict(list)
    for name in EXERCISES:
        for qid, src in _answer_cells(name).items():
            out[name, qid].append(src)
    for a in CORPUS:
        try:
            src = textwrap.dedent(inspect.getsource(a.fn))
            tree = ast.parse(src)
        except (OSError, TypeError, SyntaxError):
            continue
        fn = tree.body[0]
        if isinstance(fn, ast.FunctionDef):
            fn.name = a.question.function
            src = ast.unparse(fn)
            if src not in out[a.exercise, a.qid]:
                out[a.exercise, a.qid].append(src)
    return out


def vary(src: str, rng: random.Random) -> str:
    """``src`` with its local names changed, comments and blank lines added, and sometimes its layout redone."""
    try:
        tree = ast.parse(src)
    except SyntaxError:
        return src
    fn = tree.body[0] if tree.body and isinstance(tree.body[0], ast.FunctionDef) else None
    local = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
    local |= {a.arg for a in ast.walk(tree) if isinstance(a, ast.arg)}
    new = {old: f"{rng.choice(NAMES)}{i}" for i, old in enumerate(sorted(local)) if not keyword.iskeyword(old)}
    if fn is not None:
        new.pop(fn.name, None)
    if rng.random() < 1 / 3:
        src = ast.unparse(tree)
    toks = []
    for tok in tokenize.generate_tokens(io.StringIO(src).readline):
        prev = toks[-1] if toks else None
        attr = prev is not None and prev.string == "."
        text = new.get(tok.string, tok.string) if tok.type == tokenize.NAME and not attr else tok.string
        toks.append(tok._replace(string=text))
    out = tokenize.untokenize(toks)
    lines = out.splitlines()
    for _ in range(rng.randrange(0, 3)):
        at = rng.randrange(1, max(2, len(lines)))
        indent = lines[at - 1][: len(lines[at - 1]) - len(lines[at - 1].lstrip())]
        lines.insert(at, indent + rng.choice(("# check this", "# from the notes", "")))
    return "\n".join(lines) + "\n"


def build(students: int, seed: int) -> list[tuple[str, str, bytes]]:
    """The class as (student, exercise, notebook bytes)."""
    rng = random.Random(seed)
    pool = pools()
    released = {n: json.loads((ROOT / "exercises" / f"{n}.ipynb").read_text(encoding="utf-8")) for n in EXERCISES}
    lecture = json.loads((ROOT / "notebooks" / "09_puma560_inverse_kinematics.ipynb").read_text(encoding="utf-8"))
    lecture_cells = [
        "".join(c["source"]) for c in lecture["cells"] if c["cell_type"] == "code" and len(c["source"]) > 6
    ]
    puma = (ROOT / "puma_course" / "kinematics" / "puma560.py").read_text(encoding="utf-8")
    helpers = [ast.get_source_segment(puma, n) for n in ast.parse(puma).body if isinstance(n, ast.FunctionDef)]
    names = [f"s{i:03d}" for i in range(students)]
    sharing = {names[2 * i + 1]: names[2 * i] for i in range(10)}  # s001 copies s000's, ...
    pasting = set(names[100:105])
    lecturing = set(names[110:115])
    out = []
    chosen: dict[tuple[str, str, str], str] = {}
    for s in names:
        for n in EXERCISES:
            nb = json.loads(json.dumps(released[n]))
            if rng.random() >= 0.1:
                for cell in nb["cells"]:
                    tags = cell.get("metadata", {}).get("tags", [])
                    qid = next((t.split(":", 1)[1] for t in tags if t.startswith("question:")), None)
                    if not qid or not pool.get((n, qid)):
                        continue
                    src = vary(rng.choice(pool[n, qid]), rng)
                    if s in sharing and (sharing[s], n, qid) in chosen:
                        src = vary(chosen[sharing[s], n, qid], rng)
                    if s in pasting and n == "ex09_puma_ik" and qid == "q2":
                        src = "\n\n".join(h for h in helpers[1:5] if h) + "\n\n" + src
                    if s in lecturing and n == "ex09_puma_ik" and qid == "q1":
                        src = "\n".join(rng.sample(lecture_cells, 3)) + "\n" + src
                    chosen[s, n, qid] = src
                    cell["source"] = src
            out.append((s, n, json.dumps(nb, indent=1).encode()))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=200)
    parser.add_argument("--seed", type=int, default=30)
    args = parser.parse_args()
    notebooks = build(args.students, args.seed)
    size = sum(len(b) for _, _, b in notebooks)
    print(f"class: {args.students} students, {len(notebooks)} notebooks, {size / 1e6:.1f} MB")
    t0, c0 = time.perf_counter(), time.process_time()
    copies.package_library()
    copies.lecture_library(ROOT / "notebooks")
    t_refs, c_refs = time.perf_counter() - t0, time.process_time() - c0
    t1, c1 = time.perf_counter(), time.process_time()
    kept = [copies.handed(data, EXERCISES[n], s) for s, n, data in notebooks]
    t_read, c_read = time.perf_counter() - t1, time.process_time() - c1
    t2, c2 = time.perf_counter(), time.process_time()
    report = copies.find_copies(kept)
    t_find, c_find = time.perf_counter() - t2, time.process_time() - c2
    sources = defaultdict(int)
    for m in report.matches:
        if m.source != "classmate":
            sources[m.source, m.exercise, m.region, m.other.split(":")[0]] += 1
    del kept, report
    tracemalloc.start()  # a second pass for the memory (tracemalloc slows Python down: not timed)
    kept = [copies.handed(data, EXERCISES[n], s) for s, n, data in notebooks]
    kept_mb = tracemalloc.get_traced_memory()[0] / 1e6
    report = copies.find_copies(kept)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    kinds = defaultdict(int)
    for m in report.matches:
        kinds[m.source] += 1
    print(f"fingerprinting the package and the lectures (once per grading run): {t_refs:.2f} s (CPU {c_refs:.2f} s)")
    print(
        f"reading the answers from the notebooks (handed, {len(notebooks)} calls): {t_read:.2f} s (CPU {c_read:.2f} s)"
    )
    print(f"comparing (find_copies): {t_find:.2f} s (CPU {c_find:.2f} s)")
    print(f"total: {t_refs + t_read + t_find:.2f} s (CPU {c_refs + c_read + c_find:.2f} s)")
    print(f"what the grader keeps of the notebooks while grading (handed): {kept_mb:.1f} MB")
    print(f"peak Python memory during the two steps: {peak / 1e6:.0f} MB")
    print(f"peak resident size of the process: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    print(f"matches: {dict(kinds)}; hidden-code notes: {len(report.carried)}")
    for key, n in sorted(sources.items(), key=lambda kv: -kv[1])[:12]:
        print(f"  {n:4d} x {' '.join(key)}")
    section = "\n".join(copies.copies_section(report))
    print(f"summary section: {len(section.splitlines())} lines, {len(section) / 1e3:.0f} kB")


if __name__ == "__main__":
    main()
