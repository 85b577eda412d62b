"""The course as a static website: the lectures with their saved outputs, the exercises as handed out,
the notation and conventions, built offline from the committed notebooks (nothing is executed).

``build_site(course)`` lays out a book source in a temporary folder (the course's ``notebooks/``,
``exercises/`` and ``figures/``, a landing page, and the course's guides from ``docs/``: the readers' by
default, every one with ``guides="all"``; see :mod:`.guides`)
and builds it with Sphinx, MyST-NB and the Sphinx Book Theme (the parts Jupyter Book 1 is made
of), configured for a reader with no network:

* mathematics is rendered by MathJax 3.2.2 copied into the site (its one-file TeX-to-SVG component,
  from the ``sphinx-mathjax-offline`` distribution): no CDN, and no web font to fetch;
* the widget views of the 3-D viewer are shown as the pictures they carry (``image/png`` is ranked
  before the widget type: there is no kernel on a website);
* Sphinx's search index works offline; thebe and other launch buttons are not used;
* every lecture page offers its notebook for download (``.ipynb``).

Solutions (``solutions/``) are never copied in; the browser tests search the built pages for
the solutions' marker text and for their code.

The site layer imports the base layer only (it reads files; it does not run the course).
"""

from __future__ import annotations

from .build import SiteReport, build_site

__all__ = ["SiteReport", "build_site"]
