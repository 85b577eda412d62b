"""Benchmark: what the sandbox's per-run copy of the Python install costs (issue 21, "no host path in mounts").

    python benchmarks/bench_sandbox.py [--repeat 5]

Printed (never asserted), with and without the copy (:mod:`puma_course.grading.run.scratch`):

* per run: the time :func:`~puma_course.grading.run.sandbox.choose` takes (the copy, and the probe that starts
  one sandbox), the copy's size in memory and its number of files, and where it lives (a tmpfs of its own as
  root, a folder of /dev/shm otherwise);
* per notebook: the median time to start a sandboxed worker that imports numpy and exits, and to grade ex01's
  solution (38 calls) with :func:`~puma_course.grading.run.runner.grade_notebook`;
* what ``/proc/self/mountinfo`` shows inside: the mounts whose field 4 (the folder in its source file system)
  names a host folder outside the system's.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from puma_course.grading import EXERCISES  # noqa: E402
from puma_course.grading.run.runner import grade_notebook  # noqa: E402
from puma_course.grading.run.sandbox import MOUNT, Sandbox, child_env, choose  # noqa: E402


def _size(folder: str) -> tuple[int, int]:
    total = files = 0
    for root, _, names in os.walk(folder):
        for n in names:
            p = os.path.join(root, n)
            if not os.path.islink(p):
                total += os.path.getsize(p)
                files += 1
    return total, files


def _start(box: Sandbox, code: str) -> tuple[float, str]:
    with tempfile.TemporaryDirectory(dir=box.scratch.path if box.scratch else None) as tmp:
        lib, pkg = Path(tmp, "lib"), Path(tmp, "bin", "puma_worker")
        lib.mkdir()
        pkg.mkdir(parents=True)
        pkg.joinpath("__init__.py").write_text(
            f"def main():\n    import sys\n    sys.path += {list(box.seen_sites)!r}\n{code}"
        )
        cmd, fd = box.launch(lib, pkg.parent)
        t0 = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, env=child_env(f"{MOUNT}/work"), pass_fds=(fd,))
        seconds = time.perf_counter() - t0
        os.close(fd)
    if out.returncode != 0:
        raise SystemExit(out.stderr[-2000:])
    return seconds, out.stdout


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(argv)
    warnings.simplefilter("ignore")
    ex = EXERCISES["ex01_rotations"]
    solution = (ROOT / "solutions" / f"{ex.name}.ipynb").read_bytes()
    print(f"user {os.geteuid()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}")
    for copy in (False, True):
        t0 = time.perf_counter()
        box = choose("bwrap", copy=copy)
        chosen = time.perf_counter() - t0
        label = "copy" if copy else "bind host folders"
        print(f"\n{label}: {box.mounts}")
        line = f"   per run: choose() {chosen:.2f} s"
        if box.scratch is not None:
            size, files = _size(box.scratch.path)
            line += f" (copy {size / 2**20:.0f} MiB, {files} files, {box.scratch.kind})"
        print(line)
        starts = [_start(box, "    import numpy\n")[0] for _ in range(args.repeat)]
        print(
            f"   per notebook: start a worker importing numpy {statistics.median(starts):.3f} s "
            f"(median of {args.repeat})"
        )
        grades = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            r = grade_notebook(None, ex, "s", seed=1, data=solution, sandbox=box)
            grades.append(time.perf_counter() - t0)
            assert r.score == r.max_score, r.question_notes
        print(f"   per notebook: grade ex01's solution {statistics.median(grades):.3f} s (median of {args.repeat})")
        _, table = _start(box, "    sys.stdout.write(open('/proc/self/mountinfo').read())\n")
        system = ("/usr", "/etc/", "/newroot", "/")
        named = [ln.split()[3] for ln in table.splitlines() if ln.split()[3] not in system]
        named = [n for n in named if not n.startswith(system[:2]) and n.split("/")[1] not in ("null", "zero", "full")]
        named = [n for n in named if n not in ("/random", "/urandom", "/tty", "/irq", "/bus")]
        print(f"   mountinfo field 4 beyond the system's: {', '.join(named) or 'none'}")
        box.close()


if __name__ == "__main__":
    main()
