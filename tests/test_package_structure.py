"""The package's house rules, checked statically: imports run one way, modules stay small,
code cites pages rather than tracker numbers.

Imports (docs/development.md#1-package-layout-and-import-order): the project layers its code
one way (base -> case -> io -> models -> simulation -> campaigns/reports -> CLI), and no module
may, directly or through others, import itself. The import graph is read from the source with
:mod:`ast` (nothing is imported, so a circle that Python happens to survive today is found as
well). Circles:

* module-level imports (also inside ``try``/``if`` at module level) are the graph Python
  executes when a module is imported: it must have no cycle;
* imports inside functions (lazy imports, made to defer a heavy dependency such as capytaine
  or matplotlib) are dependencies too: the graph with them added must have no cycle either.
  A lazy import may defer a cost; it may not hide a circle;
* imports under ``if TYPE_CHECKING:`` couple modules too (an annotation names the other's
  class): the graph with every import must have no cycle either, so that such an import
  cannot hide a circle the other two graphs would show.

Direction (docs/development.md#1-package-layout-and-import-order): the layer table of that
section is the one declaration of the layers, lowest first (:func:`_layer_table` reads it); a
module may import modules of its own layer and of lower layers only. Every import counts here:
module-level, function-level and ``if TYPE_CHECKING:`` ones alike (an annotation that names a
higher layer's class still couples the lower layer to it). A module's layer is that of the most
specific pattern of the table it matches (:func:`_layer_of`).

An import of ``pkg.mod.name`` is an edge to ``pkg.mod`` (the module that defines ``name``),
or to the package ``pkg.mod`` when ``name`` is what its ``__init__`` re-exports. The implicit
import of a module's parent packages is not an edge (every package's ``__init__`` may import
its own children). ``importlib.import_module`` with a string (the top-level package's lazy
attributes) is not followed.

Size: a module over :data:`MAX_MODULE_LINES` lines must say why in its docstring, on a line
starting with ``Size:`` (e.g. ``Size: one numba kernel set that shares its private helpers;
split, the helpers would have to be public``).

Citations: code and tests cite docs pages and papers, never a numbered issue of a tracker the
reader of the code does not have (docs/development.md#8-citations-in-code): no line of a ``.py``
file under ``floatmoor/`` or ``tests/`` may match :data:`TRACKER_REFERENCE` (the word, one space,
an optional ``#``, a number). Data file names such as ``issue17_unchanged.json`` do not match.

Tests (docs/development.md#where-tests-live): ``tests/`` mirrors ``floatmoor/``; a ``.py`` file
sits at the top of ``tests/``, in a folder named in :data:`TEST_EXTRA_FOLDERS`, or in a folder
whose path is that of a package of ``floatmoor/`` (``tests/mooring/dg/`` for
``floatmoor/mooring/dg/``). The kind of a test is a marker, and every marker used is registered
in pyproject.toml, whose pytest options keep ``--strict-markers``.
"""

from __future__ import annotations

import ast
import re
import tomllib
from collections import deque
from collections.abc import Set
from functools import lru_cache
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "floatmoor"
#: The "about 600 lines" of docs/development.md: past it a module must give its reason.
MAX_MODULE_LINES = 600
#: The docstring line that gives that reason.
SIZE_REASON_PREFIX = "Size:"
#: Folders whose ``.py`` files must not cite tracker issue numbers.
CITATION_ROOTS = (PACKAGE, PACKAGE.parent / "tests")
#: A numbered tracker reference; built from pieces so that this file's source does not match.
TRACKER_REFERENCE = re.compile(r"\b[Ii]ssue" + r"s? #?\d+")


def _modules() -> dict[str, tuple[Path, bool]]:
    """Every module of the package: dotted name -> (file, is a package ``__init__``)."""
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        if is_package:
            parts = parts[:-1]
        found[".".join(parts)] = (path, is_package)
    return found


MODULES = _modules()


def _owner(name: str) -> str | None:
    """The package module a dotted import target lives in (None outside the package)."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def _targets(module: str, is_package: bool, node: ast.Import | ast.ImportFrom) -> list[str]:
    """The package modules one import statement of ``module`` reaches."""
    if isinstance(node, ast.Import):
        names = [alias.name for alias in node.names]
    else:
        if node.level:
            base = module.split(".")
            if not is_package:
                base = base[:-1]
            base = base[: len(base) - (node.level - 1)]
            source = ".".join(base + ([node.module] if node.module else []))
        else:
            source = node.module or ""
        names = [f"{source}.{alias.name}" if f"{source}.{alias.name}" in MODULES else source
                 for alias in node.names]
    owners = (_owner(name) for name in names)
    return [owner for owner in owners if owner is not None and owner != module]


def _is_type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


#: The kinds of import statement, as :func:`_import_statements` names them.
MODULE_LEVEL, FUNCTION_LEVEL, TYPE_CHECKING_ONLY = "module-level", "function-level", "TYPE_CHECKING"


def _import_statements(source: str, module: str, is_package: bool
                       ) -> list[tuple[str, str, int]]:
    """(imported package module, kind, line) of every import statement in the ``source`` of
    ``module``; kind is :data:`MODULE_LEVEL`, :data:`FUNCTION_LEVEL` or
    :data:`TYPE_CHECKING_ONLY` (under ``if TYPE_CHECKING:``, at any depth)."""
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
                         for target in _targets(module, is_package, child))
        inner = kind
        if kind == MODULE_LEVEL and isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef,
                                                       ast.Lambda)):
            inner = FUNCTION_LEVEL
        visit(child, inner)

    visit(ast.parse(source), MODULE_LEVEL)
    return found


def _imports_of(source: str, module: str, is_package: bool
                ) -> tuple[frozenset[str], frozenset[str]]:
    """(module-level, function-level) package imports in the ``source`` of ``module``
    (``TYPE_CHECKING`` ones left out)."""
    statements = _import_statements(source, module, is_package)
    top = {target for target, kind, _ in statements if kind == MODULE_LEVEL}
    lazy = {target for target, kind, _ in statements if kind == FUNCTION_LEVEL}
    return frozenset(top), frozenset(lazy - top)


@lru_cache(maxsize=None)
def _statements(module: str) -> tuple[tuple[str, str, int], ...]:
    path, is_package = MODULES[module]
    return tuple(_import_statements(path.read_text(encoding="utf-8"), module, is_package))


@lru_cache(maxsize=None)
def _imports(module: str) -> tuple[frozenset[str], frozenset[str]]:
    path, is_package = MODULES[module]
    return _imports_of(path.read_text(encoding="utf-8"), module, is_package)


def _graph(with_lazy: bool) -> dict[str, Set[str]]:
    graph = {}
    for module in MODULES:
        top, lazy = _imports(module)
        graph[module] = top | lazy if with_lazy else top
    return graph


def _components(graph: dict[str, Set[str]]) -> list[set[str]]:
    """The strongly connected components of ``graph`` with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[set[str]] = []

    def connect(node: str) -> None:  # recursion depth is bounded by the package's size
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in graph[node]:
            if target not in index:
                connect(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = set()
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.add(member)
                if member == node:
                    break
            if len(component) > 1:
                components.append(component)

    for node in sorted(graph):
        if node not in index:
            connect(node)
    return components


def _cycles(graph: dict[str, Set[str]]) -> list[list[str]]:
    """One shortest cycle through each strongly connected component of ``graph``."""
    return [_shortest_cycle(graph, component) for component in _components(graph)]


def _shortest_cycle(graph: dict[str, Set[str]], component: Set[str]) -> list[str]:
    """A shortest cycle through the first (sorted) member of a strongly connected component."""
    start = min(component)
    previous: dict[str, str] = {}
    queue = deque([start])
    while queue:
        node = queue.popleft()
        for target in sorted(graph[node] & component):
            if target == start:
                path = [node]
                while path[-1] != start:
                    path.append(previous[path[-1]])
                return [start, *reversed(path[:-1]), start]
            if target not in previous:
                previous[target] = node
                queue.append(target)
    raise AssertionError(f"{sorted(component)} is not strongly connected")


def _describe(graph: dict[str, Set[str]]) -> str:
    """Each circle as one shortest cycle, and every module caught in it."""
    return "\n".join(f"{' -> '.join(_shortest_cycle(graph, component))} (modules in this "
                     f"circle: {', '.join(sorted(component))})"
                     for component in _components(graph))


def test_cycle_finder_names_a_planted_circle() -> None:
    """The finder itself: a three-module circle beside a one-way chain is found, and only it."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set(), "e": {"d"}}
    assert _cycles(graph) == [["a", "b", "c", "a"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_relative_imports_resolve_to_package_modules() -> None:
    """``from . import x`` and ``from .x import y`` reach the modules they name."""
    node = ast.parse("from .state_space import x\nfrom . import database").body
    module = "floatmoor.hydro.radiation"
    assert _targets(module, False, node[0]) == ["floatmoor.hydro.state_space"]
    assert _targets(module, False, node[1]) == ["floatmoor.hydro.database"]


def test_module_level_imports_have_no_circle() -> None:
    graph = _graph(with_lazy=False)
    circles = _components(graph)
    assert not circles, "import circles among module-level imports:\n" + _describe(graph)


def test_imports_including_lazy_ones_run_one_way() -> None:
    graph = _graph(with_lazy=True)
    circles = _components(graph)
    assert not circles, ("import circles once the imports inside functions are counted:\n"
                         + _describe(graph))


def _graph_of_every_import() -> dict[str, Set[str]]:
    """Module-level, function-level and ``TYPE_CHECKING`` imports alike."""
    return {module: frozenset(target for target, _, _ in _statements(module)
                              if target in MODULES and target != module)
            for module in MODULES}


def test_imports_including_type_checking_ones_run_one_way() -> None:
    graph = _graph_of_every_import()
    circles = _components(graph)
    assert not circles, ("import circles once the TYPE_CHECKING imports are counted:\n"
                         + _describe(graph))


def test_every_import_graph_sees_a_type_checking_circle() -> None:
    """A circle closed only by a ``TYPE_CHECKING`` import (as one once hid in the simulation
    layer) is a circle of the graph of every import."""
    graph = {"a": frozenset({"b"}), "b": frozenset({"a"})}  # b -> a under TYPE_CHECKING
    assert _components(graph) == [{"a", "b"}]
    source = "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import floatmoor.errors\n"
    kinds = {kind for _, kind, _ in _import_statements(source, "floatmoor.case.schema", False)}
    assert kinds == {TYPE_CHECKING_ONLY}


#: The page whose section 1 table declares the layers.
DEVELOPMENT_PAGE = PACKAGE.parent / "docs" / "development.md"
#: The heading of that section.
LAYER_SECTION = "## 1. Package layout and import order"


def _layer_table(text: str) -> list[tuple[str, tuple[str, ...]]]:
    """(layer, path patterns) of each row of the layer table in :data:`LAYER_SECTION` of
    ``text``, lowest layer first: the patterns are the backquoted ``floatmoor/...`` paths of
    the row's second cell (a folder ends with ``/``; ``*`` matches within a name, ``**/`` any
    folders)."""
    section = text.split(LAYER_SECTION, 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("|")]
    layers = []
    for row in rows[2:]:  # after the header and its rule
        cells = [cell.strip() for cell in row.strip().strip("|").split("|")]
        layers.append((cells[0], tuple(re.findall(r"`(floatmoor/[^`]*)`", cells[1]))))
    return layers


def _pattern(pattern: str) -> re.Pattern[str]:
    """The regular expression of a layer-table path pattern (see :func:`_layer_table`)."""
    if pattern.endswith("/"):
        return re.compile(re.escape(pattern) + ".*")
    parts = {"**/": "(?:[^/]+/)*", "*": "[^/]*"}
    return re.compile("".join(parts.get(part, re.escape(part))
                              for part in re.split(r"(\*\*/|\*)", pattern)))


def _layer_of(path: str, layers: list[tuple[str, tuple[str, ...]]]) -> int:
    """Index in ``layers`` of the layer of the file ``path`` (``floatmoor/...``): that of the
    most specific pattern it matches (a file pattern before a folder, a longer folder before a
    shorter one). Raises AssertionError when no pattern, or patterns of two layers equally
    specific, match it."""
    matches = [((not pattern.endswith("/"), len(pattern) if pattern.endswith("/") else 0),
                index, pattern)
               for index, (_, patterns) in enumerate(layers) for pattern in patterns
               if _pattern(pattern).fullmatch(path)]
    assert matches, (f"{path} is in no layer of {DEVELOPMENT_PAGE.name}'s table: add it to "
                     "the row of its layer")
    best = max(key for key, _, _ in matches)
    found = {(index, pattern) for key, index, pattern in matches if key == best}
    assert len({index for index, _ in found}) == 1, (
        f"{path} matches patterns of several layers equally: "
        + ", ".join(f"{pattern} ({layers[index][0]})" for index, pattern in sorted(found)))
    return found.pop()[0]


def _upward_imports(layers: list[tuple[str, tuple[str, ...]]],
                    statements: dict[str, tuple[tuple[str, str, int], ...]],
                    paths: dict[str, str]) -> list[tuple[str, str, str]]:
    """(importer, imported, description) of each import, of any kind, from a lower layer to a
    higher one, one per (importer, imported) pair (its first statement)."""
    layer = {module: _layer_of(path, layers) for module, path in paths.items()}
    found: dict[tuple[str, str], str] = {}
    for module in sorted(statements):
        for target, kind, line in statements[module]:
            if layer[target] > layer[module] and (module, target) not in found:
                found[(module, target)] = (
                    f"{module} ({layers[layer[module]][0]}) imports {target} "
                    f"({layers[layer[target]][0]}): {paths[module]}:{line}, {kind}")
    return [(module, target, text) for (module, target), text in found.items()]


def _package_layers() -> list[tuple[str, tuple[str, ...]]]:
    return _layer_table(DEVELOPMENT_PAGE.read_text(encoding="utf-8"))


def _package_upward_imports() -> list[tuple[str, str, str]]:
    paths = {module: path.relative_to(PACKAGE.parent).as_posix()
             for module, (path, _) in MODULES.items()}
    return _upward_imports(_package_layers(), {module: _statements(module) for module in MODULES},
                           paths)


def test_layer_table_is_read_and_places_files() -> None:
    """The table reader and the pattern rules on a made-up page: rows lowest first, a file
    pattern before a folder, ``**/`` for any folders, no layer and a tie are errors."""
    page = (f"# Dev\n\n{LAYER_SECTION}\n\ntext\n\n"
            "| layer | packages | holds |\n| --- | --- | --- |\n"
            "| base | `floatmoor/errors.py`, `floatmoor/x.py` | errors |\n"
            "| models | `floatmoor/hydro/` (with `sub/`), `floatmoor/hydro/deep/` | models |\n"
            "| top | `floatmoor/**/cli.py` and `floatmoor/**/*_cli.py` | commands |\n"
            "| tie | `floatmoor/x.py` | wrong |\n\n## 2. Next\n\n| a | `floatmoor/no.py` |\n")
    layers = _layer_table(page)
    assert layers == [("base", ("floatmoor/errors.py", "floatmoor/x.py")),
                      ("models", ("floatmoor/hydro/", "floatmoor/hydro/deep/")),
                      ("top", ("floatmoor/**/cli.py", "floatmoor/**/*_cli.py")),
                      ("tie", ("floatmoor/x.py",))]
    assert _layer_of("floatmoor/errors.py", layers) == 0
    assert _layer_of("floatmoor/hydro/rao.py", layers) == 1
    assert _layer_of("floatmoor/hydro/deep/a.py", layers) == 1
    assert _layer_of("floatmoor/hydro/rao_cli.py", layers) == 2
    assert _layer_of("floatmoor/hydro/deep/cli.py", layers) == 2
    assert _layer_of("floatmoor/cli.py", layers) == 2
    for path, message in (("floatmoor/other.py", "in no layer"),
                          ("floatmoor/x.py", "several layers")):
        try:
            _layer_of(path, layers)
        except AssertionError as err:
            assert message in str(err)
        else:
            raise AssertionError(f"{path}: no error")


def test_direction_finder_names_a_planted_upward_import() -> None:
    """Downward and same-layer imports pass; an upward one is named with both layers, where
    and of which kind it is, whatever its kind (TYPE_CHECKING included)."""
    layers = [("base", ("floatmoor/errors.py",)), ("models", ("floatmoor/hydro/",)),
              ("reports", ("floatmoor/plots/",))]
    paths = {"floatmoor.errors": "floatmoor/errors.py", "floatmoor.hydro.a": "floatmoor/hydro/a.py",
             "floatmoor.hydro.b": "floatmoor/hydro/b.py",
             "floatmoor.plots.style": "floatmoor/plots/style.py"}
    statements = {"floatmoor.errors": (), "floatmoor.plots.style": (),
                  "floatmoor.hydro.a": (("floatmoor.errors", MODULE_LEVEL, 3),
                                        ("floatmoor.hydro.b", MODULE_LEVEL, 4)),
                  "floatmoor.hydro.b": ()}
    assert _upward_imports(layers, statements, paths) == []
    for kind in (MODULE_LEVEL, FUNCTION_LEVEL, TYPE_CHECKING_ONLY):
        planted = dict(statements, **{"floatmoor.hydro.b": (("floatmoor.plots.style", kind, 9),)})
        assert _upward_imports(layers, planted, paths) == [(
            "floatmoor.hydro.b", "floatmoor.plots.style",
            f"floatmoor.hydro.b (models) imports floatmoor.plots.style (reports): "
            f"floatmoor/hydro/b.py:9, {kind}")]


def test_type_checking_imports_are_read_for_the_direction() -> None:
    """``if TYPE_CHECKING:`` imports (also inside a function) are statements of their kind;
    the ``else`` branch runs and is not."""
    source = ("from floatmoor.errors import CaseError\n"
              "if TYPE_CHECKING:\n    from floatmoor.case.schema import Case\n"
              "else:\n    import floatmoor.io.netcdf\n"
              "def f():\n    from floatmoor.hydro import radiation\n"
              "    if TYPE_CHECKING:\n        from floatmoor.plots import style\n")
    assert _import_statements(source, "floatmoor.made_up", False) == [
        ("floatmoor.errors", MODULE_LEVEL, 1), ("floatmoor.case.schema", TYPE_CHECKING_ONLY, 3),
        ("floatmoor.io.netcdf", MODULE_LEVEL, 5), ("floatmoor.hydro.radiation", FUNCTION_LEVEL, 7),
        ("floatmoor.plots.style", TYPE_CHECKING_ONLY, 9)]


def test_every_module_is_in_one_layer() -> None:
    """Each module of the package falls in exactly one row of the layer table."""
    layers = _package_layers()
    assert len(layers) >= 2 and all(patterns for _, patterns in layers), layers
    for path, _ in MODULES.values():
        _layer_of(path.relative_to(PACKAGE.parent).as_posix(), layers)


def test_imports_run_down_the_layers() -> None:
    """No module imports a module of a higher layer, by any kind of import
    (docs/development.md#1-package-layout-and-import-order); none is excused."""
    upward = [text for module, target, text in _package_upward_imports()]
    assert not upward, ("imports from a lower layer to a higher one (move the code to the layer "
                        "it belongs to, or pass the higher layer's answer in):\n"
                        + "\n".join(upward))


def _size_problem(name: str, text: str) -> str | None:
    """Why the module ``name`` with source ``text`` breaks the size rule, or None."""
    lines = len(text.splitlines())
    if lines <= MAX_MODULE_LINES:
        return None
    docstring = ast.get_docstring(ast.parse(text)) or ""
    if any(line.strip().startswith(SIZE_REASON_PREFIX) for line in docstring.splitlines()):
        return None
    return (f"{name} has {lines} lines (over {MAX_MODULE_LINES}) and its docstring has no "
            f"line starting {SIZE_REASON_PREFIX!r} saying why")


def test_import_kinds_are_told_apart() -> None:
    """Module-level, function-level and TYPE_CHECKING-only imports of a made-up module."""
    source = ("from floatmoor.errors import CaseError\n"
              "if TYPE_CHECKING:\n    from floatmoor.case.schema import Case\n"
              "def f():\n    from floatmoor.hydro import radiation\n    import floatmoor.cli\n")
    top, lazy = _imports_of(source, "floatmoor.made_up", False)
    assert top == {"floatmoor.errors"}
    assert lazy == {"floatmoor.hydro.radiation", "floatmoor.cli"}


def test_size_rule_wants_a_reason_past_the_limit() -> None:
    body = "x = 1\n" * MAX_MODULE_LINES
    assert _size_problem("short", '"""Short."""\n' + "x = 1\n" * (MAX_MODULE_LINES - 1)) is None
    assert "601 lines" in _size_problem("long", '"""Long."""\n' + body)
    assert _size_problem("long", f'"""Long.\n\n{SIZE_REASON_PREFIX} one kernel set."""\n'
                         + body) is None


def test_every_long_module_says_why() -> None:
    problems = [_size_problem(str(path.relative_to(PACKAGE.parent)),
                              path.read_text(encoding="utf-8"))
                for path, _ in MODULES.values()]
    problems = [p for p in problems if p is not None]
    assert not problems, ("split these modules by what they hold, or say why not:\n"
                          + "\n".join(problems))


def _tracker_references(name: str, text: str) -> list[str]:
    """``name:line: text`` of every line of ``text`` that cites a numbered tracker issue."""
    return [f"{name}:{number}: {line.strip()}"
            for number, line in enumerate(text.splitlines(), start=1)
            if TRACKER_REFERENCE.search(line)]


def test_tracker_reference_pattern() -> None:
    """The pattern flags the word with a number after a space or ``#``, not data file names."""
    word = "Issue"
    planted = (f"# {word} 17: 1 %\n"
               f"x = 1  # see {word.lower()}s 6 and 7\n"
               f'"""Fixed ({word.lower()} #5)."""\n'
               f"BASELINE = '{word.lower()}17_unchanged.json'\n"
               f"# the {word.lower()}'s targets\n")
    assert _tracker_references("planted.py", planted) == [
        f"planted.py:1: # {word} 17: 1 %",
        f"planted.py:2: x = 1  # see {word.lower()}s 6 and 7",
        f'planted.py:3: """Fixed ({word.lower()} #5)."""']


def test_code_cites_no_tracker_issue_numbers() -> None:
    """Comments, docstrings and messages say what they mean or cite a docs page instead."""
    problems = []
    for root in CITATION_ROOTS:
        for path in sorted(root.rglob("*.py")):
            problems += _tracker_references(str(path.relative_to(PACKAGE.parent)),
                                            path.read_text(encoding="utf-8"))
    assert not problems, ("cite the docs page (with its anchor) or paper that holds the "
                          "decision, not the tracker's issue number:\n" + "\n".join(problems))


#: The package of the commands, their progress display and their printing: the only code that
#: may print (docs/development.md#1-package-layout-and-import-order).
PRINTING_PACKAGE = PACKAGE / "cli"


def _printing(name: str, text: str) -> list[str]:
    """``name:line: what`` of every ``print(`` call and every use of ``sys.stdout`` or
    ``sys.stderr`` in the source ``text`` (read with :mod:`ast`: text in strings and comments
    does not count)."""
    found = []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                and node.func.id == "print":
            found.append((node.lineno, "print(...)"))
        elif isinstance(node, ast.Attribute) and node.attr in ("stdout", "stderr") \
                and isinstance(node.value, ast.Name) and node.value.id == "sys":
            found.append((node.lineno, f"sys.{node.attr}"))
        elif isinstance(node, ast.ImportFrom) and node.module == "sys" \
                and any(alias.name in ("stdout", "stderr") for alias in node.names):
            found.append((node.lineno, "from sys import ..."))
    return [f"{name}:{line}: {what}" for line, what in sorted(found)]


def test_printing_finder_names_planted_prints() -> None:
    planted = ("import sys\n"
               "from sys import stderr\n"
               "def f(x):\n"
               "    print(x)\n"
               "    sys.stderr.write('print(x)')  # print(x)\n"
               "    return sys.stdout\n"
               "    self.print(x)\n")
    assert _printing("planted.py", planted) == [
        "planted.py:2: from sys import ...", "planted.py:4: print(...)",
        "planted.py:5: sys.stderr", "planted.py:6: sys.stdout"]


def test_only_the_command_line_prints() -> None:
    """Library code returns values, takes a ``progress`` callback or warns (a
    :class:`floatmoor.errors.FloatmoorWarning`); :mod:`floatmoor.cli` prints."""
    problems = []
    for path, _ in MODULES.values():
        if PRINTING_PACKAGE in path.parents:
            continue
        problems += _printing(str(path.relative_to(PACKAGE.parent)),
                              path.read_text(encoding="utf-8"))
    assert not problems, ("library code must not print: return the text, take a progress "
                          "callback or warn, and let floatmoor/cli/ print it:\n"
                          + "\n".join(problems))


def test_nothing_below_the_command_line_imports_it() -> None:
    """The command line is the top layer: only its own modules and ``python -m floatmoor``
    (floatmoor/__main__.py, the program's entry) import :mod:`floatmoor.cli`."""
    entry = {"floatmoor.cli", "floatmoor.__main__"}
    upward = []
    for module in MODULES:
        if module in entry or module.startswith("floatmoor.cli."):
            continue
        top, lazy = _imports(module)
        cli = sorted(target for target in top | lazy
                     if target == "floatmoor.cli" or target.startswith("floatmoor.cli."))
        if cli:
            upward.append(f"{module} imports {', '.join(cli)}")
    assert not upward, "the command line is imported from below:\n" + "\n".join(upward)


TESTS = PACKAGE.parent / "tests"
#: Folders of tests/ that mirror no package: data files, the NumPy oracles of the kernels, and
#: the timings (not in the default run).
TEST_EXTRA_FOLDERS = frozenset({"data", "oracles", "benchmarks"})
#: pytest's own markers, which need no registration.
BUILTIN_MARKERS = frozenset({"parametrize", "skip", "skipif", "xfail", "usefixtures",
                             "filterwarnings"})
#: A marker applied in a test file: ``pytest.mark.<name>``.
MARKER_USE = re.compile(r"\bpytest\.mark\.([A-Za-z_]\w*)")


def _misplaced_tests(tests: Path, package: Path) -> list[str]:
    """The ``.py`` files under ``tests`` in a folder that is neither the top, an extra folder
    nor the mirror of a package (a folder with an ``__init__.py``) under ``package``."""
    misplaced = []
    for path in sorted(tests.rglob("*.py")):
        folder = path.relative_to(tests).parent.parts
        if "__pycache__" in folder or not folder or folder[0] in TEST_EXTRA_FOLDERS:
            continue
        if not package.joinpath(*folder, "__init__.py").is_file():
            misplaced.append(path.relative_to(tests).as_posix())
    return misplaced


def test_misplaced_test_finder_names_planted_files(tmp_path: Path) -> None:
    package, tests = tmp_path / "pkg", tmp_path / "tests"
    for folder in (package, package / "sub", package / "sub" / "inner", package / "loose"):
        folder.mkdir(parents=True, exist_ok=True)
    for folder in (package, package / "sub", package / "sub" / "inner"):
        (folder / "__init__.py").write_text("")
    placed = ["test_top.py", "sub/test_a.py", "sub/inner/test_b.py", "oracles/x_numpy.py",
              "data/bad_cases/make.py", "benchmarks/test_bench.py"]
    planted = ["unit/test_c.py", "loose/test_d.py", "sub/verification/test_e.py",
               "inner/test_f.py"]
    for name in placed + planted:
        (tests / name).parent.mkdir(parents=True, exist_ok=True)
        (tests / name).write_text("")
    assert _misplaced_tests(tests, package) == sorted(planted)


def test_tests_mirror_the_package() -> None:
    """A test of ``floatmoor/<pkg>/<module>.py`` lives in ``tests/<pkg>/``: a folder of tests/
    that mirrors no package (a folder by kind, such as the old ``tests/unit/``) is refused."""
    misplaced = _misplaced_tests(TESTS, PACKAGE)
    assert not misplaced, ("test files in folders that mirror no package of floatmoor/ (move "
                           "them beside the package they test: "
                           "docs/development.md#where-tests-live):\n" + "\n".join(misplaced))


def test_markers_are_strict_and_registered() -> None:
    """pytest refuses an unregistered marker (``--strict-markers``), and every marker the tests
    use is registered in pyproject.toml, the kinds (verification, validation, peer, oracle)
    among them."""
    options = tomllib.loads((PACKAGE.parent / "pyproject.toml").read_text())
    options = options["tool"]["pytest"]["ini_options"]
    assert "--strict-markers" in options["addopts"]
    registered = {line.split(":", 1)[0].strip() for line in options["markers"]}
    assert {"slow", "benchmark", "verification", "validation", "peer", "oracle"} <= registered
    used = {name for path in TESTS.rglob("*.py") if "__pycache__" not in path.parts
            for name in MARKER_USE.findall(path.read_text(encoding="utf-8"))}
    assert used - BUILTIN_MARKERS - registered == set()
