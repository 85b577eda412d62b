"""The projector style (issue 25): one call switches every figure to larger fonts and thicker lines."""

from __future__ import annotations

import matplotlib as mpl
import matplotlib.pyplot as plt
import numpy as np

from puma_course.kinematics import Puma560
from puma_course.viz import PROJECTOR_STYLE, projector_style, use_course_style, use_projector_style
from puma_course.viz.path_figures import joint_path_figure
from puma_course.viz.style import COURSE_STYLE

_SIZES = ("font.size", "axes.titlesize", "axes.labelsize", "xtick.labelsize", "ytick.labelsize", "legend.fontsize")


def test_the_projector_style_is_larger_than_the_course_style_in_every_font_and_line():
    for key in _SIZES:
        assert PROJECTOR_STYLE[key] >= 1.3 * COURSE_STYLE[key], key
    assert PROJECTOR_STYLE["lines.linewidth"] >= 1.5 * COURSE_STYLE["lines.linewidth"]
    assert {k: v for k, v in PROJECTOR_STYLE.items() if k not in COURSE_STYLE or k in _SIZES or "width" in k} != {}
    assert PROJECTOR_STYLE["figure.dpi"] == COURSE_STYLE["figure.dpi"]  # same pixels, larger marks


def test_one_call_switches_it_on_and_the_course_style_switches_back():
    with mpl.rc_context():  # the other tests keep matplotlib's defaults
        use_projector_style()
        assert mpl.rcParams["font.size"] == PROJECTOR_STYLE["font.size"]
        fig, axes = joint_path_figure(np.zeros((10, 6)), revolute=Puma560().revolute)
        tick = axes[0, 0].get_yticklabels()[0]
        assert tick.get_fontsize() >= 14
        assert axes[0, 0].lines[0].get_linewidth() >= 3.0
        plt.close(fig)
        use_course_style()
        assert mpl.rcParams["font.size"] == COURSE_STYLE["font.size"]


def test_the_context_manager_restores_the_style_before_it(course_style):
    with projector_style():
        assert mpl.rcParams["lines.linewidth"] == PROJECTOR_STYLE["lines.linewidth"]
    assert mpl.rcParams["lines.linewidth"] == COURSE_STYLE["lines.linewidth"]
