"""Shared pytest configuration.

Crafted student submissions and other fixture notebooks live under
``tests/fixtures``; they are inputs to the grading tests, not lectures, so
nbval must not collect them.
"""

from __future__ import annotations

import os

import matplotlib

# Only this (test) process draws off-screen. Do not export MPLBACKEND: nbval's kernels
# inherit the environment, and a kernel with MPLBACKEND=Agg shows no figures.
matplotlib.use("Agg")
os.environ.pop("MPLBACKEND", None)

collect_ignore_glob = ["fixtures/*", "fixtures/**/*"]
