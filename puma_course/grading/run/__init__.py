"""Running a submission: stage the worker and the student-side package, run it sandboxed and limited, collect events.

:mod:`.runner` (``grade``, ``grade_notebook``), :mod:`.run_checks`, :mod:`.notebook_run`, :mod:`.child`,
:mod:`.monitor`, :mod:`.sandbox` (with :mod:`.scratch` and :mod:`.asuser`), :mod:`.limits` (with :mod:`.groups`,
:mod:`.delegation`, :mod:`.cgroupfs`), :mod:`.stage`, :mod:`.events` (what came back, judged against the plan),
:mod:`.worker` (copied into the stage) and :mod:`.student`. The submissions are read by :mod:`..intake`.
"""
