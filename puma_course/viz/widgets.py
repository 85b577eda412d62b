"""Slider panels for the lectures: ipywidgets 8 + ``interactive_output`` + matplotlib (inline).

Convention: sliders show degrees (their labels say ``θ1 [deg]``) for angles and the robot's
units for lengths (``d3 [m]``); every callback, drawing and ``readout`` receives joint values
in *radians* (lengths unchanged), as everywhere else in the course. Each redraw builds a fresh
matplotlib figure, displays it in the panel's ``Output`` and closes it, so the panel works with
the inline backend in JupyterLab 4 with nothing to install (no ipympl). Axis limits are fixed
when the panel is built, so the view does not jump while a slider moves.

This is a display module: it imports ipywidgets and matplotlib. ``import puma_course`` never
imports it.

Typical use (in a notebook; the last expression displays the panel)::

    from puma_course import Puma560
    from puma_course.viz import robot_panel
    robot_panel(Puma560(), readout="pose")
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Sequence
from typing import Any

import ipywidgets as widgets
import matplotlib.pyplot as plt
import numpy as np
from IPython import get_ipython
from IPython.display import display

from .._validate import as_array
from ..kinematics.dh import mdh
from ..kinematics.robot import Robot
from .arms import _view_points, draw_robot
from .frames import draw_frame, draw_frames, draw_points, new_axes

__all__ = ["SliderList", "joint_sliders", "Panel", "robot_panel", "dh_link_panel", "pose_readout"]


class SliderList(list[Any]):
    """A list of ``FloatSlider`` widgets that knows which ones show degrees.

    ``radians()`` returns the current joint vector in code units: degrees
    converted to radians, lengths unchanged.

    >>> s = joint_sliders(["θ1", "d2"], [-np.pi, 0.0], [np.pi, 2.0], degrees=[True, False])
    >>> s.set_radians([np.pi / 2, 1.5])
    >>> [x.value for x in s], s.radians().round(6).tolist()
    ([90.0, 1.5], [1.570796, 1.5])
    """

    def __init__(self, sliders: Sequence[widgets.FloatSlider], degrees: Sequence[bool]) -> None:
        super().__init__(sliders)
        self.degrees = tuple(bool(x) for x in degrees)

    def radians(self) -> np.ndarray:
        """The slider values as a joint vector in radians (lengths unchanged).

        >>> joint_sliders(["θ"], -np.pi, np.pi, values=np.pi).radians().round(6).tolist()
        [3.141593]
        """
        v = np.array([s.value for s in self], dtype=float)
        return np.where(self.degrees, np.radians(v), v)

    def set_radians(self, q: Any) -> None:
        """Move the sliders to the joint vector ``q`` (radians / lengths).

        >>> s = joint_sliders(["θ"], -np.pi, np.pi)
        >>> s.set_radians([-np.pi / 4]); s[0].value
        -45.0
        """
        q = as_array(q, "q", (len(self),), what=f"a joint vector of shape ({len(self)},)")
        for s, deg, v in zip(self, self.degrees, q, strict=True):
            s.value = float(np.degrees(v)) if deg else float(v)


def _per_joint(value: Any, n: int, name: str) -> list[Any]:
    if isinstance(value, (bool, np.bool_)) or np.ndim(value) == 0:
        return [value] * n
    out = list(value)
    if len(out) != n:
        raise ValueError(f"{name}: expected one value or {n} values (one per joint), got {len(out)}")
    return out


def joint_sliders(
    names: Sequence[str],
    lows: Any,
    highs: Any,
    values: Any | None = None,
    degrees: bool | Sequence[bool] = True,
    step: float | Sequence[float] | None = None,
    units: str | None = None,
) -> SliderList:
    """One ``FloatSlider`` per joint; ``lows``, ``highs``, ``values`` in code units (radians).

    Angles (``degrees`` True for that joint) are shown in degrees with the label
    ``"<name> [deg]"``; lengths (``degrees`` False, e.g. a prismatic joint) keep their value
    and read ``"<name> [<units>]"`` (``"q2 []"`` for ``units=""``, a unitless length) or just
    the name (``units=None``). ``values`` default to 0 where the limits allow, else the middle.
    ``step`` is in display units (default 1 degree, or 1/200 of the range for lengths). The
    returned :class:`SliderList` converts back with ``.radians()``.

    >>> s = joint_sliders(["θ1", "d2"], [-np.pi, 0.0], [np.pi, 2.0], [np.pi / 2, 0.5], degrees=[True, False])
    >>> [x.description for x in s], [x.value for x in s], s.radians().round(6).tolist()
    (['θ1 [deg]', 'd2'], [90.0, 0.5], [1.570796, 0.5])
    """
    names = [str(x) for x in names]
    n = len(names)
    if n == 0:
        raise ValueError("names: expected at least one joint name, got none")
    lo = as_array(_per_joint(lows, n, "lows"), "lows", (n,))
    hi = as_array(_per_joint(highs, n, "highs"), "highs", (n,))
    if np.any(hi <= lo):
        raise ValueError(f"highs: expected every high > its low, got lows={lo.tolist()}, highs={hi.tolist()}")
    mid = (lo + hi) / 2.0
    val = np.clip(mid if values is None else as_array(_per_joint(values, n, "values"), "values", (n,)), lo, hi)
    if values is None:
        val = np.where((lo <= 0) & (hi >= 0), 0.0, val)
    deg = [bool(x) for x in _per_joint(degrees, n, "degrees")]
    steps = _per_joint(step, n, "step")
    sliders: list[Any] = []
    for i in range(n):
        conv = np.degrees if deg[i] else float
        a, b, v = float(conv(lo[i])), float(conv(hi[i])), float(conv(val[i]))
        st = steps[i]
        if st is None:
            st = 1.0 if deg[i] else float(10.0 ** np.floor(np.log10((b - a) / 200.0)))
        label = f"{names[i]} [deg]" if deg[i] else (names[i] if units is None else f"{names[i]} [{units}]")
        sliders.append(
            widgets.FloatSlider(
                value=v,
                min=a,
                max=b,
                step=st,
                description=label,
                continuous_update=False,
                readout_format=".1f" if deg[i] else ".3g",
                style={"description_width": "initial"},
                layout=widgets.Layout(width="320px"),
            )
        )
    return SliderList(sliders, deg)


def pose_readout(q: np.ndarray, frames: np.ndarray, precision: int = 4, units: str = "") -> str:
    """Text of the last frame's pose: position p (in ``units``) and rotation matrix R, for a panel's readout.

    >>> print(pose_readout(np.zeros(1), np.eye(4)[None], units="m"))
    p = [0. 0. 0.] m
    R =
    [[1. 0. 0.]
     [0. 1. 0.]
     [0. 0. 1.]]
    """
    T = np.asarray(frames)[-1]
    unit = f" {units}" if units else ""
    with np.printoptions(precision=precision, suppress=True):
        return f"p = {np.round(T[:3, 3], precision) + 0.0}{unit}\nR =\n{np.round(T[:3, :3], precision) + 0.0}"


def _call_readout(fn: Callable[..., str], q: np.ndarray, frames: np.ndarray | None) -> str:
    try:
        nparams = len(inspect.signature(fn).parameters)
    except (TypeError, ValueError):  # pragma: no cover - builtins without a signature
        nparams = 2
    return str(fn(q, frames) if nparams >= 2 else fn(q))


def _limits(limits: Any) -> np.ndarray:
    L = np.asarray(limits, dtype=float)
    if L.shape == (2,):
        L = np.tile(L, (3, 1))
    if L.shape != (3, 2) or not np.all(np.isfinite(L)) or np.any(L[:, 1] <= L[:, 0]):
        raise ValueError(f"limits: expected (low, high) or a (3, 2) array of [low, high] rows, got {limits!r}")
    return L


class Panel(widgets.VBox):
    """A slider panel: sliders on the left, the drawing (and an optional readout) on the right.

    ``draw(ax, q)`` draws configuration ``q`` (radians) on a fresh 3-D axes and returns the
    frames it drew (or None). After each redraw ``last_q``, ``last_frames``, ``last_readout``
    and ``last_axes`` (the drawn axes; its figure is closed) hold what was drawn, so a test (or
    a curious student) can inspect it.

    >>> def draw(ax, q):  # a unit pointer turned by θ about z
    ...     ax.plot([0.0, np.cos(q[0])], [0.0, np.sin(q[0])], [0.0, 0.0])
    >>> panel = Panel(joint_sliders(["θ"], -np.pi, np.pi), draw)
    >>> panel.sliders[0].value = 90.0  # degrees on the slider, radians in draw
    >>> [round(float(v), 6) + 0.0 for v in panel.last_axes.lines[0].get_data_3d()[1]]  # y: 0 to sin 90°
    [0.0, 1.0]
    """

    def __init__(
        self,
        sliders: SliderList,
        draw: Callable[[Any, np.ndarray], np.ndarray | None],
        *,
        readout: Callable[..., str] | None = None,
        title: str | None = None,
        limits: Any = None,
        figsize: tuple[float, float] = (5.5, 4.8),
        elev: float = 25,
        azim: float = -60,
        dpi: float = 100,
    ) -> None:
        self.sliders = sliders
        self._draw = draw
        self._readout_fn = readout
        self._title = title
        self._limits = None if limits is None else _limits(limits)
        self._figsize, self._elev, self._azim, self._dpi = figsize, elev, azim, dpi
        self.last_q: np.ndarray | None = None
        self.last_frames: np.ndarray | None = None
        self.last_readout: str | None = None
        self.last_axes: Any = None
        self.readout_widget = widgets.HTML(value="")
        controls = widgets.VBox(list(sliders) + ([self.readout_widget] if readout is not None else []))
        if get_ipython() is not None:
            # in a kernel: the standard ipywidgets route (clears and refills the Output on every change)
            self.output = widgets.interactive_output(self._redraw, {f"s{i}": s for i, s in enumerate(sliders)})
        else:
            # plain Python (tests, doctests): same callback, wired directly, without terminal clear-codes
            self.output = widgets.Output()
            for s in sliders:
                s.observe(lambda change: self._redraw(), names="value")
            self._redraw()
        super().__init__([widgets.HBox([controls, self.output])])

    def _redraw(self, **kw: float) -> None:
        q = self.sliders.radians()
        fig, ax = new_axes(figsize=self._figsize, title=self._title, elev=self._elev, azim=self._azim, dpi=self._dpi)
        frames = self._draw(ax, q)
        if self._limits is not None:
            ax.set_xlim3d(*self._limits[0])
            ax.set_ylim3d(*self._limits[1])
            ax.set_zlim3d(*self._limits[2])
            ax.set_box_aspect(tuple(self._limits[:, 1] - self._limits[:, 0]))
        ax.locator_params(nbins=5)  # fewer tick numbers: the default ones overlap on a small 3-D axes
        self.last_q = q
        self.last_axes = ax
        self.last_frames = None if frames is None else np.asarray(frames)
        if self._readout_fn is not None:
            text = _call_readout(self._readout_fn, q, self.last_frames)
            self.last_readout = text
            self.readout_widget.value = "<pre style='font-size:85%; line-height:1.2'>" + _escape(text) + "</pre>"
        if get_ipython() is not None:  # in a kernel: show it in the panel's Output; elsewhere (tests) just close
            display(fig)
        plt.close(fig)

    def set_radians(self, q: Any) -> None:
        """Move all sliders to ``q`` (radians / lengths); the drawing follows.

        >>> from puma_course import MK3
        >>> panel = robot_panel(MK3(), readout=None)
        >>> panel.set_radians(MK3().q("qr")); np.degrees(panel.last_q).round(6).tolist()
        [0.0, 90.0, -90.0, 0.0, 0.0]
        """
        self.sliders.set_radians(q)


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _auto_limits(robot: Robot, sliders: SliderList, samples: int = 256) -> np.ndarray:
    """A cube holding the drawn arm (links and frame origins) over the start and seeded random configurations."""
    rng = np.random.default_rng(0)
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    Q = np.vstack([sliders.radians()[None], lo + (hi - lo) * rng.random((samples, robot.n))])
    P = _view_points(robot, Q)
    centre = (P.min(axis=0) + P.max(axis=0)) / 2.0
    half = max(float(np.max(P.max(axis=0) - P.min(axis=0))) / 2.0, 1e-9) * 1.1
    return np.stack([centre - half, centre + half], axis=1)


def _start(robot: Robot, q: Any) -> np.ndarray | None:
    if q is None:
        return None
    if isinstance(q, str):
        return robot.q(q)
    Q = robot.check_q(q)
    if Q.ndim != 1:
        raise ValueError(f"q: expected one joint vector of shape ({robot.n},) or a configuration name, got {Q.shape}")
    return Q


def robot_panel(
    robot: Robot,
    readout: str | Callable[..., str] | None = "pose",
    *,
    q: Any = None,
    step: float | Sequence[float] | None = None,
    title: str | None = None,
    limits: Any = None,
    figsize: tuple[float, float] = (5.5, 4.8),
    elev: float = 25,
    azim: float = -60,
    **draw_kw: Any,
) -> Panel:
    """Sliders for any robot's joints and a 3-D drawing of it (:func:`~puma_course.viz.arms.draw_robot`).

    Everything comes from the robot API: one slider per joint labelled by ``robot.joint_symbols``,
    limited by ``robot.qlim``, in degrees for revolute joints (``θ1 [deg]``) and in the robot's
    ``units`` for the others (``d3 [m]``, or ``q2 []`` for a unitless length). ``q`` is the
    start: a configuration name (``"qn"``) or a joint vector (radians / lengths); by default 0
    where the limits allow it. ``readout`` is ``"pose"`` (position and rotation of
    ``robot.fk(q)``), ``None`` or a callable ``readout(q)`` / ``readout(q, frames)`` returning
    text. ``limits`` is ``(low, high)`` for all axes or a (3, 2) array; by default a cube
    framing the arm over many configurations, fixed once for the panel. Other keywords go to
    ``draw_robot`` (here ``triads="all"``, ``axes=True``, ``labels`` {0} on the base and {m-1}
    on the last frame, a triad length of 8 % of the view, unless given; ``color``, ...). ``title``
    defaults to the name and units.

    >>> from puma_course import MK3
    >>> panel = robot_panel(MK3())
    >>> panel.sliders[1].description, panel.sliders[1].max
    ('θ2 [deg]', 180.0)
    >>> panel.sliders[1].value = 90.0  # the student sets degrees ...
    >>> np.round(panel.last_q, 4).tolist()  # ... the kinematics receives radians
    [0.0, 1.5708, 0.0, 0.0, 0.0]
    """
    if not isinstance(robot, Robot):
        raise ValueError(f"robot: expected a Robot (Puma560(), MK3(), Porter(...), ...), got {type(robot).__name__}")
    sliders = joint_sliders(robot.joint_symbols, robot.qlim[:, 0], robot.qlim[:, 1], _start(robot, q),
                            degrees=robot.revolute.tolist(), step=step, units=robot.units)  # fmt: skip
    lim = _limits(limits) if limits is not None else _auto_limits(robot, sliders)
    m = robot.frames(sliders.radians()).shape[0]
    opts: dict[str, Any] = {
        "triads": "all",
        "axes": True,
        "labels": [f"{{{i}}}" if i in (0, m - 1) else "" for i in range(m)],
        "length": 0.08 * float(np.max(lim[:, 1] - lim[:, 0])),
    }
    opts.update(draw_kw)

    def pose(q: np.ndarray) -> str:
        return pose_readout(q, robot.fk(q)[None], units=robot.units)

    if readout == "pose":
        readout_fn: Callable[..., str] | None = pose
    elif readout is None or callable(readout):
        readout_fn = readout
    else:
        raise ValueError(f"readout: expected None, 'pose' or a callable, got {readout!r}")

    def draw(ax: Any, q: np.ndarray) -> np.ndarray:
        draw_robot(ax, robot, q, **opts)
        return robot.frames(q)

    if title is None:
        title = f"{robot.name} ({robot.units})" if robot.units else robot.name
    return Panel(sliders, draw, readout=readout_fn, title=title, limits=lim, figsize=figsize, elev=elev, azim=azim)


def dh_link_panel(
    values: Sequence[float] = (np.pi / 4, 1.0, np.pi / 6, 0.5),
    length_range: tuple[float, float] = (-1.5, 1.5),
    title: str = "Craig's link matrix",
) -> Panel:
    """Sliders for (α_{i-1}, a_{i-1}, θ_i, d_i): frames {i-1} and {i} and the link matrix ^{i-1}T_i.

    The four elementary steps Rot(X, α) Trans(X, a) Rot(Z, θ) Trans(Z, d) are
    drawn as faint intermediate frames, so the path from {i-1} to {i} (a along
    X_{i-1}, then d along Z_i) is visible. ``values`` are radians / lengths.

    >>> panel = dh_link_panel()
    >>> panel.sliders[0].value, panel.sliders[1].value = 90.0, 1.0  # α_{i-1} = 90°, a_{i-1} = 1
    >>> np.round(panel.last_frames[-1][:3, 3], 4) + 0.0  # origin of {i}: (a, -sin(α) d, cos(α) d)
    array([ 1. , -0.5,  0. ])
    """
    lo, hi = length_range
    sliders = joint_sliders(
        ["α_{i-1}", "a_{i-1}", "θ_i", "d_i"],
        [-np.pi, lo, -np.pi, lo],
        [np.pi, hi, np.pi, hi],
        values,
        degrees=[True, False, True, False],
        step=[5.0, 0.05, 5.0, 0.05],
    )

    def steps(q: np.ndarray) -> np.ndarray:
        """{i-1} (identity), then Rot(X, α), Trans(X, a), Rot(Z, θ), Trans(Z, d) applied one more at a time."""
        return mdh(*(np.tri(5, 4, -1) * q).T)  # row k keeps the first k parameters: (5, 4, 4)

    span = max(abs(lo), abs(hi))
    L = 0.35 * span

    def draw(ax: Any, q: np.ndarray) -> np.ndarray:
        S = steps(q)
        draw_points(ax, S[:, :3, 3], color="0.5", lw=2, alpha=0.6)
        draw_frames(ax, S[1:4], labels=["", "", ""], length=0.6 * L, alpha=0.25, lw=1.5)
        draw_frame(ax, S[0], "{i-1}", length=L)
        draw_frame(ax, S[-1], "{i}", length=L)
        return S[[0, -1]]

    def readout(q: np.ndarray, frames: np.ndarray) -> str:
        with np.printoptions(precision=3, suppress=True):
            return f"^(i-1)T_i =\n{np.round(frames[-1], 3) + 0.0}"

    lim = np.array([[-span - L, span + L]] * 3)
    return Panel(sliders, draw, readout=readout, title=title, limits=lim)
