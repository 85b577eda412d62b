"""Release: generate the student's ``exercises/NAME.ipynb`` from ``solutions/NAME.ipynb``, or check it.

**What the generator writes.** Cell by cell, in order:

* code between ``### BEGIN SOLUTION`` and ``### END SOLUTION`` becomes a stub that raises
  ``NotImplementedError`` only when called (a code solution block must be indented, inside a
  function body, so the handed-out notebook runs to the end); in Markdown it becomes
  "*Write your answer here.*";
* ``### BEGIN HIDDEN TESTS`` ... ``### END HIDDEN TESTS`` is removed, and a cell left empty is dropped;
* outputs and execution counts are cleared; cells keep their id and their tags, nothing else;
* the notebook gets the metadata JupyterLab 4 writes (:data:`NOTEBOOK_METADATA`), without
  ``language_info.version``, which depends on the student's Python.

**Points are stored once**, in :attr:`Question.points <puma_course.grading.spec.Question.points>`.
A solution tags each answer cell ``question:qN`` and nothing more; the generator adds the
``points:N`` tag to that cell, a heading cell just above it (``**q2** · 3 points · write
`rotation_between` below``, tagged ``heading:q2``) and, after the notebook's first cell, a
summary of every question's points (tagged ``points-summary``). A solution that still carries a
``points:N`` tag, or a generated cell, is refused (ValueError): an edited tag would otherwise
look as if it changed the grading.

**Written questions** (:mod:`.written`, declared in the course's ``bank/written.py``): before the
notebook's closing Markdown cell the generator puts, per written question, a prompt cell (tagged
``written-prompt:qN``: the points, the question) and a Markdown answer cell tagged ``written:qN``, and the
points summary names them. Their rubric and worked answer stay in the bank.

**What ``release(check_only=True)`` compares** (``puma-course release --check``, and the test
suite) is what a student works with: the order of the cells, their types, their sources and
their tags (:func:`essentials`). It ignores what Jupyter rewrites when a notebook is opened,
run and saved: notebook metadata (``language_info``, ``kernelspec`` details, widget state),
cell metadata other than tags, cell ids, execution counts, outputs and the file's JSON layout.
So an exercise opened in JupyterLab and saved still passes, while an edited source, a removed
tag or a moved cell does not. ``release()`` (writing) rewrites every exercise whose bytes differ
from the generated ones, so the committed files stay exactly what the generator makes.
"""

from __future__ import annotations

import copy
import os
import re
from pathlib import Path
from typing import Any

from ..bank_loader import EXERCISES
from ..spec import Exercise, Question
from ..written import ANSWER_TAG, PLACEHOLDER, PROMPT_TAG, prompt_source, written_questions, written_summary
from . import notebook_json as nbjson

__all__ = [
    "STUB",
    "BEGIN_SOLUTION",
    "END_SOLUTION",
    "BEGIN_HIDDEN",
    "END_HIDDEN",
    "NOTEBOOK_METADATA",
    "release_notebook",
    "notebook_text",
    "essentials",
    "question_heading",
    "points_summary",
    "release",
]

STUB = 'raise NotImplementedError("write your answer here")'
BEGIN_SOLUTION, END_SOLUTION = "### BEGIN SOLUTION", "### END SOLUTION"
BEGIN_HIDDEN, END_HIDDEN = "### BEGIN HIDDEN TESTS", "### END HIDDEN TESTS"
QUESTION_TAG, POINTS_TAG, HEADING_TAG, SUMMARY_TAG = "question:", "points:", "heading:", "points-summary"

#: The notebook metadata JupyterLab 4 writes for a Python 3 kernel, minus ``language_info.version``.
NOTEBOOK_METADATA: dict[str, Any] = {
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


def _transform_source(source: str, cell_kind: str) -> str | None:
    """Replace solution blocks by a stub and drop hidden tests; None if the cell ends up empty.

    >>> _transform_source("def f():\\n    ### BEGIN SOLUTION\\n    return 1\\n    ### END SOLUTION", "code")
    'def f():\\n    raise NotImplementedError("write your answer here")'
    """
    lines = source.splitlines()
    out: list[str] = []
    mode = None
    for number, line in enumerate(lines, start=1):
        stripped = line.strip()
        if mode is None and stripped == BEGIN_SOLUTION:
            indent = line[: len(line) - len(line.lstrip())]
            if cell_kind == "code":
                if not indent:
                    raise ValueError(
                        f"line {number}: a code solution block must sit inside a function body (indented), "
                        "so the handed-out notebook still runs"
                    )
                out.append(f"{indent}{STUB}")
            else:
                out.append("*Write your answer here.*")
            mode = "solution"
        elif mode is None and stripped == BEGIN_HIDDEN:
            mode = "hidden"
        elif mode == "solution" and stripped == END_SOLUTION:
            mode = None
        elif mode == "hidden" and stripped == END_HIDDEN:
            mode = None
        elif stripped in (BEGIN_SOLUTION, END_SOLUTION, BEGIN_HIDDEN, END_HIDDEN):
            raise ValueError(f"line {number}: unbalanced marker {stripped!r}")
        elif mode is None:
            out.append(line)
    if mode is not None:
        raise ValueError(f"a {mode} block is not closed")
    text = "\n".join(out).strip("\n")
    return text if text.strip() else None


def _points(points: float) -> str:
    return f"{points:g} point" + ("" if points == 1 else "s")


def question_heading(q: Question) -> str:
    """The Markdown heading the generator puts above the answer cell of ``q``.

    >>> from puma_course.grading import EXERCISES
    >>> question_heading(EXERCISES["ex01_rotations"].question("q2"))
    '**q2** · 3 points · write `rotation_between` below'
    """
    worth = f"bonus, {_points(q.points)} (in your score, not in the maximum)" if q.bonus else _points(q.points)
    return f"**{q.qid}** · {worth} · write `{q.function}` below"


def points_summary(exercise: Exercise) -> str:
    """The Markdown summary of an exercise's points that the generator puts after its first cell.

    >>> from puma_course.grading import EXERCISES
    >>> points_summary(EXERCISES["ex06_porter_explicit"])
    '**Points:** q1 2 · q2 5 · q3 3, 10 in all; bonus q4 3 (in your score, not in the maximum).'
    """
    graded = " · ".join(f"{q.qid} {q.points:g}" for q in exercise.questions if not q.bonus)
    text = f"**Points:** {graded}, {exercise.max_score:g} in all"
    bonus = " · ".join(f"{q.qid} {q.points:g}" for q in exercise.questions if q.bonus)
    if bonus:
        text += f"; bonus {bonus} (in your score, not in the maximum)"
    return text + "."


def _tags(cell: Any) -> list[str]:
    return [str(t) for t in cell.get("metadata", {}).get("tags", [])]


def _answer_cells(nb: Any, exercise: Exercise) -> dict[int, Question]:
    """Index of each question's answer cell, after checking the tags against the question bank."""
    bank = f"bank/{exercise.name}.py"
    found: dict[str, int] = {}
    for index, cell in enumerate(nb.cells):
        where = f"cell {index + 1} ({cell.get('id', '?')})"
        for tag in _tags(cell):
            if tag.startswith(POINTS_TAG):
                qids = [t[len(QUESTION_TAG) :] for t in _tags(cell) if t.startswith(QUESTION_TAG)]
                worth = [f"{qid} is worth {exercise.question(qid).points:g}" for qid in qids if _known(exercise, qid)]
                raise ValueError(
                    f"nb: expected no {POINTS_TAG}N tag in {where}, got {tag!r}; points come from the question bank "
                    f"({', '.join([*worth, bank])}) and the release writes the tag: remove it from the solution"
                )
            if tag.startswith((HEADING_TAG, ANSWER_TAG, PROMPT_TAG)) or tag == SUMMARY_TAG:
                raise ValueError(f"nb: expected no cell that the release generates, got {where} tagged {tag!r}")
            if not tag.startswith(QUESTION_TAG):
                continue
            qid = tag[len(QUESTION_TAG) :]
            if not _known(exercise, qid):
                ids = [q.qid for q in exercise.questions]
                raise ValueError(f"nb: expected question tags among {ids} ({bank}), got {tag!r} in {where}")
            if qid in found:
                raise ValueError(f"nb: expected one cell tagged {tag!r}, got cells {found[qid] + 1} and {index + 1}")
            q = exercise.question(qid)
            if cell.cell_type != "code" or not re.search(rf"^def {re.escape(q.function)}\(", cell.source, re.M):
                raise ValueError(f"nb: expected {where}, tagged {tag!r}, to define {q.function}(), got no such def")
            found[qid] = index
    missing = [q.qid for q in exercise.questions if q.qid not in found]
    if missing:
        raise ValueError(f"nb: expected a cell tagged {QUESTION_TAG}QID per question in {bank}, none for {missing}")
    return {index: exercise.question(qid) for qid, index in found.items()}


def _known(exercise: Exercise, qid: str) -> bool:
    return any(q.qid == qid for q in exercise.questions)


def release_notebook(nb: Any, exercise: Exercise | None = None) -> Any:
    r"""The student version of a solution notebook (a new :class:`~.notebook_json.Node`; ``nb`` is untouched).

    With ``exercise`` (what :func:`release` passes), each answer cell tagged ``question:qN`` gets its
    ``points:N`` tag and a heading cell from the question bank, and a points summary follows the first
    cell; without it, only the solution and hidden-test blocks are transformed (tags copied as they are).

    >>> import nbformat
    >>> hidden = nbformat.v4.new_code_cell("### BEGIN HIDDEN TESTS\nassert f() == 1\n### END HIDDEN TESTS")
    >>> given = nbformat.v4.new_code_cell("def f():\n    ### BEGIN SOLUTION\n    return 1\n    ### END SOLUTION")
    >>> [c.source for c in release_notebook(nbformat.v4.new_notebook(cells=[given, hidden])).cells]
    ['def f():\n    raise NotImplementedError("write your answer here")']
    """
    answers = _answer_cells(nb, exercise) if exercise is not None else {}
    summary_due = exercise is not None
    out = nbjson.new_notebook()
    out.metadata = nbjson.from_dict(copy.deepcopy(NOTEBOOK_METADATA))
    for index, cell in enumerate(nb.cells):
        try:
            source = _transform_source(cell.source, cell.cell_type)
        except ValueError as exc:
            raise ValueError(f"cell {index + 1} ({cell.get('id', '?')}): {exc}") from None
        q = answers.get(index)
        if q is not None:
            heading = nbjson.new_markdown_cell(question_heading(q), metadata={"tags": [HEADING_TAG + q.qid]})
            heading["id"] = f"heading-{q.qid}"
            out.cells.append(heading)
        if source is None:
            continue
        tags = _tags(cell) + ([f"{POINTS_TAG}{q.points:g}"] if q is not None else [])
        meta = {"tags": tags} if tags else {}
        if cell.cell_type == "code":
            new = nbjson.new_code_cell(source, metadata=meta)
        elif cell.cell_type == "markdown":
            new = nbjson.new_markdown_cell(source, metadata=meta)
        else:
            new = nbjson.new_raw_cell(source, metadata=meta)
        new["id"] = cell.get("id") or f"cell-{index + 1}"
        out.cells.append(new)
        if summary_due and exercise is not None:
            text = points_summary(exercise) + written_summary(exercise)
            summary = nbjson.new_markdown_cell(text, metadata={"tags": [SUMMARY_TAG]})
            summary["id"] = SUMMARY_TAG
            out.cells.append(summary)
            summary_due = False
    if exercise is not None:
        _add_written(out, exercise)
    ids = [c["id"] for c in out.cells]
    if len(set(ids)) != len(ids):
        twice = sorted({i for i in ids if ids.count(i) > 1})
        raise ValueError(f"nb: expected distinct cell ids, got {twice} more than once")
    return out


def _add_written(out: Any, exercise: Exercise) -> None:
    """Put each written question's prompt and answer cell before the notebook's closing cell (the last one,
    when it is Markdown), else at the end (see :mod:`.written`)."""
    cells = []
    for w in written_questions(exercise):
        prompt = nbjson.new_markdown_cell(prompt_source(w), metadata={"tags": [PROMPT_TAG + w.qid]})
        prompt["id"] = f"written-prompt-{w.qid}"
        answer = nbjson.new_markdown_cell(PLACEHOLDER, metadata={"tags": [ANSWER_TAG + w.qid]})
        answer["id"] = f"written-{w.qid}"
        cells += [prompt, answer]
    at = len(out.cells) - 1 if out.cells and out.cells[-1].cell_type == "markdown" else len(out.cells)
    out.cells[at:at] = cells


def notebook_text(nb: Any) -> str:
    """The exact text :func:`release` writes for ``nb`` (nbformat's layout plus a final newline)."""
    return nbjson.writes(nb) + "\n"


def essentials(nb: Any) -> list[tuple[str, str, tuple[str, ...]]]:
    """What ``release --check`` compares: (cell type, source, sorted tags) for each cell, in order.

    >>> import nbformat
    >>> cell = nbformat.v4.new_code_cell("x = 1", metadata={"tags": ["b", "a"], "collapsed": True})
    >>> cell.outputs = [nbformat.v4.new_output("stream", text="1")]
    >>> essentials(nbformat.v4.new_notebook(cells=[cell]))
    [('code', 'x = 1', ('a', 'b'))]
    """
    return [(str(c.cell_type), _source(c), tuple(sorted(_tags(c)))) for c in nb.cells]


def _source(cell: Any) -> str:
    """A cell's source as one string (the file format may store it as a list of lines)."""
    src = cell.get("source", "")
    return "".join(str(s) for s in src) if isinstance(src, list) else str(src)


def _first_difference(old: Any, new: Any) -> str | None:
    """Where an exercise notebook differs from the generated one in what matters, or None."""
    a, b = essentials(old), essentials(new)
    for index, (x, y) in enumerate(zip(a, b, strict=False)):
        for field, i in (("type", 0), ("source", 1), ("tags", 2)):
            if x[i] != y[i]:
                return f"cell {index + 1}: {field} differs"
    if len(a) != len(b):
        return f"{len(a)} cells, expected {len(b)}"
    return None


def release(
    solutions: str | os.PathLike[str] = "solutions",
    exercises: str | os.PathLike[str] = "exercises",
    check_only: bool = False,
) -> list[str]:
    """Write (or with ``check_only`` compare) every exercise; return the names written or out of date.

    The folders default to ``solutions/`` and ``exercises/`` in the current directory. With
    ``check_only`` nothing is written and each out-of-date name comes with its first difference,
    e.g. ``"ex02_dh_puma (cell 7: source differs)"``; what counts is stated in the module docstring.
    """
    sol_dir, ex_dir = Path(solutions), Path(exercises)
    if not sol_dir.is_dir():
        raise ValueError(f"solutions: expected a folder of solution notebooks, got {str(sol_dir)!r}")
    changed = []
    for path in sorted(sol_dir.glob("*.ipynb")):
        exercise = EXERCISES.get(path.stem)
        if exercise is None:
            raise ValueError(
                f"solutions: expected notebooks named after the question bank's exercises {sorted(EXERCISES)}, "
                f"got {path.name} (add bank/{path.stem}.py)"
            )
        try:
            generated = release_notebook(nbjson.read(path), exercise)
        except ValueError as exc:
            raise ValueError(f"{path.name}: {exc}") from None
        text = notebook_text(generated)
        target = ex_dir / path.name
        if check_only:
            why = _stale(target, generated)
            if why is not None:
                changed.append(f"{path.stem} ({why})")
        elif not target.exists() or target.read_bytes() != text.encode("utf-8"):
            ex_dir.mkdir(parents=True, exist_ok=True)
            target.write_text(text, encoding="utf-8", newline="\n")
            changed.append(path.stem)
    if check_only:
        extra = {p.stem for p in ex_dir.glob("*.ipynb")} - {p.stem for p in sol_dir.glob("*.ipynb")}
        changed.extend(sorted(f"{name} (no solution)" for name in extra))
    return changed


def _stale(target: Path, generated: Any) -> str | None:
    """Why the exercise at ``target`` is out of date with ``generated``, or None if it is not."""
    if not target.exists():
        return "not generated yet"
    try:
        committed = nbjson.reads(target.read_text(encoding="utf-8"))
    except Exception as exc:  # noqa: BLE001 - nbformat raises many kinds
        return f"not a readable notebook: {type(exc).__name__}"
    return _first_difference(committed, generated)
