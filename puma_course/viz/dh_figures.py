"""Figures of Craig's frame assignment (lectures 02, 03): the common normal of two joint axes, the DH picture
with a, α, d, θ labelled, frames placed one step at a time, and a piston driving a revolute joint.

Everything drawn is computed by the kinematics layer (``common_normal``, ``frame_steps``, ``d_theta``). Labels go
through :func:`~puma_course.viz.labels.place_labels`. Static figures: 3-D labels are placed for the view they were
drawn in, so the functions here set the view (equal scale, :func:`~puma_course.viz.frames.frame_tightly`) first.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._validate import as_array, as_length
from ..kinematics.frame_assignment import CommonNormal, FrameWalk, common_normal, d_theta
from ..kinematics.spaces import actuator_from_joint
from ..transforms import homogeneous
from .dimensions import step_dimensions_figure
from .frames import AXIS_COLORS, frame_tightly, triad_letters
from .labels import Label, place_labels
from .style import AXIS_LINE, JOINT_COLOR, NORMAL_COLOR

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["draw_common_normal", "DHPicture", "draw_dh_picture", "draw_frame_walk", "draw_piston_joint",
           "plot_step_dimensions", "NORMAL_COLOR", "JOINT_COLOR"]  # fmt: skip


def _seg(ax: Any, a: Any, b: Any, **kw: Any) -> list[Any]:
    return list(ax.plot(*np.stack([a, b]).T, **kw))


def _arc(ax: Any, centre: np.ndarray, u: np.ndarray, k: np.ndarray, angle: float, r: float, color: str) -> list[Any]:
    """An arc of radius r about the unit axis k from the direction u (normal to k), turning by ``angle``; a head."""
    t = np.linspace(0.0, angle, 40)
    w = np.cross(k, u)
    P = centre + r * (np.outer(np.cos(t), u) + np.outer(np.sin(t), w))
    arts = list(ax.plot(*P.T, color=color, lw=2))
    if abs(angle) > 1e-9:  # a chevron at the end, pointing the way the angle turns
        e, tang = P[-1], np.sign(angle) * (-np.sin(angle) * u + np.cos(angle) * w)
        rad = (e - centre) / r
        for s in (1, -1):
            arts += _seg(ax, e, e - 0.22 * r * (tang * np.cos(0.5) + s * rad * np.sin(0.5)), color=color, lw=2)
    return arts


def _right_angle(ax: Any, foot: np.ndarray, x: np.ndarray, u: np.ndarray, s: float, color: str) -> None:
    ax.plot(*np.array([foot + s * x, foot + s * x + s * u, foot + s * u]).T, color=color, lw=1)


def draw_common_normal(ax: Any, p1: Any, u1: Any, p2: Any, u2: Any, *, sub: str = "i-1", names: Sequence[str] = (
        "i-1", "i"), half: float | None = None, spans: Sequence[Any] | None = None,
        place: bool = True) -> tuple[CommonNormal, list[Label]]:  # fmt: skip
    """Two joint axes (lines through p1 along u1, p2 along u2), their common normal, a and α: the DH picture's core.

    The normal (purple) runs from axis ``names[0]`` to axis ``names[1]``, at right angles to both
    (the small squares); its length is a (labelled ``a_{sub}``). The twist α (``α_{sub}``) is drawn
    at the normal's middle, between copies of the two axes' directions (dotted), about the normal.
    ``half`` scales the drawing (default: 0.8 a, at least 1); ``spans`` gives each axis line's
    extent (lo, hi) along its direction from its foot (default (-0.6 half, half)). With ``place``
    the labels are placed now (the view must be set); otherwise they are returned for the caller
    to place with others. Returns the
    :class:`~puma_course.kinematics.frame_assignment.CommonNormal` and the labels.
    """
    cn = common_normal(p1, u1, p2, u2)
    u1n, u2n = (np.asarray(u, float) / np.linalg.norm(u) for u in (u1, u2))
    L = max(0.8 * cn.a, 1.0) if half is None else as_length(half, "half", positive=True)
    spans = [(-0.6 * L, L)] * 2 if spans is None else spans
    tops = []
    for f, u, (lo, hi), x in ((cn.foot1, u1n, spans[0], cn.direction), (cn.foot2, u2n, spans[1], -cn.direction)):
        _seg(ax, f + lo * u, f + hi * u, **AXIS_LINE)
        _right_angle(ax, f, x, u, 0.07 * L, NORMAL_COLOR)
        tops.append(f + hi * u)
    _seg(ax, cn.foot1, cn.foot2, color=NORMAL_COLOR, lw=3.5)
    m, r = (cn.foot1 + cn.foot2) / 2, 0.55 * L
    for u in (u1n, u2n):  # both directions, copied to the middle of the normal
        _seg(ax, m, m + 0.8 * L * u, ls=":", lw=1.5, color="0.35")
    _arc(ax, m, u1n, cn.direction, cn.alpha, r, NORMAL_COLOR)
    mid = cn.alpha / 2
    w = np.cross(cn.direction, u1n)
    labels = [
        Label(tops[0], f"axis ${names[0]}$", "0.2", prefer=90),
        Label(tops[1], f"axis ${names[1]}$", "0.2", prefer=90),
        Label(cn.foot1 + 0.7 * (cn.foot2 - cn.foot1), f"$a_{{{sub}}}$", NORMAL_COLOR, prefer=-90),
        Label(m + r * (np.cos(mid) * u1n + np.sin(mid) * w), f"$\\alpha_{{{sub}}}$", NORMAL_COLOR, prefer=90),
    ]
    if place:
        place_labels(ax, labels)
    return cn, labels


@dataclass
class DHPicture:
    """What :func:`draw_dh_picture` computed and drew: the two normals, the parameters, the frames, the labels."""

    normals: tuple[CommonNormal, CommonNormal]
    params: dict[str, float]
    frames: tuple[np.ndarray, np.ndarray]
    labels: list[Any] = field(default_factory=list)


def draw_dh_picture(ax: Any, points: Any, directions: Any, *, i: str = "i", elev: float = 22, azim: float = -58,
                    half: float | None = None) -> DHPicture:  # fmt: skip
    """Craig's central picture: joint axes i-1, i, i+1 (lines), the normals a_{i-1}, a_i, and d_i, θ_i along axis i.

    ``points``, ``directions`` (3, 3): a point and a direction per axis. Frame {i-1} sits where the
    normal from axis i-1 to axis i leaves axis i-1, {i} where the normal to axis i+1 leaves axis i;
    d_i is the distance along axis i between the feet of the two normals and θ_i the turn about
    Z_i from X_{i-1} to X_i (drawn from a copy of X_{i-1}). Sets the view (``elev``, ``azim``),
    then places every label so that none collides. ``i`` names the middle axis ("i", or "2").
    Returns a :class:`DHPicture` whose ``params`` are a_prev, alpha_prev, d, theta, a, alpha.
    """
    P = as_array(points, "points", (3, 3), what="three points, one on each axis, shape (3, 3)")
    U = as_array(directions, "directions", (3, 3), what="three axis directions, shape (3, 3)")
    prev, nxt = (f"{i}-1", f"{i}+1") if not i.isdigit() else (str(int(i) - 1), str(int(i) + 1))
    c1, c2 = common_normal(P[0], U[0], P[1], U[1]), common_normal(P[1], U[1], P[2], U[2])
    z = U[1] / np.linalg.norm(U[1])
    d, theta = d_theta(z, c1.foot2, c1.direction, c2.foot1, c2.direction)
    L = max(0.8 * max(c1.a, c2.a), 1.0) if half is None else as_length(half, "half", positive=True)
    spans = [(-0.6 * L, L), (min(0.0, d) - 0.5 * L, max(0.0, d) + L)]
    _, lab1 = draw_common_normal(ax, P[0], U[0], P[1], U[1], sub=prev, names=(prev, i), half=L, spans=spans,
                                 place=False)  # fmt: skip
    u3 = U[2] / np.linalg.norm(U[2])
    _seg(ax, c2.foot2 - 0.6 * L * u3, c2.foot2 + L * u3, **AXIS_LINE)
    _seg(ax, c2.foot1, c2.foot2, color=NORMAL_COLOR, lw=3.5)
    _right_angle(ax, c2.foot2, -c2.direction, u3, 0.07 * L, NORMAL_COLOR)
    _seg(ax, c1.foot2, c2.foot1, color=JOINT_COLOR, lw=5, solid_capstyle="butt")  # d_i along axis i
    _seg(ax, c2.foot1, c2.foot1 + 0.7 * L * c1.direction, ls=":", lw=1.5, color="0.35")  # X_{i-1}, copied
    r = 0.45 * L
    _arc(ax, c2.foot1, c1.direction, z, theta, r, JOINT_COLOR)
    z0 = U[0] / np.linalg.norm(U[0])
    F0 = homogeneous(np.column_stack([c1.direction, np.cross(z0, c1.direction), z0]), c1.foot1)
    F1 = homogeneous(np.column_stack([c2.direction, np.cross(z, c2.direction), z]), c2.foot1)
    tl = 0.4 * L
    for F in (F0, F1):  # X and Z only, as in the textbooks' picture (Y completes the right-handed frame)
        _seg(ax, F[:3, 3], F[:3, 3] + tl * F[:3, 0], color=AXIS_COLORS[0], lw=3)
        _seg(ax, F[:3, 3], F[:3, 3] + tl * F[:3, 2], color=AXIS_COLORS[2], lw=3)
    mid = theta / 2
    lab = lab1 + [
        Label(c2.foot2 + L * u3, f"axis ${nxt}$", "0.2", prefer=90),
        Label(c2.foot1 + 0.7 * (c2.foot2 - c2.foot1), f"$a_{{{i}}}$", NORMAL_COLOR, prefer=-90),
        Label((c1.foot2 + c2.foot1) / 2, f"$d_{{{i}}}$", JOINT_COLOR, prefer=180),
        Label(c2.foot1 + r * (np.cos(mid) * c1.direction + np.sin(mid) * np.cross(z, c1.direction)),
              f"$\\theta_{{{i}}}$", JOINT_COLOR, prefer=0),
        Label(F0[:3, 3] + tl * F0[:3, 0], f"$X_{{{prev}}}$", AXIS_COLORS[0], prefer=-90),
        Label(F1[:3, 3] + tl * F1[:3, 0], f"$X_{{{i}}}$", AXIS_COLORS[0], prefer=-90),
        Label(F0[:3, 3] + tl * F0[:3, 2], f"$Z_{{{prev}}}$", AXIS_COLORS[2], prefer=180),
        Label(F1[:3, 3] + tl * F1[:3, 2], f"$Z_{{{i}}}$", AXIS_COLORS[2], prefer=180),
    ]  # fmt: skip
    ends = [c1.foot1 + t * U[0] / np.linalg.norm(U[0]) for t in spans[0]] + [c1.foot2 + t * z for t in spans[1]]
    ends += [c2.foot2 + t * u3 for t in (-0.6 * L, L)]
    frame_tightly(ax, np.vstack([c1.foot1, c1.foot2, c2.foot1, c2.foot2, *ends]), margin=0.02, zoom=1.15)
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    texts = place_labels(ax, lab, avoid=[F0[:3, 3], F1[:3, 3]], fontsize=12)
    params = dict(a_prev=c1.a, alpha_prev=c1.alpha, d=d, theta=theta, a=c2.a, alpha=c2.alpha)
    return DHPicture((c1, c2), params, (F0, F1), texts)


def _clip(a: np.ndarray, b: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The part of the segment a-b inside the box [lo, hi] (Liang-Barsky), or None: 3-D axes do not clip lines."""
    d, t0, t1 = b - a, 0.0, 1.0
    for k in range(3):
        if abs(d[k]) < 1e-15:
            if not lo[k] <= a[k] <= hi[k]:
                return None
            continue
        ta, tb = sorted(((lo[k] - a[k]) / d[k], (hi[k] - a[k]) / d[k]))
        t0, t1 = max(t0, ta), min(t1, tb)
        if t0 > t1:
            return None
    return a + t0 * d, a + t1 * d


def _sense(ax: Any, tip: np.ndarray, u: np.ndarray, size: float, eye: np.ndarray, **kw: Any) -> None:
    """A chevron at ``tip`` pointing along u, in the plane facing the viewer: the axis' positive sense."""
    w = np.cross(u, eye) / (np.linalg.norm(np.cross(u, eye)) or 1.0)
    for s in (1, -1):
        _seg(ax, tip, tip - size * (0.9 * u + s * 0.5 * w), **kw)


def draw_frame_walk(ax: Any, walk: FrameWalk, upto: int | None = None, *, points: Any = None, half: float = 0.1,
                    length: float = 0.08, units: str = "", elev: float = 22, azim: float = -58,
                    view_points: Any = None) -> list[Any]:  # fmt: skip
    """The frames :func:`~puma_course.kinematics.frame_steps.frame_steps` placed up to step ``upto``, that one in bold.

    Every joint axis is a dashed line through its frame's origin and the foot of the previous
    normal, ``half`` beyond them, with a chevron at its positive end and its number; ``points`` (an
    arm's polyline, e.g. ``robot.points(q)``) is drawn faint for orientation. Frames placed before
    are faint and bare (the context); frame {upto} is bold, its axes lettered x, y, z beside their tips,
    with its normal to the next axis (purple, a), the twist α to the next axis (an arc about X) and its
    offset d along its own axis (brown) where they are not zero. ``upto=None`` draws every frame bold (each
    lettered), ``upto=0`` the axes alone. The view frames ``view_points`` (default: all that is drawn); what
    falls outside it is clipped. Returns the placed labels (the letters first).
    """
    n = len(walk.steps)
    k = n if upto is None else int(upto)
    if not 0 <= k <= n:
        raise ValueError(f"upto: expected a step from 0 to {n}, got {upto!r}")
    segs = []
    for st in walk.steps:
        t = [0.0, -st.d] + ([] if st.normal is None else [float(np.dot(st.normal.foot1 - st.origin, st.z))])
        segs.append((st.origin + (min(t) - half) * st.z, st.origin + (max(t) + half) * st.z))
    Pp = None if points is None else as_array(points, "points", (None, 3), what="an arm's polyline, shape (p, 3)")
    shown = np.vstack([np.array(segs).reshape(-1, 3)] + ([] if Pp is None else [Pp]))
    frame_tightly(ax, shown if view_points is None else as_array(view_points, "view_points", (None, 3)))
    ax.view_init(elev=elev, azim=azim)
    e, a = np.radians(elev), np.radians(azim)  # eye: towards the viewer
    eye = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    box = np.array([ax.get_xlim3d(), ax.get_ylim3d(), ax.get_zlim3d()]).T
    span = float(box[1, 0] - box[0, 0])

    def inside(p: np.ndarray) -> bool:
        return bool(np.all(p >= box[0] - 1e-12) and np.all(p <= box[1] + 1e-12))

    drawn: list[np.ndarray] = []  # the joint axes and bold triads as drawn: the labels keep off them

    def line(a: np.ndarray, b: np.ndarray, keep: bool = False, **kw: Any) -> np.ndarray | None:
        part = _clip(np.asarray(a, float), np.asarray(b, float), box[0], box[1])
        if part is not None:
            _seg(ax, *part, **kw)
            if keep:
                drawn.append(np.stack(part))
        return None if part is None else part[1]

    if Pp is not None:
        for a, b in zip(Pp[:-1], Pp[1:], strict=True):
            line(a, b, color="tab:orange", lw=3, alpha=0.3, solid_capstyle="round")
    labels = []
    for st, (lo, hi) in zip(walk.steps, segs, strict=True):
        strong = not upto or st.i in (k, k + 1)
        style = dict(lw=1.8 if strong else 1.0, color="0.15" if strong else "0.55")
        end = line(lo, hi, keep=True, ls="--", **style)
        if end is not None and inside(hi):
            _sense(ax, hi, st.z, 0.035 * span, eye, **style)
        if end is not None:
            labels.append(Label(end, f"{st.i}", "0.15" if strong else "0.45", prefer=90, size=10))
    letters: list[Label] = []  # x, y, z at the bold triads' tips (the faint ones are the steps before: bare)
    for st in walk.steps[:k]:
        bold = upto is None or st.i == k
        L = length if bold else 0.7 * length
        ends = [line(st.origin, st.origin + L * st.frame[:3, c], keep=bold, color=AXIS_COLORS[c],
                     alpha=1.0 if bold else 0.3, lw=2.5 if bold else 1.5) for c in range(3)]  # fmt: skip
        for lb, end in zip(triad_letters(ax, st.frame, L) if bold else [], ends, strict=False):
            if end is not None:  # at the axis' tip, or where the view cuts it
                lb.point = end
                letters.append(lb)
        both = st.i == 1 and np.allclose(walk.base, st.frame)  # {0} = {1} at q = 0
        if bold:
            labels.append(Label(st.origin, "$\\{0\\}, \\{1\\}$" if both else f"$\\{{{st.i}\\}}$", "black", prefer=200))
    if upto:
        st, cn = walk.steps[k - 1], walk.steps[k - 1].normal
        if cn is not None and st.a > 0:
            line(cn.foot1, cn.foot2, color=NORMAL_COLOR, lw=4)
            labels.append(Label((cn.foot1 + cn.foot2) / 2, f"$a_{{{st.i}}}$", NORMAL_COLOR, prefer=-90))
        if cn is not None and abs(st.alpha) > 1e-12:
            r = 0.7 * length
            line(cn.foot2, cn.foot2 + 1.2 * r * st.z, ls=":", lw=1.5, color="0.3")  # Z_i, copied
            _arc(ax, cn.foot2, st.z, st.x, st.alpha, r, NORMAL_COLOR)
            m = st.alpha / 2
            labels.append(Label(cn.foot2 + r * (np.cos(m) * st.z + np.sin(m) * np.cross(st.x, st.z)),
                                f"$\\alpha_{{{st.i}}}$", NORMAL_COLOR, prefer=30))  # fmt: skip
        if abs(st.d) > 0:
            line(st.foot_prev, st.origin, color=JOINT_COLOR, lw=4, solid_capstyle="butt")
            labels.append(Label((st.foot_prev + st.origin) / 2, f"$d_{{{st.i}}}$", JOINT_COLOR, prefer=150))
    ax.locator_params(nbins=4)
    u = f" [{units}]" if units else ""
    for axis, name in zip((ax.xaxis, ax.yaxis, ax.zaxis), "xyz", strict=True):  # room for the tick numbers
        axis.set_label_text(f"{name}{u}")
        axis.labelpad = 10
    shown_labels = [lb for lb in letters + labels if inside(np.asarray(lb.point, float))]
    return place_labels(ax, shown_labels, lines=drawn, fontsize=11)


def draw_piston_joint(ax: Any, theta: float, b: float, c: float, gamma0: float = 0.0, *,
                      link: float | None = None) -> float:  # fmt: skip
    """A 2-D sketch of actuator space: a piston between a pin at distance b on the fixed link (along x) and a pin at
    distance c on the moving link, which stands at γ = θ + γ0 from the fixed one; sets an equal-aspect view, returns s.

    The piston length s comes from :func:`~puma_course.kinematics.spaces.actuator_from_joint`.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> draw_piston_joint(ax, np.pi / 2, 3.0, 4.0)  # a right angle: s = 5
    5.0
    >>> plt.close(fig)
    """
    s = float(actuator_from_joint(theta, b, c, gamma0))
    g = float(theta) + float(gamma0)
    L = 1.3 * max(b, c) if link is None else as_length(link, "link", positive=True)
    e = np.array([np.cos(g), np.sin(g)])
    pa, pb = np.array([b, 0.0]), c * e
    ax.plot([-0.15 * L, L], [0, 0], color="0.45", lw=8, solid_capstyle="round")  # the fixed link
    ax.plot([0, L * e[0]], [0, L * e[1]], color="tab:orange", lw=8, solid_capstyle="round")  # the moving link
    barrel = pa + 0.5 * abs(b - c) * (pb - pa) / s + 0.3 * min(b, c) * (pb - pa) / s
    ax.plot(*np.stack([pa, barrel]).T, color="tab:blue", lw=11, solid_capstyle="butt")  # the cylinder ...
    ax.plot(*np.stack([pa, pb]).T, color="tab:blue", lw=3.5)  # ... and its rod
    ax.plot(*np.stack([[0, 0], pa, pb]).T, "o", color="black", ms=7, zorder=5)
    t, rg = np.linspace(0, g, 30), 0.6 * b * c * abs(np.sin(g)) / s  # inside the triangle: 0.6 of the lever arm
    ax.plot(rg * np.cos(t), rg * np.sin(t), color=JOINT_COLOR, lw=1.8)
    ends = np.array([[-0.15 * L, 0], [L, 0], L * e, [0, 0]])
    lo, hi = ends.min(axis=0) - 0.12 * L, ends.max(axis=0) + 0.12 * L
    ax.set(xlim=(lo[0], hi[0]), ylim=(lo[1], hi[1]), aspect="equal")
    ax.set_axis_off()
    v = pb - pa
    nrm = np.array([-v[1], v[0]]) * (1.0 if float(np.dot([-v[1], v[0]], pa + pb)) > 0 else -1.0)
    out = np.degrees(np.arctan2(nrm[1], nrm[0]))  # beside the piston, away from the joint
    place_labels(ax, [Label(pa / 2, "$b$", "0.2", prefer=-90),
                      Label(0.55 * pb, "$c$", "tab:orange", prefer=float(np.degrees(g)) + 90),
                      Label((pa + pb) / 2, "$s$", "tab:blue", prefer=float(out)),
                      Label(rg * np.array([np.cos(g / 2), np.sin(g / 2)]), "$\\gamma$", JOINT_COLOR,
                            prefer=float(np.degrees(g / 2)))],
                 avoid=np.vstack([np.linspace(p0, p1, 40) for p0, p1 in ((pa, pb), ([0, 0], L * e), ([0, 0], [L, 0]))]),
                 fontsize=12)  # fmt: skip
    return s


# ------------------------------------------------------------------------------------------------ a step, dimensioned
def plot_step_dimensions(walk: FrameWalk, k: int, *, units: str = "m", digits: int = 5) -> Figure:
    """Frame {k} of a frame walk as a dimensioned drawing: the offset d_k, the length a_k and the twist α_k.

    Left, the plane of X_k and Z_k (seen along Y_k): axis k (dashed, a joint axis), the foot of X_{k-1}
    on it, the offset d_k from that foot to the origin of {k} along Z_k, the common normal a_k along X_k to
    axis k+1 (drawn as the line it is, or as a circle with a dot or a cross where it stands normal to the
    page), each with a dimension line and its value. Right, the view along X_k (X_k towards the reader):
    axes k and k+1 seen crossing, and the twist α_k from Z_k to Z_{k+1} as an arc. Drawn to scale, with
    the numbers the walk computed; for a step whose a_k is short beside d_k the a_k arrows point in from
    outside. The walk's frames are in the coordinates its axes were given in.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from puma_course.kinematics.frame_assignment import frame_steps
    >>> walk = frame_steps([[0, 0, 0], [1, 0, 0], [1.5, 0.3, 0]], [[0, 0, 1], [0, 1, 0], [0, 0, -1]])
    >>> fig = plot_step_dimensions(walk, 2)
    >>> sorted(t.get_text() for t in fig.axes[0].texts if t.get_text().startswith(("d2", "a2")))
    ['a2 = 0.5 m', 'd2 = 0.3 m']
    >>> import matplotlib.pyplot as plt
    >>> plt.close(fig)
    """
    return step_dimensions_figure(walk, k, units=units, digits=digits)
