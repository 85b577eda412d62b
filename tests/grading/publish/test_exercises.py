"""exercises/ is in sync with solutions/, leaks nothing, runs as handed out and earns zero;
solutions/ run and earn full marks."""

from __future__ import annotations

import re
import shutil

import nbformat
import pytest

from puma_course.grading import EXERCISES, grade, release, release_notebook
from puma_course.grading.publish.release import (
    BEGIN_HIDDEN,
    BEGIN_SOLUTION,
    END_HIDDEN,
    END_SOLUTION,
    NOTEBOOK_METADATA,
    essentials,
    notebook_text,
    points_summary,
    question_heading,
)
from puma_course.grading.written import written_summary
from tests.support import ROOT

SOLUTIONS = sorted((ROOT / "solutions").glob("*.ipynb"))
NAMES = [p.stem for p in SOLUTIONS]


def test_every_exercise_has_a_solution_notebook_and_back():
    assert sorted(NAMES) == sorted(EXERCISES)
    assert sorted(p.stem for p in (ROOT / "exercises").glob("*.ipynb")) == sorted(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_committed_exercise_equals_what_the_generator_makes(name):
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    expected = notebook_text(release_notebook(solution, EXERCISES[name]))
    committed = (ROOT / "exercises" / f"{name}.ipynb").read_text(encoding="utf-8")
    assert committed == expected, f"exercises/{name}.ipynb is stale: run `puma-course release`"


@pytest.mark.parametrize("name", NAMES)
def test_committed_exercise_has_what_the_release_check_compares(name):
    # the rule of `puma-course release --check` (cell order, types, sources, tags), which a save in
    # JupyterLab does not disturb; the test above also pins the bytes of the committed files
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    committed = nbformat.read(ROOT / "exercises" / f"{name}.ipynb", as_version=4)
    assert essentials(committed) == essentials(release_notebook(solution, EXERCISES[name]))


def test_release_check_passes_on_the_committed_course():
    assert release(ROOT / "solutions", ROOT / "exercises", check_only=True) == []


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
    assert exercise.metadata == NOTEBOOK_METADATA
    assert exercise.metadata == {
        "kernelspec": {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"},
        "language_info": {
            "codemirror_mode": {"name": "ipython", "version": 3},
            "file_extension": ".py",
            "mimetype": "text/x-python",
            "name": "python",
            "nbconvert_exporter": "python",
            "pygments_lexer": "ipython3",
        },
    }


@pytest.mark.parametrize("name", NAMES)
def test_answer_cells_are_tagged_as_the_question_bank_says(name):
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    exercise = nbformat.read(ROOT / "exercises" / f"{name}.ipynb", as_version=4)
    ex = EXERCISES[name]
    for q in ex.questions:
        cells = [c for c in solution.cells if f"question:{q.qid}" in c.metadata.get("tags", [])]
        assert len(cells) == 1, (name, q.qid)
        # the solution names the question only; its points live in the bank (Question.points)
        assert cells[0].metadata["tags"] == [f"question:{q.qid}"], (name, q.qid)
        assert re.search(rf"^def {q.function}\(", cells[0].source, re.M), (name, q.qid, q.function)
        checks = [c for c in solution.cells if c.source.strip() == f'check("{q.qid}", {q.function})']
        assert len(checks) == 1, (name, q.qid)
        # ... and the exercise carries them as written by the release: the tag and the heading above
        index = [i for i, c in enumerate(exercise.cells) if f"question:{q.qid}" in c.metadata.get("tags", [])]
        assert len(index) == 1, (name, q.qid)
        answer, heading = exercise.cells[index[0]], exercise.cells[index[0] - 1]
        assert answer.metadata["tags"] == [f"question:{q.qid}", f"points:{q.points:g}"], (name, q.qid)
        assert heading.metadata["tags"] == [f"heading:{q.qid}"], (name, q.qid)
        assert heading.source == question_heading(q)
        assert heading.source.startswith(f"**{q.qid}** · ") and f"{q.points:g} point" in heading.source
    headings = [c for c in exercise.cells if any(t.startswith("heading:") for t in c.metadata.get("tags", []))]
    assert len(headings) == len(ex.questions)
    summary = [c for c in exercise.cells if "points-summary" in c.metadata.get("tags", [])]
    assert len(summary) == 1 and exercise.cells[1] is summary[0]
    # the written questions (bank/written.py) are named after the auto-graded points, outside their total
    assert summary[0].source == points_summary(ex) + written_summary(ex)
    assert f"{ex.max_score:g} in all" in summary[0].source


@pytest.mark.parametrize("name", NAMES)
def test_solutions_write_no_points_by_hand(name):
    """Points appear in a solution nowhere: not as tags, not in headings or prose ("(3 points)", "3-point")."""
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    assert solution.metadata == NOTEBOOK_METADATA
    for cell in solution.cells:
        assert not [t for t in cell.metadata.get("tags", []) if t.startswith("points:")], cell.id
        if cell.cell_type == "markdown":
            assert not re.search(r"\d+(\.\d+)?[ -]points?\b", cell.source, re.I), (cell.id, cell.source[:80])


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


# ---------------------------------------------------------------------------- what the student's process may use
def _imports_of(source: str) -> list[tuple[str, str | None]]:
    """(module, name) of every import in a code cell (name None for ``import module``); magics skipped."""
    import ast

    lines = [line for line in source.splitlines() if not line.lstrip().startswith(("%", "!"))]
    out: list[tuple[str, str | None]] = []
    for node in ast.walk(ast.parse("\n".join(lines))):
        if isinstance(node, ast.Import):
            out += [(alias.name, None) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            out += [(node.module or "", alias.name) for alias in node.names]
    return out


SELF_CHECK = {("puma_course.grading", "check"), ("puma_course.grading", "use_exercise")}


@pytest.mark.parametrize("folder", ["solutions", "exercises"])
@pytest.mark.parametrize("name", NAMES)
def test_notebooks_import_only_numpy_the_self_check_and_the_exercises_allowed_names(folder, name):
    """In the grading sandbox only the allowed names exist: every cell, hidden tests included, must live with that."""
    allowed = {tuple(spec.split(":", 1)) for spec in EXERCISES[name].allowed}
    nb = nbformat.read(ROOT / folder / f"{name}.ipynb", as_version=4)
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        for module, imported in _imports_of(cell.source):
            if module == "numpy" or module.startswith("numpy."):
                continue
            assert (module, imported) in SELF_CHECK | allowed, (name, cell.id, module, imported)


@pytest.mark.parametrize("name", NAMES)
def test_every_exercise_says_what_the_student_will_be_able_to_do_and_names_its_allowed_tools(name):
    solution = nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4)
    opening = solution.cells[0].source
    assert opening.startswith("# Exercise ") and "After this exercise you can" in opening
    for spec in EXERCISES[name].allowed:
        module, attr = spec.split(":")
        assert attr in opening and f"`{module}`" in opening, spec


@pytest.mark.parametrize("name", NAMES)
def test_the_pictures_the_exercises_show_exist(name):
    """Pictures of mechanisms are drawn by figures/make_figures.py and committed next to the course's folders."""
    text = "\n".join(c.source for c in nbformat.read(ROOT / "exercises" / f"{name}.ipynb", as_version=4).cells)
    for target in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text):
        path = (ROOT / "exercises" / target).resolve()
        assert path.is_file() and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", target
        assert (ROOT / "solutions" / target).resolve() == path  # the same picture from the solution


@pytest.mark.slow
def test_the_figure_script_draws_every_picture(tmp_path):
    import subprocess
    import sys

    done = subprocess.run(
        [sys.executable, str(ROOT / "figures" / "make_figures.py"), str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    drawn = sorted(p.name for p in tmp_path.glob("*.png"))
    assert drawn == sorted(p.name for p in (ROOT / "figures").glob("*.png"))
    for path in tmp_path.glob("*.png"):
        assert path.stat().st_size > 20_000  # a drawing, not an empty canvas


def test_ex01_q2_says_opposite_vectors_are_not_graded_and_no_case_asks_for_them():
    """The text asked for a ValueError on opposite vectors that nothing checks: it now says no case asks for them
    (there the axis is not defined) and that raising one is good practice, not graded; and no case does."""
    import numpy as np

    q = EXERCISES["ex01_rotations"].question("q2")
    for seed in range(10):
        for u, v in q.cases(np.random.default_rng(seed)):
            u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
            assert u @ v / (np.linalg.norm(u) * np.linalg.norm(v)) > -1 + 1e-6, (seed, u, v)
    cells = nbformat.read(ROOT / "exercises" / "ex01_rotations.ipynb", as_version=4).cells
    text = " ".join(next(c.source for c in cells if c.source.startswith("## Question 2")).split())
    assert "No case asks for opposite vectors" in text and "it is not graded" in text, text
    assert "raise a `ValueError`" not in text, text
