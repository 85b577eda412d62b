"""Joint paths and joint speeds drawn for a projector: angles and lengths on separate axes (lecture 10).

A joint path of an arm with a prismatic joint mixes units: Porter's stroke q2 is a length, its
other joints are angles. Drawn on one "degrees" axis, the length is meaningless (and usually a flat
line near zero). :func:`joint_path_figure` gives the angles their own axes (degrees, or degrees per
second) and the lengths theirs (the robot's unit, or that unit per second), one column of panels per
path with the same scale across columns (so "nearest" and "naive" compare at a glance), one colour
per joint in every panel, and one legend outside the axes, at the course's legend size, so it never
hides a curve.

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import numpy as np
>>> q = np.column_stack([np.linspace(0.0, np.pi / 2, 5), np.linspace(1.0, 2.0, 5)])  # an angle and a length
>>> fig, axes = joint_path_figure(q, revolute=[True, False], names=["α1", "q2"], units="m")
>>> axes.shape, axes[0, 0].get_ylabel(), axes[1, 0].get_ylabel()
((2, 1), 'joint angle [deg]', 'joint length [m]')
>>> [round(float(v), 6) for v in axes[0, 0].lines[0].get_ydata()]  # the angle in degrees
[0.0, 22.5, 45.0, 67.5, 90.0]
>>> import matplotlib.pyplot as plt; plt.close(fig)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import matplotlib as mpl
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from .._validate import as_array, as_mask
from ..kinematics.trajectories import unwrap

__all__ = [
    "JOINT_COLORS",
    "JOINT_LINESTYLES",
    "JOINT_MARKERS",
    "MIN_LEGEND_SIZE",
    "joint_path_figure",
    "joint_axis_labels",
]

#: One colour per joint index, the same in every panel (matplotlib's tab10 cycle).
JOINT_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
                "tab:pink", "tab:gray", "tab:olive", "tab:cyan")  # fmt: skip

#: One line style and one marker per joint index besides its colour, so curves that lie on top of each
#: other (θ4 and θ6 near a wrist singularity) and readers who do not tell colours apart still separate
#: them. No style is dashed: across the course a dashed line means a joint axis.
JOINT_LINESTYLES = ("-", "-.", ":", "-", "-.", ":", "-", "-.", ":", "-")
JOINT_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "<", ">")
#: markers per curve (spread evenly; each joint's start offset so markers of coinciding curves do not coincide)
MARKERS_PER_CURVE = 8

#: The smallest legend text, in points, that a projector shows legibly.
MIN_LEGEND_SIZE = 9.0


def joint_axis_labels(units: str = "", speed: bool = False) -> tuple[str, str]:
    """The y labels of the angle axis and of the length axis, with their units.

    >>> joint_axis_labels("m")
    ('joint angle [deg]', 'joint length [m]')
    >>> joint_axis_labels("", speed=True)  # a unitless length (Porter's chain) per second
    ('joint speed [deg/s]', 'joint speed [1/s]')
    """
    if not isinstance(units, str):
        raise ValueError(f"units: expected the robot's length unit as a text ('m', 'mm', ''), got {units!r}")
    if speed:
        return "joint speed [deg/s]", f"joint speed [{units}/s]" if units else "joint speed [1/s]"
    return "joint angle [deg]", f"joint length [{units}]" if units else "joint length (unitless)"


def _as_paths(paths: Any) -> list[np.ndarray]:
    """One path (n, m) or a sequence of paths, each (n_k, m), as a list of float arrays."""
    if isinstance(paths, np.ndarray) or (isinstance(paths, Sequence) and len(paths) and np.ndim(paths[0]) == 1):
        items = [paths]
    elif isinstance(paths, Sequence) and not isinstance(paths, str) and len(paths):
        items = list(paths)
    else:
        raise ValueError(f"paths: expected a joint path of shape (n, m) or a list of them, got {paths!r:.60}")
    out = [
        as_array(p, "paths" if len(items) == 1 else f"paths[{k}]", (None, None), what="a joint path of shape (n, m)")
        for k, p in enumerate(items)
    ]
    m = out[0].shape[1]
    for k, p in enumerate(out):
        if p.shape[0] < 1 or p.shape[1] != m:
            raise ValueError(f"paths[{k}]: expected a joint path of shape (n, {m}) like the first, got {p.shape}")
    return out


def joint_path_figure(
    paths: Any,
    *,
    revolute: Any = None,
    names: Sequence[str] | None = None,
    x: Any = None,
    xlabel: str | None = None,
    units: str = "",
    titles: Sequence[str] | None = None,
    joints: Sequence[int] | None = None,
    speed: bool = False,
    figsize: tuple[float, float] | None = None,
    suptitle: str | None = None,
) -> tuple[Figure, np.ndarray]:
    """Joint paths (or joint speeds), angles and lengths on separate axes; returns ``(fig, axes)``.

    ``paths`` is one array (n, m), a configuration per row, or a list of them: one column of
    panels each, titled by ``titles``, with the same y scale in every column. ``revolute`` (a
    boolean mask, default all True; pass ``robot.revolute``) says which columns are angles: they are
    unwrapped (no 2π jumps) and drawn in degrees on the top row; the lengths get a row of their own
    in ``units``. With ``speed=True`` the rows are joint speeds (radians per second in, degrees per
    second drawn; lengths per second) and nothing is unwrapped. ``x`` (n,) is the abscissa of every
    path (e.g. the times of a time scaling; ``xlabel`` then defaults to "time t [s]"), else the pose
    index. ``joints`` picks the joints drawn (default all); ``names`` has one text per joint
    (default θ1, θ2, ...). ``axes`` is a 2-D array, rows (angles, then lengths, those present) by
    columns (paths). One legend, outside the axes on the right (centred, clear of the title), at least
    :data:`MIN_LEGEND_SIZE` pt.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, axes = joint_path_figure([np.zeros((4, 2)), np.ones((4, 2))], titles=["a", "b"])
    >>> axes.shape, [ax.get_title() for ax in axes[0]], fig.legends[0].get_texts()[1].get_text()
    ((1, 2), ['a', 'b'], 'θ2')
    >>> import matplotlib.pyplot as plt; plt.close(fig)
    """
    Q = _as_paths(paths)
    m = Q[0].shape[1]
    rev = np.ones(m, dtype=bool) if revolute is None else as_mask(revolute, "revolute", m)
    if names is None:
        names = [f"θ{j + 1}" for j in range(m)]
    elif isinstance(names, str) or len(names) != m:
        raise ValueError(f"names: expected {m} texts (one per joint), got {names!r}")
    if joints is None:
        sel = list(range(m))
    else:
        sel = [int(j) for j in joints]
        if not sel or any(not 0 <= j < m for j in sel) or len(set(sel)) != len(sel):
            raise ValueError(f"joints: expected distinct joint indices in 0..{m - 1}, got {list(joints)!r}")
    if titles is not None and (isinstance(titles, str) or len(titles) != len(Q)):
        raise ValueError(f"titles: expected {len(Q)} texts (one per path), got {titles!r}")
    if x is not None:
        xs = as_array(x, "x", (None,), what="an abscissa of shape (n,), one value per row of the paths")
        for k, p in enumerate(Q):
            if p.shape[0] != xs.shape[0]:
                raise ValueError(f"x: expected {p.shape[0]} values (one per row of paths[{k}]), got {xs.shape[0]}")
    angle_label, length_label = joint_axis_labels(units, speed)
    rows = [(angle_label, [j for j in sel if rev[j]]), (length_label, [j for j in sel if not rev[j]])]
    rows = [r for r in rows if r[1]]

    ncol = len(Q)
    if figsize is None:
        figsize = (min(4.6 * ncol + 1.4, 14.0), 3.6 if len(rows) == 1 else 5.2)
    fig, axes = plt.subplots(
        len(rows), ncol, figsize=figsize, squeeze=False, sharex="col", sharey="row", layout="constrained",
        gridspec_kw={"height_ratios": [3, 2] if len(rows) == 2 else [1]},
    )  # fmt: skip
    handles: dict[int, Any] = {}
    for c, q in enumerate(Q):
        vals = q if speed else unwrap(q, rev)
        xc = np.arange(q.shape[0]) if x is None else xs
        for r, (label, js) in enumerate(rows):
            ax = axes[r, c]
            for j in js:
                y = np.degrees(vals[:, j]) if rev[j] else vals[:, j]
                n = len(y)
                step = max(1, n // MARKERS_PER_CURVE)
                (line,) = ax.plot(
                    xc, y, color=JOINT_COLORS[j % len(JOINT_COLORS)], label=names[j],
                    linestyle=JOINT_LINESTYLES[j % len(JOINT_LINESTYLES)], marker=JOINT_MARKERS[j % len(JOINT_MARKERS)],
                    markevery=((j * step) // max(1, len(js)) % step, step), markersize=5, markerfacecolor="white",
                )  # fmt: skip
                handles.setdefault(j, line)
            if c == 0:
                ax.set_ylabel(label)
            ax.margins(x=0.02, y=0.08)
        axes[-1, c].set_xlabel(xlabel or ("pose index along the path" if x is None else "time t [s]"))
        if x is None:
            axes[-1, c].xaxis.set_major_locator(MaxNLocator(integer=True))  # pose indices: whole numbers
        if titles is not None:
            axes[0, c].set_title(titles[c])
    size = max(MIN_LEGEND_SIZE, float(mpl.font_manager.FontProperties(size=mpl.rcParams["legend.fontsize"])
                                      .get_size_in_points()))  # fmt: skip
    order = [j for j in sel if j in handles]
    fig.legend([handles[j] for j in order], [names[j] for j in order], loc="outside right center", fontsize=size,
               handlelength=2.6)  # fmt: skip
    if suptitle:
        fig.suptitle(suptitle)
    return fig, axes
