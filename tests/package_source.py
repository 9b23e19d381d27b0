"""The package's source as the house-rule tests read it: its module files, each read and
parsed once, and the import statements in them.

The structure tests (tests/test_import_cycles.py, tests/test_import_layers.py,
tests/test_module_size.py, tests/test_printing.py) read the package without importing it, so
that a rule is checked on the code as written (a circle that Python happens to survive today
is found as well). Each module file is read once per test session (:func:`source`) and its
import statements found once (:func:`statements_of`), whichever test asks first; syntax trees
are not kept (those of the whole package, kept, cost more to hold than to remake).

An import of ``pkg.mod.name`` is an edge to ``pkg.mod`` (the module that defines ``name``),
or to the package ``pkg.mod`` when ``name`` is what its ``__init__`` re-exports. The implicit
import of a module's parent packages is not an edge (every package's ``__init__`` may import
its own children). ``importlib.import_module`` with a string (the top-level package's lazy
attributes) is not followed.
"""

from __future__ import annotations

import ast
from functools import lru_cache
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PACKAGE = REPO / "floatmoor"
TESTS = REPO / "tests"


def _modules() -> dict[str, tuple[Path, bool]]:
    """Every module of the package: dotted name -> (file, is a package ``__init__``)."""
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(REPO).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package:
            parts = parts[:-1]
        found[".".join(parts)] = (path, is_package)
    return found


#: Every module of the package: dotted name -> (file, is a package ``__init__``).
MODULES = _modules()


@lru_cache(maxsize=None)
def source(path: Path) -> str:
    """The text of a source file, read once."""
    return path.read_text(encoding="utf-8")


def tree(path: Path) -> ast.Module:
    """The syntax tree of a source file."""
    return ast.parse(source(path))


def relative(path: Path) -> str:
    """``path`` relative to the repository, as messages name files."""
    return path.relative_to(REPO).as_posix()


def _owner(name: str) -> str | None:
    """The package module a dotted import target lives in (None outside the package)."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def targets(module: str, is_package: bool, node: ast.Import | ast.ImportFrom) -> list[str]:
    """The package modules one import statement of ``module`` reaches."""
    if isinstance(node, ast.Import):
        names = [alias.name for alias in node.names]
    else:
        if node.level:
            base = module.split(".")
            if not is_package:
                base = base[:-1]
            base = base[: len(base) - (node.level - 1)]
            origin = ".".join(base + ([node.module] if node.module else []))
        else:
            origin = node.module or ""
        names = [f"{origin}.{alias.name}" if f"{origin}.{alias.name}" in MODULES else origin
                 for alias in node.names]
    owners = (_owner(name) for name in names)
    return [owner for owner in owners if owner is not None and owner != module]


def _is_type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


#: The kinds of import statement, as :func:`import_statements` names them.
MODULE_LEVEL, FUNCTION_LEVEL, TYPE_CHECKING_ONLY = "module-level", "function-level", "TYPE_CHECKING"


def import_statements(code: str | ast.Module, module: str, is_package: bool
                      ) -> list[tuple[str, str, int]]:
    """(imported package module, kind, line) of every import statement in the source (or
    syntax tree) ``code`` of ``module``; kind is :data:`MODULE_LEVEL`, :data:`FUNCTION_LEVEL`
    or :data:`TYPE_CHECKING_ONLY` (under ``if TYPE_CHECKING:``, at any depth)."""
    found: list[tuple[str, str, int]] = []

    def visit(node: ast.AST, kind: str) -> None:
        for child in ast.iter_child_nodes(node):
            if _is_type_checking(child):
                for statement in child.body:  # type: ignore[attr-defined]
                    visit_one(statement, TYPE_CHECKING_ONLY)
                for statement in child.orelse:  # type: ignore[attr-defined]
                    visit_one(statement, kind)
                continue
            visit_one(child, kind)

    def visit_one(child: ast.AST, kind: str) -> None:
        if isinstance(child, (ast.Import, ast.ImportFrom)):
            found.extend((target, kind, child.lineno)
                         for target in targets(module, is_package, child))
        inner = kind
        if kind == MODULE_LEVEL and isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef,
                                                       ast.Lambda)):
            inner = FUNCTION_LEVEL
        visit(child, inner)

    visit(ast.parse(code) if isinstance(code, str) else code, MODULE_LEVEL)
    return found


def split_by_kind(statements: list[tuple[str, str, int]] | tuple[tuple[str, str, int], ...]
                  ) -> tuple[frozenset[str], frozenset[str]]:
    """(module-level, function-level) imported modules of ``statements`` (``TYPE_CHECKING``
    ones left out; a module imported at both levels is a module-level import)."""
    top = {target for target, kind, _ in statements if kind == MODULE_LEVEL}
    lazy = {target for target, kind, _ in statements if kind == FUNCTION_LEVEL}
    return frozenset(top), frozenset(lazy - top)


@lru_cache(maxsize=None)
def statements_of(module: str) -> tuple[tuple[str, str, int], ...]:
    """:func:`import_statements` of the package module ``module``."""
    path, is_package = MODULES[module]
    return tuple(import_statements(tree(path), module, is_package))


def imports(module: str) -> tuple[frozenset[str], frozenset[str]]:
    """(module-level, function-level) package imports of the package module ``module``."""
    return split_by_kind(statements_of(module))
