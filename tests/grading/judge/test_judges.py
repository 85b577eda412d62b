"""Modelling questions are graded for what is right: any valid DH table passes, a standard-DH one does not.

For every frame-assignment question, two (or three) different valid tables, worked out by hand with
different choices of the intermediate frames, earn the points; the same frames written as a standard-DH
table fail with a message saying so. Solution sets pass in any order. Malformed answers get a reason.
"""

from __future__ import annotations

import numpy as np
import pytest

from puma_course.grading import EXERCISES
from puma_course_bank._reference import chains

H, PI = np.pi / 2, np.pi


def verdict(name, qid, got, *args):
    q = EXERCISES[name].question(qid)
    return q.judge(got, q.reference(*args), args)


def standard(table):
    """The same frames written as a standard-DH table: α and a move up one row (lecture 02 §5)."""
    t = np.array(table, dtype=float)
    t[:, 0], t[:, 1] = np.r_[t[1:, 0], 0.0], np.r_[t[1:, 1], 0.0]
    return t


def rrp_tables(h, d2):
    return {
        "x1 along x0": [[0, 0, 0, h, 0], [H, 0, H, -d2, 0], [H, 0, 0, 0, 1]],
        "x1 along -x0": [[0, 0, PI, h, 0], [-H, 0, -H, -d2, 0], [H, 0, 0, 0, 1]],
        "x2 down": [[0, 0, 0, h, 0], [H, 0, -H, -d2, 0], [-H, 0, PI, 0, 1]],
    }


def puma_tables(a2, a3, d3, d4, h, d6):
    lecture = [[0, 0, 0, h, 0], [-H, 0, -H, 0, 0], [0, a2, -H, d3, 0], [-H, a3, 0, d4, 0], [H, 0, 0, 0, 0],
               [-H, 0, 0, d6, 0]]  # fmt: skip
    x1_flipped = [[0, 0, PI, h, 0], [H, 0, H, 0, 0], *lecture[2:]]
    x5_flipped = [*lecture[:4], [H, 0, PI, 0, 0], [H, 0, PI, d6, 0]]
    return {"lecture's frames": lecture, "x1 along -x0": x1_flipped, "x5 reversed": x5_flipped}


def rail_tables(c, d1, a1, a2, a3, d5):
    mk3 = [[H, a1, 0, 0, 0], [0, a2, 0, 0, 0], [0, a3, 0, 0, 0], [H, 0, 0, d5, 0]]
    return {
        "x1 along x0": [[-H, 0, 0, 0, 1], [H, 0, 0, c + d1, 0], *mk3],
        "x1 along -x0": [[-H, 0, PI, 0, 1], [-H, 0, PI, c + d1, 0], *mk3],
    }


def porter_tables(l1, l3, l4):
    rest = [[H, 0, 0, 0, 1], [-H, 0, -H, 0, 0], [H, 0, H, -l3, 0], [H, 0, 0, l4, 0]]
    return {
        "x1 along x0": [[0, 0, 0, l1, 0], [-H, 0, H, 0, 0], *rest],
        "x1 along -x0": [[0, 0, PI, l1, 0], [H, 0, -H, 0, 0], *rest],
    }


CASES = [
    ("ex02_dh_frames", "q3", rrp_tables, (0.8, 0.2)),
    ("ex03_puma_fk", "q2", puma_tables, (0.4318, 0.0203, 0.15005, 0.4318, 0.6604, 0.056)),
    ("ex04_mk3_fk", "q3", rail_tables, (450.0, 360.0, 135.0, 250.0, 215.0, 100.0)),
    ("ex05_porter_fk", "q3", porter_tables, (1.0, 0.5, 0.3)),
]
IDS = [c[0] for c in CASES]


@pytest.mark.parametrize(("name", "qid", "tables", "args"), CASES, ids=IDS)
def test_different_valid_tables_for_the_same_mechanism_all_pass(name, qid, tables, args):
    found = tables(*args)
    assert len(found) >= 2
    rows = [np.array(t, dtype=float) for t in found.values()]
    for i, a in enumerate(rows):  # really different tables, not one written twice
        for b in rows[i + 1 :]:
            assert np.max(np.abs(np.angle(np.exp(1j * (a[:, [0, 2]] - b[:, [0, 2]]))))) > 1.0
    for label, table in found.items():
        v = verdict(name, qid, table, *args)
        assert v.passed, (label, v.reason)
    # ... on the hidden lengths too: the tables are functions of the arguments
    q = EXERCISES[name].question(qid)
    for hidden in q.hidden(np.random.default_rng(7)):
        for label, table in tables(*hidden).items():
            assert q.judge(table, q.reference(*hidden), hidden).passed, (label, hidden)


#: Where frame {0}'s z axis is joint 1's (α_0 = a_0 = 0), the same frames have a standard-DH table; on the rail
#: joint 1 slides along y0, and standard DH, whose z_0 is joint 1's axis, cannot start at the question's {0}.
STANDARD_CASES = [c for c in CASES if c[0] != "ex04_mk3_fk"]


@pytest.mark.parametrize(("name", "qid", "tables", "args"), STANDARD_CASES, ids=[c[0] for c in STANDARD_CASES])
def test_the_same_frames_as_a_standard_dh_table_fail_saying_so(name, qid, tables, args):
    table = next(iter(tables(*args).values()))
    v = verdict(name, qid, standard(table), *args)
    assert not v.passed and v.mistake == "standard_dh", v
    assert "standard-DH" in v.reason and "modified DH" in v.reason


def test_the_judge_is_not_fooled_by_a_table_that_is_right_at_q_zero():
    # the RRP arm with joint 1's axis displaced along x0 and the displacement undone by a1: right at q = 0 only
    table = [[0, 0.3, 0, 0.8, 0], [H, -0.3, H, -0.2, 0], [H, 0, 0, 0, 1]]
    q = EXERCISES["ex02_dh_frames"].question("q3")
    expected = q.reference(0.8, 0.2)
    zero = np.zeros((1, 3))
    assert np.allclose(chains.table_fk(table, zero), expected["fk"](zero))  # the crafted table is right at q = 0
    v = q.judge(table, expected, (0.8, 0.2))
    assert not v.passed and v.mistake == "only_at_zero" and "right pose at q = 0" in v.reason


@pytest.mark.parametrize(
    ("got", "words"),
    [
        ("a table", "table of numbers"),
        ([[0, 0, 0, 0.8, 0], [H, 0, H, -0.2, 0]], "shape (3, 5)"),
        ([[0, 0, 0, 0.8], [H, 0, H, -0.2], [H, 0, 0, 0]], "σ_i too"),
        ([[0, 0, 0, 0.8, 0], [H, 0, H, -0.2, 0], [H, 0, 0, 0, 2]], "σ must be 0"),
        ([[0, 0, 0, 0.8, 0], [H, 0, H, np.nan, 0], [H, 0, 0, 0, 1]], "table of numbers"),
        ([[0, 0, 0, 1e300, 0], [H, 0, H, -0.2, 0], [H, 0, 0, 0, 1]], "cannot be evaluated"),
    ],
    ids=["text", "rows", "columns", "sigma", "nan", "overflow"],
)
def test_a_malformed_table_gets_a_reason(got, words):
    v = verdict("ex02_dh_frames", "q3", got, 0.8, 0.2)
    assert not v.passed and words in v.reason, v


def test_ik_answers_are_sets_any_order_any_whole_turn():
    name = "ex09_puma_ik"
    q = EXERCISES[name].question("q2")
    for args in q.cases(np.random.default_rng(11)):
        expected = q.reference(*args)
        S = np.asarray(q.right_answer(*args))
        shuffled = S[np.random.default_rng(1).permutation(len(S))] + 2 * np.pi * np.array([1, 0, -1, 0, 0, 2])
        assert q.judge(shuffled, expected, args).passed
        assert not q.judge(S[:-1], expected, args).passed


def test_the_nearest_accepts_any_whole_turn_and_a_single_row():
    # ex09 q3 and ex06 q4 (the nearest solution) were replaced (issue 22): the judge on ex09 q3's public case
    import puma_course_bank._reference.motion as motion
    from puma_course.grading.judge.judges import nearest_judge

    L = (0.4318, 0.0203, 0.15005, 0.4318)
    T = motion.puma_fk(np.radians([30.0, -50.0, 20.0, 40.0, 60.0, -30.0]), *L)
    q_ref = np.array([3.1, 1.0, 2.9, -3.1, 2.4, 0.9])
    args, judge = (T, q_ref, *L), nearest_judge()
    expected = motion.puma_nearest_expected(*args)
    S = np.asarray(expected["solutions"])
    d = np.angle(np.exp(1j * (S - q_ref)))
    best = S[np.argmin(np.sum(d * d, 1))]
    assert judge(best + 2 * np.pi, expected, args).passed and judge(best[None], expected, args).passed
    assert "one configuration" in judge(np.vstack([best, best]), expected, args).reason
