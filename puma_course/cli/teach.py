"""``puma-course slides`` and ``puma-course keys``: the instructor's kit (:mod:`puma_course.instructor`).

    puma-course slides [--course DIR] [-o DIR] [--lecture NN ...]
    puma-course keys [--course DIR] [-o DIR]

Part of the ``cli`` layer: the kit is imported only when a command runs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from .options import course

__all__ = ["add_parser", "run_slides", "run_keys"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``slides`` and ``keys`` sub-commands (``common``: the shared ``--course`` option)."""
    slides = sub.add_parser(
        "slides",
        parents=[common],
        help="build every lecture's reveal.js slides into _slides/ (offline; instructor's kit)",
        description="Build reveal.js slides of the lectures with jupyter nbconvert, from the committed notebooks "
        "(their slideshow metadata), without running them; reveal.js and MathJax are copied beside the slides, "
        "so they open offline. Press s in a slide show for the speaker view.",
    )
    slides.add_argument("-o", "--output", type=Path, default=None, metavar="DIR", help="default: <course>/_slides")
    slides.add_argument("--lecture", action="append", default=[], metavar="NN", help="only lecture NN (repeatable)")
    keys = sub.add_parser(
        "keys",
        parents=[common],
        help="render the worked answer keys (solutions/) to instructor-only HTML in _keys/",
        description="Render solutions/*.ipynb with their outputs to HTML pages and an index, for the instructor "
        "only (never publish them where students read).",
    )
    keys.add_argument("-o", "--output", type=Path, default=None, metavar="DIR", help="default: <course>/_keys")


def _report(kind: str, report: Any, first: Path) -> int:
    print(
        f"built {len(report.files)} {kind} in {report.seconds:.1f} s, {report.size / 1e6:.1f} MB: "
        f"open {first} in a browser"
    )
    return 0


def run_slides(args: argparse.Namespace) -> int:
    """``puma-course slides``: every lecture's (or each ``--lecture``'s) reveal.js slides."""
    from ..instructor import build_slides

    report = build_slides(course(args), args.output, tuple(args.lecture))
    return _report("slide shows", report, report.files[0])


def run_keys(args: argparse.Namespace) -> int:
    """``puma-course keys``: the worked answer keys as instructor-only HTML."""
    from ..instructor import build_keys

    report = build_keys(course(args), args.output)
    print("instructor only: these pages hold the answers", file=sys.stderr)
    return _report("answer pages", report, report.out / "index.html")
