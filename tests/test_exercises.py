"""exercises/ is in sync with solutions/, leaks nothing, runs as handed out and earns zero;
solutions/ run and earn full marks."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import nbformat
import pytest

from puma_course.grading import (
    BEGIN_HIDDEN,
    BEGIN_SOLUTION,
    END_HIDDEN,
    END_SOLUTION,
    EXERCISES,
    grade,
    notebook_text,
    release_notebook,
)

ROOT = Path(__file__).resolve().parent.parent
SOLUTIONS = sorted((ROOT / "solutions").glob("*.ipynb"))
NAMES = [p.stem for p in SOLUTIONS]


def test_every_exercise_has_a_solution_notebook_and_back():
    assert sorted(NAMES) == sorted(EXERCISES)
    assert sorted(p.stem for p in (ROOT / "exercises").glob("*.ipynb")) == sorted(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_committed_exercise_equals_what_the_generator_makes(name):
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    expected = notebook_text(release_notebook(solution))
    committed = (ROOT / "exercises" / f"{name}.ipynb").read_text(encoding="utf-8")
    assert committed == expected, f"exercises/{name}.ipynb is stale: run `puma-course release`"


def _blocks(source: str, begin: str, end: str, inside_wanted: bool = True) -> list[str]:
    """Stripped lines inside (or, with inside_wanted=False, outside) the begin/end blocks."""
    out, inside = [], False
    for line in source.splitlines():
        if line.strip() == begin:
            inside = True
        elif line.strip() == end:
            inside = False
        elif inside == inside_wanted and len(line.strip()) > 12:
            out.append(line.strip())
    return out


@pytest.mark.parametrize("name", NAMES)
def test_no_solution_or_hidden_test_leaks_into_the_exercise(name):
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    text = (ROOT / "exercises" / f"{name}.ipynb").read_text(encoding="utf-8")
    exercise = nbformat.reads(text, as_version=4)
    student_code = "\n".join(c.source for c in exercise.cells)
    secret, given = [], set()
    for cell in solution.cells:
        secret += _blocks(cell.source, BEGIN_SOLUTION, END_SOLUTION)
        secret += _blocks(cell.source, BEGIN_HIDDEN, END_HIDDEN)
        # lines the solution also shows outside any block (a helper given to the student) are not secrets
        given |= set(_blocks(cell.source, BEGIN_SOLUTION, END_SOLUTION, inside_wanted=False))
    assert secret, "a solution notebook without solution blocks?"
    public_lines = {line.strip() for c in exercise.cells for line in c.source.splitlines()}
    leaked = [line for line in secret if line in public_lines and line not in given]
    assert not leaked, leaked
    for marker in ("BEGIN SOLUTION", "END SOLUTION", "HIDDEN TESTS"):
        assert marker not in student_code
    for cell in exercise.cells:
        assert cell.get("outputs", []) == [] and cell.get("execution_count") is None
        assert set(cell.metadata) <= {"tags"}
    assert exercise.metadata == {
        "kernelspec": {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"},
        "language_info": {"name": "python"},
    }


@pytest.mark.parametrize("name", NAMES)
def test_answer_cells_are_tagged_as_the_question_bank_says(name):
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    ex = EXERCISES[name]
    for q in ex.questions:
        cells = [c for c in solution.cells if f"question:{q.qid}" in c.metadata.get("tags", [])]
        assert len(cells) == 1, (name, q.qid)
        assert f"points:{q.points:g}" in cells[0].metadata["tags"], (name, q.qid)
        assert re.search(rf"^def {q.function}\(", cells[0].source, re.M), (name, q.qid, q.function)
        checks = [c for c in solution.cells if c.source.strip() == f'check("{q.qid}", {q.function})']
        assert len(checks) == 1, (name, q.qid)


@pytest.fixture(scope="module")
def class_results(tmp_path_factory):
    """Grade a class of two: 'teacher' hands in the solutions, 'fresh' the exercises untouched."""
    root = tmp_path_factory.mktemp("release")
    for student, folder in (("teacher", "solutions"), ("fresh", "exercises")):
        (root / "subs" / student).mkdir(parents=True)
        for path in (ROOT / folder).glob("*.ipynb"):
            shutil.copy(path, root / "subs" / student / path.name)
    results = grade(root / "subs", root / "grades.csv", jobs=2, timeout_cell=20, timeout_total=60, seed=2024)
    return {(r.student, r.exercise): r for r in results}


@pytest.mark.parametrize("name", NAMES)
def test_solutions_execute_and_earn_full_marks(class_results, name):
    r = class_results[("teacher", name)]
    assert r.status == "ok", r.notes
    assert r.score == sum(q.points for q in EXERCISES[name].questions), r.question_notes


@pytest.mark.parametrize("name", NAMES)
def test_exercises_as_handed_out_run_without_error_and_earn_zero(class_results, name):
    r = class_results[("fresh", name)]
    assert r.status == "ok", r.notes  # no cell raised
    assert r.score == 0
    assert all("not attempted yet" in " ".join(notes) for notes in r.question_notes.values())


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_exercises_run_in_a_jupyter_kernel_as_handed_out(name):
    from nbclient import NotebookClient

    nb = nbformat.read(ROOT / "exercises" / f"{name}.ipynb", as_version=4)
    NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    texts = "".join(o.get("text", "") for o in outputs)
    assert texts.count("not attempted yet") >= len(EXERCISES[name].questions)
    assert "passed" not in texts and "FAILED" not in texts
