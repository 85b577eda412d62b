"""The package's folders are its layers (docs/architecture.md): these tests keep them so.

A lower layer never imports a higher one; no module grows past about 400 lines; there is one
angle-wrapping rule; ``import puma_course`` loads numpy only (tests/test_package.py).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from tests.support import ROOT

PKG = ROOT / "puma_course"
BASE = {"_validate", "_version", "transforms", "euler", "course", "hub", "extras"}
#: layer -> the layers it may import (besides itself)
ALLOWED = {
    "base": {"base"},
    "kinematics": {"base"},
    "symbolic": {"base", "kinematics"},
    "viz": {"base", "kinematics"},
    "grading": {"base", "kinematics"},
    "site": {"base"},  # it reads the course's files; it runs nothing of the course
    "instructor": {"base", "site", "grading"},  # the kit: slides, keys (with the written rubrics) (issue 25)
    "cli": {"base", "kinematics", "symbolic", "viz", "grading", "site", "instructor"},
    "package": {"base", "kinematics"},  # puma_course/__init__.py: the curated light re-export
}


def layer_of(parts: tuple[str, ...]) -> str:
    """The layer of a module given its path inside the package (('kinematics', 'dh') -> 'kinematics')."""
    if parts == ("__init__",):
        return "package"
    head = parts[0]
    if head in BASE:
        return "base"
    if head in ("kinematics", "symbolic", "viz", "grading", "site", "instructor", "cli"):
        return head
    raise AssertionError(f"module {'.'.join(parts)} is in no layer: add it to docs/architecture.md and here")


def modules() -> list[Path]:
    return sorted(p for p in PKG.rglob("*.py"))


def _parts(path: Path) -> tuple[str, ...]:
    rel = path.relative_to(PKG).with_suffix("")
    return tuple(rel.parts)


def imported_layers(path: Path, parts: tuple[str, ...] | None = None) -> set[str]:
    """The package layers a module imports (absolute ``puma_course.x`` or relative ``..x``).

    ``parts`` is the module's place in the package (default: from its path under ``puma_course/``).
    """
    parts = _parts(path) if parts is None else parts
    package = parts[:-1] if parts[-1] != "__init__" else parts[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        targets: list[tuple[str, ...]] = []
        if isinstance(node, ast.Import):
            targets = [tuple(a.name.split(".")) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)] if node.level > 1 else package
                mod = tuple(node.module.split(".")) if node.module else ()
                full = ("puma_course", *base, *mod)
                targets = [full] if mod else [(*full, a.name) for a in node.names]
            elif node.module:
                targets = [tuple(node.module.split(".")) + (a.name,) for a in node.names]
        for t in targets:
            if t and t[0] == "puma_course" and len(t) > 1:
                try:
                    out.add(layer_of(t[1:]))
                except AssertionError:
                    if t[1] not in {"__version__"}:  # a re-exported name, not a module
                        out.add(
                            layer_of((t[1],)) if (PKG / f"{t[1]}.py").exists() or (PKG / t[1]).is_dir() else "package"
                        )
    return out


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(PKG)))
def test_lower_layers_never_import_higher_ones(path):
    layer = layer_of(_parts(path))
    imported = imported_layers(path) - {layer, "package"}
    assert imported <= ALLOWED[layer], f"{path.relative_to(ROOT)} ({layer}) imports {sorted(imported - ALLOWED[layer])}"


def test_the_layer_test_would_catch_a_violation(tmp_path):
    """The rule above is not vacuous: a kinematics module importing viz is reported."""
    bad = tmp_path / "violation.py"
    bad.write_text("from ..viz import draw_robot\nfrom puma_course.grading import check\n", encoding="utf-8")
    assert imported_layers(bad, ("kinematics", "violation")) == {"viz", "grading"}


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(PKG)))
def test_no_module_over_about_400_lines(path):
    lines = len(path.read_text(encoding="utf-8").splitlines())
    assert lines <= 420, f"{path.relative_to(ROOT)} has {lines} lines: split it by job"


def _mod_of_pi(node: ast.AST) -> bool:
    """A ``x % (2 pi)``, ``np.mod(x, 2 pi)``, ``np.remainder`` or ``math.fmod`` by a multiple of π."""
    text = ast.unparse(node)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mod):
        return "pi" in ast.unparse(node.right).lower()
    if isinstance(node, ast.Call):
        name = ast.unparse(node.func)
        return name.split(".")[-1] in {"mod", "remainder", "fmod"} and "pi" in text.lower()
    return False


def test_one_angle_wrapping_implementation():
    """Only transforms.wrap_angle reduces angles modulo 2π; everything else calls it."""
    found = []
    for path in modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for fn in ast.walk(tree):
            if isinstance(fn, ast.FunctionDef):
                if any(_mod_of_pi(n) for n in ast.walk(fn)):
                    found.append(f"{path.relative_to(PKG)}:{fn.name}")
    assert found == ["transforms.py:wrap_angle"], found
