"""Which extra of the install brings what a command needs, and the message when it is missing.

The plain install (``pip install .``) carries what the lectures and the self-checks import; the
commands that need more say which extra to install (see ``pyproject.toml``): ``lab`` (JupyterLab
and the kernel), ``grader`` (nbformat, bubblewrap), ``site`` (Sphinx), ``instructor`` (nbconvert, and
MathJax from sphinx-mathjax-offline, which brings Sphinx, for the slides and the keys), ``dev`` (all of
them and the maintainers' tools). Standard library only (base layer).
"""

from __future__ import annotations

import importlib.util

__all__ = ["EXTRAS", "MissingExtraError", "require_extra"]

#: The extra that brings what a command needs (module to import -> extra), see pyproject.toml.
EXTRAS: dict[str, tuple[tuple[str, str], ...]] = {
    "lab": (("jupyterlab", "lab"), ("ipykernel", "lab")),
    "release": (("nbformat", "grader"),),
    "site": (("sphinx", "site"), ("myst_nb", "site")),
    "slides": (("nbformat", "instructor"), ("nbconvert", "instructor"), ("sphinx-mathjax-offline", "instructor")),
    "keys": (("nbformat", "instructor"), ("nbconvert", "instructor"), ("sphinx-mathjax-offline", "instructor")),
}


class MissingExtraError(RuntimeError):
    """A command needs a package of an extra that is not installed (the message says which extra)."""


def require_extra(command: str) -> None:
    """Raise :class:`MissingExtraError` naming the extra to install when ``command`` lacks a package.

    >>> require_extra("check")  # needs nothing beyond the plain install
    """

    for module, extra in EXTRAS.get(command, ()):
        if importlib.util.find_spec(module) is None:
            raise MissingExtraError(
                f"puma-course {command} needs {module}, which comes with the {extra!r} extra: "
                f"pip install 'puma-course[{extra}]' (in a course folder: pip install '.[{extra}]')"
            )
