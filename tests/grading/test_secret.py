"""The grading secret: every student's hidden inputs their own, drawn from a key only the instructor holds.

What holds: the key file is created once, owner-readable only, and read back the same; each question's
generator is seeded with HMAC-SHA256 of (student, exercise, question) under the key (checked against
an independent computation); no two students share a hidden input; regrading with the same key file
gives byte-identical grades; the feedback shows a run id and never the key, its fingerprint or a seed;
a notebook holding only a table of answers rebuilt at home from every seed a student could know
scores its hidden cases only when the key is such a public seed.
"""

from __future__ import annotations

import hashlib
import hmac
import os
import shutil
import stat
import subprocess
import sys
import time
import warnings
from subprocess import PIPE

import nbformat
import numpy as np
import pytest

from puma_course.cli import main
from puma_course.grading import EXERCISES, grade
from puma_course.grading.run.runner import make_plan
from puma_course.grading.secret import SECRET_FILE, Secret, from_seed, load_secret
from tests.grading.hostile.harness import KNOWN_SEEDS, _notebook, fixtures, home_table, table_key
from tests.support import ROOT

EX = "ex01_rotations"


def test_the_key_file_is_created_once_owner_only_and_read_back(tmp_path):
    path = tmp_path / "course" / SECRET_FILE
    key = load_secret(path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    text = path.read_text(encoding="ascii").strip()
    assert len(text) == 64 and bytes.fromhex(text) == key.key
    again = load_secret(path)
    assert again.key == key.key and again.fingerprint == key.fingerprint
    os.chmod(path, 0o644)  # a key others can read is made owner-only again
    load_secret(path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert ".grading-secret" in (ROOT / ".gitignore").read_text(encoding="utf-8").split()


_RACE = """
import os, sys, time
sys.path.insert(0, {root!r})
from puma_course.grading.secret import load_secret
if float(sys.argv[2]) > 0:  # this run is slow between creating its key file and writing the key into it
    real = os.fdopen
    def slow(*args, **kwargs):
        time.sleep(float(sys.argv[2]))
        return real(*args, **kwargs)
    os.fdopen = slow
print(load_secret(sys.argv[1]).fingerprint)
"""


def test_a_run_that_reads_the_key_while_another_creates_it_gets_the_whole_key(tmp_path):
    """The parts of a Slurm array started without a key file: a run that looks while another is writing the key
    must get the one key, never an empty file (before: "expected at least 32 hex digits ... got 0 characters").
    The first run is held for 1.5 s inside its write; the second starts 0.5 s later."""
    code = _RACE.format(root=str(ROOT))
    path = tmp_path / SECRET_FILE
    slow = subprocess.Popen([sys.executable, "-c", code, str(path), "1.5"], stdout=PIPE, stderr=PIPE)
    time.sleep(0.5)
    fast = subprocess.run([sys.executable, "-c", code, str(path), "0"], capture_output=True, timeout=120)
    out = slow.communicate(timeout=120)
    assert fast.returncode == 0 and slow.returncode == 0, (fast.stderr.decode()[-300:], out[1].decode()[-300:])
    prints = {fast.stdout.decode().strip(), out[0].decode().strip()}
    assert prints == {load_secret(path, create=False).fingerprint}, prints
    assert sorted(f.name for f in tmp_path.iterdir()) == [SECRET_FILE]  # no temporary file left
    assert stat.S_IMODE(path.stat().st_mode) == 0o600


@pytest.mark.parametrize("content", ["", "not hex at all", "abcd"])
def test_a_key_file_without_a_key_is_refused(tmp_path, content):
    path = tmp_path / "key"
    path.write_text(content, encoding="ascii")
    with pytest.raises(ValueError, match="^secret: expected at least 32 hex digits"):
        load_secret(path)
    with pytest.raises(ValueError, match="^secret: expected a key file"):
        load_secret(tmp_path / "absent", create=False)


def test_the_seeds_and_run_ids_are_the_documented_hmacs():
    key = Secret(bytes(range(32)))

    def mac(*parts: str) -> bytes:
        return hmac.new(bytes(range(32)), "\0".join(parts).encode(), hashlib.sha256).digest()

    assert key.case_seed("ann", EX, "q1") == int.from_bytes(mac("hidden cases", "ann", EX, "q1"), "big")
    assert key.run_id("ann", EX) == mac("run id", "ann", EX).hex()[:12]
    assert (
        key.fingerprint
        == hashlib.sha256(b"puma-course grading secret fingerprint\0" + bytes(range(32))).hexdigest()[:16]
    )
    shown = key.run_id("ann", EX) + key.fingerprint
    assert bytes(range(32)).hex()[:12] not in shown and str(key.case_seed("ann", EX, "q1"))[:12] not in shown


def _public(ex, plan):
    public = {(q.qid, k) for q in ex.questions for k in range(len(q.public))}
    return [(c.qid, table_key(c.call_args)) for c in plan if (c.qid, c.case) in public]


def _hidden(ex, plan):
    public = {(q.qid, k) for q in ex.questions for k in range(len(q.public))}
    return [(c.qid, table_key(c.call_args)) for c in plan if (c.qid, c.case) not in public]


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_every_student_gets_hidden_inputs_of_their_own(name):
    ex, key = EXERCISES[name], Secret(b"k" * 32)
    ann, bob = make_plan(ex, key, "ann"), make_plan(ex, key, "bob")
    assert _public(ex, ann) == _public(ex, bob)  # the public cases are everyone's
    hidden_ann, hidden_bob = _hidden(ex, ann), _hidden(ex, bob)
    assert hidden_ann and not set(hidden_ann) & set(hidden_bob)
    assert _hidden(ex, make_plan(ex, key, "ann")) == hidden_ann  # the same key draws the same inputs again
    assert not set(_hidden(ex, make_plan(ex, Secret(b"j" * 32), "ann"))) & set(hidden_ann)  # another key: others


def _class(tmp_path):
    subs = tmp_path / "subs"
    for student, folder in (("honest", "solutions"), ("blank", "exercises")):
        (subs / student).mkdir(parents=True)
        shutil.copy(ROOT / folder / f"{EX}.ipynb", subs / student)
    nb = nbformat.read(ROOT / "solutions" / f"{EX}.ipynb", as_version=4)
    answer = next(c for c in nb.cells if "question:q1" in c.metadata.get("tags", []))
    answer.source += (  # right on some angles only: the score depends on the hidden inputs drawn
        "\n\n\n_right = elementary_rotation\n\n\ndef elementary_rotation(axis, angle):\n"
        "    return _right(axis, angle) if angle > 0 else _right(axis, angle).T\n"
    )
    (subs / "half").mkdir()
    nbformat.write(nb, subs / "half" / f"{EX}.ipynb")
    return subs


def _grade(subs, out, fb, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return grade(subs, out, feedback=fb, jobs=2, exercises=[EX], sandbox="none", **kw)


def test_regrading_with_the_same_key_file_gives_identical_grades(tmp_path):
    subs, key = _class(tmp_path), tmp_path / "course" / SECRET_FILE
    first = _grade(subs, tmp_path / "a.csv", tmp_path / "fa", secret=key)
    again = _grade(subs, tmp_path / "b.csv", tmp_path / "fb", secret=key)
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    for f in (tmp_path / "fa").iterdir():
        assert f.read_bytes() == (tmp_path / "fb" / f.name).read_bytes()
    assert [(r.student, r.score, r.run_id) for r in first] == [(r.student, r.score, r.run_id) for r in again]
    scores = {r.student: r.score for r in first}
    assert scores["honest"] == EXERCISES[EX].max_score and scores["blank"] == 0
    assert 0 < scores["half"] < scores["honest"]
    # the CSV names the key and the run; the feedback the run only
    secret = load_secret(key)
    import csv

    with open(tmp_path / "a.csv", newline="", encoding="utf-8") as fh:
        rows = {r["student"]: r for r in csv.DictReader(fh)}
    assert {r["secret"] for r in rows.values()} == {secret.fingerprint} and {r["seed"] for r in rows.values()} == {""}
    assert rows["half"]["run"] == secret.run_id("half", EX) != rows["honest"]["run"]
    text = (tmp_path / "fa" / "half.md").read_text(encoding="utf-8")
    assert f"Run id: `{secret.run_id('half', EX)}`" in text
    assert secret.fingerprint not in text and secret.key.hex()[:16] not in text and "seed" not in text
    # another key: other run ids (and other hidden inputs)
    other = _grade(subs, tmp_path / "c.csv", None, secret=tmp_path / "other-key")
    assert {r.run_id for r in other}.isdisjoint({r.run_id for r in first})


def test_the_seed_table_notebook_scores_only_when_the_key_is_a_known_seed(tmp_path):
    """The issue's attack: answers rebuilt at home for every hidden case of every seed the student could know."""
    fx = next(f for f in fixtures() if f.name == "seed_table")
    subs = tmp_path / "subs"
    (subs / "attacker").mkdir(parents=True)
    values = {"TABLE": home_table([EX], "attacker")}
    nbformat.write(_notebook(fx, EX, values), subs / "attacker" / f"{EX}.ipynb")
    ex = EXERCISES[EX]
    share = sum(q.points * (1 - len(q.public) / len(q.cases(np.random.default_rng(0)))) for q in ex.questions)
    known = _grade(subs, tmp_path / "known.csv", None, seed=KNOWN_SEEDS[0])[0]
    assert known.score == pytest.approx(round(share, 2), abs=0.05), (known.score, known.question_notes)
    secret = _grade(subs, tmp_path / "secret.csv", None, secret=tmp_path / SECRET_FILE)[0]
    assert (secret.status, secret.score) == ("ok", 0), secret.question_notes


def test_the_cli_keeps_the_key_in_the_course_folder(tmp_path, capsys):
    course = tmp_path / "course"
    (course / "solutions").mkdir(parents=True)
    shutil.copytree(ROOT / "bank", course / "bank")  # the course's questions live beside its solutions/
    subs = _class(tmp_path)
    out = tmp_path / "g.csv"
    args = [
        "grade",
        str(subs),
        "-o",
        str(out),
        "--exercise",
        EX,
        "--quiet",
        "--course",
        str(course),
        "--sandbox",
        "none",
    ]
    assert main(args) == 0
    key = load_secret(course / SECRET_FILE, create=False)
    assert stat.S_IMODE((course / SECRET_FILE).stat().st_mode) == 0o600
    err = capsys.readouterr().err
    assert f"fingerprint {key.fingerprint}" in err and key.key.hex() not in err
    assert key.fingerprint in out.read_text(encoding="utf-8")
    assert main([*args, "--secret", str(course / SECRET_FILE), "--seed", "3"]) == 2
    assert "either --secret FILE or --seed N" in capsys.readouterr().err
    assert from_seed(3).fingerprint != key.fingerprint
