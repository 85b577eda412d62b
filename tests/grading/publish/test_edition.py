"""The student edition: everything a student needs, nothing of the key, and the same self-check verdicts.

* ``puma-course edition DIR`` writes the lectures, exercises, figures, package and the public cases'
  data, and no solution, bank, hidden test or reference code, and no rubric or worked answer of a written
  question (every file searched, as bytes);
* writing it again updates DIR in place and leaves a ``.git`` alone;
* the edition's self-check (the public cases as data, :mod:`puma_course.grading.publish.public`) gives the
  same outcome, diagnosis and hint as the instructor's bank on every public case of every question,
  for the solutions' answers and for wrong ones (each recognised mistake, zeros, not attempted);
* installed with ``pip install`` into a fresh virtual environment (slow), the edition's package holds
  none of the key either, and its ``puma-course check`` runs the public cases without a bank.
"""

from __future__ import annotations

import contextlib
import copy
import inspect
import io
import os
import pickle
import subprocess
import sys
import types
from pathlib import Path

import nbformat
import numpy as np
import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES
from puma_course.grading.judge.judges import table_judge
from puma_course.grading.judge.judges.tables import modified_table_fk
from puma_course.grading.publish.edition import write_edition
from puma_course.grading.publish.public import DATA_FILE, _key, dumps, public_exercise
from puma_course.grading.remake import Made
from puma_course.grading.results import score_question
from puma_course.grading.selfcheck import public_outcomes
from puma_course.grading.written import written_exercises, written_questions
from puma_course_bank import _reference
from tests.support import ROOT

NAMES = sorted(EXERCISES)
QUESTIONS = [(ex.name, q.qid) for ex in EXERCISES.values() for q in ex.questions]


def _answer_blocks() -> dict[str, list[list[str]]]:
    """Each solution's answer blocks (inside BEGIN/END SOLUTION or HIDDEN TESTS): their stripped lines."""
    out: dict[str, list[list[str]]] = {}
    for path in sorted((ROOT / "solutions").glob("*.ipynb")):
        blocks: list[list[str]] = []
        for cell in nbformat.read(path, as_version=4).cells:
            inside = False
            for line in cell.source.splitlines():
                s = line.strip()
                if s in ("### BEGIN SOLUTION", "### BEGIN HIDDEN TESTS"):
                    inside = True
                    blocks.append([])
                elif s in ("### END SOLUTION", "### END HIDDEN TESTS"):
                    inside = False
                elif inside and s:
                    blocks[-1].append(s)
        out[path.stem] = blocks
    return out


def _public_text() -> str:
    """What the instructor's course publishes anyway: lectures, exercises, the index and the package's source."""
    files = [*ROOT.glob("notebooks/*.ipynb"), *ROOT.glob("exercises/*.ipynb"), ROOT / "START_HERE.ipynb"]
    files += [p for p in (ROOT / "puma_course").rglob("*.py")]
    return "\n".join(p.read_text(encoding="utf-8") for p in files)


def _solution_lines() -> dict[str, list[str]]:
    """The answer lines that say something: longer than 12 characters, not a comment, and not already in
    what the course publishes (a line such as ``T = np.eye(4)`` is in the lectures too)."""
    public = _public_text()
    return {
        name: [s for block in blocks for s in block if len(s) > 12 and not s.startswith("#") and s not in public]
        for name, blocks in _answer_blocks().items()
    }


def _reference_sources() -> list[str]:
    """The source of every function of the bank (its reference code, formulas and hidden-case generators),
    lines stripped of their indentation."""
    modules = [m for name, m in sorted(sys.modules.items()) if name.startswith("puma_course_bank")]
    sources = []
    for module in modules:
        for _, fn in inspect.getmembers(module, inspect.isfunction):
            if fn.__module__ == module.__name__:
                sources.append("\n".join(line.strip() for line in inspect.getsource(fn).strip().splitlines()))
    assert len(sources) > 40 and any("def camera_pose" in s for s in sources)
    return sources


def _written_key() -> list[str]:
    """The marker's side of every written question (bank/written.py): rubric lines, a full answer, the worked answer."""
    texts = []
    for name in written_exercises():
        for w in written_questions(name):
            texts += [c.text for c in w.spec.criteria]
            texts += [line.strip() for line in (w.spec.full_answer + "\n" + w.spec.worked).splitlines()]
    texts = [t for t in texts if len(t) > 25]
    assert len(texts) > 20
    return texts


def _leaks(folder: Path) -> list[str]:
    """(file, what) for every solution line or bank function found in any file under ``folder``."""
    needles = [(f"solution {n}", line) for n, lines in _solution_lines().items() for line in lines]
    needles += [(f"answer of {n}", "\n".join(b)) for n, blocks in _answer_blocks().items() for b in blocks if b]
    needles += [("bank source", src) for src in _reference_sources()]
    needles += [("written rubric or worked answer", text) for text in _written_key()]
    found = []
    for path in folder.rglob("*"):
        if path.is_file() and not path.is_symlink():
            text = path.read_bytes().decode("utf-8", errors="replace")
            text += "\n" + "\n".join(line.strip() for line in text.splitlines())  # indentation aside
            found += [f"{path.relative_to(folder)}: {what}: {n[:60]}" for what, n in needles if n in text]
    return found


@pytest.fixture(scope="module")
def edition(tmp_path_factory):
    out = tmp_path_factory.mktemp("class-edition")
    assert main(["edition", str(out), "--course", str(ROOT)]) == 0
    return out


def test_the_edition_holds_what_a_student_needs(edition):
    top = {p.name for p in edition.iterdir()}
    wanted = {"README.md", "START_HERE.ipynb", "notebooks", "exercises", "figures", "puma_course", "pyproject.toml"}
    assert wanted <= top
    assert not top & {"solutions", "bank", "tests", "benchmarks", "docs", "js", ".ci"}
    assert sorted(p.name for p in (edition / "exercises").glob("*.ipynb")) == [f"{n}.ipynb" for n in NAMES]
    assert sorted(p.name for p in (edition / "notebooks").glob("*.ipynb")) == sorted(
        p.name for p in (ROOT / "notebooks").glob("*.ipynb")
    )
    # every figure an exercise shows is there
    for nb in (edition / "exercises").glob("*.ipynb"):
        for name in {part.split(")")[0] for part in nb.read_text(encoding="utf-8").split("../figures/")[1:]}:
            assert (edition / "figures" / name).is_file(), (nb.name, name)
    readme = (edition / "README.md").read_text(encoding="utf-8")
    for step in ("python3 -m venv .venv", "source .venv/bin/activate", ".venv\\Scripts\\Activate.ps1",
                 'pip install ".[lab]"', "puma-course lab", 'check("q1", my_function)', "puma-course check",
                 "Hand in"):  # fmt: skip
        assert step in readme, step
    # Windows: the Command Prompt's form first (PowerShell's default policy refuses Activate.ps1), and why
    assert readme.index(".venv\\Scripts\\activate.bat") < readme.index(".venv\\Scripts\\Activate.ps1")
    assert "Set-ExecutionPolicy" in readme
    assert "puma-course lab --allow-root" in readme and "sudo" in readme  # what to do as root
    assert (edition / "puma_course" / DATA_FILE.relative_to(DATA_FILE.parents[3])).is_file()
    assert not list(edition.rglob("__pycache__"))


def test_no_solution_line_or_bank_source_is_anywhere_in_the_edition(edition):
    assert _leaks(edition) == []


def test_the_leak_search_finds_a_planted_solution_and_bank_function(tmp_path):
    some_line = next(iter(_solution_lines().values()))[0]
    (tmp_path / "a.txt").write_text("x\n" + some_line + "\n", encoding="utf-8")
    (tmp_path / "b.py").write_text(inspect.getsource(_reference.chains.camera_pose), encoding="utf-8")
    (tmp_path / "c.md").write_text("  " + _written_key()[-1] + "\n", encoding="utf-8")
    assert len(_leaks(tmp_path)) >= 3 and any("written rubric" in leak for leak in _leaks(tmp_path))


def test_writing_again_updates_in_place_and_leaves_git_alone(edition):
    git = edition / ".git"
    git.mkdir(exist_ok=True)
    (git / "HEAD").write_text("ref: refs/heads/main\n", encoding="utf-8")
    stale = edition / "exercises" / "stale.ipynb"
    stale.write_text("{}", encoding="utf-8")
    before = (edition / "README.md").read_bytes()
    assert main(["edition", str(edition), "--course", str(ROOT)]) == 0
    assert (git / "HEAD").read_text(encoding="utf-8") == "ref: refs/heads/main\n"
    assert not stale.exists() and (edition / "README.md").read_bytes() == before


def test_the_edition_refuses_to_write_into_the_course_itself():
    with pytest.raises(ValueError, match="outside the course"):
        write_edition(ROOT / "solutions", ROOT)


# --------------------------------------------------------------------------------- same verdicts
@pytest.fixture(scope="module")
def public():
    """The public exercises as the edition stores them: built, written and read back."""
    return pickle.loads(dumps({name: public_exercise(EXERCISES[name]) for name in NAMES}))


@pytest.fixture(scope="module")
def solutions():
    """Each solution notebook's functions, run as a student's notebook runs (its code cells in order)."""
    out = {}
    for name in NAMES:
        ns: dict = {}
        cwd = os.getcwd()
        try:
            os.chdir(ROOT / "solutions")
            # the notebooks set numpy's print options: keep them out of this process (doctests run here too)
            with contextlib.redirect_stdout(io.StringIO()), np.printoptions():
                for cell in nbformat.read(ROOT / "solutions" / f"{name}.ipynb", as_version=4).cells:
                    if cell.cell_type == "code":
                        exec(compile(cell.source, f"{name}.ipynb", "exec"), ns)  # noqa: S102 - the course's own
        finally:
            os.chdir(cwd)
        out[name] = ns
    return out


def _as_data(fn, q):
    """A student's answer that returns, for each public case, what ``fn`` returns there (plain numbers only)."""
    table = {}
    for args in q.public:
        try:
            table[_key(tuple(args))] = fn(*copy.deepcopy(args))
        except Exception:  # noqa: BLE001 - a mistake that does not apply to this case
            table[_key(tuple(args))] = np.full(3, 7.0)
    return lambda *args: copy.deepcopy(table[_key(tuple(args))])


def _answers(q, ns):
    """(label, function): the solution's answer and wrong ones: each recognised mistake, zeros, not attempted."""
    out = [("solution", ns[q.function]), ("zeros", lambda *a: np.zeros((4, 4)))]

    def not_attempted(*args):
        raise NotImplementedError

    out.append(("not attempted", not_attempted))
    for m in q.mistakes:
        if isinstance(m.check, Made):
            out += [(m.key, _as_data(a, q)) for a in m.check.args if isinstance(a, types.FunctionType | Made)]
    # the right answer turned wrong in common ways (transposed, in degrees, one sign flipped)
    right = _as_data(ns[q.function], q)
    out.append(("transposed", lambda *a: np.swapaxes(np.atleast_2d(np.asarray(right(*a), float)), -1, -2)))
    out.append(("degrees", lambda *a: np.degrees(np.asarray(right(*a), float))))
    out.append(("negated", lambda *a: -np.asarray(right(*a), float)))
    if isinstance(q.judge_with, Made) and q.judge_with.factory is table_judge:
        out += _wrong_tables(right)
    return out


def _reversed_joint(table, j):
    """``table`` with joint j's axis z_j reversed (0-based, not the last): the same chain with q_j negated.

    Rot(X, α+π) Trans(X, a) Rot(Z, -θ - q) Trans(Z, -d) = Rot(X, α) Trans(X, a) Rot(Z, θ + q) Trans(Z, d) Rot(X, π)
    (and Trans(Z, -d + q) for a prismatic joint); the next row's α_j + π takes the Rot(X, π) back.
    """
    t = np.array(table, dtype=float)
    t[j, 0] += np.pi
    t[j, 2:4] = -t[j, 2:4]
    t[j + 1, 0] += np.pi
    return t


def _wrong_tables(right):
    """Wrong DH tables of the right shape: an offset's sign, each joint reversed, random numbers."""

    def sign(*a):
        t = np.array(right(*a), dtype=float)
        i, k = np.argwhere(np.abs(t[:, [1, 3]]) > 1e-9)[-1]  # the last non-zero offset (a or d)
        t[i, [1, 3][k]] *= -1
        return t

    def random_table(*a):
        t = np.array(right(*a), dtype=float)
        rng = np.random.default_rng(int(1e3 * np.sum(np.abs(t))))
        t[:, :4] = rng.uniform(-1.5, 1.5, (len(t), 4))
        return t

    out = [("a sign wrong", sign), ("random table", random_table)]
    for j in range(5):
        out.append((f"joint {j + 1} reversed", lambda *a, j=j: _reversed_or_same(right(*a), j)))
    return out


def _reversed_or_same(table, j):
    t = np.asarray(table, dtype=float)
    return _reversed_joint(t, j) if j < len(t) - 1 else t * [1, 1, 1, -1, 1]


@pytest.mark.parametrize(("name", "qid"), QUESTIONS, ids=[f"{n}:{q}" for n, q in QUESTIONS])
def test_the_edition_self_check_agrees_with_the_instructors(public, solutions, name, qid):
    q_bank, q_pub = EXERCISES[name].question(qid), public[name].question(qid)
    for field in ("points", "title", "hint", "bonus", "function", "public"):
        assert repr(getattr(q_pub, field)) == repr(getattr(q_bank, field)), field
    assert q_pub.hidden(np.random.default_rng(0)) == []
    answers = _answers(q_bank, solutions[name])
    assert len(answers) >= 6
    for label, fn in answers:
        ours, theirs = public_outcomes(q_bank, fn), public_outcomes(q_pub, fn)
        assert theirs == ours, (label, ours, theirs)
        assert not any("LookupError" in (reason or "") for _, reason in theirs), (label, theirs)
        if label == "joint 1 reversed":  # the course names it, so must the edition
            assert all("joint 1" in (reason or "") and "the wrong way" in (reason or "") for _, reason in theirs)
        assert score_question(q_pub.points, theirs) == score_question(q_bank.points, ours)
    solution_outcomes = public_outcomes(q_pub, solutions[name][q_bank.function])
    assert all(reason is None for _, reason in solution_outcomes), solution_outcomes


def test_a_table_judge_missing_a_recorded_pose_still_says_what_differs():
    """An edition whose data lacks a pose the diagnosis asks for answers as the grader's last resort does."""
    chain = np.array([[0.0, 0.0, 0.0, 0.8, 0], [np.pi / 2, 0.0, 0.0, 0.0, 0]])
    Q = np.random.default_rng(1).uniform(-np.pi, np.pi, (6, 2))

    def fk(P):
        if P is not Q:
            raise LookupError("the self-check has no recorded value for these arguments (a public case only)")
        return modified_table_fk(chain, P)

    expected = {"fk": fk, "Q": Q, "revolute": np.array([True, True]), "scale": 1.0}
    wrong = chain + [[0, 0, 0, 0, 0], [0, 0, 0.9, 0, 0]]  # a tool frame turned: the diagnosis asks fk(-Q)
    verdict = table_judge()(wrong, expected, ())
    assert not verdict.passed and verdict.reason.startswith("your chain reaches other poses"), verdict


def test_the_public_data_holds_no_bank_code_and_no_hidden_cases(public):
    data = dumps(public)
    assert b"puma_course_bank" not in data
    for src in _reference_sources():
        assert src.encode() not in data


def test_a_bank_function_cannot_be_written_into_an_edition():
    ex = EXERCISES["ex01_rotations"]
    with pytest.raises(ValueError, match="no code of the question bank"):
        dumps({"x": ex})  # the bank's own questions, not their public form


# --------------------------------------------------------------------------------- installed
def _venv(where: Path) -> Path:
    subprocess.run([sys.executable, "-m", "venv", str(where)], check=True)
    return where / "bin" / "python"


@pytest.mark.slow
# CI's second pass (another OpenBLAS kernel) leaves this out: a pip install and the files it puts in a venv; its one
# check is a blank exercise's 0 points (the public cases' verdicts under this kernel are tested above)
@pytest.mark.no_numerics
def test_the_installed_edition_holds_no_key_and_checks_the_public_cases(edition, tmp_path):
    python = _venv(tmp_path / "venv")
    before = sorted(p.relative_to(edition).as_posix() for p in edition.rglob("*"))
    subprocess.run([str(python), "-m", "pip", "install", "-q", str(edition)], check=True)
    # the student's folder as it was: no build/, no *.egg-info (setup.py builds in a temporary folder)
    assert sorted(p.relative_to(edition).as_posix() for p in edition.rglob("*")) == before
    site = Path(
        subprocess.run(
            [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
            check=True, capture_output=True, text=True,
        ).stdout.strip()
    )  # fmt: skip
    assert _leaks(site / "puma_course") == []
    names = {p.name.lower() for p in site.iterdir()}
    for heavy in ("jupyterlab", "nbclient", "sphinx", "playwright", "mypy"):
        assert not any(n == heavy or n.startswith(heavy + "-") for n in names), heavy
    size = sum(p.stat().st_size for p in site.rglob("*") if p.is_file() and not p.is_symlink())
    assert size < 400e6, size
    # a fresh copy of the exercise, checked by the installed command, from inside the edition
    work = edition / "exercises"
    env = {**os.environ, "PATH": f"{python.parent}{os.pathsep}{os.environ['PATH']}"}
    out = subprocess.run(
        [str(python.parent / "puma-course"), "check", "ex01_rotations"],
        cwd=work, env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    assert "q1 elementary_rotation: 0 / 2 points" in out.stdout and "not attempted" in out.stdout
