"""The control-group file system as :mod:`.limits` and :mod:`.delegation` use it: its files read and written.

Reading a counter (:func:`read_int`, :func:`read_key`), writing a setting (:func:`write_setting`), removing a group
whose last process has just been reaped (:func:`remove_group`), the grader's own group per controller
(:func:`own_groups`) and where the unified hierarchy is mounted (:func:`v2_mount`).

>>> own_groups("/nonexistent/cgroup")
{}
"""

from __future__ import annotations

import errno
import time
from pathlib import Path

__all__ = ["read_int", "read_key", "remove_group", "write_setting", "own_groups", "v2_mount"]


def read_int(path: Path) -> int:
    """The number at the start of a counter file (0 when it cannot be read)."""
    try:
        return int(path.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return 0


def read_key(path: Path, key: str) -> int:
    """The number after ``key`` in a file of ``key value`` lines (0 when absent or unreadable)."""
    try:
        for line in path.read_text().splitlines():
            parts = line.split()
            if len(parts) == 2 and parts[0] == key:
                return int(parts[1])
    except (OSError, ValueError):
        pass
    return 0


def remove_group(folder: Path) -> None:
    """Remove a group's folder, waiting up to 2 s while the kernel still holds it (gone already: nothing to do)."""
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


def write_setting(path: Path, value: str) -> None:
    """Write a setting (one value) into a control-group file."""
    with open(path, "w", encoding="ascii") as fh:
        fh.write(value)


def own_groups(proc_cgroup: str) -> dict[str, str]:
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


def v2_mount(root: Path) -> Path | None:
    """Where the unified (v2) hierarchy is mounted under ``root`` (``root`` or ``root/unified``), or None."""
    for candidate in (root, root / "unified"):
        if (candidate / "cgroup.controllers").exists():
            return candidate
    return None
