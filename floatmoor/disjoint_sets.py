"""Disjoint sets (union-find): which points or lines a mooring system joins into one group.

The case's checks (free points held by nothing), the grouping of lines solved together and the
DG system's groups of free points all ask the same question of a graph: which members are
connected. :class:`DisjointSets` answers it with path halving (Tarjan & van Leeuwen 1984), in
near-constant time per operation.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from typing import Generic, TypeVar

__all__ = ["DisjointSets"]

T = TypeVar("T", bound=Hashable)


class DisjointSets(Generic[T]):
    """A partition of ``members``, each alone at first, merged by :meth:`union`."""

    def __init__(self, members: Iterable[T]) -> None:
        self._parent: dict[T, T] = {m: m for m in members}

    def find(self, member: T) -> T:
        """The representative of ``member``'s set (the same for every member of it)."""
        parent = self._parent
        while parent[member] != member:
            parent[member] = parent[parent[member]]
            member = parent[member]
        return member

    def union(self, a: T, b: T) -> None:
        """Merge the sets of ``a`` and ``b``; ``b``'s representative represents both."""
        root_b = self.find(b)
        self._parent[self.find(a)] = root_b
