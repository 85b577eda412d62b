"""Fingerprints of Python code that survive renaming and reformatting (MOSS-style winnowing).

Code is read with Python's own :mod:`tokenize` and normalised (:func:`tokens`): every name becomes
``N`` (keywords stay), every number ``0``, every string ``S``; comments, blank lines and indentation
are dropped and a statement's end is ``;``. So renamed variables, other spacing, comments and line breaks
are invisible, while the shape of the code stays. Runs of :data:`K` tokens are hashed (a deterministic
rolling hash, so a figure never depends on the process or the machine) and the hashes are *winnowed*
(Schleimer, Wilkerson and Aiken, SIGMOD 2003: the minimum of every window of :data:`WINDOW` hashes is
kept) with ``copydetect``'s implementation, the one its ``CodeFingerprint`` uses: any run of at least
``K + WINDOW - 1`` tokens shared by two codes is found. ``copydetect`` (PyPI, MIT) is imported only when
a fingerprint is taken; its own ``CodeFingerprint`` hashes with Python's salted ``hash``, so its figures
would change from run to run, and it reads code with Pygments rather than Python's tokenizer.

:func:`similarity` is copydetect's figure: the share of one code's fingerprinted tokens that lie in
runs it shares with the other.
"""

from __future__ import annotations

import io
import keyword
import tokenize
import zlib
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

__all__ = ["K", "WINDOW", "Print", "tokens", "fingerprint", "similarity", "shared_tokens"]

#: Tokens per hashed run, and hashes per winnowing window: a shared run of K + WINDOW - 1 = 20 tokens
#: (about two lines of code) is always seen, a shared run shorter than K never.
K, WINDOW = 12, 9
_P1, _P2, _BASE = 67_108_859, 67_108_837, 1_000_003  # two primes under 2**26: a hash stays exact in a float
_DROP = {tokenize.COMMENT, tokenize.NL, tokenize.INDENT, tokenize.DEDENT, tokenize.ENCODING, tokenize.ENDMARKER}
_DROP |= {getattr(tokenize, n) for n in ("FSTRING_MIDDLE", "FSTRING_END") if hasattr(tokenize, n)}
_STRINGS = {tokenize.STRING} | {getattr(tokenize, n) for n in ("FSTRING_START",) if hasattr(tokenize, n)}


def _runnable(code: str) -> str:
    """``code`` without IPython's magics and shell escapes (``%time``, ``!pip``), which are not Python."""
    return "".join("\n" if line.lstrip().startswith(("%", "!")) else line for line in code.splitlines(True))


def tokens(code: str) -> list[str]:
    """The normalised tokens of ``code`` (what is left of a file that does not tokenize: the part before).

    >>> tokens("x = np.cos(a) + 2.5  # a comment")
    ['N', '=', 'N', '.', 'N', '(', 'N', ')', '+', '0']
    >>> tokens("total=f( b,\\n  'text')\\nreturn total") == tokens("y = g(c, \\"other\\")\\nreturn y")
    True
    """
    out: list[str] = []
    try:
        for tok in tokenize.generate_tokens(io.StringIO(_runnable(code)).readline):
            kind, text = tok.type, tok.string
            if kind in _DROP or kind == tokenize.ERRORTOKEN and not text.strip():
                continue
            if kind == tokenize.NAME:
                out.append(text if keyword.iskeyword(text) else "N")
            elif kind == tokenize.NUMBER:
                out.append("0")
            elif kind in _STRINGS:
                out.append("S")
            elif kind == tokenize.NEWLINE or text == ";":
                if out and out[-1] != ";":
                    out.append(";")
            else:
                out.append(text)
    except (tokenize.TokenError, SyntaxError):  # an unfinished bracket or a bad dedent: keep what was read
        pass
    while out and out[-1] == ";":
        out.pop()
    return out


@dataclass(frozen=True)
class Print:
    """The winnowed fingerprints of one code: ``where[h]`` are the token positions where run ``h`` starts."""

    length: int
    where: dict[int, list[int]] = field(default_factory=dict)

    @property
    def hashes(self) -> set[int]:
        return set(self.where)

    @property
    def coverage(self) -> int:
        """How many of the code's tokens lie in a fingerprinted run (copydetect's ``token_coverage``)."""
        return _covered(np.concatenate([np.asarray(v) for v in self.where.values()]) if self.where else np.array([]))


def _covered(starts: np.ndarray) -> int:
    if starts.size == 0:
        return 0
    return int(np.unique((starts.astype(np.int64)[:, None] + np.arange(K)[None, :]).ravel()).size)


def _run_hashes(toks: list[str]) -> np.ndarray:
    """The hash of every run of K tokens (two polynomial hashes mod primes under 2**26, combined)."""
    ids = np.array([zlib.crc32(t.encode()) for t in toks], dtype=np.int64)
    runs = np.lib.stride_tricks.sliding_window_view(ids, K)
    h1 = np.zeros(len(runs), dtype=np.int64)
    h2 = np.zeros(len(runs), dtype=np.int64)
    for j in range(K):
        h1 = (h1 * _BASE + runs[:, j]) % _P1
        h2 = (h2 * _BASE + runs[:, j]) % _P2
    return h1 * _P2 + h2


def fingerprint(toks: list[str], ignore: Iterable[int] = ()) -> Print:
    """The winnowed fingerprints of the normalised tokens ``toks``, leaving out the hashes in ``ignore``
    (the code the student was given).

    >>> a = fingerprint(tokens("def f(x):\\n    y = x * x + 1\\n    return [y, y - 1, y + 2, x / y]"))
    >>> b = fingerprint(tokens("def g(t):\\n    u = t*t + 1  # same\\n    return [u, u-1, u+2, t/u]"))
    >>> a.hashes == b.hashes and len(a.hashes) > 0
    True
    """
    from copydetect.utils import winnow  # the grader extra; needed only when a copy report is built

    if len(toks) < K:
        return Print(len(toks))
    hashes = _run_hashes(toks)
    chosen, idx = winnow(hashes, WINDOW, remove_duplicates=False)
    skip = set(ignore)
    where: dict[int, list[int]] = {}
    for h, i in zip(chosen.tolist(), idx.tolist(), strict=True):
        if h not in skip:
            where.setdefault(int(h), []).append(int(i))
    return Print(len(toks), where)


def shared_tokens(a: Print, common: Iterable[int]) -> int:
    """How many of ``a``'s tokens lie in runs whose hash is in ``common``."""
    starts = [i for h in common if h in a.where for i in a.where[h]]
    return _covered(np.asarray(starts, dtype=np.int64))


def similarity(a: Print, b: Print) -> tuple[float, int]:
    """The share of ``a``'s fingerprinted tokens in runs shared with ``b`` (0 to 1), and how many tokens that is.

    >>> a = fingerprint(tokens("s = 0\\nfor i in range(10):\\n    s = s + i * i\\n    print(s, i)"))
    >>> b = fingerprint(tokens("print('unrelated')"))
    >>> similarity(a, a)[0], similarity(a, b)
    (1.0, (0.0, 0))
    """
    cover = a.coverage
    if not cover:
        return 0.0, 0
    n = shared_tokens(a, a.hashes & b.hashes)
    return n / cover, n
