"""The split of a class into shards, and the shard files merge reads back (grading.shards).

The end-to-end check, two shards graded and merged against one run over the class, is in test_shard_merge.py.
"""

from __future__ import annotations

import json
import string

import pytest
from hypothesis import given
from hypothesis import strategies as st

from puma_course.grading.results import NotebookResult
from puma_course.grading.shards import Shard, ShardError, ShardFile, read_shard, read_shards, write_shard

NAMES = st.text(alphabet=string.ascii_letters + string.digits + "._-éø", min_size=1, max_size=20)


@pytest.mark.parametrize("text", ["", "1", "0/3", "4/3", "1/0", "a/b", "1/2/3", "-1/2", "1.5/2", " / "])
def test_a_bad_shard_is_refused_naming_what_came(text):
    with pytest.raises(ValueError, match="shard: expected") as exc:
        Shard.parse(text)
    assert repr(text) in str(exc.value) or text.strip().split("/")[0] in str(exc.value)


@given(st.lists(NAMES, min_size=1, max_size=40, unique=True), st.integers(1, 9))
def test_every_student_is_in_exactly_one_part(students, count):
    parts = [Shard(k, count).select(students) for k in range(1, count + 1)]
    assert sorted(s for part in parts for s in part) == sorted(students)


@given(st.lists(NAMES, min_size=2, max_size=40, unique=True), st.integers(2, 9))
def test_a_student_who_joins_moves_no_one_else(students, count):
    *before, late = students
    for k in range(1, count + 1):
        shard = Shard(k, count)
        assert [s for s in shard.select(students) if s != late] == shard.select(before)


def test_the_split_is_the_same_on_every_machine():
    # sha256 of the name, first 8 bytes big-endian, modulo N: worked out by hand with hashlib for these names
    import hashlib

    frozen = {"ann": 1, "bob": 1, "s0001": 1, "Zoë": 4}  # the parts of 5, fixed: a merge relies on them
    for name, part in frozen.items():
        h = int(hashlib.sha256(name.encode()).hexdigest()[:16], 16)
        assert [k for k in range(1, 6) if Shard(k, 5).owns(name)] == [h % 5 + 1] == [part]
    assert sum(Shard(1, 4).owns(f"s{i:04d}") for i in range(1000)) in range(200, 301)  # roughly a quarter


def _file(tmp_path, k, n, students, key="k1", version="0.3.0", name=None):
    results = tuple(
        NotebookResult(s, "ex01_rotations", "ok", 15.0, {"q1": 2.0, "q2": 0.5}, {"q1": ["1/1 cases pass"]}, ["n"], 0.25)
        for s in students
    )
    shard_file = ShardFile(Shard(k, n), key, version, ("ex01_rotations",), tuple(students), results)
    return write_shard(tmp_path / (name or f"shard-{k}-of-{n}.json"), shard_file)


def _split(n, names=("ann", "bob", "cy", "dee", "eve", "fay", "gus")):
    return [Shard(k, n).select(names) for k in range(1, n + 1)]


def test_a_shard_file_reads_back_what_was_written(tmp_path):
    parts = _split(2)
    path = _file(tmp_path, 1, 2, parts[0])
    back = read_shard(path)
    assert back.shard == Shard(1, 2) and back.students == tuple(parts[0]) and back.key == "k1"
    assert [r.scores for r in back.results] == [{"q1": 2.0, "q2": 0.5}] * len(parts[0])
    assert "k1" in path.read_text() and back.results[0].question_notes == {"q1": ["1/1 cases pass"]}


def test_shards_that_make_one_class_merge_sorted(tmp_path):
    parts = _split(3)
    paths = [_file(tmp_path, k + 1, 3, p) for k, p in enumerate(parts)]
    _, results = read_shards(list(reversed(paths)))
    assert [r.student for r in results] == sorted(s for p in parts for s in p)


def test_different_keys_are_refused_by_name(tmp_path):
    parts = _split(2)
    a = _file(tmp_path, 1, 2, parts[0], key="k1")
    b = _file(tmp_path, 2, 2, parts[1], key="k2")
    with pytest.raises(ShardError, match="different keys") as exc:
        read_shards([a, b])
    assert str(a) in str(exc.value) and str(b) in str(exc.value)


def test_different_course_versions_are_refused(tmp_path):
    parts = _split(2)
    a = _file(tmp_path, 1, 2, parts[0], version="0.3.0")
    b = _file(tmp_path, 2, 2, parts[1], version="0.2.0")
    with pytest.raises(ShardError, match="different course versions"):
        read_shards([a, b])


def test_overlapping_and_missing_shards_are_refused(tmp_path):
    parts = _split(3)
    a = _file(tmp_path, 1, 3, parts[0])
    again = _file(tmp_path, 1, 3, parts[0], name="copy.json")
    c = _file(tmp_path, 3, 3, parts[2])
    with pytest.raises(ShardError, match="overlapping shards.*part 1/3") as exc:
        read_shards([a, again, c])
    assert "copy.json" in str(exc.value)
    with pytest.raises(ShardError, match=r"missing shards: part\(s\) 2/3 of 3"):
        read_shards([a, c])
    other = _file(tmp_path, 2, 2, _split(2)[1])
    with pytest.raises(ShardError, match="different splits"):
        read_shards([a, other])


def test_a_student_in_the_wrong_part_or_in_two_is_refused(tmp_path):
    parts = _split(2)
    moved = parts[1][0]  # belongs to part 2
    twice = _file(tmp_path, 1, 2, parts[0] + [moved], name="twice.json")
    b = _file(tmp_path, 2, 2, parts[1])
    with pytest.raises(ShardError, match=f"student '{moved}' graded in two shards"):
        read_shards([twice, b])
    stray = _file(tmp_path, 1, 2, parts[0] + [moved], name="stray.json")
    rest = _file(tmp_path, 2, 2, parts[1][1:], name="rest.json")
    with pytest.raises(ShardError, match=f"student '{moved}' does not belong to part 1/2"):
        read_shards([stray, rest])


@pytest.mark.parametrize(
    ("change", "match"),
    [
        (lambda d: d.update(format="other/1"), "expected a shard file of format"),
        (lambda d: d.pop("key"), "missing or bad field"),
        (lambda d: d.update(results={}), "expected a list of results"),
        (lambda d: d["results"][0].update(scores={"q1": "2"}), "finite numbers"),
        (lambda d: d["results"][0].update(evil=1), "expected a result with the fields"),
        (lambda d: d["results"][0].update(student="zed"), "students the shard does not list"),
    ],
)
def test_a_damaged_shard_file_is_refused_naming_the_file(tmp_path, change, match):
    path = _file(tmp_path, 1, 1, ["ann"])
    data = json.loads(path.read_text())
    change(data)
    path.write_text(json.dumps(data))
    with pytest.raises(ShardError, match=match) as exc:
        read_shard(path)
    assert str(path) in str(exc.value)


def test_no_shards_and_unreadable_files_are_refused(tmp_path):
    with pytest.raises(ShardError, match="got none"):
        read_shards([])
    junk = tmp_path / "junk.json"
    junk.write_text("not json")
    with pytest.raises(ShardError, match="junk.json"):
        read_shard(junk)
    with pytest.raises(ShardError, match="nope.json"):
        read_shard(tmp_path / "nope.json")
