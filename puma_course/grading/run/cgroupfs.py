"""The control-group file system as :mod:`.limits` and :mod:`.delegation` use it: its files read and written.

Reading a counter (:func:`_int`, :func:`_key`), writing a setting (:func:`_write`), removing a group
whose last process has just been reaped (:func:`_rmdir`), the grader's own group per controller
(:func:`_own_groups`) and where the unified hierarchy is mounted (:func:`_v2_mount`).

>>> _own_groups("/nonexistent/cgroup")
{}
"""

from __future__ import annotations

import errno
import time
from pathlib import Path

__all__: list[str] = []


def _int(path: Path) -> int:
    try:
        return int(path.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return 0


def _key(path: Path, key: str) -> int:
    try:
        for line in path.read_text().splitlines():
            parts = line.split()
            if len(parts) == 2 and parts[0] == key:
                return int(parts[1])
    except (OSError, ValueError):
        pass
    return 0


def _rmdir(folder: Path) -> None:
    for _ in range(100):  # a killed process leaves its group a moment after it is reaped
        try:
            folder.rmdir()
            return
        except FileNotFoundError:
            return
        except OSError as exc:
            if exc.errno != errno.EBUSY:
                return
            time.sleep(0.02)


def _write(path: Path, value: str) -> None:
    with open(path, "w", encoding="ascii") as fh:
        fh.write(value)


def _own_groups(proc_cgroup: str) -> dict[str, str]:
    """The grader's own group by controller ("" for v2's unified line), from ``/proc/self/cgroup``."""
    out: dict[str, str] = {}
    try:
        text = Path(proc_cgroup).read_text()
    except OSError:
        return out
    for line in text.splitlines():
        parts = line.split(":", 2)
        if len(parts) == 3:
            for controller in parts[1].split(","):
                out[controller] = parts[2]
    return out


def _v2_mount(root: Path) -> Path | None:
    for candidate in (root, root / "unified"):
        if (candidate / "cgroup.controllers").exists():
            return candidate
    return None
