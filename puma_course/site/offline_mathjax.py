"""MathJax 3 for pages that must work offline, accessibility included.

``sphinx-mathjax-offline`` bundles MathJax 3.2.2, whose component ``tex-svg-full.js`` carries the
speech-rule engine (SRE) that gives speech, Braille and the expression explorer. MathJax's loader
looks for SRE's locale maps at ``[mathjax]/sre/mathmaps`` (next to the component) and loads the
explorer from ``[mathjax]/a11y/``; both are copied here, beside the component. SRE's own fall-back
addresses (its maps, the maps for Internet Explorer and an XPath polyfill for browsers without
``document.evaluate``) name cdn.jsdelivr.net; they are rewritten to files beside the component, so no
file of a built page names a CDN and nothing is fetched from one (a browser that would need the
polyfill gets a local 404, not a request to another host).
"""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

__all__ = ["MATHJAX_FILE", "mathjax_root", "copy_offline_mathjax", "CDN_REWRITES"]

MATHJAX_FILE = "tex-svg-full.js"

#: exact strings of MathJax 3.2.2's SRE that name a CDN, and what replaces them (each must occur)
CDN_REWRITES = (
    ('"https://cdn.jsdelivr.net/npm/speech-rule-engine@"+', '"./sre/mathmaps"||'),
    ('"https://cdn.jsdelivr.net/npm/sre-mathmaps-ie@"+', '"./sre/mathmaps_ie.js"||'),
    ('"https://cdn.jsdelivr.net/npm/wicked-good-xpath@1.3.0/dist/wgxpath.install.js"', '"./sre/wgxpath.install.js"'),
)


def mathjax_root() -> Path:
    """The folder of MathJax's components in the ``sphinx-mathjax-offline`` distribution."""
    spec = importlib.util.find_spec("sphinx-mathjax-offline")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError("MathJax is missing: pip install -e '.[site]' (it brings sphinx-mathjax-offline)")
    return Path(next(iter(spec.submodule_search_locations))) / "static" / "mathjax"


def _rewrite(text: str, name: str) -> str:
    for old, new in CDN_REWRITES:
        text = text.replace(old, new)
    if "cdn.jsdelivr.net" in text:
        raise RuntimeError(f"{name}: a CDN address is left after the rewrite (a MathJax other than 3.2.2?)")
    return text


def copy_offline_mathjax(dest: Path) -> None:
    """Copy ``tex-svg-full.js``, its accessibility components (``a11y/``), SRE's maps (``sre/``) and the
    licence into ``dest``, every CDN address rewritten (:data:`CDN_REWRITES`)."""
    root = mathjax_root()
    dest.mkdir(parents=True, exist_ok=True)
    # the explorer enriches the MathML it gets from input/mml.js; a11y/ holds the explorer and SRE
    extra = [Path("input/mml.js"), *sorted(p.relative_to(root) for p in (root / "a11y").glob("*.js"))]
    for rel in [Path(MATHJAX_FILE), *extra]:
        target = dest / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(_rewrite((root / rel).read_text(encoding="utf-8"), str(rel)), encoding="utf-8")
    if (dest / "sre").exists():
        shutil.rmtree(dest / "sre")
    shutil.copytree(root / "sre", dest / "sre")
    shutil.copy2(Path(__file__).with_name("MATHJAX-LICENSE"), dest / "LICENSE")
