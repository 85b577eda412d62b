"""A marking document is inert: nothing a student writes or names can fetch, link or pose as another student.

The document is rendered with a real Markdown renderer (markdown-it-py, CommonMark, with and without its
``$...$`` formulas, as MyST and JupyterLab read them); every image source and link target in it must be one of
the marker's own attachment files, no raw HTML may come from a student, and the only headings are the
document's own, one per student. Students whose names become the same file name keep their own sketches.
"""

from __future__ import annotations

import base64
import re
from pathlib import Path

import nbformat
import pytest
from markdown_it import MarkdownIt
from mdit_py_plugins.dollarmath import dollarmath_plugin

from puma_course.cli import main
from puma_course.grading.output.marking import _inert
from puma_course.grading.written import ANSWER_TAG, written_questions
from tests.support import ROOT

EX = "ex02_dh_frames"
QID = written_questions(EX)[0].qid
PNG = b"\x89PNG\r\n\x1a\n" + bytes(range(40))

#: Every way a student's Markdown or HTML could show a remote image, link elsewhere or open a heading.
HOSTILE = r"""My frames: ![sketch](attachment:frames.png)
![reference image][r] and ![r] and ![r][] and [a link][r] and [r]
[r]: http://evil.example/ref.png "title"
[inline](http://evil.example/a) ![inline](http://evil.example/b.png "t") ![nested [alt]](http://evil.example/c.png)
![angle](<http://evil.example/sp ace.png>) [x]( http://evil.example/spaced )
<img src="http://evil.example/d.png" srcset="http://evil.example/e.png 2x"> <a href="http://evil.example/f">a</a>
<iframe src="http://evil.example/g"></iframe>
<http://evil.example/h> <mail@evil.example>
bare http://evil.example/i, www.evil.example and mail@evil.example
### `bob`
bob
===
alice
---
- ## `cy`
> ### `dan`
  # `eve`
***
$[x](http://evil.example/j)$ and $$\href{http://evil.example/k}{k}$$ and $a < b$, $\left[ x \right]$
\[x](http://evil.example/l) and \![y](http://evil.example/m.png)
<svg><image href="http://evil.example/n"/></svg><style>body{background:url(http://evil.example/o)}</style>
&lt;img src=http://evil.example/p&gt; &#91;q&#93;(http://evil.example/q)
"""
STUDENTS = {
    "Ann Lee": (HOSTILE, PNG + b"ann lee"),
    "Ann_Lee": ("Frames {1} and {2}, see my sketch.", PNG + b"ann_lee"),
    "eve [x](javascript:alert(1)) ![i](http:x)": ("### `Ann Lee`\nI copied nothing.", PNG + b"eve"),
    "bob": (r"The origin of {1} is where the axes cross, at height $h$; $z_2 = -y_0$.", None),
}


def _hand_in(base: Path, answer: str, sketch: bytes | None) -> None:
    nb = nbformat.read(ROOT / "exercises" / f"{EX}.ipynb", as_version=4)
    cell = next(c for c in nb.cells if ANSWER_TAG + QID in c.get("metadata", {}).get("tags", []))
    cell.source = answer
    if sketch is not None:
        cell["attachments"] = {
            "frames.png": {"image/png": base64.b64encode(sketch).decode()},
            "![x](http://evil.example/r.png)": {"text/html": base64.b64encode(b"<b>").decode()},
        }
    base.mkdir(parents=True)
    nbformat.write(nb, base / f"{EX}.ipynb")


def _renderers() -> list[MarkdownIt]:
    return [MarkdownIt("commonmark").enable("table"), MarkdownIt("commonmark").enable("table").use(dollarmath_plugin)]


def _walk(tokens):
    for t in tokens:
        yield t
        yield from _walk(t.children or [])


@pytest.fixture(scope="module")
def marking(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("inert")
    for name, (answer, sketch) in STUDENTS.items():
        _hand_in(root / "hand-in" / name, answer, sketch)
    out = root / "marking"
    assert main(["collect-written", str(root / "hand-in"), "-o", str(out), "--course", str(ROOT)]) == 0
    return out


@pytest.mark.parametrize("renderer", [0, 1], ids=["commonmark", "with formulas"])
def test_no_remote_url_and_no_student_heading_survives_rendering(marking, renderer):
    doc = (marking / f"{EX}-{QID}.md").read_text(encoding="utf-8")
    md = _renderers()[renderer]
    tokens = list(_walk(md.parse(doc)))
    targets = [t.attrGet(a) for t in tokens for a in ("src", "href", "srcset") if t.attrGet(a) is not None]
    assert targets and all(re.fullmatch(r"attachments/[\w.-]+\.png", str(x)) for x in targets), targets
    assert not [t.content for t in tokens if t.type in ("html_block", "html_inline")]
    html = md.render(doc)
    assert not re.search(r"(?i)<(img|a|iframe|svg|image|style)\b", html.replace('<img src="attachments/', "")), html
    assert not re.search(r"(?i)(https?|javascript):/?/?|www\.|mailto", " ".join(targets))
    # the text is shown, as written, but no renderer can link it: no URL is left whole
    assert "evil.example/ref.png" in doc and not re.search(r"(?i)https?://|www\.evil|\w@evil", doc)
    headings = [tokens[i + 1].content for i, t in enumerate(tokens) if t.type == "heading_open"]
    h3 = [tokens[i + 1].content for i, t in enumerate(tokens) if t.type == "heading_open" and t.tag == "h3"]
    assert sorted(h3) == sorted(f"`{s}`" for s in STUDENTS), h3
    assert len(headings) == 4 + len(STUDENTS), headings  # title, question, rubric, answers + one per student
    hr = [i for i, t in enumerate(tokens) if t.type == "hr"]
    assert len(hr) == len(STUDENTS), "a rule drawn by a student's text"


def test_students_whose_names_make_the_same_file_name_keep_their_own_sketches(marking):
    doc = (marking / f"{EX}-{QID}.md").read_text(encoding="utf-8")
    files = sorted((marking / "attachments").iterdir())
    assert len(files) == 3 and len({f.read_bytes() for f in files}) == 3, files
    sections = {}
    for part in doc.split("\n---\n")[1:]:
        heading = re.search(r"^### `(.+)`$", part, re.M)
        assert heading is not None, part
        sections[heading.group(1)] = re.findall(r"\]\((attachments/[^)]+)\)", part)
    for name, (_, sketch) in STUDENTS.items():
        shown = sections[name]
        assert len(shown) == (sketch is not None), (name, shown)
        if sketch is not None:
            assert (marking / shown[0]).read_bytes() == sketch, name


def test_formulas_still_render_and_plain_text_reads_the_same():
    md = MarkdownIt("commonmark").use(dollarmath_plugin)
    text = r"$\left[ x \right] < 2$ and a [b] # c"
    tokens = list(_walk(md.parse(_inert(text))))
    assert [t.content for t in tokens if t.type == "math_inline"] == [r"\left\lbrack{} x \right\rbrack{} \lt{} 2"]
    assert "a [b] # c" in md.render(_inert(text))
