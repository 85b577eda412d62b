"""Code a notebook carries without showing it: large encoded blobs, and the calls that would unpack or run them.

Read statically, nothing is run. :func:`payloads` looks at every string of a handed-in notebook (cell
sources, outputs, attachments, metadata) and, in code cells, at every string literal (adjacent
literals joined): a run of at least :data:`MIN_BLOB` base64 characters is decoded and told by its first
bytes (images, the normal content of outputs and attachments, are passed over; a zip, gzip, bzip2, xz or
zlib stream, a pickle, Python source or other bytes are reported). What an archive or a compressed
stream holds is opened within :data:`MAX_UNPACKED` bytes, and the Python source found in it, or in a long
plain string literal, is returned so that :mod:`.copies` can compare it with the package's source. The
names of calls that decode or run code (``exec``, ``b64decode``, ``zipimport``, ...) in code cells are
listed too, and so are the names that reach past the grader's interface into its objects (``ctypes``,
``__closure__``, ``gc.get_objects``, ...: no tripwire sees them). A report for the instructor: it changes no mark.
"""

from __future__ import annotations

import ast
import base64
import binascii
import bz2
import io
import lzma
import re
import tarfile
import tokenize
import zipfile
import zlib
from collections.abc import Iterator
from typing import Any

from .text import plural

__all__ = ["MIN_BLOB", "MAX_UNPACKED", "SUSPECT_CALLS", "REACHES", "payloads", "notebook_strings"]

#: Base64 runs shorter than this (characters) are not reported: about 1.5 kB of data.
MIN_BLOB = 2000
#: A plain (not base64) string literal in a code cell longer than this is reported.
MIN_LITERAL = 4000
#: At most this many bytes are unpacked from one blob (a zip bomb stays small).
MAX_UNPACKED = 8_000_000
#: Names whose presence in a code cell says code is decoded, unpacked or run at run time.
SUSPECT_CALLS = frozenset(
    "exec eval compile b64decode b32decode b16decode a85decode b85decode decodebytes standard_b64decode "
    "urlsafe_b64decode ZipFile zipimport zipimporter decompress marshal FunctionType CodeType __import__ "
    "import_module".split()
)
#: Names (or string literals) that reach into live objects: the grader's wrappers, closures and memory.
REACHES = frozenset(
    "ctypes cast py_object pythonapi __closure__ cell_contents get_objects get_referents get_referrers".split()
)
_B64 = re.compile(rf"[A-Za-z0-9+/_-]{{{MIN_BLOB},}}={{0,2}}")
_IMAGES = (b"\x89PNG", b"\xff\xd8\xff", b"GIF8", b"RIFF", b"%PDF", b"<svg", b"<?xml")
_MAGIC = (
    (b"PK\x03\x04", "a zip archive"),
    (b"\x1f\x8b", "a gzip stream"),
    (b"BZh", "a bzip2 stream"),
    (b"\xfd7zXZ", "an xz stream"),
    (b"\x80\x04", "a pickle"),
    (b"\x80\x05", "a pickle"),
)


def _text(value: Any) -> str:
    return "".join(str(s) for s in value) if isinstance(value, list) else str(value)


def notebook_strings(nb: Any, where: str = "notebook") -> Iterator[tuple[str, str]]:
    """Every string in the notebook's JSON, with where it is (``cell 7 source``, ``cell 3 outputs``)."""
    if isinstance(nb, dict) and isinstance(nb.get("cells"), list):
        for i, cell in enumerate(nb["cells"]):
            if isinstance(cell, dict):
                for key, value in cell.items():
                    yield from notebook_strings(value if key != "source" else _text(value), f"cell {i} {key}")
        yield from notebook_strings(nb.get("metadata"), "notebook metadata")
    elif isinstance(nb, dict):
        for value in nb.values():
            yield from notebook_strings(value, where)
    elif isinstance(nb, list):
        for value in nb:
            yield from notebook_strings(value, where)
    elif isinstance(nb, str):
        yield where, nb


def _scan(code: str) -> tuple[list[str], set[str]]:
    """The string literals of ``code``, adjacent ones joined (``"ab" "cd"`` -> ``"abcd"``; f-strings left out),
    and the names it uses."""
    out: list[str] = []
    names: set[str] = set()
    joined = False
    try:
        for tok in tokenize.generate_tokens(io.StringIO(code).readline):
            if tok.type == tokenize.NAME:
                names.add(tok.string)
            if tok.type == tokenize.STRING:
                try:
                    value = ast.literal_eval(tok.string)
                except (ValueError, SyntaxError, MemoryError):
                    joined = False
                    continue
                text = value.decode("latin-1") if isinstance(value, bytes) else str(value)
                if joined:
                    out[-1] += text
                else:
                    out.append(text)
                joined = True
            elif tok.type not in (tokenize.NL, tokenize.COMMENT) and tok.string not in ("(", ")", "+"):
                joined = False
    except (tokenize.TokenError, SyntaxError):
        pass
    return out, names


def _unpack(data: bytes) -> tuple[str, list[tuple[str, str]]]:
    """What ``data`` is (``"a zip archive of 3 files: a.py, ..."``) and the Python sources it holds."""
    kind = next((what for magic, what in _MAGIC if data.startswith(magic)), "")
    if not kind and data[:1] == b"x" and data[1:2] in (b"\x01", b"\x5e", b"\x9c", b"\xda"):
        kind = "a zlib stream"
    sources: list[tuple[str, str]] = []
    try:
        if kind == "a zip archive":
            with zipfile.ZipFile(io.BytesIO(data)) as z:
                names = z.namelist()
                budget = MAX_UNPACKED
                for info in z.infolist():
                    if info.filename.endswith(".py") and 0 < info.file_size <= budget:
                        budget -= info.file_size
                        with z.open(info) as f:
                            sources.append((info.filename, f.read(info.file_size).decode("utf-8", "replace")))
            shown = ", ".join(names[:4]) + (", ..." if len(names) > 4 else "")
            return f"a zip archive of {plural(len(names), 'file')}: {shown}", sources
        if kind in ("a gzip stream", "a bzip2 stream", "an xz stream", "a zlib stream"):
            inner = _decompress(kind, data)
            what, found = _unpack(inner)
            if inner[257:262] == b"ustar":
                with tarfile.open(fileobj=io.BytesIO(inner)) as t:
                    members = [m for m in t.getmembers() if m.isfile()]
                    for m in members:
                        member = t.extractfile(m) if m.name.endswith(".py") else None
                        if member is not None:
                            sources.append((m.name, member.read().decode("utf-8", "replace")))
                return f"{kind} of a tar archive of {plural(len(members), 'file')}", sources
            return f"{kind} of {what}", found
        if kind:
            return kind, sources
    except (OSError, EOFError, ValueError, zipfile.BadZipFile, tarfile.TarError, lzma.LZMAError, zlib.error):
        return f"{kind or 'data'} that does not unpack", sources
    if _python(data):
        return "Python source", [("(decoded)", data.decode())]
    return "bytes", sources


def _decompress(kind: str, data: bytes) -> bytes:
    """The first :data:`MAX_UNPACKED` bytes of a compressed stream."""
    if kind == "a gzip stream":
        return zlib.decompressobj(wbits=31).decompress(data, MAX_UNPACKED)
    if kind == "a zlib stream":
        return zlib.decompressobj().decompress(data, MAX_UNPACKED)
    if kind == "a bzip2 stream":
        return bz2.BZ2Decompressor().decompress(data, MAX_UNPACKED)
    return lzma.LZMADecompressor().decompress(data, MAX_UNPACKED)


def _python(data: bytes | str) -> bool:
    """Whether ``data`` reads as Python source with at least one definition or statement of a few lines."""
    try:
        text = data.decode("utf-8") if isinstance(data, bytes) else data
        tree = ast.parse(text)
    except (UnicodeDecodeError, SyntaxError, ValueError, RecursionError, MemoryError):
        return False
    return len(tree.body) >= 2 or any(isinstance(n, (ast.FunctionDef, ast.ClassDef)) for n in tree.body)


def _blob(where: str, run: str) -> tuple[str, list[tuple[str, str]]] | None:
    try:
        data = base64.b64decode(run + "=" * (-len(run) % 4), altchars=b"-_" if "-" in run or "_" in run else None)
    except (binascii.Error, ValueError):
        return None
    if data.startswith(_IMAGES):
        return None
    what, sources = _unpack(data)
    note = f"{where}: {len(run)} base64 characters holding {what}"
    return note, [(f"{where}, {name}", text) for name, text in sources]


def payloads(nb: Any, given: frozenset[str] = frozenset()) -> tuple[list[str], list[tuple[str, str]]]:
    """What the notebook ``nb`` (its parsed JSON) carries: the notes, and the Python sources found in blobs
    or long literals as (where, source). Code cells whose text is in ``given`` (the exercise's own) are not
    read again.

    >>> import base64, zlib
    >>> blob = base64.b64encode(zlib.compress(("def f(x):\\n    return x\\n" * 400).encode(), 0)).decode()
    >>> nb = {"cells": [{"cell_type": "code", "source": f"import zlib, base64\\nexec(zlib.decompress(base64."
    ...                  f"b64decode('{blob}')))", "metadata": {}, "outputs": []}]}
    >>> notes, found = payloads(nb)
    >>> notes[0]
    'cell 0 source: 12284 base64 characters holding a zlib stream of Python source'
    >>> notes[1], found[0][0]
    ('cell 0: calls b64decode, decompress, exec', 'cell 0 source, (decoded)')
    """
    notes: list[str] = []
    found: list[tuple[str, str]] = []
    seen: set[str] = set()
    cells = nb.get("cells", []) if isinstance(nb, dict) else []
    for i, cell in enumerate(cells if isinstance(cells, list) else []):
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        source = _text(cell.get("source", ""))
        if source.strip() in given:
            continue
        literals, names = _scan(source)
        for text in literals:
            squeezed = re.sub(r"\s+", "", text)
            if _B64.fullmatch(squeezed) or len(text) < MIN_LITERAL:
                continue
            seen.add(squeezed)
            notes.append(f"cell {i}: a string literal of {len(text)} characters")
            if _python(text):
                found.append((f"cell {i}, a string literal", text))
        calls = sorted(names & SUSPECT_CALLS)
        literal_runs = [re.sub(r"\s+", "", t) for t in literals]
        for run in (r for r in literal_runs if _B64.fullmatch(r)):
            seen.add(run)
            hit = _blob(f"cell {i} source", run)
            if hit is not None:
                notes.append(hit[0])
                found += hit[1]
        if calls:
            notes.append(f"cell {i}: calls {', '.join(calls)}")
        reaches = sorted((names | set(literals)) & REACHES)
        if reaches:
            notes.append(f"cell {i}: reaches into objects with {', '.join(reaches)} (read it: no tripwire sees this)")
    for where, text in notebook_strings(nb):
        for m in _B64.finditer(re.sub(r"\\n|\s+", "", text)):
            if m.group() in seen or any(m.group() in s for s in seen):
                continue
            seen.add(m.group())
            hit = _blob(where, m.group())
            if hit is not None:
                notes.append(hit[0])
                found += hit[1]
    return notes, found
