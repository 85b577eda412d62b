"""The delegated control-group subtree (issue 21), on a fake hierarchy: what ``puma-course limits delegate`` makes
and gives away, how the grader finds it, and what ``--undo`` removes. The real kernel's side (an unprivileged
grader's notebooks limited in it) is tested in test_hostile_unprivileged.py (``-k delegated``)."""

from __future__ import annotations

import os
import pwd
import shutil
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading.run.delegation import delegate, find_delegated, parent_name, undelegate
from puma_course.grading.run.limits import describe

# CI's second pass (another OpenBLAS kernel) leaves this out: a control-group subtree on a fake hierarchy: files and
# names, no numerics.
pytestmark = pytest.mark.no_numerics

CONTROLLERS = ("memory", "pids", "cpu", "cpuacct")


def _fake_v1(root: Path) -> Path:
    for c in CONTROLLERS:
        (root / c).mkdir(parents=True)
        (root / c / "cgroup.procs").write_text("")
    return root


def _nobody() -> pwd.struct_passwd:
    try:
        entry = pwd.getpwnam("nobody")
    except KeyError:
        pytest.skip("no user 'nobody' here")
    if os.geteuid() != 0:
        pytest.skip("giving a folder to another user needs root")
    return entry


def test_parent_name_refuses_what_is_no_user_name():
    assert parent_name("grader_1") == "puma-grading-grader_1"
    for bad in ("../etc", "a/b", "", "x" * 40, None):
        with pytest.raises(ValueError, match="user: expected a user name"):
            parent_name(bad)  # type: ignore[arg-type]


def test_delegate_refuses_root_and_unknown_users(tmp_path):
    root = _fake_v1(tmp_path)
    with pytest.raises(ValueError, match="user: expected an existing user name, got 'nosuchuser9z'"):
        delegate("nosuchuser9z", root=root)
    with pytest.raises(ValueError, match="other than root"):
        delegate("root", root=root)
    assert sorted(p.name for p in (root / "memory").iterdir()) == ["cgroup.procs"]  # nothing made


def test_delegate_gives_the_folder_only_and_the_grader_finds_it(tmp_path):
    nobody = _nobody()
    root = _fake_v1(tmp_path)
    lines = delegate("nobody", root=root)
    parents = [root / c / "puma-grading-nobody" for c in CONTROLLERS]
    assert all(p.is_dir() and p.stat().st_uid == nobody.pw_uid for p in parents), lines
    assert (root / "memory" / "cgroup.procs").stat().st_uid == 0  # the hierarchy's own files stay root's
    assert any("memory" in line and "the folder only" in line for line in lines), lines
    # the grader (its own groups somewhere below the top) finds it at the top, above its own group
    own = {c: "/some/session" for c in CONTROLLERS}
    run = find_delegated(root, own, "puma-grading-1-ab", user="nobody")
    assert not isinstance(run, str) and run is not None, run
    assert run.version == 1 and run.delegated
    assert run.folders == {c: root / c / "puma-grading-nobody" / "puma-grading-1-ab" for c in CONTROLLERS}
    assert describe(run).startswith("per notebook (cgroup v1, delegated): ")
    # a subtree below the grader's own group is found there first
    (root / "memory" / "some" / "puma-grading-nobody").mkdir(parents=True)
    deeper = find_delegated(root, {c: "/some" for c in CONTROLLERS}, "puma-grading-2-cd", user="nobody")
    assert not isinstance(deeper, str) and deeper is not None
    assert deeper.folders["memory"] == root / "memory" / "some" / "puma-grading-nobody" / "puma-grading-2-cd"
    # no subtree for another user; a subtree missing a controller is said
    assert find_delegated(root, own, "x", user="somebodyelse") is None
    shutil.rmtree(root / "pids" / "puma-grading-nobody")
    got = find_delegated(root, {c: "/" for c in CONTROLLERS}, "puma-grading-3-ef", user="nobody")
    assert isinstance(got, str) and "has no pids folder" in got, got


def test_undo_removes_the_subtree_and_every_group_under_it(tmp_path):
    _nobody()
    root = _fake_v1(tmp_path)
    delegate("nobody", root=root)
    find_delegated(root, {}, "puma-grading-1-ab", user="nobody")
    (root / "memory" / "puma-grading-nobody" / "puma-grading-1-ab" / "nb-1").mkdir()
    lines = undelegate("nobody", root=root)
    assert sorted(lines) == sorted(f"removed {root / c / 'puma-grading-nobody'}" for c in CONTROLLERS)
    assert not any((root / c / "puma-grading-nobody").exists() for c in CONTROLLERS)
    assert undelegate("nobody", root=root) == [f"nothing to undo: no puma-grading-nobody under {root}"]


def test_the_command_says_what_is_wrong(capsys):
    assert main(["limits", "delegate", "--user", "nosuchuser9z"]) == 2
    err = capsys.readouterr().err
    assert "nosuchuser9z" in err and ("existing user name" in err or "root" in err), err
