"""Build the course's static website (see the package docstring for what it holds and why)."""

from __future__ import annotations

import html
import io
import re
import shutil
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ..course import find_course
from .guides import Guide, guides_of, site_markdown

__all__ = ["SiteReport", "build_site", "repository_url", "MATHJAX_FILE", "MATHJAX_VERSION", "ARCHIVE"]

#: the student edition's archive, at the site's root and linked from the landing page
ARCHIVE = "puma-course-student.zip"

#: MathJax 3.2.2's single-file component: TeX input with every extension, SVG output. It draws glyphs
#: as SVG paths, so the page fetches no font and nothing else at view time (2.2 MB, served locally).
MATHJAX_FILE = "tex-svg-full.js"
MATHJAX_VERSION = "3.2.2"


@dataclass(frozen=True)
class SiteReport:
    """What a build produced: the output folder, its pages, the time it took, its size, Sphinx's warnings."""

    out: Path
    pages: tuple[str, ...]
    seconds: float
    size_bytes: int
    warnings: tuple[str, ...] = field(default_factory=tuple)


def _readme_sections(readme: str) -> dict[str, str]:
    """The README's level-2 sections by their heading text (up to the first parenthesis)."""
    parts = re.split(r"^## ", readme, flags=re.M)
    out = {"_intro": parts[0]}
    for part in parts[1:]:
        title, _, body = part.partition("\n")
        out[title.split("(")[0].strip()] = body
    return out


def first_commands(readme: str, key: str) -> str | None:
    """The fenced block that follows ``<!-- first-commands: KEY -->`` in ``readme`` (README's Start), or None."""
    m = re.search(rf"<!-- first-commands: {re.escape(key)} -->\s*```[\w-]*\n(.*?)```", readme, re.S)
    return m.group(1).strip() if m else None


def _title(nb_path: Path) -> str:
    import nbformat

    nb = nbformat.read(nb_path, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return nb_path.stem.replace("_", " ")


def repository_url(root: Path) -> str | None:
    """The course's repository address from ``pyproject.toml``: ``[tool.puma-course] repository``, else
    ``[project.urls]`` ``Repository`` (or ``Source``, ``Homepage``); None when there is none."""
    import importlib

    try:  # the standard library's since Python 3.11 (3.10: no repository from pyproject.toml)
        tomllib = importlib.import_module("tomllib")
    except ModuleNotFoundError:  # pragma: no cover
        return None
    try:
        data = tomllib.loads((root / "pyproject.toml").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    url = data.get("tool", {}).get("puma-course", {}).get("repository")
    urls = data.get("project", {}).get("urls", {})
    for key in ("Repository", "Source", "Homepage"):
        url = url or urls.get(key)
    return str(url) if url else None


#: writes the student edition of a course into a new folder (``puma-course edition``'s writer, handed in by the
#: command: the site layer reads the course's files and imports nothing above the base layer)
EditionWriter = Callable[[Path, Path], object]


def _edition_archive(course: Path, dest_dir: Path, edition: EditionWriter) -> Path:
    """The student edition as ``dest_dir/ARCHIVE``, one top folder ``puma-course/`` inside."""
    with tempfile.TemporaryDirectory(prefix="puma-edition-") as tmp:
        tree = Path(tmp) / "puma-course"
        edition(tree, course)  # exactly what `puma-course edition DIR` hands a student
        dest_dir.mkdir(parents=True, exist_ok=True)
        made = shutil.make_archive(str(dest_dir / ARCHIVE.removesuffix(".zip")), "zip", tmp, "puma-course")
    return Path(made)


def _get_the_course(repo_url: str | None, archive: bool = True) -> list[str]:
    """The landing page's "Get the course" section: the archive (when built), and the repository when known."""
    if not archive and not repo_url:
        return []
    lines = ["## Get the course", ""]
    lines += [] if not archive else [
             f'<a class="puma-archive" href="{ARCHIVE}" download>Download the course ({ARCHIVE})</a>: '
             "the lectures, the exercises, the index START_HERE.ipynb and the `puma_course` package the "
             "notebooks run on, in one folder (no solutions). Unpack it and follow *Read, then run* below "
             "from the folder it makes.", ""]  # fmt: skip
    if repo_url:
        shown = html.escape(repo_url, quote=True)
        lines += [f'Or take it from its repository: <a class="puma-repository" href="{shown}">{html.escape(repo_url)}'
                  "</a>.", ""]  # fmt: skip
    return lines


def _landing_page(
    root: Path,
    lectures: list[Path],
    exercises: list[Path],
    repo_url: str | None = None,
    archive: bool = True,
    guides: list[Guide] | None = None,
) -> str:
    sections = _readme_sections((root / "README.md").read_text(encoding="utf-8"))
    intro = sections["_intro"].split("\n", 1)[1].strip()  # without the "# puma-course" title
    start = sections.get("Start", "")
    command = re.search(r"```bash\n(.*?)```", start, re.S)
    unix = first_commands(start, "linux-macos")
    windows = first_commands(start, "windows")
    install = unix or (command.group(1).strip() if command else 'python -m pip install -e ".[lab]" && puma-course lab')
    lines = ["# puma-course: kinematics of robot manipulators", "", intro, "", *_get_the_course(repo_url, archive),
             "## Read, then run", "",
             "Every page of this site is a notebook of the course, shown with the outputs it had when it was "
             "last run: figures, tables, animations that play, and a picture of each 3-D panel. Nothing here "
             "runs code; to change the numbers and turn the arms, install the course (Python 3.10 or newer) "
             "and open it in JupyterLab, from the course folder (Linux and macOS):", "", "```bash", install, "```", "",
             *(["On Windows:", "", "```bat", windows, "```", ""] if windows else []),
             "Each lecture page has a download button (top right) for its notebook; it runs in the "
             "course, which the archive above holds.", "",
             "## Lectures", ""]  # fmt: skip
    for nb in lectures:
        lines.append(f"- [{_title(nb)}](notebooks/{nb.name})")
    lines += ["", "## Exercises", "",
              "The exercises as they are handed out: write each answer where the notebook says, then run its "
              "self-check. Solutions are not published.", ""]  # fmt: skip
    for nb in exercises:
        lines.append(f"- [{_title(nb)}](exercises/{nb.name})")
    lines += ["", "## The course's conventions", "", "[Notation and conventions](conventions.md): the symbols of "
              "every arm, units, the three readings of a transform, the DH flavour, the IK results.", ""]  # fmt: skip
    others = [g for g in guides or [] if g.page != "conventions"]
    if others:
        lines += ["## Guides", ""] + [f"- [{g.title}]({g.page}.md)" for g in others] + [""]
    lines += ["```{toctree}", ":hidden:", ":caption: Lectures", ""] + [f"notebooks/{nb.stem}" for nb in lectures]
    lines += ["```", "", "```{toctree}", ":hidden:", ":caption: Exercises", ""]
    lines += [f"exercises/{nb.stem}" for nb in exercises] + ["```", ""]
    lines += ["```{toctree}", ":hidden:", ":caption: The course", "", "conventions", *(g.page for g in others)]
    lines += ["```", ""]
    return "\n".join(lines)


def _conventions_page(root: Path) -> str:
    """The notation and conventions from a course's README, for a course without ``docs/conventions.md``."""
    sections = _readme_sections((root / "README.md").read_text(encoding="utf-8"))
    out = ["# Notation and conventions", "",
           "The course states its notation and its conventions once; every lecture follows them.", ""]  # fmt: skip
    for key in ("Notation", "Conventions"):
        body = sections.get(key, "")
        # links into the repository (notebooks, folders) are rewritten for the site or dropped
        body = re.sub(r"\[([^\]]+)\]\((?!https?:)(?!notebooks/|exercises/)[^)]*\)", r"\1", body)
        out += [f"## {key}", "", body.strip(), ""]
    return "\n".join(out)


def _copy_lecture(nb: Path, dest: Path) -> None:
    """Copy a lecture for the build, its animations given their cells' text alternatives (:mod:`.alt_text`)."""
    import json

    from .alt_text import with_animation_alt

    data = json.loads(nb.read_text(encoding="utf-8"))
    if with_animation_alt(data):
        dest.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    else:
        shutil.copy2(nb, dest)


def _mathjax_source() -> Path:
    """MathJax's component, from the ``sphinx-mathjax-offline`` distribution (which bundles MathJax 3.2.2)."""
    import importlib.util

    spec = importlib.util.find_spec("sphinx-mathjax-offline")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError("the site needs MathJax: pip install -e '.[site]' (it brings sphinx-mathjax-offline)")
    return Path(next(iter(spec.submodule_search_locations))) / "static" / "mathjax" / MATHJAX_FILE


def _copy_mathjax(dest: Path) -> None:
    # with its speech-rule-engine maps and accessibility components, CDN addresses rewritten (issue 25)
    from .offline_mathjax import copy_offline_mathjax

    _mathjax_source()  # the clear message when MathJax is missing
    copy_offline_mathjax(dest)


_CONF = """
project = "puma-course"
author = "the puma-course authors"
extensions = ["myst_nb", "puma_course.site.math"]
exclude_patterns = ["_build", "**/.ipynb_checkpoints"]
html_theme = "sphinx_book_theme"
html_title = "puma-course"
html_static_path = ["../assets"]
html_extra_path = ["../extra"]
html_theme_options = {{
    "use_download_button": True,
    "use_fullscreen_button": False,
    "use_repository_button": False,
    "launch_buttons": {{}},
    "show_toc_level": 2,
}}
html_css_files = ["puma.css"]
html_js_files = ["puma-a11y.js"]
html_show_sourcelink = False
html_copy_source = True
myst_enable_extensions = ["dollarmath", "amsmath", "html_image", "html_admonition"]
myst_heading_anchors = 3
nb_execution_mode = "off"
nb_ipywidgets_js = {{}}
nb_mime_priority_overrides = [("html", "application/vnd.jupyter.widget-view+json", None)]
nb_merge_streams = True
mathjax_path = "mathjax/{mathjax}"
# MyST marks every section "tex2jax_ignore" (a stray $ in prose is not mathematics); MathJax typesets
# the elements it marked "math" and the notebooks' outputs, and nothing else
mathjax3_config = {{
    "options": {{"processHtmlClass": "math|output_area", "ignoreHtmlClass": "tex2jax_ignore|mathjax_ignore"}},
    "tex": {{"inlineMath": [["\\\\(", "\\\\)"]], "displayMath": [["\\\\[", "\\\\]"]], "processEscapes": True}},
    "svg": {{"fontCache": "global"}},
}}
# the theme's light/dark switch starts from the reader's system setting otherwise, and the notebooks'
# figures are drawn for a white page
html_context = {{"default_mode": "light"}}
myst_update_mathjax = False  # the configuration above is complete
suppress_warnings = ["myst.header", "mystnb.unknown_mime_type"]
"""


#: the theme's search button is named "Search" but shows "Search Ctrl+K": WCAG 2.5.3 (label in name) wants the
#: name to hold the visible text, so the button is named by its content instead
_JS = """document.addEventListener("DOMContentLoaded", () => {
  document.querySelectorAll("button.search-button__button[aria-label]").forEach((b) => {
    if (b.textContent.trim()) b.removeAttribute("aria-label");
  });
});
"""

#: the site's own style: on a wide screen the sidebar holds the search field, so the theme's top bar
#: (a second search field and nothing else) is hidden; below 960 px it stays (it opens the sidebar)
_CSS = """@media (min-width: 960px) {
  #pst-header { display: none !important; }
}
"""


def build_site(
    course: str | Path | None = None,
    out: str | Path | None = None,
    repo_url: str | None = None,
    edition: EditionWriter | None = None,
    guides: str = "readers",
) -> SiteReport:
    """Build the website of the course at ``course`` (default: the course around the current folder).

    ``out`` (default ``<course>/_site``) receives the HTML; it is replaced. ``repo_url`` is the
    repository the landing page points to (default: :func:`repository_url` of the course's
    ``pyproject.toml``; none, when it names none). The landing page also links the student
    edition's archive (:data:`ARCHIVE`), built here. Everything else the build writes (Sphinx's
    doctrees, MyST-NB's ``jupyter_execute/``) stays in a temporary folder, so the course is left as
    it was. ``guides`` says which of the course's guides (``docs/*.md``) become pages: ``"readers"`` (those
    written for students, :data:`~puma_course.site.guides.READER_GUIDES`) or ``"all"`` (the instructors' and
    maintainers' too, for an instructor's own copy; see :mod:`puma_course.site.guides`). Returns a
    :class:`SiteReport`. Raises ``ValueError`` when the folder is not a course or ``guides`` is unknown.
    """
    from sphinx.application import Sphinx

    root = find_course(course)
    chosen = guides_of(root, guides)
    out_dir = Path(out) if out is not None else root / "_site"
    if repo_url is None:
        repo_url = repository_url(root)
    if repo_url is not None and not re.fullmatch(r"https?://[^\s\"'<>]+", repo_url):
        raise ValueError(f"repo_url: expected an http:// or https:// address, got {repo_url!r}")
    lectures = sorted((root / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    exercises = sorted((root / "exercises").glob("ex*.ipynb"))
    if not lectures:
        raise ValueError(f"course: expected lectures in {root / 'notebooks'}, found none")
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="puma-site-") as tmp:
        base = Path(tmp)
        src = base / "src"
        (src / "notebooks").mkdir(parents=True)
        (src / "exercises").mkdir()
        for nb in lectures:
            _copy_lecture(nb, src / "notebooks" / nb.name)
        for nb in exercises:
            shutil.copy2(nb, src / "exercises" / nb.name)
        if (root / "figures").is_dir():
            shutil.copytree(root / "figures", src / "figures", ignore=shutil.ignore_patterns("*.py", "__pycache__"))
        landing = _landing_page(root, lectures, exercises, repo_url, edition is not None, chosen)
        (src / "index.md").write_text(landing, encoding="utf-8")
        if not any(g.page == "conventions" for g in chosen):  # a course without docs/conventions.md
            (src / "conventions.md").write_text(_conventions_page(root), encoding="utf-8")
        names = ({nb.name for nb in lectures}, {nb.name for nb in exercises})
        for guide in chosen:
            (src / f"{guide.page}.md").parent.mkdir(parents=True, exist_ok=True)
            (src / f"{guide.page}.md").write_text(site_markdown(guide, chosen, *names), encoding="utf-8")
        (src / "conf.py").write_text(_CONF.format(mathjax=MATHJAX_FILE), encoding="utf-8")
        _copy_mathjax(base / "assets" / "mathjax")
        (base / "assets" / "puma.css").write_text(_CSS, encoding="utf-8")
        (base / "assets" / "puma-a11y.js").write_text(_JS, encoding="utf-8")
        if edition is not None:  # `puma-course site` hands in the edition's writer
            _edition_archive(root, base / "extra", edition)
        warnings = io.StringIO()
        # built inside the temporary folder (MyST-NB writes jupyter_execute/ next to Sphinx's output
        # folder), then moved to out_dir
        html_dir = base / "html"
        app = Sphinx(str(src), str(src), str(html_dir), str(base / "doctrees"), "html",
                     status=io.StringIO(), warning=warnings, freshenv=True)  # fmt: skip
        app.build()
        if out_dir.exists():
            shutil.rmtree(out_dir)
        out_dir.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(str(html_dir), str(out_dir))
    for source_map in out_dir.glob("_static/**/*.map"):  # the theme's 3 MB of source maps serve no reader
        source_map.unlink()
    pages = tuple(sorted(str(p.relative_to(out_dir)) for p in out_dir.rglob("*.html") if "_static" not in p.parts))
    size = sum(p.stat().st_size for p in out_dir.rglob("*") if p.is_file())
    plain = re.sub(r"\x1b\[[0-9;]*m", "", warnings.getvalue())  # without the terminal's colours
    found = tuple(line for line in plain.splitlines() if line.strip())
    return SiteReport(out_dir, pages, time.perf_counter() - start, size, found)
