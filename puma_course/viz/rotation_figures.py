"""The figures of lecture 01: frames in a row, fixed versus moving axes, Euler-angle turns, the gimbal lock.

Drawing only: the rotations come from :mod:`puma_course.transforms` and :mod:`puma_course.euler`,
and the lecture computes what is plotted; these helpers do the layout that makes it readable
(one small axes per frame so each triad fills its picture, the same view in all of them, angle
curves that draw no false vertical stroke where an angle wraps from +180° to -180°). Angles go
in as radians and are shown in degrees.

* :func:`draw_triad`: one frame in its own 3-D axes, its tips named x, y, z and, dashed, the
  axis of the turn that produced it; :func:`plot_frame_sequence`: a grid of those, one per step;
* :func:`plot_fixed_vs_moving`: two motions composed about the moving axes (A B) and about the
  fixed axes (B A);
* :func:`plot_euler_steps`: the three turns of ZYZ (about the moving axes) or of roll-pitch-yaw
  (about the fixed axes), one frame after each turn;
* :func:`draw_angle_sweep`: angles against a parameter, broken where they wrap;
* :func:`draw_lock_gain`: how far a small turn of R moves φ and ψ near the gimbal lock, on log
  axes, beside the first-order values cot ϑ and 1/sin ϑ.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure

from .._validate import as_array, as_rotation
from ..transforms import axis_angle, homogeneous, rotx, roty, rotz
from .frames import AXIS_COLORS, draw_frame
from .style import text_color

__all__ = ["CONVENTIONS", "draw_triad", "plot_frame_sequence", "plot_fixed_vs_moving", "plot_euler_steps",
           "draw_angle_sweep", "draw_lock_gain"]  # fmt: skip

#: The Euler-angle sets :func:`plot_euler_steps` draws: "zyz" (φ, ϑ, ψ) and "rpy" (roll, pitch, yaw).
CONVENTIONS = ("zyz", "rpy")

_E = np.eye(3)
_TIP = 1.18  # a tip's name sits this many triad lengths from the origin
_AXIS_REACH = 1.3  # a turn axis is drawn this many triad lengths to each side of the origin


def _rotation_part(value: Any, name: str) -> np.ndarray:
    """A rotation (3, 3) from a rotation or a rigid transform (4, 4); refused otherwise."""
    arr = as_array(value, name, what="a 3x3 rotation or a 4x4 transform")
    if arr.shape == (4, 4):
        arr = arr[:3, :3]
    return as_rotation(arr, name)


def draw_triad(ax: Any, rotation: Any, *, turn_axis: Any = None, length: float = 1.0, lw: float = 3.0) -> list[Any]:
    """Draw one frame's triad at the origin of its own 3-D axes, its tips named x, y, z in their colours.

    The lines are the columns of ``rotation`` (3, 3), or of the rotation of a transform (4, 4):
    x red, y green, z blue. ``turn_axis`` (a 3-vector) adds the axis of the turn that produced
    the frame as a dashed grey line through the origin. The axes hold the unit ball with equal
    scaling, without ticks (only directions matter); the scene's own axes are named on the box.
    Returns the artists: three lines, three tip names, then the turn axis if any.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = plt.figure()
    >>> ax = fig.add_subplot(projection="3d")
    >>> arts = draw_triad(ax, rotz(np.pi / 2), turn_axis=[0, 0, 1])
    >>> len(arts), [round(float(v), 12) + 0.0 for v in arts[0].get_data_3d()[1]]  # the x axis ends on y
    (7, [0.0, 1.0])
    >>> plt.close(fig)
    """
    R = _rotation_part(rotation, "rotation")
    length = float(as_array(length, "length", ()))
    if length <= 0:
        raise ValueError(f"length: expected a positive number, got {length}")
    artists: list[Any] = []
    artists += draw_frame(ax, homogeneous(R, np.zeros(3)), length=length, lw=lw)
    for k, name in enumerate("xyz"):
        tip = _TIP * length * R[:, k]
        artists.append(ax.text(*tip, name, color=text_color(AXIS_COLORS[k]), fontsize=12, fontweight="bold",
                               ha="center", va="center"))  # fmt: skip
    if turn_axis is not None:
        v = as_array(turn_axis, "turn_axis", (3,))
        n = float(np.sqrt(v @ v))
        if n == 0.0:
            raise ValueError("turn_axis: expected a non-zero 3-vector, got a zero vector")
        ends = np.stack([-_AXIS_REACH * length * v / n, _AXIS_REACH * length * v / n])
        artists += ax.plot(*ends.T, ls="--", lw=1.5, color="0.3")
    r = _AXIS_REACH * length
    ax.set(xlim=(-r, r), ylim=(-r, r), zlim=(-r, r), xticks=[], yticks=[], zticks=[])
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("scene x", labelpad=-12)
    ax.set_ylabel("scene y", labelpad=-12)
    ax.set_zlabel("scene z", labelpad=-12)
    return artists


def plot_frame_sequence(
    rotations: Sequence[Any],
    titles: Sequence[str],
    *,
    turn_axes: Sequence[Any] | None = None,
    ncols: int | None = None,
    row_titles: Sequence[str] | None = None,
    figsize: tuple[float, float] | None = None,
    elev: float = 22,
    azim: float = -55,
) -> tuple[Figure, np.ndarray]:
    """One small 3-D axes per frame, in rows of ``ncols`` (default: all in one row), each titled.

    ``turn_axes`` (one per frame, a 3-vector or None) dashes the axis of the turn that produced
    each frame; ``row_titles`` names each row (written at the left of its first axes). All axes
    share one view (``elev``, ``azim`` in degrees), so the frames compare at a glance.
    Returns ``(fig, axes)`` with axes of shape (rows, ncols).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, axes = plot_frame_sequence([np.eye(3), rotz(0.5)], ["start", "after"])
    >>> axes.shape, axes[0, 1].get_title()
    ((1, 2), 'after')
    >>> plt.close(fig)
    """
    Rs = [_rotation_part(R, f"rotations[{i}]") for i, R in enumerate(rotations)]
    k = len(Rs)
    if k == 0:
        raise ValueError("rotations: expected at least one rotation, got none")
    if len(titles) != k:
        raise ValueError(f"titles: expected {k} texts (one per rotation), got {len(titles)}")
    turns = [None] * k if turn_axes is None else list(turn_axes)
    if len(turns) != k:
        raise ValueError(f"turn_axes: expected {k} entries (a 3-vector or None per rotation), got {len(turns)}")
    ncols = k if ncols is None else int(ncols)
    if ncols < 1:
        raise ValueError(f"ncols: expected a positive whole number, got {ncols}")
    nrows = -(-k // ncols)
    if row_titles is not None and len(row_titles) != nrows:
        raise ValueError(f"row_titles: expected {nrows} texts (one per row), got {len(row_titles)}")
    size = (round(2.8 * ncols + (1.2 if row_titles else 0.0), 1), round(2.9 * nrows, 1))
    fig = plt.figure(figsize=figsize or size)
    axes = np.empty((nrows, ncols), dtype=object)
    for i in range(nrows * ncols):
        ax = fig.add_subplot(nrows, ncols, i + 1, projection="3d")
        axes.flat[i] = ax
        if i >= k:
            ax.set_axis_off()
            continue
        draw_triad(ax, Rs[i], turn_axis=turns[i])
        ax.view_init(elev=elev, azim=azim)
        ax.set_title(titles[i])
    for r, text in enumerate(row_titles or []):
        axes[r, 0].text2D(-0.12, 0.5, text, transform=axes[r, 0].transAxes, rotation=90, ha="right", va="center",
                          fontsize=12)  # fmt: skip
    return fig, axes


def _turn_axis(R: np.ndarray) -> np.ndarray | None:
    k, t = axis_angle(R)
    return None if abs(float(t)) < 1e-12 else np.asarray(k)


def plot_fixed_vs_moving(A: Any, B: Any, names: tuple[str, str] = ("A", "B")) -> tuple[Figure, np.ndarray]:
    r"""First A, then B: about the moving axes (A B, top row) and about the fixed axes (B A, bottom row).

    ``A`` and ``B`` are rotations (3, 3) or transforms (4, 4; only their rotations are drawn).
    Each row shows the start, the frame after A and the frame after B, the axis of each turn
    dashed: on top B turns about its own axis carried along by A (A k_B), below about the fixed
    k_B. Returns ``(fig, axes)``, axes of shape (2, 3).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, axes = plot_fixed_vs_moving(rotz(np.pi / 2), rotx(np.pi / 2))
    >>> [ax.get_title() for ax in axes[:, 2]]
    ['after $B$: $A\\,B$', 'after $B$: $B\\,A$']
    >>> plt.close(fig)
    """
    RA, RB = _rotation_part(A, "A"), _rotation_part(B, "B")
    a, b = names
    kA, kB = _turn_axis(RA), _turn_axis(RB)
    rotations = [_E, RA, RA @ RB, _E, RA, RB @ RA]
    titles = ["start", f"after ${a}$", f"after ${b}$: ${a}\\,{b}$",
              "start", f"after ${a}$", f"after ${b}$: ${b}\\,{a}$"]  # fmt: skip
    turns = [None, kA, None if kB is None else RA @ kB, None, kA, kB]
    return plot_frame_sequence(rotations, titles, turn_axes=turns, ncols=3,
                               row_titles=["moving axes", "fixed axes"])  # fmt: skip


def _euler_steps(angles: Any, convention: str) -> tuple[list[np.ndarray], list[np.ndarray], list[str], str]:
    """The frames after each turn, the axis of each turn (in scene coordinates), the titles."""
    if not isinstance(convention, str) or convention not in CONVENTIONS:
        raise ValueError(f"convention: expected one of {CONVENTIONS}, got {convention!r}")
    a, b, c = (float(v) for v in as_array(angles, "angles", (3,), what="three angles in radians"))
    deg = np.degrees([a, b, c]).round(0).astype(int).tolist()
    if convention == "zyz":  # about the moving axes: multiply on the right
        R1 = rotz(a)
        R2 = R1 @ roty(b)
        R3 = R2 @ rotz(c)
        turns = [_E[2], R1[:, 1], R2[:, 2]]
        labels = ["start", f"1: about $z$, $\\varphi$ = {deg[0]}°", f"2: about $y'$, $\\vartheta$ = {deg[1]}°",
                  f"3: about $z''$, $\\psi$ = {deg[2]}°"]  # fmt: skip
        title = r"ZYZ: $R_z(\varphi)\,R_y(\vartheta)\,R_z(\psi)$, turns about the moving axes"
    else:  # roll, pitch, yaw about the fixed axes: multiply on the left
        R1 = rotx(a)
        R2 = roty(b) @ R1
        R3 = rotz(c) @ R2
        turns = [_E[0], _E[1], _E[2]]
        labels = ["start", f"1: about $x_0$, roll = {deg[0]}°", f"2: about $y_0$, pitch = {deg[1]}°",
                  f"3: about $z_0$, yaw = {deg[2]}°"]  # fmt: skip
        title = r"RPY: $R_z(\mathrm{yaw})\,R_y(\mathrm{pitch})\,R_x(\mathrm{roll})$, turns about the fixed axes"
    return [_E, R1, R2, R3], turns, labels, title


def plot_euler_steps(angles: Any, convention: str = "zyz", *, elev: float = 22,
                     azim: float = -55) -> tuple[Figure, np.ndarray]:  # fmt: skip
    r"""The three turns of an Euler-angle set: the frame after each turn, the axis of each turn dashed.

    ``convention="zyz"``: ``angles`` = (φ, ϑ, ψ), turns about z, the new y', the newest z''
    (moving axes, Rz(φ) Ry(ϑ) Rz(ψ)). ``"rpy"``: (roll, pitch, yaw), turns about the fixed
    x, y, z (Rz(yaw) Ry(pitch) Rx(roll)). The last frame is the rotation the set describes; the
    figure's title names the product; ``elev``, ``azim`` (degrees) set the one view of all four.
    Returns ``(fig, axes)``, axes of shape (1, 4).

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, axes = plot_euler_steps([0.5, 0.7, 0.3])
    >>> axes[0, 1].get_title()
    '1: about $z$, $\\varphi$ = 29°'
    >>> plt.close(fig)
    """
    Rs, turns, titles, title = _euler_steps(angles, convention)
    fig, axes = plot_frame_sequence(Rs, titles, turn_axes=[None, *turns], elev=elev, azim=azim)
    fig.suptitle(title)
    return fig, axes


def _break_at_wraps(x: np.ndarray, y_deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Insert a gap (NaN) wherever consecutive values jump by more than 180°: an angle wrapping, not moving."""
    jumps = np.flatnonzero(np.abs(np.diff(y_deg)) > 180.0) + 1
    return np.insert(x, jumps, np.nan), np.insert(y_deg, jumps, np.nan)


def draw_angle_sweep(
    ax: Any,
    x: Any,
    angles: Any,
    labels: Sequence[str],
    *,
    xlabel: str,
    styles: Sequence[str] | None = None,
) -> list[Any]:
    """Plot angles (radians, shape (N,) or (N, m)) in degrees against ``x`` (N,), one line per column.

    A line is broken where its angle wraps (a jump of more than 180° between neighbours), so a
    wrap from +180° to -180° draws no false vertical stroke. The y axis spans -180°..180° in steps
    of 90°; the legend sits below the axes, off the data. Returns the lines.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = plt.subplots()
    >>> (line,) = draw_angle_sweep(ax, [0, 1, 2], np.radians([170.0, 179.0, -178.0]), ["φ"], xlabel="t [s]")
    >>> line.get_ydata().round(1).tolist()  # a gap where the angle wraps
    [170.0, 179.0, nan, -178.0]
    >>> plt.close(fig)
    """
    xs = as_array(x, "x", (None,), what="a 1-D array of parameter values")
    A = as_array(angles, "angles", what="angles in radians, of shape (N,) or (N, m)")
    if A.ndim == 1:
        A = A[:, None]
    if A.ndim != 2 or A.shape[0] != xs.shape[0]:
        raise ValueError(f"angles: expected shape ({xs.shape[0]},) or ({xs.shape[0]}, m), got {A.shape}")
    if len(labels) != A.shape[1]:
        raise ValueError(f"labels: expected {A.shape[1]} texts (one per column of angles), got {len(labels)}")
    styles = ["-"] * A.shape[1] if styles is None else list(styles)
    if len(styles) != A.shape[1]:
        raise ValueError(f"styles: expected {A.shape[1]} line styles, got {len(styles)}")
    lines = []
    for col, lab, st in zip(A.T, labels, styles, strict=True):
        xb, yb = _break_at_wraps(xs, np.degrees(col))
        lines += ax.plot(xb, yb, st, label=lab)
    ax.set(ylim=(-190, 190), yticks=[-180, -90, 0, 90, 180], xlabel=xlabel, ylabel="angle [deg]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.17), ncol=min(len(labels), 4), frameon=False)
    return lines


def draw_lock_gain(
    ax: Any,
    theta: Any,
    gains: Any,
    labels: Sequence[str],
    *,
    reference: bool = True,
) -> list[Any]:
    """Measured gains (change of an angle / size of the turn of R) against ϑ (radians), on log axes.

    ``gains`` (N,) or (N, m) are drawn as markers, ϑ in degrees on the x axis. With
    ``reference`` the first-order values are drawn too: cot ϑ (how far φ moves when R turns by δ
    about the horizontal axis along (r13, r23)) dashed, and 1/sin ϑ (how far ψ moves) dotted.
    Both grow like 1/ϑ towards the lock ϑ = 0. ϑ must lie in (0, π/2). Returns the lines.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = plt.subplots()
    >>> th = np.array([0.01, 0.1, 1.0])
    >>> lines = draw_lock_gain(ax, th, 1 / np.tan(th), ["φ"])
    >>> len(lines), ax.get_xscale(), ax.get_yscale()
    (3, 'log', 'log')
    >>> plt.close(fig)
    """
    th = as_array(theta, "theta", (None,), what="a 1-D array of angles in radians")
    if np.any(th <= 0.0) or np.any(th >= np.pi / 2):
        raise ValueError(f"theta: expected angles in (0, π/2) radians, got values from {th.min():g} to {th.max():g}")
    G = as_array(gains, "gains", what="positive gains of shape (N,) or (N, m)")
    if G.ndim == 1:
        G = G[:, None]
    if G.ndim != 2 or G.shape[0] != th.shape[0] or np.any(G <= 0.0):
        raise ValueError(f"gains: expected positive values of shape ({th.shape[0]},) or ({th.shape[0]}, m), got "
                         f"shape {G.shape}")  # fmt: skip
    if len(labels) != G.shape[1]:
        raise ValueError(f"labels: expected {G.shape[1]} texts (one per column of gains), got {len(labels)}")
    deg = np.degrees(th)
    lines = []
    for g, lab, marker in zip(G.T, labels, "os^v", strict=False):
        lines += ax.plot(deg, g, marker, ls="none", ms=7, mfc="none", mew=1.6, label=lab)
    if reference:
        # solid and dotted: a dashed line means an axis of turning in every lecture
        lines += ax.plot(deg, 1.0 / np.tan(th), "-", color="0.45", lw=1.5, label=r"$\cot\vartheta$")
        lines += ax.plot(deg, 1.0 / np.sin(th), ":", color="0.1", lw=1.5, label=r"$1/\sin\vartheta$")
    ax.set(xscale="log", yscale="log", xlabel=r"$\vartheta$ [deg]", ylabel="change of angle / size of turn")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="upper right")
    return lines
