"""Text on a figure that must not collide: labels beside points, and the tick numbers of a 3-D axes.

One placement rule serves every lecture's figure (the DH pictures of lectures 02-03, Porter's chain in
05-07): :func:`place_labels` puts each :class:`Label` beside its point, trying the sides nearest the
preferred one at growing distances, and takes the first side where the text stays inside the axes,
overlaps no label placed before, covers no other labelled point or ``avoid`` point and crosses no
polyline in ``lines``; :func:`label_points` is the same for named points; :func:`overlapping_labels`
checks a finished figure. For 3-D axes, :func:`tidy_axes` and :func:`fit_ticks` keep only as many tick
numbers as fit the view (:func:`tick_label_boxes` measures them). 3-D labels are placed for the view
they were drawn in: set the view and the limits first.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from matplotlib.ticker import FixedLocator, MaxNLocator

from .._validate import as_array, as_count
from .style import text_color

__all__ = ["Label", "place_labels", "label_points", "overlapping_labels", "tidy_axes", "fit_ticks",
           "tick_label_boxes", "screen_points"]  # fmt: skip

_BOX = dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8)
_SIDES = range(0, 360, 30)  # directions tried around a point, degrees (0 = right)
_RADII = (9.0, 16.0, 25.0, 36.0, 50.0, 66.0)  # distances tried, points, nearest first
_MARKER = 3.0  # a drawn point's marker reaches about this far (points)
_STEPS = [1, 2, 2.5, 5, 10]  # nice tick steps


@dataclass
class Label:
    """A text to place beside a 3-D (or 2-D) ``point``; ``prefer`` is the side tried first (degrees, 0 = right)."""

    point: Any
    text: str
    color: str = "black"
    prefer: float | None = None
    size: float | None = None


def _check_3d(ax: Any) -> None:
    if getattr(ax, "name", "") != "3d":
        raise ValueError(f"ax: expected a 3-D axes (projection='3d'), got {type(ax).__name__}")


def _screen(ax: Any, P: np.ndarray) -> np.ndarray:
    """Points (k, 3) or (k, 2) in the axes' 2-D data coordinates (projected for a 3-D axes)."""
    P = np.atleast_2d(P)
    if P.shape[1] == 2:
        return P
    V = np.column_stack([P, np.ones(len(P))]) @ np.asarray(ax.get_proj()).T  # homogeneous, as mplot3d projects
    return V[:, :2] / V[:, 3:4]


def screen_points(ax: Any, points: Any) -> np.ndarray:
    """Points (k, 3) (or (k, 2)) in the axes' 2-D data coordinates, projected as a 3-D axes draws them."""
    return _screen(ax, np.asarray(points, float))


def _area(a: Any, b: Any) -> float:
    w, h = min(a.x1, b.x1) - max(a.x0, b.x0), min(a.y1, b.y1) - max(a.y0, b.y0)
    return float(w * h) if w > 0 and h > 0 else 0.0


def _crosses(a: np.ndarray, b: np.ndarray, box: Any) -> bool:
    """Does the 2-D segment a-b (display units) pass through the Bbox ``box``? (sampled every few pixels)"""
    n = int(min(200, 2 + math.hypot(*(b - a)) / 3.0))
    return any(box.contains(*(a + t * (b - a))) for t in np.linspace(0.0, 1.0, n))


def place_labels(ax: Any, labels: Sequence[Label], *, avoid: Any = None, lines: Sequence[Any] = (),
                 fontsize: float = 11, draw: bool = True) -> list[Any]:  # fmt: skip
    """Put each label beside its point where it overlaps no label placed before; returns the annotations.

        Sides are tried nearest first (the preferred one, then the others around it) at growing
        distances; a side is taken when the text stays inside the axes, overlaps no earlier label (nor a tick
    number or an axis label),
        covers no other label's point or ``avoid`` point ((k, 3) or (k, 2)) and crosses none of the
        polylines in ``lines`` (each (m, 3) or (m, 2), e.g. the links). Where no side is free, the one
        that collides least wins. Call it after the view and limits are final; ``draw=False`` skips the
        first drawing of the figure (it settles the layout) when it was just drawn, e.g. labelling
        several axes of one figure in turn. The texts are annotations at the projected points (left out
        of the layout).

        >>> import matplotlib; matplotlib.use("Agg")
        >>> import matplotlib.pyplot as plt
        >>> fig, ax = plt.subplots()
        >>> ax.set(xlim=(0, 1), ylim=(0, 1))
        [(0.0, 1.0), (0.0, 1.0)]
        >>> texts = place_labels(ax, [Label([0.5, 0.5], "first"), Label([0.52, 0.5], "second")])
        >>> overlapping_labels(texts)
        []
        >>> plt.close(fig)
    """
    fig = ax.figure
    if draw:
        fig.canvas.draw()  # settle the layout and the projection before measuring
    renderer = fig.canvas.get_renderer()
    anchors = _screen(ax, np.array([np.asarray(lb.point, float) for lb in labels])) if labels else np.zeros((0, 2))
    keep_out = list(ax.transData.transform(anchors) if len(anchors) else anchors)
    if avoid is not None and np.size(avoid):
        keep_out += list(ax.transData.transform(_screen(ax, np.asarray(avoid, float))))
    segments = []
    for line in lines:
        d = ax.transData.transform(_screen(ax, np.asarray(line, float)))
        segments += [(d[k], d[k + 1]) for k in range(len(d) - 1)]
    frame, marker = ax.get_window_extent(renderer), _MARKER * fig.dpi / 72.0
    placed: list[Any] = _axis_texts(ax, renderer)  # tick numbers and axis labels count as placed labels
    out = []
    for k, lb in enumerate(labels):
        start = 45.0 if lb.prefer is None else lb.prefer
        sides = sorted(_SIDES, key=lambda a: min(abs(a - start) % 360, 360 - abs(a - start) % 360))
        best, best_score = None, np.inf
        ann = ax.annotate(lb.text, xy=anchors[k], xytext=(0, 0), textcoords="offset points", color=text_color(lb.color),
                          fontsize=lb.size or fontsize, bbox=_BOX, zorder=20, annotation_clip=False)  # fmt: skip
        ann.set_in_layout(False)
        for r in _RADII:
            for a in sides:
                c, s = np.cos(np.radians(a)), np.sin(np.radians(a))
                ann.set_position((r * c, r * s))
                ann.set_ha("left" if c > 0.35 else "right" if c < -0.35 else "center")
                ann.set_va("bottom" if s > 0.35 else "top" if s < -0.35 else "center")
                bb = ann.get_window_extent(renderer).padded(2.0)
                score = sum(_area(bb, p) for p in placed)
                score += 1e4 * sum(bool(bb.padded(marker).contains(*q)) for j, q in enumerate(keep_out) if j != k)
                score += 1e5 * (bb.x0 < frame.x0 or bb.x1 > frame.x1 or bb.y0 < frame.y0 or bb.y1 > frame.y1)
                score += 500.0 * sum(_crosses(p, q, bb) for p, q in segments)
                if score < best_score:
                    best, best_score = (r * c, r * s, ann.get_ha(), ann.get_va()), score
                if score == 0:  # the first free side at this distance
                    break
            if best_score == 0:
                break
        assert best is not None
        ann.set(position=best[:2], ha=best[2], va=best[3])
        placed.append(ann.get_window_extent(renderer).padded(2.0))
        out.append(ann)
    return out


def _tick_boxes(axis: Any, renderer: Any) -> list[Any]:
    """The window extents of an axis' tick numbers drawn inside the view."""
    (lo, hi), locs = sorted(axis.get_view_interval()), axis.get_majorticklocs()
    eps, ticks = 1e-9 * max(1.0, abs(hi - lo)), axis.get_major_ticks(len(locs))
    return [t.label1.get_window_extent(renderer) for loc, t in zip(locs, ticks, strict=True)
            if lo - eps <= loc <= hi + eps and t.label1.get_visible() and t.label1.get_text()]  # fmt: skip


def _axis_texts(ax: Any, renderer: Any) -> list[Any]:
    """The boxes of the tick numbers (inside the view) and the axis labels drawn on ``ax``."""
    out = []
    for axis in (ax.xaxis, ax.yaxis, *([ax.zaxis] if getattr(ax, "name", "") == "3d" else [])):
        out += [box.padded(1.0) for box in _tick_boxes(axis, renderer)]
        if axis.label.get_visible() and axis.label.get_text():
            out.append(axis.label.get_window_extent(renderer).padded(1.0))
    return out


def label_points(ax: Any, points: Any, names: Sequence[str], *, avoid: Sequence[Any] = (), fontsize: float = 10.0,
                 color: str | Sequence[str] = "k", first: Sequence[Label] = ()) -> list[Any]:  # fmt: skip
    """Label 3-D points (k, 3) with ``names`` so that no two labels overlap and no label hides a point.

    :func:`place_labels` for named points: empty names are skipped (their points are still kept
    free), ``avoid`` holds polylines (each (m, 3), e.g. the links) the labels should not cross,
    ``color`` is one colour or one per point. Call it last, when view and limits are set. Returns the
    annotations. Labels in ``first`` (e.g. a triad's letters, :func:`~puma_course.viz.frames.triad_letters`) are
    placed before the names, with them, and returned first.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from puma_course.viz.frames import set_equal
    >>> fig, ax = plt.figure(), plt.axes(projection="3d")
    >>> P = np.array([[0.0, 0.0, 0.0], [0.01, 0.0, 0.0], [1.0, 1.0, 1.0]]); set_equal(ax, P)
    >>> [a.get_text() for a in label_points(ax, P, ["a", "b", ""])]
    ['a', 'b']
    >>> plt.close(fig)
    """
    P = as_array(points, "points", (3,), batch=True, what="points of shape (k, 3)").reshape(-1, 3)
    if isinstance(names, str) or len(names) != len(P):
        raise ValueError(f"names: expected one text per point ({len(P)}), got {names!r}")
    colors = [color] * len(P) if isinstance(color, str) else [str(c) for c in color]
    if len(colors) != len(P):
        raise ValueError(f"color: expected one colour or one per point ({len(P)}), got {len(colors)}")
    lines = [as_array(a, "avoid", (3,), batch=True, what="polylines of shape (m, 3)").reshape(-1, 3) for a in avoid]
    named = [i for i, name in enumerate(names) if name]
    unnamed = P[[i for i, name in enumerate(names) if not name]]
    labels = list(first) + [Label(P[i], names[i], colors[i]) for i in named]
    return place_labels(ax, labels, avoid=unnamed, lines=lines, fontsize=fontsize)


def overlapping_labels(texts: Sequence[Any]) -> list[tuple[str, str]]:
    """The pairs of texts (matplotlib Text or annotations) whose boxes on the drawn figure overlap."""
    if not texts:
        return []
    fig = texts[0].figure
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(r) for t in texts]
    return [(texts[i].get_text(), texts[j].get_text()) for i in range(len(texts)) for j in range(i + 1, len(texts))
            if _area(boxes[i], boxes[j]) > 0]  # fmt: skip


def tidy_axes(ax: Any, *, nbins: int = 4, units: str = "", pad: float = 2.0) -> Any:
    """Make a 3-D axes readable: at most ``nbins`` + 1 ticks per axis, labels x, y, z (with ``units``).

    Tick numbers sit ``pad`` points from their axis; the box is drawn at zoom 0.9, which leaves room
    for the z label inside the figure.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig = plt.figure()
    >>> ax = tidy_axes(fig.add_subplot(projection="3d"), units="m")
    >>> fig.canvas.draw()
    >>> ax.get_xlabel(), len(tick_label_boxes(ax)["z"]) <= 5
    ('x [m]', True)
    >>> plt.close(fig)
    """
    _check_3d(ax)
    nbins = as_count(nbins, "nbins", minimum=2)
    unit = f" [{units}]" if units else ""
    for axis, name in ((ax.xaxis, "x"), (ax.yaxis, "y"), (ax.zaxis, "z")):
        axis.set_major_locator(MaxNLocator(nbins=nbins, steps=_STEPS))
        axis.set_tick_params(pad=pad)
        axis.set_label_text(name + unit)
        axis.labelpad = 4.0
    ax.set_box_aspect((1, 1, 1), zoom=0.9)
    return ax


def tick_label_boxes(ax: Any) -> dict[str, list[Any]]:
    """The window extents of the tick numbers drawn (inside the view) on each axis of a drawn 3-D axes."""
    renderer = ax.figure.canvas.get_renderer()
    return {name: _tick_boxes(axis, renderer) for name, axis in (("x", ax.xaxis), ("y", ax.yaxis), ("z", ax.zaxis))}


def _collide(boxes: Sequence[Any], others: Sequence[Any] = (), pad: float = 4.0) -> bool:
    padded = [b.padded(pad) for b in boxes]
    if any(a.overlaps(b) for i, a in enumerate(padded) for b in padded[i + 1 :]):
        return True
    return any(a.overlaps(b.padded(pad)) for a in padded for b in others)


def fit_ticks(ax: Any, max_bins: int = 4) -> Any:
    """Give each axis of a 3-D axes as many ticks (at most ``max_bins`` + 1) as fit without collisions.

    Call it after the view and the limits are set. The figure is drawn and each axis' tick numbers
    are compared, with each other and with the other axes' numbers; an axis whose numbers collide
    gets fewer ticks (down to its first and last one) and the figure is drawn again, until nothing collides.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from puma_course.viz.frames import set_equal
    >>> fig = plt.figure(figsize=(4.0, 3.6))
    >>> ax = fig.add_subplot(projection="3d")
    >>> ax.view_init(elev=5, azim=-2)  # the x axis is seen almost end on
    >>> set_equal(ax, [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]])
    >>> ax = fit_ticks(ax)
    >>> fig.canvas.draw()
    >>> len(tick_label_boxes(ax)["x"]), len(tick_label_boxes(ax)["y"])
    (2, 3)
    >>> plt.close(fig)
    """
    _check_3d(ax)
    max_bins = as_count(max_bins, "max_bins", minimum=2)
    axes, bins = {"x": ax.xaxis, "y": ax.yaxis, "z": ax.zaxis}, dict.fromkeys("xyz", max_bins)
    for axis in axes.values():
        axis.set_major_locator(MaxNLocator(nbins=max_bins, steps=_STEPS))
    while True:  # one drawing per round: every axis whose numbers collide loses a tick
        ax.figure.canvas.draw()
        boxes = tick_label_boxes(ax)
        bad = [k for k in axes if _collide(boxes[k], [b for j, v in boxes.items() if j != k for b in v])]
        if not bad or all(bins[k] == 1 for k in bad):
            break
        for k in bad:
            bins[k] -= 1
            if bins[k] >= 2:
                axes[k].set_major_locator(MaxNLocator(nbins=bins[k], steps=_STEPS))
            else:  # even three numbers collide: keep the first and the last tick only
                lo, hi = sorted(axes[k].get_view_interval())
                locs = [v for v in axes[k].get_majorticklocs() if lo <= v <= hi]
                axes[k].set_major_locator(FixedLocator([locs[0], locs[-1]] if len(locs) > 2 else locs))
    return ax
