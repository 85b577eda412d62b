"""Benchmark: how big is each install? Print site-packages size and package count per extra, in fresh venvs.

    python benchmarks/bench_install.py [--course DIR] [--extras plain,lab,grader,dev] [--keep]

For each install (plain ``pip install DIR``, ``DIR[lab]``, ``DIR[grader]``, ``DIR[dev]``) it makes a
fresh virtual environment, installs the course non-editable with pip (the warm pip cache serves the
wheels), and prints the size of site-packages (every file, pip and setuptools included), the number
of distributions installed, and whether the heavy tools a student should not get (JupyterLab,
nbclient, Sphinx, Playwright, mypy) came with it. ``--course`` installs another folder, a student
edition written by ``puma-course edition DIR`` say. Figures are printed, never asserted.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("jupyterlab", "nbclient", "sphinx", "playwright", "mypy")


def measure(course: Path, extra: str, work: Path) -> dict[str, object]:
    """Install ``course`` (with ``extra``, "plain" for none) into a fresh venv under ``work``; its figures."""
    venv = work / f"venv-{extra}"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    target = str(course) if extra == "plain" else f"{course}[{extra}]"
    start = time.perf_counter()
    subprocess.run([str(python), "-m", "pip", "install", "--quiet", target], check=True, cwd=work)
    seconds = time.perf_counter() - start
    site = Path(
        subprocess.run(
            [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
            check=True, capture_output=True, text=True,
        ).stdout.strip()
    )  # fmt: skip
    size = sum(p.stat().st_size for p in site.rglob("*") if p.is_file() and not p.is_symlink())
    dists = sorted(p.name.split("-")[0].lower() for p in site.glob("*.dist-info"))
    heavy = [h for h in HEAVY if h in dists]
    return {"extra": extra, "mb": size / 1e6, "packages": len(dists), "heavy": heavy, "seconds": seconds}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--course", type=Path, default=ROOT, help="the folder to install (default: this course)")
    parser.add_argument("--extras", default="plain,lab,grader,dev", help="comma-separated: plain, lab, grader, dev")
    args = parser.parse_args()
    print(f"{'install':<10} {'site-packages':>14} {'packages':>9}  heavy tools     (pip, s)")
    with tempfile.TemporaryDirectory(prefix="puma-bench-install-") as tmp:
        for extra in args.extras.split(","):
            got = measure(args.course.resolve(), extra.strip(), Path(tmp))
            heavy = ", ".join(got["heavy"]) or "none"  # type: ignore[arg-type]
            print(f"{got['extra']:<10} {got['mb']:>11.0f} MB {got['packages']:>9}  {heavy:<15} ({got['seconds']:.0f})")


if __name__ == "__main__":
    main()
