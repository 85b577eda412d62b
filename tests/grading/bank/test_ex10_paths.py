"""Exercise 10's paths (q3): drawn with batched inverse kinematics, the same paths as before for the same key.

``tests/fixtures/ex10_paths_main.json`` holds what main 346a31c drew, solving each pose with ``arm.ik`` in the
rejection loop of ``puma_paths`` (saved before the change): the public cases, and the hidden cases of three keys
x three students and of three public seeds, each path summed up by its length, tool offset d, start q0, first
and last pose and the sum of all its entries. The batched solve must keep every accept/reject decision, so every
draw after it is the same too. And the bank draws nothing when it is imported.
"""

from __future__ import annotations

import json
import zlib

import numpy as np
import pytest

from puma_course.grading import EXERCISES
from puma_course.grading.secret import Secret
from tests.support import ROOT

SAVED = json.loads((ROOT / "tests" / "fixtures" / "ex10_paths_main.json").read_text(encoding="utf-8"))


def _summary(case) -> dict:
    path, q0, d = case
    path = np.asarray(path)
    return {"n": int(path.shape[0]), "d": float(d), "q0": np.asarray(q0).tolist(), "first": path[0].ravel().tolist(),
            "last": path[-1].ravel().tolist(), "sum": float(np.sum(path))}  # fmt: skip


def _same(got: list[dict], saved: list[dict]) -> None:
    assert [g["n"] for g in got] == [s["n"] for s in saved]  # a changed decision changes every later draw
    for g, s in zip(got, saved, strict=True):
        for field in ("d", "q0", "first", "last", "sum"):
            np.testing.assert_allclose(g[field], s[field], rtol=1e-12, atol=1e-12, err_msg=field)


def _q3():
    return EXERCISES["ex10_trajectories"].question("q3")


def test_the_public_paths_are_the_ones_drawn_before():
    _same([_summary(c) for c in _q3().public], SAVED["public"])


@pytest.mark.parametrize("entry", SAVED["cases"], ids=lambda e: f"key{e['key']}-{e['student']}" if "key" in e else
                         f"seed{e['seed']}")  # fmt: skip
def test_the_hidden_paths_of_a_key_and_student_are_the_ones_drawn_before(entry):
    if "key" in entry:
        seed = Secret(bytes([entry["key"]]) * 32).case_seed(entry["student"], "ex10_trajectories", "q3")
    else:
        seed = [entry["seed"], zlib.crc32(b"ex10_trajectories:q3")]  # as make_plan seeds a public key
    _same([_summary(c) for c in _q3().hidden(np.random.default_rng(seed))], entry["cases"])


def test_the_saved_draws_cover_several_keys_students_and_seeds():
    keys = {(e["key"], e["student"]) for e in SAVED["cases"] if "key" in e}
    assert len(keys) == 9 and len({k for k, _ in keys}) == 3 and len({e["seed"] for e in SAVED["cases"] if "seed" in e})
    assert all(len(e["cases"]) == 3 for e in SAVED["cases"]) and len(SAVED["public"]) == 2


def test_loading_the_bank_draws_no_path():
    import subprocess
    import sys

    code = (
        "from puma_course.grading import load_bank, EXERCISES\n"
        f"load_bank({str(ROOT)!r})\n"
        "p = EXERCISES['ex10_trajectories'].question('q3').public\n"
        "print(p._cases is None, len(p), p._cases is not None)"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.stdout.split() == ["True", "2", "True"], done.stdout + done.stderr
