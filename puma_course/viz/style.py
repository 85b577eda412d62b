"""The course's figure style: readable on a projector, the same in every lecture.

``use_course_style()`` (each lecture's first code cell calls it) sets matplotlib's defaults:
figures drawn at 110 dpi, fonts of 11 pt (legends 10 pt, never below 9), ticks that leave room
for each other, constrained layout so labels are not clipped, and no memory of the previous
figure's size. Animations keep their own ``dpi`` argument (see :func:`~.arms.animate_frames`).
"""

from __future__ import annotations

from typing import Any

import matplotlib as mpl

__all__ = ["COURSE_STYLE", "use_course_style"]

#: matplotlib rcParams of the course (``plt.rcParams.update(COURSE_STYLE)``)
COURSE_STYLE: dict[str, Any] = {
    "figure.dpi": 110,
    "savefig.dpi": 110,
    "figure.figsize": (6.4, 4.4),
    "figure.constrained_layout.use": True,
    "font.size": 11,
    "axes.titlesize": 12,
    "axes.labelsize": 11,
    "xtick.labelsize": 10,
    "ytick.labelsize": 10,
    "legend.fontsize": 10,
    "legend.framealpha": 0.85,
    "axes.grid": False,
    "lines.linewidth": 2.0,
    "image.cmap": "viridis",
}


def use_course_style() -> None:
    """Apply :data:`COURSE_STYLE` to matplotlib (call once per notebook, before drawing).

    >>> use_course_style()
    >>> import matplotlib as mpl
    >>> mpl.rcParams["figure.dpi"] >= 100 and mpl.rcParams["legend.fontsize"] >= 9
    True
    """
    params: Any = mpl.rcParams  # matplotlib types its keys as literals; the style's keys are checked by the test
    params.update(COURSE_STYLE)
