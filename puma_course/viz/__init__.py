"""Viz layer: drawing the course's arms and frames with matplotlib, animations and slider panels.

* :mod:`~puma_course.viz.frames`: a 3-D axes with equal scaling, frame triads, polylines;
* :mod:`~puma_course.viz.arms`: any robot through the robot API (:func:`draw_robot`: links
  ``robot.points(q)``, triads ``robot.frames(q)``), any chain from its frames
  (:func:`draw_chain`), pictures and jshtml animations;
* :mod:`~puma_course.viz.three_step`: the pictures and the animation of the three-step procedure;
* :mod:`~puma_course.viz.viewer`: the WebGL viewer (an anywidget with three.js bundled): any
  chain or robot, turned with the mouse, ghost arms, targets, animations;
* :mod:`~puma_course.viz.widgets`: joint sliders and the :class:`Panel` joining them to a viewer;
* :mod:`~puma_course.viz.animation`: ``jshtml(anim, alt=...)``, an offline player showing its first frame unscripted;
* :mod:`~puma_course.viz.alt_text`: ``figure_alt(alt)``, the text alternative of a cell's figures in JupyterLab;
* :mod:`~puma_course.viz.style`: the course's figure style (``use_course_style()``; ``use_projector_style()``
  for a lecture hall);
* :mod:`~puma_course.viz.panels`: the lectures' panels, :func:`robot_panel` (any robot, optional
  IK ghosts) and :func:`dh_link_panel`.

It loads matplotlib, ipywidgets and anywidget; ``import puma_course`` does not import it.

>>> import matplotlib
>>> matplotlib.use("Agg")
>>> from puma_course import Puma560
>>> from puma_course.viz import plot_robot
>>> fig, ax = plot_robot(Puma560(), Puma560().q("qr"))
>>> ax.get_title()
'PUMA-560'
>>> import matplotlib.pyplot as plt; plt.close(fig)
"""

from __future__ import annotations

from . import alt_text, animation, arms, frames, panels, style, three_step, viewer, widgets
from .alt_text import figure_alt
from .animation import jshtml
from .arms import animate_frames, animate_robot, draw_chain, draw_robot, plot_chain, plot_robot
from .frames import AXIS_COLORS, draw_frame, draw_frames, draw_points, new_axes, set_equal, triad_letters
from .panels import RobotPanel, dh_link_panel, robot_panel
from .style import COURSE_STYLE, PROJECTOR_STYLE, projector_style, use_course_style, use_projector_style
from .viewer import RobotViewer, Viewer
from .widgets import Panel, SliderList, frame_name, joint_sliders, pose_readout

__all__ = [
    "AXIS_COLORS",
    "alt_text",
    "animation",
    "jshtml",
    "COURSE_STYLE",
    "use_course_style",
    "use_projector_style",
    "projector_style",
    "PROJECTOR_STYLE",
    "Panel",
    "RobotPanel",
    "RobotViewer",
    "SliderList",
    "Viewer",
    "animate_frames",
    "animate_robot",
    "arms",
    "dh_link_panel",
    "draw_chain",
    "draw_frame",
    "draw_frames",
    "draw_points",
    "draw_robot",
    "figure_alt",
    "triad_letters",
    "frame_name",
    "frames",
    "joint_sliders",
    "new_axes",
    "panels",
    "style",
    "plot_chain",
    "plot_robot",
    "pose_readout",
    "robot_panel",
    "set_equal",
    "three_step",
    "viewer",
    "widgets",
]
