"""README is a front door and docs/ holds the guides (issue 32): README stays small, every guide is reachable
from README or the docs index, and every relative link of README and docs/ opens a file (and, for a link into
a Markdown page, a heading of that page)."""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import unquote, urlparse

from tests.support import ROOT

DOCS = ROOT / "docs"
PAGES = sorted(DOCS.glob("*.md"))
_LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")

#: the front door's ceiling (issue 32: "at most 12 KB"), in bytes
README_LIMIT = 12_000


def _links(markdown: str) -> list[str]:
    """The targets of Markdown links, outside fenced and inline code."""
    text = re.sub(r"```.*?```", "", markdown, flags=re.DOTALL)
    text = re.sub(r"`[^`\n]*`", "", text)
    return _LINK.findall(text)


def slug(heading: str) -> str:
    """GitHub's (and MyST's ``myst_heading_anchors``) anchor of a heading: lower case, punctuation dropped,
    spaces to hyphens."""
    text = re.sub(r"`|\*\*|\*", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.DOTALL)
    return {slug(m[1]) for m in re.finditer(r"^#{1,6} (.+)$", text, flags=re.M)}


def _local(page: Path) -> list[tuple[str, Path, str]]:
    """(the link as written, the file it names, its #fragment) for every relative link of ``page``."""
    out = []
    for target in _links(page.read_text(encoding="utf-8")):
        url = urlparse(target)
        if url.scheme or url.netloc:
            continue
        path = (page.parent / unquote(url.path)) if url.path else page
        out.append((target, path, url.fragment))
    return out


def test_slug_is_githubs():
    assert slug("Install sizes") == "install-sizes"
    assert slug("What holds in Gradescope's container") == "what-holds-in-gradescopes-container"
    assert slug("Notation (one page, used by every lecture)") == "notation-one-page-used-by-every-lecture"


def test_the_readme_is_a_front_door_of_at_most_12_kb():
    size = (ROOT / "README.md").stat().st_size
    assert size <= README_LIMIT, f"README.md is {size:,} bytes; move the guide's text to docs/"


def test_the_readme_names_the_first_commands_the_test_command_and_the_docs_index():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "<!-- first-commands: linux-macos -->" in readme and "<!-- first-commands: windows -->" in readme
    assert 'python -m pip install -e ".[dev]" && python -m pytest' in readme
    assert "docs/index.md" in _links(readme)


def test_every_docs_page_is_reachable_from_the_readme_or_the_docs_index():
    assert len(PAGES) >= 15, [p.name for p in PAGES]
    linked = set()
    for page in (ROOT / "README.md", DOCS / "index.md"):
        linked |= {path.resolve() for _, path, _ in _local(page)}
    unreached = [p.name for p in PAGES if p.name != "index.md" and p.resolve() not in linked]
    assert not unreached, f"docs pages linked neither from README nor from docs/index.md: {unreached}"


def test_every_relative_link_of_the_readme_and_the_docs_resolves():
    broken = []
    seen = 0
    for page in [ROOT / "README.md", *PAGES]:
        for target, path, fragment in _local(page):
            seen += 1
            where = f"{page.relative_to(ROOT)} -> {target}"
            if not path.exists():
                broken.append(f"{where} (no such file)")
            elif fragment and path.suffix == ".md" and fragment not in anchors(path):
                broken.append(f"{where} (no heading #{fragment})")
    assert seen > 80, seen  # the scan found the links
    assert not broken, "\n".join(broken)


def test_a_broken_link_and_a_missing_anchor_are_caught(tmp_path):
    """The check above can fail: a page with a dead link and a dead anchor yields both."""
    page = tmp_path / "p.md"
    page.write_text("# Title\n\n[a](missing.md) [b](#title) [c](#nowhere) `[d](not-a-link.md)`\n", encoding="utf-8")
    found = [(t, p.exists(), f and f in anchors(p)) for t, p, f in _local(page)]
    assert found == [("missing.md", False, ""), ("#title", True, True), ("#nowhere", True, False)]
