"""Drawing arms, frames and animations with matplotlib (3-D, equal scaling).

Every function takes plain arrays: a chain's frames ``(k, 4, 4)`` (from
``DHChain.frames(q)`` or ``porter.frames(q)``) or joint points ``(k, 3)``.
Nothing here computes kinematics; this module depends on the kinematics
modules, never the reverse.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation

from ._validate import as_array

__all__ = [
    "new_axes",
    "set_equal",
    "draw_frame",
    "draw_frames",
    "draw_points",
    "draw_chain",
    "plot_chain",
    "animate_frames",
    "puma_points",
    "draw_puma",
    "AXIS_COLORS",
]

AXIS_COLORS = ("tab:red", "tab:green", "tab:blue")  # x, y, z


def new_axes(
    figsize: tuple[float, float] = (6.0, 5.0),
    title: str | None = None,
    elev: float = 25,
    azim: float = -60,
    dpi: float | None = None,
):
    """A new figure with one 3-D axes; returns ``(fig, ax)``.

    Angles ``elev``/``azim`` in degrees (matplotlib's view); axes labelled x, y, z.

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
    """Equal scaling on all three axes, framing ``points`` (k, 3) or what is drawn.

    The cube's half side is half the largest extent times ``1 + margin``.

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
        P = as_array(points, "points", (3,), batch=True).reshape(-1, 3)
        lims = np.stack([P.min(axis=0), P.max(axis=0)], axis=1)
    centre = lims.mean(axis=1)
    half = max(float(np.max(lims[:, 1] - lims[:, 0])) / 2.0, 1e-9) * (1.0 + margin)
    ax.set_xlim3d(centre[0] - half, centre[0] + half)
    ax.set_ylim3d(centre[1] - half, centre[1] + half)
    ax.set_zlim3d(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))


def draw_frame(ax: Any, T: Any, label: str | None = None, length: float = 0.1, alpha: float = 1.0, lw: float = 2.0):
    """Draw one frame's triad (x red, y green, z blue) with an optional label ``{i}``.

    ``T`` maps the frame's coordinates into the axes' (world) coordinates: the
    triad's lines are the columns of its rotation, from its origin.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> arts = draw_frame(ax, np.eye(4), label="{0}", length=1.0)
    >>> len(arts), arts[0].get_color(), [float(v) for v in arts[0].get_data_3d()[0]]
    (4, 'tab:red', [0.0, 1.0])
    >>> plt.close(fig)
    """
    T = as_array(T, "T", (4, 4))
    o = T[:3, 3]
    artists = []
    for k in range(3):
        e = o + length * T[:3, k]
        artists += ax.plot([o[0], e[0]], [o[1], e[1]], [o[2], e[2]], color=AXIS_COLORS[k], alpha=alpha, lw=lw)
    if label:
        artists.append(ax.text(*(o + 0.25 * length * (T[:3, 0] + T[:3, 1])), label, fontsize=9, alpha=alpha))
    return artists


def draw_frames(ax: Any, frames: Any, labels: Sequence[str] | None = None, length: float = 0.1, **kw: Any) -> list:
    """Draw a triad for every frame in ``frames`` (k, 4, 4); labels default to {0}..{k-1}.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> arts = draw_frames(ax, np.stack([np.eye(4)] * 2))
    >>> len(arts), [a.get_text() for a in arts if hasattr(a, "get_text")]
    (8, ['{0}', '{1}'])
    >>> plt.close(fig)
    """
    F = as_array(frames, "frames", (4, 4), batch=True).reshape(-1, 4, 4)
    if labels is None:
        labels = [f"{{{i}}}" for i in range(len(F))]
    artists = []
    for T, lab in zip(F, labels, strict=False):
        artists += draw_frame(ax, T, lab, length=length, **kw)
    return artists


def draw_points(ax: Any, points: Any, color: str = "0.3", lw: float = 4.0, alpha: float = 1.0, marker: str = "o", **kw):
    """Draw a polyline through joint points (k, 3): the links of an arm.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = new_axes()
    >>> (line,) = draw_points(ax, [[0, 0, 0], [1, 0, 0], [1, 1, 0]], color="k")
    >>> [float(v) for v in line.get_data_3d()[1]]
    [0.0, 0.0, 1.0]
    >>> plt.close(fig)
    """
    P = as_array(points, "points", (3,), batch=True).reshape(-1, 3)
    return ax.plot(P[:, 0], P[:, 1], P[:, 2], color=color, lw=lw, alpha=alpha, marker=marker, ms=lw + 2, **kw)


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
) -> list:
    """Draw a chain from its frames (k, 4, 4): links between origins, joint axes (z), triads.

    The joint axis of frame {i} is its z axis, drawn as a thin dashed line.
    Returns the artists: one link polyline, one axis line per frame, then the triads.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> fig, ax = new_axes()
    >>> arts = draw_chain(ax, arm.frames(arm.q("qz")), triads=False)
    >>> len(arts)  # 1 polyline + 7 joint axes
    8
    >>> plt.close(fig)
    """
    F = as_array(frames, "frames", (4, 4), batch=True).reshape(-1, 4, 4)
    P = F[:, :3, 3]
    span = float(np.max(np.ptp(P, axis=0))) if len(P) > 1 else 1.0
    L = length if length is not None else 0.12 * max(span, 1e-9)
    artists = list(draw_points(ax, P, color=color, alpha=alpha))
    if axes:
        for T in F:
            o, z = T[:3, 3], T[:3, 2]
            a, b = o - 0.6 * L * z, o + 0.6 * L * z
            seg = np.stack([a, b])
            artists += ax.plot(*seg.T, ls="--", lw=1, color="tab:blue", alpha=0.5 * alpha)
    if triads:
        artists += draw_frames(ax, F, labels=labels, length=L, alpha=alpha)
    return artists


def plot_chain(frames: Any, title: str | None = None, ax: Any | None = None, **kw: Any):
    """Convenience: a new 3-D axes with one chain drawn and equal scaling; returns ``(fig, ax)``.

    The base origin is always in view (the limits include (0, 0, 0)).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.robots import puma560
    >>> arm = puma560()
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
    F = as_array(frames, "frames", (4, 4), batch=True).reshape(-1, 4, 4)
    set_equal(ax, np.vstack([F[:, :3, 3], np.zeros((1, 3))]))
    return fig, ax


def animate_frames(
    frames_seq: Any,
    *,
    extra: Callable[[Any, int], list] | None = None,
    title: str | None = None,
    interval: int = 80,
    figsize: tuple[float, float] = (5.0, 4.5),
    dpi: int = 72,
    **kw: Any,
) -> FuncAnimation:
    """An animation of a chain whose frames over time are ``frames_seq`` (T, k, 4, 4).

    ``extra(ax, t)`` may draw more on each frame (a target, a path) and return
    its artists. Show it in a notebook with ``HTML(anim.to_jshtml())``: it plays
    in JupyterLab with nothing to install. Keep T and ``dpi`` modest. Other
    keywords go to :func:`draw_chain` (e.g. ``triads=False``, ``color``).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> seq = arm.frames(np.linspace(arm.q("qz"), arm.q("qr"), 3))  # (3, 7, 4, 4)
    >>> anim = animate_frames(seq, triads=False, dpi=40, figsize=(2.0, 2.0))
    >>> type(anim).__name__, anim.to_jshtml().count("data:image/png")
    ('FuncAnimation', 3)
    """
    S = as_array(frames_seq, "frames_seq", (None, 4, 4), batch=True)
    if S.ndim == 3:
        S = S[None]
    # The dpi must be given at creation: plt.close() resets a later set_dpi() (matplotlib 3.11).
    fig, ax = new_axes(figsize=figsize, title=title, dpi=dpi)
    pts = S[:, :, :3, 3].reshape(-1, 3)
    lims = np.vstack([pts, np.zeros((1, 3))])

    def draw(t: int) -> list:
        ax.cla()
        if title:
            ax.set_title(title)
        arts = draw_chain(ax, S[t], **kw)
        if extra is not None:
            arts += list(extra(ax, t))
        set_equal(ax, lims)
        return arts

    anim = FuncAnimation(fig, draw, frames=len(S), interval=interval, blit=False)
    plt.close(fig)
    return anim


def puma_points(frames: Any, d3: float, a3: float, pedestal: float = 0.35) -> np.ndarray:
    """Six points that draw a PUMA-560 with its shoulder offset visible, from its frames.

    ``frames`` (7, 4, 4) or (N, 7, 4, 4) are ``puma560().frames(q)`` (Craig's
    modified DH, lecture 03): frames {1} and {2} sit at the base origin and
    {4} = {5} = {6} at the wrist centre, so a polyline through the frame origins
    hides the sideways offset d3. The points are: a foot ``pedestal`` below the
    base origin along z0, the base origin, the end of the offset d3 along z2,
    the origin of {3} (the upper arm a2 ends there), the end of the step a3
    along x3, and the wrist centre (origin of {4}; the forearm d4 ends there).
    Returns (6, 3) or (N, 6, 3).

    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> P = puma_points(arm.frames(arm.q("qz")), arm.lengths["d3"], arm.lengths["a3"])
    >>> np.round(P, 5) + 0.0  # at qz the wrist centre is (a2 + a3, d3, -d4)
    array([[ 0.     ,  0.     , -0.35   ],
           [ 0.     ,  0.     ,  0.     ],
           [ 0.     ,  0.15005,  0.     ],
           [ 0.4318 ,  0.15005,  0.     ],
           [ 0.4521 ,  0.15005,  0.     ],
           [ 0.4521 ,  0.15005, -0.4318 ]])
    """
    F = as_array(frames, "frames", (7, 4, 4), batch=True, what="a PUMA-560's frames {0}..{6}")
    o = F[..., :3, 3]
    foot = o[..., 0, :] - pedestal * F[..., :3, 2][..., 0, :]
    shoulder = o[..., 2, :] + d3 * F[..., :3, 2][..., 2, :]
    step = o[..., 3, :] + a3 * F[..., :3, 0][..., 3, :]
    return np.stack([foot, o[..., 0, :], shoulder, o[..., 3, :], step, o[..., 4, :]], axis=-2)


def draw_puma(
    ax: Any,
    frames: Any,
    d3: float,
    a3: float,
    *,
    color: str = "tab:orange",
    alpha: float = 1.0,
    lw: float = 4.0,
    pedestal: float = 0.35,
    wrist_frame: bool = True,
    frame_length: float = 0.12,
    label: str | None = None,
) -> list:
    """Draw one PUMA-560 from its frames (7, 4, 4): grey pedestal, links with the offset d3, hand triad.

    The links run through :func:`puma_points`; the triad of the hand frame
    {6} (``frames[6]``, the pose ^0T_6) is drawn at the wrist centre when
    ``wrist_frame``. Use a low ``alpha`` for ghost arms and ``label`` for a legend.
    Returns the artists.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.robots import puma560
    >>> arm = puma560()
    >>> fig, ax = new_axes()
    >>> arts = draw_puma(ax, arm.frames(arm.q("qn")), arm.lengths["d3"], arm.lengths["a3"], label="qn")
    >>> len(arts), arts[1].get_label()  # pedestal, links, 3 triad lines
    (5, 'qn')
    >>> plt.close(fig)
    """
    F = as_array(frames, "frames", (7, 4, 4), what="one PUMA-560's frames {0}..{6}")
    P = puma_points(F, d3, a3, pedestal)
    artists = list(ax.plot(*P[:2].T, color="0.5", lw=lw + 2, alpha=alpha))
    artists += ax.plot(*P[1:].T, color=color, lw=lw, marker="o", ms=lw, alpha=alpha, label=label)
    if wrist_frame:
        artists += draw_frame(ax, F[6], length=frame_length, alpha=alpha)
    return artists
