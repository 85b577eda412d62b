"""The course's figure style: readable on a projector, the same in every lecture.

``use_course_style()`` (each lecture's first code cell calls it) sets matplotlib's defaults:
figures drawn at 110 dpi, fonts of 11 pt (legends 10 pt, never below 9), ticks that leave room
for each other, constrained layout so labels are not clipped, and no memory of the previous
figure's size. Animations keep their own ``dpi`` argument (see :func:`~.arms.animate_frames`).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

import matplotlib as mpl

__all__ = [
    "COURSE_STYLE",
    "PROJECTOR_STYLE",
    "use_course_style",
    "use_projector_style",
    "projector_style",
    "contrast_ratio",
    "text_color",
    "colour_only_lines",
    "low_contrast_texts",
]

#: Colour of a common normal, a and α (link parameters); of d and θ (joint parameters): the DH drawings
#: (:mod:`.dh_figures`, :mod:`.dimensions`).
NORMAL_COLOR, JOINT_COLOR = "tab:purple", "tab:brown"
#: How the DH drawings draw a joint axis (a dashed grey line): keyword arguments of ``ax.plot``.
AXIS_LINE: dict[str, Any] = dict(ls="--", lw=1.2, color="0.35")

#: matplotlib rcParams of the course (``plt.rcParams.update(COURSE_STYLE)``)
COURSE_STYLE: dict[str, Any] = {
    "figure.dpi": 110,
    "savefig.dpi": 110,
    "figure.figsize": (6.4, 4.4),
    "figure.constrained_layout.use": True,
    "font.size": 11,
    "axes.titlesize": 12,
    "axes.labelsize": 11,
    "xtick.labelsize": 10,
    "ytick.labelsize": 10,
    "legend.fontsize": 10,
    "legend.framealpha": 0.85,
    "axes.grid": False,
    "lines.linewidth": 2.0,
    "image.cmap": "viridis",
}


def use_course_style() -> None:
    """Apply :data:`COURSE_STYLE` to matplotlib (call once per notebook, before drawing).

    >>> use_course_style()
    >>> import matplotlib as mpl
    >>> mpl.rcParams["figure.dpi"] >= 100 and mpl.rcParams["legend.fontsize"] >= 9
    True
    """
    params: Any = mpl.rcParams  # matplotlib types its keys as literals; the style's keys are checked by the test
    params.update(COURSE_STYLE)


#: the course style for a lecture hall: about 1.5 times the fonts and lines, read from the back row of a
#: room whose projector shows a 1216-px-wide figure strip (:func:`use_projector_style`, :func:`projector_style`)
PROJECTOR_STYLE: dict[str, Any] = {
    **COURSE_STYLE,
    "font.size": 16,
    "axes.titlesize": 17,
    "axes.labelsize": 16,
    "xtick.labelsize": 14,
    "ytick.labelsize": 14,
    "legend.fontsize": 14,
    "lines.linewidth": 3.0,
    "lines.markersize": 8,
    "axes.linewidth": 1.5,
    "xtick.major.width": 1.5,
    "ytick.major.width": 1.5,
    "grid.linewidth": 1.2,
}


def use_projector_style() -> None:
    """Switch every following figure to :data:`PROJECTOR_STYLE` (larger fonts, thicker lines): one call.

    Call it instead of :func:`use_course_style` (or after it) when teaching from the notebooks on a
    projector; ``use_course_style()`` switches back.

    >>> use_projector_style()
    >>> import matplotlib as mpl
    >>> mpl.rcParams["font.size"] >= 16 and mpl.rcParams["lines.linewidth"] >= 3
    True
    >>> use_course_style()
    """
    params: Any = mpl.rcParams
    params.update(PROJECTOR_STYLE)


@contextlib.contextmanager
def projector_style() -> Iterator[None]:
    """The projector style for the figures drawn inside a ``with`` block; the style before it comes back after.

    >>> import matplotlib as mpl
    >>> with projector_style():
    ...     mpl.rcParams["font.size"]
    16.0
    """
    params: Any = PROJECTOR_STYLE  # matplotlib types its keys as literals (see use_course_style)
    with mpl.rc_context(params):
        yield


# ---- readable without colour (issue 34; WCAG 2.1 1.4.1 use of colour, 1.4.3 contrast) --------------------


def contrast_ratio(fg: Any, bg: Any = "white") -> float:
    """WCAG 2.1's contrast ratio of two matplotlib colours, (L1 + 0.05) / (L2 + 0.05), from 1 to 21.

    A colour's alpha is blended over ``bg`` first (``bg`` itself taken as opaque).

    >>> round(contrast_ratio("black", "white"), 2), round(contrast_ratio("#767676"), 2)  # 4.54: AA's grey
    (21.0, 4.54)
    >>> contrast_ratio("0.5") < 4.5 < contrast_ratio("0.35")
    True
    """
    from matplotlib.colors import to_rgba  # noqa: PLC0415 - `import puma_course.viz.style` stays light

    def luminance(rgb: Any) -> float:
        c = [v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4 for v in rgb]
        return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]

    back = to_rgba(bg)[:3]
    r, g, b, a = to_rgba(fg)
    front = [a * f + (1 - a) * k for f, k in zip((r, g, b), back, strict=True)]
    hi, lo = sorted([luminance(front), luminance(back)], reverse=True)
    return (hi + 0.05) / (lo + 0.05)


def text_color(color: Any, ground: Any = "white", minimum: float = 4.5) -> Any:
    """``color`` for a text on ``ground``: itself at ``minimum``:1 contrast or more, else its hue darkened until so.

    Lines keep the palette's colours (3:1 is enough for a line, WCAG 1.4.11); the letters naming them need 4.5:1.

    >>> text_color("tab:red")  # 5.4:1 already
    'tab:red'
    >>> c = text_color("tab:green"); round(contrast_ratio("tab:green"), 2), c, round(contrast_ratio(c), 2)
    (3.4, '#258825', 4.54)
    """
    from matplotlib.colors import to_hex, to_rgba  # noqa: PLC0415

    if color is None or contrast_ratio(color, ground) >= minimum:
        return color
    r, g, b, a = to_rgba(color)
    for k in range(1, 21):
        f = 1 - 0.025 * k
        darker = to_hex((r * f, g * f, b * f))
        if contrast_ratio(darker, ground) >= minimum:
            return darker
    return "black"


def _line_key(line: Any) -> tuple[str, str]:
    ls = line.get_linestyle()
    ls = "None" if ls in ("None", "none", " ", "") else ls
    marker = str(line.get_marker())
    return ls, "None" if marker in ("None", "none", " ", "") else marker


def colour_only_lines(fig: Any) -> list[str]:
    """Pairs of lines in one axes told apart by colour alone: same line style and marker, different colour.

    A line is told apart otherwise when its style or marker differs, its width differs by a factor of 1.5 or more,
    its colour differs in lightness by a contrast of 3:1 or more (it survives greyscale and colour blindness), or
    when a text of the axes (not the legend) is drawn in its colour or in :func:`text_color` of it (a direct label).
    A triad's axes (:func:`~.frames.draw_frame`, gid ``triad-x`` ...) are not compared: x, y, z in red, green,
    blue is a convention, its order fixed by the right hand, and a named frame's axes are lettered.
    Returns one sentence per pair; [] is readable.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0, 1], [0, 1], color="tab:blue", label="a"); _ = ax.plot([0, 1], [1, 0], color="tab:red")
    >>> colour_only_lines(fig)
    ["axes 0: 'a' and '_child1' differ by colour only (tab:blue vs tab:red), style '-' marker 'None'"]
    >>> _ = ax.lines[1].set_linestyle("--")
    >>> colour_only_lines(fig)
    []
    >>> plt.close(fig)
    """
    from matplotlib.colors import to_hex  # noqa: PLC0415

    found: list[str] = []
    for k, ax in enumerate(fig.axes):
        labelled = {to_hex(t.get_color()) for t in ax.texts if t.get_visible() and t.get_text().strip()}
        seen: dict[tuple[str, str], dict[str, Any]] = {}
        for line in ax.lines:
            if not line.get_visible() or line.get_alpha() == 0 or str(line.get_gid()).startswith("triad"):
                continue
            colour = to_hex(line.get_color())
            if colour in labelled or to_hex(text_color(line.get_color())) in labelled:
                continue
            key = _line_key(line)
            if key == ("None", "None"):
                continue  # nothing drawn
            others = seen.setdefault(key, {})
            for other, first in others.items():
                wide = max(first.get_linewidth(), line.get_linewidth()) / max(
                    min(first.get_linewidth(), line.get_linewidth()), 1e-9
                )
                if other != colour and wide < 1.5 and contrast_ratio(other, colour) < 3.0:
                    found.append(
                        f"axes {k}: {first.get_label()!r} and {line.get_label()!r} differ by colour only "
                        f"({_name(first.get_color())} vs {_name(line.get_color())}), style {key[0]!r} marker {key[1]!r}"
                    )
            others.setdefault(colour, line)
    return found


def _name(colour: Any) -> str:
    return colour if isinstance(colour, str) else str(colour)


def low_contrast_texts(fig: Any, minimum: float = 4.5) -> list[str]:
    """Every visible text of ``fig`` (titles, labels, tick labels, texts, legends) below ``minimum``:1 on its ground.

    The ground is the axes' face colour for a text of an axes, else the figure's.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> _ = ax.set_title("ok"); _ = ax.text(0, 0, "faint", color="0.6")
    >>> low_contrast_texts(fig)
    ["'faint' 0.6 on #ffffff: 2.85:1"]
    >>> plt.close(fig)
    """
    from matplotlib.colors import to_hex  # noqa: PLC0415
    from matplotlib.text import Text  # noqa: PLC0415

    found: list[str] = []
    fig.canvas.draw()  # tick labels exist once drawn
    for text in fig.findobj(Text):
        if not text.get_visible() or not text.get_text().strip():
            continue
        ax = text.axes
        ground = ax.get_facecolor() if ax is not None else fig.get_facecolor()
        colour = text.get_color()
        alpha = text.get_alpha()
        if alpha is not None:
            from matplotlib.colors import to_rgba  # noqa: PLC0415

            colour = to_rgba(colour, alpha)
        ratio = contrast_ratio(colour, to_hex(ground))
        if ratio < minimum:
            found.append(f"{text.get_text()!r} {_name(text.get_color())} on {to_hex(ground)}: {ratio:.2f}:1")
    return found
