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
from puma_course.grading.model import EXERCISES
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
        ]
        if images:
            figures += 1
            alt = cell["metadata"].get("mystnb", {}).get("image", {}).get("alt", "")
            assert len(alt) > 30, f"{lecture.name}: a figure without alt text: {''.join(cell['source'])[:80]!r}"
    assert figures >= 1


def test_the_kit_stays_out_of_the_student_edition(tmp_path):
    from puma_course.grading.edition import write_edition

    write_edition(tmp_path / "edition", ROOT)  # what `puma-course edition DIR` hands a student
    assert not (tmp_path / "edition" / "instructor").exists()
    assert not list((tmp_path / "edition").rglob("outcomes.json"))
    assert not list((tmp_path / "edition").rglob("solutions"))
