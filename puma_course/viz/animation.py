"""Animations that play anywhere, offline: matplotlib's JavaScript player without its CDN stylesheet.

``anim.to_jshtml()`` draws its play/step buttons with Font Awesome icons and links the icon
stylesheet from a CDN (maxcdn.bootstrapcdn.com): offline, or on the course's static site (which
must fetch nothing at view time), the buttons come out blank. :func:`jshtml` returns the same player
with that link replaced by a few inline CSS rules drawing each icon as a Unicode glyph, so the
animation plays with no network, in JupyterLab and on the website alike.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["jshtml", "offline_player", "ICON_CSS"]

#: the icons of matplotlib's player, as Unicode glyphs (the classes it uses, scoped to its buttons)
_GLYPHS = {
    "fa-play": "\\25B6",  # ▶
    "fa-pause": "\\275A\\275A",  # ❚❚
    "fa-step-forward": "\\25B6\\2759",  # ▶❙
    "fa-step-backward": "\\2759\\25C0",  # ❙◀
    "fa-fast-forward": "\\25B6\\25B6\\2759",  # ▶▶❙
    "fa-fast-backward": "\\2759\\25C0\\25C0",  # ❙◀◀
    "fa-plus": "+",
    "fa-minus": "\\2212",  # −
}
ICON_CSS = (
    "<style>.animation i.fa{font-style:normal;font-family:sans-serif;display:inline-block;min-width:1.2em}"
    + "".join(f'.animation i.{cls}:before{{content:"{glyph}"}}' for cls, glyph in _GLYPHS.items())
    + ".animation i.fa-flip-horizontal{transform:scaleX(-1)}</style>"
)
_CDN_LINK = re.compile(r"<link[^>]*font-awesome[^>]*>", re.I)


def offline_player(html: str) -> str:
    """``html`` from ``to_jshtml()`` with the Font Awesome CDN link replaced by inline icon styles.

    >>> offline_player('<link rel="stylesheet" href="https://maxcdn.bootstrapcdn.com/font-awesome/4.4.0/'
    ...                'css/font-awesome.min.css"><div class="animation">...</div>').startswith("<style>")
    True
    """
    if not isinstance(html, str):
        raise ValueError(f"html: expected the text of an animation's to_jshtml(), got {type(html).__name__}")
    return _CDN_LINK.sub(lambda _: ICON_CSS, html, count=1) if _CDN_LINK.search(html) else ICON_CSS + html


def jshtml(anim: Any) -> Any:
    """An IPython ``HTML`` display of ``anim`` (a matplotlib animation) that plays offline.

    Use it where a lecture wrote ``HTML(anim.to_jshtml())``.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from matplotlib.animation import FuncAnimation
    >>> fig, ax = plt.subplots()
    >>> anim = FuncAnimation(fig, lambda i: [], frames=2)
    >>> html = jshtml(anim).data
    >>> "bootstrapcdn" in html, "fa-play" in html
    (False, True)
    >>> plt.close(fig)
    """
    from IPython.display import HTML

    if not hasattr(anim, "to_jshtml"):
        raise ValueError(f"anim: expected a matplotlib animation (FuncAnimation), got {type(anim).__name__}")
    import matplotlib as mpl

    # the frames at the figure's own dpi (the animation's), not the course style's savefig.dpi
    with mpl.rc_context({"savefig.dpi": "figure"}):
        return HTML(offline_player(anim.to_jshtml()))
