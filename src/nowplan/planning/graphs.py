"""Graph helpers of the automatic hierarchy (:mod:`nowplan.planning.abstraction`): a union-find over
literal classes and Tarjan's strongly connected components."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nowplan.planning.abstraction import LiteralClass


class UnionFind:
    def __init__(self, items: Iterable[LiteralClass]) -> None:
        self.parent = {c: c for c in items}

    def find(self, c: LiteralClass) -> LiteralClass:
        root = c
        while self.parent[root] != root:
            root = self.parent[root]
        while self.parent[c] != root:  # path compression, bounded by the path's length
            self.parent[c], c = root, self.parent[c]
        return root

    def union(self, a: LiteralClass, b: LiteralClass) -> None:
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            lo, hi = sorted((ra, rb))
            self.parent[hi] = lo  # the smallest class represents the group: deterministic


def sccs(nodes: list[LiteralClass], succ: Mapping[LiteralClass, set[LiteralClass]]) -> list[list[LiteralClass]]:
    """Tarjan's algorithm, iterative (no recursion limit), in a deterministic order."""
    index: dict[LiteralClass, int] = {}
    low: dict[LiteralClass, int] = {}
    on_stack: set[LiteralClass] = set()
    stack: list[LiteralClass] = []
    out: list[list[LiteralClass]] = []
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work: list[tuple[LiteralClass, Iterator[LiteralClass]]] = [(root, iter(sorted(succ[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(succ[w]))))
                    advanced = True
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp: list[LiteralClass] = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                out.append(sorted(comp))
    return out
