"""The copy report (issue 30, deliverable 4): near-copies of the package, a lecture or a classmate, never a mark.

The fixture class (``tests/fixtures/copies``): ann and ben share q1 (ben renamed and reformatted it), cat pastes
``Puma560.ik``'s source into q2, dan builds q1 from lecture 09's cells, eve is honest, fay blank, gus carries
part of the package as a base64 zip. The report must name exactly those, with figures clear of the threshold,
and grading with it gives the marks grading without it gives.
"""

from __future__ import annotations

import base64
import gzip
import io
import json
import random
import zipfile
from pathlib import Path

import pytest

from puma_course.grading import EXERCISES, grade
from puma_course.grading.bank_loader import load_bank
from puma_course.grading.output import copies as cp
from puma_course.grading.output.fingerprints import WINDOW, K, fingerprint, similarity, tokens
from puma_course.grading.output.payloads import payloads
from puma_course.grading.run import runner
from tests.fixtures.copies import EXERCISE, EXPECTED, build_class

#: Every figure of the fixture class stays this far from the threshold, on its own side.
MARGIN = 0.05


ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(autouse=True, scope="module")
def _this_course():
    """The exercise's own cells come from the loaded course's release: load this repository's bank, whatever another
    test run before in the same process loaded (tests/grading/publish/test_gradescope.py loads one zip's bank at a
    time)."""
    load_bank(ROOT)


@pytest.fixture(scope="module")
def klass(tmp_path_factory, _this_course):
    folder = tmp_path_factory.mktemp("copies") / "submissions"
    names = build_class(folder)
    ex = EXERCISES[EXERCISE]
    handed = [cp.handed((folder / n / f"{EXERCISE}.ipynb").read_bytes(), ex, n) for n in names]
    return folder, handed, cp.find_copies(handed)


def test_renaming_reformatting_and_comments_are_invisible_to_the_tokens():
    a = "def f(x, y):\n    total = x * 2.5 + y  # add\n    return [total, 'a']\n"
    b = 'def g(alpha,\n      beta):\n    s=alpha*7+beta\n\n    return [ s,\n  "bb" ]'
    hand = ["def", "N", "(", "N", ",", "N", ")", ":", ";", "N", "=", "N", "*", "0", "+", "N", ";", "return"]
    hand += ["[", "N", ",", "S", "]"]
    assert tokens(a) == tokens(b) == hand
    assert tokens("%time x = 1\n!ls\ny = (") == ["N", "=", "("]  # IPython's lines out; an unfinished rest kept


def test_winnowing_finds_every_long_shared_run_and_no_short_one():
    """Schleimer et al.'s guarantee, on random token streams: a shared run of K + WINDOW - 1 tokens is always
    found; one of K - 1 tokens never (unrelated streams over a large alphabet share no run of K)."""
    rng = random.Random(30)
    for trial in range(40):
        alphabet = [f"t{i}" for i in range(500)]
        run = [rng.choice(alphabet) for _ in range(K + WINDOW - 1 if trial % 2 == 0 else K - 1)]
        a = (
            [rng.choice(alphabet) for _ in range(rng.randrange(0, 80))]
            + run
            + [rng.choice(alphabet) for _ in range(50)]
        )
        b = (
            [rng.choice(alphabet) for _ in range(rng.randrange(0, 80))]
            + run
            + [rng.choice(alphabet) for _ in range(50)]
        )
        share, size = similarity(fingerprint(a), fingerprint(b))
        if trial % 2 == 0:
            assert size >= K, (trial, share, size)
        else:
            assert size == 0, (trial, share, size)


def test_the_exercises_own_code_is_left_out_and_blank_notebooks_match_nothing(klass):
    _, handed, report = klass
    fay = next(h for h in handed if h.student == "fay")
    assert fay.code == {} and fay.carried == []
    released = (cp.PACKAGE.parent / "exercises" / f"{EXERCISE}.ipynb").read_bytes()
    blanks = [cp.handed(released, EXERCISES[EXERCISE], f"blank{i}") for i in range(12)]
    assert cp.find_copies(blanks).matches == []


def test_the_report_names_exactly_the_copies_with_figures_above_the_threshold(klass):
    _, _, report = klass
    got = {kind: {(q, a, b.split(":")[0]) for q, a, b in report.pairs(kind)} for kind in EXPECTED}
    package = {(q, a, b) for q, a, b in got["package"] if not q.startswith(f"{EXERCISE}:hidden")}
    assert got["classmate"] == EXPECTED["classmate"]
    assert package == EXPECTED["package"]
    assert got["lecture"] == EXPECTED["lecture"]
    for m in report.matches:
        assert m.share >= cp.LEVEL + MARGIN or (m.other_share or 0) >= cp.LEVEL + MARGIN, m
        assert m.size >= cp.MIN_TOKENS, m
    cat = next(m for m in report.matches if m.student == "cat")
    assert {"_reach", "_arm", "_wrist"} <= set(cat.other.split(": ")[1].split(", ")), cat.other
    named = {m.student for m in report.matches} | {m.other for m in report.matches if m.source == "classmate"}
    assert "eve" not in named and "fay" not in named


def test_no_other_pair_comes_near_the_threshold(klass):
    """Every figure the report did not list is at least MARGIN below the threshold (not a near miss)."""
    _, handed, report = klass
    given = cp._given(EXERCISE)
    prints = {(h.student, r): fingerprint(tokens(c), given) for h in handed for r, c in h.code.items()}
    listed = {(m.student, m.other) for m in report.matches if m.source == "classmate"}
    for (a, ra), pa in prints.items():
        for (b, rb), pb in prints.items():
            if a < b and ra == rb and (a, b) not in listed:
                assert max(similarity(pa, pb)[0], similarity(pb, pa)[0]) <= cp.LEVEL - MARGIN, (a, b, ra)
    lectures = cp.lecture_library(cp.PACKAGE.parent / "notebooks")
    for (student, region), p in prints.items():
        for kind, lib in (("package", cp.package_library()), ("lecture", lectures)):
            if (student, kind) not in {(m.student, m.source) for m in report.matches}:
                assert lib.match(p)[0] <= cp.LEVEL - MARGIN, (student, region, kind)


def test_a_zip_of_the_package_is_reported_with_what_it_holds(klass):
    _, handed, report = klass
    assert [s for s, _, _ in report.carried] == ["gus", "gus"]
    notes = " ".join(n for _, _, n in report.carried)
    assert "zip archive of 3 files: puma_course/kinematics/puma560.py" in notes and "b64decode" in notes
    hidden = [m for m in report.matches if m.student == "gus"]
    assert any("Puma560.ik" in m.other and m.share >= cp.LEVEL + MARGIN for m in hidden), hidden


def test_images_are_passed_over_and_a_blob_in_an_attachment_is_not():
    png = base64.b64encode(b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 12).decode()
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        z.writestr("pkg/| x ![i](http://evil.example/p.png).py", "def f(x):\n    return x\n" * 300)
    blob = base64.b64encode(buf.getvalue()).decode()
    nb = {
        "cells": [
            {"cell_type": "code", "source": "x = 1", "metadata": {}, "outputs": [{"data": {"image/png": png}}]},
            {
                "cell_type": "markdown",
                "source": "sketch",
                "metadata": {},
                "attachments": {"a.png": {"image/png": blob}},
            },
        ]
    }
    notes, found = payloads(nb)
    assert len(notes) == 1 and notes[0].startswith("cell 1 attachments: ") and "a zip archive of 1 file" in notes[0]
    assert len(found) == 1
    report = cp.CopyReport(carried=[("eve|x", EXERCISE, notes[0])])
    text = "\n".join(cp.copies_section(report))
    assert "`` eve\\|x ``" not in text and "`eve\\|x`" in text  # a table's pipe escaped, inside a code span
    assert "`cell 1 attachments: " in text  # the member name (a link) only inside a code span


def test_reaching_into_the_graders_objects_is_listed_and_plain_code_is_not():
    """The reviewer's q4 answer (the tripwire's saved ufunc read through a closure and ctypes) and gc reaches."""
    reach = (
        "def relative_pose(T_a, T_b):\n    import ctypes\n    w = np.linalg._umath_linalg.inv\n"
        "    addr = [c.cell_contents for c in w.__closure__ if isinstance(c.cell_contents, int)][0]\n"
        "    return ctypes.cast(addr, ctypes.py_object).value(T_a, signature='d->d') @ T_b\n"
    )
    sources = [reach, "import gc\nobs = gc.get_referents(f)\n", "x = getattr(f, '__closure__')", "y = np.eye(3)\n"]
    nb = {"cells": [{"cell_type": "code", "source": s, "metadata": {}, "outputs": []} for s in sources]}
    notes, found = payloads(nb)
    assert notes == [
        "cell 0: reaches into objects with __closure__, cast, cell_contents, ctypes, py_object "
        "(read it: no tripwire sees this)",
        "cell 1: reaches into objects with get_referents (read it: no tripwire sees this)",
        "cell 2: reaches into objects with __closure__ (read it: no tripwire sees this)",
    ]
    assert found == []


def test_a_notebook_that_is_not_json_gives_nothing_and_never_raises():
    h = cp.handed(b"\xff{not json", EXERCISES[EXERCISE], "zed")
    assert h.code == {} and h.carried == []
    deep = json.dumps({"cells": [{"cell_type": "code", "source": "x", "metadata": {}, "outputs": [[[[[["a"]]]]]]}]})
    assert cp.handed(deep.encode(), EXERCISES[EXERCISE], "zed").code == {"setup": "x"}
    odd = [{"cells": {"a": 1}}, {"cells": [{"cell_type": "code", "source": {"x": 1}, "metadata": []}]}, [1, 2], "x"]
    for nb in odd:
        assert isinstance(cp.handed(json.dumps(nb).encode(), EXERCISES[EXERCISE], "zed"), cp.Handed)
    nested = "".join(f"v{i} = {i * 7919 % 10007}\n" for i in range(3000)).encode()
    for _ in range(60):  # a gzip of a gzip of ... : read within its bounds, not run
        nested = gzip.compress(nested)
    cell = {"cell_type": "code", "source": f"B = '{base64.b64encode(nested).decode()}'", "metadata": {}}
    h = cp.handed(json.dumps({"cells": [cell]}).encode(), EXERCISES[EXERCISE], "zed")
    assert h.carried and "gzip stream" in h.carried[0], h.carried


def test_without_copydetect_the_summary_says_so_and_grading_goes_on(monkeypatch, klass):
    _, handed, _ = klass
    real = cp.importlib.util.find_spec
    monkeypatch.setattr(cp.importlib.util, "find_spec", lambda name: None if name == "copydetect" else real(name))
    report = cp.find_copies(handed)
    assert report.matches == [] and "copydetect is missing" in report.notes[0]
    assert "copydetect is missing" in "\n".join(cp.copies_section(report))


def test_grading_writes_the_report_in_the_summary_and_keeps_every_mark(klass, tmp_path, monkeypatch):
    folder, _, _ = klass
    with_report = grade(folder, tmp_path / "with.csv", exercises=[EXERCISE], jobs=2, seed=7)
    summary = (tmp_path / "with-summary.md").read_text(encoding="utf-8")
    assert "## Possible copies (" in summary and "marks unchanged" in summary
    for line in ("| `q1` | `ann` | a classmate's answer | `ben` |", "| `q2` | `cat` | the package's source |"):
        assert line in summary, summary[-2000:]
    monkeypatch.setattr(runner, "find_copies", lambda kept: None)
    without = grade(folder, tmp_path / "without.csv", exercises=[EXERCISE], jobs=2, seed=7)
    assert "Possible copies" not in (tmp_path / "without-summary.md").read_text(encoding="utf-8")
    assert [(r.student, r.scores, r.status) for r in with_report] == [(r.student, r.scores, r.status) for r in without]
    marks = {r.student: sum(r.scores.values()) for r in with_report}
    assert marks["fay"] == 0 and marks["eve"] == 5 and marks["ann"] == 7  # honest q1 + q3, blank, the solution's
