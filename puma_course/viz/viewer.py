"""The WebGL viewer: an anywidget drawing a chain of frames with three.js, turned with the mouse.

:class:`Viewer` draws any chain given its frames (m, 4, 4) and the polyline of its links:
links as tubes, one triad per frame (x red, y green, z blue) labelled ``{i}`` (the labels are
placed on the screen so they never overlap), the joint axes (each frame's z) dashed, a ground
grid, optional target triads, ghost arms and a played animation. :class:`RobotViewer` feeds it
from the robot API (``robot.frames(q)``, ``robot.points(q)``). Drag to turn, wheel to zoom,
right-drag to pan, "reset view" to come back.

The scene (styles, labels, view) is sent to the browser once; each pose change sends only the
frames and the link points (a few hundred numbers), so a slider move is redrawn in a few
milliseconds, with no picture made on the kernel. The front end is ``static/viewer.js``,
built from ``js/src`` with three.js bundled (nothing is fetched at run time).

Displayed in a notebook, a viewer (and a :class:`~puma_course.viz.widgets.Panel`) also leaves
a static PNG of its first pose (matplotlib) in the output, as an ``<img alt>`` in ``text/html``
(:func:`with_picture`), which a reader sees before the kernel runs and a static page shows.

>>> from puma_course import Puma560
>>> v = RobotViewer(Puma560(), "qz")
>>> [f["label"] for f in v.scene["frames"]]
['{0}', '{1}', '{2}', '{3}', '{4}', '{5}', '{6}']
>>> v.set_q(Puma560().q("qr"))   # sends 7 frames and 6 link points, nothing else
>>> len(v.pose["frames"]), len(v.pose["points"])
(112, 18)
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import anywidget
import matplotlib.pyplot as plt
import numpy as np
import traitlets

from .._validate import as_array
from ..kinematics.ik import IKSolutions
from ..kinematics.robot import Robot
from .alt_text import current_alt, img_html
from .frames import AXIS_COLORS, draw_frame, draw_points, new_axes, note_below, set_equal

__all__ = ["Viewer", "RobotViewer", "view_box"]

_STATIC = Path(__file__).parent / "static"

#: Colour of the links (matplotlib's tab:orange, as in the static figures).
LINK_COLOR = "#ff7f0e"


def _flat(a: np.ndarray, digits: int = 7) -> list[float]:
    """Numbers for the browser: rounded (a pose needs no more) and with -0.0 made 0.0."""
    return [float(x) for x in np.round(np.asarray(a, dtype=float).ravel(), digits) + 0.0]


def view_box(points: Any, margin: float = 0.08) -> tuple[np.ndarray, float]:
    """Centre and radius of the sphere a view must show to hold ``points`` (..., 3), with a margin.

    >>> c, r = view_box([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], margin=0.0)
    >>> c.tolist(), r
    ([1.0, 0.0, 0.0], 1.0)
    """
    P = as_array(points, "points", what="points of shape (..., 3)").reshape(-1, 3)
    lo, hi = P.min(axis=0), P.max(axis=0)
    centre = (lo + hi) / 2.0
    radius = float(np.max(np.linalg.norm(P - centre, axis=1)))
    return centre, max(radius, 1e-9) * (1.0 + margin)


class Viewer(anywidget.AnyWidget):
    """A WebGL view of a chain of frames: links, triads labelled {i}, joint axes, grid; mouse orbit.

    ``frames`` (m, 4, 4) map each frame into the base frame; ``points`` (p, 3) is the links'
    polyline (default: the frame origins). The number of frames and points is fixed for a viewer
    (a pose update moves them). ``labels`` (one text per frame, "" for none; default ``{i}``),
    ``lengths`` (triad lengths, one or per frame), ``faint`` (frames drawn faint), ``axes``
    (draw each frame's z axis dashed: its joint axis) style the frames. ``view_points`` are
    points the view must always hold (default: the first pose and the origin); the camera looks
    at their centre from ``azim``/``elev`` (degrees, matplotlib's convention; z up). The ground
    grid lies at the height of the first link point (where the arm stands; ``floor`` sets it)
    and spans ``reach_points`` (default: the view points), its spacing written in ``units``.

    >>> import numpy as np
    >>> v = Viewer(np.stack([np.eye(4), np.eye(4)]), labels=["{a}", ""], units="m")
    >>> v.scene["frames"][0]["label"], v.scene["frames"][1]["label"], v.scene["units"]
    ('{a}', '', 'm')
    """

    _esm = _STATIC / "viewer.js"

    scene = traitlets.Dict().tag(sync=True)
    pose = traitlets.Dict().tag(sync=True)
    ghosts = traitlets.Dict().tag(sync=True)
    targets: traitlets.List[Any] = traitlets.List().tag(sync=True)
    animation = traitlets.Dict().tag(sync=True)
    height = traitlets.Int(420).tag(sync=True)

    def __init__(
        self,
        frames: Any,
        points: Any = None,
        *,
        labels: Sequence[str] | None = None,
        lengths: float | Sequence[float] | None = None,
        faint: Sequence[bool] | None = None,
        axes: bool | Sequence[bool] = True,
        view_points: Any = None,
        reach_points: Any = None,
        floor: float | None = None,
        title: str = "",
        units: str = "",
        note: str = "",
        azim: float = -60.0,
        elev: float = 25.0,
        height: int = 420,
        link_radius: float | None = None,
        link_color: str = LINK_COLOR,
    ) -> None:
        F = as_array(frames, "frames", (None, 4, 4))
        m = F.shape[0]
        P = F[:, :3, 3] if points is None else as_array(points, "points", (None, 3))
        V = np.vstack([F[:, :3, 3], P, np.zeros((1, 3))]) if view_points is None else as_array(
            view_points, "view_points", what="points of shape (..., 3)").reshape(-1, 3)  # fmt: skip
        centre, radius = view_box(V)
        R = V if reach_points is None else as_array(reach_points, "reach_points", what="points of shape (..., 3)")
        rc, rr = view_box(R.reshape(-1, 3))
        labels = [f"{{{i}}}" for i in range(m)] if labels is None else [str(s) for s in labels]
        if len(labels) != m:
            raise ValueError(f"labels: expected {m} texts (one per frame), got {len(labels)}")
        if lengths is None:
            L = np.full(m, 0.16 * radius)
        else:
            L = as_array(np.broadcast_to(np.asarray(lengths, dtype=float), (m,)), "lengths", (m,))
        fnt = [False] * m if faint is None else [bool(x) for x in faint]
        ax = [bool(axes)] * m if isinstance(axes, (bool, np.bool_)) else [bool(x) for x in axes]
        if len(fnt) != m or len(ax) != m:
            raise ValueError(f"faint, axes: expected {m} values (one per frame)")
        styles = [
            {"label": labels[i], "length": float(L[i]), "faint": fnt[i], "axis": ax[i],
             "priority": 2 if i in (0, m - 1) else (0 if fnt[i] else 1)}
            for i in range(m)
        ]  # fmt: skip
        low = float(P[0, 2] if floor is None else floor)
        super().__init__(
            scene={
                "frames": styles,
                "points": int(P.shape[0]),
                "link": {"radius": float(link_radius or 0.018 * radius), "color": link_color},
                "center": _flat(centre),
                "radius": float(radius),
                "grid": {"z": low, "size": 2.0 * rr, "center": _flat(rc)},
                "view": {"azim": float(azim), "elev": float(elev)},
                "units": units,
                "title": title,
                "note": note,
            },
            height=int(height),
        )
        self._last: tuple[np.ndarray, np.ndarray] = (F, P)
        self._seq = 0
        self.show(F, P)

    # ---- what moves -------------------------------------------------------------------
    def show(self, frames: Any, points: Any = None) -> None:
        """Send a new pose: the frames (m, 4, 4) and the link points (p, 3), the same counts as at the start."""
        sc = self.scene
        m, p = len(sc["frames"]), sc["points"]
        F = as_array(frames, "frames", (m, 4, 4), what=f"{m} frames of shape (4, 4)")
        P = F[:, :3, 3] if points is None else as_array(points, "points", (p, 3), what=f"{p} points of shape (3,)")
        self._last = (F, P)
        self._seq += 1
        self.pose = {"frames": _flat(F), "points": _flat(P), "seq": self._seq}

    def set_ghosts(self, arms: Sequence[tuple[Any, Any]], selected: int | None = None) -> None:
        """Draw ghost arms, each ``(frames, points)`` (translucent); ``selected`` (an index) is drawn stronger."""
        out = []
        for k, (F, P) in enumerate(arms):
            Fk = as_array(F, f"arms[{k}] frames", (None, 4, 4))
            Pk = Fk[:, :3, 3] if P is None else as_array(P, f"arms[{k}] points", (None, 3))
            out.append({"frames": _flat(Fk), "points": _flat(Pk)})
        if selected is not None and not 0 <= selected < len(out):
            raise ValueError(f"selected: expected an index in 0..{len(out) - 1} or None, got {selected}")
        self.ghosts = {"arms": out, "selected": -1 if selected is None else int(selected)}

    def set_targets(self, poses: Any, labels: Sequence[str] | None = None) -> None:
        """Draw target frames (k, 4, 4) (or one (4, 4)) as larger translucent triads, labelled (default "target")."""
        T = as_array(poses, "poses", (4, 4), batch=True).reshape(-1, 4, 4)
        names = ["target" if len(T) == 1 else f"target {k + 1}" for k in range(len(T))] if labels is None else labels
        if len(names) != len(T):
            raise ValueError(f"labels: expected {len(T)} texts (one per target), got {len(names)}")
        self.targets = [{"frame": _flat(t), "label": str(s)} for t, s in zip(T, names, strict=True)]

    def play(self, frames_seq: Any, points_seq: Any = None, *, fps: float = 12.0, loop: bool = False) -> None:
        """Precomputed poses (T, m, 4, 4) (and link points (T, p, 3)) played in the browser with a play button.

        The browser steps through them at ``fps`` with no round trip to the kernel; a step
        slider scrubs; the starting view frames every pose. A new pose from the kernel (a
        slider) stops the animation.
        """
        sc = self.scene
        m, p = len(sc["frames"]), sc["points"]
        S = as_array(frames_seq, "frames_seq", (None, m, 4, 4))
        Q = S[:, :, :3, 3] if points_seq is None else as_array(points_seq, "points_seq", (len(S), p, 3))
        if not fps > 0:
            raise ValueError(f"fps: expected a positive number of frames per second, got {fps!r}")
        centre, radius = view_box(np.vstack([Q.reshape(-1, 3), S[:, :, :3, 3].reshape(-1, 3), np.zeros((1, 3))]))
        self.animation = {"poses": [{"frames": _flat(F), "points": _flat(P)} for F, P in zip(S, Q, strict=True)],
                          "fps": float(fps), "loop": bool(loop),
                          "view": {"center": _flat(centre), "radius": max(radius, self.scene["radius"])}}  # fmt: skip

    # ---- the static picture -------------------------------------------------------------
    def _draw_static(self, ax: Any) -> None:
        sc = self.scene
        F, P = self._last
        for arm in self.ghosts.get("arms", []):
            draw_points(ax, np.reshape(arm["points"], (-1, 3)), color="0.55", lw=2.5, alpha=0.35)
        draw_points(ax, P, color=sc["link"]["color"], lw=4)
        for style, T in zip(sc["frames"], F, strict=True):
            alpha = 0.3 if style["faint"] else 1.0
            if style["axis"]:
                o, z = T[:3, 3], T[:3, 2]
                L = 1.1 * style["length"]
                ax.plot(*np.stack([o - L * z, o + L * z]).T, ls="--", lw=1, color=AXIS_COLORS[2], alpha=0.5 * alpha)
            # a named frame (the ends) is lettered x, y, z; the frames between stay bare, in the named ones' colours
            draw_frame(ax, T, style["label"] if style["priority"] == 2 else None, length=style["length"], alpha=alpha)
        for t in self.targets:
            draw_frame(ax, np.reshape(t["frame"], (4, 4)), t["label"], length=1.3 * sc["frames"][-1]["length"],
                       alpha=0.5)  # fmt: skip

    def _tips(self) -> list[np.ndarray]:
        """The tips of the triads' three axes as drawn (each (m, 3)), so the picture frames them too."""
        F, _ = self._last
        L = np.array([f["length"] for f in self.scene["frames"]])[:, None]
        return [L * F[:, :3, k] for k in range(3)]

    def static_png(self, dpi: int = 110, note: str | None = None) -> bytes:
        """A PNG of the pose shown (matplotlib, the same view as the live one): the picture left in the notebook.

        ``note`` is written small under the picture; the picture a saved notebook keeps for the live widget
        carries :data:`STILL_NOTE`, so a reader knows the view turns once the cell runs.

        >>> import numpy as np
        >>> Viewer(np.eye(4)[None]).static_png()[:8]
        b'\\x89PNG\\r\\n\\x1a\\n'
        """
        sc = self.scene
        w = 5.6
        fig, ax = new_axes(figsize=(w, w * min(max(self.height, 200), 800) / 560.0), title=sc["title"] or None,
                           elev=sc["view"]["elev"], azim=sc["view"]["azim"], dpi=dpi)  # fmt: skip
        try:
            self._draw_static(ax)
            F, P = self._last
            shown = [P, F[:, :3, 3], np.zeros((1, 3))]
            shown += [np.reshape(a["points"], (-1, 3)) for a in self.ghosts.get("arms", [])]
            shown += [np.reshape(t["frame"], (4, 4))[None, :3, 3] for t in self.targets]
            set_equal(ax, np.vstack(shown + [F[:, :3, 3] + 1.1 * L for L in self._tips()]), margin=0.1)
            ax.locator_params(nbins=4)  # few tick numbers: more overlap on a small 3-D axes
            if sc["units"]:
                ax.set(xlabel=f"x [{sc['units']}]", ylabel=f"y [{sc['units']}]", zlabel=f"z [{sc['units']}]")
            if note:
                note_below(fig, ax, note)
            buf = io.BytesIO()
            fig.savefig(buf, format="png", dpi=dpi)
        finally:
            plt.close(fig)
        return buf.getvalue()

    def still_alt(self) -> str:
        """A text alternative of the still picture: the title, what is drawn, where the last frame's origin is.

        >>> Viewer(np.eye(4)[None], title="one frame").still_alt()
        "A still picture of the 3-D view of one frame: 1 frame drawn as an x, y, z triad (x red, y green, z blue) \
and a ground grid; the last frame's origin at (0, 0, 0). Run the cell in JupyterLab for the live view."
        """
        sc = self.scene
        F, _ = self._last
        m = len(F)
        what = "1 frame drawn as an x, y, z triad" if m == 1 else f"{m} frames drawn as x, y, z triads"
        links = ", their links" if m > 1 else ""
        ghosts = len(self.ghosts.get("arms", []))
        extra = f", {ghosts} other solutions as grey ghost arms" if ghosts else ""
        units = f" {sc['units']}" if sc.get("units") else ""
        origin = ", ".join(f"{v:.4g}" for v in np.round(F[-1][:3, 3], 4) + 0.0)
        return (f"A still picture of the 3-D view of {sc['title'] or 'a chain of frames'}: {what} (x red, y green, "
                f"z blue){links}{extra} and a ground grid; the last frame's origin at ({origin}){units}. "
                "Run the cell in JupyterLab for the live view.")  # fmt: skip

    def __repr__(self) -> str:
        """What a text-only front end shows: the title and the number of frames, never a memory address."""
        title = self.scene.get("title") or "frames"
        return f"{type(self).__name__}({title!r}, {len(self._last[0])} frames)"

    def _repr_mimebundle_(self, **kwargs: Any) -> tuple[dict[Any, Any], dict[Any, Any]] | None:
        data = super()._repr_mimebundle_(**kwargs)
        return with_picture(data, self)


#: Written under the still picture a saved notebook (or the website) shows in place of a live viewer.
STILL_NOTE = "A still picture: run the cell in JupyterLab to turn the view and move the arm."


def with_picture(data: Any, viewer: Viewer) -> Any:
    """Add the viewer's still picture to a widget's display bundle, for front ends without the live model.

    The picture is an ``<img alt>`` in ``text/html`` (JupyterLab shows an untrusted notebook's HTML with its
    alt; its image renderer gives an ``image/png`` none), one copy of the PNG, reduced to a 256-colour palette
    (:func:`small_png`). The alt is the one :func:`~.alt_text.figure_alt` gave the cell, else
    :meth:`Viewer.still_alt`.
    """
    if isinstance(data, tuple):  # (data, metadata)
        return (with_picture(data[0], viewer), data[1])
    if isinstance(data, dict):
        data = {k: v for k, v in data.items() if k != "image/png"}
        png = small_png(viewer.static_png(note=STILL_NOTE))
        data["text/html"] = img_html(png, current_alt() or viewer.still_alt())
    return data


def small_png(png: bytes) -> bytes:
    """The same picture in a 256-colour palette (median cut, no dither: white stays white), dpi kept; 2-3 x smaller.

    >>> from puma_course import MK3
    >>> png = RobotViewer(MK3(), "qr").static_png()
    >>> small = small_png(png)
    >>> small[:8] == png[:8], len(small) < len(png) / 2
    (True, True)
    """
    from PIL import Image  # noqa: PLC0415 - Pillow comes with matplotlib; only a saved picture needs it

    with Image.open(io.BytesIO(png)) as im:
        dpi = im.info.get("dpi")
        small = im.convert("RGB").quantize(256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    buf = io.BytesIO()
    small.save(buf, format="png", optimize=True, **({"dpi": dpi} if dpi else {}))
    return buf.getvalue()


def _labels(labels: str | Sequence[str], m: int) -> list[str]:
    if isinstance(labels, str):
        if labels == "all":
            return [f"{{{i}}}" for i in range(m)]
        if labels == "ends":
            return [f"{{{i}}}" if i in (0, m - 1) else "" for i in range(m)]
        if labels == "none":
            return [""] * m
        raise ValueError(f"labels: expected 'all', 'ends', 'none' or one text per frame, got {labels!r}")
    out = [str(s) for s in labels]
    if len(out) != m:
        raise ValueError(f"labels: expected {m} texts (one per frame), got {len(out)}")
    return out


def reach_points(robot: Robot, q: np.ndarray | None = None, samples: int = 256) -> np.ndarray:
    """Points a view of ``robot`` must hold: its links and frames over seeded random joint vectors, ``q``, the base."""
    rng = np.random.default_rng(0)
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    Q = lo + (hi - lo) * rng.random((samples, robot.n))
    if q is not None:
        Q = np.vstack([q[None], Q])
    P = robot.points(Q).reshape(-1, 3)
    O = robot.frames(Q)[..., :3, 3].reshape(-1, 3)
    return np.vstack([P, O, np.zeros((1, 3))])


class RobotViewer(Viewer):
    """A :class:`Viewer` of any robot through the robot API: ``robot.frames(q)`` and ``robot.points(q)``.

    ``q`` is the start (a configuration name or a joint vector; default 0 clipped to the
    limits). ``labels`` is ``"all"`` (``{0}`` ... ``{m-1}``, default), ``"ends"``, ``"none"``
    or one text per frame. The camera frames the first pose (turn, zoom and pan with the
    mouse); the grid spans the arm's whole reach. :meth:`set_q` moves the arm, :meth:`show_ik` draws the
    solutions of an inverse problem as ghost arms, :meth:`animate` plays a joint path.

    >>> from puma_course import MK3
    >>> v = RobotViewer(MK3(), "qr")
    >>> v.scene["title"], v.scene["units"], v.q.round(4).tolist()
    ('Motoman MK3', 'mm', [0.0, 1.5708, -1.5708, 0.0, 0.0])
    """

    def __init__(
        self,
        robot: Robot,
        q: Any = None,
        *,
        labels: str | Sequence[str] = "all",
        axes: bool = True,
        title: str | None = None,
        **kw: Any,
    ) -> None:
        if not isinstance(robot, Robot):
            raise ValueError(
                f"robot: expected a Robot (Puma560(), MK3(), Porter(...), ...), got {type(robot).__name__}"
            )
        self.robot = robot
        q0 = start_q(robot, q)
        F = robot.frames(q0)
        m = F.shape[0]
        P0 = robot.points(q0)
        R = reach_points(robot, q0)
        _, r = view_box(R)
        lengths: Any = np.full(m, 0.11 * r)
        lengths[[0, -1]] *= 1.3  # the base and the tool stand out
        kw.setdefault("note", "drag or arrow keys: turn · wheel or +/-: zoom · right-drag: pan")
        tips = F[:, None, :3, 3] + lengths[:, None, None] * np.swapaxes(F[:, :3, :3], 1, 2)  # (m, 3 axes, 3)
        kw.setdefault("view_points", np.vstack([P0, F[:, :3, 3], tips.reshape(-1, 3), np.zeros((1, 3))]))
        super().__init__(F, P0, labels=_labels(labels, m), lengths=lengths, axes=axes, reach_points=R,
                         title=robot.name if title is None else title, units=robot.units, **kw)  # fmt: skip
        self.q = q0

    def set_q(self, q: Any) -> None:
        """Move the arm to ``q`` (radians / lengths): sends its frames and link points."""
        Q = self.robot.check_q(q)
        if Q.ndim != 1:
            raise ValueError(f"q: expected one joint vector of shape ({self.robot.n},), got {Q.shape}")
        self.q = Q
        self.show(self.robot.frames(Q), self.robot.points(Q))

    def show_ik(self, solutions: IKSolutions | Any, selected: int | None = 0) -> None:
        """Draw every configuration of ``solutions`` (an ``IKSolutions`` or (k, n) joint vectors) as a ghost arm.

        ``selected`` picks the one drawn stronger (None: none). An empty set clears the ghosts.
        """
        Q = np.asarray(solutions.q if isinstance(solutions, IKSolutions) else solutions, dtype=float)
        Q = Q.reshape(-1, self.robot.n)
        if len(Q) == 0:
            self.set_ghosts([])
            return
        F, P = self.robot.frames(Q), self.robot.points(Q)
        self.set_ghosts(list(zip(F, P, strict=True)), selected=selected)

    def animate(self, q_path: Any, *, fps: float = 12.0, loop: bool = False) -> None:
        """Play the joint path ``q_path`` (T, n) in the viewer: a play button and a step slider, run in the browser."""
        Q = self.robot.check_q(q_path)
        if Q.ndim == 1:
            Q = Q[None]
        self.play(self.robot.frames(Q), self.robot.points(Q), fps=fps, loop=loop)


def start_q(robot: Robot, q: Any) -> np.ndarray:
    """The start of a view or panel: a configuration name, a joint vector, or None (0 clipped to the limits)."""
    if q is None:
        lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
        return np.where((lo <= 0) & (hi >= 0), 0.0, (lo + hi) / 2.0)
    if isinstance(q, str):
        return robot.q(q)
    Q = robot.check_q(q)
    if Q.ndim != 1:
        raise ValueError(f"q: expected one joint vector of shape ({robot.n},) or a configuration name, got {Q.shape}")
    return Q
