"""The student-side ``puma_course``: what a graded notebook can import, and nothing more.

:func:`build` writes, for one exercise, a package folder that the grading worker puts first on
the student's ``sys.path`` (and, under the OS sandbox, is the only ``puma_course`` the student's
process can see at all). It holds:

* ``puma_course.grading`` with ``check`` and ``use_exercise`` as stubs, so the self-check cells of
  a notebook run while grading (they print one line and judge nothing);
* the names in :attr:`~puma_course.grading.Exercise.allowed` (``"module"`` for a whole module,
  ``"module:name"`` for one name), each copied with what it needs and nothing else
  (:mod:`.shake`), and re-exported wherever the real package re-exports it (an allowed
  ``puma_course.transforms:rodrigues`` is also ``from puma_course import rodrigues``);
* nothing else: importing any other part of the package fails with an ``ImportError`` saying it
  is not available in this exercise.

An allowed class holds its allowed members only: the exercise's answer keys that are members of it
(``Puma560.ik``) are not in the copy, nor what only they use; reading one raises AttributeError
saying it is not available in this exercise. Reference answers are never in it: the question bank
(``puma_course.grading``) is refused as an allowed name, and expected values are computed in the
grader's process only.
"""

from __future__ import annotations

import importlib
import keyword
import os
from collections.abc import Iterable
from pathlib import Path

from . import templates
from .shake import ROOT_PACKAGE, module_file, shake

__all__ = ["build", "requirements", "lock"]

_GRADING = f"{ROOT_PACKAGE}.grading"


def _parse(spec: object) -> tuple[str, str | None]:
    if not isinstance(spec, str) or spec.count(":") > 1:
        raise ValueError(f"allowed: expected 'module' or 'module:name' inside {ROOT_PACKAGE}, got {spec!r}")
    module, _, name = spec.partition(":")
    parts = module.split(".")
    if parts[0] != ROOT_PACKAGE or not all(p.isidentifier() and not keyword.iskeyword(p) for p in parts):
        raise ValueError(f"allowed: expected 'module' or 'module:name' inside {ROOT_PACKAGE}, got {spec!r}")
    if module == _GRADING or module.startswith(_GRADING + "."):
        raise ValueError(
            f"allowed: the grading package holds the answer key and is never given to the student, got {spec!r}"
        )
    if name and not (name.isidentifier() and not keyword.iskeyword(name)):
        raise ValueError(f"allowed: expected a name after ':' in {spec!r}")
    if module_file(module) is None:
        raise ValueError(f"allowed: expected a module of {ROOT_PACKAGE}, got {module!r} in {spec!r}")
    return module, (name or None)


def requirements(allowed: Iterable[str]) -> set[tuple[str, str | None]]:
    """The ``(module, name)`` pairs to copy for ``allowed``, re-exports in parent packages included.

    >>> sorted(requirements(["puma_course.transforms:rodrigues"]))
    [('puma_course', 'rodrigues'), ('puma_course.transforms', 'rodrigues')]
    """
    out: set[tuple[str, str | None]] = set()
    for spec in allowed:
        module, name = _parse(spec)
        out.add((module, name))
        if name is None:
            continue
        try:
            obj = getattr(importlib.import_module(module), name)
        except AttributeError:
            raise ValueError(f"allowed: {module} has no {name!r} (in {spec!r})") from None
        parts = module.split(".")
        for k in range(1, len(parts)):
            parent = ".".join(parts[:k])
            if parent != _GRADING and getattr(importlib.import_module(parent), name, None) is obj:
                out.add((parent, name))
    return out


def _target(folder: Path, module: str) -> Path:
    real = module_file(module)
    rel = Path(*module.split("."))
    return folder / rel / "__init__.py" if real is not None and real.name == "__init__.py" else folder / f"{rel}.py"


def build(
    exercise_name: str, allowed: Iterable[str], folder: str | os.PathLike[str], answers: Iterable[str] = ()
) -> Path:
    """Write the student-side package for an exercise into ``folder`` (created); return ``folder``.

    ``folder`` is what goes first on the student's ``sys.path``: it holds ``puma_course/``.
    ``answers`` are the exercise's answer keys (:attr:`~puma_course.grading.Exercise.answer_keys`):
    those not named in ``allowed`` are left out of the copy, class members included (an allowed
    ``Puma560`` keeps ``fk``, ``frames``, ``points``, its named configurations, but has no ``ik``,
    no ``ik_batch`` and none of the private helpers that compute them).
    """
    allowed = tuple(allowed)
    folder = Path(folder)
    sources = shake(requirements(allowed), frozenset(answers) - set(allowed))
    sources.setdefault(ROOT_PACKAGE, "")
    footer = templates.MODULE_FOOTER.format(allowed=templates.message(allowed))
    for module, body in sources.items():
        path = _target(folder, module)
        path.parent.mkdir(parents=True, exist_ok=True)
        text = templates.HEADER.format(module=module, exercise=exercise_name) + body + "\n" + footer
        if module == ROOT_PACKAGE:
            text += templates.PACKAGE_FOOTER
        path.write_text(text, encoding="utf-8")
    grading = folder / ROOT_PACKAGE / "grading" / "__init__.py"
    grading.parent.mkdir(parents=True, exist_ok=True)
    grading.write_text(templates.GRADING_STUB + footer, encoding="utf-8")
    return folder


def lock(folder: str | os.PathLike[str], writable: bool = False) -> None:
    """Make every file under ``folder`` read-only (or, with ``writable``, writable again, to delete it)."""
    for root, dirs, files in os.walk(folder):
        for name in files:
            os.chmod(os.path.join(root, name), 0o644 if writable else 0o444)
        for name in dirs:
            os.chmod(os.path.join(root, name), 0o755 if writable else 0o555)
    os.chmod(folder, 0o755 if writable else 0o555)
