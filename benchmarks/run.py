"""Speed of the course's kinematics on this machine, printed as a Markdown table.

Run from the repository root::

    /work/venv/bin/python benchmarks/run.py                # everything (executes every notebook: ~1-2 min)
    /work/venv/bin/python benchmarks/run.py --quick        # skip notebook execution and grading

Figures are the best of a few repeats (per-pose times for batches divide the
batch time by its size). A module that does not exist yet shows ``n/a``; a row
that fails shows ``n/a (error ...)``; the script never stops on one row.
Nothing here is asserted: tests never check timings (shared, noisy machines).
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PORTER_L = (1.0, 0.5, 0.3)  # l1, l3, l4 for Porter's chain

rows: list[tuple[str, str, str]] = []


def best(fn: Callable[[], object], repeat: int = 5, number: int = 1) -> float:
    """Best wall time of ``number`` calls, over ``repeat`` repeats, per call (seconds)."""
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t) / number)
    return min(times)


def row(what: str, target: str, compute: Callable[[], str]) -> None:
    """Add a table row; any failure becomes ``n/a`` with the reason, never a crash."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            value = compute()
    except (ImportError, AttributeError) as err:
        value = f"n/a ({type(err).__name__}: {str(err)[:60]})"
    except Exception as err:  # noqa: BLE001 - a benchmark row must not stop the others
        value = f"n/a (error {type(err).__name__}: {str(err)[:60]})"
    rows.append((what, value, target))
    print(f"  {what}: {value}", file=sys.stderr, flush=True)


def _porter():
    from puma_course import porter

    return porter


# ---------------------------------------------------------------- forward kinematics
def fk_rows(n: int) -> None:
    rng = np.random.default_rng(0)

    def puma() -> str:
        from puma_course.robots import puma560

        arm, q = puma560(), rng.uniform(-np.pi, np.pi, (n, 6))
        return f"{best(lambda: arm.fk(q), 3) / n * 1e9:.0f} ns/pose"

    def mk3() -> str:
        from puma_course.robots import mk3 as make

        arm, q = make(), rng.uniform(-np.pi, np.pi, (n, 5))
        return f"{best(lambda: arm.fk(q), 3) / n * 1e9:.0f} ns/pose"

    def porter() -> str:
        p = _porter()
        q = np.column_stack(
            [rng.uniform(0, 2 * np.pi, (n, 2)), rng.uniform(0.2, 1.5, n), rng.uniform(0, 2 * np.pi, (n, 3))]
        )
        return f"{best(lambda: p.fk(q, *PORTER_L), 3) / n * 1e9:.0f} ns/pose"

    row(f"fk PUMA-560, batch of {n:,}", "≤ 1000 ns/pose", puma)
    row(f"fk MK3, batch of {n:,}", "", mk3)
    row(f"fk Porter's chain (porter.fk), batch of {n:,}", "", porter)


# ---------------------------------------------------------------- inverse kinematics
def _porter_poses(n: int) -> np.ndarray:
    p = _porter()
    rng = np.random.default_rng(1)
    q = np.column_stack(
        [rng.uniform(0, 2 * np.pi, (n, 2)), rng.uniform(0.2, 1.5, n), rng.uniform(0, 2 * np.pi, (n, 3))]
    )
    return p.fk(q, *PORTER_L)


def ik_rows(n_scalar: int, n_batch: int) -> None:
    from puma_course.robots import puma560

    arm = puma560()
    rng = np.random.default_rng(2)
    T_scalar = arm.fk(rng.uniform(-np.pi, np.pi, (n_scalar, 6)))
    T_batch = arm.fk(rng.uniform(-np.pi, np.pi, (n_batch, 6)))

    def per_pose(fn: Callable[[np.ndarray], object], Ts: np.ndarray) -> str:
        return f"{best(lambda: [fn(T) for T in Ts], 3) / len(Ts) * 1e6:.1f} µs/pose"

    def porter_v1() -> str:
        p = _porter()
        return per_pose(lambda T: p.ik_explicit(T, *PORTER_L), _porter_poses(n_scalar))

    def porter_v2() -> str:
        p = _porter()
        return per_pose(lambda T: p.ik_geometric(T, *PORTER_L), _porter_poses(n_scalar))

    def porter_batch() -> str:
        p = _porter()
        Ts = _porter_poses(n_batch)
        return f"{best(lambda: p.ik_explicit_batch(Ts, *PORTER_L), 3) / n_batch * 1e6:.2f} µs/pose"

    def puma_scalar() -> str:
        return per_pose(arm.ik, T_scalar)

    def puma_batch() -> str:
        return f"{best(lambda: arm.ik_batch(T_batch), 3) / n_batch * 1e6:.2f} µs/pose"

    row("all-solution ik Porter Ver.1 (porter.ik_explicit), one pose per call", "≤ 200 µs/pose", porter_v1)
    row("all-solution ik Porter Ver.2 (porter.ik_geometric), one pose per call", "", porter_v2)
    row(f"all-solution ik Porter Ver.1 batch (ik_explicit_batch, {n_batch:,})", "", porter_batch)
    row("all-solution ik PUMA-560 (puma560().ik), one pose per call", "≤ 100 µs/pose", puma_scalar)
    row(f"all-solution ik PUMA-560 batch (ik_batch, {n_batch:,})", "", puma_batch)


# ---------------------------------------------------------------- trajectories
def trajectory_rows() -> None:
    def puma() -> str:
        from puma_course import trajectories as tr
        from puma_course.robots import puma560

        arm = puma560()
        q0 = arm.q("qn")
        T0 = arm.fk(q0)
        path = tr.circle_path(T0[:3, 3] - [0, 0.1, 0], 0.1, [1, 0, 0], T0[:3, :3], 1000, start=[0, 1, 0])
        cand = tr.puma_candidates(arm)
        return f"{best(lambda: tr.follow(path, cand, q0), 5):.4f} s"

    def porter() -> str:
        from puma_course import trajectories as tr

        p = _porter()
        q0 = np.array([0.3, 0.4, 1.0, 0.5, 0.6, 0.7])
        T0 = p.fk(q0, *PORTER_L)
        path = tr.circle_path(T0[:3, 3] - [0, 0.3, 0], 0.3, [0, 0, 1], T0[:3, :3], 1000, start=[0, 1, 0])
        cand = tr.porter_candidates(*PORTER_L)
        return f"{best(lambda: tr.follow(path, cand, q0, revolute=tr.PORTER_REVOLUTE), 5):.4f} s"

    row("trajectory, 1,000 poses, PUMA-560 (batched ik + nearest continuation)", "≤ 0.2 s", puma)
    row("trajectory, 1,000 poses, Porter's chain (Ver.1 batch + nearest)", "≤ 0.2 s", porter)


# ---------------------------------------------------------------- import time
def import_row() -> None:
    def measure() -> str:
        def run(code: str) -> float:
            t = time.perf_counter()
            subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT, capture_output=True)
            return time.perf_counter() - t

        bare = min(run("pass") for _ in range(5))
        numpy_only = min(run("import numpy") for _ in range(5))
        full = min(run("import puma_course") for _ in range(5))
        heavy = subprocess.run(
            [
                sys.executable,
                "-c",
                "import sys, puma_course; "
                "print(', '.join(sorted({'sympy', 'matplotlib', 'ipywidgets'} & set(sys.modules))))",
            ],
            check=True,
            cwd=ROOT,
            capture_output=True,
            text=True,
        ).stdout.strip()
        return (
            f"{(full - bare) * 1e3:.0f} ms, of which numpy {(numpy_only - bare) * 1e3:.0f} ms "
            f"(sympy/matplotlib/ipywidgets loaded: {heavy or 'none'})"
        )

    row("`import puma_course` (fresh process, minus bare python)", "fast: numpy only", measure)


# ---------------------------------------------------------------- notebooks and grading
def notebook_rows(timeout: int) -> None:
    try:
        import nbformat
        from nbclient import NotebookClient
    except ImportError as err:
        rows.append(("notebook execution", f"n/a ({err})", ""))
        return
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    if not notebooks:
        rows.append(("notebook execution", "n/a (no notebooks)", ""))
    for nb_path in notebooks:

        def run(nb_path: Path = nb_path) -> str:
            nb = nbformat.read(nb_path, as_version=4)
            client = NotebookClient(
                nb, timeout=timeout, kernel_name="python3", resources={"metadata": {"path": str(nb_path.parent)}}
            )
            t = time.perf_counter()
            client.execute()
            return f"{time.perf_counter() - t:.1f} s"

        row(f"execute notebooks/{nb_path.name} (fresh kernel, incl. start-up)", "seconds", run)


def grading_rows() -> None:
    script = ROOT / "benchmarks" / "bench_grading.py"
    if not script.exists():
        rows.append(("grading, seconds per notebook", "n/a (benchmarks/bench_grading.py not present)", ""))
        return
    try:
        out = subprocess.run(
            [sys.executable, str(script)], cwd=ROOT, capture_output=True, text=True, timeout=900, check=False
        )
        text = (out.stdout.strip() or out.stderr.strip()).splitlines()
        lines = [ln for ln in text if ln.strip()]
        if out.returncode != 0 or not lines:
            rows.append(("grading (bench_grading.py)", f"n/a (exit {out.returncode}: {' '.join(lines[-1:])[:80]})", ""))
            return
        table = [ln for ln in lines if ln.startswith("|") and "---" not in ln]
        if table:  # a Markdown table of its own: take its body rows
            for ln in table[1:]:
                cells = [c.strip() for c in ln.strip("|").split("|")]
                rows.append((f"grading: {cells[0]}", " / ".join(cells[1:]), ""))
        else:
            for ln in lines[-5:]:
                rows.append(("grading (bench_grading.py)", ln.strip()[:200], ""))
    except Exception as err:  # noqa: BLE001
        rows.append(("grading (bench_grading.py)", f"n/a (error {type(err).__name__}: {err})", ""))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip notebook execution and grading")
    ap.add_argument("--n", type=int, default=100_000, help="batch size for fk and batched ik (default 100,000)")
    ap.add_argument("--timeout", type=int, default=600, help="per-cell timeout when executing notebooks (s)")
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    os.environ.setdefault("MPLBACKEND", "Agg")

    fk_rows(args.n)
    ik_rows(n_scalar=500, n_batch=args.n)
    trajectory_rows()
    import_row()
    if not args.quick:
        notebook_rows(args.timeout)
        grading_rows()

    print(
        f"Benchmarks on {platform.node() or 'this machine'}: {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, numpy {np.__version__}\n"
    )
    print("| quantity | measured | target |")
    print("| --- | --- | --- |")
    for what, value, target in rows:
        print(f"| {what} | {value} | {target} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
