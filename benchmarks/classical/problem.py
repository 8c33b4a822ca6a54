"""Shared pieces of the problem generators: PDDL problem text and random graphs.

Everything here is deterministic for a given ``random.Random``: collections
are lists or dicts (never sets, whose string order changes between
processes), and every random choice goes through the generator passed in.
"""

from __future__ import annotations

import heapq
import random
from collections.abc import Iterable, Sequence

Edge = tuple[int, int]


def fact(*parts: str) -> str:
    """``fact("at", "a", "b")`` → ``"(at a b)"``."""
    return "(" + " ".join(parts) + ")"


def _wrap(items: Sequence[str], indent: str, width: int = 88) -> list[str]:
    lines: list[str] = []
    line = indent
    for it in items:
        if len(line) + len(it) + 1 > width and line.strip():
            lines.append(line.rstrip())
            line = indent
        line += it + " "
    if line.strip():
        lines.append(line.rstrip())
    return lines


def problem_text(
    domain: str,
    name: str,
    objects: Sequence[tuple[Sequence[str], str | None]],
    init: Iterable[str],
    goal: Iterable[str],
    *,
    costs: bool = False,
    comment: str = "",
) -> str:
    """A PDDL problem; ``objects`` is ``[(names, type or None)]``; ``costs`` adds total-cost."""
    out = [f"; {comment}"] if comment else []
    out += [f"(define (problem {name})", f"  (:domain {domain})", "  (:objects"]
    for names, typ in objects:
        if names:
            out += _wrap([*names, *(["-", typ] if typ else [])], "    ")
    out.append("  )")
    init = list(init) + (["(= (total-cost) 0)"] if costs else [])
    out += ["  (:init"] + _wrap(init, "    ") + ["  )"]
    out += ["  (:goal (and"] + _wrap(list(goal), "    ") + ["  ))"]
    if costs:
        out.append("  (:metric minimize (total-cost))")
    out.append(")")
    return "\n".join(out) + "\n"


def connected_graph(n: int, extra: float, rng: random.Random) -> list[Edge]:
    """Undirected edges ``(i, j)``, ``i < j``, of a random connected graph on ``0..n-1``.

    A random spanning tree (each node joins a random earlier one, in a
    shuffled order), then each other pair with probability ``extra``.
    """
    order = list(range(n))
    rng.shuffle(order)
    edges: list[Edge] = []
    for k in range(1, n):
        a, b = order[k], order[rng.randrange(k)]
        edges.append((min(a, b), max(a, b)))
    for i in range(n):
        for j in range(i + 1, n):
            if (i, j) not in edges and rng.random() < extra:
                edges.append((i, j))
    return sorted(edges)


def distances(n: int, edges: Sequence[Edge], weight: dict[Edge, int] | None = None) -> list[list[int]]:
    """All-pairs shortest path lengths (Dijkstra from each node; unit weights by default)."""
    adj: list[list[tuple[int, int]]] = [[] for _ in range(n)]
    for e in edges:
        w = 1 if weight is None else weight[e]
        adj[e[0]].append((e[1], w))
        adj[e[1]].append((e[0], w))
    big = 10**9
    out = []
    for s in range(n):
        dist = [big] * n
        dist[s] = 0
        heap = [(0, s)]
        while heap:
            d, u = heapq.heappop(heap)
            if d > dist[u]:
                continue
            for v, w in adj[u]:
                if d + w < dist[v]:
                    dist[v] = d + w
                    heapq.heappush(heap, (d + w, v))
        out.append(dist)
    return out


def towers(items: Sequence[str], rng: random.Random, max_towers: int | None = None) -> list[list[str]]:
    """``items`` shuffled and split into random towers (bottom first)."""
    order = list(items)
    rng.shuffle(order)
    result: list[list[str]] = []
    for it in order:
        limit = max_towers if max_towers is not None else len(order)
        if result and (len(result) >= limit or rng.random() < 0.6):
            rng.choice(result).append(it)
        else:
            result.append([it])
    return result
