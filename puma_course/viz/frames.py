"""Axes and coordinate frames: a 3-D axes with equal scaling, triads, polylines (matplotlib).

A frame is a 4x4 transform mapping its coordinates into the axes' (world) coordinates; its
triad is drawn as the columns of its rotation from its origin, x red, y green, z blue
(:data:`AXIS_COLORS`). Nothing here computes kinematics.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from .._validate import as_array
from .style import text_color

__all__ = [
    "AXIS_COLORS",
    "AXIS_LETTERS",
    "TRIAD_LETTERS",
    "new_axes",
    "set_equal",
    "frame_tightly",
    "draw_frame",
    "draw_frames",
    "triad_letters",
    "triad_key",
    "draw_points",
    "note_below",
]

#: Colours of a triad's x, y and z axes.
AXIS_COLORS = ("tab:red", "tab:green", "tab:blue")


def new_axes(
    figsize: tuple[float, float] = (6.0, 5.0),
    title: str | None = None,
    elev: float = 25,
    azim: float = -60,
    dpi: float | None = None,
) -> tuple[Figure, Any]:
    """A new figure with one 3-D axes; returns ``(fig, ax)``.

    Angles ``elev``/``azim`` in degrees (matplotlib's view); axes labelled x, y, z. Give ``dpi``
    here rather than later: ``plt.close`` resets a later ``set_dpi`` (matplotlib 3.11).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes(title="demo")
    >>> ax.name, ax.get_title(), ax.get_xlabel()
    ('3d', 'demo', 'x')
    >>> plt.close(fig)
    """
    fig = plt.figure(figsize=figsize, dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=elev, azim=azim)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    if title:
        ax.set_title(title)
    return fig, ax


def set_equal(ax: Any, points: Any | None = None, margin: float = 0.1) -> None:
    """Equal scaling on all three axes, framing ``points`` (..., 3) or what is drawn.

    The cube's half side is half the largest extent times ``1 + margin``. ``points`` may be
    any stack of points, e.g. ``robot.points(Q)`` for a batch Q (N, n).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> set_equal(ax, [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0]], margin=0.0)
    >>> [float(v) for v in ax.get_xlim3d()], [float(v) for v in ax.get_ylim3d()]
    ([0.0, 2.0], [-0.5, 1.5])
    >>> plt.close(fig)
    """
    if points is None:
        lims = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()])
    else:
        P = as_array(points, "points", what="points of shape (..., 3)")
        if P.ndim == 0 or P.shape[-1] != 3 or P.size == 0:
            raise ValueError(f"points: expected points of shape (..., 3), got an array of shape {P.shape}")
        P = P.reshape(-1, 3)
        lims = np.stack([P.min(axis=0), P.max(axis=0)], axis=1)
    centre = lims.mean(axis=1)
    half = max(float(np.max(lims[:, 1] - lims[:, 0])) / 2.0, 1e-9) * (1.0 + margin)
    ax.set_xlim3d(centre[0] - half, centre[0] + half)
    ax.set_ylim3d(centre[1] - half, centre[1] + half)
    ax.set_zlim3d(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))


def frame_tightly(ax: Any, points: Any, margin: float = 0.05, zoom: float = 1.0) -> None:
    """Equal scale on a 3-D axes whose box fits ``points`` (k, 3) (no cube: less white space than ``set_equal``)."""
    P = as_array(points, "points", (None, 3), what="points to frame, shape (k, 3)")
    lo, hi = P.min(axis=0), P.max(axis=0)
    half = np.maximum(hi - lo, 0.3 * float(np.max(hi - lo)) + 1e-12) * (0.5 + margin)
    mid = (lo + hi) / 2
    ax.set(xlim3d=(mid[0] - half[0], mid[0] + half[0]), ylim3d=(mid[1] - half[1], mid[1] + half[1]),
           zlim3d=(mid[2] - half[2], mid[2] + half[2]))  # fmt: skip
    ax.set_box_aspect(tuple(half), zoom=zoom)


#: the letters at the tips of a triad's axes, so a triad reads without its colours (issue 25)
AXIS_LETTERS = ("x", "y", "z")
#: whether :func:`draw_frame` writes them on a named frame by default (``letters=None``); an unnamed triad
#: (a ghost arm's, an animation's) stays bare, so the figures a reader must read are the ones lettered
TRIAD_LETTERS = True


def draw_frame(
    ax: Any,
    T: Any,
    label: str | None = None,
    length: float = 0.1,
    alpha: float = 1.0,
    lw: float = 2.0,
    letters: bool | None = None,
) -> list[Any]:
    """Draw one frame's triad (x red, y green, z blue) with an optional label ``{i}``.

    ``T`` maps the frame's coordinates into the axes' (world) coordinates: the triad's lines
    are the columns of its rotation, from its origin. Returns three lines, the label when given,
    then the letters x, y, z at the axes' tips (in the axes' colours) when ``letters`` is True
    (default: on a labelled frame, when :data:`TRIAD_LETTERS`), so a reader who does not tell red
    from green reads the axes.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> arts = draw_frame(ax, np.eye(4), label="{0}", length=1.0)
    >>> len(arts), arts[0].get_color(), [float(v) for v in arts[0].get_data_3d()[0]]
    (7, 'tab:red', [0.0, 1.0])
    >>> [a.get_text() for a in arts[4:]]
    ['x', 'y', 'z']
    >>> plt.close(fig)
    """
    T = as_array(T, "T", (4, 4))
    o = T[:3, 3]
    artists: list[Any] = []
    for k in range(3):
        e = o + length * T[:3, k]
        artists += ax.plot([o[0], e[0]], [o[1], e[1]], [o[2], e[2]], color=AXIS_COLORS[k], alpha=alpha, lw=lw,
                           gid=f"triad-{AXIS_LETTERS[k]}")  # fmt: skip
    if label:
        # a frame's name and letters stay opaque on a faint triad: a text keeps 4.5:1 (issue 34)
        artists.append(ax.text(*(o + 0.25 * length * (T[:3, 0] + T[:3, 1])), label, fontsize=9))
    if (TRIAD_LETTERS and bool(label)) if letters is None else letters:
        for k in range(3):
            tip = o + 1.18 * length * T[:3, k]
            artists.append(ax.text(*tip, AXIS_LETTERS[k], color=text_color(AXIS_COLORS[k]), fontsize=8,
                                   ha="center", va="center", fontweight="bold"))  # fmt: skip
    return artists


def draw_frames(ax: Any, frames: Any, labels: Sequence[str] | None = None, length: float = 0.1, **kw: Any) -> list[Any]:
    """Draw a triad for every frame in ``frames`` (k, 4, 4); labels default to {0}..{k-1}.

    Other keywords (``alpha``, ``lw``, ``letters``) go to :func:`draw_frame`; a labelled triad has its
    axes lettered.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> arts = draw_frames(ax, np.stack([np.eye(4)] * 2))
    >>> len(arts), [a.get_text() for a in arts if hasattr(a, "get_text")]
    (14, ['{0}', 'x', 'y', 'z', '{1}', 'x', 'y', 'z'])
    >>> len(draw_frames(ax, np.stack([np.eye(4)] * 2), letters=False))
    8
    >>> plt.close(fig)
    """
    F = as_array(frames, "frames", (4, 4), batch=True).reshape(-1, 4, 4)
    if labels is None:
        labels = [f"{{{i}}}" for i in range(len(F))]
    artists: list[Any] = []
    for T, lab in zip(F, labels, strict=False):
        artists += draw_frame(ax, T, lab, length=length, **kw)
    return artists


def triad_letters(
    ax: Any, T: Any, length: float, *, size: float = 10.0, names: Sequence[str] = AXIS_LETTERS
) -> list[Any]:
    """Labels x, y, z for the tips of the triad of ``T`` (length ``length``), to place with the figure's other labels.

    Each :class:`~puma_course.viz.labels.Label` sits at its axis' tip, in the axis' colour, and prefers the side
    its axis points to on the screen, so :func:`~puma_course.viz.labels.place_labels` puts it just beyond the
    tip unless another label or a line is there. Set the view and the limits first (the side is measured on
    the projected figure). ``names`` may carry subscripts, e.g. ``["$x_4$", "$y_4$", "$z_4$"]``.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes(elev=0, azim=-90)  # looking along +y: x points right, z up
    >>> [(lb.text, round(lb.prefer)) for lb in triad_letters(ax, np.eye(4), 1.0)[::2]]
    [('x', 0), ('z', 90)]
    >>> plt.close(fig)
    """
    from .labels import Label, screen_points

    T = as_array(T, "T", (4, 4))
    if len(names) != 3:
        raise ValueError(f"names: expected three texts (x, y, z), got {names!r}")
    o, tips = T[:3, 3], T[:3, 3] + float(length) * T[:3, :3].T
    S = ax.transData.transform(screen_points(ax, np.vstack([o, tips])))
    out = []
    for k in range(3):
        d = S[k + 1] - S[0]
        prefer = float(np.degrees(np.arctan2(d[1], d[0]))) % 360.0 if np.hypot(*d) > 1e-9 else 45.0
        out.append(Label(tips[k], names[k], AXIS_COLORS[k], prefer=prefer, size=size))
    return out


def triad_key(ax: Any, loc: str = "upper left", **kw: Any) -> Any:
    """A legend naming a triad's colours: x red, y green, z blue (solid lines), for figures with many bare triads.

    Where letters at every tip would clutter (a panel of six frames), the key says which colour is which
    axis; other keywords go to ``ax.legend``. Returns the legend.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> [t.get_text() for t in triad_key(ax).get_texts()]
    ['x axis', 'y axis', 'z axis']
    >>> plt.close(fig)
    """
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color=c, lw=2.5) for c in AXIS_COLORS]
    kw = {"fontsize": 9, "handlelength": 1.5, "framealpha": 0.85, "title": kw.pop("title", "triads"), **kw}
    return ax.legend(handles, [f"{n} axis" for n in AXIS_LETTERS], loc=loc, **kw)


def draw_points(
    ax: Any, points: Any, color: str = "0.3", lw: float = 4.0, alpha: float = 1.0, marker: str = "o", **kw: Any
) -> list[Any]:
    """Draw a polyline through points (k, 3), with a marker at each: the links of an arm.

    Other keywords (``label``, ``ls``, ...) go to ``ax.plot``. Returns the one line.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> (line,) = draw_points(ax, [[0, 0, 0], [1, 0, 0], [1, 1, 0]], color="k")
    >>> [float(v) for v in line.get_data_3d()[1]]
    [0.0, 0.0, 1.0]
    >>> plt.close(fig)
    """
    P = as_array(points, "points", (3,), batch=True).reshape(-1, 3)
    return list(ax.plot(P[:, 0], P[:, 1], P[:, 2], color=color, lw=lw, alpha=alpha, marker=marker, ms=lw + 2, **kw))


def note_below(fig: Any, ax: Any, note: str, gap_px: float = 4.0) -> None:
    """Write ``note`` under everything ``ax`` draws (tick numbers, axis labels): the figure grows downwards to hold it.

    The axes keep their size in pixels; the note never sits on the x label or its numbers.
    """
    fig.canvas.draw()  # lay the figure out once (constrained layout, 3-D axis labels), then keep it as laid out
    fig.set_layout_engine("none")
    text = fig.text(0.01, 0.0, note, fontsize=9, color="0.35", style="italic", ha="left", va="bottom")
    renderer = fig.canvas.get_renderer()
    text_h = text.get_window_extent(renderer).height
    drawn = ax.get_tightbbox(renderer)  # pixels from the figure's bottom left
    need = text_h + 2 * gap_px - drawn.y0  # pixels missing under the axes' lowest drawing
    if need > 0:
        dpi = fig.dpi
        w, h = fig.get_size_inches()
        box = ax.get_position()  # figure fractions of the old height
        h_new = h + need / dpi
        fig.set_size_inches(w, h_new)
        ax.set_position([box.x0, (box.y0 * h + need / dpi) / h_new, box.width, box.height * h / h_new])
    text.set_y(gap_px / (fig.get_size_inches()[1] * fig.dpi))
