"""Read a package's import graph from its source (``ast``, nothing imported) and report two faults.

* **Private names taken across modules**: ``from .x import _y``, ``from puma_course import _version``,
  ``x._y`` on a name bound to an imported module of the package, or a private module (``_ops.py``)
  imported from outside the package that holds it. A module's private names are its own; a private
  module (``judge/judges/_poses.py``, ``_validate.py``) may be imported by the modules of the package
  that holds it and of that package's subpackages (``from .._validate import as_array``), but its
  underscore names may not, and only the package's own modules may take it by name
  (``from . import _poses``; ``from .. import _version`` in a subpackage is reported).
* **Import circles**: strongly connected components of the graph "module A imports module B",
  counting imports at module level and inside functions alike (a late import hides a circle, it
  does not remove it). Imports under ``if TYPE_CHECKING:`` are left out: they never run.

An import ``from pkg import name`` is an edge to ``pkg.name`` when that is a module, else to ``pkg``;
``import a.b`` is an edge to ``a.b``. Running a submodule also runs its package's ``__init__``, but
that is not counted as an edge (every package would otherwise be a circle with its submodules).

Why ``ast`` and not a library: grimp (pip-installable; import-linter is built on it) gives the
same module graph, but it records which module imports which (and the line as text), not the
*names* taken, so the private-name check would still be written here; the circle check is then
thirty lines of Tarjan. One standard-library reader for both keeps CI free of another dependency.

Used by tests/test_architecture.py on ``puma_course``; the functions take any package folder so the
tests can plant a violation in a small package under ``tmp_path`` and see it reported.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path


def is_private(name: str) -> bool:
    """``_x`` is private; ``__x__`` (``__version__``, ``__init__``) is not."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def package_modules(root: Path) -> dict[str, Path]:
    """Every module of the package in folder ``root``, by dotted name (``pkg.sub.mod``; ``pkg.sub`` for
    ``pkg/sub/__init__.py``)."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root.parent).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


@dataclass(frozen=True)
class Import:
    """One name or module a module imports from the package."""

    importer: str  #: dotted name of the importing module
    target: str  #: dotted name of the module imported (or imported from)
    name: str | None  #: the name taken from ``target`` by ``from target import name``; None for a module
    line: int
    statement: str  #: the import as written


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    """ids of the nodes under ``if TYPE_CHECKING:`` (or ``if typing.TYPE_CHECKING:``)."""
    out: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and ast.unparse(node.test).split(".")[-1] == "TYPE_CHECKING":
            for child in node.body:
                out.update(id(n) for n in ast.walk(child))
    return out


def _longest_module(dotted: str, known: dict[str, Path]) -> str | None:
    parts = dotted.split(".")
    for end in range(len(parts), 0, -1):
        if ".".join(parts[:end]) in known:
            return ".".join(parts[:end])
    return None


def imports_of(module: str, path: Path, known: dict[str, Path]) -> list[Import]:
    """The package modules and names ``module`` imports (anywhere in it, ``if TYPE_CHECKING:`` left out)."""
    top = next(iter(known)).split(".")[0]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skip = _type_checking_nodes(tree)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == top:
                    target = _longest_module(alias.name, known) or alias.name
                    out.append(Import(module, target, None, node.lineno, ast.unparse(node)))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                source = ".".join([*base, *(node.module.split(".") if node.module else [])])
            else:
                source = node.module or ""
            if source.split(".")[0] != top:
                continue
            for alias in node.names:
                sub = f"{source}.{alias.name}"
                if sub in known:  # from pkg import submodule
                    out.append(Import(module, sub, None, node.lineno, ast.unparse(node)))
                    if is_private(alias.name) and source != package:  # a private module by name, from afar
                        out.append(Import(module, source, alias.name, node.lineno, ast.unparse(node)))
                else:
                    target = _longest_module(source, known) or source
                    out.append(Import(module, target, alias.name, node.lineno, ast.unparse(node)))
    return out


def _private_module_outsider(imp: Import) -> bool:
    """A private module (``a._b`` or below it) imported from outside the package that holds it."""
    parts = imp.target.split(".")
    for i, part in enumerate(parts):
        if is_private(part):
            holder = ".".join(parts[:i])
            if not (imp.importer == holder or imp.importer.startswith(holder + ".")):
                return True
    return False


def _module_aliases(tree: ast.AST, module: str, imps: list[Import], known: dict[str, Path]) -> dict[str, str]:
    """Local name -> package module, for the names an ``import`` or ``from pkg import module`` binds."""
    top = module.split(".")[0]
    out = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == top:
                    if alias.asname:
                        out[alias.asname] = alias.name
                    else:
                        out[alias.name.split(".")[0]] = alias.name.split(".")[0]
    by_line = {(i.line, i.target.rpartition(".")[2]): i.target for i in imps if i.name is None}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            for alias in node.names:
                target = by_line.get((node.lineno, alias.name))
                if target in known:
                    out[alias.asname or alias.name] = target
    return out


def private_imports(root: Path) -> set[str]:
    """Every private name one module takes from another, as ``importer takes module._name``, and every
    private module imported from outside its package, as ``importer takes pkg._module``."""
    known = package_modules(root)
    found = set()
    for module, path in known.items():
        imps = imports_of(module, path, known)
        for imp in imps:
            if imp.name is not None and is_private(imp.name):
                found.add(f"{module} takes {imp.target}.{imp.name}")
            elif _private_module_outsider(imp):
                found.add(f"{module} takes {imp.target}")
        tree = ast.parse(path.read_text(encoding="utf-8"))
        aliases = _module_aliases(tree, module, imps, known)
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and is_private(node.attr):
                head = ast.unparse(node.value)
                first, _, rest = head.partition(".")
                if first in aliases:
                    owner = aliases[first] + (f".{rest}" if rest else "")
                    if owner in known and owner != module:
                        found.add(f"{module} takes {owner}.{node.attr}")
    return found


def import_graph(root: Path) -> dict[str, set[str]]:
    """module -> the package modules it imports (module level and in functions; not under TYPE_CHECKING)."""
    known = package_modules(root)
    graph: dict[str, set[str]] = {m: set() for m in known}
    for module, path in known.items():
        for imp in imports_of(module, path, known):
            if imp.target in known and imp.target != module:
                graph[module].add(imp.target)
    return graph


def strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's strongly connected components of more than one node, each sorted, in sorted order."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(out)


def import_circles(root: Path) -> set[str]:
    """Each import circle of the package as ``a <-> b <-> c`` (its modules sorted)."""
    return {" <-> ".join(c) for c in strongly_connected(import_graph(root))}


def missing_modules(files: list[Path], root: Path) -> set[str]:
    """Absolute imports of the package (``puma_course.x.y``) in ``files`` that name no module of it.

    ``from pkg.a import b`` needs ``pkg.a`` to be a module; ``import pkg.a.b`` needs ``pkg.a.b``.
    Names taken from a module (``b`` above) are not checked.
    """
    known = package_modules(root)
    top = root.name
    found = set()
    for path in files:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                names = [node.module]
            for name in names:
                if name.split(".")[0] == top and name not in known:
                    found.add(f"{path.name}:{node.lineno}: {name}")
    return found
