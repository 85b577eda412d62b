"""Figures of lecture 09, the PUMA-560's inverse kinematics, and the small computations behind them.

* :func:`plot_solutions`: every solution of one pose on one scale, with the wrist (:func:`draw_wrist`:
  frames {4}, {5}, {6} each on its own link) so that a flip pair differs visibly; :func:`plot_wrist_flip`;
* :func:`plot_shoulder_top_view`: θ1 seen from above, the offset d3, the circle ρ = |d3|, both shoulders;
* :func:`branch_gaps`, :func:`singularity_sweep`, :func:`plot_singularity_sweeps`: det J and the gap between
  the two branches that merge, along a sweep of one joint through each singularity;
* :func:`plot_workspace` (a sampled workspace from above and from the side).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Arc, Circle

from .._validate import as_array, as_count, as_length
from ..kinematics.ik import IKSolutions, SingularityWarning
from ..kinematics.puma560 import Puma560
from .arms import draw_robot
from .frames import draw_frame, set_equal, triad_letters
from .ik_sweeps import DECIDED_JOINT, SWEPT_JOINT, as_puma, branch_gaps, plot_singularity_sweeps, singularity_sweep
from .labels import Label, place_labels
from .style import text_color

__all__ = [
    "DECIDED_JOINT",
    "SWEPT_JOINT",
    "branch_gaps",
    "draw_wrist",
    "wrist_letters",
    "plot_shoulder_top_view",
    "plot_singularity_sweeps",
    "plot_solutions",
    "plot_workspace",
    "plot_wrist_flip",
    "singularity_sweep",
]


# ------------------------------------------------------------------------------------------------ the wrist
def draw_wrist(ax: Any, arm: Puma560, q: Any, *, length: float = 0.07, frames: Sequence[int] = (4, 5, 6),
               axes: bool = True, labels: bool = True, lw: float = 2.5) -> list[Any]:  # fmt: skip
    """Draw the PUMA-560's wrist at ``q``: the forearm's end, the hand's flange, the joint axes z4, z5, z6
    (dashed, with ``axes``) and the triads of ``frames`` (some of {4}, {5}, {6}), each on its own link.

    The three frames share one origin, the wrist centre; drawn there they hide each other. A frame
    is fixed to its link, so it may be drawn anywhere on it: {4} is drawn on the forearm (back along
    z4), {5} at the wrist centre, {6} at the end of the flange (along z6). Returns the artists.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.viz import new_axes
    >>> fig, ax = new_axes()
    >>> arts = draw_wrist(ax, Puma560(), Puma560().q("qn"))
    >>> len(arts)  # forearm, flange, 3 axes, 3 triads of 3 lines with a label each
    17
    >>> plt.close(fig)
    """
    arm = as_puma(arm)
    L = as_length(length, "length", positive=True)
    if isinstance(frames, str) or not set(frames) <= {4, 5, 6}:
        raise ValueError(f"frames: expected some of the wrist frames 4, 5, 6, got {frames!r}")
    F = arm.frames(arm.check_q(q))
    if F.ndim != 3:
        raise ValueError(f"q: expected one joint vector of shape (6,), got a batch of {F.shape[0]}")
    w, z4, z6 = F[4, :3, 3], F[4, :3, 2], F[6, :3, 2]
    arts = list(ax.plot(*np.stack([w - 2.2 * L * z4, w]).T, color="tab:orange", lw=9, alpha=0.45,
                        solid_capstyle="butt"))  # fmt: skip
    arts += ax.plot(*np.stack([w, w + 1.5 * L * z6]).T, color="0.3", lw=6, solid_capstyle="butt")
    if axes:
        for j in (4, 5, 6):
            z = F[j, :3, 2]
            arts += ax.plot(*np.stack([w - 1.4 * L * z, w + 1.4 * L * z]).T, ls="--", lw=1, color="0.45")
    for j, T in _wrist_triads(F, L, frames).items():
        arts += draw_frame(ax, T, None, length=L, lw=lw)
        if labels:  # beyond the tip of the x axis (red): the axis a flip reverses
            box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8}
            arts.append(ax.text(*(T[:3, 3] + 1.3 * L * T[:3, 0]), f"{{{j}}}", ha="center", va="center", bbox=box))
    return arts


def _drawn_lines(ax: Any) -> list[np.ndarray]:
    """The polylines drawn on a 3-D axes, each (m, 3): the letters keep off them."""
    lines: list[Any] = list(ax.lines)
    return [np.transpose(ln.get_data_3d()) for ln in lines]


def _wrist_triads(F: np.ndarray, L: float, frames: Sequence[int]) -> dict[int, np.ndarray]:
    """The frames of :func:`draw_wrist`, each moved along its link to where it is drawn: {4} back on the
    forearm, {5} at the wrist centre, {6} at the end of the flange."""
    w, z4, z6 = F[4, :3, 3], F[4, :3, 2], F[6, :3, 2]
    places = {4: w - 1.4 * L * z4, 5: w, 6: w + 1.5 * L * z6}
    out = {}
    for j in sorted(set(frames)):
        T = F[j].copy()
        T[:3, 3] = places[j]
        out[j] = T
    return out


def wrist_letters(ax: Any, arm: Puma560, q: Any, *, length: float = 0.07, frames: Sequence[int] = (4, 5, 6),
                  subscripts: bool = True) -> list[Label]:  # fmt: skip
    """The letters of the triads :func:`draw_wrist` draws, for :func:`~puma_course.viz.labels.place_labels`.

    ``subscripts`` names each axis with its frame (x₄, y₄, z₄: the frame and the axis in one text, in place of
    draw_wrist's ``{4}``), otherwise plain x, y, z. Call it when the view and the limits are final.
    """
    arm = as_puma(arm)
    F = arm.frames(arm.check_q(q))
    out: list[Label] = []
    for j, T in _wrist_triads(F, as_length(length, "length", positive=True), frames).items():
        names = [f"${n}_{j}$" for n in "xyz"] if subscripts else ["x", "y", "z"]
        out += triad_letters(ax, T, length, names=names)
    return out


def _view_of_wrist(F: np.ndarray) -> tuple[float, float]:
    """(elev, azim) in degrees: looking at the wrist from beside the forearm, a little behind and above it."""
    z4 = F[4, :3, 2]
    side = np.cross(z4, [0.0, 0.0, 1.0])
    side = side / max(float(np.linalg.norm(side)), 1e-12) if np.linalg.norm(side) > 1e-6 else F[4, :3, 0]
    d = -0.5 * z4 - side + 0.5 * np.array([0.0, 0.0, 1.0])
    d = d / np.linalg.norm(d)
    return math.degrees(math.asin(float(d[2]))), math.degrees(math.atan2(float(d[1]), float(d[0])))


def plot_wrist_flip(arm: Puma560, q_noflip: Any, q_flip: Any, *, titles: Sequence[str] = ("noflip", "flip"),
                    length: float = 0.07) -> Figure:  # fmt: skip
    """Two close-ups of the wrist side by side, seen from the same direction (:func:`draw_wrist`).

    For a flip pair the forearm and the hand are the same; the triads of {4} and {5} turn over. Each triad's
    axes are named at their tips with their frame (x₄, y₄, z₄, ...: :func:`wrist_letters`).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> arm = Puma560()
    >>> sol = arm.ik(arm.fk(np.radians([30, -50, 20, 40, 60, -30])))
    >>> fig = plot_wrist_flip(arm, sol.q[0], sol.q[1])
    >>> [ax.get_title().splitlines()[0] for ax in fig.axes]
    ['noflip', 'flip']
    >>> plt.close(fig)
    """
    arm = as_puma(arm)
    Q = [arm.check_q(q_noflip), arm.check_q(q_flip)]
    elev, azim = _view_of_wrist(arm.frames(Q[0]))
    fig = plt.figure(figsize=(9.0, 4.6))
    for k, (q, title) in enumerate(zip(Q, titles, strict=True)):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        ax.view_init(elev=elev, azim=azim)
        arts = draw_wrist(ax, arm, q, length=length, labels=False)
        set_equal(ax, np.hstack([a.get_data_3d() for a in arts if hasattr(a, "get_data_3d")]).T, margin=0.02)
        ax.set_box_aspect((1, 1, 1), zoom=1.2)
        ax.set_axis_off()
        t4, t5, t6 = (round(float(np.degrees(v)), 1) + 0.0 for v in q[3:])
        ax.set_title(f"{title}\nθ4 = {t4:g}°, θ5 = {t5:g}°, θ6 = {t6:g}°")
    fig.canvas.draw()
    for ax, q in zip(fig.axes, Q, strict=True):  # x4, y4, z4, ... beside the tips: the frame and the axis in one text
        lines = _drawn_lines(ax)
        place_labels(ax, wrist_letters(ax, arm, q, length=length), lines=lines, fontsize=11, draw=False)
    return fig


def plot_solutions(arm: Puma560, solutions: IKSolutions, *, grid: float = 0.25, elev: float = 20,
                   azim: float = -60, columns: int = 4) -> Figure:  # fmt: skip
    """Every solution of ``solutions`` in its own 3-D panel, all on one scale (grid lines every ``grid`` metres).

    Each arm carries its wrist (:func:`draw_wrist`): the hand's flange (dark) and the triad of {4}
    on the forearm, its axes lettered x, y, z; a flip pair has the same links, and its {4} is turned over by
    half a turn.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> arm = Puma560()
    >>> fig = plot_solutions(arm, arm.ik(arm.fk(arm.q("qn"))))
    >>> len(fig.axes), fig.axes[0].get_title()
    (8, 'left/up/noflip')
    >>> plt.close(fig)
    """
    arm = as_puma(arm)
    if not isinstance(solutions, IKSolutions) or len(solutions) == 0:
        raise ValueError(f"solutions: expected the IKSolutions of a reachable pose, got {solutions!r}")
    grid = as_length(grid, "grid", positive=True)
    cols = as_count(columns, "columns", minimum=1)
    rows = -(-len(solutions) // cols)
    pts = arm.points(solutions.q).reshape(-1, 3)
    fig = plt.figure(figsize=(2.75 * cols, 2.9 * rows + 0.4))
    shown: list[tuple[Any, np.ndarray]] = []
    for i, (label, q) in enumerate(zip(solutions.labels, solutions.q, strict=True)):
        ax = fig.add_subplot(rows, cols, i + 1, projection="3d")
        ax.view_init(elev=elev, azim=azim)
        draw_robot(ax, arm, q, triads="none", lw=3.5)
        draw_wrist(ax, arm, q, length=0.12, frames=(4,), axes=False, labels=False, lw=2.5)
        shown.append((ax, q))
        set_equal(ax, pts, margin=0.02)
        ax.set_box_aspect((1, 1, 1), zoom=1.15)
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            lo, hi = axis.get_view_interval()
            axis.set_ticks(np.arange(math.ceil(lo / grid), math.floor(hi / grid) + 1) * grid)
            axis.set_ticklabels([])
        ax.set_title(label, fontsize=11)
    fig.suptitle(f"{len(solutions)} configurations, one hand pose (grid lines every {grid:g} m)")
    fig.canvas.draw()
    for ax, q in shown:  # {4}'s x, y, z: a flip pair's x and y point the other way
        lines = _drawn_lines(ax)
        place_labels(ax, wrist_letters(ax, arm, q, length=0.12, frames=(4,), subscripts=False), lines=lines,
                     fontsize=10, draw=False)  # fmt: skip
    return fig


# ------------------------------------------------------------------------------------------------ θ1 from above
def plot_shoulder_top_view(arm: Puma560, T: Any) -> Figure:
    """θ1 seen from above: the wrist centre, the circle ρ = |d3| it may not enter, and for each shoulder the
    direction x1 (an arrow, θ1 measured from x0), the offset d3 along y1 (thick) and the arm's plane, a vertical
    plane seen edge-on from above (a light band; dashed lines are kept for joint axes, as in every lecture).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> arm = Puma560()
    >>> fig = plot_shoulder_top_view(arm, arm.fk(np.radians([30, -50, 20, 40, 60, -30])))
    >>> fig.axes[0].get_xlabel()
    'x [m]'
    >>> plt.close(fig)
    """
    arm = as_puma(arm)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        sol = arm.ik(T)
    if not sol.success:
        raise ValueError(f"T: expected a reachable pose, got one that is not ({sol.reason})")
    w = np.asarray(T, dtype=float)[:3, 3]
    d3 = arm.lengths["d3"]
    fig, ax = plt.subplots(figsize=(6.4, 6.2))
    ax.add_patch(Circle((0, 0), abs(d3), facecolor="tab:red", alpha=0.12, edgecolor="tab:red",
                        label=f"ρ < |d3| = {abs(d3):g} m: never reached"))  # fmt: skip
    arrow = 2.2 * abs(d3) if d3 else 0.3
    ax.annotate("", (arrow, 0), (0, 0), arrowprops={"arrowstyle": "->", "color": "0.4", "lw": 1.2})
    ax.text(1.15 * arrow, 0, "x0", color="0.4", ha="center", va="center")
    shown: list[Any] = [np.zeros(2), w[:2], [1.2 * arrow, 0.0]]
    for shoulder, color in (("left", "tab:blue"), ("right", "tab:purple")):
        k = next((i for i, lab in enumerate(sol.labels) if lab.startswith(shoulder)), None)
        if k is None:
            continue
        q = sol.q[k]
        P = arm.points(q)[:, :2]  # foot, base, end of d3, elbow, end of a3, wrist centre
        x1 = arrow * np.array([math.cos(q[0]), math.sin(q[0])])
        ax.plot(*P[1:3].T, color=color, lw=5, solid_capstyle="round",
                label=f"shoulder {shoulder}: θ1 = {math.degrees(q[0]):.1f}°")  # fmt: skip
        ax.plot(*np.stack([P[2], P[5]]).T, color=color, lw=9, alpha=0.22, solid_capstyle="butt")
        ax.annotate("", (float(x1[0]), float(x1[1])), (0, 0), arrowprops={"arrowstyle": "->", "color": color})
        ax.text(float(1.15 * x1[0]), float(1.15 * x1[1]), "x1", color=text_color(color), ha="center", va="center")
        t1 = math.degrees(q[0])
        ax.add_patch(Arc((0, 0), 1.5 * arrow, 1.5 * arrow, theta1=min(0.0, t1), theta2=max(0.0, t1), color=color,
                         lw=1.5))  # fmt: skip
        shown += [P[1:], 1.2 * x1]
    ax.plot(*w[:2], marker="*", ms=16, color="k", ls="none", label="the wrist centre")
    S = np.vstack([np.reshape(p, (-1, 2)) for p in shown])
    lo, hi = S.min(axis=0) - 0.06, S.max(axis=0) + 0.06
    ax.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), aspect="equal", xlabel="x [m]", ylabel="y [m]",
           title="from above: offset d3 (thick), arm plane (light band)")  # fmt: skip
    ax.locator_params(nbins=6)
    fig.legend(loc="outside lower center", ncols=2, fontsize=10)
    return fig


# ------------------------------------------------------------------------------------------------ singularities
def plot_workspace(points: Any, *, units: str, title: str, color: str = "tab:blue",
                   top_circles: Sequence[tuple[Any, float, str, str]] = (),
                   side_circles: Sequence[tuple[Any, float, str, str]] = (),
                   side_lines: Sequence[tuple[float, str, str]] = (),
                   side_floor: tuple[float, str] | None = None) -> Figure:  # fmt: skip
    """Top view (x, y) and side view (ρ = distance from the base axis, z) of sampled points (N, 3).

    ``top_circles``/``side_circles`` are bounds drawn over the samples, each ``(centre (2,), radius,
    label, colour)``; ``side_lines`` vertical lines ``(ρ, label, colour)``, all drawn solid (dashed lines
    mean joint axes in the course). ``side_floor`` ``(z, label)`` draws a floor in the side view, shaded
    below, with room under it. The legend sits below the plots, never over them (and labels nothing at an
    edge of a view).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> P = np.random.default_rng(0).normal(size=(200, 3))
    >>> fig = plot_workspace(P, units="m", title="demo", top_circles=[((0, 0), 2.0, "r = 2", "k")])
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['x [m]', 'ρ [m]']
    >>> plt.close(fig)
    """
    P = as_array(points, "points", (3,), batch=True).reshape(-1, 3)
    rho = np.hypot(P[:, 0], P[:, 1])
    fig, (top, side) = plt.subplots(1, 2, figsize=(9.0, 5.4), width_ratios=[2, 1.15])
    top.scatter(P[:, 0], P[:, 1], s=1.5, alpha=0.4, color=color, lw=0, rasterized=True)
    side.scatter(rho, P[:, 2], s=1.5, alpha=0.4, color=color, lw=0, rasterized=True)
    t = np.linspace(0, 2 * np.pi, 361)
    for ax, circles in ((top, top_circles), (side, side_circles)):
        for centre, r, label, col in circles:
            cx, cy = np.asarray(centre, dtype=float)
            x, y = cx + r * np.cos(t), cy + r * np.sin(t)
            if ax is side:
                x, y = np.where(x >= 0, x, np.nan), y
            ax.plot(x, y, color=col, lw=1.6, label=label)
    for rho0, label, col in side_lines:
        side.axvline(rho0, color=col, lw=1.6, label=label)
    if side_floor is not None:
        z0, label = float(side_floor[0]), str(side_floor[1])
        zs = np.append(P[:, 2], z0)
        room = 0.06 * float(zs.max() - zs.min() or 1.0)
        side.axhspan(z0 - 2 * room, z0, color="0.85", lw=0)
        side.axhline(z0, color="0.25", lw=2.6, label=label)  # the edge of the shaded band, wider than the bounds
        side.set_ylim(bottom=z0 - room)
    top.set(aspect="equal", xlabel=f"x [{units}]", ylabel=f"y [{units}]", title="top view")
    side.set(aspect="equal", xlabel=f"ρ [{units}]", ylabel=f"z [{units}]", title="side view (every θ1)")
    top.locator_params(nbins=5), side.locator_params(nbins=5)
    fig.suptitle(title)
    named: dict[str, Any] = {}  # one entry per label (a bound may be drawn in both views)
    for ax in (top, side):
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            named.setdefault(lab, h)
    if named:
        fig.legend(list(named.values()), list(named), loc="outside lower center", ncols=min(len(named), 3))
    return fig


# ------------------------------------------------------------------------------------------------ the panel's picture
