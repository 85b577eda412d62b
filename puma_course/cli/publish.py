"""The ``puma-course`` commands that publish the course: ``site`` (its website) and ``edition`` (what students get).

Part of the ``cli`` layer: the builders are imported only when a command runs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from .options import course

__all__ = ["add_parser", "run_site", "run_edition"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``site`` and ``edition`` sub-commands (``common``: the shared ``--course`` option)."""
    site = sub.add_parser(
        "site",
        parents=[common],
        help="build the course's website (lectures, exercises, notation) into _site/",
        description="Build the course as a static website from the committed notebooks, without running them "
        "and without the network. Open <output>/index.html in a browser.",
    )
    site.add_argument(
        "-o", "--output", type=Path, default=None, metavar="DIR", help="where the site goes (default: <course>/_site)"
    )
    site.add_argument(
        "--repo-url",
        default=None,
        metavar="URL",
        help="the course's repository, linked from the landing page (default: [tool.puma-course] repository, "
        "else [project.urls] Repository, in the course's pyproject.toml; none when neither is set)",
    )
    ed = sub.add_parser(
        "edition",
        parents=[common],
        help="write the student edition (the course without its answer key) into DIR",
        description="Write the student edition into DIR: lectures, exercises, figures, the package, the self-check's "
        "public cases; no solution, bank, hidden test or seed. Again: updates DIR in place, its .git untouched.",
    )
    ed.add_argument("out", type=Path, metavar="DIR", help="where the edition goes (e.g. ../class-edition)")


def run_edition(args: argparse.Namespace) -> int:
    """``puma-course edition DIR``: the student edition of the course written into DIR."""
    from ..grading.output.text import plural
    from ..grading.publish.edition import write_edition

    ed = write_edition(args.out, course(args))
    made = f"{plural(len(ed.exercises), 'exercise')}, {plural(len(ed.files), 'file')}"
    print(f"wrote the student edition ({made}) to {ed.root}")
    return 0


def run_site(args: argparse.Namespace) -> int:
    """``puma-course site``: the course's website built (lectures, exercises, notation, the edition's archive)."""
    root = course(args)
    try:
        from ..site import build_site
    except ImportError as exc:  # pragma: no cover - the extra is missing
        print(f"puma-course site: {exc}; install the site's tools: pip install -e '.[site]'", file=sys.stderr)
        return 2
    from ..grading.publish.edition import write_edition

    report = build_site(root, args.output, repo_url=args.repo_url, edition=write_edition)
    print(
        f"built {len(report.pages)} pages in {report.seconds:.1f} s, {report.size_bytes / 1e6:.1f} MB: "
        f"open {report.out / 'index.html'} in a browser"
    )
    for line in report.warnings[:20]:
        print(f"  sphinx: {line}", file=sys.stderr)
    return 0
