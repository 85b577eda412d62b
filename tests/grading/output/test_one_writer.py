"""Only the one writer (:mod:`puma_course.grading.output.writer`) writes a run's files.

The marks module used to hold ``merge_csv`` and ``merge_feedback``, which read back the CSV and the feedback a run
had written and rewrote them with the written marks: called on their own they gave a feedback file whose total
differed from the gradebook's (issue 32). The marks now reach every file through the writer alone.
"""

from __future__ import annotations

import ast
import inspect

from puma_course.grading.output import marks


def test_the_marks_module_reads_marks_and_writes_no_file():
    assert not {"merge_csv", "merge_feedback"} & set(vars(marks))
    tree = ast.parse(inspect.getsource(marks))
    called = {n.func.id for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
    attrs = {n.func.attr for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)}
    assert "replace_atomically" not in called and not {"write_text", "write_bytes"} & attrs
