"""Plain helpers shared by the test modules (fixtures live in conftest.py).

Import as ``from tests.support import ROOT, random_q``.
"""

from __future__ import annotations

import base64
import re
import struct
from pathlib import Path
from typing import Any

import numpy as np

#: The repository root (the course folder).
ROOT = Path(__file__).resolve().parents[1]


def random_q(n: int, seed: int, N: int | None = None, low: float = -np.pi, high: float = np.pi) -> np.ndarray:
    """Joint angles drawn uniformly from [low, high): shape (n,) or (N, n), reproducible by ``seed``."""
    rng = np.random.default_rng(seed)
    return rng.uniform(low, high, n if N is None else (N, n))


def jshtml_png_sizes(html: str) -> list[tuple[int, int]]:
    """(width, height) in pixels of every PNG frame embedded in an animation's ``to_jshtml()``, read from
    each PNG header (IHDR), so a test can check the figure's dpi was kept."""
    frames = re.findall(r"data:image/png;base64,((?:[A-Za-z0-9+/=]|\\\n)+)", html)
    sizes = []
    for b64 in frames:
        png = base64.b64decode(b64.replace("\\\n", ""))
        sizes.append(struct.unpack(">II", png[16:24]))
    return sizes


def assert_no_overlap(boxes: list, pad: float = 0.0) -> None:
    """No two of the matplotlib Bboxes overlap (each grown by ``pad`` pixels)."""
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not a.padded(pad).overlaps(b.padded(pad)), f"{a} overlaps {b}"


def course_site(tmp_path_factory: Any) -> tuple[Path, str]:
    """The course site as ``puma-course site -o DIR`` builds it (docs/website.md): ``(DIR, what it printed)``.

    Built once per test run and shared by every test that reads it (tests/site/test_build.py,
    tests/browser/test_site.py, tests/browser/test_axe.py), whichever pytest worker runs them: the first
    to ask builds it under a lock in the folder the run's workers share, keyed by the course's files (git's
    tracked and untracked, not ignored), and the others wait and read it. Nothing may write into it.
    """
    import fcntl
    import hashlib
    import os
    import subprocess
    import sys

    base = Path(tmp_path_factory.getbasetemp())
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base  # pytest-N/ holds every worker's popen-gwK
    files = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT, capture_output=True, check=True,
    ).stdout.split(b"\0")  # fmt: skip
    digest = hashlib.sha256(sys.version.encode())
    for name in sorted(f for f in files if f):
        path = ROOT / os.fsdecode(name)
        if path.is_file():
            digest.update(name + b"\0" + path.read_bytes())
    folder = shared / f"course-site-{digest.hexdigest()[:16]}"
    folder.mkdir(parents=True, exist_ok=True)
    out, printed = folder / "html", folder / "printed.txt"
    with open(folder / "lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not printed.exists():
            command = Path(sys.executable).with_name("puma-course")
            argv = [str(command)] if command.exists() else [sys.executable, "-m", "puma_course.cli"]
            proc = subprocess.run(
                [*argv, "site", "--course", str(ROOT), "-o", str(out)],
                capture_output=True, text=True, timeout=1200,
            )  # fmt: skip
            assert proc.returncode == 0, f"puma-course site failed:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
            printed.write_text(proc.stdout, encoding="utf-8")
    return out, printed.read_text(encoding="utf-8")
