"""No import circles (docs/development.md#1-package-layout-and-import-order): no module of the
package may, directly or through others, import itself.

The import graph is read from the source (tests/package_source.py: nothing is imported, so a
circle that Python happens to survive today is found as well). Circles:

* module-level imports (also inside ``try``/``if`` at module level) are the graph Python
  executes when a module is imported: it must have no cycle;
* imports inside functions (lazy imports, made to defer a heavy dependency such as capytaine
  or matplotlib) are dependencies too: the graph with them added must have no cycle either.
  A lazy import may defer a cost; it may not hide a circle;
* imports under ``if TYPE_CHECKING:`` couple modules too (an annotation names the other's
  class): the graph with every import must have no cycle either, so that such an import
  cannot hide a circle the other two graphs would show.
"""

from __future__ import annotations

import ast
from collections import deque
from collections.abc import Set

from tests.package_source import (FUNCTION_LEVEL, MODULE_LEVEL, MODULES, TYPE_CHECKING_ONLY,
                                  import_statements, imports, split_by_kind, statements_of,
                                  targets)


def _graph(with_lazy: bool) -> dict[str, Set[str]]:
    graph = {}
    for module in MODULES:
        top, lazy = imports(module)
        graph[module] = top | lazy if with_lazy else top
    return graph


def _graph_of_every_import() -> dict[str, Set[str]]:
    """Module-level, function-level and ``TYPE_CHECKING`` imports alike."""
    return {module: frozenset(target for target, _, _ in statements_of(module)
                              if target in MODULES and target != module)
            for module in MODULES}


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
    assert targets(module, False, node[0]) == ["floatmoor.hydro.state_space"]
    assert targets(module, False, node[1]) == ["floatmoor.hydro.database"]


def test_module_level_imports_have_no_circle() -> None:
    graph = _graph(with_lazy=False)
    circles = _components(graph)
    assert not circles, "import circles among module-level imports:\n" + _describe(graph)


def test_imports_including_lazy_ones_run_one_way() -> None:
    graph = _graph(with_lazy=True)
    circles = _components(graph)
    assert not circles, ("import circles once the imports inside functions are counted:\n"
                         + _describe(graph))


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
    kinds = {kind for _, kind, _ in import_statements(source, "floatmoor.case.schema", False)}
    assert kinds == {TYPE_CHECKING_ONLY}


def test_import_kinds_are_told_apart() -> None:
    """Module-level, function-level and TYPE_CHECKING-only imports of a made-up module."""
    source = ("from floatmoor.errors import CaseError\n"
              "if TYPE_CHECKING:\n    from floatmoor.case.schema import Case\n"
              "def f():\n    from floatmoor.hydro import radiation\n    import floatmoor.cli\n")
    top, lazy = split_by_kind(import_statements(source, "floatmoor.made_up", False))
    assert top == {"floatmoor.errors"}
    assert lazy == {"floatmoor.hydro.radiation", "floatmoor.cli"}
    assert {kind for _, kind, _ in import_statements(source, "floatmoor.made_up", False)} == {
        MODULE_LEVEL, FUNCTION_LEVEL, TYPE_CHECKING_ONLY}
