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
from typing import Any

from jupyter_server.services.contents.largefilemanager import AsyncLargeFileManager

__all__ = ["CourseContentsManager", "with_running_python"]


def with_running_python(model: dict[str, Any], version: str | None = None) -> dict[str, Any]:
    """``model`` (a contents model) with a Python notebook's ``language_info.version`` set to ``version``.

    ``version`` defaults to this interpreter's; other models, and notebooks of other languages or
    without ``language_info``, come back unchanged.

    >>> m = {"type": "notebook", "content": {"metadata": {"language_info": {"name": "python", "version": "3.9.1"}}}}
    >>> with_running_python(m, "3.12.4")["content"]["metadata"]["language_info"]["version"]
    '3.12.4'
    >>> with_running_python({"type": "file", "content": "x"}, "3.12.4")
    {'type': 'file', 'content': 'x'}
    """
    content = model.get("content") if model.get("type") == "notebook" else None
    info = content.get("metadata", {}).get("language_info") if isinstance(content, dict) else None
    if isinstance(info, dict) and info.get("name") == "python" and "version" in info:
        info["version"] = version or platform.python_version()
    return model


class CourseContentsManager(AsyncLargeFileManager):
    """JupyterLab's default file manager, with :func:`with_running_python` applied to every notebook read."""

    async def get(self, path: str, content: bool = True, type: str | None = None, format: str | None = None,
                  require_hash: bool = False) -> dict[str, Any]:  # fmt: skip
        model = await super().get(path, content=content, type=type, format=format, require_hash=require_hash)
        return with_running_python(model)
