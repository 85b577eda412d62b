"""Judging an answer: :mod:`.compare` (tolerances), :mod:`.diagnose` (named mistakes), :mod:`.judges`
(questions judged by equivalence) and :mod:`.bounds` (the size of an answer the grader reads)."""
