"""The Gradescope autograder: the zip ``puma-course gradescope`` builds, run as Gradescope runs it.

Gradescope's tree (gradescope-autograders.readthedocs.io, "Autograder Specifications": ``/autograder/source`` = the
unpacked zip, ``/autograder/run_autograder``, ``/autograder/submission``, ``/autograder/results``) is laid out in a
temporary folder; ``setup.sh`` runs once in a throwaway container (offline), and ``run_autograder`` runs for each
submission in a fresh one, as root, with no bubblewrap inside (:mod:`tests.grading.publish.container`): with Docker's
default capabilities (no new namespaces, as on Gradescope) or with every capability (new namespaces allowed).
Every ``results.json`` is validated against :data:`RESULTS_SCHEMA`, written from that page's "Output format".
The attacks of issue 30 are in ``test_hostile_gradescope.py``.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import jsonschema
import nbformat
import pytest

from puma_course import __version__
from puma_course.cli import main
from puma_course.grading import EXERCISES, NotebookResult
from puma_course.grading.publish.gradescope import _bank_files, _find_notebook, results_json, wheel_name
from tests.grading.publish import container
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: the autograder zip and its container: packaging; an
# honest answer's numerics under this kernel are test_exercises' full marks.
pytestmark = pytest.mark.no_numerics

EX = "ex01_rotations"
#: the containers: Docker's default capabilities (Gradescope's case), every capability (new namespaces allowed)
CAPS = ["docker", "all"]

_VISIBILITY = {"enum": ["hidden", "after_due_date", "after_published", "visible"]}
_FORMAT = {"enum": ["text", "html", "simple_format", "md", "ansi"]}
#: results.json as Gradescope's "Output format" defines it (score required here: we always give it).
RESULTS_SCHEMA = {
    "type": "object",
    "required": ["score", "tests"],
    "additionalProperties": False,
    "properties": {
        "score": {"type": "number"},
        "execution_time": {"type": "number", "minimum": 0},
        "output": {"type": "string"},
        "output_format": _FORMAT,
        "test_output_format": _FORMAT,
        "test_name_format": _FORMAT,
        "visibility": _VISIBILITY,
        "stdout_visibility": _VISIBILITY,
        "extra_data": {"type": "object"},
        "tests": {
            "type": "array",
            "items": {
                "type": "object",
                "required": ["name"],
                "additionalProperties": False,
                "properties": {
                    "score": {"type": "number"},
                    "max_score": {"type": "number", "minimum": 0},
                    "status": {"enum": ["passed", "failed"]},
                    "name": {"type": "string"},
                    "name_format": _FORMAT,
                    "number": {"type": "string"},
                    "output": {"type": "string"},
                    "output_format": _FORMAT,
                    "tags": {"type": "array", "items": {"type": "string"}},
                    "visibility": _VISIBILITY,
                    "extra_data": {"type": "object"},
                },
            },
        },
        "leaderboard": {"type": "array"},
    },
}

HOSTILE_CELL = """
import json, os, subprocess
for target in ("/autograder/results/results.json", "/autograder/source/autograder.json"):
    try:
        with open(target, "w") as fh:
            json.dump({"score": 999, "tests": []}, fh)
    except Exception:
        pass
try:
    from puma_course.grading import EXERCISES  # the answer key: absent from the student's package
    print("LEAKED", len(EXERCISES))
except Exception:
    pass
def elementary_rotation(axis, angle):
    # fails the public cases with one reason (raises) and each hidden case with its own, so the hidden
    # cases' details are among the notes whatever the number of public cases
    if round(float(angle), 6) in (0.4, -1.2, 2.0, 1.570796, 1.1):
        raise ValueError("not today")
    return __import__("numpy").eye(3) * 999
"""


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("zip") / "a.zip"
    assert main(["gradescope", EX, "-o", str(out), "--course", str(ROOT)]) == 0
    return out


@pytest.fixture(scope="module")
def image(autograder_zip, tmp_path_factory) -> container.Image:
    if container.why_not():
        pytest.skip(f"no throwaway container here: {container.why_not()}")
    made = container.build_image(autograder_zip, tmp_path_factory.mktemp("image"))
    assert made.setup.returncode == 0, made.setup.stdout[-2000:] + made.setup.stderr[-2000:]
    return made


def _run(image: container.Image, tmp_path: Path, notebook: bytes | None, caps: str = "docker") -> dict:
    done = container.run_submission(image, tmp_path, notebook, caps=caps)
    assert done.returncode == 0, done.stderr[-2000:]
    results = done.results
    assert results is not None, done.stderr[-2000:]
    jsonschema.validate(results, RESULTS_SCHEMA)
    assert results["extra_data"]["sandbox"] == "user"
    # what the student sees says what held: the user, and the namespaces only where the container allowed them
    assert "ran as the unprivileged user puma-student (not root)" in results["output"], results["output"]
    assert ("in PID and mount namespaces of its own" in results["output"]) == (caps == "all")
    results["_source_config"] = json.loads((done.tree / "source" / "autograder.json").read_text(encoding="utf-8"))
    return results


def test_the_zip_holds_what_the_specification_asks_at_its_root(autograder_zip):
    with zipfile.ZipFile(autograder_zip) as zf:
        names = set(zf.namelist())
        assert {"setup.sh", "run_autograder", "autograder.json", f"dist/{wheel_name()}"} <= names
        for name in ("setup.sh", "run_autograder"):
            assert zf.getinfo(name).external_attr >> 16 & 0o111, f"{name} is not executable"
            assert zf.read(name).startswith(b"#!/usr/bin/env bash\n")
        assert f"dist/{wheel_name(__version__)}".encode() in zf.read("setup.sh")
        config = json.loads(zf.read("autograder.json"))
    assert config == {"exercise": EX, "version": __version__, "wheel": wheel_name()}


@pytest.mark.parametrize("caps", CAPS, ids=["docker-caps", "namespaces"])
def test_honest_notebook_gets_full_marks(image, tmp_path, caps):
    r = _run(image, tmp_path, (ROOT / "solutions" / f"{EX}.ipynb").read_bytes(), caps)
    assert r["score"] == 15
    scored = [t for t in r["tests"] if "max_score" in t]
    assert [t["name"].split()[0] for t in scored] == ["q1", "q2", "q3", "q4", "q5", "q6"]
    assert all(t["score"] == t["max_score"] and t["visibility"] == "visible" for t in scored)
    assert sum(t["max_score"] for t in scored) == 15
    assert "passed" in scored[0]["output"] and "15 / 15" in r["output"]
    feedback = [t for t in r["tests"] if t["name"] == "Feedback file"][0]
    assert feedback["visibility"] == "after_due_date" and "Total: **15 / 15**" in feedback["output"]
    assert r["extra_data"]["version"] == __version__


def test_blank_notebook_scores_0_and_hidden_case_details_wait_for_the_due_date(image, tmp_path):
    r = _run(image, tmp_path, (ROOT / "exercises" / f"{EX}.ipynb").read_bytes())
    assert r["score"] == 0
    scored = [t for t in r["tests"] if "max_score" in t]
    assert all(t["score"] == 0 for t in scored) and len(scored) == 6
    assert all("hidden case " not in t["output"] for t in r["tests"] if t["visibility"] == "visible")
    assert "hidden case" not in r["output"]


def test_broken_notebook_scores_0_and_says_why(image, tmp_path):
    r = _run(image, tmp_path, b'{"cells": [')
    assert r["score"] == 0 and r["extra_data"]["status"] == "malformed"
    assert "malformed" in r["output"]


def test_missing_notebook_scores_0_and_says_what_to_upload(image, tmp_path):
    r = _run(image, tmp_path, None)
    assert r["score"] == 0 and f"upload {EX}.ipynb" in r["output"]


@pytest.mark.parametrize("caps", CAPS, ids=["docker-caps", "namespaces"])
def test_hostile_notebook_gains_nothing(image, tmp_path, caps):
    nb = nbformat.read(ROOT / "exercises" / f"{EX}.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(HOSTILE_CELL))
    r = _run(image, tmp_path, nbformat.writes(nb).encode(), caps)
    # its forged results.json is replaced by the real one, written after its process is gone
    assert r["score"] == 0
    details = {t["name"]: t for t in r["tests"] if t["name"].endswith(": hidden cases")}
    assert details["q1 elementary_rotation: hidden cases"]["visibility"] == "after_due_date"
    assert "hidden case" in details["q1 elementary_rotation: hidden cases"]["output"]
    assert r["_source_config"]["exercise"] == EX  # /autograder is out of the student's user's reach
    assert "LEAKED" not in json.dumps(r)
    q1 = [t for t in r["tests"] if t["name"].startswith("q1 ")][0]
    assert q1["score"] == 0 and "FAILED" in q1["output"]


def test_setup_sh_installs_the_pinned_wheel_offline_and_makes_the_user(autograder_zip, tmp_path):
    if container.why_not():
        pytest.skip(f"no throwaway container here: {container.why_not()}")
    made = container.build_image(autograder_zip, tmp_path, system_site=False)
    assert made.setup.returncode == 0, made.setup.stdout[-2000:] + made.setup.stderr[-2000:]
    tree = made.tree
    py = "/autograder/puma-venv/bin/python"

    def inside(code: str) -> subprocess.CompletedProcess[str]:
        return container.container(tree, made.etc, [py, "-c", code])

    found = inside("import puma_course.grading.publish.gradescope")
    # the dependencies were not installed (offline, --no-deps): the import of numpy fails, the version is there
    meta = inside("import importlib.metadata as m; print(m.version('puma-course'))")
    assert meta.stdout.strip() == __version__, meta.stderr
    assert found.returncode != 0 and "numpy" in found.stderr
    installed = list((tree / "puma-venv").glob("lib/python*/site-packages/puma_course/grading/publish/gradescope.py"))
    assert installed, "the wheel did not install the package's files"
    # the user, unprivileged; the package, its record and the zip's folder root's alone
    user = [line.split(":") for line in (made.etc / "passwd").read_text().splitlines() if line.startswith("puma-")]
    assert [(u[0], int(u[2])) for u in user] == [("puma-student", made.uid)] and int(user[0][3]) != 0
    package = installed[0].parents[1]
    for folder in (package, *package.parent.glob("puma_course-*.dist-info"), tree / "source"):
        st = folder.stat()
        assert st.st_uid == 0 and st.st_mode & 0o077 == 0, (folder, oct(st.st_mode))


def test_hidden_case_details_are_held_back_until_the_due_date():
    ex = EXERCISES[EX]
    r = NotebookResult.blank("s", ex)
    r.scores["q1"] = 1.0
    r.question_notes["q1"] = ["5/9 cases pass", "hidden case 7: values differ for axis 'z', angle 2.5"]
    out = results_json(r, ex, ["status: ok"], "# Feedback", 1.2, {"seed": 1})
    jsonschema.validate(out, RESULTS_SCHEMA)
    visible = [t for t in out["tests"] if t["visibility"] == "visible"]
    assert all("angle 2.5" not in t["output"] for t in visible)
    assert "1 hidden-case failure(s)" in visible[0]["output"] and visible[0]["score"] == 1.0
    later = [t for t in out["tests"] if t["visibility"] == "after_due_date"]
    assert any("hidden case 7: values differ for axis 'z', angle 2.5" in t["output"] for t in later)
    assert out["score"] == 1.0 and sum(t.get("max_score", 0) for t in out["tests"]) == ex.max_score


def test_the_course_bank_folder_goes_into_the_zip(tmp_path):
    assert _bank_files(tmp_path) == {}  # a folder without a bank ships none
    shutil.copytree(ROOT / "bank", tmp_path / "bank", ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "bank" / "__pycache__").mkdir(parents=True)
    (tmp_path / "bank" / "__pycache__" / "x.pyc").write_bytes(b"0")
    files = _bank_files(tmp_path)
    mine = (tmp_path / "bank" / "ex01_rotations.py").read_bytes()
    assert files["bank/ex01_rotations.py"] == mine and not any("__pycache__" in n for n in files)
    (tmp_path / "solutions").mkdir()  # a course folder
    out = tmp_path / "a.zip"
    assert main(["gradescope", EX, "-o", str(out), "--course", str(tmp_path)]) == 0
    with zipfile.ZipFile(out) as zf:
        assert zf.read("bank/ex01_rotations.py") == mine
        assert not [n for n in zf.namelist() if n.startswith("bank/ex") and n != "bank/ex01_rotations.py"]
        assert b"register(_exercise.EXERCISE)" in zf.read("bank/__init__.py")


_SAME_PLANS = """
import json, sys
from pathlib import Path
import numpy as np
from puma_course.grading.bank_loader import EXERCISES, load_bank
from puma_course.grading.plan import make_plan

def norm(v):
    if isinstance(v, dict):
        return {k: norm(x) for k, x in sorted(v.items()) if not callable(x)}
    if isinstance(v, (list, tuple)):
        return [norm(x) for x in v]
    if isinstance(v, (np.ndarray, np.generic, float)):
        return np.asarray(v).tolist()
    return v if isinstance(v, (int, str, bool, type(None))) else repr(type(v))

def plan(name):
    return [[c.qid, c.case, c.function, c.args, norm(c.expected)] for c in make_plan(EXERCISES[name], 7, "student")]

full, sub = sys.argv[1], sys.argv[2]
for name in sys.argv[3:]:
    load_bank(full)
    want = plan(name)
    load_bank(Path(sub) / name)
    assert sorted(EXERCISES) == [name], (name, sorted(EXERCISES))
    assert plan(name) == want, name
print("same", len(sys.argv) - 3)
"""


def test_each_zip_carries_its_own_exercise_bank_alone_and_it_plans_as_the_whole_bank(tmp_path):
    """The zip's bank registers its exercise only, holds no other exercise's module but those it imports, and gives
    the same planned calls and expected values as the course's whole bank (every exercise, seed 7)."""
    for name in EXERCISES:
        files = _bank_files(ROOT, name)
        others = [f for f in files if f.startswith("bank/ex") and f != f"bank/{name}.py"]
        # ex06 and ex07 import ex05's public inputs; no other exercise module goes along
        assert others == (
            ["bank/ex05_porter_fk.py"] if name in ("ex06_porter_explicit", "ex07_porter_geometric") else []
        )
        assert (
            not any("written" in f for f in files)
            and files[f"bank/{name}.py"] == (ROOT / "bank" / f"{name}.py").read_bytes()
        )
        for rel, data in files.items():
            (tmp_path / name / rel).parent.mkdir(parents=True, exist_ok=True)
            (tmp_path / name / rel).write_bytes(data)
    done = subprocess.run(
        [sys.executable, "-c", _SAME_PLANS, str(ROOT), str(tmp_path), *EXERCISES],
        capture_output=True, text=True, timeout=600, cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0 and done.stdout.strip() == f"same {len(EXERCISES)}", done.stderr[-3000:]


@pytest.mark.parametrize("many", [False, True])
def test_a_submitted_file_name_cannot_forge_lines_of_the_visible_output(tmp_path, many):
    forged = (
        "x\u202e.ipynb as ex01_rotations.ipynb\nstatus: ok\nex01_rotations: 15 \u2215 15 points\n\u202e" + "y" * 150
    )
    (tmp_path / f"{forged}.ipynb").write_text("{}")
    if many:
        (tmp_path / "other.ipynb").write_text("{}")
    path, said = _find_notebook(tmp_path, "ex01_rotations")
    assert (path is None) == many
    assert "\n" not in said and "\u202e" not in said and len(said) < 300, said
    assert "\\x0astatus: ok\\x0a" in said and "\\u202e" in said  # shown escaped, inside a code span
    assert said.startswith("2 notebooks were submitted (`" if many else "graded `x\\u202e.ipynb as"), said
