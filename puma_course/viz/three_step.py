"""Pictures and the animation of the three-step wrist-frame procedure (lecture 08).

Companion of :mod:`puma_course.kinematics.three_step`: nothing here computes kinematics, it draws
the :class:`~puma_course.kinematics.three_step.ThreeStepSolution` that
``ThreeStepArm(l1, l2).three_step(w, target)`` returns, sampled by
:func:`~puma_course.kinematics.three_step.motion`.
The arm is drawn as grey links s-e-w, the moving wrist frame as an RGB triad
(f1 red, f2 green, f3 blue), the target frame as a thick red triad and the
wrist centre's path in green, as in the source's Figure 3.
"""

from __future__ import annotations

from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from .._validate import as_array
from ..kinematics.three_step import Motion, ThreeStepArm, ThreeStepSolution, motion
from ..transforms import wrap_angle
from .frames import AXIS_COLORS, draw_points, set_equal
from .labels import Label, place_labels
from .style import text_color

__all__ = ["PHASE_TITLES", "draw_triad", "draw_state", "plot_steps", "plot_triangle", "animate"]

#: The title of each phase of :func:`~puma_course.kinematics.three_step.motion` (0 is the start).
PHASE_TITLES = (
    "start",
    "step 1: base turns by δ0 about e_z",
    "step 2: shoulder and elbow, K(a, δ)",
    "step 3: wrist, composite rotation",
)


def draw_triad(
    ax: Any,
    origin: Any,
    R: Any,
    length: float = 0.5,
    color: str | None = None,
    lw: float = 2.0,
    alpha: float = 1.0,
    label: str | None = None,
) -> list[Any]:
    """Draw the columns of the rotation ``R`` as arrows from ``origin``; one colour or x/y/z = red/green/blue.

    Returns the artists: three lines and their labels f1, f2, f3 (plus ``label``).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = plt.figure()
    >>> ax = fig.add_subplot(projection="3d")
    >>> arts = draw_triad(ax, [0.0, 0.0, 0.0], np.eye(3), length=1.0, label="target")
    >>> len(arts), [float(v) for v in arts[0].get_data_3d()[0]]  # 3 lines + 3 texts + label; f1 along x
    (7, [0.0, 1.0])
    >>> plt.close(fig)
    """
    o = as_array(origin, "origin", (3,))
    R = as_array(R, "R", (3, 3))
    artists: list[Any] = []
    for k in range(3):
        tip = o + length * R[:, k]
        c = color or AXIS_COLORS[k]
        artists += ax.plot(*np.stack([o, tip]).T, color=c, lw=lw, alpha=alpha, gid=f"triad-f{k + 1}")
        # the letters stay opaque on a faint triad: a text keeps 4.5:1 (issue 34)
        artists.append(ax.text(*(o + 1.12 * length * R[:, k]), f"f{k + 1}", color=text_color(c), fontsize=7))
    if label:
        artists.append(ax.text(*(o - 0.25 * length * R[:, 2]), label, fontsize=8, color=text_color(color or "k")))
    return artists


def draw_state(ax: Any, points: Any, frame: Any, length: float = 0.5, alpha: float = 1.0) -> list[Any]:
    """Draw one arm configuration: links s-e-w (3, 3) and the wrist frame at w.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = plt.figure()
    >>> ax = fig.add_subplot(projection="3d")
    >>> arts = draw_state(ax, [[0, 0, 0], [1.5, 0, 0], [2.5, 0, 0]], np.eye(3))
    >>> len(arts)  # the link polyline + the triad's 3 lines and 3 labels
    7
    >>> plt.close(fig)
    """
    P = as_array(points, "points", (3, 3))
    artists = list(draw_points(ax, P, color="0.35", lw=4.0, alpha=alpha))
    artists += draw_triad(ax, P[2], frame, length=length, alpha=alpha)
    return artists


def _scene(ax: Any, sol: ThreeStepSolution, m: Motion, k: int, length: float) -> list[Any]:
    """Everything but the arm at sample ``k``: floor cross, target, start ghost, path so far."""
    arts: list[Any] = []
    arts += ax.plot([0, 0], [0, 0], [-0.2, 0.2], color="k", lw=1)  # the base axis
    arts += draw_triad(ax, sol.w, sol.target, length=length, color="red", lw=4.0, alpha=0.45)
    arts += ax.plot(*m.points[0].T, color="0.6", lw=1.5, ls=":")  # the straight-arm start
    path = m.path[: k + 1]
    arts += ax.plot(*path.T, color="tab:green", lw=2.5)
    return arts


def _limits(sol: ThreeStepSolution, m: Motion, length: float) -> np.ndarray:
    tips = sol.w + length * sol.target.T
    return np.vstack([m.points.reshape(-1, 3), tips, np.zeros((1, 3))])


def plot_steps(
    sol: ThreeStepSolution,
    length: float = 0.5,
    figsize: tuple[float, float] = (9.0, 8.0),
    title: str | None = None,
) -> Figure:
    """Four panels: the start and the arm with its wrist frame after steps 1, 2 and 3; returns ``fig``.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import ThreeStepArm
    >>> fig = plot_steps(ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0])))
    >>> [ax.get_title() for ax in fig.axes][:2]
    ['start', 'step 1: base turns by δ0 about e_z']
    >>> plt.close(fig)
    """
    n = 12
    m = motion(sol, steps_per_phase=n)  # samples 0, n, 2n, 3n: the start and the ends of steps 1, 2, 3
    lims = _limits(sol, m, length)
    fig = plt.figure(figsize=figsize)
    for i, k in enumerate(range(0, 3 * n + 1, n)):
        ax = fig.add_subplot(2, 2, i + 1, projection="3d")
        ax.view_init(elev=20, azim=-50)
        _scene(ax, sol, m, k, length)
        draw_state(ax, m.points[k], m.frames[k], length=length)
        ax.set_title(PHASE_TITLES[i], fontsize=9)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        set_equal(ax, lims, margin=0.05)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def _arc(ax: Any, centre: np.ndarray, start: float, sweep: float, r: float, color: str) -> np.ndarray:
    """An arc of radius r about a 2-D centre from the direction ``start`` through ``sweep`` (radians); its middle."""
    t = np.linspace(start, start + sweep, 40)
    ax.plot(centre[0] + r * np.cos(t), centre[1] + r * np.sin(t), color=color, lw=1.6)
    mid = start + sweep / 2
    return centre + r * np.array([np.cos(mid), np.sin(mid)])


def plot_triangle(arm: ThreeStepArm, w: Any, figsize: tuple[float, float] = (6.4, 5.6)) -> Figure:
    """Step 2 in the arm's plane: shoulder s, elbow e and wrist centre w, both elbow branches, and the angles
    γ (elevation of the line s-w), θ (between the upper arm and s-w, eq. 5) and β (at the elbow).

    Drawn from ``arm.three_step(w, I, elbow)`` for ``"up"`` and ``"down"``: the points are ``arm.joint_points`` of
    each solution, seen in the vertical plane through the base axis and w (horizontal: distance from the axis).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = plot_triangle(ThreeStepArm(1.5, 1.0), [0.5, 0.5, 2.0])
    >>> fig.axes[0].get_title()
    'step 2 in the arm plane: the triangle s, e, w'
    >>> plt.close(fig)
    """
    if not isinstance(arm, ThreeStepArm):
        raise ValueError(f"arm: expected ThreeStepArm(l1, l2), got {type(arm).__name__}")
    up, down = (arm.three_step(w, np.eye(3), elbow=e) for e in ("up", "down"))
    r_hat = np.array([np.cos(up.theta0), np.sin(up.theta0), 0.0])

    def plane(sol: ThreeStepSolution) -> np.ndarray:  # rows s, e, w as (horizontal distance, height)
        P = arm.joint_points(sol.theta0, sol.theta1, sol.theta2)
        return np.column_stack([P @ r_hat, P[:, 2]])

    (s_, e_up, w_), e_dn = plane(up), plane(down)[1]
    fig, ax = plt.subplots(figsize=figsize)
    l3 = float(np.hypot(*(w_ - s_)))
    ax.axhline(0.0, color="0.6", lw=1, ls=":")
    ax.plot(*np.transpose([s_, w_]), color="0.45", lw=1.2, ls="--")
    ax.plot(*np.transpose([s_, e_up, w_]), "o-", color="tab:blue", lw=3, ms=6, label="elbow up")
    ax.plot(*np.transpose([s_, e_dn, w_]), "o--", color="tab:orange", lw=2, ms=5, label="elbow down")
    g_mid = _arc(ax, s_, 0.0, up.phi, 0.22 * l3, "tab:green")
    t_mid = _arc(ax, s_, up.phi, up.theta, 0.36 * l3, "tab:purple")
    a_s, a_w = (float(np.arctan2(*(p - e_up)[::-1])) for p in (s_, w_))
    b_mid = _arc(ax, e_up, a_s, float(wrap_angle(a_w - a_s)), 0.16 * l3, "tab:red")
    labels = [
        Label(s_, "$s$", prefer=225), Label(w_, "$w$", prefer=0), Label(e_up, "$e$ (up)", "tab:blue", prefer=135),
        Label(e_dn, "$e$ (down)", "tab:orange", prefer=-45),
        Label(g_mid, "$\\gamma$", "tab:green", prefer=0), Label(t_mid, "$\\theta$", "tab:purple", prefer=0),
        Label(b_mid, "$\\beta$", "tab:red", prefer=-90),
        Label((s_ + e_up) / 2, "$\\ell_1$", "tab:blue", prefer=135), Label((e_up + w_) / 2, "$\\ell_2$", "tab:blue",
                                                                             prefer=45),
        Label(0.8 * s_ + 0.2 * w_ + 0.0, "$\\ell_3$", "0.35", prefer=-45),
    ]  # fmt: skip
    ax.set_aspect("equal", adjustable="datalim")  # the axes fill the figure; the wider limits show more plane
    ax.margins(0.12)
    ax.set(
        xlabel="distance from the base axis", ylabel="height z", title="step 2 in the arm plane: the triangle s, e, w"
    )
    ax.xaxis.set_major_locator(MaxNLocator(nbins=5, steps=[1, 2, 5, 10]))  # round steps, few numbers
    ax.legend(loc="lower right")
    place_labels(
        ax, labels, lines=[np.array([s_, e_up, w_]), np.array([s_, e_dn, w_]), np.array([s_, w_])], fontsize=12
    )
    return fig


def animate(
    sol: ThreeStepSolution,
    steps_per_phase: int = 10,
    length: float = 0.5,
    figsize: tuple[float, float] = (4.2, 4.0),
    dpi: int = 60,
    interval: int = 120,
) -> FuncAnimation:
    """The source's Figure 3: the arm moves through the three steps to the red target frame.

    3 * steps_per_phase + 1 frames (see :func:`~puma_course.kinematics.three_step.motion`).
    Show it with :func:`~puma_course.viz.animation.jshtml`: it plays in JupyterLab with
    nothing to install. The figure is created with its ``dpi`` (set at creation
    so that closing the figure does not reset it).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import ThreeStepArm
    >>> sol = ThreeStepArm(1.5, 1.0).three_step([0.5, 0.5, 2.0], np.diag([-1.0, 1.0, -1.0]))
    >>> anim = animate(sol, steps_per_phase=1)
    >>> type(anim).__name__, len(list(anim.new_frame_seq()))  # 3 * 1 + 1 frames
    ('FuncAnimation', 4)
    >>> anim.to_jshtml().count("data:image/png")  # one embedded PNG per frame
    4
    """
    m = motion(sol, steps_per_phase=steps_per_phase)
    lims = _limits(sol, m, length)
    fig = plt.figure(figsize=figsize, dpi=dpi)
    ax = fig.add_subplot(projection="3d")

    def draw(k: int) -> list[Any]:
        ax.cla()
        ax.view_init(elev=20, azim=-50)
        arts = _scene(ax, sol, m, k, length)
        arts += draw_state(ax, m.points[k], m.frames[k], length=length)
        ax.set_title(PHASE_TITLES[int(m.phase[k])], fontsize=9)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        set_equal(ax, lims, margin=0.05)
        ax.grid(False)  # the grid lines nearly double the size of every PNG frame
        return arts

    anim = FuncAnimation(fig, draw, frames=len(m.phase), interval=interval, blit=False)
    plt.close(fig)
    return anim
