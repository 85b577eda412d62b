"""A frame step of Craig's frame assignment as a dimensioned drawing (lecture 03's step 3).

Two flat views, drawn by :func:`~.dh_figures.plot_step_dimensions` (which documents them): the plane of X_k
and Z_k with dimension lines for d_k and a_k, and the view along X_k with the twist α_k. The geometry comes
from :func:`~puma_course.kinematics.frame_assignment.frame_steps`; nothing is computed here but where to draw.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..kinematics.frame_assignment import FrameWalk
from .frames import AXIS_COLORS
from .style import AXIS_LINE, JOINT_COLOR, NORMAL_COLOR, text_color

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["step_dimensions_figure"]


def _dimension(ax: Any, a: np.ndarray, b: np.ndarray, side: np.ndarray, gap: float, text: str, color: str,
               *, outside: bool = False) -> Any:
    """A dimension line from a to b (2-D), drawn ``gap`` away on ``side`` with extension lines and arrow heads.

    ``outside`` puts the heads outside the extension lines, pointing in (for a short length). The text sits
    beside the middle of the line, away from the measured points. Returns the text artist.
    """
    a2, b2 = a + gap * side, b + gap * side
    over = 0.18 * abs(gap) * side
    for p, q in ((a, a2), (b, b2)):  # extension lines, a little past the dimension line
        ax.plot(*np.stack([p + 0.15 * gap * side, q + over]).T, color=color, lw=0.9)
    if outside:
        u = (b2 - a2) / np.linalg.norm(b2 - a2)
        tail = 0.9 * abs(gap)
        ax.plot(*np.stack([a2 - tail * u, b2 + tail * u]).T, color=color, lw=1.2)
        for tip, d in ((a2, u), (b2, -u)):
            ax.annotate("", tip, tip - 0.8 * tail * d, arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.2,
                                                                  "shrinkA": 0, "shrinkB": 0})  # fmt: skip
    else:
        ax.annotate("", a2, b2, arrowprops={"arrowstyle": "<|-|>", "color": color, "lw": 1.2, "shrinkA": 0,
                                            "shrinkB": 0})  # fmt: skip
    box = {"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.9}
    if outside:  # the text after the outer arrow of b, clear of the extension lines
        u = (b2 - a2) / np.linalg.norm(b2 - a2)
        at = b2 + 0.95 * abs(gap) * u
        return ax.text(*at, text, color=text_color(color), ha="left" if u[0] >= 0 else "right", va="center",
                       fontsize=12, bbox=box)  # fmt: skip
    mid = (a2 + b2) / 2
    horizontal = abs(float((b2 - a2)[0])) >= abs(float((b2 - a2)[1]))
    ha = "center" if horizontal else ("right" if side[0] < 0 else "left")
    va = ("bottom" if side[1] > 0 else "top") if horizontal else "center"
    pad = 0.35 * abs(gap) * side
    return ax.text(*(mid + pad), text, color=text_color(color), ha=ha, va=va, fontsize=12, bbox=box)


def _symbol(ax: Any, p: np.ndarray, into: bool, r: float, color: str) -> None:
    """A vector normal to the page: a circle with a dot (towards the reader) or a cross (into the page)."""
    from matplotlib.patches import Circle

    ax.add_patch(Circle(tuple(p), r, fill=False, ec=color, lw=1.6, zorder=6))
    if into:
        for s in (1, -1):
            ax.plot(*np.stack([p + 0.7 * r * np.array([-1, -s]), p + 0.7 * r * np.array([1, s])]).T, color=color,
                    lw=1.6, zorder=6)  # fmt: skip
    else:
        ax.plot(*p, "o", color=color, ms=3, zorder=6)


def step_dimensions_figure(walk: FrameWalk, k: int, *, units: str = "m", digits: int = 5) -> Figure:
    """The figure of :func:`~.dh_figures.plot_step_dimensions` (see there)."""
    import matplotlib.pyplot as plt

    if not isinstance(k, (int, np.integer)) or isinstance(k, bool) or not 2 <= k <= len(walk.steps) - 1:
        raise ValueError(f"k: expected a frame 2 .. {len(walk.steps) - 1} (one with a frame before and an axis "
                         f"after it), got {k!r}")  # fmt: skip
    st, prev, nxt = walk.steps[k - 1], walk.steps[k - 2], walk.steps[k]
    O, X, Z = st.origin, st.x, st.z
    Y = np.cross(Z, X)
    u_ = f" {units}" if units else ""
    sub, nk = str(k), str(k + 1)

    def plan(p: np.ndarray) -> np.ndarray:  # the plane of X_k (across) and Z_k (up); -Y_k towards the reader
        return np.array([float(np.dot(p - O, X)), float(np.dot(p - O, Z))])

    fig, (left, right) = plt.subplots(1, 2, figsize=(9.0, 5.4), width_ratios=[1.2, 1])
    size = max(abs(st.d), abs(st.a), 1e-9)
    m = 0.28 * size  # margins and arrow lengths scale with the step
    foot, end = plan(st.foot_prev), plan(O + st.a * X)
    # axis k (dashed: a joint axis), the line X_{k-1} through its foot, the normal a_k (purple)
    v_lo, v_hi = min(foot[1], 0.0) - m, max(foot[1], 0.0) + m
    left.plot([0, 0], [v_lo, v_hi], **AXIS_LINE)
    left.text(0, v_lo, f" axis {sub}", ha="left", va="bottom", color="0.3", fontsize=11)
    xp = plan(st.foot_prev + prev.x) - foot
    if np.linalg.norm(xp) > 0.5:  # X_{k-1} lies in the page: draw its line through the foot
        left.plot(*np.stack([foot - 0.6 * m * xp, foot + 0.9 * m * xp]).T, color="0.6", lw=1.2)
        tip = foot + 0.9 * m * xp
        left.text(*tip, f"X{k - 1}", color="0.45", ha="left" if xp[0] >= 0 else "right", va="center",
                  fontsize=11)  # fmt: skip
    left.plot(*foot, "o", color="0.45", ms=5, zorder=5)
    left.plot(*np.stack([np.zeros(2), end]).T, color=NORMAL_COLOR, lw=4, solid_capstyle="butt", zorder=4)
    # the triad of {k}: X_k and Z_k in the page, Y_k normal to it
    L = 0.55 * m + 1.2 * abs(st.a)
    for d, name, col in ((np.array([1.0, 0.0]), f"X{sub}", AXIS_COLORS[0]), (np.array([0.0, 1.0]), f"Z{sub}",
                                                                                AXIS_COLORS[2])):  # fmt: skip
        left.annotate("", tuple(L * d), (0, 0), arrowprops={"arrowstyle": "-|>", "color": col, "lw": 1.8,
                                                            "shrinkA": 0, "shrinkB": 0}, zorder=5)  # fmt: skip
        left.text(*(L * d + 0.12 * m * d), name, color=text_color(col), ha="left" if d[0] else "center",
                  va="center" if d[0] else "bottom", fontsize=12)  # fmt: skip
    r = 0.09 * m
    _symbol(left, np.zeros(2), True, r, AXIS_COLORS[1])  # Y_k = Z_k x X_k points away from the reader
    left.text(-1.3 * r, -1.3 * r, f"Y{sub}", color=text_color(AXIS_COLORS[1]), ha="right", va="top", fontsize=12)
    left.text(-1.3 * r, 1.3 * r, f"{{{sub}}}", color="k", ha="right", va="bottom", fontsize=13, weight="bold")
    # axis k+1 through the end of the normal: a line in the page, or a circle where it stands normal to it
    zn = plan(O + nxt.z) - plan(O)
    if np.linalg.norm(zn) > 0.5:
        left.plot(*np.stack([end - 0.8 * m * zn, end + 0.8 * m * zn]).T, **AXIS_LINE)
        left.text(*(end + 0.8 * m * zn), f"axis {nk}", color="0.3", ha="left", va="bottom", fontsize=11)
    else:
        into = float(np.dot(nxt.z, Y)) > 0  # +Y_k points away from the reader (the reader sits on -Y_k)
        _symbol(left, end, into, r, "0.3")
        left.text(*(end + np.array([0.1 * m, -0.25 * m])), f"axis {nk}: Z{nk} {'into' if into else 'out of'} the page",
                  color="0.3", ha="left", va="top", fontsize=11)  # fmt: skip
    # the dimensions: d_k from the foot of X_{k-1} to the origin (brown), a_k along the normal (purple)
    texts = []
    if abs(st.d) > 1e-12:
        texts.append(_dimension(left, foot, np.zeros(2), np.array([-1.0, 0.0]), 0.45 * m,
                                f"d{sub} = {st.d:.{digits}g}{u_}", JOINT_COLOR))  # fmt: skip
    if abs(st.a) > 1e-12:
        texts.append(_dimension(left, np.zeros(2), end, np.array([0.0, -1.0]) if foot[1] > 0 else np.array([0, 1.0]),
                                0.5 * m, f"a{sub} = {st.a:.{digits}g}{u_}", NORMAL_COLOR,
                                outside=abs(st.a) < 0.35 * size))  # fmt: skip
    pts = np.array([foot, np.zeros(2), end, [0.0, v_lo], [0.0, v_hi], [L + 0.3 * m, 0.0], [0.0, L + 0.3 * m],
                    [-1.3 * m, 0.0], end + [2.2 * m, 0.0]])  # fmt: skip
    lo, hi = pts.min(axis=0) - 0.15 * m, pts.max(axis=0) + 0.15 * m
    left.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), aspect="equal")
    left.set_axis_off()
    left.set_title(f"the plane of X{sub} and Z{sub}, seen along Y{sub}: d{sub} and a{sub} to scale", fontsize=11)
    # right: seen along X_k (X_k towards the reader): Z_k across, X_k x Z_k up
    W = np.cross(X, Z)
    zk1 = np.array([float(np.dot(nxt.z, Z)), float(np.dot(nxt.z, W))])
    right.plot([-1.25, 1.25], [0, 0], **AXIS_LINE)
    right.plot(*np.stack([-1.25 * zk1, 1.25 * zk1]).T, **AXIS_LINE)
    for d, name, col in ((np.array([1.0, 0.0]), f"Z{sub}", AXIS_COLORS[2]), (zk1, f"Z{nk}", "0.2")):
        right.annotate("", tuple(d), (0, 0), arrowprops={"arrowstyle": "-|>", "color": col, "lw": 2.2,
                                                         "shrinkA": 0, "shrinkB": 0})  # fmt: skip
        off = np.array([-d[1], d[0]]) * (1.0 if d[0] < -0.3 or d[1] < -0.3 else -1.0)  # beside the tip, off the line
        right.text(*(0.92 * d + 0.14 * off), name, color=text_color(col), ha="left" if off[0] > 0.3 else "center",
                   va="top" if off[1] < -0.3 else ("bottom" if off[1] > 0.3 else "center"), fontsize=12)  # fmt: skip
    right.text(-1.2, 0.06, f"axis {sub}", color="0.3", ha="left", va="bottom", fontsize=11)
    right.text(*(-1.2 * zk1 + np.array([0.06, 0.0])), f"axis {nk}", color="0.3", ha="left",
               va="bottom" if zk1[1] < 0 else "top", fontsize=11)  # fmt: skip
    t = np.linspace(0.0, st.alpha, 60)
    arc = 0.55 * np.stack([np.cos(t), np.sin(t)], axis=1)
    right.plot(*arc[:-1].T, color=NORMAL_COLOR, lw=2.2)
    right.annotate("", tuple(arc[-1]), tuple(arc[-6]), arrowprops={"arrowstyle": "-|>", "color": NORMAL_COLOR,
                                                                    "lw": 2.2, "shrinkA": 0, "shrinkB": 0})  # fmt: skip
    mid = 0.72 * np.array([np.cos(st.alpha / 2), np.sin(st.alpha / 2)])
    right.text(*mid, f"α{sub} = {np.degrees(st.alpha):+.0f}°", color=text_color(NORMAL_COLOR), ha="left", va="center",
               fontsize=13, bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.9})  # fmt: skip
    _symbol(right, np.zeros(2), False, 0.08, AXIS_COLORS[0])
    right.text(-0.12, 0.12, f"X{sub}", color=text_color(AXIS_COLORS[0]), ha="right", va="bottom", fontsize=12)
    right.set(xlim=(-1.35, 1.6), ylim=(-1.4, 1.4), aspect="equal")
    right.set_axis_off()
    right.set_title(f"seen along X{sub} (towards you): the twist α{sub}\nfrom Z{sub} to Z{nk}, about X{sub}",
                    fontsize=11)  # fmt: skip
    return fig
