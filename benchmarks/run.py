"""Speed and memory of the course's kinematics on this machine, printed as a Markdown table.

Run from the repository root::

    python benchmarks/run.py            # everything, including executing every lecture (~1-2 min)
    python benchmarks/run.py --quick    # skip the notebooks and the 10^6-pose memory run
    python benchmarks/run.py --kinematics  # only the one-pose fk, Jacobian and ik rows, side by side

Robotics Toolbox for Python is measured side by side when it is installed
(``pip install ".[bench]"``): its DH model (``DHRobot.fkine``), its compiled ETS path
(``ETS.eval``), its Jacobians (``ETS.jacob0``, compiled; ``DHRobot.jacob0``) and its analytic PUMA
inverse (``ikine_a``, run for all eight configurations as ours gives all eight solutions); the same
poses for both, and the ratio peer/ours printed. Figures are the best of a few repeats;
per-pose times for batches divide the batch time by its size. Nothing here is asserted: tests
never check timings (shared, noisy machines); quote ratios, and rerun on an idle machine.
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
rows: list[tuple[str, str, str, str]] = []


def best(fn: Callable[[], object], repeat: int = 5, number: int = 1) -> float:
    """Best wall time per call (seconds) of ``number`` calls, over ``repeat`` repeats."""
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t) / number)
    return min(times)


def row(what: str, target: str, ours: Callable[[], str], peer: Callable[[], str] | None = None) -> None:
    """Add a table row (ours, the peer's); a failing measurement becomes ``n/a`` with the reason."""

    def safe(fn: Callable[[], str] | None) -> str:
        if fn is None:
            return ""
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                return fn()
        except ImportError as err:
            return f"n/a ({err.name} not installed)"
        except Exception as err:  # noqa: BLE001 - one row must not stop the others
            return f"n/a ({type(err).__name__}: {str(err)[:60]})"

    a, b = safe(ours), safe(peer)
    rows.append((what, a, b, target))
    print(f"  {what}: {a}" + (f"   [RTB: {b}]" if b else ""), file=sys.stderr, flush=True)


def _us(seconds: float) -> str:
    return f"{seconds * 1e6:.1f} µs"


def _ns_per(seconds: float, n: int) -> str:
    return f"{seconds / n * 1e9:.0f} ns/pose"


#: Robotics Toolbox's eight arm configurations (left/right, up/down, noflip/flip): ikine_a gives one per call.
CONFIGS = tuple(s + e + w for s in "lr" for e in "ud" for w in "nf")


def _rtb_puma():  # noqa: ANN202 - an optional dependency
    import roboticstoolbox as rtb

    return rtb.models.DH.Puma560()


def robots() -> dict[str, object]:
    from puma_course import MK3, Porter, Puma560, ThreeStepArm

    return {"PUMA-560": Puma560(), "MK3": MK3(), "Porter": Porter(1.0, 0.5, 0.3), "three-step arm": ThreeStepArm()}


def _qs(robot, n: int, seed: int = 0) -> np.ndarray:  # noqa: ANN001
    rng = np.random.default_rng(seed)
    return rng.uniform(robot.qlim[:, 0], robot.qlim[:, 1], (n, robot.n))


# ---------------------------------------------------------------- forward kinematics
def fk_rows(n: int, batch: bool = True) -> None:
    for name, arm in robots().items():
        q1 = _qs(arm, 1)[0]
        Q = _qs(arm, n)
        peer1 = peerN = None
        if name == "PUMA-560":

            def peer1(q1: np.ndarray = q1) -> str:
                p = _rtb_puma()
                ets = p.ets()
                return f"DH {_us(best(lambda: p.fkine(q1), 5, 2000))}, ETS {_us(best(lambda: ets.eval(q1), 5, 5000))}"

            def peerN(Q: np.ndarray = Q) -> str:
                p = _rtb_puma()
                Qs = Q[:10_000]
                return (f"DH {_ns_per(best(lambda: p.fkine(Qs), 1), len(Qs))}, "
                        f"ETS {_ns_per(best(lambda: p.ets().fkine(Qs), 2), len(Qs))}")  # fmt: skip

        target1 = "≤ 5 µs" if name == "PUMA-560" else "≤ 15 µs"
        row(f"fk {name}, one pose", target1, lambda arm=arm, q1=q1: _us(best(lambda: arm.fk(q1), 5, 5000)), peer1)
        if batch:
            row(f"fk {name}, batch of {n:,}", "≤ 1.5x 0.3-0.5 µs/pose" if name == "PUMA-560" else "",
                lambda arm=arm, Q=Q: _ns_per(best(lambda: arm.fk(Q), 3), n), peerN)  # fmt: skip


# ---------------------------------------------------------------- inverse kinematics
def _ik_peer(arm, q: np.ndarray, T: np.ndarray) -> str:  # noqa: ANN001
    """``ikine_a`` run for the eight configurations of 20 poses against our ``ik`` (all eight) of the same poses."""
    p = _rtb_puma()
    Ts = [p.fkine(qq) for qq in q[:20]]  # its own poses of the same joint vectors (its table differs from ours)
    rtb = best(lambda: [p.ikine_a(t, c) for t in Ts for c in CONFIGS], 3) / len(Ts)
    ours = best(lambda: [arm.ik(t) for t in T[:20]], 5) / len(Ts)
    # the ratio is to our figure timed beside the peer's (printed with it), not to the row's own timing
    return f"`ikine_a` for the 8 configurations {_us(rtb)} ({rtb / ours:.1f}x ours at {_us(ours)}, timed beside it)"


def ik_rows(n: int, batch: bool = True) -> None:
    for name, arm in robots().items():
        if not batch and name != "PUMA-560":
            continue
        q = _qs(arm, 200, 1)
        T = arm.fk(q)
        Tb = arm.fk(_qs(arm, n, 2))
        peer = None
        if name == "PUMA-560":

            def peer(arm=arm, q: np.ndarray = q, T: np.ndarray = T) -> str:  # noqa: ANN001
                return _ik_peer(arm, q, T)

        def one(arm=arm, T=T) -> str:  # noqa: ANN001
            return _us(best(lambda: [arm.ik(t) for t in T], 5) / len(T))

        target = "≤ 1.5x 23-28 µs" if name == "PUMA-560" else ""
        row(f"ik {name}, every solution of one pose", target, one, peer)
        if not batch:
            continue
        row(
            f"ik_batch {name}, {n:,} poses",
            "",
            lambda arm=arm, Tb=Tb: f"{best(lambda: arm.ik_batch(Tb), 2) / n * 1e6:.2f} µs/pose",
        )


# ---------------------------------------------------------------- Jacobian
def jacobian_rows() -> None:
    """The geometric Jacobian of one pose (per pose, the same 200 poses for both) and of a batch.

    Robotics Toolbox's ``jacob0`` is the Jacobian of the last frame of its standard-DH PUMA, whose origin
    is the wrist centre as ours is (its table adds a base height and puts the joint zeros elsewhere, so
    the numbers differ; the work is the same 6 x 6 of a spherical-wrist arm); ``ETS.jacob0`` is its
    compiled C path, ``DHRobot.jacob0`` its Python one.
    """
    arm = robots()["PUMA-560"]
    Q = _qs(arm, 200, 3)
    Qb = _qs(arm, 100_000, 4)
    from puma_course.kinematics.jacobian import geometric_jacobian

    def ours() -> float:
        return best(lambda: [arm.jacobian(q) for q in Q], 7) / len(Q)

    def peer() -> str:
        p = _rtb_puma()
        ets = p.ets()
        c = best(lambda: [ets.jacob0(q) for q in Q], 7) / len(Q)
        dh = best(lambda: [p.jacob0(q) for q in Q[:20]], 3) / 20
        mine = ours()
        # the ratios are to our figure timed beside the peer's (printed with them), not to the row's own timing
        return (f"ETS.jacob0 (C) {_us(c)} ({c / mine:.1f}x ours at {_us(mine)}, timed beside it), "
                f"DHRobot.jacob0 {_us(dh)} ({dh / mine:.0f}x ours)")  # fmt: skip

    row("Jacobian PUMA-560, one pose (closed form)", "≤ ETS.jacob0", lambda: _us(ours()), peer)
    row("Jacobian PUMA-560, one pose, generic DH walk (`geometric_jacobian`)", "",
        lambda: _us(best(lambda: [geometric_jacobian(arm, q) for q in Q], 7) / len(Q)))  # fmt: skip
    row(f"Jacobian PUMA-560, batch of {len(Qb):,}", "",
        lambda: _ns_per(best(lambda: arm.jacobian(Qb), 3), len(Qb)))  # fmt: skip


def ik_memory_row(n: int) -> None:
    """Peak resident memory of Puma560().ik_batch on n poses, in a fresh process, against the result's size."""
    code = f"""
import resource, numpy as np
from puma_course import Puma560
arm = Puma560()
q = np.random.default_rng(0).uniform(-np.pi, np.pi, ({n}, 6))
T = arm.fk(q)
del q
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
b = arm.ik_batch(T)
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
size = b.q.nbytes + b.valid.nbytes + b.flags.nbytes + b.reason.nbytes
print((peak - base) * 1024, size)
"""

    def measure() -> str:
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
        peak, size = int(out[0]), int(out[1])
        return f"peak +{peak / 2**20:.0f} MiB for a {size / 2**20:.0f} MiB result ({peak / size:.1f}x)"

    row(
        f"ik_batch PUMA-560 working memory, {n:,} poses", "a few times the result (before: 2.9 GB for 440 MiB)", measure
    )


# ---------------------------------------------------------------- trajectories, import, notebooks
def trajectory_rows() -> None:
    from puma_course import Porter, Puma560
    from puma_course.kinematics import trajectories as tr

    arm = Puma560()
    q0 = arm.q("qn")
    T0 = arm.fk(q0)
    path = tr.circle_path(T0[:3, 3] - [0, 0.1, 0], 0.1, [1, 0, 0], T0[:3, :3], 1000, start=[0, 1, 0])
    row("trajectory, 1,000 poses, PUMA-560 (batched ik + nearest)", "≤ 0.2 s",
        lambda: f"{best(lambda: tr.follow(arm, path, q0), 3):.4f} s")  # fmt: skip
    pa = Porter(1.0, 0.5, 0.3)
    qp = np.array([0.3, 0.4, 1.0, 0.5, 0.6, 0.7])
    Tp = pa.fk(qp)
    pp = tr.line_path(Tp, Tp[:3, 3] + [0.3, 0.2, 0.4], 1000)
    row("trajectory, 1,000 poses, Porter (Ver.1 batch + nearest)", "≤ 0.2 s",
        lambda: f"{best(lambda: tr.follow(pa, pp, qp), 3):.4f} s")  # fmt: skip


def import_row() -> None:
    def measure() -> str:
        def run(code: str) -> float:
            return best(lambda: subprocess.run([sys.executable, "-c", code], check=True), 5)

        bare, np_, pkg = run("pass"), run("import numpy"), run("import puma_course")
        heavy = subprocess.run(
            [sys.executable, "-c", "import sys, puma_course; print(','.join(m for m in ('sympy', 'matplotlib', "
             "'ipywidgets', 'nbformat') if m in sys.modules) or 'none')"],
            capture_output=True, text=True, check=True,
        ).stdout.strip()  # fmt: skip
        return (
            f"{(pkg - bare) * 1e3:.0f} ms, of which numpy {(np_ - bare) * 1e3:.0f} ms (heavy modules loaded: {heavy})"
        )

    row("import puma_course (fresh process, minus bare python)", "numpy only", measure)


def notebook_rows() -> None:
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):

        def run(nb: Path = nb) -> str:
            import nbformat
            from nbclient import NotebookClient

            doc = nbformat.read(nb, as_version=4)
            t = time.perf_counter()
            NotebookClient(
                doc, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(nb.parent)}}
            ).execute()
            return f"{time.perf_counter() - t:.1f} s"

        row(f"execute {nb.relative_to(ROOT)} (fresh kernel, incl. start-up)", "seconds", run)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the notebooks and the 10^6-pose memory run")
    parser.add_argument("--kinematics", action="store_true", help="only the one-pose fk, Jacobian and ik rows")
    parser.add_argument("--n", type=int, default=100_000, help="batch size for the per-pose figures")
    args = parser.parse_args()
    os.chdir(ROOT)
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"numpy {np.__version__}", file=sys.stderr)  # fmt: skip
    if args.kinematics:
        fk_rows(0, batch=False)
        jacobian_rows()
        ik_rows(0, batch=False)
        _print_table()
        return
    fk_rows(args.n)
    jacobian_rows()
    ik_rows(args.n)
    if not args.quick:
        ik_memory_row(1_000_000)
    trajectory_rows()
    import_row()
    if not args.quick:
        notebook_rows()
    _print_table()


def _print_table() -> None:
    print("| quantity | puma_course | Robotics Toolbox | target |")
    print("| --- | --- | --- | --- |")
    for what, ours, peer, target in rows:
        print(f"| {what} | {ours} | {peer} | {target} |")


if __name__ == "__main__":
    main()
