"""Notebooks read and written as nbformat reads and writes them, without importing nbformat.

``import nbformat`` imports its validator, hence jsonschema and its format checkers, which compile dozens of
grammars at import (``rfc3987_syntax``: about 3 s, python-jsonschema/jsonschema #1392): a command that only
reads and writes notebooks (``release``, ``release --check``) would pay that on every run. This module reads
and writes the same JSON with the standard library:

* :func:`reads` / :func:`read` give what ``nbformat.reads(text, as_version=4)`` gives for an nbformat-4 file:
  nodes with attribute access (:class:`Node`), multi-line strings joined, transient fields dropped (an older
  format is handed to nbformat itself, which converts it);
* :func:`writes` gives the exact text of ``nbformat.writes`` (sorted keys, one-space indent, strings split
  into lines);
* :func:`new_notebook` and the ``new_*_cell`` functions build what ``nbformat.v4`` builds.

What nbformat adds on top, the schema check, is the tests' job: ``tests/grading/publish/test_release.py`` validates
every notebook release writes against nbformat's schema and compares this module with nbformat on every
notebook of the course. Standard library only.
"""

from __future__ import annotations

import copy
import json
import os
import uuid
from typing import Any

__all__ = ["Node", "from_dict", "reads", "read", "writes", "new_notebook", "new_code_cell", "new_markdown_cell",
           "new_raw_cell"]  # fmt: skip

#: the notebook format written (nbformat.v4's ``nbformat`` and ``nbformat_minor``)
NBFORMAT, NBFORMAT_MINOR = 4, 5


class Node(dict[str, Any]):
    """A dict whose keys are also attributes (``cell.source``), like nbformat's ``NotebookNode``.

    >>> n = Node(cell_type="code")
    >>> n.source = "x = 1"
    >>> n.cell_type, n["source"]
    ('code', 'x = 1')
    """

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name: str, value: Any) -> None:
        self[name] = value

    def __delattr__(self, name: str) -> None:
        try:
            del self[name]
        except KeyError:
            raise AttributeError(name) from None


def from_dict(value: Any) -> Any:
    """``value`` with every dict in it (at any depth) made a :class:`Node`."""
    if isinstance(value, dict):
        return Node({k: from_dict(v) for k, v in value.items()})
    if isinstance(value, list | tuple):
        return [from_dict(v) for v in value]
    return value


def _is_json_mime(mime: str) -> bool:
    return mime == "application/json" or (mime.startswith("application/") and mime.endswith("+json"))


def _rejoin_bundle(data: dict[str, Any]) -> None:
    for key, value in list(data.items()):
        if not _is_json_mime(key) and isinstance(value, list) and all(isinstance(line, str) for line in value):
            data[key] = "".join(value)


def _split_bundle(data: dict[str, Any]) -> None:
    for key, value in list(data.items()):
        if isinstance(value, str) and (key.startswith("text/") or key in ("application/javascript", "image/svg+xml")):
            data[key] = value.splitlines(True)


def _strip_transient(nb: dict[str, Any]) -> None:
    """Drop what nbformat never stores (in both reading and writing)."""
    for key in ("orig_nbformat", "orig_nbformat_minor", "signature"):
        nb.get("metadata", {}).pop(key, None)
    for cell in nb.get("cells", []):
        cell.get("metadata", {}).pop("trusted", None)


def reads(text: str) -> Any:
    """The notebook in ``text``, as ``nbformat.reads(text, as_version=4)`` reads it (not validated).

    >>> nb = reads('{"cells": [{"cell_type": "markdown", "metadata": {}, "source": ["a\\\\n", "b"]}], '
    ...            '"metadata": {}, "nbformat": 4, "nbformat_minor": 5}')
    >>> nb.cells[0].source
    'a\\nb'
    """
    data = json.loads(text)
    if not isinstance(data, dict) or data.get("nbformat") != NBFORMAT:
        import nbformat  # an older (or unknown) format: nbformat converts it, or says why it cannot

        return nbformat.reads(text, as_version=NBFORMAT)
    nb = from_dict(data)
    for cell in nb.get("cells", []):
        if isinstance(cell.get("source"), list):
            cell.source = "".join(cell.source)
        for attachment in cell.get("attachments", {}).values():
            _rejoin_bundle(attachment)
        if cell.get("cell_type") == "code":
            for output in cell.get("outputs", []):
                kind = output.get("output_type", "")
                if kind in ("execute_result", "display_data"):
                    _rejoin_bundle(output.get("data", {}))
                elif kind and isinstance(output.get("text", ""), list):
                    output.text = "".join(output.text)
    _strip_transient(nb)
    return nb


def read(path: str | os.PathLike[str]) -> Any:
    """The notebook in the file ``path`` (UTF-8), as :func:`reads` reads it."""
    with open(path, encoding="utf-8") as fh:
        return reads(fh.read())


class _Bytes(json.JSONEncoder):
    def default(self, o: Any) -> Any:
        return o.decode("ascii") if isinstance(o, bytes) else super().default(o)


def writes(nb: Any) -> str:
    """The text ``nbformat.writes(nb)`` gives (``nb`` itself is left as it is; not validated)."""
    nb = copy.deepcopy(nb)
    for cell in nb["cells"]:
        if isinstance(cell.get("source"), str):
            cell["source"] = cell["source"].splitlines(True)
        for attachment in cell.get("attachments", {}).values():
            _split_bundle(attachment)
        if cell["cell_type"] == "code":
            for output in cell["outputs"]:
                if output["output_type"] in ("execute_result", "display_data"):
                    _split_bundle(output.get("data", {}))
                elif output["output_type"] == "stream" and isinstance(output["text"], str):
                    output["text"] = output["text"].splitlines(True)
    _strip_transient(nb)
    return json.dumps(nb, cls=_Bytes, indent=1, sort_keys=True, separators=(",", ": "), ensure_ascii=False)


def _cell(cell_type: str, source: str, extra: dict[str, Any], **fields: Any) -> Node:
    cell = Node(id=uuid.uuid4().hex[:8], cell_type=cell_type, metadata=Node(), **fields)
    cell.source = source
    cell.update(extra)
    return cell


def new_code_cell(source: str = "", **extra: Any) -> Node:
    """A code cell, as ``nbformat.v4.new_code_cell`` makes it (a random ``id`` unless one is given)."""
    return _cell("code", source, extra, execution_count=None, outputs=[])


def new_markdown_cell(source: str = "", **extra: Any) -> Node:
    """A Markdown cell, as ``nbformat.v4.new_markdown_cell`` makes it."""
    return _cell("markdown", source, extra)


def new_raw_cell(source: str = "", **extra: Any) -> Node:
    """A raw cell, as ``nbformat.v4.new_raw_cell`` makes it."""
    return _cell("raw", source, extra)


def new_notebook(**extra: Any) -> Node:
    """An empty notebook, as ``nbformat.v4.new_notebook`` makes it."""
    nb = Node(nbformat=NBFORMAT, nbformat_minor=NBFORMAT_MINOR, metadata=Node(), cells=[])
    nb.update(extra)
    return nb
