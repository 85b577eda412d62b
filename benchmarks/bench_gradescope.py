"""Benchmark: the issue-30 attacks on the Gradescope autograder, per zip, run as Gradescope runs it (figures printed).

    python benchmarks/bench_gradescope.py ZIP_DIR [RUNS]

``ZIP_DIR`` holds ``ex01_rotations.zip`` and ``ex09_puma_ik.zip`` built by ``puma-course gradescope`` (by this
version, or by an earlier one: check out the other version elsewhere and build them there). Each zip's
``setup.sh`` runs once in a throwaway container (:mod:`tests.grading.publish.container`; offline, the venv seeing this
Python's site-packages: an earlier ``setup.sh`` without ``PUMA_VENV_OPTIONS`` is edited to do the same), then
each attack in ``tests/fixtures/hostile/gradescope/`` is graded ``RUNS`` times (default 3) with Docker's
capabilities and with all of them. Printed per run: the score, run_autograder's exit code, whether the attack
signalled a leak (exit code 97), whether results.json was forged, ex09 q2's score, the seconds. Root only.
"""

from __future__ import annotations

import secrets
import shutil
import sys
import tempfile
import time
import uuid
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.grading.hostile.harness import _notebook, of  # noqa: E402
from tests.grading.publish import container as c  # noqa: E402


def main(zips: Path, runs: int) -> None:
    work = Path(tempfile.mkdtemp(prefix="bench-gradescope-"))
    try:
        images = {}
        for ex in ("ex01_rotations", "ex09_puma_ik"):
            tree = c.lay_out(zips / f"{ex}.zip", work / ex)
            setup = (tree / "source" / "setup.sh").read_text()
            if "PUMA_VENV_OPTIONS" not in setup:
                venv = "python3 -m venv /autograder"
                setup = setup.replace(venv, venv.replace("venv", "venv --system-site-packages", 1))
                (tree / "source" / "setup.sh").write_text(setup)
            etc = c.copy_etc(work / ex / "etc")
            env = {"PUMA_PIP_OPTIONS": "--no-index --no-deps", "PUMA_VENV_OPTIONS": "--system-site-packages"}
            env["PUMA_STUDENT_UID"] = str(61000 + secrets.randbelow(3000))
            done = c.container(tree, etc, ["/autograder/source/setup.sh"], env=env, etc_writable=True)
            if done.returncode != 0:
                sys.exit(f"setup.sh failed for {ex}: {done.stderr[-2000:]}")
            images[ex] = c.Image(tree, etc, 0, done)
        for param in of("gradescope"):
            fx = param.values[0]
            ex = fx.exercises[0]
            for caps in ("docker", "all"):
                rows = []
                for i in range(runs):
                    mark = f"puma-hostile-{uuid.uuid4().hex[:12]}"
                    nb = nbformat.writes(_notebook(fx, ex, {"MARK": mark})).encode()
                    t0 = time.perf_counter()
                    env = {"PUMA_HOSTILE_SECRET": mark}
                    r = c.run_submission(images[ex], work / f"{fx.name}-{caps}-{i}", nb, caps=caps, env=env)
                    res = r.results or {}
                    q2 = [t.get("score") for t in res.get("tests", []) if t["name"].startswith("q2 ")][:1]
                    forged = "forged" in res or res.get("output") == "all good"
                    leak = "exit code 97" in res.get("output", "")
                    rows.append(
                        f"score={res.get('score')} rc={r.returncode} leak={leak} forged={forged} q2={q2} "
                        f"{time.perf_counter() - t0:.1f}s"
                    )
                print(f"{fx.name:26s} {caps:6s} | " + " | ".join(rows), flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    if c.why_not():
        sys.exit(f"cannot run here: {c.why_not()}")
    main(Path(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 3)
