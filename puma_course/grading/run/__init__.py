"""Running a submission: read it, stage the worker and the student-side package, run it sandboxed, collect events.

:mod:`.runner` (``grade``, ``grade_notebook``), :mod:`.run_checks`, :mod:`.child`, :mod:`.sandbox`,
:mod:`.limits`, :mod:`.stage`, :mod:`.submissions`, :mod:`.collect`, :mod:`.events` (what came back,
judged against the plan), :mod:`.worker` (copied into the stage) and :mod:`.student`.
"""
