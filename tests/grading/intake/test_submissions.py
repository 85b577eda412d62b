"""grading.intake.submissions: students and notebooks read without following links, whatever the folder holds."""

from __future__ import annotations

import errno
import os

import pytest

from puma_course.grading.intake import submissions as subs_mod
from puma_course.grading.intake.submissions import MAX_NOTEBOOK_BYTES, read_path, read_student, scan
from tests.support import ROOT

# CI's second pass (another OpenBLAS kernel) leaves this out: reading students' folders and files: no numerics.
pytestmark = pytest.mark.no_numerics

EX = "ex01_rotations"


def test_scan_lists_folders_and_links_and_makes_names_printable_and_unique(tmp_path):
    for name in ("ann", ".hidden", "b\nx", "caf\udce9", "-rf"):
        (tmp_path / name).mkdir()
    (tmp_path / "file.ipynb").write_text("{}", encoding="utf-8")
    (tmp_path / "link").symlink_to(tmp_path / "ann")
    (tmp_path / "b\\x0ax").mkdir()  # shows like "b\nx" does
    found = {s.name: s for s in scan(tmp_path)}
    assert set(found) == {"ann", "b\\x0ax", "b\\x0ax~2", "caf\\xe9", "-rf", "link"}
    assert found["link"].refused is not None and "symbolic link" in found["link"].refused
    assert all(s.refused is None for n, s in found.items() if n != "link")


def test_read_student_refuses_what_is_not_a_regular_file(tmp_path):
    home = tmp_path / "s"
    home.mkdir()
    (home / "a.ipynb").symlink_to(ROOT / "solutions" / f"{EX}.ipynb")
    os.mkfifo(home / "b.ipynb")
    (home / "c.ipynb").mkdir()
    (home / "d.ipynb").write_bytes(b"x" * (MAX_NOTEBOOK_BYTES + 1))
    (home / "e.ipynb").write_text("{}", encoding="utf-8")
    (home / "other.ipynb").write_text("{}", encoding="utf-8")
    student = scan(tmp_path)[0]
    got = read_student(tmp_path, student, ["a", "b", "c", "d", "e", "f"])
    states = {k: nb.state for k, nb in got.notebooks.items()}
    assert states == {"a": "refused", "b": "refused", "c": "refused", "d": "malformed", "e": "read", "f": "missing"}
    assert "symbolic link" in got.notebooks["a"].note and got.notebooks["a"].data is None
    assert "pipe" in got.notebooks["b"].note and "folder" in got.notebooks["c"].note
    assert got.notebooks["e"].data == b"{}" and got.others == ["`other.ipynb`"]


def test_an_unreadable_folder_or_file_is_reported_not_raised(tmp_path, monkeypatch):
    (tmp_path / "s").mkdir()
    (tmp_path / "s" / f"{EX}.ipynb").write_text("{}", encoding="utf-8")
    student = scan(tmp_path)[0]
    real_open = os.open

    def deny(path, flags, *args, **kwargs):
        if str(path).endswith(("s", ".ipynb")):
            raise PermissionError(errno.EACCES, "Permission denied")
        return real_open(path, flags, *args, **kwargs)

    monkeypatch.setattr(subs_mod.os, "open", deny)
    got = read_student(tmp_path, student, [EX])
    assert got.notebooks[EX].state == "unreadable" and "Permission denied" in got.notebooks[EX].note


@pytest.mark.skipif(
    os.geteuid() == 0,
    reason="not run as root: the unreadable-folder case needs a user who cannot read a folder of mode 000",
)
def test_a_folder_of_mode_000_is_unreadable(tmp_path):
    (tmp_path / "s").mkdir()
    os.chmod(tmp_path / "s", 0)
    try:
        got = read_student(tmp_path, scan(tmp_path)[0], [EX])
    finally:
        os.chmod(tmp_path / "s", 0o755)
    assert got.notebooks[EX].state == "unreadable"


def test_read_path_follows_no_link_in_the_last_part(tmp_path):
    (tmp_path / "nb.ipynb").symlink_to("/etc/passwd")
    got = read_path(tmp_path / "nb.ipynb")
    assert got.state == "refused" and got.data is None
    assert read_path(tmp_path / "none.ipynb").state == "missing"
