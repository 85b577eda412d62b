"""Hostile fixtures against the Gradescope autograder, run as Gradescope runs it (issue 30).

Each attack in ``tests/fixtures/hostile/gradescope/`` is appended to the handed-out exercise and graded by the zip
``puma-course gradescope`` builds: ``setup.sh`` once (the image), then ``run_autograder`` as root in a fresh
throwaway container without bubblewrap (:mod:`tests.grading.publish.container`), with Docker's default capabilities
(no new namespaces: Gradescope's case) and with every capability (the grader's PID and mount namespaces).
The grader's environment holds a secret the attacks look for. Every attack must gain nothing: run_autograder
ends normally, results.json is the grader's (root's, written once, score 0, no leak signalled by exit code 97),
and the honest and blank notebooks of the same exercise get full marks and 0 in the same image.
"""

from __future__ import annotations

import json
import shutil
import time
import uuid
from pathlib import Path

import jsonschema
import nbformat
import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES
from tests.grading.hostile.harness import _notebook, of
from tests.grading.publish import container
from tests.grading.publish.test_gradescope import RESULTS_SCHEMA
from tests.support import ROOT

pytestmark = [
    pytest.mark.hostile,
    pytest.mark.skipif(bool(container.why_not()), reason=f"no throwaway container here: {container.why_not()}"),
]

CAPS = ["docker", "all"]
EXERCISES_USED = ("ex01_rotations", "ex09_puma_ik")


@pytest.fixture(scope="module")
def images(tmp_path_factory) -> dict[str, container.Image]:
    out = {}
    for ex in EXERCISES_USED:
        folder = tmp_path_factory.mktemp(ex)
        assert main(["gradescope", ex, "-o", str(folder / "a.zip"), "--course", str(ROOT)]) == 0
        image = container.build_image(folder / "a.zip", folder / "image")
        assert image.setup.returncode == 0, image.setup.stdout[-2000:] + image.setup.stderr[-2000:]
        out[ex] = image
    return out


def _grade(image: container.Image, tmp: Path, notebook: bytes, caps: str, mark: str) -> container.Run:
    run = container.run_submission(image, tmp, notebook, caps=caps, env={"PUMA_HOSTILE_SECRET": mark})
    assert run.returncode == 0, (run.stdout[-2000:], run.stderr[-2000:])  # the grader was not killed
    assert run.results is not None, run.stderr[-2000:]
    jsonschema.validate(run.results, RESULTS_SCHEMA)
    # results.json is root's, written once by rename (one link), in a folder only root may open
    st = run.results_stat
    assert st is not None and st.st_uid == 0 and st.st_nlink == 1 and not st.st_mode & 0o022
    folder = (run.tree / "results").stat()
    assert folder.st_uid == 0 and folder.st_mode & 0o777 == 0o700
    assert run.results["extra_data"]["sandbox"] == "user"
    output = run.results["output"]
    assert "unprivileged user puma-student" in output and "WARNING" not in output, output
    namespaces = "in PID and mount namespaces of its own" in output
    assert namespaces == (caps == "all"), output
    return run


@pytest.mark.parametrize("caps", CAPS)
@pytest.mark.parametrize(("fx", "mode"), of("gradescope"))
def test_gradescope_attack_gains_nothing(fx, mode, caps, images, tmp_path):
    (exercise,) = fx.exercises
    mark = f"puma-hostile-{uuid.uuid4().hex[:12]}"
    nb = _notebook(fx, exercise, {"MARK": mark})
    start = time.monotonic()
    run = _grade(images[exercise], tmp_path, nbformat.writes(nb).encode(), caps, mark)
    r = run.results
    assert r is not None
    assert "exit code 97" not in r["output"], r["output"]  # no leak signalled
    if fx.expect == "earned":  # riding on the solution: the grader finishes normally, in no longer than a grading
        full = sum(q.points for q in EXERCISES[exercise].questions)
        took = time.monotonic() - start
        assert "autograder failed" not in r["output"], r["output"]
        if caps == "all":  # in a PID namespace of its own, the worker's end ends the daemon: the solution's marks
            assert r["score"] == full and "status: ok" in r["output"] and took < 120, (took, r["output"])
        else:  # without one, the daemon also stops the student's own worker (its 60 s total limit): its own marks
            assert r["score"] <= full and "were still running after it ended: they were stopped" in r["output"]
            assert took < 200, took  # the notebook's limit and the grading, not a kill helper's timeout on top
        return
    assert "forged" not in r and r["score"] == 0, r["output"]
    assert all(t.get("score", 0) == 0 for t in r["tests"]), r["tests"]
    assert r["extra_data"]["exercise"] == exercise and isinstance(r["extra_data"]["seed"], int)
    assert mark not in json.dumps(r)
    if fx.name == "daemon_rewrites_results" and caps == "docker":
        # no namespace ends it with the worker: the grader found it by its uid and stopped it
        assert "were still running after it ended: they were stopped" in r["output"], r["output"]
    if fx.name == "site_packages_ik":
        q2 = [t for t in r["tests"] if t["name"].startswith("q2 ")][0]
        assert q2["score"] == 0 and "FAILED" in q2["output"], q2


@pytest.mark.parametrize("caps", CAPS)
@pytest.mark.parametrize("exercise", EXERCISES_USED)
def test_honest_and_blank_in_the_same_image(exercise, caps, images, tmp_path):
    full = sum(q.points for q in EXERCISES[exercise].questions)
    for folder, want in (("solutions", full), ("exercises", 0)):
        run = _grade(images[exercise], tmp_path / folder, (ROOT / folder / f"{exercise}.ipynb").read_bytes(), caps, "x")
        assert run.results is not None and run.results["score"] == want, run.results
        assert "status: ok" in run.results["output"]


def test_without_the_user_nothing_runs_as_root(images, tmp_path):
    """An image whose setup made no puma-student (and a read-only /etc: it cannot be made now) grades nothing."""
    image = images["ex01_rotations"]
    etc = tmp_path / "etc"
    shutil.copytree(image.etc, etc, symlinks=True)
    for name in ("passwd", "group", "shadow", "gshadow"):
        path = etc / name
        if path.is_file():
            lines = path.read_text().splitlines(keepends=True)
            path.write_text("".join(line for line in lines if not line.startswith("puma-student:")))
    nb = (ROOT / "solutions" / "ex01_rotations.ipynb").read_bytes()
    run = container.run_submission(container.Image(image.tree, etc, image.uid, image.setup), tmp_path / "run", nb)
    assert run.returncode == 0 and run.results is not None, run.stderr[-2000:]
    assert run.results["score"] == 0 and run.results["tests"] == []
    assert "not graded: the unprivileged user puma-student does not exist" in run.results["output"]
