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
    """A new figure with one 3-D axes; returns ``(fig, ax)``."""
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
    """Equal scaling on all three axes, framing ``points`` (k, 3) or what is drawn."""
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
    """Draw one frame's triad (x red, y green, z blue) with an optional label ``{i}``."""
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
    """Draw a triad for every frame in ``frames`` (k, 4, 4); labels default to {0}..{k-1}."""
    F = as_array(frames, "frames", (4, 4), batch=True).reshape(-1, 4, 4)
    if labels is None:
        labels = [f"{{{i}}}" for i in range(len(F))]
    artists = []
    for T, lab in zip(F, labels, strict=False):
        artists += draw_frame(ax, T, lab, length=length, **kw)
    return artists


def draw_points(ax: Any, points: Any, color: str = "0.3", lw: float = 4.0, alpha: float = 1.0, marker: str = "o", **kw):
    """Draw a polyline through joint points (k, 3): the links of an arm."""
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
    """Convenience: a new 3-D axes with one chain drawn and equal scaling; returns ``(fig, ax)``."""
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
    in JupyterLab with nothing to install. Keep T and ``dpi`` modest.
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
