"""``puma-course release``: exercises/ written from solutions/, or checked against them."""

from __future__ import annotations

import shutil

from puma_course.cli import main
from tests.support import ROOT


def test_release_in_a_course_without_solutions_exits_2(tmp_path, capsys, monkeypatch):
    (tmp_path / "lectures-only" / "notebooks").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "lectures-only")
    assert main(["release", "--check"]) == 2
    err = capsys.readouterr().err
    assert "solutions: expected a folder" in err and "does not exist" in err


def test_release_check_passes_on_the_committed_exercises(capsys, monkeypatch):
    monkeypatch.chdir(ROOT)
    assert main(["release", "--check"]) == 0
    assert "up to date" in capsys.readouterr().out


def test_release_writes_and_check_detects_a_stale_exercise(tmp_path, capsys):
    sol, ex = tmp_path / "solutions", tmp_path / "exercises"
    sol.mkdir()
    shutil.copy(ROOT / "solutions" / "ex01_rotations.ipynb", sol)
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex)]) == 0
    assert (ex / "ex01_rotations.ipynb").read_bytes() == (ROOT / "exercises" / "ex01_rotations.ipynb").read_bytes()
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    with open(ex / "ex01_rotations.ipynb", "a", encoding="utf-8") as fh:
        fh.write(" ")
    # the file's layout is not what the check compares (JupyterLab rewrites it on every save) ...
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 0
    # ... a cell's source is
    path = ex / "ex01_rotations.ipynb"
    path.write_text(path.read_text(encoding="utf-8").replace("(axis, angle):", "(axis, angle=0):", 1), encoding="utf-8")
    assert main(["release", "--solutions", str(sol), "--exercises", str(ex), "--check"]) == 1
    assert "ex01_rotations" in capsys.readouterr().err
