"""Copy only what is asked for out of the course package: one name, with what that name needs, and nothing else.

:func:`shake` takes requirements ``(module, name)`` (``name`` None: the whole module) and returns,
for every module of the package that ends up needed, the source of a reduced copy of it holding
just the top-level statements that define the required names and, transitively, the names those
statements use (found with :mod:`symtable`, Python's own scoping, so a function's local variable
never drags in a module-level name of the same spelling). Imports from outside the package
(numpy, math, typing) are kept as they are; imports from inside it become requirements in their turn
and are cut down to the names still used. A module used only as ``module.attr`` requires just
those attributes.

So a student-side copy of ``rodrigues`` holds ``rodrigues``, ``skew``, ``_angle`` and the input
checks they call, and not ``rotx``, ``axis_angle`` or ``inverse_transform`` from the same file.
Statements that define nothing (calls at module level) are dropped: package modules are
definitions only.
"""

from __future__ import annotations

import ast
import importlib.util
import symtable
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["shake", "module_file", "is_module"]

ROOT_PACKAGE = "puma_course"


def module_file(name: str) -> Path | None:
    """The source file of the package module ``name`` (None if there is no such module)."""
    if name != ROOT_PACKAGE and not name.startswith(ROOT_PACKAGE + "."):
        return None
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError, AttributeError):
        return None
    if spec is None or not spec.origin or not spec.origin.endswith(".py"):
        return None
    return Path(spec.origin)


def is_module(name: str) -> bool:
    """True if ``name`` is a module of the package."""
    return module_file(name) is not None


def _resolve_relative(module: str, is_package: bool, level: int, target: str | None) -> str:
    """The absolute name of ``from <level dots><target> import ...`` written in ``module``."""
    if level == 0:
        return target or ""
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[: len(base) - (level - 1)]
    return ".".join(base + ([target] if target else []))


@dataclass
class _Import:
    """A name bound by an import statement: from ``module`` (absolute), attribute ``attr`` (None: the module)."""

    module: str
    attr: str | None


@dataclass
class _Source:
    """One parsed package module: its statements, what each binds, and where each bound name comes from."""

    name: str
    is_package: bool
    tree: ast.Module
    table: symtable.SymbolTable
    future_annotations: bool
    binders: dict[str, list[int]] = field(default_factory=dict)
    imports: dict[str, _Import] = field(default_factory=dict)

    @classmethod
    def load(cls, name: str, absent: frozenset[str] = frozenset()) -> _Source:
        path = module_file(name)
        if path is None:
            raise ValueError(f"allowed: expected a module of {ROOT_PACKAGE}, got {name!r}")
        text = path.read_text(encoding="utf-8")
        tree = ast.parse(text, filename=str(path))
        if absent:
            stripped = _strip_members(name, path.name == "__init__.py", tree, absent)
            if stripped is not None:
                text, tree = stripped, ast.parse(stripped, filename=str(path))
        future = any(
            isinstance(s, ast.ImportFrom) and s.module == "__future__" and any(a.name == "annotations" for a in s.names)
            for s in tree.body
        )
        src = cls(name, path.name == "__init__.py", tree, symtable.symtable(text, str(path), "exec"), future)
        for index, stmt in enumerate(tree.body):
            for bound in _bound_names(stmt):
                src.binders.setdefault(bound, []).append(index)
            if isinstance(stmt, ast.ImportFrom) and stmt.module != "__future__":
                origin = _resolve_relative(name, src.is_package, stmt.level, stmt.module)
                for alias in stmt.names:
                    sub = f"{origin}.{alias.name}"
                    is_sub = origin.startswith(ROOT_PACKAGE) and is_module(sub)
                    bound = alias.asname or alias.name
                    src.imports[bound] = _Import(sub, None) if is_sub else _Import(origin, alias.name)
            elif isinstance(stmt, ast.Import):
                for alias in stmt.names:
                    if alias.asname:
                        src.imports[alias.asname] = _Import(alias.name, None)
                    else:
                        top = alias.name.split(".")[0]
                        src.imports[top] = _Import(top, None)
        return src

    def statement_needs(self, index: int) -> tuple[set[str], dict[str, set[str] | None]]:
        """(module-level names the statement uses, {name: attributes used as name.attr, or None if used bare})."""
        stmt = self.tree.body[index]
        names: set[str] = set()
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            for table in self.table.get_children():
                if table.get_name() == stmt.name and table.get_lineno() in _def_lines(stmt):
                    names |= _scope_globals(table)
            names |= _loaded(_evaluated_at_definition(stmt, self.future_annotations))
        elif not isinstance(stmt, (ast.Import, ast.ImportFrom)):
            names |= _loaded(_without_annotations(stmt) if self.future_annotations else [stmt])
        attrs: dict[str, set[str] | None] = {}
        for name in names:
            if name in self.imports and self.imports[name].attr is None:
                attrs[name] = _attributes_of(stmt, name)
        return names, attrs

    def nested_imports(self, index: int) -> list[tuple[str, str | None]]:
        """Package names imported inside a function or class body (imports deferred to call time)."""
        stmt = self.tree.body[index]
        if not isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            return []
        found: list[tuple[str, str | None]] = []
        for node in ast.walk(stmt):
            if isinstance(node, ast.ImportFrom):
                origin = _resolve_relative(self.name, self.is_package, node.level, node.module)
                if origin.split(".")[0] == ROOT_PACKAGE:
                    found += [(origin, a.name) for a in node.names]
            elif isinstance(node, ast.Import):
                found += [(a.name, None) for a in node.names if a.name.split(".")[0] == ROOT_PACKAGE]
        return found


#: Source of the stand-in for a class member an exercise does not give (``_ALLOWED_HERE`` comes from the
#: generated module's footer, defined once the module has run; ABCMeta reads the member before). It
#: holds nothing of the member: reading it raises AttributeError.
ABSENT_MEMBER = '''
class _AbsentMember:
    """A member of this class that this exercise does not give: reading it says so."""

    __slots__ = ("label",)

    def __set_name__(self, owner, name):
        self.label = owner.__name__ + "." + name

    def __get__(self, obj, owner=None):
        raise AttributeError(
            self.label + " is not available in this exercise: write it yourself "
            "(what this exercise lets you import from puma_course: " + str(globals().get("_ALLOWED_HERE")) + ")"
        )
'''


def _absent_globals(module: str, is_package: bool, tree: ast.Module, absent: frozenset[str]) -> set[str]:
    """Module-level names of ``module`` that are answers: defined here or imported from where they are."""
    names = {spec.partition(":")[2] for spec in absent if spec.partition(":")[0] == module}
    found = {n for n in names if "." not in n}
    for stmt in tree.body:
        if isinstance(stmt, ast.ImportFrom) and stmt.module != "__future__":
            origin = _resolve_relative(module, is_package, stmt.level, stmt.module)
            found |= {a.asname or a.name for a in stmt.names if f"{origin}:{a.name}" in absent}
    return found


def _member_refs(stmt: ast.stmt, class_name: str) -> tuple[set[str], set[str]]:
    """(global names a member reads, attributes it reads on ``self``, ``cls`` or its own class).

    A name the member binds itself (an argument, an assignment) is its own, not a global.
    """
    names, attrs, own = set(), set(), set()
    for node in ast.walk(stmt):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
            names.add(node.id)
        elif isinstance(node, ast.Name):
            own.add(node.id)
        elif isinstance(node, ast.arg):
            own.add(node.arg)
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            if node.value.id in ("self", "cls", class_name):
                attrs.add(node.attr)
    return names - own, attrs


def _strip_members(module: str, is_package: bool, tree: ast.Module, absent: frozenset[str]) -> str | None:
    """The module's source with the answer members of its classes replaced by :data:`ABSENT_MEMBER` (None: none).

    A class loses the members named in ``absent`` (``"module:Class.member"``), every member that reads a
    module-level answer (a name of ``absent``) or a removed member of its own class, and then the private
    members (``_name``) that removed members read and no remaining member does: what computes an answer
    is not there.
    """
    answers = _absent_globals(module, is_package, tree, absent)
    changed = False
    for stmt in tree.body:
        if not isinstance(stmt, ast.ClassDef):
            continue
        named = {spec.rpartition(".")[2] for spec in absent if spec.startswith(f"{module}:{stmt.name}.")}
        members = {m.name: m for m in stmt.body if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef))}
        refs = {n: _member_refs(m, stmt.name) for n, m in members.items()}
        drop = named & set(members)
        more = True
        while more:
            more = False
            for n, (names, attrs) in refs.items():
                if n not in drop and (names & answers or attrs & drop):
                    drop.add(n)
                    more = True
        if not drop:
            continue
        more = True
        while more:  # private helpers of removed members that no remaining member uses
            more = False
            used = set().union(*(refs[n][1] for n in members if n not in drop))
            helpers = set().union(*(refs[n][1] for n in drop if n in refs))
            for n in members:
                private = n.startswith("_") and not (n.startswith("__") and n.endswith("__"))
                if private and n in helpers and n not in drop and n not in used:
                    drop.add(n)
                    more = True
        body: list[ast.stmt] = []
        for m in stmt.body:
            if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)) and m.name in drop:
                body.append(ast.copy_location(ast.parse(f"{m.name} = _AbsentMember()").body[0], m))
            else:
                body.append(m)
        stmt.body = body
        changed = True
    if not changed:
        return None
    head = 0
    for head, first in enumerate([*tree.body, None]):
        future = isinstance(first, ast.ImportFrom) and first.module == "__future__"
        if not (future or (head == 0 and isinstance(first, ast.Expr))):
            break
    tree.body[head:head] = ast.parse(ABSENT_MEMBER).body
    return ast.unparse(ast.fix_missing_locations(tree))


def _bound_names(stmt: ast.stmt) -> list[str]:
    """The module-level names a top-level statement binds."""
    if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return [stmt.name]
    if isinstance(stmt, (ast.Import, ast.ImportFrom)):
        if isinstance(stmt, ast.ImportFrom) and stmt.module == "__future__":
            return []
        return [(a.asname or a.name).split(".")[0] for a in stmt.names]
    if isinstance(stmt, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
        targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
        return [n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)]
    if isinstance(stmt, (ast.If, ast.Try, ast.With, ast.For)):
        return [
            n.id
            for sub in ast.walk(stmt)
            if isinstance(sub, (ast.Assign, ast.AnnAssign))
            for t in (sub.targets if isinstance(sub, ast.Assign) else [sub.target])
            for n in ast.walk(t)
            if isinstance(n, ast.Name)
        ] + [s.name for s in ast.walk(stmt) if isinstance(s, (ast.FunctionDef, ast.ClassDef)) and s is not stmt]
    return []


def _def_lines(stmt: ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef) -> set[int]:
    return {stmt.lineno, *(d.lineno for d in stmt.decorator_list)}


def _scope_globals(table: symtable.SymbolTable) -> set[str]:
    """Module-level names used anywhere inside a function or class scope, nested scopes included."""
    found = {s.get_name() for s in table.get_symbols() if s.is_global() and s.is_referenced()}
    for child in table.get_children():
        found |= _scope_globals(child)
    return found


def _evaluated_at_definition(stmt: ast.AST, future_annotations: bool) -> list[ast.AST]:
    """The parts of a def or class evaluated in the module's scope.

    Decorators, defaults and bases; annotations too, unless they are postponed (``from __future__ import annotations``).
    """
    parts: list[ast.AST] = list(getattr(stmt, "decorator_list", []))
    if isinstance(stmt, ast.ClassDef):
        parts += [*stmt.bases, *stmt.keywords]
    elif isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef)):
        parts += [d for d in (*stmt.args.defaults, *stmt.args.kw_defaults) if d is not None]
        if not future_annotations:
            args = [*stmt.args.posonlyargs, *stmt.args.args, *stmt.args.kwonlyargs, stmt.args.vararg, stmt.args.kwarg]
            parts += [a.annotation for a in args if a is not None and a.annotation is not None]
            parts += [stmt.returns] if stmt.returns is not None else []
    return parts


def _without_annotations(stmt: ast.stmt) -> list[ast.AST]:
    if isinstance(stmt, ast.AnnAssign):
        return [stmt.target] + ([stmt.value] if stmt.value is not None else [])
    return [stmt]


def _loaded(nodes: list[ast.AST]) -> set[str]:
    return {n.id for node in nodes for n in ast.walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def _attributes_of(stmt: ast.stmt, name: str) -> set[str] | None:
    """The attributes read as ``name.attr`` in ``stmt``; None when ``name`` is also used otherwise."""
    attrs: set[str] = set()
    parents = {id(child): node for node in ast.walk(stmt) for child in ast.iter_child_nodes(node)}
    for node in ast.walk(stmt):
        if isinstance(node, ast.Name) and node.id == name and isinstance(node.ctx, ast.Load):
            parent = parents.get(id(node))
            if isinstance(parent, ast.Attribute) and parent.value is node:
                attrs.add(parent.attr)
            else:
                return None
    return attrs


def _reduced_import(stmt: ast.Import | ast.ImportFrom, keep: set[str]) -> ast.stmt | None:
    names = [a for a in stmt.names if (a.asname or a.name).split(".")[0] in keep]
    if not names:
        return None
    if isinstance(stmt, ast.ImportFrom):
        return ast.ImportFrom(module=stmt.module, names=names, level=stmt.level)
    return ast.Import(names=names)


def shake(requirements: set[tuple[str, str | None]], absent: frozenset[str] = frozenset()) -> dict[str, str]:
    """For each needed package module, the source of its reduced copy (see the module docstring).

    ``requirements`` are ``(module, name)`` pairs, ``name`` None for a whole module. ``absent`` names
    answers (``"module:name"``, ``"module:Class.member"``) to leave out: a class keeps its other members
    and says, for a missing one, that it is not available in this exercise (:func:`_strip_members`).
    Raises ValueError (naming ``allowed``) for a module or name the package does not have.
    """
    sources: dict[str, _Source] = {}
    kept: dict[str, set[int]] = {}
    imported_names: dict[str, set[str]] = {}
    todo = sorted(requirements, key=lambda r: (r[0], r[1] or ""))
    seen: set[tuple[str, str | None]] = set()
    while todo:
        module, name = todo.pop()
        if (module, name) in seen:
            continue
        seen.add((module, name))
        if module not in sources:
            sources[module] = _Source.load(module, absent)
            kept[module], imported_names[module] = set(), set()
            parent = module.rpartition(".")[0]
            if parent:
                todo.append((parent, "__package__"))  # the package must exist, with nothing more in it
        src = sources[module]
        if name == "__package__":
            continue
        if name is None:
            wanted = [n for n in src.binders if n != "__all__"]
        elif name in src.binders:
            wanted = [name]
        elif is_module(f"{module}.{name}"):
            todo.append((f"{module}.{name}", None))
            continue
        else:
            raise ValueError(f"allowed: expected a name defined in {module}, got {name!r}")
        for bound in wanted:
            todo += _need(src, bound, kept[module], imported_names[module])
    return {module: _render(sources[module], kept[module], imported_names[module]) for module in sources}


def _need(src: _Source, name: str, kept: set[int], imported: set[str]) -> list[tuple[str, str | None]]:
    """Keep the statements binding ``name`` in ``src``; return the requirements this adds elsewhere."""
    more: list[tuple[str, str | None]] = []
    if name in src.imports:
        imported.add(name)
        origin = src.imports[name]
        if origin.module.split(".")[0] == ROOT_PACKAGE:
            more.append((origin.module, origin.attr))
    for index in src.binders.get(name, []):
        if index in kept:
            continue
        kept.add(index)
        names, module_attrs = src.statement_needs(index)
        more += src.nested_imports(index)
        for used in sorted(names):
            if used in module_attrs and src.imports[used].module.split(".")[0] == ROOT_PACKAGE:
                imported.add(used)
                attrs = module_attrs[used]
                source_module = src.imports[used].module
                if attrs is None:
                    more.append((source_module, None))
                else:
                    more += [(source_module, "__package__")] + [(source_module, a) for a in sorted(attrs)]
            elif used in src.binders and used != name:
                more += _need(src, used, kept, imported)
    return more


def _render(src: _Source, kept: set[int], imported: set[str]) -> str:
    out: list[ast.stmt] = []
    if src.future_annotations:
        out.append(ast.ImportFrom(module="__future__", names=[ast.alias("annotations")], level=0))
    for index, stmt in enumerate(src.tree.body):
        if isinstance(stmt, (ast.Import, ast.ImportFrom)):
            if isinstance(stmt, ast.ImportFrom) and stmt.module == "__future__":
                continue
            reduced = _reduced_import(stmt, imported)
            if reduced is not None:
                out.append(reduced)
        elif index in kept:
            out.append(stmt)
    return ast.unparse(ast.fix_missing_locations(ast.Module(body=out, type_ignores=[])))
