"""Figures of lecture 04, the Motoman MK3: the nearest attainable pose of goals it cannot reach.

:func:`plot_nearest_attainable` draws goals from above (each with its arm plane, the goal's approach dashed and
the nearest attainable one solid, a cross where it points straight down) and one goal's arm plane face on, with
the arm at two solutions of its nearest pose (:meth:`~puma_course.kinematics.mk3.MK3.nearest_attainable`).
:func:`plot_wrist_circle` draws one goal's arm plane: the circle of wrist points p - d5 z' as the approach z' turns
in it, against the annuli joint 2 reaches, and the approach the search chose.
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
from ..kinematics.mk3_reach import wrist_arcs
from ..transforms import wrap_angle
from .style import text_color

__all__ = ["plot_nearest_attainable", "plot_wrist_circle", "ARROW"]

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
        # named beside its point too, in its colour: the goals are not told apart by colour alone (issue 34)
        top.annotate(name, p[:2], xytext=(7, -13), textcoords="offset points", color=text_color(colour), fontsize=9)
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


def plot_wrist_circle(arm: MK3, goal: Any, name: str = "goal") -> Figure:
    """One goal's arm plane, face on: where the wrist point can be as the approach turns in the plane.

    The base axis, joint 2 in both arm planes (front at (a1, d1), back at (-a1, d1)) and the annuli it reaches
    (|a2 - a3| to a2 + a3 from it, shaded); the circle of wrist points w' = p - d5 z' about the tool point p,
    solid where the arm reaches w' and dotted where it does not; the wrist point and approach of the goal's
    projection onto the plane (dashed, a cross) and of the nearest attainable pose (solid, a dot). The goal's
    tool point must be off the base axis.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.transforms import homogeneous, rotx
    >>> fig = plot_wrist_circle(MK3(), homogeneous(rotx(2.0), [400.0, 100.0, 300.0]))
    >>> fig.axes[0].get_xlabel()
    'along the arm plane [mm]'
    >>> plt.close(fig)
    """
    if not isinstance(arm, MK3):
        raise ValueError(f"arm: expected an MK3, got {type(arm).__name__}")
    T = as_transform(goal, "goal")
    if not isinstance(name, str):
        raise ValueError(f"name: expected a string, got {type(name).__name__}")
    h = math.hypot(T[0, 3], T[1, 3])
    if h <= 1e-6:
        raise ValueError("goal: expected a tool point off the base axis (its arm plane is then not fixed), got "
                         f"({T[0, 3]:g}, {T[1, 3]:g}, {T[2, 3]:g})")  # fmt: skip
    d1, a1, a2, a3, d5 = arm.lengths.values()
    er = np.array([T[0, 3], T[1, 3], 0.0]) / h
    m = np.array([-er[1], er[0], 0.0])
    p = np.array([h, T[2, 3]])
    z = T[:3, 2]
    zp = z - (m @ z) * m
    near, info = arm.nearest_attainable(T)
    zn = near[:3, 2]

    fig, (whole, zoom) = plt.subplots(1, 2, figsize=(12.0, 6.2), gridspec_kw={"width_ratios": [1.25, 1]},
                                      layout="constrained")  # fmt: skip
    t = np.linspace(0.0, 2.0 * math.pi, 1441)
    ring = np.column_stack([np.cos(t), np.sin(t)])
    beta = np.linspace(-math.pi, math.pi, 1441)  # the approach's angle from e_r towards e_z
    W = p - d5 * np.column_stack([np.cos(beta), np.sin(beta)])
    ok = np.zeros(beta.size, dtype=bool)
    for lo, hi in wrist_arcs(float(p[0]), float(p[1]), tuple(arm.lengths.values())):
        past = wrap_angle(beta - lo)  # how far past the arc's start, going round the positive way
        ok |= np.where(past < 0.0, past + 2.0 * math.pi, past) <= hi - lo
    shown = (
        (zp / np.linalg.norm(zp), "--", "X", "the goal's approach projected onto the plane"),
        (zn, "-", "o", f"the nearest attainable approach, {math.degrees(info.angle):.2f}° from the goal's"),
    )
    for ax in (whole, zoom):
        for k, (jr, label) in enumerate(((a1, "front"), (-a1, "back (over the base)"))):
            # front and back told apart by line style and marker too, not by green and olive alone (issue 34)
            colour, line, mark = (("tab:green", "-", "^"), ("tab:olive", "--", "v"))[k]
            outer, inner = (a2 + a3) * ring + (jr, d1), abs(a2 - a3) * ring[::-1] + (jr, d1)
            ax.fill(*np.concatenate([outer, inner]).T, color=colour, alpha=0.12, lw=0)
            ax.plot(*outer.T, line, color=colour, lw=1.0, alpha=0.8)
            ax.plot(*inner.T, line, color=colour, lw=1.0, alpha=0.8)
            reach = f"{abs(a2 - a3):g} to {a2 + a3:g} {arm.units}"
            edge = "solid" if k == 0 else "dashed"
            ax.plot(jr, d1, mark, color=colour, ms=9, label=f"joint 2, {label}: reaches {reach} (shaded, {edge} edge)")
        ax.plot(*W.T, ":", color="0.3", lw=1.5, label="wrist points p − d5 z′ the arm does not reach")
        ax.plot(*np.where(ok[:, None], W, np.nan).T, "-", color="tab:blue", lw=3.5, label="wrist points it reaches")
        ax.plot(*p, "ko", ms=6)
        ax.annotate("p", p, xytext=(6, 6), textcoords="offset points")
        for zz, style, mark, text in shown:
            u = np.array([zz @ er, zz[2]])
            w = p - d5 * u
            arrow = dict(arrowstyle="-|>", color="tab:red", lw=2.0, ls=style)
            ax.annotate("", xy=p + 0.5 * d5 * u, xytext=w, arrowprops=arrow)
            ax.plot(*w, mark, color="tab:red", ms=9, label=f"{text}, and its wrist point")
        ax.axvline(0.0, color="0.5", ls="-.", lw=1)
        ax.set(aspect="equal", xlabel=f"along the arm plane [{arm.units}]", ylabel=f"z [{arm.units}]")
        ax.grid(alpha=0.3)
    whole.set_title(f"{name}: the arm plane")
    zoom.set(xlim=(p[0] - 1.9 * d5, p[0] + 1.9 * d5), ylim=(p[1] - 1.7 * d5, p[1] + 1.7 * d5),
             title="near p: the circle of wrist points")  # fmt: skip
    handles, labels = whole.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=9, frameon=False)
    return fig
