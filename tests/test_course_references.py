"""What the docs, the hints and the instructor's notes say about the course agrees with the course itself
(issues 22 and 25): README's exercise table with the bank, the written questions the docs name with
``bank/written.py``, and every "lecture NN §M" with the lecture's numbered sections."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from puma_course.grading import load_bank
from puma_course.grading.bank_loader import EXERCISES
from puma_course.grading.written import written_questions
from tests.support import ROOT

LECTURES = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
#: "lecture 02 §5", "lecture 10 §2-3", "lecture 02 §3 and §5", "lecture 01 §5, §6"
_REF = re.compile(r"[Ll]ecture (\d{2})(?:'s)?,? §(\d+(?:-\d+)?(?:(?:, | and )§\d+(?:-\d+)?)*)(\.\d+)?")


@pytest.fixture(scope="module", autouse=True)
def _bank():
    load_bank(ROOT)


def _numbered_sections(lecture: Path) -> dict[int, str]:
    """A lecture's ``## N · Title`` sections: {N: title}."""
    found = {}
    for cell in json.loads(lecture.read_text(encoding="utf-8"))["cells"]:
        if cell["cell_type"] == "markdown":
            for m in re.finditer(r"^## (\d+) · (.+)$", "".join(cell["source"]), re.M):
                found[int(m[1])] = m[2]
    return found


SECTIONS = {p.name[:2]: _numbered_sections(p) for p in LECTURES}


def _text(path: Path) -> str:
    """A file's text as a reader sees it: a notebook's cells joined, Python's adjacent string literals joined."""
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".ipynb":
        return "\n".join("".join(c["source"]) for c in json.loads(text)["cells"])
    if path.suffix == ".py":
        text = re.sub(r"\"\s*\n\s*[rbfu]*\"", "", text)  # "... (lecture 02 "\n  "§5: ..." is one string
    return text


def _numbers(spec: str) -> list[int]:
    out = []
    for part in re.findall(r"\d+(?:-\d+)?", spec):
        first, _, last = part.partition("-")
        out += [int(first)] + ([int(last)] if last else [])
    return out


def _referring_files() -> list[Path]:
    """The bank's hints and mistakes, and the instructor's kit (tests/test_lectures.py checks the package, the
    solutions, the exercises, the lectures and README with a simpler pattern)."""
    return sorted([*(ROOT / "bank").glob("*.py"), *(ROOT / "instructor").rglob("*.md")])


def test_the_references_are_found_where_they_are_split_over_two_string_literals():
    hint = '    hint="Multiply them in the order the frames move (lecture 02 "\n        "§5: about the moving axes)'
    assert [m[1] for m in _REF.finditer(re.sub(r"\"\s*\n\s*[rbfu]*\"", "", hint))] == ["02"]
    assert _numbers("§2-4 and §7, §9") == [2, 4, 7, 9]
    assert _REF.search("the rotation (lecture 08 §3.5)")[3] == ".5"


def test_every_lecture_section_reference_names_a_section_of_that_lecture():
    wrong, seen = [], 0
    for path in _referring_files():
        text = _text(path)
        for m in _REF.finditer(text):
            seen += 1
            missing = [n for n in _numbers(m[2]) if n not in SECTIONS.get(m[1], {})]
            if m[1] not in SECTIONS or missing or m[3]:  # no lecture numbers its sections "§3.5"
                wrong.append(f"{path.relative_to(ROOT)}: {m[0]!r}")
        if path.parent.name == "notes":  # a bare "§M" in notes/NN.md is lecture NN's
            for m in re.finditer(r"§(\d+)", _REF.sub("", text)):
                seen += 1
                if int(m[1]) not in SECTIONS[path.stem]:
                    wrong.append(f"{path.relative_to(ROOT)}: {m[0]!r} (lecture {path.stem})")
    assert seen > 40, seen  # the pattern still finds the hints' references
    assert not wrong, wrong


def _exercise_table() -> dict[str, list[str]]:
    """The exercise table (docs/students.md): {exercise name: [after lecture, points, it ends with]}."""
    rows = {}
    for line in (ROOT / "docs" / "students.md").read_text(encoding="utf-8").splitlines():
        m = re.match(r"\| \[Exercise \d+: [^]]+\]\((?:\.\./)?exercises/(ex\d\d_\w+)\.ipynb\) \| (.+) \|$", line)
        if m:
            rows[m[1]] = [cell.strip() for cell in m[2].split(" | ")]
    return rows


def test_the_readmes_exercise_table_has_the_banks_points_and_last_question():
    rows = _exercise_table()
    assert sorted(rows) == sorted(EXERCISES)
    for name, (_after, points, ends_with) in rows.items():
        ex = EXERCISES[name]
        bonus = sum(q.points for q in ex.questions if q.bonus)
        assert points == f"{ex.max_score:g}" + (f" + {bonus:g} bonus" if bonus else ""), (name, points)
        last = ex.questions[-1]
        assert f"{last.qid} `{last.function}`" in ends_with, f"{name}: 'it ends with' does not name {last.qid}"
        # the last question that counts in the maximum too, when the last one is a bonus
        counted = [q for q in ex.questions if not q.bonus][-1]
        assert f"{counted.qid} `{counted.function}`" in ends_with, (name, counted.qid)


def _written_section() -> str:
    section = (ROOT / "docs" / "written.md").read_text(encoding="utf-8")  # the page is the section
    kit = (ROOT / "instructor" / "README.md").read_text(encoding="utf-8")
    return section + "\n" + kit


def test_the_written_questions_the_docs_name_are_the_banks():
    written = {(name[:4], w.qid) for name in EXERCISES for w in written_questions(name)}
    assert written
    text = _written_section()
    named = {(m[1], m[2]) for m in re.finditer(r"\b(ex\d\d) (q\d+)\b", text)}  # "ex02 q5"
    named |= {(m[1], m[2]) for m in re.finditer(r"\b(ex\d\d)_\w+?-(q\d+)\b", text)}  # ex02_dh_frames-q5-marks.csv
    assert not named - written, f"the docs name written questions the bank does not have: {sorted(named - written)}"
    assert written <= named, f"the docs leave out written questions: {sorted(written - named)}"
    for m in re.finditer(r"written:(q\d+)", text):  # a grades.csv column
        assert m[1] in {qid for _, qid in written}, m[0]
