"""What the instructor hands out: :mod:`.release` (``exercises/`` from ``solutions/``, with :mod:`.notebook_json`),
:mod:`.edition` (the student edition) with :mod:`.public` (its self-check's public cases as data), and
:mod:`.gradescope` (the autograder zip) with :mod:`.gradescope_run` (the run inside Gradescope's container)."""
