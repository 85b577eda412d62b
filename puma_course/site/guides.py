"""The course's guides (``docs/*.md``) as pages of the website.

The site is what students read, so by default it carries the guides written for readers of the course
(:data:`READER_GUIDES`: working with the course, the notation, the viewer, accessibility). The instructors'
and maintainers' guides stay out of it: they describe the grader's blind spots (``docs/safety.md``) and name
the solution markers the site must never show (``docs/authoring.md``). ``guides="all"`` renders them too, for
an instructor's own copy of the site.

Each page is copied with its links rewritten for the site: a link to a lecture, an exercise or another
rendered guide points to its page there (MyST resolves it, ``#anchors`` kept); a link to anything the site
does not hold (a test file, ``instructor/``, a guide left out) keeps its text and loses its target.
"""

from __future__ import annotations

import posixpath
import re
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import urlparse

__all__ = ["READER_GUIDES", "OTHER_GUIDES", "GUIDES", "Guide", "guides_of", "site_markdown"]

#: the guides every site carries, in the order of its navigation
READER_GUIDES = ("students", "conventions", "viewer", "accessibility")

#: the instructors' and maintainers' guides, in the order of the navigation of a site built with ``guides="all"``
#: (any other ``docs/*.md`` follows, by name)
OTHER_GUIDES = ("instructors", "authoring", "edition", "grading", "platforms", "written", "safety", "hub", "website",
                "maintainers", "architecture", "performance")  # fmt: skip

#: the choices of ``build_site(guides=...)``
GUIDES = ("readers", "all")

#: the conventions page keeps its address at the site's root (``conventions.html``); other guides go under
#: ``guides/``
_ROOT_PAGES = {"conventions"}

_LINK = re.compile(r"(?<!!)\[([^\]]*)\]\(([^)\s]+)\)")
_FENCE = re.compile(r"^[ \t]*(```|~~~)", re.M)


@dataclass(frozen=True)
class Guide:
    """One guide on the site: its file in the course, its page in the site's source (no suffix), its title."""

    source: Path
    page: str
    title: str


def _title(text: str, fallback: str) -> str:
    m = re.search(r"^# (.+)$", text, re.M)
    return m.group(1).strip() if m else fallback


def guides_of(root: Path, guides: str = "readers") -> list[Guide]:
    """The guides of the course at ``root`` the site renders: ``"readers"`` (:data:`READER_GUIDES` that exist)
    or ``"all"`` (those first, then every other ``docs/*.md`` but its index, by name)."""
    if guides not in GUIDES:
        raise ValueError(f"guides: expected one of {', '.join(map(repr, GUIDES))}, got {guides!r}")
    docs = root / "docs"
    names = [n for n in READER_GUIDES if (docs / f"{n}.md").is_file()]
    if guides == "all":
        names += [n for n in OTHER_GUIDES if (docs / f"{n}.md").is_file()]
        names += sorted(p.stem for p in docs.glob("*.md") if p.stem not in names and p.stem != "index")
    out = []
    for name in names:
        source = docs / f"{name}.md"
        page = name if name in _ROOT_PAGES else f"guides/{name}"
        out.append(Guide(source, page, _title(source.read_text(encoding="utf-8"), name)))
    return out


def _site_path(repo_path: str, pages: dict[str, str], lectures: set[str], exercises: set[str]) -> str | None:
    """The site source file (relative to the source root) a course file is shown as, or None."""
    if repo_path in pages:
        return pages[repo_path] + ".md"
    folder, _, name = repo_path.rpartition("/")
    if (folder == "notebooks" and name in lectures) or (folder == "exercises" and name in exercises):
        return repo_path
    return None


def site_markdown(guide: Guide, rendered: list[Guide], lectures: set[str], exercises: set[str]) -> str:
    """``guide``'s Markdown with its links rewritten for the site (see the module's docstring).

    ``rendered`` are the guides on the site; ``lectures`` and ``exercises`` the notebook file names it holds.
    Fenced blocks are left alone."""
    pages = {f"docs/{g.source.name}": g.page for g in rendered}
    here = posixpath.dirname(guide.page)

    def rewrite(m: re.Match[str]) -> str:
        text, target = m.group(1), m.group(2)
        url = urlparse(target)
        if url.scheme or url.netloc or not url.path:  # the web, mail, or an anchor on this page
            return m.group(0)
        repo_path = posixpath.normpath(posixpath.join("docs", url.path))
        site = _site_path(repo_path, pages, lectures, exercises)
        if site is None:
            return text
        rel = posixpath.relpath(site, here or ".")
        return f"[{text}]({rel}{'#' + url.fragment if url.fragment else ''})"

    parts = _FENCE.split(guide.source.read_text(encoding="utf-8"))
    # split keeps the fence markers: text, fence, code, fence, text, ... ; rewrite the text outside fences
    out, inside = [], False
    for part in parts:
        if part in ("```", "~~~"):
            inside = not inside
            out.append(part)
        else:
            out.append(part if inside else _LINK.sub(rewrite, part))
    return "".join(out)
