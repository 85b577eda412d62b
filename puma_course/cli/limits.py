"""The ``puma-course limits`` command: the grader's per-notebook limits, and a delegated subtree for a user.

    puma-course limits show                         what a grading run here would get (as whoever runs it)
    puma-course limits delegate --user NAME         (root) a control-group subtree for NAME's grader
    puma-course limits delegate --user NAME --undo  (root) remove it, and every group under it

See :mod:`puma_course.grading.run.delegation`. Part of the ``cli`` layer: the grader is imported only when the
command runs.
"""

from __future__ import annotations

import argparse
import os
from typing import Any

__all__ = ["add_parser", "run"]


def add_parser(sub: Any, common: argparse.ArgumentParser) -> None:
    """The ``limits`` sub-command and its ``show`` and ``delegate`` actions (about this machine: no ``--course``,
    so ``common`` is not its parent)."""
    lim = sub.add_parser(
        "limits",
        help="show the grader's per-notebook limits here; (root) delegate a control-group subtree to a grading user",
        description="Without root, the grader limits each notebook's processes one by one (PER PROCESS ONLY). "
        "Root can delegate a control-group subtree to the grading user once; the grader run by that user then "
        "makes a control group per notebook under it ('per notebook (cgroup v1, delegated)').",
    )
    actions = lim.add_subparsers(dest="action", required=True, metavar="ACTION", help="show or delegate")
    actions.add_parser("show", help="the limits a grading run here would get, and why")
    dg = actions.add_parser("delegate", help="(root) give USER a control-group subtree for its grader")
    dg.add_argument("--user", required=True, metavar="NAME", help="the grading user (who runs puma-course grade)")
    dg.add_argument("--undo", action="store_true", help="remove the subtree and every group under it")


def run(args: argparse.Namespace) -> int:
    """``puma-course limits show|delegate``; raises ValueError (exit code 2) on bad input or without root."""
    from ..grading.run import delegation, limits

    if args.action == "show":
        run = limits.open_run()
        try:
            print(f"limits: {run.label}; {limits.call_limit(run, 10.0)}")
            for c, folder in run.folders.items():
                print(f"  {c}: a run's groups go under {folder.parent}")
        finally:
            run.close()
        return 0 if run.enforced else 1
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        raise ValueError("delegate: expected to run as root (it gives a user a control-group subtree), got a user")
    try:
        lines = delegation.undelegate(args.user) if args.undo else delegation.delegate(args.user)
    except OSError as exc:  # the hierarchy refused (read-only, or a v2 parent that holds processes)
        raise ValueError(f"delegate: the control-group file system refused: {exc}") from exc
    print("\n".join(lines))
    if args.undo:
        return 0
    print(f"undo: puma-course limits delegate --user {args.user} --undo")
    return 0
