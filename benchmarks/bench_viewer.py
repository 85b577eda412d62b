"""Latency of a joint panel in a real browser: from a slider move to the repainted arm.

Starts JupyterLab on 127.0.0.1 (a random token, a temporary copy of the lectures), opens a
lecture in Debian's Chromium driven by Playwright, runs it, focuses a slider of its panel and
presses an arrow key ``--moves`` times (each press moves the joint one step). Each move is
timed in the page: from the key press (a capturing keydown listener, before the slider sees
it) to the end of the viewer's next render of a new pose (the kernel's answer has arrived,
the frames are set and WebGL has drawn). Prints every time, the median and quantiles; the
server is stopped by its PID.

    python benchmarks/bench_viewer.py                       # lecture 03, 20 moves of θ2
    python benchmarks/bench_viewer.py --notebook 05_porter_direct_problem.ipynb --slider 0
    python benchmarks/bench_viewer.py --ik                  # the IK panels: Porter's (06) and the PUMA's (09)

JupyterLab runs as ``puma-course lab`` starts it (default settings, windowed notebook).

The target of issue 13 is a median of at most 100 ms (the matplotlib panels took about 1 s).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.browser.lab import (  # noqa: E402
    Lab,
    browser,
    install_key_clock,
    missing,
    open_notebook,
    press_and_time,
    press_and_time_parts,
    run_all,
    viewers,
)


def _time_moves(page: object, lab: Lab, name: str, args: argparse.Namespace) -> tuple[list[float], list[float], str]:
    """Open and run lecture ``name``; time ``args.moves`` key presses on slider ``args.slider`` of its first panel."""
    p: Any = page
    open_notebook(p, lab, name)
    run_all(p)
    box = viewers(p).first
    box.wait_for(timeout=30_000)
    box.scroll_into_view_if_needed()
    p.wait_for_function("b => b.__puma.poseRenders >= 1", arg=box.element_handle())
    install_key_clock(p)
    handle = p.locator(".jp-Notebook .widget-slider .noUi-handle").nth(args.slider)
    handle.focus()
    for _ in range(args.warmup):
        press_and_time(p, handle, box)
    parts = [
        press_and_time_parts(p, handle, box, "ArrowRight" if k % 10 < 5 else "ArrowLeft") for k in range(args.moves)
    ]
    description = p.locator(".jp-Notebook .widget-slider .widget-label").nth(args.slider).inner_text()
    return [t for t, _ in parts], [m for _, m in parts], description


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--notebook", action="append", help="lecture to time (repeat for several; default 03)")
    ap.add_argument("--ik", action="store_true", help="time the IK panels: lectures 06 (Porter) and 09 (PUMA-560)")
    ap.add_argument("--slider", type=int, default=1, help="which slider of the panel (0 = first joint)")
    ap.add_argument("--moves", type=int, default=20)
    ap.add_argument("--warmup", type=int, default=2, help="moves before timing (first comm messages, JIT)")
    args = ap.parse_args(argv)
    why = missing()
    if why:
        print(f"cannot run: {why}", file=sys.stderr)
        return 2
    notebooks = list(args.notebook or [])
    if args.ik:
        notebooks += ["06_porter_inverse_explicit.ipynb", "09_puma560_inverse_kinematics.ipynb"]
    t0 = time.perf_counter()
    with Lab() as lab, browser() as b:
        for name in notebooks or ["03_puma560_forward_kinematics.ipynb"]:
            page = b.new_page(viewport={"width": 1400, "height": 1000})
            times, to_message, description = _time_moves(page, lab, name, args)
            page.close()
            q = statistics.quantiles(times, n=10, method="inclusive")
            print(f"{name}: slider {args.slider} ({description}), {len(times)} moves, key press -> repaint [ms]")
            print("  each: " + " ".join(f"{t:.0f}" for t in times))
            print(f"  min {min(times):.1f}  p10 {q[0]:.1f}  p25 {statistics.quantiles(times, n=4)[0]:.1f}  "
                  f"median {statistics.median(times):.1f}  p75 {statistics.quantiles(times, n=4)[2]:.1f}  "
                  f"p90 {q[-1]:.1f}  max {max(times):.1f}")  # fmt: skip
            print(f"  of which key press -> the kernel's pose arrives: median {statistics.median(to_message):.1f}, "
                  f"max {max(to_message):.1f}; the browser's draw after it: median "
                  f"{statistics.median([t - m for t, m in zip(times, to_message, strict=True)]):.1f}")  # fmt: skip
            print(f"  target: median <= 100 ms -> {'met' if statistics.median(times) <= 100 else 'NOT met'}")
    print(f"whole run {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
