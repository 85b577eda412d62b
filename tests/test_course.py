"""The course folder: found from where a command runs; its index and README link to files that exist."""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import unquote, urlparse

import nbformat
import pytest

from puma_course.course import INDEX, MARKERS, CourseNotFoundError, course_root, find_course, is_course
from tests.support import ROOT


def _course(folder: Path, marker: str = "solutions") -> Path:
    (folder / marker).mkdir(parents=True)
    return folder.resolve()


def _outside_any_course(tmp_path: Path) -> Path:
    """tmp_path itself, unless some folder above it happens to be a course (then the test cannot run here)."""
    here = tmp_path.resolve()
    if any(is_course(f) for f in (here, *here.parents)):
        pytest.skip(
            "not run: the test needs a folder outside any course, "
            f"and a folder above {here} holds {' or '.join(MARKERS)}"
        )
    return here


# --------------------------------------------------------------------------- finding the course
@pytest.mark.parametrize("marker", MARKERS)
def test_either_marker_folder_makes_a_course(tmp_path, marker):
    root = _course(tmp_path / "course", marker)
    assert is_course(root)
    assert find_course(root) == root


def test_found_from_any_folder_below_the_root(tmp_path):
    root = _course(tmp_path / "course")
    deep = root / "notebooks" / "figures" / "old"
    deep.mkdir(parents=True)
    assert find_course(deep) == root
    assert find_course(root / "solutions") == root


def test_the_current_directory_is_the_default_start(tmp_path, monkeypatch):
    root = _course(tmp_path / "course", "notebooks")
    (root / "exercises").mkdir()
    monkeypatch.chdir(root / "exercises")
    assert find_course() == root
    assert course_root() == root


def test_a_relative_start_is_taken_from_the_current_directory(tmp_path, monkeypatch):
    root = _course(tmp_path / "course")
    (root / "a" / "b").mkdir(parents=True)
    monkeypatch.chdir(root / "a")
    assert find_course("b") == root
    assert find_course(Path("b") / "..") == root


def test_the_nearest_course_wins(tmp_path):
    outer = _course(tmp_path / "outer", "notebooks")
    inner = _course(outer / "notebooks" / "inner", "solutions")
    (inner / "work").mkdir()
    assert find_course(inner / "work") == inner
    assert find_course(outer / "notebooks") == outer


def test_a_file_named_like_a_marker_does_not_make_a_course(tmp_path):
    here = _outside_any_course(tmp_path)
    for marker in MARKERS:
        (here / marker).write_text("not a folder", encoding="utf-8")
    assert not is_course(here)
    with pytest.raises(CourseNotFoundError):
        find_course(here)


def test_outside_a_course_the_error_names_what_and_where_it_searched(tmp_path):
    here = _outside_any_course(tmp_path)
    start = here / "a" / "b"
    start.mkdir(parents=True)
    with pytest.raises(CourseNotFoundError) as info:
        find_course(start)
    err = info.value
    assert isinstance(err, ValueError)
    assert err.searched == (start, start.parent, here, *here.parents)
    message = str(err)
    assert message.startswith("start: expected")
    assert "solutions/" in message and "notebooks/" in message
    for folder in err.searched:
        assert repr(str(folder)) in message


@pytest.mark.parametrize("kind", ["missing", "file"])
def test_a_start_that_is_not_a_folder_is_refused(tmp_path, kind):
    start = tmp_path / "x"
    if kind == "file":
        start.write_text("", encoding="utf-8")
    with pytest.raises(CourseNotFoundError, match="start: expected .*'" + re.escape(str(start)) + "'"):
        find_course(start)


def test_a_named_course_is_used_as_it_is(tmp_path, monkeypatch):
    root = _course(tmp_path / "course")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    assert course_root(root) == root
    assert course_root(str(root)) == root


@pytest.mark.parametrize(
    ("make", "why"),
    [
        (lambda p: None, "does not exist"),
        (lambda p: p.write_text("", encoding="utf-8"), "is not a folder"),
        (lambda p: p.mkdir(), "holds neither solutions/ nor notebooks/"),
    ],
)
def test_a_named_folder_that_is_not_a_course_is_refused(tmp_path, make, why):
    named = tmp_path / "named"
    make(named)
    with pytest.raises(CourseNotFoundError, match="course: expected a course folder") as info:
        course_root(named)
    assert repr(str(named)) in str(info.value) and why in str(info.value)


def test_a_named_folder_inside_a_course_is_not_walked_up_from(tmp_path):
    root = _course(tmp_path / "course", "notebooks")
    with pytest.raises(CourseNotFoundError, match="holds neither"):
        course_root(root / "notebooks")


def test_this_repository_is_a_course():
    assert find_course(ROOT / "puma_course") == ROOT.resolve()


# --------------------------------------------------------------------------- the index and the README
_LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def _links(markdown: str) -> list[str]:
    """The targets of Markdown links, outside fenced and inline code."""
    text = re.sub(r"```.*?```", "", markdown, flags=re.DOTALL)
    text = re.sub(r"`[^`\n]*`", "", text)
    return _LINK.findall(text)


def _local_files(targets: list[str], base: Path) -> list[Path]:
    """The local files the link targets name (web links and in-page anchors left out)."""
    files = []
    for target in targets:
        url = urlparse(target)
        if url.scheme or url.netloc or not url.path:
            continue
        files.append(base / unquote(url.path))
    return files


def _index_text() -> str:
    nb = nbformat.read(ROOT / INDEX, as_version=4)
    return "\n\n".join(cell.source for cell in nb.cells)


def test_the_index_is_a_markdown_only_notebook_that_opens_without_asking_for_a_kernel():
    nb = nbformat.read(ROOT / INDEX, as_version=4)
    nbformat.validate(nb)
    assert nb.cells and {cell.cell_type for cell in nb.cells} == {"markdown"}
    assert nb.metadata["kernelspec"]["name"] == "python3"


def test_every_link_of_the_index_opens_an_existing_file():
    targets = _links(_index_text())
    files = _local_files(targets, ROOT)
    assert len(files) == len(targets), "the index should link only to course files"
    missing = [str(f.relative_to(ROOT)) for f in files if not f.is_file()]
    assert not missing, f"{INDEX} links to missing files: {missing}"


def test_the_index_links_every_lecture_and_every_exercise():
    linked = {f.resolve() for f in _local_files(_links(_index_text()), ROOT)}
    course = sorted((ROOT / "notebooks").glob("*.ipynb")) + sorted((ROOT / "exercises").glob("*.ipynb"))
    assert len(course) >= 10
    unlinked = [str(p.relative_to(ROOT)) for p in course if p.resolve() not in linked]
    assert not unlinked, f"{INDEX} does not link: {unlinked}"


def test_the_index_says_how_to_work():
    text = _index_text()
    assert "Run All Cells" in text and "self-check" in text and 'check("q1"' in text


def test_every_local_link_of_the_readme_opens_an_existing_file():
    targets = _links((ROOT / "README.md").read_text(encoding="utf-8"))
    files = _local_files(targets, ROOT)
    assert files, "the README's contents table should link the course's notebooks"
    missing = [str(f.relative_to(ROOT)) for f in files if not f.exists()]
    assert not missing, f"README.md links to missing files: {missing}"


def test_the_readme_contents_link_the_index_every_lecture_and_every_exercise():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    contents = readme.split("## Contents", 1)[1].split("\n## ", 1)[0]
    linked = {f.resolve() for f in _local_files(_links(contents), ROOT)}
    wanted = [
        ROOT / INDEX,
        *sorted((ROOT / "notebooks").glob("*.ipynb")),
        *sorted((ROOT / "exercises").glob("*.ipynb")),
    ]
    unlinked = [str(p.relative_to(ROOT)) for p in wanted if p.resolve() not in linked]
    assert not unlinked, f"README's contents do not link: {unlinked}"
