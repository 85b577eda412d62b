"""The instructor's kit: slides of every lecture and the answer keys, built offline from the course.

    puma-course slides [--course DIR] [-o DIR] [--lecture NN ...]   (default: <course>/_slides)
    puma-course keys [--course DIR] [-o DIR]                         (default: <course>/_keys)

The slides are ``jupyter nbconvert --to slides`` of each lecture (reveal.js), cut for a 1280×720 projector by
:mod:`.layout` (a slide at every ``#``/``##`` heading, a sub-slide at ``###`` and wherever the content would run
beyond about one screen, the instructor notes as reveal's speaker notes); the template (``templates/puma_slides``)
takes reveal.js 4, RequireJS and MathJax 3 from the output folder, where they are copied from this package
(``static/``: reveal.js 4.6.1 and RequireJS 2.3.8 from npm, MIT) and from ``sphinx-mathjax-offline`` (MathJax
3.2.2), so the slides open from a USB stick with no network. Speaker view: press ``s``.

The answer keys are ``solutions/*.ipynb`` (the worked solutions, with their outputs, the release's solution
markers taken out, and each written question's prompt, rubric and worked answer from ``bank/written.py`` added)
rendered to an HTML page each and an index, for the instructor only: the output folder is outside the student
edition (which is written from an explicit list of folders) and the default ``_keys`` is git-ignored.

The syllabus, the schedule, the outcome map and the instructor notes are Markdown and JSON files
in the course's ``instructor/`` folder (:func:`load_outcome_map` reads and checks the map).
"""

from __future__ import annotations

import dataclasses
import html
import json
import re
import shutil
import time
from pathlib import Path
from typing import Any

from ..course import course_root

__all__ = [
    "SlidesReport",
    "build_slides",
    "build_keys",
    "key_notebook",
    "written_key",
    "load_outcome_map",
    "lecture_outcomes",
    "CDN_HOSTS",
]

_HERE = Path(__file__).parent
ASSETS = "assets"
#: the hosts a page must never load from: a CDN reference in a built file is a defect (offline courses)
CDN_HOSTS = (
    "cdn.jsdelivr.net",
    "unpkg.com",
    "cdnjs.cloudflare.com",
    "cdn.mathjax.org",
    "ajax.googleapis.com",
    "fonts.googleapis.com",
    "code.jquery.com",
    "cdn.plot.ly",
)


@dataclasses.dataclass(frozen=True)
class SlidesReport:
    """What a build wrote: the folder, the HTML files, the seconds it took and the bytes written."""

    out: Path
    files: tuple[Path, ...]
    seconds: float
    size: int


def _find(course: str | Path | None) -> Path:
    return course_root(course)


def _lectures(root: Path, numbers: tuple[str, ...] = ()) -> list[Path]:
    lectures = sorted((root / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    if numbers:
        wanted = {n.zfill(2) for n in numbers}
        unknown = wanted - {p.name[:2] for p in lectures}
        if unknown:
            raise ValueError(f"lecture: expected one of {[p.name[:2] for p in lectures]}, got {sorted(unknown)}")
        lectures = [p for p in lectures if p.name[:2] in wanted]
    if not lectures:
        raise ValueError(f"course: expected lectures in {root / 'notebooks'}, found none")
    return lectures


def _copy_assets(dest: Path) -> None:
    from ..site.offline_mathjax import copy_offline_mathjax

    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(_HERE / "static", dest)
    copy_offline_mathjax(dest / "mathjax")


def _size(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())


def build_slides(
    course: str | Path | None = None, out: str | Path | None = None, lectures: tuple[str, ...] = ()
) -> SlidesReport:
    """Write ``<out>/NN_name.slides.html`` for every lecture (or the ``lectures`` numbered) and their assets.

    ``out`` (default ``<course>/_slides``) receives the slides and ``assets/`` (reveal.js, RequireJS,
    MathJax); nothing in the pages refers to a URL outside that folder. Raises ``ValueError`` when
    the folder is not a course or a lecture number is unknown.
    """
    import nbformat
    from nbconvert import SlidesExporter
    from traitlets.config import Config

    from ..site.alt_text import with_animation_alt
    from .layout import slide_cells

    root = _find(course)
    out_dir = Path(out) if out is not None else root / "_slides"
    chosen = _lectures(root, lectures)
    start = time.perf_counter()
    out_dir.mkdir(parents=True, exist_ok=True)
    _copy_assets(out_dir / ASSETS)
    config = Config()
    config.TemplateExporter.extra_template_basedirs = [str(_HERE / "templates")]
    config.SlidesExporter.template_name = "puma_slides"
    config.SlidesExporter.reveal_url_prefix = f"{ASSETS}/reveal"
    config.SlidesExporter.reveal_theme = "white"
    config.SlidesExporter.reveal_scroll = True
    exporter = SlidesExporter(config=config)
    files = []
    for nb_path in chosen:
        nb = nbformat.read(nb_path, as_version=4)
        with_animation_alt(nb)
        notes_file = root / "instructor" / "notes" / f"{nb_path.name[:2]}.md"
        notes = notes_file.read_text(encoding="utf-8") if notes_file.is_file() else None
        nb = slide_cells(nb, notes)
        body, _ = exporter.from_notebook_node(nb, resources={"puma_assets": ASSETS})
        body = _with_alt_text(body, nb)
        target = out_dir / f"{nb_path.stem}.slides.html"
        target.write_text(body, encoding="utf-8")
        files.append(target)
    return SlidesReport(out_dir, tuple(files), time.perf_counter() - start, _size(out_dir))


def build_keys(course: str | Path | None = None, out: str | Path | None = None) -> SlidesReport:
    """Render the worked solutions (``solutions/*.ipynb``, outputs included) to HTML: one page each and an index.

    ``out`` defaults to ``<course>/_keys``. MathJax comes from ``assets/`` beside the pages, and no
    page refers to a CDN. Raises ``ValueError`` when the course has no ``solutions/``.
    """
    import nbformat
    from nbconvert import HTMLExporter
    from traitlets.config import Config

    root = _find(course)
    solutions = sorted((root / "solutions").glob("ex*.ipynb"))
    if not solutions:
        raise ValueError(f"course: expected worked solutions in {root / 'solutions'}, found none")
    out_dir = Path(out) if out is not None else root / "_keys"
    start = time.perf_counter()
    out_dir.mkdir(parents=True, exist_ok=True)
    _copy_assets(out_dir / ASSETS)
    config = Config()
    config.TemplateExporter.extra_template_basedirs = [str(_HERE / "templates")]
    config.HTMLExporter.template_name = "puma_keys"
    exporter = HTMLExporter(config=config)
    from ..grading import load_bank

    load_bank(root)  # the course's questions: the written ones' rubrics and worked answers go into the keys
    files, items = [], []
    for nb_path in solutions:
        nb = key_notebook(nbformat.read(nb_path, as_version=4), nb_path.stem)
        body, _ = exporter.from_notebook_node(nb, resources={"puma_assets": ASSETS})
        target = out_dir / f"{nb_path.stem}.html"
        target.write_text(body, encoding="utf-8")
        files.append(target)
        items.append(f'<li><a href="{target.name}">{html.escape(_title(nb) or nb_path.stem)}</a></li>')
    index = out_dir / "index.html"
    index.write_text(
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>Answer keys (instructor only)'
        "</title></head><body><h1>puma-course: worked answer keys</h1><p><strong>Instructor only.</strong> "
        "These pages hold the answers; do not publish them where students can read them.</p><ul>"
        + "".join(items)
        + "</ul></body></html>\n",
        encoding="utf-8",
    )
    files.append(index)
    return SlidesReport(out_dir, tuple(files), time.perf_counter() - start, _size(out_dir))


#: the release's markers around a solution or hidden tests (a line of its own); the keys leave them out
_MARKER = re.compile(r"^[ \t]*#+[ \t]*(?:BEGIN|END)[ \t]+(?:SOLUTION|HIDDEN TESTS)[ \t]*\n?", re.M)


def _cell(text: str) -> str:
    return " ".join(text.replace("|", "\\|").split())


def written_key(exercise: str) -> str:
    """The Markdown of ``exercise``'s written questions for the key: each one's prompt, rubric with points
    (the lines a marker scores) and worked answer ("" when it has none). Needs the course's bank loaded."""
    from ..grading.written import written_questions

    out = []
    for w in written_questions(exercise):
        rubric = "\n".join(f"| {c.name} | {c.points:g} | {_cell(c.text)} |" for c in w.spec.criteria)
        out.append(
            f"### {w.qid} · written · {w.points:g} points · {w.spec.title}\n\n"
            f"**Prompt (what the students read)**\n\n{w.spec.prompt.strip()}\n\n"
            f"**Rubric**\n\n| criterion | points | what earns them |\n|---|---:|---|\n{rubric}\n"
            f"| **total** | **{w.points:g}** | |\n\n"
            f"**A full answer**\n\n{w.spec.full_answer.strip()}\n\n"
            f"**Worked answer**\n\n{w.spec.worked.strip()}"
        )
    if not out:
        return ""
    return "## Written questions (marked by hand): rubrics and worked answers\n\n" + "\n\n".join(out)


def key_notebook(nb: Any, exercise: str) -> Any:
    """The worked solution ``nb`` as the key shows it: the solution and hidden-test markers taken out of the
    code and the exercise's written questions (:func:`written_key`) added at the end. Changes ``nb``."""
    import nbformat

    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.source = _MARKER.sub("", cell.source)
    written = written_key(exercise)
    if written:
        nb.cells.append(nbformat.v4.new_markdown_cell(written))
    return nb


_NO_ALT = 'alt="No description has been provided for this image"'


def _with_alt_text(body: str, nb: Any) -> str:
    """nbconvert's page with each figure's ``alt`` taken from its cell (``mystnb.image.alt``, as on the website).

    nbconvert writes a placeholder ``alt`` on every image, in the order of the notebook's image outputs;
    they are replaced one by one when the counts agree (otherwise the page is left as nbconvert wrote it).
    """
    alts = []
    for cell in nb.cells:
        alt = cell.get("metadata", {}).get("mystnb", {}).get("image", {}).get("alt")
        for output in cell.get("outputs", []):
            if any(k.startswith("image/") for k in output.get("data", {})):
                alts.append(alt)
    parts = body.split(_NO_ALT)
    if len(parts) - 1 != len(alts):
        return body
    out = [parts[0]]
    for alt, rest in zip(alts, parts[1:], strict=True):
        out.append(f'alt="{html.escape(alt, quote=True)}"' if alt else _NO_ALT)
        out.append(rest)
    return "".join(out)


def _title(nb: Any) -> str | None:
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return None


_ITEM = re.compile(r"\n(?:\d+\.|\*|-) ")


def lecture_outcomes(notebook: str | Path) -> list[str]:
    """The items under a lecture's "What you will be able to do" heading, each as one line of text."""
    nb = json.loads(Path(notebook).read_text(encoding="utf-8"))
    for cell in nb["cells"]:
        source = "".join(cell["source"])
        if cell["cell_type"] == "markdown" and "## What you will be able to do" in source:
            body = source.split("## What you will be able to do", 1)[1]
            body = re.split(r"\n\s*\n(?![ \t]|\d+\.|\*|-)", body.strip() + "\n\n", maxsplit=1)[0]
            return [" ".join(item.split()) for item in _ITEM.split("\n" + body.strip()) if item.strip()]
    raise ValueError(f"notebook: expected a '## What you will be able to do' section in {notebook}, found none")


def load_outcome_map(course: str | Path | None = None) -> dict[str, list[dict[str, Any]]]:
    """``instructor/outcomes.json``: for each lecture file, its outcomes and the questions that assess them.

    Each entry is ``{"outcome": <the start of the outcome's text>, "assessed_by": ["exNN_name.qK", ...]}``
    or ``{"outcome": ..., "not_assessed": <why>}``. Raises ``ValueError`` naming the first entry that
    is malformed; :mod:`tests.instructor.test_instructor` checks it against the lectures and the question bank.
    """
    root = _find(course)
    path = root / "instructor" / "outcomes.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    if not isinstance(data, dict):
        raise ValueError(f"outcomes.json: expected an object keyed by lecture file, got {type(data).__name__}")
    for lecture, entries in data.items():
        for entry in entries:
            if not isinstance(entry, dict) or not isinstance(entry.get("outcome"), str):
                raise ValueError(f"outcomes.json: expected {{'outcome': str, ...}} under {lecture}, got {entry!r}")
            if bool(entry.get("assessed_by")) == bool(entry.get("not_assessed")):
                raise ValueError(
                    f"outcomes.json: expected exactly one of 'assessed_by' and 'not_assessed' for {entry['outcome']!r}"
                )
    return data


def _sections(notebook: Path) -> list[str]:
    """The titles of a lecture's ``##`` sections, without their number (``"3 · The table"`` -> ``"The table"``)."""
    nb = json.loads(notebook.read_text(encoding="utf-8"))
    titles = []
    for cell in nb["cells"]:
        if cell["cell_type"] == "markdown":
            for line in "".join(cell["source"]).splitlines():
                if line.startswith("## "):
                    titles.append(re.sub(r"^\d+\s*·\s*", "", line[3:].strip()))
    return titles


def load_schedule(course: str | Path | None = None) -> dict[str, Any]:
    """``instructor/schedule.json``, checked against the lectures: every numbered section of every lecture
    is in exactly one meeting, every item names a section that exists, and no meeting runs over its minutes.

    Items are ``[lecture number or "", section title (its start), minutes]``; ``""`` is an activity
    (recap, exercise time). Raises ``ValueError`` naming what is wrong.
    """
    root = _find(course)
    data = json.loads((root / "instructor" / "schedule.json").read_text(encoding="utf-8"))
    limit = data["meeting_minutes"]
    lectures = {p.name[:2]: p for p in _lectures(root)}
    sections = {n: _sections(p) for n, p in lectures.items()}
    seen: dict[tuple[str, str], int] = {}
    for k, meeting in enumerate(data["meetings"], 1):
        total = sum(item[2] for item in meeting["items"])
        if total > limit:
            raise ValueError(f"schedule: expected at most {limit} minutes in meeting {k}, got {total}")
        for number, start, _minutes in meeting["items"]:
            if not number:
                continue
            if number not in sections:
                raise ValueError(f"schedule: meeting {k} names lecture {number!r}, which the course does not have")
            hits = [t for t in sections[number] if t.startswith(start)]
            if len(hits) != 1:
                raise ValueError(f"schedule: meeting {k}: expected one section of lecture {number} starting {start!r}, "
                                 f"found {hits}")  # fmt: skip
            seen[(number, hits[0])] = k
    skip = tuple(data.get("not_scheduled", ()))
    missing = [f"{n} {t}" for n, ts in sections.items() for t in ts if (n, t) not in seen and not t.startswith(skip)]
    if missing:
        raise ValueError(f"schedule: expected every section in a meeting, these are in none: {missing}")
    return data


def schedule_markdown(course: str | Path | None = None) -> str:
    """The schedule as the Markdown table committed as ``instructor/schedule.md`` (regenerate it with this)."""
    data = load_schedule(course)
    out = [
        "# Schedule: 15 meetings of 75 minutes",
        "",
        "Generated from `schedule.json` by `puma_course.instructor.schedule_markdown()`; edit the JSON, then run",
        "`python -c \"from puma_course.instructor import schedule_markdown as s; open('instructor/schedule.md', 'w')"
        '.write(s())"`.',
        "Sections are the lectures' `##` headings; appendices and Errata sections are reading.",
        "",
    ]
    for k, meeting in enumerate(data["meetings"], 1):
        out += [f"## Meeting {k}: {meeting['topic']}", "", f"Exercise: {meeting['exercise']}", "",
                "| lecture | section or activity | minutes |", "|---|---|---:|"]  # fmt: skip
        for number, title, minutes in meeting["items"]:
            out.append(f"| {number or '—'} | {title} | {minutes} |")
        out.append(f"| | **total** | **{sum(i[2] for i in meeting['items'])}** |")
        out.append("")
    return "\n".join(out)
