"""Joint sliders and the panel that joins them to the WebGL viewer (:mod:`.viewer`); the readout.

The lectures' panels are built in :mod:`.panels` (``robot_panel``, ``dh_link_panel``).

Convention: sliders show degrees (their labels say ``θ1 [deg]``) for angles and the robot's
units for lengths (``d3 [m]``); every callback, the viewer and the readout receive joint values
in *radians* (lengths unchanged), as everywhere else in the course. A slider move sends the new
frames to the browser (no picture is drawn on the kernel), so the arm follows the slider while
it is dragged; the view turns with the mouse. Displayed, a panel also leaves a static picture
(PNG) of its first pose in the notebook for readers who have not run it.

This is a display module: it imports ipywidgets and anywidget. ``import puma_course`` never
imports it.

Typical use (in a notebook; the last expression displays the panel)::

    from puma_course import Puma560
    from puma_course.viz import robot_panel
    robot_panel(Puma560(), readout="pose")
"""

from __future__ import annotations

import html
import inspect
from collections.abc import Callable, Sequence
from typing import Any

import ipywidgets as widgets
import numpy as np

from .._validate import as_array
from .viewer import Viewer, with_picture

__all__ = ["SliderList", "joint_sliders", "Panel", "pose_readout", "frame_name"]


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
    continuous_update: bool = True,
) -> SliderList:
    """One ``FloatSlider`` per joint; ``lows``, ``highs``, ``values`` in code units (radians).

    Angles (``degrees`` True for that joint) are shown in degrees with the label
    ``"<name> [deg]"``; lengths (``degrees`` False, e.g. a prismatic joint) keep their value
    and read ``"<name> [<units>]"`` (``"q2 [length]"`` for ``units=""``: a chain that names no
    unit has lengths in its own unit, never an empty ``[]``) or just the name (``units=None``).
    ``values`` default to 0 where the limits allow, else the middle.
    ``step`` is in display units (default 1 degree, or 1/200 of the range for lengths). The
    returned :class:`SliderList` converts back with ``.radians()``. ``continuous_update``
    (default) reports values while a slider is dragged, so the view follows the hand.

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
        label = f"{names[i]} [deg]" if deg[i] else (names[i] if units is None else f"{names[i]} [{units or 'length'}]")
        sliders.append(
            widgets.FloatSlider(
                value=v,
                min=a,
                max=b,
                step=st,
                description=label,
                continuous_update=continuous_update,
                readout_format=".1f" if deg[i] else ".3g",
                style={"description_width": "95px"},
                layout=widgets.Layout(width="340px"),
            )
        )
    return SliderList(sliders, deg)


_SUP = str.maketrans("0123456789-i()", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻ⁱ⁽⁾")
_SUB = str.maketrans("0123456789-i()", "₀₁₂₃₄₅₆₇₈₉₋ᵢ₍₎")


def frame_name(parent: str, child: str) -> str:
    """The name of a transform from frame {child} to {parent}, written as the lectures do: ⁰T₆.

    >>> frame_name("0", "6"), frame_name("i-1", "i")
    ('⁰T₆', 'ⁱ⁻¹Tᵢ')
    """
    return f"{parent.translate(_SUP)}T{child.translate(_SUB)}"


def pose_readout(T: Any, name: str = "T", units: str = "", precision: int = 4) -> str:
    """Text of a pose as its 4x4 matrix, named (``⁰T₆ =``), the lengths' units said once.

    >>> print(pose_readout(np.eye(4), frame_name("0", "1"), units="m"))
    ⁰T₁ =   (lengths in m)
    [[1. 0. 0. 0.]
     [0. 1. 0. 0.]
     [0. 0. 1. 0.]
     [0. 0. 0. 1.]]
    """
    M = as_array(T, "T", (4, 4))
    unit = f"   (lengths in {units})" if units else ""
    with np.printoptions(precision=precision, suppress=True):
        return f"{name} ={unit}\n{np.round(M, precision) + 0.0}"


def _call_readout(fn: Callable[..., str], q: np.ndarray, frames: np.ndarray | None) -> str:
    try:
        nparams = len(inspect.signature(fn).parameters)
    except (TypeError, ValueError):  # pragma: no cover - builtins without a signature
        nparams = 2
    return str(fn(q, frames) if nparams >= 2 else fn(q))


class Panel(widgets.HBox):
    """A joint panel: sliders (and a readout) on the left, a live :class:`~.viewer.Viewer` on the right.

    ``pose(q)`` returns the frames (m, 4, 4) and the link points (p, 3) to show for the joint
    vector ``q`` (radians); each slider move calls it and sends them to ``viewer`` (only what
    moved). ``readout(q)`` or ``readout(q, frames)`` returns the text shown under the sliders.
    ``q`` is the joint vector shown: :meth:`set_radians` keeps it exact (an IK solution stays
    on its pose) while the sliders show it rounded to their steps.
    ``controls`` are more widgets put under the sliders. After each update ``last_q``,
    ``last_frames``, ``last_points`` and ``last_readout`` hold what was sent, so a test (or a
    curious student) can inspect it.

    >>> def pose(q):  # a unit pointer turned by θ about z: frames {0} and {1}
    ...     T = np.eye(4); T[:2, :2] = [[np.cos(q[0]), -np.sin(q[0])], [np.sin(q[0]), np.cos(q[0])]]
    ...     T[:3, 3] = T[:3, 0]
    ...     F = np.stack([np.eye(4), T])
    ...     return F, F[:, :3, 3]
    >>> panel = Panel(joint_sliders(["θ"], -np.pi, np.pi), Viewer(pose(np.zeros(1))[0]), pose)
    >>> panel.sliders[0].value = 90.0  # degrees on the slider, radians in pose
    >>> np.round(panel.last_frames[1][:3, 3], 6).tolist(), panel.viewer.pose["points"][3:5]
    ([0.0, 1.0, 0.0], [0.0, 1.0])
    """

    def __init__(
        self,
        sliders: SliderList,
        viewer: Viewer,
        pose: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
        *,
        readout: Callable[..., str] | None = None,
        controls: Sequence[widgets.Widget] = (),
    ) -> None:
        self.sliders = sliders
        self.viewer = viewer
        self._pose = pose
        self._readout_fn = readout
        self._holding = False
        self.q = sliders.radians()  # the joint vector shown, exact (a slider shows it rounded to its step)
        self.last_q: np.ndarray | None = None
        self.last_frames: np.ndarray | None = None
        self.last_points: np.ndarray | None = None
        self.last_readout: str | None = None
        self.readout_widget = widgets.HTML(value="")
        for s in sliders:
            s.observe(self._on_slider, names="value")
        left = list(sliders) + list(controls) + ([self.readout_widget] if readout is not None else [])
        viewer.layout = widgets.Layout(flex="1 1 auto", min_width="320px")
        super().__init__(
            [widgets.VBox(left, layout=widgets.Layout(flex="0 0 auto", width="350px")), viewer],
            layout=widgets.Layout(width="100%", align_items="flex-start"),
        )
        self._update()

    def _on_slider(self, change: Any) -> None:
        if self._holding:
            return
        k = next(i for i, s in enumerate(self.sliders) if s is change["owner"])
        deg = self.sliders.degrees[k]
        shown = float(np.degrees(self.q[k])) if deg else float(self.q[k])
        if abs(change["new"] - shown) <= 0.5 * float(change["owner"].step) + 1e-9:
            return  # the browser snapped an exact value (set_radians) to the slider's step: keep the exact one
        self.q = self.q.copy()
        self.q[k] = np.radians(change["new"]) if deg else float(change["new"])
        self._update()

    def _update(self) -> None:
        q = self.q
        frames, points = self._pose(q)
        self.viewer.show(frames, points)
        self.last_q, self.last_frames, self.last_points = q, np.asarray(frames), np.asarray(points)
        if self._readout_fn is not None:
            text = _call_readout(self._readout_fn, q, self.last_frames)
            self.last_readout = text
            self.readout_widget.value = (
                "<pre class='puma-readout' style='font-size:12px; line-height:1.25; margin:6px 0 0 0'>"
                + html.escape(text, quote=False) + "</pre>"
            )  # fmt: skip
        self.on_update(q)

    def on_update(self, q: np.ndarray) -> None:
        """Called after every update with the joint vector shown (a hook for subclasses)."""

    def set_radians(self, q: Any) -> None:
        """Move all sliders to ``q`` (radians / lengths); the view follows once, at ``q`` exactly.

        >>> from puma_course import MK3
        >>> from puma_course.viz import robot_panel
        >>> panel = robot_panel(MK3(), readout=None)
        >>> panel.set_radians(MK3().q("qr")); np.degrees(panel.last_q).round(6).tolist()
        [0.0, 90.0, -90.0, 0.0, 0.0]
        """
        q = as_array(q, "q", (len(self.sliders),), what=f"a joint vector of shape ({len(self.sliders)},)")
        self._holding = True
        try:
            self.sliders.set_radians(q)
        finally:
            self._holding = False
        self.q = q.copy()
        self._update()

    def _repr_mimebundle_(self, **kwargs: Any) -> Any:
        return with_picture(super()._repr_mimebundle_(**kwargs), self.viewer)
