"""The lectures' joint panels: :func:`robot_panel` for any robot, :func:`dh_link_panel` for one DH link.

Sliders (degrees for angles, the robot's units for lengths) drive a WebGL view
(:mod:`.viewer`); the readout is the pose matrix. See :mod:`.widgets` for the building blocks.

Typical use (in a notebook; the last expression displays the panel)::

    from puma_course import Puma560
    from puma_course.viz import robot_panel
    robot_panel(Puma560(), readout="pose")
"""

from __future__ import annotations

import html
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import ipywidgets as widgets
import numpy as np

from ..kinematics.dh import mdh
from ..kinematics.ik import IKSolutions, SingularityWarning
from ..kinematics.robot import Robot
from .viewer import RobotViewer, Viewer, start_q
from .widgets import Panel, SliderList, frame_name, joint_sliders, pose_readout

__all__ = ["RobotPanel", "robot_panel", "dh_link_panel"]


class RobotPanel(Panel):
    """The panel of a robot (:func:`robot_panel`), with the optional IK ghosts and their selector."""

    def __init__(self, robot: Robot, sliders: SliderList, viewer: RobotViewer, *, readout: Callable[..., str] | None,
                 ik: bool) -> None:  # fmt: skip
        self.robot = robot
        self.ik = ik
        self.solutions: IKSolutions | None = None
        self._branches: list[str] = []
        controls: list[widgets.Widget] = []
        if ik:
            wide = widgets.Layout(width="340px")
            self.ik_selector = widgets.Dropdown(
                description="IK solution", options=[], style={"description_width": "95px"}, layout=wide
            )
            self.ik_go = widgets.Button(
                description="move the arm there", layout=wide,
                tooltip="set the sliders to the selected solution (same hand pose)",
            )  # fmt: skip
            self.ik_status = widgets.HTML(value="")
            self.ik_selector.observe(self._on_select, names="value")
            self.ik_go.on_click(lambda _: self.go_to_solution())
            controls = [self.ik_selector, self.ik_go, self.ik_status]
        super().__init__(sliders, viewer, lambda q: (robot.frames(q), robot.points(q)), readout=readout,
                         controls=controls)  # fmt: skip

    def on_update(self, q: np.ndarray) -> None:
        if not self.ik:
            return
        assert isinstance(self.viewer, RobotViewer)
        with warnings.catch_warnings():  # a singular pose is said in the status line, not as a warning
            warnings.simplefilter("ignore", SingularityWarning)
            sol = self.robot.ik(self.robot.fk(q), near=q)
        self.solutions = sol
        names = list(sol.labels) or [f"solution {k + 1}" for k in range(len(sol))]
        # the selected branch (its label) stays selected while the arm moves; the order is nearest first
        old = self.ik_selector.value
        keep = self._branches[old] if old is not None and old < len(self._branches) else None
        self._branches = names
        self.ik_selector.unobserve(self._on_select, names="value")
        try:
            self.ik_selector.options = [(f"{k + 1}: {lab}", k) for k, lab in enumerate(names)]
            self.ik_selector.value = names.index(keep) if keep in names else (0 if names else None)
        finally:
            self.ik_selector.observe(self._on_select, names="value")
        if sol.success:
            text = f"{len(sol)} configurations reach this hand pose (grey ghosts, the selected one blue)"
            if sol.singular:
                text += "; singular: " + "; ".join(sol.messages.get(k, k) for k in sol.singular)
        else:
            text = f"no solution: {sol.reason}"
        self.ik_status.value = (
            f"<div style='font-size:12px; line-height:1.3; width:340px'>{html.escape(text, quote=False)}</div>"
        )
        self.viewer.show_ik(sol, selected=self.ik_selector.value)

    def _on_select(self, change: Any) -> None:
        if self.solutions is not None and isinstance(self.viewer, RobotViewer):
            self.viewer.show_ik(self.solutions, selected=change["new"])

    def go_to_solution(self, k: int | None = None) -> None:
        """Move the sliders to IK solution ``k`` (default: the selected one); the hand pose stays."""
        if self.solutions is None or len(self.solutions) == 0:
            return
        k = self.ik_selector.value if k is None else int(k)
        self.set_radians(self.solutions.q[k])


def robot_panel(
    robot: Robot,
    readout: str | Callable[..., str] | None = "pose",
    *,
    q: Any = None,
    step: float | Sequence[float] | None = None,
    title: str | None = None,
    labels: str | Sequence[str] = "all",
    ik: bool = False,
    height: int = 440,
    azim: float = -60,
    elev: float = 25,
) -> RobotPanel:
    """Sliders for any robot's joints driving a WebGL view of it (:class:`~.viewer.RobotViewer`).

    Everything comes from the robot API: one slider per joint labelled by ``robot.joint_symbols``,
    limited by ``robot.qlim``, in degrees for revolute joints (``θ1 [deg]``) and in the robot's
    ``units`` for the others (``d3 [m]``, or ``q2 [length]`` for a chain that names no unit). ``q`` is the
    start: a configuration name (``"qn"``) or a joint vector (radians / lengths); by default 0
    where the limits allow it. ``readout`` is ``"pose"`` (the matrix ``robot.fk(q)``, named
    ⁰Tₙ), ``None`` or a callable ``readout(q)`` / ``readout(q, frames)`` returning text.
    ``labels`` names the frames' triads (``"all"``: {0} ... {m-1}; ``"ends"``, ``"none"`` or one
    text per frame). ``ik=True`` adds the inverse problem of the current hand pose: every
    solution drawn as a ghost arm, a selector that highlights one, and a button that moves the
    arm there. ``title`` defaults to the robot's name; the view holds the arm over its whole
    joint range and starts from ``azim``/``elev`` (degrees).

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
    q0 = start_q(robot, q)
    sliders = joint_sliders(robot.joint_symbols, robot.qlim[:, 0], robot.qlim[:, 1], q0,
                            degrees=robot.revolute.tolist(), step=step, units=robot.units)  # fmt: skip
    viewer = RobotViewer(robot, sliders.radians(), labels=labels, title=title, height=height, azim=azim, elev=elev)
    m = len(viewer.scene["frames"])
    name = frame_name("0", str(m - 1))

    def pose(q: np.ndarray) -> str:
        return pose_readout(robot.fk(q), name, units=robot.units)

    if readout == "pose":
        readout_fn: Callable[..., str] | None = pose
    elif readout is None or callable(readout):
        readout_fn = readout
    else:
        raise ValueError(f"readout: expected None, 'pose' or a callable, got {readout!r}")
    return RobotPanel(robot, sliders, viewer, readout=readout_fn, ik=ik)


def dh_link_panel(
    values: Sequence[float] = (np.pi / 4, 1.0, np.pi / 6, 0.5),
    length_range: tuple[float, float] = (-1.5, 1.5),
    title: str = "Craig's link matrix",
    height: int = 420,
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
        ["αᵢ₋₁", "aᵢ₋₁", "θᵢ", "dᵢ"],  # plain Unicode: a slider's label shows no TeX
        [-np.pi, lo, -np.pi, lo],
        [np.pi, hi, np.pi, hi],
        values,
        degrees=[True, False, True, False],
        step=[1.0, 0.05, 1.0, 0.05],
        units="",
    )

    def steps(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """{i-1} (identity), then Rot(X, α), Trans(X, a), Rot(Z, θ), Trans(Z, d) applied one more at a time."""
        S = mdh(*(np.tri(5, 4, -1) * q).T)  # row k keeps the first k parameters: (5, 4, 4)
        return S, S[:, :3, 3]

    span = max(abs(lo), abs(hi))
    L = 0.35 * span
    F0, _ = steps(sliders.radians())
    # the view holds the two frames as they start (origins and axis tips), so they fill the picture;
    # a slider that carries {i} out of it makes the viewer frame the pose again
    tips = (F0[:, :3, 3][:, None, :] + L * np.swapaxes(F0[:, :3, :3], 1, 2)).reshape(-1, 3)
    viewer = Viewer(F0, F0[:, :3, 3], labels=["{i-1}", "", "", "", "{i}"], lengths=[L, 0.6 * L, 0.6 * L, 0.6 * L, L],
                    faint=[False, True, True, True, False], axes=[True, False, False, False, True],
                    view_points=np.vstack([F0[:, :3, 3], tips]), title=title, height=height, link_radius=0.012 * span,
                    link_color="#8c8c8c", note="grey: the path of the origin (a along X, then d along Z)")  # fmt: skip
    name = frame_name("i-1", "i")

    def readout(q: np.ndarray, frames: np.ndarray) -> str:
        return pose_readout(frames[-1], name, precision=3)

    return Panel(sliders, viewer, steps, readout=readout)
