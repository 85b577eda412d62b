"""The figures of lectures 05-07 (Porter's chain): readable 3-D axes and labels that do not collide.

* readable 3-D axes and labels come from :mod:`~puma_course.viz.labels` (``tidy_axes``, ``fit_ticks``,
  ``label_points``): as many tick numbers as fit, labels that overlap neither each other, the points
  nor, where they can, the drawn links;
* :func:`ver2_points`, :func:`parallel_circle` - the points of the geometric construction (Ver.2)
  and the circle of possible p3 when the planes are parallel, read from the robot API;
* :func:`plot_frames`, :func:`plot_solutions`, :func:`plot_construction`, :func:`plot_parallel_planes`:
  the lectures' figures. No kinematics of its own: every point comes from ``Porter``'s API.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from .._validate import as_array, as_count, as_transform
from ..kinematics.ik import SingularityWarning
from ..kinematics.porter import Porter
from .arms import draw_chain
from .frames import draw_points, set_equal, triad_letters
from .labels import fit_ticks, label_points, tidy_axes

__all__ = ["POINT_NAMES", "FRAME_NAMES", "ver2_points", "parallel_circle", "plot_frames", "plot_solutions",
           "plot_construction", "plot_parallel_planes"]  # fmt: skip

#: Names of Porter's points as drawn (mathtext): p0 and p1 coincide.
POINT_NAMES = ("$p_0 = p_1$", "$p_2$", "$p_3$", "$p_4$", "$p_5$")
#: Names of Porter's frames as drawn: F1 (F0 turned by α1) shares F0's origin.
FRAME_NAMES = ("$F_0, F_1$", "", "$F_2$", "$F_3$", "$F_4$", "$F_5$")


def _check_porter(arm: Any) -> Porter:
    if not isinstance(arm, Porter):
        raise ValueError(f"arm: expected Porter(l1, l3, l4), got {type(arm).__name__}")
    return arm


def _axes(fig: Figure, pos: tuple[int, int, int], elev: float, azim: float) -> Any:
    ax = tidy_axes(fig.add_subplot(*pos, projection="3d"))
    ax.view_init(elev=elev, azim=azim)
    return ax


def _frame(ax: Any, pts: np.ndarray, margin: float) -> None:
    set_equal(ax, pts, margin=margin)
    fit_ticks(ax)


def ver2_points(arm: Porter, T: Any, near: Any = None) -> dict[str, np.ndarray]:
    """The geometric construction (Ver.2) for the pose T, read from the robot API.

    Keys: ``p0``, ``p2``, ``p4``, ``p5``, ``x5`` (the hand's x axis), ``n`` (the unit normal
    (p2 - p0) x (p4 - p0) of the arm plane P: the axis y1 of α2 and α3), ``p3`` (the elbow point of
    each configuration of ``arm.ik(T, near=near, method="geometric")``, (k, 3)) and ``q`` (those
    configurations). P must be defined (p4 off the z0 axis); the ik's warning is not repeated.

    >>> arm = Porter(1.0, 0.5, 0.3); V = ver2_points(arm, arm.fk([0.6, -0.5, 1.2, 0.8, 0.7, -0.4]))
    >>> V["p3"].shape, round(float(np.linalg.norm(V["p3"][0] - V["p4"])), 12)
    ((2, 3), 0.5)
    """
    arm = _check_porter(arm)
    T = as_transform(T, "T")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        G = arm.ik(T, near=near, method="geometric")
    if not G.success:
        raise ValueError(f"T: expected a pose the arm reaches, got one it does not ({G.reason})")
    if "p4_on_z0_axis" in G.singular:
        raise ValueError("T: expected a pose whose wrist point p4 is off the z0 axis (the plane P is not defined)")
    pts = arm.points(G.q)
    p0, p2, p4, p5 = pts[0, 0], pts[0, 2], pts[0, 4], pts[0, 5]
    m = np.cross(p2 - p0, p4 - p0)
    return {"p0": p0, "p2": p2, "p4": p4, "p5": p5, "x5": T[:3, 0].copy(), "n": m / math.hypot(*m),
            "p3": pts[:, 3].copy(), "q": G.q.copy()}  # fmt: skip


def parallel_circle(arm: Porter, T: Any, samples: int = 121) -> np.ndarray:
    """The circle of possible p3 when the planes are parallel (x5 normal to P): (samples, 3), closed.

    Centre p4, radius l3, in the arm plane P (whose normal is x5 here). Raises ``ValueError`` if
    the pose is not a parallel-planes pose.

    >>> arm = Porter(1.0, 0.5, 0.3); C = parallel_circle(arm, arm.fk([0.7, 0.3, 1.2, 0.4, np.pi / 2, 0.5]), samples=5)
    >>> np.round(np.linalg.norm(C - (C[0] + C[2]) / 2, axis=1), 12).tolist()
    [0.5, 0.5, 0.5, 0.5, 0.5]
    """
    arm = _check_porter(arm)
    T = as_transform(T, "T")
    samples = as_count(samples, "samples", minimum=3)
    if "planes_parallel" not in arm.classify(T):
        raise ValueError("T: expected a pose with parallel planes (x5 normal to the arm plane, c4 = 0)")
    x5, p4, up = T[:3, 0], T[:3, 3] - arm.lengths["l4"] * T[:3, 0], np.array([0.0, 0.0, 1.0])
    u = np.cross(x5, up) / math.hypot(*np.cross(x5, up))  # the horizontal direction of P (x5 is normal to P)
    l3, t = arm.lengths["l3"], np.linspace(0.0, 2.0 * math.pi, samples)
    return p4 + l3 * (np.outer(np.cos(t), up) + np.outer(np.sin(t), u))


def _plane_patch(ax: Any, a1: float, pts: np.ndarray, color: str = "0.5", alpha: float = 0.12) -> np.ndarray:
    """The vertical plane at angle ``a1`` through z0, as a rectangle just covering ``pts`` (k, 3); its corners."""
    u, up = np.array([math.cos(a1), math.sin(a1), 0.0]), np.array([0.0, 0.0, 1.0])
    r, z = pts @ u, pts[:, 2]
    m = 0.08 * max(float(np.ptp(r)), float(np.ptp(z)), 1e-9)
    lo, hi, zlo, zhi = min(r.min(), 0.0) - m, r.max() + m, min(z.min(), 0.0) - m, z.max() + m
    corners = np.array([lo * u + zlo * up, hi * u + zlo * up, hi * u + zhi * up, lo * u + zhi * up])
    grid = corners[[0, 1, 3, 2]].reshape(2, 2, 3)  # [[lower left, lower right], [upper left, upper right]]
    ax.plot_surface(grid[..., 0], grid[..., 1], grid[..., 2], color=color, alpha=alpha, edgecolor="0.6", lw=0.8,
                    shade=False)  # fmt: skip
    return corners


#: each joint's axis in Porter's frames F0..F5: (frame index, axis column) -- α1 about z0 through p0, α2 about y1
#: (= y2) through p2, the stroke q2 along x2 from p2, α3 about y2 (= y3) through p3, α4 about z3 (= z4) through p4,
#: α5 about x4 (= x5) through p4 and p5 (lecture 05, the table of section 1)
JOINT_AXES = ((0, 2), (2, 1), (2, 0), (3, 1), (4, 2), (5, 0))


def joint_axis_lines(frames: Any) -> np.ndarray:
    """Each joint's axis as a point and a unit direction, from the frames F0..F5: (6, 2, 3) (or (N, 6, 2, 3)).

    >>> L = joint_axis_lines(Porter(1.0, 0.5, 0.3).frames(np.zeros(6)))
    >>> (L[1] + 0.0).tolist()  # α2 turns about y through p2 = (0, 0, l1)
    [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]]
    """
    F = as_array(frames, "frames", (6, 4, 4), batch=True, what="Porter's frames F0..F5, shape (6, 4, 4)")
    idx = np.array(JOINT_AXES)
    points = F[..., idx[:, 0], :3, 3]
    directions = np.take_along_axis(F[..., idx[:, 0], :3, :], idx[:, 1][:, None, None], axis=-1)[..., 0]
    return np.stack([points, directions], axis=-2)


def plot_frames(arm: Porter, Q: Any, titles: Sequence[str] | None = None, *, figsize: tuple[float, float] | None = None,
                elev: float = 22.0, azim: float = -60.0) -> Figure:  # fmt: skip
    """One 3-D panel per configuration in ``Q`` (k, 6): links, frames F0..F5 with their triads and names.

    The dashed lines are the joint axes (:func:`joint_axis_lines`), as in every lecture's figures: a
    frame's z axis is a joint axis in a Denavit-Hartenberg chain, not in Porter's. The base triad F0 has its
    axes lettered x, y, z (it stands apart); the other five share its colours and stay bare, since eighteen
    letters would crowd F4 and F5.

    All panels share one cube of limits (so they compare at a glance) filled by the arms.

    >>> fig = plot_frames(Porter(1.0, 0.5, 0.3), np.zeros((2, 6)), ["a", "b"]); [ax.get_title() for ax in fig.axes]
    ['a', 'b']
    >>> plt.close(fig)
    """
    arm = _check_porter(arm)
    Q = as_array(Q, "Q", (6,), batch=True, what="configurations of shape (k, 6)").reshape(-1, 6)
    k = len(Q)
    if titles is not None and (isinstance(titles, str) or len(titles) != k):
        raise ValueError(f"titles: expected one title per configuration ({k}), got {titles!r}")
    F = arm.frames(Q)
    L = 0.14 * max(float(np.ptp(F[:, :, :3, 3].reshape(-1, 3), axis=0).max()), 1e-9)
    tips = F[:, :, :3, 3][..., None, :] + L * np.swapaxes(F[:, :, :3, :3], -1, -2)
    box = np.vstack([F[:, :, :3, 3].reshape(-1, 3), tips.reshape(-1, 3)])
    fig = plt.figure(figsize=figsize or (5.2 * k, 5.0))
    for j in range(k):
        ax = _axes(fig, (1, k, j + 1), elev, azim)
        draw_chain(ax, F[j], labels=[""] * 6, length=L, axes=False)
        for o, u in joint_axis_lines(F[j]):
            ax.plot(*np.stack([o - 0.6 * L * u, o + 0.6 * L * u]).T, ls="--", lw=1, color="tab:blue", alpha=0.5)
        _frame(ax, box, 0.02)
        if titles is not None:
            ax.set_title(titles[j])
    for j, ax in enumerate(fig.axes):
        triads = [np.stack([F[j, i, :3, 3], tips[j, i, a]]) for i in range(6) for a in range(3)]
        letters = triad_letters(ax, F[j, 0], L)  # F0's axes lettered: the other triads share its colours
        label_points(ax, F[j, :, :3, 3], FRAME_NAMES, avoid=[F[j, :, :3, 3], *triads], first=letters)
    return fig


def plot_solutions(arm: Porter, solutions: Any, *, figsize: tuple[float, float] = (10.5, 5.0), elev: float = 18.0,
                   azim: float = -50.0) -> Figure:  # fmt: skip
    """The solutions of one pose, one panel per arm plane (α1): the first solid, the others faded.

    ``solutions`` is an :class:`~puma_course.kinematics.ik.IKSolutions` (or (k, 6) rows) for one
    pose. Each panel labels p0 ... p5 and, for every configuration, its elbow point p3; the base triad's axes
    are lettered x, y, z, the other triads share its colours (letters on every one would crowd the wrist).

    >>> arm = Porter(1.0, 0.5, 0.3); fig = plot_solutions(arm, arm.ik(arm.fk([0.6, -0.5, 1.2, 0.8, 0.7, -0.4])))
    >>> len(fig.axes)
    2
    >>> plt.close(fig)
    """
    arm = _check_porter(arm)
    S = as_array(np.asarray(solutions, dtype=float), "solutions", (6,), batch=True).reshape(-1, 6)
    if len(S) == 0:
        raise ValueError("solutions: expected at least one configuration, got none")
    firsts = [i for i in range(len(S)) if all(math.cos(S[i, 0] - S[j, 0]) <= 0.5 for j in range(i))]
    planes = [[i for i in range(len(S)) if math.cos(S[i, 0] - S[f, 0]) > 0.5] for f in firsts]  # one per arm plane
    P = arm.points(S)
    fig = plt.figure(figsize=figsize if len(planes) > 1 else (figsize[0] / 2 + 0.5, figsize[1]))
    colors = ["0.15", "tab:orange", "tab:purple", "tab:cyan"]
    for k, g in enumerate(planes):
        ax = _axes(fig, (1, len(planes), k + 1), elev, azim)
        for j, i in enumerate(g):
            draw_chain(ax, arm.frames(S[i]), labels=[""] * 6, alpha=1.0 if j == 0 else 0.5, color=colors[j % 4],
                       length=0.08 * float(np.ptp(P.reshape(-1, 3), axis=0).max()))  # fmt: skip
        _frame(ax, P.reshape(-1, 3), 0.05)
        count = {1: "one configuration", 2: "two configurations"}.get(len(g), f"{len(g)} configurations")
        ax.set_title(f"$\\alpha_1 = {math.degrees(S[g[0]][0]):.1f}^\\circ$: {count}")
        names, pts, cols = [POINT_NAMES[i] for i in (0, 1, 3, 4)], [P[g[0], i] for i in (0, 2, 4, 5)], ["k"] * 4
        for j, i in enumerate(g):
            pts.append(P[i, 3])
            names.append(f"$p_3$ ({j + 1})" if len(g) > 1 else "$p_3$")
            cols.append("k" if j == 0 else "tab:orange")
        F0 = arm.frames(S[g[0]])[0]  # the base triad's axes lettered; the others share its colours
        letters = triad_letters(ax, F0, 0.08 * float(np.ptp(P.reshape(-1, 3), axis=0).max()))
        label_points(ax, np.array(pts), names, avoid=[P[i] for i in g], color=cols, first=letters)
    return fig


def plot_construction(arm: Porter, T: Any, near: Any = None, *, figsize: tuple[float, float] = (7.0, 6.0),
                      elev: float = 16.0, azim: float | None = None) -> Figure:  # fmt: skip
    """Ver.2 drawn: the plane P, its normal n (from p0), the points p0, p2, p4, p5, the candidates for p3.

    The configurations of ``arm.ik(T, near=near, method="geometric")`` are drawn (the first dark, the other orange),
    each elbow point numbered; the dotted line through p4 carries both p3 = p4 ± l3 z4. ``azim``
    defaults to α1 - 65° (degrees): the plane, its normal and every axis's tick numbers show.

    >>> arm = Porter(1.0, 0.5, 0.3); fig = plot_construction(arm, arm.fk([0.6, -0.5, 1.2, 0.8, 0.7, -0.4]))
    >>> fig.axes[0].get_title()
    'Ver.2: the plane P and the two candidates for $p_3$'
    >>> plt.close(fig)
    """
    V = ver2_points(arm, T, near)
    a1, fig = float(V["q"][0, 0]), plt.figure(figsize=figsize)
    ax = _axes(fig, (1, 1, 1), elev, math.degrees(a1) - 65.0 if azim is None else azim)
    arms = arm.points(V["q"])
    n_tip = V["p0"] + 0.35 * float(np.ptp(arms.reshape(-1, 3), axis=0).max()) * V["n"]
    corners = _plane_patch(ax, a1, arms.reshape(-1, 3))
    for k, pts in enumerate(arms):
        draw_points(ax, pts, color=["0.15", "tab:orange"][k % 2], alpha=1.0 if k == 0 else 0.6, lw=3.5,
                    label=f"configuration {k + 1}")  # fmt: skip
    ax.plot(*V["p3"].T, ls=":", lw=1.5, color="tab:red")  # the line p4 ± l3 z4
    ax.scatter(*V["p3"].T, s=40, color="tab:red", depthshade=False, zorder=5)
    ax.quiver(*V["p0"], *(n_tip - V["p0"]), color="tab:green", lw=2.5, arrow_length_ratio=0.2)
    ax.set_title("Ver.2: the plane P and the two candidates for $p_3$")
    ax.legend(loc="upper left")
    _frame(ax, np.vstack([arms.reshape(-1, 3), n_tip[None], corners]), 0.0)
    names = ["$p_0$", "$p_2$", "$p_4$", "$p_5$", *[f"$p_3$ ({k + 1})" for k in range(len(V["p3"]))], "$n$", "plane $P$"]
    pts = np.vstack([V["p0"], V["p2"], V["p4"], V["p5"], V["p3"], n_tip, corners[3]])
    cols = ["k"] * 4 + ["tab:red"] * len(V["p3"]) + ["tab:green", "0.35"]
    label_points(ax, pts, names, avoid=[*arms, np.stack([V["p0"], n_tip])], color=cols)
    return fig


def plot_parallel_planes(arm: Porter, T: Any, q_ref: Any = None, *, figsize: tuple[float, float] = (7.0, 6.0),
                         elev: float = 12.0) -> Figure:  # fmt: skip
    """Parallel planes drawn: the circle of possible p3, Porter's minimal-q2 arm, and (faded) ``q_ref``.

    ``q_ref`` is any other configuration reaching T (e.g. the one that made it); a legend names the three.

    >>> arm = Porter(1.0, 0.5, 0.3); fig = plot_parallel_planes(arm, arm.fk([0.7, 0.3, 1.2, 0.4, np.pi / 2, 0.5]))
    >>> fig.axes[0].get_title()
    'parallel planes: $p_3$ on a circle, the smallest $q_2$ chosen'
    >>> plt.close(fig)
    """
    arm = _check_porter(arm)
    C = parallel_circle(arm, T)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularityWarning)
        G = arm.ik(T, method="geometric")
    best, shown = arm.points(G[0]), [arm.points(G[0]), C]
    fig, a1 = plt.figure(figsize=figsize), float(G[0][0])
    ax = _axes(fig, (1, 1, 1), elev, math.degrees(a1) - 60.0)
    draw_points(ax, best, color="0.15", lw=3.5, label="Porter's choice: the smallest $q_2$")
    if q_ref is not None:
        ref = arm.points(arm.check_q(q_ref))
        if ref.ndim != 2:
            raise ValueError(f"q_ref: expected one configuration (6,), got shape {np.shape(q_ref)}")
        draw_points(ax, ref, color="tab:orange", alpha=0.6, lw=3.0, label="another configuration reaching $T$")
        shown.append(ref)
    corners = _plane_patch(ax, a1, np.vstack(shown))
    ax.plot(*C.T, color="tab:red", lw=1.5, label="every possible $p_3$")
    ax.set_title("parallel planes: $p_3$ on a circle, the smallest $q_2$ chosen")
    ax.legend(loc="upper left")
    _frame(ax, np.vstack(shown + [corners]), 0.0)
    label_points(ax, best[[0, 2, 3, 4, 5]], ["$p_0$", "$p_2$", "$p_3$", "$p_4$", "$p_5$"], avoid=[best, C, *shown[2:]])
    return fig
