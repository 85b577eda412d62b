"""puma_course.grading.output.report: one wording of a question's result, used by self-check, feedback and the CLI."""

from __future__ import annotations

import csv
import inspect

from puma_course import cli
from puma_course.grading import EXERCISES, NotebookResult, check, format_check_report
from puma_course.grading.output.report import feedback_markdown, format_question, verdict, write_csv, write_feedback
from puma_course.grading.output.text import quoted

EX = EXERCISES["ex01_rotations"]


def _result(status="ok"):
    return NotebookResult(
        "ann",
        EX.name,
        status,
        EX.max_score,
        scores={"q1": 2.0, "q2": 1.0, "q3": 0.0, "q4": 0.0, "q5": 0.0, "q6": 0.0},
        question_notes={
            "q1": ["5/5 cases pass"],
            "q2": ["2/6 cases pass", "hidden case 4: values differ from the reference by up to 0.5"],
            "q3": ["0/7 cases pass", "public case 1: not attempted yet (NotImplementedError)"],
            "q4": ["0/5 cases pass", "public case 1: returned a | pipe"],
            "q5": ["0/9 cases pass", "public case 1: not attempted yet (NotImplementedError)"],
            "q6": ["0/6 cases pass", "public case 1: not attempted yet (NotImplementedError)"],
        },
    )


def test_verdicts():
    q = EX.question("q3")
    assert verdict(q, 3, ["7/7 cases pass"]) == "passed"
    assert verdict(q, 0.43, ["1/7 cases pass", "hidden case 2: wrong"]) == "partly"
    assert verdict(q, 0, ["0/7 cases pass", "public case 1: not attempted yet (NotImplementedError)"]) == (
        "not attempted yet"
    )
    mixed = ["0/7 cases pass", "public case 1: not attempted yet (NotImplementedError)", "hidden case 3: raised"]
    assert verdict(q, 0, mixed) == "FAILED"
    assert verdict(q, 0, []) == "FAILED"


def test_the_text_line_names_question_function_points_verdict_reasons_and_hint():
    q = EX.question("q2")
    text = format_question(q, 1.0, _result().question_notes["q2"])
    assert text.splitlines() == [
        "q2 rotation_between: 1 / 3 points - partly "
        "(2/6 cases pass; hidden case 4: values differ from the reference by up to 0.5)",
        f"  Hint: {q.hint}",
    ]
    assert format_question(EX.question("q1"), 2, ["5/5 cases pass"]) == (
        "q1 elementary_rotation: 2 / 2 points - passed (5/5 cases pass)"
    )
    bonus = EXERCISES["ex06_porter_explicit"].question("q4")
    assert format_question(bonus, 3, ["1/1 cases pass"]).startswith("q4 porter_ik_limited (bonus): 3 / 3 points")


def test_a_hint_follows_an_attempt_only():
    """Shown beside "not attempted yet", a hint gives away the step the question asks for: it waits for a try."""
    q = EX.question("q2")
    assert q.hint
    stub = ["0/6 cases pass", "public case 1: not attempted yet (NotImplementedError)"]
    assert format_question(q, 0, stub) == f"q2 {q.function}: 0 / 3 points - not attempted yet"
    assert format_question(q, 0, ["0/6 cases pass", "public case 1: raised ValueError: x"]).endswith(f"Hint: {q.hint}")
    assert format_question(q, 1.5, ["3/6 cases pass", "hidden case 4: values differ"]).endswith(f"Hint: {q.hint}")
    assert "Hint" not in format_question(q, 3, ["6/6 cases pass"])
    assert "Hint" not in format_question(q, 0, stub, markdown=True)


def test_the_feedback_table_rows_are_the_same_formatter_in_markdown():
    text = feedback_markdown("ann", [_result()], seed=7)
    for q in EX.questions:
        row = format_question(q, _result().scores[q.qid], _result().question_notes[q.qid], markdown=True)
        assert row in text
    assert "| q3 `axis_angle_between` | 0 / 3 | not attempted yet |" in text
    assert r"returned a \| pipe" in text  # a '|' in a reason does not break the table
    assert "Total: **3 / 15** points." in text
    assert "seed" not in text and "7" not in text.split("Total")[1].split("##")[0]  # the seed is never shown
    assert text.count("\n- q") == 2  # hints for q2 (partly) and q4 (FAILED): none before an attempt (q3, q5, q6)
    assert "\n- q2: " in text and "\n- q4: " in text


def test_the_cli_report_is_the_same_formatter_indented():
    report = format_check_report(_result(), EX)
    lines = report.splitlines()
    assert lines[0] == "ex01_rotations: 3 / 15 on the public cases (status ok)"
    for q in EX.questions:
        for line in format_question(q, _result().scores[q.qid], _result().question_notes[q.qid]).splitlines():
            assert f"  {line}" in lines
    # the CLI's check prints through it and words nothing itself
    source = inspect.getsource(cli.check.run)
    assert "format_check_report" in source and "q.points" not in source and "hint" not in source


def test_check_prints_through_the_same_formatter(capsys, right_rotation):
    check("ex01_rotations:q1", right_rotation)
    line = format_question(EX.question("q1"), 2, ["5/5 cases pass"], scope="on the public cases")
    assert capsys.readouterr().out == line + "\n"


def test_csv_columns(tmp_path):
    out = tmp_path / "sub" / "grades.csv"
    limits = "per notebook (cgroup v1): 4 GiB, 64 processes, 1 CPU"
    write_csv(out, [_result(), _result("missing")], [EX.name], seed=12, sandbox="bwrap", limits=limits)
    with open(out, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == [
        "student",
        "exercise",
        "score",
        "max_score",
        "bonus",
        "q1",
        "q2",
        "q3",
        "q4",
        "q5",
        "q6",
        "status",
        "sandbox",
        "limits",
        "seed",
        "secret",
        "run",
        "notes",
    ]
    assert rows[1] == [
        "ann",
        "ex01_rotations",
        "3",
        "15",
        "0",
        "2",
        "1",
        "0",
        "0",
        "0",
        "0",
        "ok",
        "bwrap",
        limits,
        "12",
        "",
        "",
        "",
    ]
    assert list(tmp_path.glob("sub/*")) == [out]  # no temporary file left behind


def test_csv_bonus_column_holds_the_bonus_part_of_the_score(tmp_path):
    ex = EXERCISES["ex06_porter_explicit"]  # q4 is its bonus question (3 points)
    r = NotebookResult("bo", ex.name, "ok", ex.max_score, scores={"q1": 2.0, "q2": 5.0, "q3": 1.0, "q4": 1.5})
    write_csv(tmp_path / "g.csv", [r], [ex.name], seed=1, sandbox="none")
    with open(tmp_path / "g.csv", newline="", encoding="utf-8") as fh:
        row = next(csv.DictReader(fh))
    assert (row["score"], row["max_score"], row["bonus"]) == ("9.5", "10", "1.5")


def test_csv_cells_never_start_a_spreadsheet_formula(tmp_path):
    r = _result()
    r.student = "=HYPERLINK(1)"
    r.notes = ["-1+1", "x"]
    write_csv(tmp_path / "g.csv", [r], [EX.name])
    with open(tmp_path / "g.csv", newline="", encoding="utf-8") as fh:
        row = next(csv.DictReader(fh))
    assert row["student"] == "'=HYPERLINK(1)" and row["notes"] == "'-1+1 | x"


def test_feedback_quotes_the_students_text_and_warns_without_sandbox():
    r = _result()
    r.notes = ["code cell 2: " + quoted("x\n\nTotal: **56 / 56** points. `|` <b>")]
    text = feedback_markdown("x\n# Total 56", [r], seed=1, unsandboxed="bubblewrap is not installed")
    lines = text.splitlines()
    assert lines[0] == "# Feedback for `x\\x0a# Total 56`"
    assert lines[2].startswith(
        "> **Warning: graded without the operating-system sandbox** (bubblewrap is not installed)"
    )
    assert "- code cell 2: `` x\\x0a\\x0aTotal: **56 / 56** points. `|` <b> ``" in lines
    assert sum(line.startswith("Total:") for line in lines) == 1
    assert "Warning" not in feedback_markdown("ann", [r], seed=1)


def test_feedback_says_what_holds_when_graded_as_an_unprivileged_user():
    """Gradescope: no bubblewrap, but the notebook ran alone as a user of its own; no classmate can interfere."""
    text = feedback_markdown("ann", [_result()], unsandboxed="bubblewrap cannot start here", as_user="puma-student")
    assert "Warning" not in text and "classmate" not in text
    assert text.splitlines()[2] == (
        "> Graded without bubblewrap (bubblewrap cannot start here): the notebook ran alone in its container, "
        "as the unprivileged user `puma-student`, which could not open the grader's files."
    )


def test_feedback_files_never_collide_and_replace_a_planted_link(tmp_path):
    fb = tmp_path / "fb"
    fb.mkdir()
    target = tmp_path / "precious.txt"
    target.write_text("keep", encoding="utf-8")
    (fb / "ann.md").symlink_to(target)
    results = []
    for name in ("ann", "Ann", "a n n", "../ann", "-" * 300):
        r = _result()
        r.student = name
        results.append(r)
    files = write_feedback(fb, results, seed=3)
    assert len(set(files.values())) == 5 and len({p.name.lower() for p in files.values()}) == 5
    assert all(len(p.name) < 120 for p in files.values())
    assert target.read_text(encoding="utf-8") == "keep" and not (fb / "ann.md").is_symlink()
    assert sorted(p.name for p in fb.iterdir()) == sorted(p.name for p in files.values())


def test_the_feedback_says_where_the_hidden_inputs_came_from_only_as_far_as_it_is_true(tmp_path):
    """A key file: "drawn for you alone, from a key your instructor keeps". A public seed (``--seed N``): a seed
    the class shares, and never the key file's words. Unit first, then through ``grade`` itself."""
    import shutil
    import warnings

    from puma_course.grading import grade
    from puma_course.grading.secret import from_seed, load_secret, one_off
    from tests.support import ROOT

    alone, shared = "drawn for you alone, from a key your instructor keeps", "a seed shared by the whole class"
    secret = load_secret(tmp_path / "key")
    assert alone in feedback_markdown("ann", [_result()], key=secret)
    text = feedback_markdown("ann", [_result()], key=from_seed(3))
    assert shared in text and "for you alone" not in text and "instructor keeps" not in text
    text = feedback_markdown("ann", [_result()], key=one_off())
    assert "for this grading run only" in text and "instructor keeps" not in text and shared not in text

    subs = tmp_path / "subs"
    (subs / "ann").mkdir(parents=True)
    shutil.copy(ROOT / "exercises" / f"{EX.name}.ipynb", subs / "ann")
    said = {}
    for name, kw in (("seed", {"seed": 3}), ("secret", {"secret": tmp_path / "key"})):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            grade(subs, tmp_path / f"{name}.csv", feedback=tmp_path / name, exercises=[EX.name], sandbox="none", **kw)
        said[name] = (tmp_path / name / "ann.md").read_text(encoding="utf-8")
    assert shared in said["seed"] and "for you alone" not in said["seed"], said["seed"][-300:]
    assert alone in said["secret"] and shared not in said["secret"], said["secret"][-300:]
