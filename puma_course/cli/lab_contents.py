"""The file manager ``puma-course lab`` gives JupyterLab: notebooks open unmodified on any Python.

A saved notebook records the Python that last ran it (``metadata.language_info.version``).
When JupyterLab 4 connects a notebook to its kernel it writes the kernel's own version there,
and a different one marks the notebook modified before the student has touched it. The
lectures are saved on one Python; :class:`CourseContentsManager` hands every notebook to the
browser with the version of the Python that runs the server (the interpreter of the course's
virtual environment, whose ``python3`` kernel the notebooks use), so the kernel's value is the
one already there. Nothing is written to disk; saving writes what JupyterLab writes anyway.
"""

from __future__ import annotations

import platform
import sys
from typing import Any

from jupyter_server.services.contents.largefilemanager import AsyncLargeFileManager

__all__ = ["CourseContentsManager", "kernel_language_info", "with_running_python"]


def kernel_language_info(version: str | None = None) -> dict[str, Any]:
    """The ``language_info`` an IPython kernel on this interpreter reports (ipykernel's ``kernel_info`` reply).

    JupyterLab writes exactly this into a notebook's metadata when its kernel connects.

    >>> sorted(kernel_language_info("3.12.4").items())[-1]
    ('version', '3.12.4')
    """
    return {
        "codemirror_mode": {"name": "ipython", "version": sys.version_info[0]},
        "file_extension": ".py",
        "mimetype": "text/x-python",
        "name": "python",
        "nbconvert_exporter": "python",
        "pygments_lexer": f"ipython{sys.version_info[0]}",
        "version": version or platform.python_version(),
    }


def with_running_python(model: dict[str, Any], version: str | None = None) -> dict[str, Any]:
    """``model`` (a contents model) with a Python notebook's ``language_info`` as the running kernel reports it.

    The version becomes ``version`` (default: this interpreter's), and whatever else the kernel reports and
    the notebook lacks is filled in (a notebook saved by a tool that wrote no ``version``, or only
    ``name``, would otherwise be marked modified on opening). A notebook whose kernel is Python but which
    has no ``language_info`` gets one. Other models, and notebooks of other languages, come back unchanged.

    >>> m = {"type": "notebook", "content": {"metadata": {"language_info": {"name": "python", "version": "3.9.1"}}}}
    >>> with_running_python(m, "3.12.4")["content"]["metadata"]["language_info"]["version"]
    '3.12.4'
    >>> m = {"type": "notebook", "content": {"metadata": {"language_info": {"name": "python"}}}}
    >>> with_running_python(m, "3.12.4")["content"]["metadata"]["language_info"]["mimetype"]
    'text/x-python'
    >>> with_running_python({"type": "file", "content": "x"}, "3.12.4")
    {'type': 'file', 'content': 'x'}
    """
    content = model.get("content") if model.get("type") == "notebook" else None
    meta = content.get("metadata") if isinstance(content, dict) else None
    if not isinstance(meta, dict):
        return model
    info, spec = meta.get("language_info"), meta.get("kernelspec")
    if isinstance(info, dict):
        python = info.get("name") == "python"
    else:
        python = info is None and isinstance(spec, dict) and spec.get("language") == "python"
    if python:
        meta["language_info"] = {**(info or {}), **kernel_language_info(version)}
    return model


class CourseContentsManager(AsyncLargeFileManager):
    """JupyterLab's default file manager, with :func:`with_running_python` applied to every notebook read."""

    async def get(self, path: str, content: bool = True, type: str | None = None, format: str | None = None,
                  require_hash: bool = False) -> dict[str, Any]:  # fmt: skip
        model = await super().get(path, content=content, type=type, format=format, require_hash=require_hash)
        return with_running_python(model)
