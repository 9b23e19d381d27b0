"""Disjoint sets against connected components found by breadth-first search."""

from __future__ import annotations

from collections import deque

import numpy as np

from floatmoor.disjoint_sets import DisjointSets


def _components_by_search(n: int, edges: list[tuple[int, int]]) -> set[frozenset[int]]:
    neighbours: dict[int, set[int]] = {i: set() for i in range(n)}
    for a, b in edges:
        neighbours[a].add(b)
        neighbours[b].add(a)
    seen: set[int] = set()
    out = set()
    for start in range(n):
        if start in seen:
            continue
        component, queue = {start}, deque([start])
        while queue:
            for other in neighbours[queue.popleft()] - component:
                component.add(other)
                queue.append(other)
        seen |= component
        out.add(frozenset(component))
    return out


def test_sets_are_the_connected_components_of_random_graphs() -> None:
    rng = np.random.default_rng(19)
    for n, m in [(1, 0), (5, 0), (30, 12), (60, 45), (40, 200)]:
        edges = [(int(a), int(b)) for a, b in rng.integers(0, n, size=(m, 2))]
        sets = DisjointSets(range(n))
        for a, b in edges:
            sets.union(a, b)
        groups: dict[int, set[int]] = {}
        for i in range(n):
            groups.setdefault(sets.find(i), set()).add(i)
        assert {frozenset(g) for g in groups.values()} == _components_by_search(n, edges)


def test_union_keeps_the_second_sets_representative() -> None:
    sets = DisjointSets("abcd")
    sets.union("a", "b")
    sets.union("c", "a")
    assert sets.find("a") == sets.find("c") == "b"
    assert sets.find("d") == "d"
