"""The viewer's JavaScript: node's test runner on its pure functions, and the committed bundle built from the sources.

``puma_course/viz/static/viewer.js`` is built by ``js/build.mjs`` (``npm ci && npm run build`` in ``js/``);
its first line carries the sha256 of the sources it was built from, recomputed here as build.mjs does.
"""

from __future__ import annotations

import hashlib
import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
JS = ROOT / "js"
BUNDLE = ROOT / "puma_course" / "viz" / "static" / "viewer.js"


def _source_hash() -> str:
    h = hashlib.sha256()
    for path in sorted((JS / "src").glob("*.js"), key=lambda p: p.name):
        h.update(f"{path.name}\n{path.read_text(encoding='utf-8')}\n".encode())
    three = json.loads((JS / "package.json").read_text(encoding="utf-8"))["devDependencies"]["three"]
    h.update(f"three {three}\n".encode())
    return h.hexdigest()


def test_bundle_was_built_from_the_current_sources():
    first = BUNDLE.read_text(encoding="utf-8").splitlines()[0]
    assert f"sources sha256 {_source_hash()}" in first, "js/src changed: run `npm ci && npm run build` in js/"


def test_bundle_loads_nothing_from_the_network():
    text = BUNDLE.read_text(encoding="utf-8")
    assert not re.search(r"""(\bfrom|\bimport)\s*\(?\s*["'](https?:)?//""", text)  # no module from a URL
    for marker in ("cdn.jsdelivr", "unpkg.com", "esm.sh", "cdnjs"):
        assert marker not in text
    assert BUNDLE.stat().st_size < 800_000  # three.js (only what is used) and the viewer


@pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed: the JavaScript unit tests cannot run")
def test_node_unit_tests_pass():
    run = subprocess.run(["node", "--test", "test/"], cwd=JS, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "# fail 0" in run.stdout
