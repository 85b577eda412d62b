"""The package's folders are its layers (docs/architecture.md): these tests keep them so.

A lower layer never imports a higher one; no module takes another's private names; no import
circle (tests/architecture.py reads the graph); there is one angle-wrapping rule; ``import
puma_course`` loads numpy only (tests/test_package.py).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from tests import architecture
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


#: the violations still to fix (empty: there are none; the tests below fail if one appears or if an entry here is
#: no longer a violation, so this set only ever shrinks)
KNOWN_PRIVATE: set[str] = set()
KNOWN_CIRCLES: set[str] = set()


def test_no_module_takes_another_modules_private_names():
    """A module's underscore names are its own: no ``from .x import _y``, no ``x._y``, no private module
    imported from outside the package that holds it (tests/architecture.py says exactly what counts)."""
    found = architecture.private_imports(PKG)
    assert sorted(found - KNOWN_PRIVATE) == [], "private names taken across modules: make them public or move them"
    assert sorted(KNOWN_PRIVATE - found) == [], "fixed: remove these from KNOWN_PRIVATE"


def test_no_import_circles():
    """No two modules import each other, directly or round a longer loop, at module level or inside a
    function (``if TYPE_CHECKING:`` imports excepted: they never run). Move what both sides share into a
    module both import; a late import only hides the circle."""
    found = architecture.import_circles(PKG)
    assert sorted(found - KNOWN_CIRCLES) == [], "import circles: move what both sides share into a third module"
    assert sorted(KNOWN_CIRCLES - found) == [], "fixed: remove these from KNOWN_CIRCLES"


def _plant(root: Path, files: dict[str, str]) -> Path:
    """A small package ``pkg`` under ``root`` with the given files (path -> source)."""
    for name, text in files.items():
        path = root / "pkg" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root / "pkg"


def test_the_private_name_check_would_catch_a_violation(tmp_path):
    """Each form is reported; a public name, a dunder, a private module used inside its own package and
    an underscore alias of a public name are not."""
    pkg = _plant(
        tmp_path,
        {
            "__init__.py": "from ._version import __version__\n",
            "_version.py": "__version__ = '1'\n",
            "a.py": "_y = 1\nz = 2\n",
            "sub/__init__.py": "",
            "sub/_helpers.py": "_h = 1\nh = 2\n",
            "sub/ok.py": "from ._helpers import h\nfrom . import _helpers\nfrom .. import __version__\n"
            "from ..a import z as _z\nimport html as _html\nfrom .._version import __version__ as v\n",
            "sub/bad.py": "from ..a import _y, z\nfrom ._helpers import _h\n",
            "far.py": "from .sub import _helpers\nfrom . import _version\n",  # _version: its own package's
            "sub/far.py": "from .. import _version\n",
            "far2.py": "from .sub._helpers import h\n",
            "attr1.py": "from . import a\n\n\ndef f():\n    return a._y + a.z\n",
            "attr2.py": "import pkg.a\n\nv = pkg.a._y\n",
            "attr3.py": "import pkg.a as alias\n\nv = alias._y\n",
        },
    )
    assert architecture.private_imports(pkg) == {
        "pkg.sub.bad takes pkg.a._y",
        "pkg.sub.bad takes pkg.sub._helpers._h",
        "pkg.far takes pkg.sub._helpers",  # a private module of another package
        "pkg.sub.far takes pkg._version",  # a private name of pkg, taken by name from a subpackage
        "pkg.far2 takes pkg.sub._helpers",
        "pkg.attr1 takes pkg.a._y",
        "pkg.attr2 takes pkg.a._y",
        "pkg.attr3 takes pkg.a._y",
    }


def test_the_circle_check_would_catch_a_violation(tmp_path):
    """A two-module circle closed by an import inside a function and a three-module loop are both
    reported; an ``if TYPE_CHECKING:`` import and a package importing its own submodules are not."""
    pkg = _plant(
        tmp_path,
        {
            "__init__.py": "from .a import f\nfrom .c import g\n",
            "a.py": "from .b import h\n\n\ndef f():\n    return h()\n",
            "b.py": "def h():\n    from . import a\n\n    return a\n",
            "c.py": "import pkg.d\n\ng = 1\n",
            "d.py": "from .e import x\n",
            "e.py": "from typing import TYPE_CHECKING\n\nfrom pkg import c\n\nif TYPE_CHECKING:\n"
            "    from . import a\nx = 1\n",
            "lone.py": "import typing\n\nif typing.TYPE_CHECKING:\n    from .quiet import x\n",
            "quiet.py": "from . import lone\n\nx = 1\n",
        },
    )
    assert architecture.import_circles(pkg) == {"pkg.a <-> pkg.b", "pkg.c <-> pkg.d <-> pkg.e"}


def test_every_module_named_in_an_import_exists():
    """No package or test file imports a ``puma_course`` module that is not there (left behind by a move)."""
    files = modules() + sorted((ROOT / "tests").rglob("*.py"))
    assert sorted(architecture.missing_modules(files, PKG)) == []


def test_the_missing_module_check_would_catch_one(tmp_path):
    pkg = _plant(tmp_path, {"__init__.py": "", "a.py": "x = 1\n"})
    user = tmp_path / "user.py"
    user.write_text("import pkg.a\nfrom pkg.a import x\nfrom pkg import a\nfrom pkg.gone import y\nimport pkg.b\n")
    assert architecture.missing_modules([user], pkg) == {"user.py:4: pkg.gone", "user.py:5: pkg.b"}


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
