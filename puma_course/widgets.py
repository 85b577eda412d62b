"""Slider panels for the lectures: ipywidgets 8 + ``interactive_output`` + matplotlib (inline).

Convention: sliders show degrees (their labels say ``θ1 [deg]``) for angles and
plain units for lengths; every callback, ``frames_fn`` and ``readout`` receives
joint values in *radians* (lengths unchanged), as everywhere else in the course.
Each redraw builds a fresh matplotlib figure, displays it in the panel's
``Output`` and closes it, so the panel works with the inline backend in
JupyterLab 4 with nothing to install (no ipympl). Axis limits are fixed when the
panel is built, so the view does not jump while a slider moves.

This is a display module: it imports ipywidgets and matplotlib. ``import
puma_course`` never imports it.

Typical use (in a notebook; the last expression displays the panel)::

    from puma_course import puma560
    from puma_course.widgets import chain_panel
    arm = puma560()
    chain_panel(arm.frames, 6, readout="pose", title="PUMA-560")
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

from . import plotting
from ._validate import as_array
from .dh import mdh

__all__ = ["SliderList", "joint_sliders", "Panel", "chain_panel", "dh_link_panel", "pose_readout"]


class SliderList(list):
    """A list of ``FloatSlider`` widgets that knows which ones show degrees.

    ``radians()`` returns the current joint vector in code units: degrees
    converted to radians, lengths unchanged.
    """

    def __init__(self, sliders: Sequence[widgets.FloatSlider], degrees: Sequence[bool]) -> None:
        super().__init__(sliders)
        self.degrees = tuple(bool(x) for x in degrees)

    def radians(self) -> np.ndarray:
        """The slider values as a joint vector in radians (lengths unchanged)."""
        v = np.array([s.value for s in self], dtype=float)
        return np.where(self.degrees, np.radians(v), v)

    def set_radians(self, q: Any) -> None:
        """Move the sliders to the joint vector ``q`` (radians / lengths)."""
        q = as_array(q, "q", (len(self),), what=f"a joint vector of shape ({len(self)},)")
        for s, deg, v in zip(self, self.degrees, q, strict=True):
            s.value = float(np.degrees(v)) if deg else float(v)


def _per_joint(value: Any, n: int, name: str) -> list:
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
    units: str = "",
) -> SliderList:
    """One ``FloatSlider`` per joint; ``lows``, ``highs``, ``values`` in code units (radians).

    Angles (``degrees`` True for that joint) are shown in degrees with the label
    ``"<name> [deg]"``; lengths (``degrees`` False, e.g. a prismatic joint) keep
    their value and read ``"<name> [<units>]"`` (or just the name). ``step``
    is in display units (default 1 degree, or 1/200 of the range for lengths).
    The returned :class:`SliderList` converts back with ``.radians()``.

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
    sliders = []
    for i in range(n):
        conv = np.degrees if deg[i] else float
        a, b, v = float(conv(lo[i])), float(conv(hi[i])), float(conv(val[i]))
        st = steps[i]
        if st is None:
            st = 1.0 if deg[i] else float(10.0 ** np.floor(np.log10((b - a) / 200.0)))
        label = f"{names[i]} [deg]" if deg[i] else (f"{names[i]} [{units}]" if units else names[i])
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


def pose_readout(q: np.ndarray, frames: np.ndarray, precision: int = 4) -> str:
    """Text of the last frame's pose: position p and rotation matrix R (for a panel's readout).

    >>> print(pose_readout(np.zeros(1), np.eye(4)[None]))
    p = [0. 0. 0.]
    R =
    [[1. 0. 0.]
     [0. 1. 0.]
     [0. 0. 1.]]
    """
    T = np.asarray(frames)[-1]
    with np.printoptions(precision=precision, suppress=True):
        return f"p = {np.round(T[:3, 3], precision) + 0.0}\nR =\n{np.round(T[:3, :3], precision) + 0.0}"


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

    ``draw(ax, q)`` draws configuration ``q`` (radians) on a fresh 3-D axes.
    After each redraw ``last_q``, ``last_frames`` and ``last_readout`` hold
    what was drawn, so a test (or a curious student) can inspect it.
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
        fig, ax = plotting.new_axes(
            figsize=self._figsize, title=self._title, elev=self._elev, azim=self._azim, dpi=self._dpi
        )
        frames = self._draw(ax, q)
        if self._limits is not None:
            ax.set_xlim3d(*self._limits[0])
            ax.set_ylim3d(*self._limits[1])
            ax.set_zlim3d(*self._limits[2])
            ax.set_box_aspect(tuple(self._limits[:, 1] - self._limits[:, 0]))
        ax.locator_params(nbins=5)  # fewer tick numbers: the default ones overlap on a small 3-D axes
        self.last_q = q
        self.last_frames = None if frames is None else np.asarray(frames)
        if self._readout_fn is not None:
            text = _call_readout(self._readout_fn, q, self.last_frames)
            self.last_readout = text
            self.readout_widget.value = "<pre style='font-size:85%; line-height:1.2'>" + _escape(text) + "</pre>"
        if get_ipython() is not None:  # in a kernel: show it in the panel's Output; elsewhere (tests) just close
            display(fig)
        plt.close(fig)

    def set_radians(self, q: Any) -> None:
        """Move all sliders to ``q`` (radians / lengths); the drawing follows."""
        self.sliders.set_radians(q)


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _auto_limits(frames_fn: Callable[[np.ndarray], Any], sliders: SliderList, samples: int = 48) -> np.ndarray:
    """A cube holding every frame origin over the initial and some seeded random configurations."""
    rng = np.random.default_rng(0)
    lo = np.array([s.min for s in sliders])
    hi = np.array([s.max for s in sliders])
    deg = np.array(sliders.degrees)
    Q = lo + (hi - lo) * rng.random((samples, len(sliders)))
    Q = np.where(deg, np.radians(Q), Q)
    pts = [np.zeros((1, 3))]
    for q in np.vstack([sliders.radians()[None], Q]):
        F = as_array(frames_fn(q), "frames_fn(q)", (4, 4), batch=True).reshape(-1, 4, 4)
        pts.append(F[:, :3, 3])
    P = np.vstack(pts)
    centre = (P.min(axis=0) + P.max(axis=0)) / 2.0
    half = max(float(np.max(P.max(axis=0) - P.min(axis=0))) / 2.0, 1e-9) * 1.1
    return np.stack([centre - half, centre + half], axis=1)


def chain_panel(
    frames_fn: Callable[[np.ndarray], Any],
    joints: int | Sequence[str],
    lows: Any = -np.pi,
    highs: Any = np.pi,
    values: Any | None = None,
    *,
    degrees: bool | Sequence[bool] = True,
    step: float | Sequence[float] | None = None,
    units: str = "",
    readout: str | Callable[..., str] | None = None,
    title: str | None = None,
    limits: Any = None,
    labels: Sequence[str] | None = None,
    length: float | None = None,
    figsize: tuple[float, float] = (5.5, 4.8),
    elev: float = 25,
    azim: float = -60,
) -> Panel:
    """Sliders for a chain's joints and a 3-D drawing of ``frames_fn(q)`` (k, 4, 4), q in radians.

    ``joints`` is the number of joints (names θ1..θn) or their names.
    ``readout`` is ``None``, ``"pose"`` (end-effector p and R from the last
    frame) or a callable ``readout(q)`` / ``readout(q, frames)`` returning text.
    ``limits`` is ``(low, high)`` for all axes or a (3, 2) array; by default a
    cube framing the arm over many configurations, fixed once for the panel.
    Works for any chain: ``chain_panel(arm.frames, 6)`` or, for Porter's chain,
    ``chain_panel(lambda q: porter.frames(q, l1, l3, l4), names, ...)``.

    >>> from puma_course import mk3
    >>> panel = chain_panel(mk3().frames, 5, readout="pose")
    >>> panel.sliders[1].description, panel.sliders[1].max
    ('θ2 [deg]', 180.0)
    >>> panel.sliders[1].value = 90.0  # the student sets degrees ...
    >>> np.round(panel.last_q, 4).tolist()  # ... the kinematics receives radians
    [0.0, 1.5708, 0.0, 0.0, 0.0]
    """
    names = [f"θ{i + 1}" for i in range(joints)] if isinstance(joints, (int, np.integer)) else list(joints)
    sliders = joint_sliders(names, lows, highs, values, degrees=degrees, step=step, units=units)
    lim = _limits(limits) if limits is not None else _auto_limits(frames_fn, sliders)
    L = length if length is not None else 0.08 * float(np.max(lim[:, 1] - lim[:, 0]))
    if readout == "pose":
        readout_fn: Callable[..., str] | None = pose_readout
    elif readout is None or callable(readout):
        readout_fn = readout
    else:
        raise ValueError(f"readout: expected None, 'pose' or a callable, got {readout!r}")

    def draw(ax: Any, q: np.ndarray) -> np.ndarray:
        F = as_array(frames_fn(q), "frames_fn(q)", (4, 4), batch=True).reshape(-1, 4, 4)
        plotting.draw_chain(ax, F, labels=labels, length=L)
        return F

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
        al, a, th, d = q
        I = np.eye(4)
        return np.stack(
            [
                I,
                mdh(al, 0.0, 0.0, 0.0),
                mdh(al, a, 0.0, 0.0),
                mdh(al, a, th, 0.0),
                mdh(al, a, th, d),
            ]
        )

    span = max(abs(lo), abs(hi))
    L = 0.35 * span

    def draw(ax: Any, q: np.ndarray) -> np.ndarray:
        S = steps(q)
        plotting.draw_points(ax, S[:, :3, 3], color="0.5", lw=2, alpha=0.6)
        plotting.draw_frames(ax, S[1:4], labels=["", "", ""], length=0.6 * L, alpha=0.25, lw=1.5)
        plotting.draw_frame(ax, S[0], "{i-1}", length=L)
        plotting.draw_frame(ax, S[-1], "{i}", length=L)
        return S[[0, -1]]

    def readout(q: np.ndarray, frames: np.ndarray) -> str:
        with np.printoptions(precision=3, suppress=True):
            return f"^(i-1)T_i =\n{np.round(frames[-1], 3) + 0.0}"

    lim = np.array([[-span - L, span + L]] * 3)
    return Panel(sliders, draw, readout=readout, title=title, limits=lim)
