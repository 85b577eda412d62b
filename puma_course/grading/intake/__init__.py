"""Reading what students handed in, without trusting it.

:mod:`.submissions` reads ``SUBMISSIONS/<student>/<exercise>.ipynb`` without following links; :mod:`.collect`
reads a learning platform's download (Canvas, Moodle) as students and notebooks.
"""
