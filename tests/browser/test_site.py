"""The static website in a real browser: built from the committed notebooks, served on 127.0.0.1,
every page opened in Chromium with the network cut off at 127.0.0.1 (marker ``browser``).

Asserts: no console errors; nothing requested from another host; every math element rendered by the
bundled MathJax; every animation's controls present and one animation advancing when played; every
internal link resolving to a file of the site; no page holding a solution (the markers, or a line of a
solution's code). Screenshots of the landing page and one lecture go to ``tests/artifacts/``.
"""

from __future__ import annotations

import html
import re
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from urllib.parse import unquote, urldefrag, urljoin, urlparse

import nbformat
import pytest

from tests.support import ROOT, course_site

pytestmark = pytest.mark.browser


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site as ``puma-course site`` builds it (once per test run: :func:`tests.support.course_site`)."""
    out, printed = course_site(tmp_path_factory)
    pages = re.search(r"built (\d+) pages", printed)
    assert pages and int(pages.group(1)) >= 20, printed
    return out


@pytest.fixture(scope="module")
def server(site: Path) -> Iterator[str]:
    port = _free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "http.server", str(port), "--bind", "127.0.0.1", "--directory", str(site)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        base = f"http://127.0.0.1:{port}/"
        _wait_for(base)
        yield base
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _wait_for(url: str, seconds: float = 15.0) -> None:
    import urllib.request

    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            urllib.request.urlopen(url, timeout=2).close()
            return
        except OSError:
            time.sleep(0.1)
    raise RuntimeError(f"the site's server at {url} did not answer")


def _pages(site: Path) -> list[str]:
    return sorted(str(p.relative_to(site)) for p in site.rglob("*.html") if "_static" not in p.relative_to(site).parts)


def _offline_page(chromium: Any, external: list[str], errors: list[str]) -> Any:
    context = chromium.new_context(viewport={"width": 1300, "height": 900})
    # a lecture page with its figures and MathJax can take over Playwright's default 30 s to load on a busy
    # machine (seen at load 15); what is checked is what the page shows, not how fast it came
    context.set_default_navigation_timeout(120_000)

    def route(r: Any) -> None:
        host = urlparse(r.request.url).hostname
        if host in ("127.0.0.1", None) or r.request.url.startswith("data:"):
            r.continue_()
        else:
            external.append(r.request.url)
            r.abort()

    context.route("**/*", route)
    page = context.new_page()
    page.on("console", lambda m: errors.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"pageerror: {e}"))
    return context, page


def _math_rendered(page: Any) -> tuple[int, int]:
    """(math elements on the page, math elements MathJax rendered), after MathJax's first typesetting."""
    if page.locator(".math").count():
        # MathJax loads deferred: wait for it, then for the promise of its first typesetting
        page.wait_for_function("() => window.MathJax && window.MathJax.startup && window.MathJax.startup.promise",
                               timeout=30_000)  # fmt: skip
        page.evaluate("() => MathJax.startup.promise")
    return page.evaluate(
        """() => {
            const els = [...document.querySelectorAll('.math.notranslate')];
            const done = els.filter(e => e.querySelector('mjx-container svg') && !e.querySelector('[data-mjx-error]'));
            return [els.length, done.length];
        }"""
    )


def test_every_page_offline_without_errors_and_with_its_math_rendered(site, server, chromium, artifacts):
    failures: list[str] = []
    total_math = 0
    for rel in _pages(site):
        external: list[str] = []
        errors: list[str] = []
        context, page = _offline_page(chromium, external, errors)
        try:
            page.goto(server + rel, wait_until="load")
            n, done = _math_rendered(page)
            total_math += n
            if done < n:
                failures.append(f"{rel}: {n - done} of {n} math elements not rendered")
            if rel == "index.html":
                page.screenshot(path=str(artifacts / "site_landing.png"), full_page=False)
            if rel.startswith("notebooks/03_"):
                page.screenshot(path=str(artifacts / "site_lecture_03.png"), full_page=False)
        finally:
            context.close()
        if external:
            failures.append(f"{rel}: requested from another host: {sorted(set(external))[:3]}")
        if errors:
            failures.append(f"{rel}: {errors[:3]}")
    assert total_math > 100, "the lectures' mathematics did not reach the site"
    assert not failures, "\n".join(failures)


def test_animations_have_their_controls_and_play(site, server, chromium):
    animated = [rel for rel in _pages(site) if 'class="animation"' in (site / rel).read_text(encoding="utf-8")]
    assert animated, "no page of the site holds an animation"
    external: list[str] = []
    errors: list[str] = []
    for rel in animated:
        context, page = _offline_page(chromium, external, errors)
        try:
            page.goto(server + rel, wait_until="load")
            players = page.locator("div.animation")
            assert players.count() >= 1
            for i in range(players.count()):
                buttons = players.nth(i).locator("button")
                assert buttons.count() >= 8, f"{rel}: animation {i} lacks its controls"
                # the icons come from the site itself: the course player's text glyphs, matplotlib's player's
                # inline glyphs (an <i> with a ::before character), or the theme's bundled Font Awesome,
                # which swaps each <i> for an inline <svg>
                drawn = page.evaluate(
                    """(b) => {
                        if (!b.querySelector('i, svg') && b.textContent.trim()) return true;  // a text glyph
                        const svg = b.querySelector('svg');
                        if (svg) return svg.getBoundingClientRect().width > 4;
                        const i = b.querySelector('i');
                        const c = i ? getComputedStyle(i, '::before').content : 'none';
                        return !['none', 'normal', '""'].includes(c);
                    }""",
                    buttons.nth(5).element_handle(),
                )
                assert drawn, f"{rel}: animation {i}: blank play icon"
            slider = players.first.locator("input[type=range]")
            before = int(slider.input_value())
            players.first.locator("button[title='Play']").click()
            page.wait_for_timeout(800)
            assert int(slider.input_value()) != before, f"{rel}: the animation did not advance when played"
        finally:
            context.close()
    assert not external and not errors, (external[:3], errors[:3])


def test_search_finds_a_lecture_offline(site, server, chromium):
    external: list[str] = []
    errors: list[str] = []
    context, page = _offline_page(chromium, external, errors)
    try:
        page.goto(server + "search.html?q=Rodrigues", wait_until="load")
        hits = page.locator("#search-results ul.search li a")
        hits.first.wait_for(timeout=20_000)
        targets = [hits.nth(i).get_attribute("href") or "" for i in range(hits.count())]
    finally:
        context.close()
    assert any(t.startswith("notebooks/01_") for t in targets), targets
    assert not external and not errors, (external[:3], errors[:3])


def test_every_internal_link_resolves(site):
    broken = []
    for rel in _pages(site):
        text = (site / rel).read_text(encoding="utf-8")
        for href in re.findall(r'href="([^"]+)"', text):
            href = html.unescape(href)
            if href.startswith(("http:", "https:", "mailto:", "#", "javascript:", "data:")):
                continue
            target, fragment = urldefrag(urljoin(rel, href))
            target = urlparse(target).path  # without ?digest=… cache keys
            path = site / unquote(target)
            if target.endswith("/"):
                path = path / "index.html"
            if not path.exists():
                broken.append(f"{rel} -> {href}")
            elif fragment and path.suffix == ".html":
                page = path.read_text(encoding="utf-8")
                if f'id="{fragment}"' not in page:
                    broken.append(f"{rel} -> {href} (no anchor {fragment!r})")
    assert not broken, "\n".join(broken[:20])


def _solution_lines() -> set[str]:
    lines = set()
    for path in (ROOT / "solutions").glob("*.ipynb"):
        for cell in nbformat.read(path, as_version=4).cells:
            inside = False
            for line in cell.source.splitlines():
                s = line.strip()
                if s in ("### BEGIN SOLUTION", "### BEGIN HIDDEN TESTS"):
                    inside = True
                elif s in ("### END SOLUTION", "### END HIDDEN TESTS"):
                    inside = False
                elif inside and len(s) >= 25 and not s.startswith("#"):
                    lines.add(s)
    # a line the student is handed anyway (in a released exercise or in a lecture) is not a leak
    public = "\n".join(
        cell.source
        for path in [*(ROOT / "exercises").glob("*.ipynb"), *(ROOT / "notebooks").glob("*.ipynb")]
        for cell in nbformat.read(path, as_version=4).cells
    )
    return {line for line in lines if line not in public}


def test_no_page_contains_a_solution(site):
    markers = ("BEGIN SOLUTION", "END SOLUTION", "BEGIN HIDDEN TESTS", "END HIDDEN TESTS")
    code = _solution_lines()
    assert len(code) > 20  # the search below is not vacuous
    leaks = []
    for path in site.rglob("*"):
        if path.suffix not in (".html", ".ipynb", ".txt", ".js", ".md") or not path.is_file():
            continue
        text = html.unescape(re.sub(r"<[^>]+>", "", path.read_text(encoding="utf-8", errors="replace")))
        leaks += [f"{path.relative_to(site)}: {m}" for m in markers if m in text]
        leaks += [f"{path.relative_to(site)}: {line[:60]}" for line in code if line in text]
    assert not leaks, "\n".join(leaks[:20])
