"""Shared pytest configuration.

Crafted student submissions and other fixture notebooks live under
``tests/fixtures``; they are inputs to the grading tests, not lectures, so
nbval must not collect them.
"""

from __future__ import annotations

import os

import matplotlib

os.environ.setdefault("MPLBACKEND", "Agg")
matplotlib.use("Agg")

collect_ignore_glob = ["fixtures/*", "fixtures/**/*"]
