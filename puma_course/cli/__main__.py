"""``python -m puma_course.cli``: the ``puma-course`` command (as the installed script runs it)."""

from __future__ import annotations

import sys

from . import main

if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
