"""The instructor's kit (issue 25): the outcome map, the schedule, slides and answer keys built offline,
and the lectures' figures' text alternatives."""

from __future__ import annotations

import contextlib
import io
import json
import re
from pathlib import Path

import pytest

from puma_course.cli import main
from puma_course.grading.bank_loader import EXERCISES
from puma_course.instructor import (
    CDN_HOSTS,
    lecture_outcomes,
    load_outcome_map,
    load_schedule,
    schedule_markdown,
)
from tests.support import ROOT

LECTURES = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
#: a reference the browser would fetch from another host: src=, href= or an import/require of http(s)://
_REMOTE = re.compile(
    r"""(?:src|href)\s*=\s*["']?(?:https?:)?//|@import\s+url\(["']?https?:|require\(\s*\[?["']https?:"""
)


def test_every_outcome_of_every_lecture_maps_to_a_question_or_says_not_assessed():
    mapping = load_outcome_map(ROOT)
    assert sorted(mapping) == sorted(p.name for p in LECTURES)
    for lecture in LECTURES:
        outcomes = lecture_outcomes(lecture)
        entries = mapping[lecture.name]
        assert len(outcomes) >= 3, (lecture.name, outcomes)
        for outcome in outcomes:
            hits = [e for e in entries if outcome.startswith(e["outcome"])]
            assert len(hits) == 1, f"{lecture.name}: outcome {outcome[:70]!r} is in the map {len(hits)} times"
        for entry in entries:
            assert any(o.startswith(entry["outcome"]) for o in outcomes), f"{lecture.name}: no outcome {entry}"


def test_every_question_the_map_names_exists_in_the_bank():
    from puma_course.grading import load_bank
    from puma_course.grading.written import written_questions

    load_bank(ROOT)  # the course's questions (its bank/, beside solutions/), auto-graded and written
    known = {f"{name}.{q.qid}" for name, ex in EXERCISES.items() for q in ex.questions}
    known |= {f"{name}.{w.qid}" for name in EXERCISES for w in written_questions(name)}
    named = {qid for entries in load_outcome_map(ROOT).values() for e in entries for qid in e.get("assessed_by", ())}
    assert named, "the map names no question"
    assert not named - known, sorted(named - known)


#: Questions no outcome assesses, each with the reason (none: every question assesses a lecture's outcome).
UNMAPPED: dict[str, str] = {}


def test_every_question_auto_graded_or_written_assesses_an_outcome():
    from puma_course.grading import load_bank
    from puma_course.grading.written import written_questions

    load_bank(ROOT)
    every = {f"{name}.{q.qid}" for name, ex in EXERCISES.items() for q in ex.questions}
    written = {f"{name}.{w.qid}" for name in EXERCISES for w in written_questions(name)}
    assert written, "the bank declares no written question"
    named = {qid for entries in load_outcome_map(ROOT).values() for e in entries for qid in e.get("assessed_by", ())}
    assert not set(UNMAPPED) & named, sorted(set(UNMAPPED) & named)
    assert not (every | written) - named - set(UNMAPPED), sorted((every | written) - named - set(UNMAPPED))


def test_a_malformed_map_entry_is_refused(tmp_path):
    (tmp_path / "notebooks").mkdir()
    (tmp_path / "instructor").mkdir()
    (tmp_path / "instructor" / "outcomes.json").write_text(json.dumps({"01_x.ipynb": [{"outcome": "**Read**"}]}))
    with pytest.raises(ValueError, match="exactly one of 'assessed_by' and 'not_assessed'"):
        load_outcome_map(tmp_path)


def test_the_schedule_covers_every_section_in_15_meetings_of_75_minutes():
    data = load_schedule(ROOT)  # raises when a section is missing, unknown or a meeting runs over
    assert len(data["meetings"]) == 15
    for meeting in data["meetings"]:
        assert 60 <= sum(item[2] for item in meeting["items"]) <= 75


def test_the_schedule_teaches_the_sections_in_course_order():
    from puma_course.instructor import _sections

    order = {(p.name[:2], title): k for k, (p, title) in
             enumerate((p, t) for p in LECTURES for t in _sections(p))}  # fmt: skip
    taught = []
    for m, meeting in enumerate(load_schedule(ROOT)["meetings"], 1):
        for number, start, _minutes in meeting["items"]:
            if number:
                (title,) = [t for (n, t) in order if n == number and t.startswith(start)]
                taught.append((order[(number, title)], f"meeting {m}: {number} {title}"))
    late = [(a[1], b[1]) for a, b in zip(taught, taught[1:], strict=False) if b[0] < a[0]]
    assert not late, f"taught before a section it follows: {late}"


def test_the_committed_schedule_page_is_generated_from_the_json():
    assert (ROOT / "instructor" / "schedule.md").read_text(encoding="utf-8") == schedule_markdown(ROOT)


def test_the_kit_has_a_syllabus_and_notes_for_every_lecture():
    assert "Schedule" in (ROOT / "instructor" / "syllabus.md").read_text(encoding="utf-8")
    for lecture in LECTURES:
        notes = (ROOT / "instructor" / "notes" / f"{lecture.name[:2]}.md").read_text(encoding="utf-8")
        predicts = sum("".join(c["source"]).count("**Predict.**") for c in json.loads(lecture.read_text())["cells"])
        for heading in ("Where students stumble", "On the board", "Predict answers"):
            assert f"## {heading}" in notes, (lecture.name, heading)
        answers = re.split(r"\n## ", notes.split("## Predict answers", 1)[1])[0]
        numbers = [int(n) for n in re.findall(r"^(\d+)\. ", answers, re.M)]
        assert numbers == list(range(1, predicts + 1)), f"{lecture.name}: {predicts} Predict prompts, answers {numbers}"


def _offline(folder: Path) -> None:
    for page in folder.rglob("*"):
        if page.suffix not in (".html", ".css", ".js") or not page.is_file():
            continue
        text = page.read_text(encoding="utf-8", errors="replace")
        if page.suffix == ".html":
            assert not _REMOTE.search(text), f"{page.name}: {_REMOTE.search(text)}"
        for host in CDN_HOSTS:
            assert host not in text, f"{page.relative_to(folder)} names {host}"


def test_one_lectures_slides_build_offline_with_reveal_and_mathjax_beside_them(tmp_path):
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["slides", "--course", str(ROOT), "-o", str(tmp_path), "--lecture", "03"]) == 0
    assert re.search(r"built 1 slide shows in [\d.]+ s, [\d.]+ MB", printed.getvalue()), printed.getvalue()
    page = tmp_path / "03_puma560_forward_kinematics.slides.html"
    text = page.read_text(encoding="utf-8")
    assert text.count("<section") > 10  # one per slide and sub-slide: the notebook's metadata was used
    for local in ("assets/reveal/dist/reveal.js", "assets/reveal/dist/reveal.css", "assets/require.js",
                  "assets/mathjax/tex-svg-full.js", "assets/reveal/plugin/notes/notes.js"):  # fmt: skip
        assert local in text, local
        assert (tmp_path / local).is_file(), local
    _offline(tmp_path)


def test_an_unknown_lecture_number_is_refused(tmp_path, capsys):
    assert main(["slides", "--course", str(ROOT), "-o", str(tmp_path), "--lecture", "99"]) == 2
    assert "lecture: expected one of" in capsys.readouterr().err


def test_the_answer_keys_render_offline_with_an_index(tmp_path):
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["keys", "--course", str(ROOT), "-o", str(tmp_path)]) == 0
    index = (tmp_path / "index.html").read_text(encoding="utf-8")
    for nb in sorted((ROOT / "solutions").glob("ex*.ipynb")):
        assert f'href="{nb.stem}.html"' in index
        assert (tmp_path / f"{nb.stem}.html").stat().st_size > 10_000
    assert "Instructor only" in index
    _offline(tmp_path)


@pytest.mark.parametrize("lecture", LECTURES, ids=lambda p: p.name[:2])
def test_every_figure_of_every_lecture_has_alt_text_and_every_cell_a_slide_type(lecture):
    nb = json.loads(lecture.read_text(encoding="utf-8"))
    figures = 0
    for cell in nb["cells"]:
        assert cell["metadata"].get("slideshow", {}).get("slide_type") in ("slide", "subslide", "fragment", "-", "skip",
                                                                           "notes"), cell["source"][:1]  # fmt: skip
        images = [
            o
            for o in cell.get("outputs", [])
            if any(k.startswith("image/") for k in o.get("data", {}))
            or "_anim_img" in "".join(o.get("data", {}).get("text/html", ""))  # an animation's frames
            or "".join(o.get("data", {}).get("text/html", "")).startswith("<img")  # a figure with its alt
        ]
        if images:
            figures += 1
            alt = cell["metadata"].get("mystnb", {}).get("image", {}).get("alt", "")
            assert len(alt) > 30, f"{lecture.name}: a figure without alt text: {''.join(cell['source'])[:80]!r}"
    assert figures >= 1


def test_the_kit_stays_out_of_the_student_edition(tmp_path):
    from puma_course.grading.publish.edition import write_edition

    write_edition(tmp_path / "edition", ROOT)  # what `puma-course edition DIR` hands a student
    assert not (tmp_path / "edition" / "instructor").exists()
    assert not list((tmp_path / "edition").rglob("outcomes.json"))
    assert not list((tmp_path / "edition").rglob("solutions"))


# --- slides cut for a projector, speaker notes, keys with the written questions (issue 25, review) ---

_H2 = re.compile(r"<h2[ >]")


@pytest.fixture(scope="module")
def lecture_09_slides(tmp_path_factory):
    out = tmp_path_factory.mktemp("slides09")
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["slides", "--course", str(ROOT), "-o", str(out), "--lecture", "09"]) == 0
    return out, (out / "09_puma560_inverse_kinematics.slides.html").read_text(encoding="utf-8")


def _headings(notebook: Path, level: str) -> list[str]:
    from puma_course.instructor.layout import _blocks

    nb = json.loads(notebook.read_text(encoding="utf-8"))
    return [line for c in nb["cells"] if c["cell_type"] == "markdown"
            for line, free in _blocks("".join(c["source"])) if free and line.startswith(level + " ")]  # fmt: skip


def test_every_section_heading_of_lecture_09_starts_a_slide(lecture_09_slides):
    _, text = lecture_09_slides
    text = re.sub(r'<aside class="notes">.*?</aside>', "", text, flags=re.S)  # the speaker notes have headings too
    lecture = next(p for p in LECTURES if p.name.startswith("09"))
    sections = _headings(lecture, "##")
    assert len(sections) >= 14  # §1-§14 and the lecture's other ## sections
    assert len(_H2.findall(text)) == len(sections)
    # reveal's slides are <section>s; each ## heading is in the first cell of one, alone
    chunks = text.split("<section")
    for chunk in chunks:
        if _H2.search(chunk):
            assert len(_H2.findall(chunk)) == 1
            cells = [m.start() for m in re.finditer(r'<div class="jp-Cell ', chunk)]
            assert cells and _H2.search(chunk).start() < (cells[1] if len(cells) > 1 else len(chunk)), chunk[:300]
    assert text.count("<section") > 4 * len(sections)  # the long sections are flowed onto sub-slides


def test_the_slides_carry_the_lecture_notes_as_speaker_notes_with_the_plugin_local(lecture_09_slides):
    out, text = lecture_09_slides
    notes = re.findall(r'<aside class="notes">(.*?)</aside>', text, flags=re.S)
    assert notes, "no speaker notes"
    assert "Where students stumble" in notes[0] and "On the board" in notes[0]  # notes/09.md on the title slide
    assert text.index('<aside class="notes">') < text.index("What you will be able to do")
    assert '"assets/reveal/plugin/notes/notes.js"' in text and "plugins: [RevealNotes]" in text
    assert (out / "assets" / "reveal" / "plugin" / "notes" / "notes.js").is_file()


def test_markdown_is_split_at_headings_but_not_inside_code_or_display_math():
    from puma_course.instructor.layout import split_markdown

    source = "Answer of §1.\n\n## 2 · Next\n\nText\n```python\n# a comment\n```\n$$\n# not a heading\n$$\n### 2.1 · Sub"
    assert split_markdown(source) == [
        "Answer of §1.",
        "## 2 · Next\n\nText\n```python\n# a comment\n```\n$$\n# not a heading\n$$",
        "### 2.1 · Sub",
    ]
    assert split_markdown("One.\n\nTwo\nstill two.\n\n\n$$\na\n\nb\n$$", at_paragraphs=True) == [
        "One.",
        "Two\nstill two.",
        "$$\na\n\nb\n$$",
    ]


def test_slide_cells_start_slides_at_headings_and_give_a_figure_its_own_sub_slide():
    import nbformat

    from puma_course.instructor.layout import BUDGET, slide_cells

    figure = nbformat.v4.new_code_cell("plot()")
    figure.outputs = [nbformat.v4.new_output("display_data", data={"image/png": "iVBOR", "text/plain": "<Figure>"})]
    skipped = nbformat.v4.new_markdown_cell("## hidden")
    skipped.metadata["slideshow"] = {"slide_type": "skip"}
    long_text = "\n\n".join(f"Paragraph {k}: " + "words " * 60 for k in range(12))
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_markdown_cell("# Title\n\nIntro.\n\n## 1 · First\n\nText."),
        nbformat.v4.new_code_cell("x = 1"),
        figure,
        nbformat.v4.new_markdown_cell("After the figure.\n\n### 1.1 · Detail\n\nMore."),
        skipped,
        nbformat.v4.new_markdown_cell(long_text),
    ])  # fmt: skip
    cut = slide_cells(nb, "## Predict answers\n\n1. Yes.")
    kinds = [(c.source.split("\n")[0][:14], c.metadata["slideshow"]["slide_type"]) for c in cut.cells]
    assert kinds[:7] == [
        ("# Title", "slide"),
        ("**Predict answ", "notes"),  # the notes file after the title slide's cell, its headings bold lines
        ("## 1 · First", "slide"),
        ("x = 1", "-"),
        ("plot()", "subslide"),  # a figure on a sub-slide of its own
        ("After the figu", "subslide"),  # and what follows on the next
        ("### 1.1 · Deta", "subslide"),
    ]
    assert ("## hidden", "skip") in kinds
    pieces = [c for c in cut.cells if c.source.startswith("Paragraph")]
    assert len(pieces) == 12 and sum(c.metadata["slideshow"]["slide_type"] == "subslide" for c in pieces) >= 3
    assert len(nb.cells) == 6 and nb.cells[0].source.startswith("# Title\n\nIntro.\n\n## 1")  # the input is unchanged
    assert BUDGET < 720


def test_predict_answers_are_read_from_the_notes():
    from puma_course.instructor.layout import predict_answers

    notes = (ROOT / "instructor" / "notes" / "03.md").read_text(encoding="utf-8")
    answers = predict_answers(notes)
    assert len(answers) == len(re.findall(r"^\d+\. ", notes.split("## Predict answers")[1], flags=re.M))
    assert answers[2].startswith("Joints 2 and 3 counted the other way") and "nothing else changes" in answers[2]


def test_the_keys_hold_the_written_questions_and_no_solution_markers(tmp_path):
    import importlib.util

    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["keys", "--course", str(ROOT), "-o", str(tmp_path)]) == 0
    for page in tmp_path.glob("ex*.html"):
        text = page.read_text(encoding="utf-8")
        assert "BEGIN SOLUTION" not in text and "END SOLUTION" not in text, page.name
        assert "HIDDEN TESTS" not in text, page.name
    # the bank's own declaration, read here independently of the keys' code
    spec = importlib.util.spec_from_file_location("_written_bank", ROOT / "bank" / "written.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.WRITTEN
    for exercise, items in module.WRITTEN.items():
        text = (tmp_path / f"{exercise}.html").read_text(encoding="utf-8")
        assert text.count("Worked answer") == len(items), exercise
        for w in items:
            assert w.title.split("$")[0].strip()[:30] in text, (exercise, w.title)
            assert f"{w.points:g} points" in text
            for c in w.criteria:
                row = rf"<td>{re.escape(c.name)}</td>\s*<td[^>]*>{c.points:g}</td>"
                assert re.search(row, text), (exercise, c.name)
    _offline(tmp_path)


@pytest.mark.parametrize("command", ["slides", "keys"])
def test_without_the_instructor_extra_the_kit_says_which_to_install(command, tmp_path, monkeypatch, capsys):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "sphinx-mathjax-offline" else real(name, *a)
    )
    assert main([command, "--course", str(ROOT), "-o", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "'instructor' extra" in err and "pip install" in err and "Traceback" not in err
    assert not list(tmp_path.iterdir())  # nothing built
