"""Animations that play anywhere, offline, and show their first frame before any script runs.

:func:`jshtml` turns a matplotlib animation into the course's own small player (an IPython ``HTML``
display). Matplotlib's ``anim.to_jshtml()`` would do, but (1) it links Font Awesome from a CDN, so
offline or on the course's static site its buttons come out blank; (2) its ``<img>`` has no picture
until a script gives it one, and JupyterLab runs no script of an untrusted notebook (every notebook a
student has just opened), so a lecture showed a broken image over dead buttons; (3) its slider has
no name and its image no text alternative.

The player here:

* carries the first frame in the HTML itself (``src``, with ``alt`` text and the frames' pixel size
  written in ``width``/``height`` and the style), so the picture is there, at its size, with or
  without scripts; its size never depends on layout at the time a script runs (JupyterLab's
  windowed notebook keeps cells out of view out of layout, and Chromium then drew an image that
  got its picture there at 0 x 0: an IntersectionObserver lays a fresh copy out if that happens);
* ships its buttons and slider hidden, with a line saying they appear once the cell has run (no
  control sits there dead); its script shows them and removes the line (in a trusted notebook,
  after Run All, on the website);
* draws its icons as text glyphs (nothing fetched), names every button, labels its slider with the
  visible word "frame", and marks the slider ``data-lm-suppress-shortcuts`` so JupyterLab's
  command-mode shortcuts leave its arrow keys alone.

:func:`offline_player` still rewrites a bare ``to_jshtml()`` for code that uses matplotlib's player.
"""

from __future__ import annotations

import base64
import html as _html
import io
import re
import struct
import uuid
from typing import Any

__all__ = ["jshtml", "player_html", "offline_player", "ICON_CSS"]

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

#: the player's buttons in matplotlib's order: (action, name, glyph)
_BUTTONS = (
    ("slower", "Decrease speed", "\u2212"),
    ("first", "First frame", "\u2759\u25c0\u25c0"),
    ("previous", "Previous frame", "\u2759\u25c0"),
    ("reverse", "Play backwards", "\u25c0"),
    ("pause", "Pause", "\u275a\u275a"),
    ("play", "Play", "\u25b6"),
    ("next", "Next frame", "\u25b6\u2759"),
    ("last", "Last frame", "\u25b6\u25b6\u2759"),
    ("faster", "Increase speed", "+"),
)

_CSS = """<style>
.puma-anim,.puma-anim .animation{display:inline-block;text-align:center;max-width:100%}
.puma-anim img{display:block;margin:0 auto}
.puma-anim .anim-label{margin:0 .4em;white-space:nowrap}
.puma-anim input.anim-slider{width:min(374px,70%);vertical-align:middle}
.puma-anim .anim-buttons{margin:6px 0}
.puma-anim .anim-buttons button{min-width:36px;padding:2px 4px;font-family:sans-serif}
.puma-anim .anim-note{font-size:90%;margin:2px 0}
</style>"""

#: the player's behaviour; UID, INTERVAL and LOOP are filled in, FRAMES holds frames 1.. (frame 0 is the img's src)
_SCRIPT = """<script>
(function () {
  var box = document.getElementById("_anim_boxUID");
  if (!box || box.getAttribute("data-ready")) return;
  box.setAttribute("data-ready", "1");
  var frames = [null, FRAMES];
  var img = document.getElementById("_anim_imgUID");
  frames[0] = img.getAttribute("src");
  var slider = box.querySelector("input.anim-slider"), loop = box.querySelector("input.anim-loop");
  var count = box.querySelector(".anim-count"), note = box.querySelector(".anim-note");
  var current = 0, direction = 0, timer = null, interval = INTERVAL;
  frames.forEach(function (f) { (new Image()).src = f; });  // decoded ahead of play
  // Chromium can leave an image that got its picture while JupyterLab kept its cell out of layout
  // at 0 x 0: a fresh copy of the element is laid out (looked up by id: the copy replaces it)
  function laidOut() {
    var now = document.getElementById(img.id) || img;
    if (now.getBoundingClientRect().width === 0 && box.getBoundingClientRect().width > 0) {
      var copy = now.cloneNode();
      now.replaceWith(copy);
      now = copy;
    }
    img = now;
    return img;
  }
  function show(k) {
    current = k;
    laidOut().src = frames[k];
    slider.value = String(k);
    count.textContent = (k + 1) + " / " + frames.length;
  }
  function stop() {
    direction = 0;
    if (timer !== null) { clearInterval(timer); timer = null; }
  }
  function tick() {
    var k = current + direction;
    if (k < 0 || k >= frames.length) {
      if (!loop.checked) { stop(); return; }
      k = (k + frames.length) % frames.length;
    }
    show(k);
  }
  function play(d) {
    stop();
    if (d > 0 && current === frames.length - 1) show(0);
    else if (d < 0 && current === 0) show(frames.length - 1);
    else laidOut();
    direction = d;
    timer = setInterval(tick, interval);
  }
  function speed(f) {
    interval *= f;
    if (direction !== 0) play(direction);
  }
  var act = {
    slower: function () { speed(1 / 0.7); }, faster: function () { speed(0.7); },
    first: function () { stop(); show(0); }, last: function () { stop(); show(frames.length - 1); },
    previous: function () { stop(); show(Math.max(0, current - 1)); },
    next: function () { stop(); show(Math.min(frames.length - 1, current + 1)); },
    reverse: function () { play(-1); }, play: function () { play(1); }, pause: stop
  };
  box.querySelectorAll("button[data-act]").forEach(function (b) {
    b.addEventListener("click", act[b.getAttribute("data-act")]);
  });
  slider.addEventListener("input", function () { stop(); show(parseInt(slider.value, 10)); });
  box.querySelector(".anim-player").hidden = false;
  if (note) note.remove();
  if (window.IntersectionObserver) {
    new IntersectionObserver(function (entries) {
      entries.forEach(function (e) { if (e.isIntersecting) laidOut(); });
    }).observe(box);
  }
})();
</script>"""


def _png_size(data: bytes) -> tuple[int, int]:
    """(width, height) of a PNG from its IHDR chunk."""
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        raise ValueError("frames: expected PNG images, got bytes that do not start with a PNG header")
    w, h = struct.unpack(">II", data[16:24])
    return int(w), int(h)


def player_html(frames: list[bytes], alt: str, interval: float = 200.0, loop: bool = True) -> str:
    """The player's HTML for ``frames`` (PNG bytes, one per frame), described by ``alt``.

    The first frame is the ``<img>``'s own picture; ``interval`` is the time between frames in
    milliseconds; ``loop`` the initial state of its "loop" box.

    >>> from PIL import Image
    >>> def png(c):
    ...     buf = io.BytesIO(); Image.new("RGB", (30, 20), c).save(buf, "png"); return buf.getvalue()
    >>> page = player_html([png("red"), png("blue")], alt="a square turning blue")
    >>> re.search(r'<img [^>]*>', page).group(0).count('width="30" height="20"'), 'alt="a square turning blue"' in page
    (1, True)
    >>> page.count("data:image/png;base64,"), page.count("<button ")
    (2, 9)
    """
    if not frames:
        raise ValueError("frames: expected at least one PNG frame, got none")
    if not isinstance(alt, str) or not alt.strip():
        raise ValueError(f"alt: expected a text describing the animation, got {alt!r}")
    if not interval > 0:
        raise ValueError(f"interval: expected a positive time between frames in ms, got {interval!r}")
    w, h = _png_size(frames[0])
    uid = uuid.uuid4().hex
    urls = ["data:image/png;base64," + base64.b64encode(f).decode("ascii") for f in frames]
    n = len(frames)
    checked = ' checked="checked"' if loop else ""
    style = f"width:{w}px;max-width:100%;height:auto;aspect-ratio:{w}/{h}"
    buttons = "\n".join(
        f'    <button type="button" data-act="{act}" title="{name}" aria-label="{name}">{glyph}</button>'
        for act, name, glyph in _BUTTONS
    )
    body = f"""<div class="puma-anim"><div class="animation" id="_anim_box{uid}">
  <img id="_anim_img{uid}" src="{urls[0]}" width="{w}" height="{h}" style="{style}" alt="{_html.escape(alt)}">
  <div class="anim-player" hidden="hidden">
  <div class="anim-controls">
    <label class="anim-label">frame <input id="_anim_slider{uid}" class="anim-slider" type="range" min="0"
      max="{n - 1}" step="1" value="0" data-lm-suppress-shortcuts="true"></label>
    <span class="anim-count">1 / {n}</span>
  </div>
  <div class="anim-buttons">
{buttons}
    <label class="anim-label"><input class="anim-loop" type="checkbox"{checked}> loop</label>
  </div>
  </div>
  <p class="anim-note">The first of {n} frames. The buttons that play them appear once this cell has run
  (Run All, or run the cell): JupyterLab starts no script of a notebook it has not run or trusted.</p>
</div></div>"""
    script = (
        _SCRIPT.replace("UID", uid)
        .replace("INTERVAL", repr(float(interval)))
        .replace("FRAMES", ",\n    ".join(f'"{u}"' for u in urls[1:]))
    )
    return _CSS + "\n" + body + "\n" + script


def offline_player(html: str) -> str:
    """``html`` from matplotlib's ``to_jshtml()`` with the Font Awesome CDN link replaced by inline icon styles.

    >>> offline_player('<link rel="stylesheet" href="https://maxcdn.bootstrapcdn.com/font-awesome/4.4.0/'
    ...                'css/font-awesome.min.css"><div class="animation">...</div>').startswith("<style>")
    True
    """
    if not isinstance(html, str):
        raise ValueError(f"html: expected the text of an animation's to_jshtml(), got {type(html).__name__}")
    return _CDN_LINK.sub(lambda _: ICON_CSS, html, count=1) if _CDN_LINK.search(html) else ICON_CSS + html


def _frames(anim: Any) -> list[bytes]:
    """Every frame of ``anim`` as PNG bytes, drawn at its figure's own dpi (as ``anim.save`` draws them)."""
    from matplotlib.animation import AbstractMovieWriter

    class _Collect(AbstractMovieWriter):
        def __init__(self) -> None:
            super().__init__(fps=5)
            self.pngs: list[bytes] = []

        def setup(self, fig: Any, outfile: Any, dpi: float | None = None) -> None:
            self.outfile, self.fig = outfile, fig
            self.dpi = fig.dpi if dpi is None else dpi

        def grab_frame(self, **savefig_kwargs: Any) -> None:
            buf = io.BytesIO()
            self.fig.savefig(buf, format="png", dpi=self.dpi, **savefig_kwargs)
            self.pngs.append(buf.getvalue())

        def finish(self) -> None:
            pass

    import matplotlib as mpl

    writer = _Collect()
    with mpl.rc_context({"savefig.dpi": "figure"}):  # the figure's own dpi, not the course style's savefig.dpi
        anim.save("frames", writer=writer)
    return writer.pngs


def jshtml(anim: Any, alt: str | None = None) -> Any:
    """An IPython ``HTML`` display of ``anim`` (a matplotlib animation): the course's player, offline.

    ``alt`` describes the animation for a screen reader (default: a line naming it an animation
    and its number of frames; a lecture gives its own). The frames keep the figure's dpi.

    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from matplotlib.animation import FuncAnimation
    >>> fig, ax = plt.subplots(figsize=(2, 1), dpi=50)
    >>> anim = FuncAnimation(fig, lambda i: [], frames=2)
    >>> page = jshtml(anim, alt="an empty plot").data
    >>> "bootstrapcdn" in page, 'width="100" height="50"' in page, page.count("data:image/png")
    (False, True, 2)
    >>> plt.close(fig)
    """
    from IPython.display import HTML

    if not hasattr(anim, "to_jshtml") or not hasattr(anim, "save"):
        raise ValueError(f"anim: expected a matplotlib animation (FuncAnimation), got {type(anim).__name__}")
    frames = _frames(anim)
    if alt is None:
        alt = f"An animation of {len(frames)} frames."
    interval = float(getattr(anim, "_interval", 200.0))
    return HTML(player_html(frames, alt, interval=interval, loop=bool(getattr(anim, "_repeat", True))))
