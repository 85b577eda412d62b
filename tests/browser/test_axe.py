"""axe-core's WCAG 2.1 A/AA rules in Chromium over every static page the course hands out (issue 34).

Every page of the course site (``puma-course site``), every slide deck (``puma-course slides``, in reveal's
print layout so that every slide is laid out, not only the first) and every instructor key
(``puma-course keys``) is served from 127.0.0.1 and checked by axe-core with the tags wcag2a, wcag2aa,
wcag21a and wcag21aa; a test fails on any violation and lists, per page, each rule with its node count.
No sampling: one browser and one context per kind visit every page in turn.

axe-core comes from npm (``.ci/run``: ``npm install --prefix .ci axe-core@4``) and is read from the disk,
so nothing is fetched at test time; without it these tests are skipped with the reason.
Per-page counts of the last run: ``tests/artifacts/axe_<kind>.json``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.browser.test_site import _free_port, _offline_page, _wait_for
from tests.support import ROOT, course_site

pytestmark = pytest.mark.browser

TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]


def axe_script() -> Path | None:
    """axe.min.js: ``$PUMA_AXE``, else ``.ci/node_modules`` (where ``.ci/run`` installs it), else npm's global root."""
    candidates = [Path(os.environ["PUMA_AXE"])] if os.environ.get("PUMA_AXE") else []
    candidates.append(ROOT / ".ci" / "node_modules" / "axe-core" / "axe.min.js")
    try:
        npm_root = subprocess.run(["npm", "root", "-g"], capture_output=True, text=True, timeout=30).stdout.strip()
        if npm_root:
            candidates.append(Path(npm_root) / "axe-core" / "axe.min.js")
    except (OSError, subprocess.SubprocessError):
        pass
    return next((c for c in candidates if c.is_file()), None)


@pytest.fixture(scope="module")
def axe() -> str:
    script = axe_script()
    if script is None:
        pytest.skip(
            "!!! axe-core is missing: npm install --prefix .ci axe-core@4 (.ci/run does it) or set PUMA_AXE to "
            "axe.min.js; the WCAG 2.1 A/AA checks are SKIPPED !!!"
        )
    return script.read_text(encoding="utf-8")


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """One temporary root; each kind is built into its folder by the test that needs it (``-k`` picks one)."""
    pytest.importorskip("myst_nb", reason="the site needs its extra (pip install -e '.[site]')")
    return tmp_path_factory.mktemp("axe")


def build(root: Path, kind: str, factory: pytest.TempPathFactory) -> Path:
    """Build the site, the slides or the keys into ``root/kind`` as ``puma-course site|slides|keys`` does.

    The site is the one built once per test run (:func:`tests.support.course_site`), linked in as ``root/site``.
    """
    from puma_course.instructor import build_keys, build_slides

    if kind == "site":
        (root / kind).symlink_to(course_site(factory)[0], target_is_directory=True)
    elif kind == "slides":
        build_slides(ROOT, root / kind)
    else:
        build_keys(ROOT, root / kind)
    return root / kind


@pytest.fixture(scope="module")
def served(built: Path) -> Iterator[str]:
    port = _free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "http.server", str(port), "--bind", "127.0.0.1", "--directory", str(built)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        base = f"http://127.0.0.1:{port}/"
        _wait_for(base)
        yield base
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def _pages(folder: Path, kind: str) -> list[str]:
    pages = sorted(
        str(p.relative_to(folder))
        for p in folder.rglob("*.html")
        if not {"_static", "assets"} & set(p.relative_to(folder).parts)
    )
    if kind == "slides":
        pages = [p for p in pages if p.endswith(".slides.html")]
    return pages


_SETTLE = """async () => {
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) await MathJax.startup.promise;
    if (document.querySelector('.reveal')) {
        const t0 = Date.now();
        while (!document.querySelector('.reveal.ready') && Date.now() - t0 < 20000)
            await new Promise(r => setTimeout(r, 50));
    }
    await new Promise(r => setTimeout(r, 200));
}"""

#: reveal leaves ``hidden`` and ``aria-hidden`` on the slides that were not current when it switched to its print
#: layout, where every slide is displayed: without this axe would judge every link of those as hidden yet focusable
_SHOW_ALL = """() => document.querySelectorAll('.reveal .slides section').forEach(
    s => { s.removeAttribute('hidden'); s.removeAttribute('aria-hidden'); })"""

_RUN = """async (tags) => {
    const r = await axe.run(document, {runOnly: {type: 'tag', values: tags}, resultTypes: ['violations']});
    return r.violations.map(v => ({id: v.id, impact: v.impact, nodes: v.nodes.length,
                                   first: v.nodes[0] ? v.nodes[0].target.join(' ') : ''}));
}"""


def audit(chromium: Any, base: str, folder: Path, kind: str, script: str) -> dict[str, list[dict[str, Any]]]:
    """{page: [{id, impact, nodes, first}, ...]} for every page of ``kind`` (the slides in reveal's print layout)."""
    external: list[str] = []
    errors: list[str] = []
    context, page = _offline_page(chromium, external, errors)
    results: dict[str, list[dict[str, Any]]] = {}
    try:
        for rel in _pages(folder, kind):
            url = f"{base}{kind}/{rel}" + ("?print-pdf" if kind == "slides" else "")
            page.goto(url, wait_until="load")
            page.evaluate(_SETTLE)
            if kind == "slides":  # reveal's navigation state: in the print layout every slide is shown
                page.evaluate(_SHOW_ALL)
            page.add_script_tag(content=script)
            results[rel] = page.evaluate(_RUN, TAGS)
    finally:
        context.close()
    assert not external, external[:3]
    return results


def _check(kind: str, results: dict[str, list[dict[str, Any]]], artifacts: Path) -> None:
    (artifacts / f"axe_{kind}.json").write_text(json.dumps(results, indent=1), encoding="utf-8")
    assert results, f"no {kind} page was found"
    failures = []
    for rel, violations in results.items():
        if violations:
            failures.append(
                f"{kind}/{rel}: " + ", ".join(f"{v['id']} x{v['nodes']} ({v['first']})" for v in violations)
            )
    assert not failures, f"WCAG 2.1 A/AA violations on {len(failures)} of {len(results)} pages:\n" + "\n".join(failures)


#: the slides and the keys are checked by test_axe_decks.py (the same test): a file of its own, so that a second
#: pytest worker (``--dist loadfile``) takes them while this one checks the site
@pytest.mark.parametrize("kind", ["site"])
def test_every_page_meets_wcag21_aa_under_axe(kind, axe, built, served, chromium, artifacts, tmp_path_factory):
    check_every_page(kind, axe, built, served, chromium, artifacts, tmp_path_factory)


def check_every_page(kind, axe, built, served, chromium, artifacts, tmp_path_factory):
    """Build ``kind``, audit every page of it, fail on any violation (the body of the test, here and in the decks')."""
    _check(kind, audit(chromium, served, build(built, kind, tmp_path_factory), kind, axe), artifacts)
