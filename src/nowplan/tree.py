"""The planning-and-execution tree of a run, rebuilt from its trace events.

Each ``plan`` event is a node; its ``parent``/``parent_step`` fields hang it
under the step of the plan it refines (seed 000 Fig. 3).  Steps are marked
executed when an ``action`` or a child plan used them; pops and replans are
attached to their plans.  :func:`render_text` prints the tree for a
terminal; the HTML viewer uses the same structure.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any


@dataclass
class PlanNode:
    plan_id: int
    parent: int | None
    parent_step: int | None
    goal: list[str]
    method: str
    cost: float
    steps: list[dict[str, Any]]
    children: dict[int, list[PlanNode]] = field(default_factory=dict)  # step index -> sub-plans
    executed: set[int] = field(default_factory=set)
    pop_reason: str | None = None
    replans: list[dict[str, Any]] = field(default_factory=list)


def build_tree(events: Iterable[dict[str, Any]]) -> tuple[list[PlanNode], dict[int, PlanNode]]:
    """Top-level plan nodes (children of the root) and every node by id."""
    nodes: dict[int, PlanNode] = {}
    roots: list[PlanNode] = []
    for e in events:
        kind = e.get("event")
        if kind == "plan":
            node = PlanNode(
                int(e["plan_id"]), e.get("parent"), e.get("parent_step"), list(e.get("goal", [])),
                str(e.get("method", "")), float(e.get("cost", 0.0)), list(e.get("steps", [])),
            )
            nodes[node.plan_id] = node
            parent = nodes.get(node.parent) if node.parent is not None else None
            if parent is None:
                roots.append(node)
            else:
                parent.children.setdefault(int(node.parent_step or 0), []).append(node)
                parent.executed.add(int(node.parent_step or 0))
        elif kind == "action":
            n = nodes.get(e.get("plan_id", -1))
            if n is not None:
                n.executed.add(int(e.get("index", 0)))
        elif kind == "pop":
            n = nodes.get(e.get("plan_id", -1))
            if n is not None:
                n.pop_reason = str(e.get("reason"))
        elif kind == "replan":
            n = nodes.get(e.get("plan_id", -1))
            if n is not None:
                n.replans.append(e)
    return roots, nodes


def same_goal_child(node: PlanNode) -> PlanNode | None:
    """The one sub-plan of a one-step plan, when it is for the same goal (shown once, not nested)."""
    real = node.steps[1:]
    if len(real) != 1:
        return None
    kids = node.children.get(int(real[0]["index"]), [])
    if len(kids) != 1 or kids[0].goal != node.goal or kids[0] is node:
        return None
    return kids[0]


def render_text(events: Iterable[dict[str, Any]], max_lines: int = 400) -> str:
    """An indented text rendering of the tree (``*`` marks executed steps).

    A one-step plan refined into one plan for the same goal is printed once, as
    ``plan 4 -> 5``: the nesting would repeat the same goal and step.
    """
    roots, _ = build_tree(events)
    lines: list[str] = []

    def emit(node: PlanNode, indent: str) -> None:
        merged: list[int] = []
        while (child := same_goal_child(node)) is not None:
            merged.append(node.plan_id)
            node = child
        popped = f"  [popped: {node.pop_reason}]" if node.pop_reason and node.pop_reason != "done" else ""
        ids = "".join(f"{m} -> " for m in merged) + str(node.plan_id)
        lines.append(f"{indent}plan {ids} ({node.method}) for {' & '.join(node.goal) or 'True'}{popped}")
        for s in node.steps[1:]:
            idx = int(s["index"])
            mark = "*" if idx in node.executed else " "
            kind = "prim" if s.get("primitive") else f"abs-{s.get('hidden', '?')}"
            lines.append(f"{indent}  {mark} {idx}. {s['action']}  <{kind}>")
            for child in node.children.get(idx, []):
                emit(child, indent + "      ")

    for r in roots:
        emit(r, "")
    if len(lines) > max_lines:
        lines = lines[:max_lines] + [f"... ({len(lines) - max_lines} more lines)"]
    return "\n".join(lines)
