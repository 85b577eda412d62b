"""puma_course.hub: the edition's repo2docker files and the links an instructor hands out (tests/hub runs them)."""

from __future__ import annotations

from pathlib import Path
from urllib.parse import parse_qs, urlsplit

import pytest

from puma_course.hub import GITIGNORE_LINES, binder_link, nbgitpuller_link, write_binder_files


def test_binder_files_install_the_package_and_nbgitpuller_only(tmp_path: Path) -> None:
    (tmp_path / "pyproject.toml").write_text("[project]\nname = 'x'\n")
    (tmp_path / ".gitignore").write_text("grades*.csv\n__pycache__/\n")
    written = write_binder_files(tmp_path)
    assert written == [tmp_path / "binder" / "requirements.txt", tmp_path / ".gitignore"]
    reqs = [
        line.strip()
        for line in (tmp_path / "binder" / "requirements.txt").read_text().splitlines()
        if line.strip() and not line.startswith("#")
    ]
    assert reqs == [".", "nbgitpuller"]  # no extra: no jupyterlab, grader, site or dev tools
    ignore = (tmp_path / ".gitignore").read_text().splitlines()
    assert ignore[:2] == ["grades*.csv", "__pycache__/"]  # the edition's own lines kept, first
    assert set(GITIGNORE_LINES) <= set(ignore) and ignore.count("__pycache__/") == 1
    write_binder_files(tmp_path)  # idempotent
    assert (tmp_path / ".gitignore").read_text().splitlines() == ignore


def test_binder_files_need_the_edition_folder(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="dest: expected the edition's folder"):
        write_binder_files(tmp_path)


def test_nbgitpuller_link_carries_its_parameters() -> None:
    link = nbgitpuller_link("https://hub.example.edu/", "https://git.example.edu/kin/puma-course.git/", branch="w5",
                            path="notebooks/03_x.ipynb", target="kin")  # fmt: skip
    parts = urlsplit(link)
    assert (parts.scheme, parts.netloc, parts.path) == ("https", "hub.example.edu", "/hub/user-redirect/git-pull")
    assert parse_qs(parts.query) == {
        "repo": ["https://git.example.edu/kin/puma-course.git/"],
        "branch": ["w5"],
        "urlpath": ["lab/tree/kin/notebooks/03_x.ipynb"],
    }
    default = parse_qs(urlsplit(nbgitpuller_link("http://h", "git://127.0.0.1:9003/puma-course")).query)
    assert default["urlpath"] == ["lab/tree/puma-course/START_HERE.ipynb"] and default["branch"] == ["main"]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [({"hub": ""}, "hub: expected"), ({"repo": " "}, "repo: expected"), ({"target": "a/b"}, "target: expected")],
)
def test_nbgitpuller_link_refuses_bad_input(kwargs: dict[str, str], match: str) -> None:
    args = {"hub": "https://h", "repo": "https://g/r"} | kwargs
    with pytest.raises(ValueError, match=match):
        nbgitpuller_link(**args)


def test_binder_link() -> None:
    assert binder_link("o/n", "v1", "notebooks/01 a.ipynb") == (
        "https://mybinder.org/v2/gh/o/n/v1?urlpath=lab/tree/notebooks/01%20a.ipynb"
    )
    with pytest.raises(ValueError, match="github_repo: expected 'owner/name'"):
        binder_link("o/n/x")
