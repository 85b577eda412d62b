"""No committed notebook output names the folder it was executed in.

The lectures, exercises and solutions are committed with their outputs, and a traceback shows where each
frame's file lives: ``/work/main/puma_course/transforms.py`` or ``…/.venv/lib/python3.12/site-packages/
numpy/…``. That names the maintainer's folders (and users), and it changes with every checkout. The outputs
keep the path from the package or library on (``puma_course/transforms.py``, ``numpy/linalg/…``), which is
what a reader needs.

This module is also the tool that strips them, after a notebook was re-executed::

    python -m tests.test_output_paths notebooks/01_rotations_and_transforms.ipynb [...]

It rewrites each notebook in place (outputs only) and names what it could not strip. nbval never compares
tracebacks, so stripping them changes no lecture's test; ``tests/nbval_sanitize.cfg`` strips the same
prefixes from the outputs it does compare.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Any

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted(
    [ROOT / "START_HERE.ipynb"]
    + [p for folder in ("notebooks", "exercises", "solutions") for p in (ROOT / folder).glob("*.ipynb")]
)

#: What a committed output must not hold: a home or work folder, or an installed library's folder.
FORBIDDEN = re.compile(r"/work/|/root/|/home/|/Users/|[A-Za-z]:\\Users\\|site-packages|dist-packages")
_PART = r"[^/\\\s\"'\x1b:<>()\[\],;]+"  # one folder name: no separator, space, quote, escape or punctuation
#: Where an absolute path starts: after no path character, or just after a terminal colour code (``\x1b[32m``)
_START = r"(?:(?<![\w.~-])|(?<=\x1b\[\dm)|(?<=\x1b\[\d\dm)|(?<=\x1b\[\d;\d\dm))"
#: An absolute folder ending in an installed library's folder, or before the course's package: dropped.
_LIBRARY = re.compile(rf"{_START}(?:/{_PART})+/(?:site|dist)-packages/")
_PACKAGE = re.compile(rf"{_START}(?:/{_PART})+/(?=puma_course/|puma_course_bank/|bank/)")


def strip_paths(text: str) -> str:
    """``text`` with the folders before an installed library or the course's package dropped.

    >>> strip_paths("File \\x1b[32m/work/main/puma_course/transforms.py:125\\x1b[39m, in rodrigues")
    'File \\x1b[32mpuma_course/transforms.py:125\\x1b[39m, in rodrigues'
    >>> strip_paths("/home/ann/.venv/lib/python3.12/site-packages/numpy/linalg/_linalg.py:104")
    'numpy/linalg/_linalg.py:104'
    >>> strip_paths("see notebooks/../puma_course/x.py and 1/2/puma_course")
    'see notebooks/../puma_course/x.py and 1/2/puma_course'
    """
    return _PACKAGE.sub("", _LIBRARY.sub("", text))


def _texts(output: dict[str, Any]) -> list[tuple[Any, Any]]:
    """Every (container, key) of an output that holds text: a stream, an error's value and traceback, data."""
    found: list[tuple[Any, Any]] = []
    if "text" in output:
        found.append((output, "text"))
    if "evalue" in output:
        found.append((output, "evalue"))
    found += [(output["traceback"], i) for i in range(len(output.get("traceback", [])))]
    found += [(output["data"], k) for k, v in output.get("data", {}).items() if isinstance(v, (str, list))]
    return found


def _join(value: Any) -> str:
    return "".join(value) if isinstance(value, list) else str(value)


def found_paths(nb: Any) -> list[str]:
    """Where the outputs of ``nb`` name a folder: "cell N: …the path…" (outputs only, images left out)."""
    out = []
    for n, cell in enumerate(nb.cells, start=1):
        for output in cell.get("outputs", []):
            for box, key in _texts(output):
                if key in ("image/png", "image/jpeg"):
                    continue
                text = _join(box[key])
                for m in FORBIDDEN.finditer(text):
                    out.append(f"cell {n}: …{text[max(0, m.start() - 40) : m.end() + 40]!r}…")
    return out


def strip_notebook(path: Path) -> bool:
    """Strip the paths from the outputs of the notebook at ``path``, in place; True when it changed."""
    nb = nbformat.read(path, as_version=4)
    changed = False
    for cell in nb.cells:
        for output in cell.get("outputs", []):
            for box, key in _texts(output):
                if key in ("image/png", "image/jpeg"):
                    continue
                value = box[key]
                new = [strip_paths(s) for s in value] if isinstance(value, list) else strip_paths(str(value))
                if new != value:
                    box[key], changed = new, True
    if changed:
        nbformat.write(nb, path)
    return changed


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: f"{p.parent.name}/{p.stem[:12]}")
def test_no_output_names_a_folder(path):
    found = found_paths(nbformat.read(path, as_version=4))
    assert not found, (
        f"{path.relative_to(ROOT)}: outputs name folders (strip them: python -m tests.test_output_paths "
        f"{path.relative_to(ROOT)}): {found[:4]}"
    )


def test_the_scan_finds_what_it_should_and_the_strip_removes_it(tmp_path):
    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("rodrigues(1, 2)")
    frame = "\x1b[36mFile \x1b[39m\x1b[32m/work/wt/i25t/puma_course/kinematics/three_step/arm.py:172\x1b[39m, in f"
    lib = "/root/.venv/lib/python3.11/site-packages/numpy/linalg/_linalg.py:104"
    cell.outputs = [
        nbformat.v4.new_output("error", ename="ValueError", evalue="axis: expected a vector", traceback=[frame, lib]),
        nbformat.v4.new_output("stream", name="stdout", text="/home/ann/course/bank/ex01.py\n"),
        nbformat.v4.new_output("execute_result", data={"text/plain": "'/Users/ann/x/puma_course/__init__.py'"}),
    ]
    nb.cells.append(cell)
    assert len(found_paths(nb)) == 5  # the library's line twice: /root/ and site-packages
    path = tmp_path / "nb.ipynb"
    nbformat.write(nb, path)
    assert strip_notebook(path) and not strip_notebook(path)  # a second run changes nothing
    again = nbformat.read(path, as_version=4)
    assert found_paths(again) == []
    error = again.cells[0].outputs[0]
    assert error.traceback == [frame.replace("/work/wt/i25t/", ""), "numpy/linalg/_linalg.py:104"]
    assert again.cells[0].outputs[1].text == "bank/ex01.py\n"
    assert again.cells[0].source == "rodrigues(1, 2)" and error.evalue == "axis: expected a vector"
    # a path the strip cannot shorten is still found: the test names it, for the maintainer to look at
    cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text="saved to /home/ann/out.png\n")]
    assert strip_paths(cell.outputs[0].text) == cell.outputs[0].text and len(found_paths(nb)) == 1


def test_the_nbval_sanitizer_strips_the_same_prefixes():
    """A compared output that shows a path reads the same wherever the lecture ran (as nbval reads the file)."""
    from nbval.plugin import get_sanitize_patterns

    pairs = get_sanitize_patterns((ROOT / "tests" / "nbval_sanitize.cfg").read_text(encoding="utf-8"))
    assert len(pairs) >= 8

    def sanitize(text: str) -> str:
        for regex, replace in pairs:
            text = re.sub(regex, replace, text)
        return text

    for where in ("/work/main/", "/home/ann/course/", "/opt/venv/lib/python3.12/site-packages/"):
        for name in ("puma_course/transforms.py", "bank/ex01_rotations.py"):
            assert sanitize(f"File \x1b[32m{where}{name}:125") == f"File \x1b[32m{name}:125"
    assert sanitize("/x/lib/python3.11/site-packages/numpy/a.py") == "numpy/a.py"
    assert (
        sanitize("notebooks/../puma_course/a.py and 1/2/puma_course/")
        == "notebooks/../puma_course/a.py and 1/2/puma_course/"
    )
    assert (
        sanitize(strip_paths("/root/v/lib/site-packages/numpy/a.py, /w/puma_course/b.py"))
        == "numpy/a.py, puma_course/b.py"
    )


def main(argv: list[str]) -> int:
    """Strip the paths from the notebooks named in ``argv``; name what is left (exit 1 when anything is)."""
    if not argv:
        print("usage: python -m tests.test_output_paths NOTEBOOK.ipynb [...]", file=sys.stderr)
        return 2
    left = 0
    for name in argv:
        path = Path(name)
        print(f"{name}: {'stripped' if strip_notebook(path) else 'nothing to strip'}")
        for where in found_paths(nbformat.read(path, as_version=4)):
            print(f"  still names a folder, {where}", file=sys.stderr)
            left += 1
    return 1 if left else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
