"""An independent PDDL plan checker for the tests (ADL semantics, no nowplan code).

It reads the ORIGINAL domain and problem text with its own tokenizer and
replays a plan: preconditions (and, or, not, imply, forall, exists, =,
derived predicates) are
evaluated in the state, conditional and universally quantified effects are
all evaluated in the state before the action (deletes, then adds), and
``(increase (total-cost) ...)`` is summed from the problem's function values.
Derived predicates (recursive or not) are recomputed after every change of
the state, naively: strata by counting negations along dependencies, then
per stratum every typed tuple of objects is tried until nothing changes.
"""

from __future__ import annotations

import re
from typing import Any

Tree = Any  # str | list[Tree]


def parse(text: str) -> Tree:
    text = re.sub(r";[^\n]*", " ", text.lower())
    stack: list[list[Tree]] = [[]]
    for tok in re.findall(r"\(|\)|[^\s()]+", text):
        if tok == "(":
            stack.append([])
        elif tok == ")":
            done = stack.pop()
            stack[-1].append(done)
        else:
            stack[-1].append(tok)
    # a file's (define ...) form (PDDL 1.x files put (in-package "PDDL") before it), else the first item
    return next((x for x in stack[0] if isinstance(x, list) and x and x[0] == "define"), stack[0][0])


def typed(items: list[Tree]) -> list[tuple[str, tuple[str, ...]]]:
    out, pending, i = [], [], 0
    while i < len(items):
        if items[i] == "-":
            t = items[i + 1]
            types = tuple(t[1:]) if isinstance(t, list) else (t,)
            out += [(n, types) for n in pending]
            pending, i = [], i + 2
        else:
            pending.append(items[i])
            i += 1
    return out + [(n, ("object",)) for n in pending]


class Sim:
    def __init__(self, domain_text: str, problem_text: str) -> None:
        d, p = parse(domain_text), parse(problem_text)
        self.parent: dict[str, str] = {}
        self.objects: dict[str, str] = {}
        self.actions: dict[str, list[Tree]] = {}
        self.derived: dict[str, list[tuple[list[str], Tree]]] = {}
        self.derived_types: dict[str, list[tuple[str, ...]]] = {}
        self.dstate: set[tuple[str, ...]] = set()
        for sec in d[2:]:
            if sec[0] == ":types":
                for n, ts in typed(sec[1:]):
                    self.parent[n] = ts[0]
            elif sec[0] == ":constants":
                self.objects.update((n, ts[0]) for n, ts in typed(sec[1:]))
            elif sec[0] == ":action":
                self.actions[sec[1]] = sec
            elif sec[0] == ":derived":
                self.derived.setdefault(sec[1][0], []).append(([v for v, _ in typed(sec[1][1:])], sec[2]))
                self.derived_types[sec[1][0]] = [ts for _, ts in typed(sec[1][1:])]
        self.state: set[tuple[str, ...]] = set()
        self.values: dict[tuple[str, ...], float] = {}
        self.goal: Tree = ["and"]
        for sec in p[2:]:
            if sec[0] == ":objects":
                self.objects.update((n, ts[0]) for n, ts in typed(sec[1:]))
            elif sec[0] == ":init":
                for f in sec[1:]:
                    if f[0] == "=":
                        self.values[tuple(f[1])] = float(f[2])
                    else:
                        self.state.add(tuple(f))
            elif sec[0] == ":goal":
                self.goal = sec[1]
        self.cost = 0.0
        self.close()

    def _uses(self, f: Tree, positive: bool, out: set) -> None:
        if isinstance(f, str) or not f:
            return
        if f[0] == "not":
            self._uses(f[1], not positive, out)
        elif f[0] in ("and", "or"):
            for x in f[1:]:
                self._uses(x, positive, out)
        elif f[0] == "imply":
            self._uses(f[1], not positive, out)
            self._uses(f[2], positive, out)
        elif f[0] in ("forall", "exists"):
            self._uses(f[2], positive, out)
        elif f[0] in self.derived:
            out.add((f[0], positive))

    def close(self) -> None:
        """The derived facts of the state: stratum by stratum, naive fixpoint over all tuples."""
        stratum = {p: 0 for p in self.derived}
        for _ in range(len(stratum) ** 2 + 1):
            grew = False
            for p, defs in self.derived.items():
                uses: set = set()
                for _, body in defs:
                    self._uses(body, True, uses)
                for q, positive in uses:
                    need = stratum[q] + (0 if positive else 1)
                    if need > stratum[p]:
                        stratum[p], grew = need, True
            if not grew:
                break
        self.dstate = set()
        for level in sorted(set(stratum.values())):
            preds = [p for p in self.derived if stratum[p] == level]
            changed = True
            while changed:
                changed = False
                for p in preds:
                    tuples = [()]
                    for types in self.derived_types[p]:
                        tuples = [(*t, o) for t in tuples for o in self.domain_of(types)]
                    for args in tuples:
                        if (p, *args) in self.dstate:
                            continue
                        if any(self.holds(body, dict(zip(params, args))) for params, body in self.derived[p]):
                            self.dstate.add((p, *args))
                            changed = True

    def is_a(self, t: str, types: tuple[str, ...]) -> bool:
        seen = set()
        while t not in seen:
            if t in types or "object" in types:
                return True
            seen.add(t)
            t = self.parent.get(t, "object")
        return t in types

    def domain_of(self, types: tuple[str, ...]) -> list[str]:
        return [o for o, t in self.objects.items() if self.is_a(t, types)]

    def holds(self, f: Tree, b: dict[str, str]) -> bool:
        if not f:
            return True
        op = f[0]
        if op == "and":
            return all(self.holds(x, b) for x in f[1:])
        if op == "or":
            return any(self.holds(x, b) for x in f[1:])
        if op == "not":
            return not self.holds(f[1], b)
        if op == "imply":
            return not self.holds(f[1], b) or self.holds(f[2], b)
        if op in ("forall", "exists"):
            combos = [dict(b)]
            for v, types in typed(f[1]):
                combos = [{**c, v: o} for c in combos for o in self.domain_of(types)]
            test = all if op == "forall" else any
            return test(self.holds(f[2], c) for c in combos)
        args = tuple(b.get(a, a) for a in f[1:])
        if op in self.derived:  # computed by close() after every change of the state
            return (op, *args) in self.dstate
        if op == "=":
            return args[0] == args[1]
        return (op, *args) in self.state

    def effects(self, e: Tree, b: dict[str, str], adds: set, dels: set) -> None:
        if not e:
            return
        op = e[0]
        if op == "and":
            for x in e[1:]:
                self.effects(x, b, adds, dels)
        elif op == "when":
            if self.holds(e[1], b):
                self.effects(e[2], b, adds, dels)
        elif op == "forall":
            combos = [dict(b)]
            for v, types in typed(e[1]):
                combos = [{**c, v: o} for c in combos for o in self.domain_of(types)]
            for c in combos:
                self.effects(e[2], c, adds, dels)
        elif op == "increase":
            self.cost += self.number(e[2], b)
        elif op == "not":
            dels.add(tuple([e[1][0], *(b.get(a, a) for a in e[1][1:])]))
        else:
            adds.add(tuple([op, *(b.get(a, a) for a in e[1:])]))

    def number(self, x: Tree, b: dict[str, str]) -> float:
        if isinstance(x, str):
            return float(x)
        if x[0] in ("+", "-", "*", "/"):
            vals = [self.number(a, b) for a in x[1:]]
            if x[0] == "+":
                return sum(vals)
            if x[0] == "*":
                out = 1.0
                for v in vals:
                    out *= v
                return out
            if len(vals) == 1:
                return -vals[0]
            return vals[0] - vals[1] if x[0] == "-" else vals[0] / vals[1]
        return self.values[tuple([x[0], *(b.get(a, a) for a in x[1:])])]

    def apply(self, step: str) -> None:
        name, *args = parse(step)
        act = self.actions[name]
        keys = {act[i]: act[i + 1] for i in range(2, len(act) - 1, 2)}
        params = [v for v, _ in typed(keys.get(":parameters", []))]
        assert len(params) == len(args), step
        b = dict(zip(params, args))
        for (v, types), o in zip(typed(keys.get(":parameters", [])), args):
            assert o in self.objects and self.is_a(self.objects[o], types), f"{step}: {o} is not a {types}"
        assert self.holds(keys.get(":precondition", []), b), f"precondition of {step} fails"
        adds: set = set()
        dels: set = set()
        self.effects(keys.get(":effect", []), b, adds, dels)
        self.state = (self.state - dels) | adds
        self.close()


def check_plan(domain_text: str, problem_text: str, steps: list[str]) -> float:
    """Replay ``steps``; AssertionError if one is inapplicable or the goal fails; returns the cost."""
    sim = Sim(domain_text, problem_text)
    for s in steps:
        sim.apply(s)
    assert sim.holds(sim.goal, {}), "the goal does not hold after the plan"
    return sim.cost
