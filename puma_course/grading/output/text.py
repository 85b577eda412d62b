"""Text that comes from a student, made safe to show: one line, short, quoted as code, no formula for a spreadsheet.

Everything a student controls and the grader repeats (error messages, type names, folder and
file names) passes through here: :func:`one_line` escapes control and invisible characters
(line breaks, terminal escapes, bidirectional overrides) and cuts the text short; :func:`quoted`
also wraps it in a Markdown code span that no backtick inside can close, so it renders as
literal text in the feedback, never as headings, tables, links or HTML. :func:`display_name`
turns any folder name (bytes that are not UTF-8 included) into a printable, bounded name, and
:func:`csv_safe` keeps a spreadsheet from reading a cell as a formula.
"""

from __future__ import annotations

import hashlib
import os
import re
import unicodedata

__all__ = ["one_line", "quoted", "display_name", "csv_safe", "file_stem", "plural"]

#: Characters that start a formula in spreadsheet programs (OWASP's list for CSV injection).
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "\n")


def plural(count: float, noun: str, nouns: str | None = None) -> str:
    """``count`` with its noun, singular for exactly one (``nouns``: the plural, default ``noun + "s"``).

    >>> plural(1, "point"), plural(0.5, "point"), plural(2, "answer"), plural(0, "file")
    ('1 point', '0.5 points', '2 answers', '0 files')
    """
    return f"{count:g} {noun if count == 1 else nouns or noun + 's'}"


def _escape_char(ch: str) -> str:
    code = ord(ch)
    if 0xDC80 <= code <= 0xDCFF:  # a byte that was not UTF-8 (surrogateescape)
        return f"\\x{code - 0xDC00:02x}"
    if unicodedata.category(ch) in ("Cc", "Cf", "Cs", "Co", "Cn", "Zl", "Zp"):
        return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"
    return ch


def one_line(text: object, limit: int = 200) -> str:
    """``text`` on one line: control, format and invisible characters escaped, at most ``limit`` characters.

    >>> one_line("a\\nb\\x1b[2J\\u202e"), one_line("x" * 10, limit=5)
    ('a\\\\x0ab\\\\x1b[2J\\\\u202e', 'xxxx…')
    """
    if not isinstance(text, str):
        text = str(text)
    text = text[: limit * 4]
    out = "".join(ch if ch.isprintable() or ch == " " else _escape_char(ch) for ch in text)
    return out if len(out) <= limit else out[: max(0, limit - 1)] + "…"


def quoted(text: object, limit: int = 200) -> str:
    """``text`` as a Markdown code span (one line, at most ``limit`` characters inside).

    The fence is one backtick longer than the longest run of backticks inside, so nothing in the
    text can end the span early.

    >>> quoted("x = 1"), quoted("a ` b"), quoted("`")
    ('`x = 1`', '`` a ` b ``', '`` ` ``')
    """
    inner = one_line(text, limit)
    runs = [len(m) for m in re.findall(r"`+", inner)]
    fence = "`" * (max(runs, default=0) + 1)
    if runs or inner.startswith(" ") or inner.endswith(" ") or not inner:
        inner = f" {inner} "
    return f"{fence}{inner}{fence}"


def display_name(name: str | bytes, limit: int = 80) -> str:
    """A folder or file name as the grader shows it: printable, one line, bounded (a hash keeps long ones apart).

    >>> display_name("Ann Lee"), display_name(b"caf\\xe9"), display_name("x" * 90)[-10:]
    ('Ann Lee', 'caf\\\\xe9', 'x…efdfd9ee')
    """
    raw = name if isinstance(name, bytes) else os.fsencode(name)
    text = raw.decode("utf-8", errors="surrogateescape")
    shown = "".join(ch if ch.isprintable() else _escape_char(ch) for ch in text)
    if len(shown) <= limit:
        return shown
    digest = hashlib.sha256(raw).hexdigest()[:8]
    return f"{shown[: limit - 10]}…{digest}"


def csv_safe(text: str) -> str:
    """A CSV cell a spreadsheet shows as text: a leading ``'`` when it would start a formula.

    >>> csv_safe("=HYPERLINK(1)"), csv_safe("ann"), csv_safe("-rf")
    ("'=HYPERLINK(1)", 'ann', "'-rf")
    """
    return "'" + text if text.startswith(_FORMULA_START) else text


def file_stem(name: str, limit: int = 100) -> str:
    """A file-name-safe stem for ``name`` (letters, digits, ``_.-``), bounded, never empty or hidden.

    >>> file_stem("../Ann Lee"), file_stem("-rf"), file_stem("***")
    ('Ann_Lee', 'rf', 'student')
    """
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._-") or "student"
    if len(stem) > limit:
        stem = stem[: limit - 9] + "_" + hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:8]
    return stem
