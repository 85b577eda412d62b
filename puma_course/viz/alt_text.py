"""Figures that carry their text alternative into JupyterLab, not only into the course site (issue 34).

JupyterLab shows an ``image/png`` output as a bare ``<img>``: its image renderer reads the picture's
``width``, ``height``, ``unconfined`` and ``needs_background`` from the output's metadata, never an alt
(JupyterLab 4, ``@jupyterlab/rendermime``'s ``renderImage``). An output that also holds ``text/html``
is shown through that (HTML ranks before PNG, and an untrusted notebook keeps an ``<img>`` with a
``data:`` source and its ``alt``). So a lecture cell calls :func:`figure_alt` first; every matplotlib
figure the cell then shows is the inline backend's PNG as ``<img src="data:image/png;base64,..." alt="...">``
in a ``text/html`` output, instead of a bare ``image/png`` (one copy of the picture: a notebook keeps its size).
The alt is forgotten when the cell ends. Outside IPython (a script, a doctest) it does nothing.
A joint panel or viewer shown by the cell uses the same alt for its still picture (:func:`current_alt`,
``viz.viewer.with_picture``), which is also an ``<img alt>`` in ``text/html``.

The text is the one the cell's ``metadata.mystnb.image.alt`` gives the site (``site/alt_text.py``);
``tests/viz/test_alt_text.py`` checks that both say the same.
"""

from __future__ import annotations

import base64
import html
from typing import Any

from matplotlib.figure import Figure

__all__ = ["current_alt", "figure_alt", "img_html"]

_STATE: dict[str, Any] = {"alt": None, "shell": None, "png": None, "wrapper": None}


def img_html(png: str | bytes, alt: str) -> str:
    """An ``<img>`` of a PNG (bytes, or their base64 text) with its text alternative, as one HTML string.

    >>> img_html(b"\\x89PNG", 'a "bent" arm & a frame')
    '<img src="data:image/png;base64,iVBORw==" alt="a &quot;bent&quot; arm &amp; a frame">'
    """
    text = base64.b64encode(png).decode("ascii") if isinstance(png, bytes) else png
    return f'<img src="data:image/png;base64,{text}" alt="{html.escape(alt, quote=True)}">'


def _check_alt(alt: Any) -> str:
    if not isinstance(alt, str) or len(alt.strip()) < 10:
        raise ValueError(f"alt: expected a sentence describing the figure (10 characters or more), got {alt!r}")
    return alt


def _figure_html(fig: Figure) -> str | None:
    """The text/html formatter of a Figure: the inline backend's own PNG in an ``<img alt>`` while an alt is set."""
    alt, printer = _STATE["alt"], _STATE["png"]
    if alt is None or printer is None:
        return None
    png: Any = printer(fig)
    if isinstance(png, tuple):  # (data, metadata) for a retina figure
        png = png[0]
    if not png:
        return None
    return img_html(png, alt)


def _png_unless_alt(fig: Figure) -> Any:
    """The image/png formatter of a Figure: the inline backend's, except while an alt is set (the HTML has it)."""
    return None if _STATE["alt"] is not None else _STATE["png"](fig)


def current_alt() -> str | None:
    """The text alternative :func:`figure_alt` gave the running cell, or None (a joint panel's still picture uses it).

    >>> current_alt() is None  # no IPython cell running here
    True
    """
    alt: str | None = _STATE["alt"]
    return alt


def _forget(*_: Any) -> None:
    _STATE["alt"] = None


def figure_alt(alt: str) -> None:
    """Give every figure this cell shows the text alternative ``alt`` in JupyterLab (and nbconvert).

    Call it first in a figure's cell; the alt holds until the cell ends. Outside IPython it only checks ``alt``.

    >>> figure_alt("The PUMA-560 at qz: upper arm level, forearm hanging.")  # no IPython here: nothing shown
    >>> figure_alt("")
    Traceback (most recent call last):
    ...
    ValueError: alt: expected a sentence describing the figure (10 characters or more), got ''
    """
    _check_alt(alt)
    try:
        from IPython import get_ipython  # noqa: PLC0415 - IPython is optional: a script has no display
    except ImportError:
        return
    shell = get_ipython()
    if shell is None or not hasattr(shell, "display_formatter"):
        return
    if _STATE["shell"] is not shell:
        shell.display_formatter.formatters["text/html"].for_type(Figure, _figure_html)
        shell.events.register("post_run_cell", _forget)  # after post_execute, where the inline backend shows
        _STATE["shell"] = shell
    _STATE["alt"] = alt  # a joint panel's still picture takes it too (current_alt), with or without matplotlib's
    png = shell.display_formatter.formatters["image/png"]
    current = png.lookup_by_type(Figure) if Figure in png.type_printers else None
    if current is None:
        return  # no inline backend (no PNG of figures): no figure to give the alt to
    if current is not _png_unless_alt:  # the inline backend's printer, (re)registered by %matplotlib inline
        _STATE["png"] = current
        png.for_type(Figure, _png_unless_alt)
