"""A Sphinx extension of the site: display mathematics shown as JupyterLab shows it.

Sphinx wraps every display block that holds a ``\\\\`` in ``\\begin{split}``, and MathJax refuses a
``\\tag`` there ("\\tag not allowed in split environment"), while the lectures number the sources'
equations with ``\\tag`` next to matrices (``\\begin{bmatrix} … \\\\ … \\end{bmatrix}``). A line break
inside an environment is not a line of the display, so here a block is wrapped only when it breaks a
line outside every environment; everything else is MyST's (and Sphinx's) rendering.
"""

from __future__ import annotations

import re
from typing import Any

_ENVIRONMENT = re.compile(r"\\begin\{([A-Za-z*]+)\}.*?\\end\{\1\}", re.S)
_BREAK = "\\\\"


def breaks_outside_environments(tex: str) -> bool:
    """Whether ``tex`` has a line break (``\\\\``) outside every ``\\begin … \\end`` environment.

    >>> breaks_outside_environments(r"e = \\begin{bmatrix} a \\\\ b \\end{bmatrix} \\tag{1}")
    False
    >>> breaks_outside_environments(r"a = 1 \\\\ b = 2")
    True
    """
    return _BREAK in _ENVIRONMENT.sub("", tex)


def visit_displaymath(self: Any, node: Any) -> None:
    """Sphinx's HTML visitor for display math, without the ``split`` wrapper a block does not need."""
    from docutils import nodes
    from myst_parser.sphinx_ext.mathjax import html_visit_displaymath

    text = node.astext()
    if "amsmath" in node.get("classes", []) or node.get("number") or _BREAK not in text or \
            breaks_outside_environments(text):  # fmt: skip
        html_visit_displaymath(self, node)
        return
    prefix, suffix = self.builder.config.mathjax_display
    self.body.append(self.starttag(node, "div", CLASS="math notranslate nohighlight"))
    self.body.append(prefix + self.encode(text) + suffix + "</div>\n")
    raise nodes.SkipNode


def _install(app: Any) -> None:
    if "mathjax" in app.registry.html_block_math_renderers:
        app.registry.html_block_math_renderers["mathjax"] = (visit_displaymath, None)


def setup(app: Any) -> dict[str, Any]:
    """Register the visitor once MyST has installed its own (``builder-inited``, later priority)."""
    app.connect("builder-inited", _install, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
