"""The website's build, without a browser: ``puma-course site`` from the committed notebooks.

What a reader needs is on it (every lecture and exercise, the notation page, the downloads), and what
would break "no network" or "no solutions" is not (a remote script, a solution notebook). The
browser-level checks (math rendered, animations playing, search) are in tests/browser/test_site.py.
"""

from __future__ import annotations

import html
import re
import sys
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.course import CourseNotFoundError
from tests.support import ROOT, course_site

pytest.importorskip("myst_nb", reason="website build not tested: MyST-NB is missing (pip install -e '.[site]')")


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    """``puma-course site --course ROOT -o DIR``, built once per test run for every test that reads the site."""
    return course_site(tmp_path_factory)


def test_the_command_reports_pages_time_and_size(built):
    out, printed = built
    m = re.search(r"built (\d+) pages in ([\d.]+) s, ([\d.]+) MB", printed)
    assert m, printed
    assert int(m.group(1)) == len([p for p in out.rglob("*.html") if "_static" not in p.parts])
    assert float(m.group(3)) > 1.0


def test_every_lecture_and_exercise_has_a_page_and_no_solution_does(built):
    out, _ = built
    for nb in (ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"):
        assert (out / "notebooks" / f"{nb.stem}.html").is_file(), nb.name
    for nb in (ROOT / "exercises").glob("ex*.ipynb"):
        assert (out / "exercises" / f"{nb.stem}.html").is_file(), nb.name
    assert (out / "conventions.html").is_file() and (out / "search.html").is_file()
    assert not list(out.rglob("*solution*")), "a solutions file reached the site"


def test_each_lecture_page_offers_its_notebook_for_download(built):
    out, _ = built
    for page in (out / "notebooks").glob("*.html"):
        href = f"../_sources/notebooks/{page.stem}.ipynb"
        assert href in page.read_text(encoding="utf-8"), f"{page.name}: no download link to its notebook"
        assert (out / "_sources" / "notebooks" / f"{page.stem}.ipynb").is_file()


def test_the_landing_page_says_what_the_course_is_and_how_to_install_it(built):
    out, _ = built
    text = html.unescape(re.sub(r"<[^>]+>", "", (out / "index.html").read_text(encoding="utf-8")))
    assert "kinematics" in text.lower()
    assert "pip install" in text and "puma-course lab" in text
    for nb in (ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"):
        assert f"notebooks/{nb.stem}.html" in (out / "index.html").read_text(encoding="utf-8")


def test_no_page_loads_anything_from_another_host(built):
    """Scripts, styles, fonts and images come from the site; links to other sites may stay links."""
    out, _ = built
    remote = re.compile(
        r"""<(?:script|img|iframe|source)[^>]+src=["']?(?:https?:)?//|<link[^>]+href=["']?(?:https?:)?//"""
    )
    offenders = [str(p.relative_to(out)) for p in out.rglob("*.html") if remote.search(p.read_text(encoding="utf-8"))]
    assert not offenders, offenders
    assert (out / "_static" / "mathjax" / "tex-svg-full.js").stat().st_size > 1_000_000
    assert "Apache License" in (out / "_static" / "mathjax" / "LICENSE").read_text(encoding="utf-8")


def test_the_site_of_a_folder_that_is_not_a_course_is_refused(tmp_path):
    from puma_course.site import build_site

    with pytest.raises(CourseNotFoundError):
        build_site(tmp_path, tmp_path / "out")


def test_a_tagged_display_with_a_matrix_is_not_wrapped_in_split(built):
    """MathJax refuses \\tag inside split; lecture 08's eq. (1) has a bmatrix (line breaks) and a \\tag."""
    out, _ = built
    page = html.unescape((out / "notebooks" / "08_three_step_wrist_frame.html").read_text(encoding="utf-8"))
    blocks = re.findall(r'<div class="math notranslate nohighlight">(.*?)</div>', page, re.S)
    tagged = [b for b in blocks if "\\tag{" in b and "\\\\" in b]
    assert tagged, "lecture 08 lost its tagged matrix display"
    assert not [b for b in tagged if "\\begin{split}" in b]


def _anchors(page: str) -> list[dict[str, str | None]]:
    from html.parser import HTMLParser

    found: list[dict[str, str | None]] = []

    class Anchors(HTMLParser):
        def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
            if tag == "a":
                found.append(dict(attrs))

    Anchors().feed(page)
    return found


def test_the_landing_page_links_the_student_edition_and_it_holds_no_solutions(built):
    import zipfile

    from puma_course.site.build import ARCHIVE

    out, _ = built
    hrefs = [a.get("href") for a in _anchors((out / "index.html").read_text(encoding="utf-8"))]
    assert ARCHIVE in hrefs, "the landing page does not link the course's archive"
    with zipfile.ZipFile(out / ARCHIVE) as z:
        names = z.namelist()
    tops = {n.split("/")[1] for n in names if n.count("/") >= 2 or not n.endswith("/")}
    assert {"START_HERE.ipynb", "notebooks", "exercises", "puma_course", "pyproject.toml", "README.md"} <= tops
    assert all(n.startswith("puma-course/") for n in names)
    assert not [n for n in names if "/solutions/" in n or n.rstrip("/").endswith("/solutions")], "solutions/ shipped"
    bank = [n for n in names if "/grading/bank/" in n or n.startswith("puma-course/bank/")]
    assert not bank, "the question bank shipped"
    for nb in (ROOT / "exercises").glob("ex*.ipynb"):
        assert f"puma-course/exercises/{nb.name}" in names


def test_the_repository_link_is_the_one_given_else_the_pyproject_one_else_none(tmp_path, built):
    from puma_course.site.build import _get_the_course, repository_url

    out, _ = built
    # this course's pyproject names no repository: the landing page offers the archive alone
    assert repository_url(ROOT) is None
    assert not [
        a for a in _anchors((out / "index.html").read_text(encoding="utf-8")) if a.get("class") == "puma-repository"
    ]
    url = "https://git.example.org/robotics/puma-course"
    page = "\n".join(_get_the_course(url))
    assert [a.get("href") for a in _anchors(page) if a.get("class") == "puma-repository"] == [url]
    if sys.version_info < (3, 11):
        pytest.skip("reading the repository from pyproject.toml not checked: Python 3.10 has no tomllib")
    (tmp_path / "pyproject.toml").write_text(f'[tool.puma-course]\nrepository = "{url}"\n', encoding="utf-8")
    assert repository_url(tmp_path) == url
    (tmp_path / "pyproject.toml").write_text(f'[project]\nname = "x"\n[project.urls]\nRepository = "{url}/2"\n')
    assert repository_url(tmp_path) == url + "/2"


def test_the_site_command_takes_a_repository_link(tmp_path, monkeypatch):
    from puma_course import site

    seen = {}

    def fake(course, out, repo_url=None, edition=None):
        seen["repo_url"] = repo_url
        raise ValueError("stop here")

    monkeypatch.setattr(site, "build_site", fake)
    assert main(["site", "--course", str(ROOT), "-o", str(tmp_path / "s"), "--repo-url", "https://x.example/c"]) == 2
    assert seen == {"repo_url": "https://x.example/c"}


def test_a_repository_link_that_is_not_a_web_address_is_refused(tmp_path, capsys):
    for bad in ("javascript:alert(1)", "git@example.org:c.git", 'https://x.example/"><script>'):
        assert main(["site", "--course", str(ROOT), "-o", str(tmp_path / "s"), "--repo-url", bad]) == 2
        assert "repo_url: expected an http:// or https:// address" in capsys.readouterr().err
    assert not (tmp_path / "s").exists()


@pytest.mark.slow
def test_building_the_site_in_a_clean_clone_leaves_git_status_clean(tmp_path):
    """`puma-course site` with its defaults (output _site/ in the course) changes nothing git tracks or sees."""
    import subprocess

    clone = tmp_path / "course"
    subprocess.run(["git", "clone", "-q", "--no-hardlinks", str(ROOT), str(clone)], check=True, timeout=120)
    proc = subprocess.run(
        [sys.executable, "-m", "puma_course.cli", "site"], cwd=clone, capture_output=True, text=True, timeout=600
    )
    assert proc.returncode == 0, proc.stderr
    assert (clone / "_site" / "index.html").is_file()
    status = subprocess.run(["git", "status", "--porcelain", "--ignored=no"], cwd=clone, capture_output=True, text=True)
    assert status.stdout == "", f"the build left files git sees:\n{status.stdout}"
    assert not (clone / "jupyter_execute").exists()


def test_every_image_of_every_lecture_page_has_its_text_alternative(built):
    """The lectures' figures carry ``mystnb.image.alt``; MyST-NB renders it as the ``<img>``'s ``alt`` (issue 25)."""
    out, _ = built
    for page in sorted((out / "notebooks").glob("*.html")):
        imgs = re.findall(r"<img\b[^>]*>", page.read_text(encoding="utf-8"))
        assert imgs, f"{page.name}: no figure"
        for img in imgs:
            alt = re.search(r"""\balt=(["'])(.*?)\1""", img)
            assert alt and len(html.unescape(alt.group(2)).strip()) > 20, f"{page.name}: {img[:160]}"


def test_no_file_of_the_site_names_a_cdn_host(built):
    """MathJax's speech-rule-engine maps are bundled and its fall-back addresses rewritten (issue 25)."""
    from puma_course.instructor import CDN_HOSTS

    out, _ = built
    named = []
    for path in out.rglob("*"):
        if path.is_file() and path.suffix in (".html", ".js", ".css", ".json", ".txt", ".svg", ".map"):
            text = path.read_text(encoding="utf-8", errors="replace")
            named += [f"{path.relative_to(out)}: {host}" for host in CDN_HOSTS if host in text]
    assert not named, named
    assert (out / "_static" / "mathjax" / "sre" / "mathmaps" / "en.json").is_file()
    assert (out / "_static" / "mathjax" / "a11y" / "explorer.js").is_file()


# ---------------------------------------------------------------- the guides (docs/*.md) as pages (issue 32)
def _internal_links_broken(out: Path, rel: str) -> list[str]:
    """The links of page ``rel`` that open no file of the site, or no element with the #anchor they name."""
    from urllib.parse import unquote, urldefrag, urljoin, urlparse

    broken = []
    for href in re.findall(r'href="([^"]+)"', (out / rel).read_text(encoding="utf-8")):
        href = html.unescape(href)
        if href.startswith(("http:", "https:", "mailto:", "#", "javascript:", "data:")):
            continue
        target, fragment = urldefrag(urljoin(rel, href))
        path = out / unquote(urlparse(target).path)
        if not path.exists():
            broken.append(f"{rel} -> {href}")
        elif fragment and path.suffix == ".html" and f'id="{fragment}"' not in path.read_text(encoding="utf-8"):
            broken.append(f"{rel} -> {href} (no anchor {fragment!r})")
    return broken


def _text(page: Path) -> str:
    return html.unescape(re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8")))


def test_the_readers_guides_are_pages_in_the_sites_navigation_and_the_instructors_are_not(built):
    from puma_course.site.guides import OTHER_GUIDES, READER_GUIDES

    out, _ = built
    landing = (out / "index.html").read_text(encoding="utf-8")
    for name in READER_GUIDES:
        rel = "conventions.html" if name == "conventions" else f"guides/{name}.html"
        page = out / rel
        assert page.is_file(), rel
        title = (ROOT / "docs" / f"{name}.md").read_text(encoding="utf-8").splitlines()[0].removeprefix("# ")
        assert title in _text(page), (rel, title)
        assert 'class="bd-sidebar-primary' in page.read_text(encoding="utf-8"), f"{rel}: no navigation"
        assert f'href="{rel}"' in landing, f"the landing page does not link {rel}"
        assert not _internal_links_broken(out, rel), _internal_links_broken(out, rel)
    # what the notation page says comes from docs/conventions.md now (README holds no copy)
    assert "Three readings of one transform" in _text(out / "conventions.html")
    for name in OTHER_GUIDES:
        assert not (out / "guides" / f"{name}.html").exists(), f"an instructor's guide is on the site: {name}"
    # a guide's link to a lecture opens the lecture's page; one to a guide left out keeps its text only
    students = (out / "guides" / "students.html").read_text(encoding="utf-8")
    assert 'href="../notebooks/01_rotations_and_transforms.html"' in students
    assert 'href="../exercises/ex10_trajectories.html"' in students


def test_a_guides_links_are_rewritten_for_the_site(tmp_path):
    from puma_course.site.guides import guides_of, site_markdown

    docs = tmp_path / "docs"
    docs.mkdir()
    (docs / "conventions.md").write_text("# Notation\n\n[home](students.md#how-to-work)\n", encoding="utf-8")
    (docs / "grading.md").write_text("# Grading\n", encoding="utf-8")
    (docs / "students.md").write_text(
        "# For students\n\n[lecture](../notebooks/01_a.ipynb) [ex](../exercises/ex01_a.ipynb#q1) "
        "[notation](conventions.md#units) [grading](grading.md) [test](../tests/test_x.py) [web](https://x.org) "
        "[here](#for-students) ![figure](../figures/f.png)\n\n```text\n[kept](grading.md)\n```\n",
        encoding="utf-8",
    )
    chosen = guides_of(tmp_path)
    assert [(g.page, g.title) for g in chosen] == [("guides/students", "For students"), ("conventions", "Notation")]
    text = site_markdown(chosen[0], chosen, {"01_a.ipynb"}, {"ex01_a.ipynb"})
    assert "[lecture](../notebooks/01_a.ipynb) [ex](../exercises/ex01_a.ipynb#q1)" in text
    assert "[notation](../conventions.md#units) grading test [web](https://x.org) [here](#for-students)" in text
    assert "![figure](../figures/f.png)" in text and "[kept](grading.md)" in text  # an image and code untouched
    assert "[home](guides/students.md#how-to-work)" in site_markdown(chosen[1], chosen, set(), set())
    assert [g.page for g in guides_of(tmp_path, "all")] == ["guides/students", "conventions", "guides/grading"]
    with pytest.raises(ValueError, match=r"guides: expected one of 'readers', 'all', got 'some'"):
        guides_of(tmp_path, "some")


@pytest.mark.slow
def test_every_guide_is_a_page_of_the_instructors_site_and_its_links_resolve(tmp_path):
    """``build_site(guides="all")``: every docs/*.md but the index is a page, every internal link opens."""
    from puma_course.site import build_site

    report = build_site(ROOT, tmp_path / "site", guides="all")
    out = report.out
    names = sorted(p.stem for p in (ROOT / "docs").glob("*.md") if p.stem != "index")
    assert len(names) >= 15
    rels = ["conventions.html" if n == "conventions" else f"guides/{n}.html" for n in names]
    missing = [r for r in rels if not (out / r).is_file()]
    assert not missing, missing
    broken = [b for r in rels for b in _internal_links_broken(out, r)]
    assert not broken, "\n".join(broken[:20])
    # Sphinx's own notes on a second build in one process (nodes registered again) are not the guides'
    about = [w for w in report.warnings if "guides/" in w or "conventions" in w]
    assert not about, about
