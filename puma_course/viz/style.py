"""The course's figure style: readable on a projector, the same in every lecture.

``use_course_style()`` (each lecture's first code cell calls it) sets matplotlib's defaults:
figures drawn at 110 dpi, fonts of 11 pt (legends 10 pt, never below 9), ticks that leave room
for each other, constrained layout so labels are not clipped, and no memory of the previous
figure's size. Animations keep their own ``dpi`` argument (see :func:`~.arms.animate_frames`).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

import matplotlib as mpl

__all__ = ["COURSE_STYLE", "PROJECTOR_STYLE", "use_course_style", "use_projector_style", "projector_style"]

#: Colour of a common normal, a and α (link parameters); of d and θ (joint parameters): the DH drawings
#: (:mod:`.dh_figures`, :mod:`.dimensions`).
NORMAL_COLOR, JOINT_COLOR = "tab:purple", "tab:brown"
#: How the DH drawings draw a joint axis (a dashed grey line): keyword arguments of ``ax.plot``.
AXIS_LINE: dict[str, Any] = dict(ls="--", lw=1.2, color="0.35")

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


#: the course style for a lecture hall: about 1.5 times the fonts and lines, read from the back row of a
#: room whose projector shows a 1216-px-wide figure strip (:func:`use_projector_style`, :func:`projector_style`)
PROJECTOR_STYLE: dict[str, Any] = {
    **COURSE_STYLE,
    "font.size": 16,
    "axes.titlesize": 17,
    "axes.labelsize": 16,
    "xtick.labelsize": 14,
    "ytick.labelsize": 14,
    "legend.fontsize": 14,
    "lines.linewidth": 3.0,
    "lines.markersize": 8,
    "axes.linewidth": 1.5,
    "xtick.major.width": 1.5,
    "ytick.major.width": 1.5,
    "grid.linewidth": 1.2,
}


def use_projector_style() -> None:
    """Switch every following figure to :data:`PROJECTOR_STYLE` (larger fonts, thicker lines): one call.

    Call it instead of :func:`use_course_style` (or after it) when teaching from the notebooks on a
    projector; ``use_course_style()`` switches back.

    >>> use_projector_style()
    >>> import matplotlib as mpl
    >>> mpl.rcParams["font.size"] >= 16 and mpl.rcParams["lines.linewidth"] >= 3
    True
    >>> use_course_style()
    """
    params: Any = mpl.rcParams
    params.update(PROJECTOR_STYLE)


@contextlib.contextmanager
def projector_style() -> Iterator[None]:
    """The projector style for the figures drawn inside a ``with`` block; the style before it comes back after.

    >>> import matplotlib as mpl
    >>> with projector_style():
    ...     mpl.rcParams["font.size"]
    16.0
    """
    params: Any = PROJECTOR_STYLE  # matplotlib types its keys as literals (see use_course_style)
    with mpl.rc_context(params):
        yield
