"""Drawing arms: any robot through the robot API, or a chain from its frames; pictures and animations.

:func:`draw_robot` draws every arm of the course the same way, from what the arm itself says:
its links are the polyline ``robot.points(q)`` (the PUMA-560's shows the shoulder offset d3),
its triads the frames ``robot.frames(q)``. :func:`draw_chain` draws any chain given only its
frames (links through the frame origins). Animations are ``FuncAnimation`` objects to show with
``viz.jshtml(anim)``, which plays in JupyterLab and on the course's website with nothing fetched.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.figure import Figure

from .._validate import as_array
from ..kinematics.robot import Robot
from .frames import draw_frame, draw_frames, draw_points, new_axes, set_equal

__all__ = ["draw_chain", "draw_robot", "plot_chain", "plot_robot", "animate_frames", "animate_robot"]

#: Which triads :func:`draw_robot` draws: every frame, the last one (the end effector) or none.
TRIADS = ("all", "last", "none")


def _frame_stack(frames: Any, name: str = "frames") -> np.ndarray:
    return as_array(frames, name, (4, 4), batch=True).reshape(-1, 4, 4)


def _joint_axes(ax: Any, F: np.ndarray, length: float, alpha: float) -> list[Any]:
    """The z axis of every frame (its joint axis) as a thin dashed line through its origin."""
    artists: list[Any] = []
    for T in F:
        o, z = T[:3, 3], T[:3, 2]
        artists += ax.plot(*np.stack([o - 0.6 * length * z, o + 0.6 * length * z]).T, ls="--", lw=1,
                           color="tab:blue", alpha=0.5 * alpha)  # fmt: skip
    return artists


def draw_chain(
    ax: Any,
    frames: Any,
    *,
    axes: bool = True,
    triads: bool = True,
    labels: Sequence[str] | None = None,
    length: float | None = None,
    color: str = "0.3",
    alpha: float = 1.0,
) -> list[Any]:
    """Draw a chain from its frames (k, 4, 4): links between origins, joint axes (z), triads.

    The joint axis of frame {i} is its z axis, drawn as a thin dashed line. ``length`` (triads
    and axes) defaults to 0.12 times the chain's extent. Returns the artists: one link polyline,
    one axis line per frame, then the triads.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import Puma560
    >>> arm = Puma560()
    >>> fig, ax = new_axes()
    >>> arts = draw_chain(ax, arm.frames(arm.q("qz")), triads=False)
    >>> len(arts)  # 1 polyline + 7 joint axes
    8
    >>> plt.close(fig)
    """
    F = _frame_stack(frames)
    P = F[:, :3, 3]
    span = float(np.max(np.ptp(P, axis=0))) if len(P) > 1 else 1.0
    L = length if length is not None else 0.12 * max(span, 1e-9)
    artists = list(draw_points(ax, P, color=color, alpha=alpha))
    if axes:
        artists += _joint_axes(ax, F, L, alpha)
    if triads:
        artists += draw_frames(ax, F, labels=labels, length=L, alpha=alpha)
    return artists


def _triad_indices(triads: str | Sequence[int], m: int) -> list[int]:
    if isinstance(triads, str):
        if triads not in TRIADS:
            raise ValueError(f"triads: expected one of {TRIADS} or a list of frame indices, got {triads!r}")
        return {"all": list(range(m)), "last": [m - 1], "none": []}[triads]
    idx = [int(i) for i in triads]
    if any(not -m <= i < m for i in idx):
        raise ValueError(f"triads: expected frame indices in 0..{m - 1}, got {list(triads)!r}")
    return [i % m for i in idx]


def _default_length(P: np.ndarray) -> float:
    """Triad length: 8 % of the arm's total link length (the same in every pose of a revolute arm)."""
    total = float(np.sum(np.linalg.norm(np.diff(P, axis=0), axis=1)))
    return 0.08 * (total if total > 0.0 else 1.0)


def draw_robot(
    ax: Any,
    robot: Robot,
    q: Any,
    *,
    color: str = "tab:orange",
    alpha: float = 1.0,
    lw: float = 4.0,
    label: str | None = None,
    triads: str | Sequence[int] = "last",
    labels: Sequence[str] | None = None,
    length: float | None = None,
    axes: bool = False,
    ls: str = "-",
    marker: str = "o",
) -> list[Any]:
    """Draw any robot at ``q`` (n,) or several at (N, n): links ``robot.points(q)``, triads ``robot.frames(q)``.

    ``triads`` picks the frames whose triads are drawn: ``"last"`` (the end effector, default),
    ``"all"``, ``"none"`` or a list of indices into ``robot.frames(q)``; ``labels`` has one text
    per frame, e.g. ``["{0}", "", ..., "{6}"]`` (default: no texts); ``axes`` adds each frame's
    z axis (its joint axis) dashed. Use a low ``alpha`` for ghost arms and ``label`` for a legend
    (given to the first arm's links only). A triad with a text in ``labels`` has its axes lettered x, y, z
    (:func:`~puma_course.viz.frames.draw_frame`); the others stay bare, as in a ghost arm or an animation's
    frames, where letters would clutter (a still picture names the triads it asks the reader to read, e.g.
    with :func:`~puma_course.viz.frames.triad_letters`). ``length`` (triads) defaults to 8 % of the total link
    length. ``ls`` and ``marker`` style the links, so that two arms drawn together differ by more than their
    colour (e.g. ``ls="--", marker="s"`` for the second). Returns the artists, per arm: the links line first, then
    axes and triads.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import Puma560
    >>> arm = Puma560()
    >>> fig, ax = new_axes()
    >>> arts = draw_robot(ax, arm, arm.q("qn"), label="qn")
    >>> len(arts), arts[0].get_label()  # the links and the hand triad's 3 lines
    (4, 'qn')
    >>> dashed = draw_robot(ax, arm, arm.q("qz"), ls="--", marker="s", triads="none")
    >>> dashed[0].get_linestyle(), dashed[0].get_marker()
    ('--', 's')
    >>> bool(np.allclose(np.transpose(arts[0].get_data_3d()), arm.points(arm.q("qn"))))
    True
    >>> plt.close(fig)
    """
    if not isinstance(robot, Robot):
        raise ValueError(f"robot: expected a Robot (Puma560(), MK3(), Porter(...), ...), got {type(robot).__name__}")
    Q = robot.check_q(q)
    P, F = robot.points(Q), robot.frames(Q)
    if Q.ndim == 1:
        P, F = P[None], F[None]
    m = F.shape[-3]
    idx = _triad_indices(triads, m)
    if labels is None:
        labels = [""] * m
    elif len(labels) != m:
        raise ValueError(f"labels: expected {m} texts (one per frame of {robot.name}), got {len(labels)}")
    artists: list[Any] = []
    for j, (Pj, Fj) in enumerate(zip(P, F, strict=True)):
        L = length if length is not None else _default_length(Pj)
        artists += draw_points(
            ax, Pj, color=color, lw=lw, alpha=alpha, marker=marker, ls=ls, label=label if j == 0 else None
        )
        if axes:
            artists += _joint_axes(ax, Fj, L, alpha)
        for i in idx:
            artists += draw_frame(ax, Fj[i], labels[i], length=L, alpha=alpha)
    return artists


def _view_points(robot: Robot, Q: np.ndarray) -> np.ndarray:
    """Every point a drawing of ``robot`` at ``Q`` shows (links and frame origins) and the base origin."""
    P = robot.points(Q).reshape(-1, 3)
    O = robot.frames(Q)[..., :3, 3].reshape(-1, 3)
    return np.vstack([P, O, np.zeros((1, 3))])


def plot_chain(frames: Any, title: str | None = None, ax: Any | None = None, **kw: Any) -> tuple[Figure, Any]:
    """A new 3-D axes (or ``ax``) with one chain drawn by :func:`draw_chain`, equal scaling; ``(fig, ax)``.

    The base origin is always in view (the limits include (0, 0, 0)).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import Puma560
    >>> arm = Puma560()
    >>> fig, ax = plot_chain(arm.frames(arm.q("qr")), title="PUMA-560 at qr")
    >>> ax.get_title(), bool(np.isclose(np.ptp(ax.get_xlim3d()), np.ptp(ax.get_zlim3d())))
    ('PUMA-560 at qr', True)
    >>> plt.close(fig)
    """
    if ax is None:
        fig, ax = new_axes(title=title)
    else:
        fig = ax.figure
    draw_chain(ax, frames, **kw)
    F = _frame_stack(frames)
    set_equal(ax, np.vstack([F[:, :3, 3], np.zeros((1, 3))]))
    return fig, ax


def plot_robot(robot: Robot, q: Any, title: str | None = None, ax: Any | None = None, **kw: Any) -> tuple[Figure, Any]:
    """A new 3-D axes (or ``ax``) with ``robot`` drawn at ``q`` by :func:`draw_robot`, equal scaling; ``(fig, ax)``.

    ``title`` defaults to the robot's name; other keywords go to :func:`draw_robot`.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import MK3
    >>> fig, ax = plot_robot(MK3(), MK3().q("qr"), triads="all")
    >>> ax.get_title(), len(ax.lines)  # the links and 6 triads of 3 lines
    ('Motoman MK3', 19)
    >>> plt.close(fig)
    """
    if ax is None:
        fig, ax = new_axes(title=robot.name if title is None else title)
    else:
        fig = ax.figure
    draw_robot(ax, robot, q, **kw)
    set_equal(ax, _view_points(robot, robot.check_q(q)))
    return fig, ax


def _animate(
    count: int,
    draw_one: Callable[[Any, int], list[Any]],
    lims: np.ndarray,
    extra: Callable[[Any, int], Any] | None,
    title: str | None,
    interval: int,
    figsize: tuple[float, float],
    dpi: float,
) -> FuncAnimation:
    # The dpi must be given at creation: plt.close() resets a later set_dpi() (matplotlib 3.11).
    fig, ax = new_axes(figsize=figsize, title=title, dpi=dpi)

    def draw(t: int) -> list[Any]:
        ax.cla()
        if title:
            ax.set_title(title)
        ax.set(xlabel="x", ylabel="y", zlabel="z")
        arts = draw_one(ax, t)
        if extra is not None:
            arts += list(extra(ax, t))
        set_equal(ax, lims)
        return arts

    anim = FuncAnimation(fig, draw, frames=count, interval=interval, blit=False)
    plt.close(fig)
    return anim


def animate_frames(
    frames_seq: Any,
    *,
    extra: Callable[[Any, int], Any] | None = None,
    title: str | None = None,
    interval: int = 80,
    figsize: tuple[float, float] = (5.0, 4.5),
    dpi: int = 110,
    **kw: Any,
) -> FuncAnimation:
    """An animation of a chain whose frames over time are ``frames_seq`` (T, k, 4, 4).

    ``extra(ax, t)`` may draw more on each frame (a target, a path) and return its artists.
    Show it with :func:`~puma_course.viz.animation.jshtml`. Keep T and ``dpi`` modest (the figure is created
    with its ``dpi``, so closing it does not reset it). Other keywords go to :func:`draw_chain`
    (e.g. ``triads=False``, ``color``).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import Puma560
    >>> arm = Puma560()
    >>> seq = arm.frames(np.linspace(arm.q("qz"), arm.q("qr"), 3))  # (3, 7, 4, 4)
    >>> anim = animate_frames(seq, triads=False, dpi=40, figsize=(2.0, 2.0))
    >>> type(anim).__name__, anim.to_jshtml().count("data:image/png")
    ('FuncAnimation', 3)
    """
    S = as_array(frames_seq, "frames_seq", (None, 4, 4), batch=True)
    if S.ndim == 3:
        S = S[None]
    lims = np.vstack([S[:, :, :3, 3].reshape(-1, 3), np.zeros((1, 3))])
    return _animate(len(S), lambda ax, t: draw_chain(ax, S[t], **kw), lims, extra, title, interval, figsize, dpi)


def animate_robot(
    robot: Robot,
    q_seq: Any,
    *,
    extra: Callable[[Any, int], Any] | None = None,
    title: str | None = None,
    interval: int = 80,
    figsize: tuple[float, float] = (5.0, 4.5),
    dpi: int = 110,
    **kw: Any,
) -> FuncAnimation:
    """An animation of ``robot`` moving through the joint vectors ``q_seq`` (T, n), drawn by :func:`draw_robot`.

    ``extra``, ``interval``, ``figsize`` and ``dpi`` as in :func:`animate_frames`; other
    keywords go to :func:`draw_robot` (e.g. ``triads="none"``, ``color``). The view frames
    every pose of the sequence and the base origin.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course import Puma560
    >>> arm = Puma560()
    >>> anim = animate_robot(arm, np.linspace(arm.q("qz"), arm.q("qr"), 3), dpi=40, figsize=(2.0, 2.0))
    >>> type(anim).__name__, anim.to_jshtml().count("data:image/png")
    ('FuncAnimation', 3)
    """
    if not isinstance(robot, Robot):
        raise ValueError(f"robot: expected a Robot (Puma560(), MK3(), Porter(...), ...), got {type(robot).__name__}")
    Q = robot.check_q(q_seq)
    if Q.ndim == 1:
        Q = Q[None]
    lims = _view_points(robot, Q)
    return _animate(len(Q), lambda ax, t: draw_robot(ax, robot, Q[t], **kw), lims, extra, title, interval, figsize,
                    dpi)  # fmt: skip
