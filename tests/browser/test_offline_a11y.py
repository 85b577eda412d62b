"""MathJax's accessibility and the instructor's slides, offline, in Chromium (issue 25).

The speech-rule engine's maps are bundled beside MathJax (:mod:`puma_course.site.offline_mathjax`):
with every request to another host aborted, the explorer still gives a formula its spoken form.
The slides of a lecture open from the disk (``file://``) with reveal.js running and the math typeset.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from puma_course.instructor import build_slides
from puma_course.site.offline_mathjax import copy_offline_mathjax
from tests.browser.test_site import _free_port, _offline_page, _wait_for
from tests.support import ROOT

pytestmark = pytest.mark.browser

_PAGE = """<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>speech</title>
<script>window.MathJax = {options: {menuOptions: {settings: {explorer: true}}}};</script>
<script src="tex-svg-full.js"></script></head><body><p>\\(x^2 + \\sqrt{y}\\)</p></body></html>
"""


def test_the_explorer_speaks_a_formula_with_the_bundled_maps_and_no_network(tmp_path, chromium):
    pytest.importorskip("myst_nb", reason="MathJax comes with the site's extra (pip install -e '.[site]')")
    copy_offline_mathjax(tmp_path)
    (tmp_path / "speech.html").write_text(_PAGE, encoding="utf-8")
    port = _free_port()
    proc = subprocess.Popen([sys.executable, "-m", "http.server", str(port), "--bind", "127.0.0.1", "--directory",
                             str(tmp_path)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    external: list[str] = []
    errors: list[str] = []
    try:
        base = f"http://127.0.0.1:{port}/"
        _wait_for(base)
        context, page = _offline_page(chromium, external, errors)
        requested: list[str] = []
        page.on("request", lambda r: requested.append(r.url))
        page.goto(base + "speech.html", wait_until="load")
        page.wait_for_function("() => document.querySelector('[data-semantic-speech]') !== null", timeout=30_000)
        speech = page.locator("[data-semantic-speech]").first.get_attribute("data-semantic-speech")
        context.close()
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    assert speech and "squared" in speech and "root" in speech.lower(), speech
    assert any(u.endswith("/sre/mathmaps/en.json") for u in requested), requested
    assert not external, external


def test_a_lectures_slides_open_from_the_disk_with_reveal_and_math(tmp_path, chromium, artifacts):
    pytest.importorskip("myst_nb", reason="MathJax comes with the site's extra (pip install -e '.[site]')")
    report = build_slides(ROOT, tmp_path, ("01",))
    context = chromium.new_context(viewport={"width": 1280, "height": 800})
    external: list[str] = []
    context.route("http*://**/*", lambda r: (external.append(r.request.url), r.abort()))
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(report.files[0].as_uri(), wait_until="load")
    page.wait_for_function("() => document.querySelector('.reveal.ready') !== null", timeout=30_000)
    page.wait_for_function("() => document.querySelectorAll('mjx-container').length > 5", timeout=30_000)
    for _ in range(3):
        page.keyboard.press("ArrowRight")
    page.wait_for_timeout(500)
    page.screenshot(path=str(artifacts / "slides_01.png"))
    total = page.evaluate("() => document.querySelectorAll('.reveal .slides section').length")
    alts = page.evaluate("() => [...document.querySelectorAll('.reveal img')].map(i => i.alt)")
    context.close()
    assert total > 10, total
    assert alts and all(len(a) > 30 and "No description" not in a for a in alts), alts
    assert not errors, errors
    assert not external, external
