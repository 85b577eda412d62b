"""Do the slides fit a projector? Slides per lecture and slides taller than the screen, in a real browser.

Builds the slides (``puma-course slides``, all lectures, into a temporary folder unless ``--slides DIR``
names a folder already built), times the build and weighs it, then opens each lecture's page from disk in
Debian's Chromium driven by Playwright at 1280×720, waits for reveal.js and MathJax, shows every slide
(``Reveal.getSlides()``, each in turn with ``Reveal.slide(h, v)``) and reads its ``scrollHeight``, the
height of its content (reveal.js lays a slide out at 1280×700). Prints, per lecture, the slides, those
taller than 720 px and than 1.5 screens (1080 px), the tallest, and the total over the screen heights;
with ``--shot NN:K`` also a screenshot of slide K (0-based, in ``Reveal.getSlides()`` order) of lecture NN.

    python benchmarks/bench_slides.py                          # build then measure
    python benchmarks/bench_slides.py --slides _slides --shot 09:5 --shot-file /tmp/s.png

Figures are printed, not asserted (tests/instructor/test_instructor.py checks the structure instead).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SCREEN_W, SCREEN_H = 1280, 720

_MEASURE = r"""async () => {
  const Reveal = await new Promise(r => require(["assets/reveal/dist/reveal.js"], r));
  for (let k = 0; k < 100 && !Reveal.isReady(); k++) await new Promise(r => setTimeout(r, 100));
  if (window.MathJax && MathJax.startup) await MathJax.startup.promise;
  const out = [];
  for (const s of Reveal.getSlides()) {
    const i = Reveal.getIndices(s);
    Reveal.slide(i.h, i.v);
    await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));
    out.push([s.scrollHeight, s.innerText.slice(0, 70).replace(/\s+/g, ' ')]);
  }
  return out;
}"""


def measure(folder: Path, shot: tuple[str, int] | None, shot_file: Path, verbose: bool = False) -> None:
    from playwright.sync_api import sync_playwright

    pages = sorted(folder.glob("[0-9][0-9]_*.slides.html"))
    print(f"{'lecture':<44}{'slides':>7}{'>720px':>8}{'>1080px':>9}{'tallest':>9}{'screens':>9}")
    totals = [0, 0, 0, 0.0]
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium")
        page = browser.new_page(viewport={"width": SCREEN_W, "height": SCREEN_H})
        for html in pages:
            page.goto(html.as_uri())
            page.wait_for_function("typeof require !== 'undefined'")
            measured = page.evaluate(_MEASURE)
            heights = [h for h, _ in measured]
            tall = sum(h > SCREEN_H for h in heights)
            very = sum(h > 1.5 * SCREEN_H for h in heights)
            screens = sum(heights) / SCREEN_H
            totals[0] += len(heights)
            totals[1] += tall
            totals[2] += very
            totals[3] += screens
            print(f"{html.name[:-12]:<44}{len(heights):>7}{tall:>8}{very:>9}{max(heights):>9}{screens:>9.1f}")
            for k, (h, text) in enumerate(measured):
                if verbose and h > 1.5 * SCREEN_H:
                    print(f"    slide {k}: {h} px  {text!r}")
            if shot and html.name.startswith(shot[0]):
                page.evaluate(
                    "k => require(['assets/reveal/dist/reveal.js'], R => { const i = R.getIndices(R.getSlides()[k]);"
                    " R.slide(i.h, i.v); })",
                    shot[1],
                )
                page.wait_for_timeout(800)
                page.screenshot(path=str(shot_file))
                print(f"  screenshot of slide {shot[1]}: {shot_file}")
        browser.close()
    print(f"{'all lectures':<44}{totals[0]:>7}{totals[1]:>8}{totals[2]:>9}{'':>9}{totals[3]:>9.1f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--slides", type=Path, default=None, help="a folder of built slides (default: build them)")
    parser.add_argument("--shot", default=None, metavar="NN:K", help="screenshot slide K of lecture NN")
    parser.add_argument("-v", "--verbose", action="store_true", help="name the slides taller than 1.5 screens")
    parser.add_argument("--shot-file", type=Path, default=Path(tempfile.gettempdir()) / "slide.png")
    args = parser.parse_args()
    shot = None
    if args.shot:
        number, k = args.shot.split(":")
        shot = (number.zfill(2), int(k))
    if args.slides is not None:
        measure(args.slides, shot, args.shot_file, args.verbose)
        return
    from puma_course.instructor import build_slides

    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        report = build_slides(ROOT, Path(tmp))
        print(f"puma-course slides (all lectures): {time.perf_counter() - start:.1f} s, {len(report.files)} pages, "
              f"{report.size / 1e6:.1f} MB with the assets")  # fmt: skip
        measure(Path(tmp), shot, args.shot_file, args.verbose)


if __name__ == "__main__":
    main()
