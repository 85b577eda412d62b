"""Benchmark: how long do the commands take to start? Print wall seconds per command, fresh process each time.

    python benchmarks/bench_startup.py [--root DIR] [--repeat 5] [--no-bytecode]

Times, each in a fresh Python process (the package imported from ``--root``, default this checkout, so an
older checkout, ``git worktree add /tmp/old 346a31c`` say, is measured the same way): ``import puma_course``,
``puma-course --help``, ``puma-course release --check`` (the course's exercises compared with its solutions),
``puma-course edition DIR`` (the student edition written into a temporary folder), and, for scale,
``import nbformat`` (which imports jsonschema's format checkers). Each command runs once unmeasured, then
``--repeat`` times; the table gives the median and the best, and each median over ``import puma_course``'s.

Python's bytecode cache is on, kept in a temporary folder (``PYTHONPYCACHEPREFIX``), as for an installed
package; ``--no-bytecode`` compiles every module on every run (``PYTHONDONTWRITEBYTECODE``, as some CI
images set it). Figures are printed, never asserted: a shared machine's load moves them.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def commands(out: Path) -> list[tuple[str, list[str]]]:
    """(label, arguments after ``python``) of every command timed."""
    cli = ["-m", "puma_course.cli"]
    return [
        ("import puma_course", ["-c", "import puma_course"]),
        ("puma-course --help", [*cli, "--help"]),
        ("puma-course release --check", [*cli, "release", "--check"]),
        ("puma-course edition DIR", [*cli, "edition", str(out)]),
        ("import nbformat (for scale)", ["-c", "import nbformat"]),
    ]


def run_once(args: list[str], root: Path, env: dict[str, str]) -> float:
    start = time.perf_counter()
    done = subprocess.run([sys.executable, *args], cwd=root, env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode not in (0, 1):  # release --check exits 1 on an out-of-date course: still a timing
        raise SystemExit(f"{args}: exit code {done.returncode}\n{done.stderr}")
    return seconds


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", type=Path, default=ROOT, help="the checkout whose package and course are timed")
    parser.add_argument("--repeat", type=int, default=5, help="measured runs per command (default 5)")
    parser.add_argument("--no-bytecode", action="store_true", help="compile every module on every run")
    args = parser.parse_args()
    root = args.root.resolve()
    with tempfile.TemporaryDirectory(prefix="bench-startup-") as tmp:
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "PYTHONPYCACHEPREFIX")}
        env["PYTHONPATH"] = str(root)  # before the editable install's finder: the package of --root
        if args.no_bytecode:
            env["PYTHONDONTWRITEBYTECODE"] = "1"
        else:
            env["PYTHONPYCACHEPREFIX"] = str(Path(tmp) / "pycache")
        rows = []
        for label, cmd in commands(Path(tmp) / "edition"):
            run_once(cmd, root, env)  # the bytecode cache filled, the files in the page cache
            times = [run_once(cmd, root, env) for _ in range(args.repeat)]
            rows.append((label, statistics.median(times), min(times)))
    base = rows[0][1]
    print(f"root: {root}  python {sys.version.split()[0]}  bytecode cache: {'off' if args.no_bytecode else 'on'}  "
          f"runs: {args.repeat} (+1 unmeasured)")  # fmt: skip
    print(f"{'command':<30} {'median s':>9} {'best s':>8} {'x import':>9}")
    for label, median, best in rows:
        print(f"{label:<30} {median:>9.3f} {best:>8.3f} {median / base:>9.1f}")


if __name__ == "__main__":
    main()
