"""Figures of lecture 04, the Motoman MK3: the nearest attainable pose of goals it cannot reach.

:func:`plot_nearest_attainable` draws goals from above (each with its arm plane, the goal's approach dashed and
the nearest attainable one solid, a cross where it points straight down) and one goal's arm plane face on, with
the arm at two solutions of its nearest pose (:meth:`~puma_course.kinematics.mk3.MK3.nearest_attainable`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from .._validate import as_count, as_transform
from ..kinematics.mk3 import MK3

__all__ = ["plot_nearest_attainable", "ARROW"]

#: Length of the approach arrows (mm).
ARROW = 150.0
_COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple")


def _arrow(ax: Any, start: np.ndarray, d: np.ndarray, colour: str, dashed: bool) -> None:
    style = dict(arrowstyle="-|>", color=colour, lw=2.0 if dashed else 2.5, ls="--" if dashed else "-")
    ax.annotate("", xy=start + ARROW * d, xytext=start, arrowprops=style)


def plot_nearest_attainable(arm: MK3, goals: Sequence[Any], names: Sequence[str], *, face_on: int = 0) -> Figure:
    """Goals (4, 4) and their nearest attainable poses: from above, and goal ``face_on``'s arm plane face on.

    Left: the base axis, and per goal its tool point, its arm plane (dotted, through the base axis and the
    point), its approach's horizontal part dashed and the nearest attainable approach solid (a cross when that
    points straight down). Right: the arm plane of goal ``face_on`` seen face on, the arm at the first two
    solutions of its nearest pose and the new approach. Up to four goals; the face-on goal's nearest pose
    must be reachable and its tool point off the base axis.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.transforms import homogeneous, rotx
    >>> fig = plot_nearest_attainable(MK3(), [homogeneous(rotx(2.0), [400.0, 100.0, 300.0])], ["tilted"])
    >>> [ax.get_title() for ax in fig.axes]
    ['from above: goal dashed, nearest solid', 'tilted: nearest pose, face on']
    >>> plt.close(fig)
    """
    if not isinstance(arm, MK3):
        raise ValueError(f"arm: expected an MK3, got {type(arm).__name__}")
    Ts = [as_transform(T, f"goals[{i}]") for i, T in enumerate(goals)]
    if not 1 <= len(Ts) <= len(_COLOURS):
        raise ValueError(f"goals: expected 1 to {len(_COLOURS)} poses (4, 4), got {len(Ts)}")
    if isinstance(names, str) or len(names) != len(Ts) or not all(isinstance(n, str) for n in names):
        raise ValueError(f"names: expected {len(Ts)} strings, one per goal, got {names!r}")
    k = as_count(face_on, "face_on", maximum=len(Ts) - 1)
    near = [arm.nearest_attainable(T) for T in Ts]
    Tk, info = near[k]
    h_len = math.hypot(Tk[0, 3], Tk[1, 3])
    if not info.success or h_len == 0.0:
        why = info.reason or "its tool point is on the base axis (no arm plane to face)"
        raise ValueError(f"face_on: expected a goal whose nearest pose the arm reaches, got goal {k}: {why}")

    fig, (top, side) = plt.subplots(1, 2, figsize=(11, 4.8), gridspec_kw={"width_ratios": [1, 1.15]})
    seen = [np.zeros(2)]  # what the left panel must show: the base, the tool points, the arrows' tips
    for T, (T_att, _), colour, name in zip(Ts, near, _COLOURS, names, strict=False):
        p, zg, zn = T[:3, 3], T[:3, 2], T_att[:3, 2]
        seen += [p[:2], p[:2] + ARROW * zg[:2], p[:2] + ARROW * zn[:2]]
        top.plot([0.0, 1.5 * p[0]], [0.0, 1.5 * p[1]], ":", color=colour, lw=1.5)  # its arm plane
        top.plot(*p[:2], "o", color=colour, ms=8, label=name)
        _arrow(top, p[:2], zg[:2], colour, True)
        if math.hypot(zn[0], zn[1]) > 1e-9:
            _arrow(top, p[:2], zn[:2], colour, False)
        else:
            top.plot(*p[:2], "x", color=colour, ms=16, mew=2.5)  # the tool turned straight down
    top.plot(0.0, 0.0, "ks", ms=8, label="base axis")
    lo, hi = np.min(seen, axis=0) - 0.4 * ARROW, np.max(seen, axis=0) + 0.4 * ARROW
    top.set(aspect="equal", xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1] + ARROW), xlabel=f"x [{arm.units}]",
            ylabel=f"y [{arm.units}]", title="from above: goal dashed, nearest solid")  # fmt: skip
    top.legend(loc="upper left")
    top.grid(alpha=0.3)

    h = np.array([Tk[0, 3], Tk[1, 3], 0.0]) / h_len  # the face-on plane's horizontal direction
    side.axvline(0.0, color="0.5", ls="-.", lw=1)  # the base axis
    sol = arm.ik(Tk)
    p, zn = Tk[:3, 3], Tk[:3, 2]
    shown = [np.array([0.0, 0.0]), np.array([p @ h + ARROW * (zn @ h), p[2] + ARROW * zn[2]])]
    for q, label, style in zip(sol.q[:2], sol.labels[:2], ["o-", "s--"], strict=False):
        P = arm.points(q)
        side.plot(P @ h, P[:, 2], style, color=_COLOURS[k], lw=2.5, ms=6, label=label)
        shown += list(np.column_stack([P @ h, P[:, 2]]))
    _arrow(side, np.array([p @ h, p[2]]), np.array([zn @ h, zn[2]]), "k", False)
    lo, hi = np.min(shown, axis=0) - 0.4 * ARROW, np.max(shown, axis=0) + 0.4 * ARROW
    side.set(aspect="equal", xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1] + ARROW),
             xlabel=f"along the arm plane [{arm.units}]", ylabel=f"z [{arm.units}]",
             title=f"{names[k]}: nearest pose, face on")  # fmt: skip
    side.legend(loc="upper right")
    side.grid(alpha=0.3)
    return fig
