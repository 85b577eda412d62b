"""Text alternatives of the lectures' figures, where MyST-NB does not put them by itself.

A lecture cell describes its figure in ``metadata.mystnb.image.alt``; MyST-NB renders that as the
``alt`` of an image output. An animation (a ``text/html`` output) shows its frames in an
``<img id="_anim_img…">`` that MyST-NB passes through untouched. ``viz.jshtml(anim, alt=...)`` writes
the alt itself (JupyterLab shows it too); for an animation without one (matplotlib's own player),
the copy of a notebook that the website (and the slides) are built from gets the cell's text on that
element, so a screen reader announces the animation. The committed notebooks are not changed.
"""

from __future__ import annotations

import html
import re
from typing import Any

__all__ = ["cell_alt", "with_animation_alt"]

_ANIM_IMG = re.compile(r'<img id="_anim_img[0-9a-f]*"(?![^>]*\balt=)')


def cell_alt(cell: dict[str, Any]) -> str | None:
    """The text alternative a cell's metadata gives its figure (``mystnb.image.alt``), or None."""
    alt = cell.get("metadata", {}).get("mystnb", {}).get("image", {}).get("alt")
    return alt if isinstance(alt, str) and alt.strip() else None


def with_animation_alt(nb: dict[str, Any]) -> int:
    """Put each cell's alt on the frame ``<img>`` of its animations, in place; returns how many were set.

    >>> nb = {"cells": [{"cell_type": "code", "metadata": {"mystnb": {"image": {"alt": "An arm turning"}}},
    ...        "outputs": [{"output_type": "display_data", "data": {"text/html": '<img id="_anim_img0f">'}}]}]}
    >>> with_animation_alt(nb), nb["cells"][0]["outputs"][0]["data"]["text/html"]
    (1, '<img id="_anim_img0f" alt="An arm turning">')
    """
    count = 0
    for cell in nb.get("cells", []):
        alt = cell_alt(cell)
        if cell.get("cell_type") != "code" or alt is None:
            continue
        for output in cell.get("outputs", []):
            data = output.get("data", {})
            if "text/html" not in data:
                continue
            text = "".join(data["text/html"]) if isinstance(data["text/html"], list) else data["text/html"]
            attribute = f' alt="{html.escape(alt, quote=True)}"'
            new, n = _ANIM_IMG.subn(lambda m, a=attribute: m.group(0) + a, text)
            if n:
                data["text/html"] = new
                count += n
    return count
