"""The instructor's grading secret: every student's hidden inputs come from it, and only the instructor holds it.

A :class:`Secret` is 32 random bytes kept in a key file of the course folder (``.grading-secret``,
created on first use, readable by its owner only, listed in ``.gitignore`` and never copied into
anything a student gets). The hidden inputs of a question are drawn from a generator seeded with
HMAC-SHA256 of (student, exercise, question) under the secret, so

* no two students share a hidden input, and no student can compute another's (or their own) without the key;
* regrading with the same key gives every student the same inputs again, so the same grades.

What leaves the grader's process names the key without revealing it: the CSV keeps its
:attr:`~Secret.fingerprint` (which key graded) and each notebook's :meth:`~Secret.run_id`; the
feedback shows the run id only. Both are HMAC or SHA-256 outputs under labels of their own: neither
gives the key nor any seed.

A public integer seed (``grade(seed=N)``, ``--seed N``) still works for demonstrations and tests:
it stands for the key ``puma-course public seed N``, so the cases still differ per student, but
anyone who knows N can rebuild them.
"""

from __future__ import annotations

import hashlib
import hmac
import os
import secrets
import stat
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Secret", "SECRET_FILE", "load_secret", "from_seed", "one_off", "choose_key", "command_key"]

#: The key file's name in the course folder.
SECRET_FILE = ".grading-secret"
_BYTES = 32


@dataclass(frozen=True)
class Secret:
    """A grading key (see the module docstring). ``seed`` is set when the key stands for a public seed."""

    key: bytes = field(repr=False)
    source: str = ""
    seed: int | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.key, bytes) or len(self.key) < 16:
            raise ValueError(f"secret: expected at least 16 bytes of key, got {type(self.key).__name__}")

    def _mac(self, *parts: str) -> bytes:
        return hmac.new(self.key, "\0".join(parts).encode("utf-8"), hashlib.sha256).digest()

    @property
    def fingerprint(self) -> str:
        """16 hex digits naming the key (which key graded a CSV), from which the key cannot be recovered.

        >>> from_seed(7).fingerprint == from_seed(7).fingerprint != from_seed(8).fingerprint
        True
        """
        return hashlib.sha256(b"puma-course grading secret fingerprint\0" + self.key).hexdigest()[:16]

    def case_seed(self, student: str, exercise: str, qid: str) -> int:
        """The seed of one question's hidden inputs for one student (256 bits; never printed anywhere)."""
        return int.from_bytes(self._mac("hidden cases", student, exercise, qid), "big")

    def run_id(self, student: str, exercise: str) -> str:
        """12 hex digits naming one student's hidden inputs of one exercise: shown in the feedback, kept in the CSV.

        It identifies the run (the same key, student and exercise give the same id) and reveals nothing
        that would rebuild the inputs.

        >>> s = from_seed(1)
        >>> len(s.run_id("ann", "ex01")), s.run_id("ann", "ex01") != s.run_id("bob", "ex01")
        (12, True)
        """
        return self._mac("run id", student, exercise).hex()[:12]


def from_seed(seed: int) -> Secret:
    """The key that a public integer seed stands for (demonstrations and tests: not a secret)."""
    if isinstance(seed, bool) or not isinstance(seed, int):
        raise ValueError(f"seed: expected a whole number, got {seed!r}")
    return Secret(f"puma-course public seed {seed}".encode().ljust(16, b"\0"), f"seed {seed}", seed)


def one_off() -> Secret:
    """A fresh key that is never saved: the hidden inputs of this run cannot be drawn again."""
    return Secret(secrets.token_bytes(_BYTES), "one-off")


def load_secret(path: str | os.PathLike[str], create: bool = True) -> Secret:
    """The key in the file ``path``; with ``create``, a new one written there first if the file does not exist.

    A new file is created with permissions 0600 (owner only) and holds 64 hex digits. ValueError
    (naming ``secret``) when the file is missing and ``create`` is False, or holds no key.
    """
    p = Path(path)
    if not p.exists():
        if not create:
            raise ValueError(f"secret: expected a key file, got {str(p)!r}, which does not exist")
        p.parent.mkdir(parents=True, exist_ok=True)
        # written whole to a temporary file, then linked into place: another run starting at the same moment (the
        # parts of a Slurm array) sees no file or the whole key, never an empty one; the first link wins
        tmp = p.with_name(f".{p.name}.{secrets.token_hex(8)}.tmp")
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            with os.fdopen(fd, "w", encoding="ascii") as fh:
                fh.write(secrets.token_hex(_BYTES) + "\n")
            try:
                os.link(tmp, p)
            except FileExistsError:  # another grading run created it meanwhile: use that one
                pass
        finally:
            tmp.unlink(missing_ok=True)
    if p.is_symlink() or not p.is_file():
        raise ValueError(f"secret: expected a regular key file, got {str(p)!r}")
    text = p.read_text(encoding="ascii", errors="replace").strip()
    try:
        key = bytes.fromhex(text)
    except ValueError:
        key = b""
    if len(key) < 16:
        raise ValueError(f"secret: expected at least 32 hex digits in {str(p)!r}, got {len(text)} characters")
    if os.name == "posix" and p.stat().st_mode & (stat.S_IRWXG | stat.S_IRWXO):
        os.chmod(p, 0o600)  # a key others can read is no secret: take their access away
    return Secret(key, str(p))


def choose_key(secret: Secret | str | os.PathLike[str] | None, seed: int | None) -> Secret:
    """A grading run's key: ``secret`` (a key, or its file, created there if absent), else the public
    ``seed``'s, else a one-off key. ValueError when both are given."""
    if secret is not None and seed is not None:
        raise ValueError(f"seed: expected either a secret or a seed, got both (seed {seed!r})")
    if isinstance(secret, Secret):
        return secret
    if secret is not None:
        return load_secret(secret)
    return one_off() if seed is None else from_seed(int(seed))


def command_key(secret: Path | None, seed: int | None, course: Path) -> tuple[Secret, str]:
    """``puma-course grade``'s key and the line it prints: ``--seed N``'s public key, else the key file
    (``--secret FILE``, else ``course/.grading-secret``, created on first use)."""
    if seed is not None:
        if secret is not None:
            raise ValueError(f"seed: expected either --secret FILE or --seed N, got both (--seed {seed})")
        return from_seed(seed), f"hidden inputs: from the public seed {seed} (anyone who knows it can rebuild them)"
    path = secret if secret is not None else course / SECRET_FILE
    new = not path.exists()
    key = load_secret(path)
    where = "created in" if new else "in"
    return key, (
        f"hidden inputs: each student's own, from the key {where} {path} (fingerprint {key.fingerprint}; "
        "keep this file: the same file regrades identically)"
    )
