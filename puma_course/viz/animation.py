"""Animations that play anywhere, offline: matplotlib's JavaScript player without its CDN stylesheet.

``anim.to_jshtml()`` draws its play/step buttons with Font Awesome icons and links the icon
stylesheet from a CDN (maxcdn.bootstrapcdn.com): offline, or on the course's static site (which
must fetch nothing at view time), the buttons come out blank. :func:`jshtml` returns the same player
with that link replaced by a few inline CSS rules drawing each icon as a Unicode glyph, so the
animation plays with no network, in JupyterLab and on the website alike.

The player's ``<img>`` also gets the frames' size (``width``/``height`` attributes, read from the
first frame's PNG header) and a few lines of script that lay it out when it comes into view.
matplotlib's own player leaves the image unsized until its script gives it a picture; in
JupyterLab's default (windowed) notebook the cell is often off screen at that moment, kept out of
layout by the browser, and Chromium then drew the image at 0 x 0 until the first click on ▶ gave
it a new picture, which pushed the buttons away from under the pointer (that click was lost).
"""

from __future__ import annotations

import base64
import re
import struct
from typing import Any

__all__ = ["jshtml", "offline_player", "sized_image", "ICON_CSS"]

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
_IMG = re.compile(r'<img id="(_anim_img[0-9a-f]*)">')
_FIRST_FRAME = re.compile(r'frames\[0\] = "data:image/(png|jpeg);base64,((?:[A-Za-z0-9+/=]|\\\n)+)"')


#: Chromium gives no box to an image that reaches a page inside a cell JupyterLab's windowed notebook
#: keeps out of layout (content-visibility: auto) and gets its picture there; a fresh copy of the
#: element, made when the player comes into view, is laid out (matplotlib's player finds its image by id).
_SHOW = """<script>
(function () {
  var img = document.getElementById("IMG_ID");
  if (!img || !window.IntersectionObserver) return;
  var seen = new IntersectionObserver(function (entries) {
    entries.forEach(function (entry) {
      if (!entry.isIntersecting) return;
      var now = document.getElementById("IMG_ID");
      if (now && now.getBoundingClientRect().width === 0) now.replaceWith(now.cloneNode());
      seen.disconnect();
    });
  });
  seen.observe(img.parentNode);
})();
</script>
"""


def _png_size(data: bytes) -> tuple[int, int] | None:
    """(width, height) of a PNG from its IHDR chunk, or None when ``data`` is not a PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        return None
    w, h = struct.unpack(">II", data[16:24])
    return int(w), int(h)


def sized_image(html: str) -> str:
    """``html`` with the player's ``<img>`` given its frames' size (see the module's text).

    >>> import io
    >>> from PIL import Image
    >>> buf = io.BytesIO(); Image.new("RGB", (30, 20)).save(buf, "png")
    >>> b64 = base64.b64encode(buf.getvalue()).decode()
    >>> html = '<img id="_anim_img0a">\\n  frames[0] = "data:image/png;base64,' + b64 + '";'
    >>> sized_image(html).split(">")[0]
    '<img id="_anim_img0a" width="30" height="20"'
    >>> "IntersectionObserver" in sized_image(html)
    True
    """
    frame = _FIRST_FRAME.search(html)
    if frame is None or not _IMG.search(html):
        return html
    b64 = frame.group(2).replace("\\\n", "")
    size = _png_size(base64.b64decode(b64[:64] + "=" * (-len(b64[:64]) % 4))[:24])
    if size is None:
        return html
    w, h = size
    img_id = _IMG.search(html).group(1)  # type: ignore[union-attr]
    return _IMG.sub(lambda m: f'<img id="{m.group(1)}" width="{w}" height="{h}">', html, count=1) + _SHOW.replace(
        "IMG_ID", img_id
    )


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
        return HTML(sized_image(offline_player(anim.to_jshtml())))
