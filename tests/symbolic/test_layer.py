"""The symbolic layer keeps its promises: printed data derives nothing, kinematics enters in one place at most."""

from __future__ import annotations

import ast
import re
from pathlib import Path

from tests.support import ROOT

PACKAGE = ROOT / "puma_course" / "symbolic"
BASE = {"puma_course._validate", "puma_course.transforms", "puma_course.course"}
STDLIB_OK = {"__future__", "collections", "types", "typing", "re", "math", "dataclasses", "functools"}


def _imports(path: Path) -> set[str]:
    """Absolute names of the modules ``path`` imports (relative imports resolved)."""
    package = ".".join(path.relative_to(ROOT).with_suffix("").parts[:-1])
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")
            if node.level:
                base = base[: len(base) - node.level + 1]
                name = ".".join(base + ([node.module] if node.module else []))
            else:
                name = node.module or ""
            out.add(name)
            out.update(f"{name}.{a.name}" for a in node.names if f"{name}.{a.name}".startswith("puma_course."))
    # the doctests' imports count too: an example that builds a robot ties the module to its spelling
    for m in _DOCTEST_IMPORT.finditer(path.read_text()):
        if m.group(1) == "import":
            out.add(m.group(2))
        else:
            out.update(f"{m.group(2)}.{n.split(' as ')[0].strip()}" for n in m.group(3).split(","))
    return out


_DOCTEST_IMPORT = re.compile(r">>> (from|import) (puma_course[\w.]*)(?: import ([\w ,]+))?")


def _modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def test_printed_imports_only_sympy_and_the_notation():
    for path in sorted((PACKAGE / "printed").glob("*.py")):
        for name in _imports(path):
            top = name.split(".")[0]
            ok = (
                top in STDLIB_OK
                or top == "sympy"
                or name.startswith("puma_course.symbolic.notation")
                or name.startswith("puma_course.symbolic.printed")
            )
            assert ok, f"{path.relative_to(ROOT)} imports {name}: printed/ holds data, it derives and checks nothing"


def test_kinematics_enters_the_layer_in_one_module_at_most():
    outside = {}
    for path in _modules():
        names = {
            n
            for n in _imports(path)
            if n.startswith("puma_course") and not n.startswith("puma_course.symbolic") and n not in BASE
        }
        names.discard("puma_course")
        if names:
            outside[str(path.relative_to(ROOT))] = sorted(names)
    assert len(outside) <= 1, f"kinematics imported in several places: {outside}"


def test_modules_stay_small():
    for path in _modules():
        n = len(path.read_text().splitlines())
        assert n <= 400, f"{path.relative_to(ROOT)} has {n} lines"
