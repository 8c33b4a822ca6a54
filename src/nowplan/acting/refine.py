"""Refinements that make progress: no swap of a refined step for a more abstract sibling.

HPN refines an abstract step ω by planning its pre-image at ``NextLevel(α, ω)`` (seed 002
Alg. 1 line 7), which makes ω, and only ω, one criticality class more concrete.  The plan
found may then use a *sibling* (another instance of ω's operator) that still hides the
precondition just exposed, because hiding it makes the sibling cheaper: on pieces, refining
``move_arm(a, b)`` (the arm must be at ``a``) chose an abstract ``move_arm(c, b)`` from a
cell ``c`` nearer ``b``; refining that chose one from a cell nearer still, one pushed plan
per cell, until the plan stack was 64 deep.  Such a chain is a recursion of refinements
within one action, bounded only by the number of instances.

:func:`refine_without_swaps` checks the plan made for a refinement: when a step is more
abstract than an instance of its operator refined higher up the chain (an override of the
level map), the refinement is planned again with that operator *floored* at that level
(:meth:`nowplan.core.levels.LevelMap.floored`; the floor then holds in every plan below),
until no step is.  Along a chain every push then lowers the lowest refined level of one
operator by at least one class, so the chain is no deeper than twice the operators'
criticality classes in all, wherever the floored problems have plans (the check applies
from the second swap in a row: a step that was itself swapped in); a plan with no such
step is kept as it was made, with no extra planning, and so is one whose floored problem
has no plan (then the plan stack's depth limit remains the bound).

Many refinements need no planner call (under ``--criticality auto``, most of them on
benchmarks/classical): :func:`direct_refinement` finds the shortest chain of at most
:data:`DIRECT_STEPS` steps ending in the refined step whose actions supply what the refinement
exposes (the executive tries it before planning; the planner refines the step when there is none).
"""

from __future__ import annotations

import gc
from collections.abc import Hashable
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.plan import Plan, PlanStep

# the floored attempt's node budget: 4x the nodes the plan it replaces took, at least this; a floored
# problem harder than that (marsupial: a travel whose packing the generators cannot plan from the
# current belief) keeps the plan as made instead of exhausting a search space per refinement
FLOOR_NODES = 200

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame
    from nowplan.planning.grounding import Grounder


def refine_without_swaps(ex: Executive, new: Plan, goal: Goal, levels: LevelMap, parent: Frame,
                         refined: Action) -> Plan:
    """``new`` (made for ``goal`` at ``levels`` to refine the step ``refined`` of ``parent``) if
    ``refined`` was not itself swapped in (more abstract, in ``parent``'s plan, than a refined
    instance of its operator) or none of ``new``'s steps is more abstract than a refined instance
    of its operator; else the plan made again with those operators floored.  So one swap is
    refined as seed 002 refines (marsupial's plans swap a travel for a sibling once, and planning
    every such refinement again cost RCHPN up to 25x its planning time), and a second swap in a
    row, the start of a recursion, is not.  When the floored problem has no plan (marsupial: a plane that
    cannot be packed for its travel from the current belief, the seed's generators planning in
    the now), the plan made without the floor is kept, as seed 002 refines: the hierarchy needs
    the sibling there, and the stack's depth limit stays the bound.  The floored attempt may expand
    4x the nodes of the plan it would replace (at least :data:`FLOOR_NODES`).  Each round adds or lowers a
    floor, so the rounds are bounded by the operators' criticality classes."""
    if parent.plan.levels.floored([refined]) is parent.plan.levels:
        return new  # the step refined was no swap: its plan may swap once
    plan = new
    while True:
        floored = levels.floored(s.action for s in plan.steps if s.action is not None)
        if floored is levels:
            return plan
        what = ", ".join(f"{n} <= {v}" for n, v in sorted(floored.floors))
        ex.trace.emit("note", plan_id=parent.plan_id,
                      text="executive: the refinement's plan swaps in a more abstract instance of an "
                           f"operator refined above it; planning it again with that operator floored ({what})")
        expanded = ex.made_with(plan).get("expanded")
        budget = max(FLOOR_NODES, 4 * expanded) if isinstance(expanded, int) else None
        again = ex.make_plan(goal, floored, parent, max_nodes=budget)
        if again is None:
            ex.trace.emit("note", plan_id=parent.plan_id,
                          text=f"executive: no plan with {what}; keeping the refinement's plan as made")
            return plan
        ex.reject_plan(plan, parent, f"swaps in an instance more abstract than one refined above it ({what})")
        plan, levels = again, floored




class Achievers:
    """Ground actions by the atoms their effects make true, looked up one atom at a time.

    Each atom's achievers come from the regression grounder (:class:`nowplan.planning.grounding.Grounder`:
    effect unification, static joins, typed objects), which keeps them per atom in the domain's
    stores keyed on what they depend on: the operators, the objects and the static facts (its
    ``signature``).  :meth:`lookup` makes a grounder for the executive's current objects and
    belief on every direct refinement, so an answer kept for other objects or static facts (an
    object added, a static fact changed by an exogenous event) is never used; the same static
    facts share the answers with the planner's own calls.  The lookup only proposes actions:
    each is checked in the belief.  (Grounding the whole task once per level instead cost
    logistics-20 ~0.045 s on the first refinement, half of HPN's planning time there, for the
    few dozen atoms the refinements ask.)
    """

    def __init__(self) -> None:
        # achievers grouped by a precondition they share (see AtomAchievers.applicable), by the identity
        # of the grounder's kept list (held: the grounder hands the same list out while it is valid)
        self.groups: dict[int, tuple[list[Action], list[tuple[Atom | None, int, list[Action]]]]] = {}
        # the grounder's signature (objects and static facts) and when it was read: what the executive had
        # seen then (the belief and objects it held, failed actions, exogenous changes)
        self._signature: tuple[Hashable, Hashable] | None = None
        # when (as above) and the concrete grounding's achievers index then (None: no grounding made)
        self._concrete: tuple[Hashable, dict[Atom, list[Action]] | None] | None = None

    def lookup(self, ex: Executive) -> AtomAchievers:
        """The achievers of atoms for ``ex``'s objects and belief as they are now.

        The static facts are read again only after news (a failed action or an exogenous change, or
        another belief or other objects): an action that succeeds changes no static fact (no operator has one as an
        effect), and reading them scans the whole belief (a sixth of logistics-40's direct refinements).

        Where the problem's concrete grounding is made already and covers the belief (``--criticality
        auto`` makes it in its set-up and shares it with every level), the achievers are read from it
        (:func:`nowplan.planning.task_grounding.adders_of`): its actions, bound once, instead of the
        same instances grounded again from the operators, and only reachable ones (an action the relaxed
        exploration from the belief does not reach never applies; the grounder's answers add nothing a
        chain could execute).  It is asked once per news too."""
        from nowplan.planning.grounding import Grounder
        from nowplan.planning.task_grounding import adders_of, cached_grounding

        if len(self.groups) > _GROUPS_KEPT:
            self.groups.clear()
        when = (id(ex.belief), id(ex.problem.objects), ex.metrics.failed_actions, ex.metrics.exogenous_changes)
        if self._concrete is None or self._concrete[0] != when:
            g = cached_grounding(ex.domain, ex.problem.objects, ex.belief, -1)
            self._concrete = (when, adders_of(g) if g is not None else None)
        if self._concrete[1] is not None:
            return AtomAchievers(None, self.groups, self._concrete[1])
        known = self._signature[1] if self._signature is not None and self._signature[0] == when else None
        # (direct chains need a belief that lists its facts: forward_unsupported was asked)
        grounder = Grounder(ex.domain, ex.problem.objects, ex.belief, lists_facts=True, signature=known)
        self._signature = (when, grounder.signature)
        return AtomAchievers(grounder, self.groups)


_GROUPS_KEPT = 4096


class AtomAchievers:
    """One direct refinement's view of the achievers of an atom: a grounding's index (``adders``) or the
    grounder's answers, grounded on demand."""

    def __init__(self, grounder: Grounder | None,
                 groups: dict[int, tuple[list[Action], list[tuple[Atom | None, int, list[Action]]]]],
                 adders: dict[Atom, list[Action]] | None = None) -> None:
        self.grounder = grounder
        self._goal = Goal.of([])  # the domains refined by chains have no generators: the goal is never read
        self._groups = groups
        self._adders = adders

    def of(self, u: Atom) -> list[Action]:
        """The ground actions one of whose effects is ``u`` (statically possible ones; kept per atom)."""
        if self._adders is not None:
            return self._adders.get(u, _NO_ACTIONS)
        assert self.grounder is not None
        return self.grounder.achievers(u, self._goal)

    def one_of(self, need: list[Atom]) -> tuple[Atom, list[Action]]:
        """An atom of ``need`` with its achievers: of the atoms whose achievers are known already, the one
        with the fewest, else the first (grounding one atom only).  An action that adds every atom of
        ``need`` adds each of them, so whichever atom is taken, the same actions remain candidates."""
        if self._adders is not None:  # every atom's achievers are known
            return min(((u, self.of(u)) for u in need), key=lambda x: len(x[1]))
        assert self.grounder is not None
        known = [(u, acts) for u in need if (acts := self.grounder.known(u)) is not None]
        if known:
            return min(known, key=lambda x: len(x[1]))
        return need[0], self.of(need[0])

    def applicable(self, acts: list[Action], levels: LevelMap, holds: Any) -> list[Action]:
        """Those of ``acts`` (a list the grounder kept) whose preconditions at ``levels`` hold now.

        ``acts`` are grouped, once, by operator and the first of its most critical preconditions
        (kept at every level below that criticality; a level map only lowers levels below its top):
        when that precondition is false, a group is passed over with one test (the achievers of
        ``fuel-level(a, l)`` in zenotravel are the flights of ``a`` from every city with every fuel
        level; the aircraft is in one city)."""
        hit = self._groups.get(id(acts))
        if hit is None or hit[0] is not acts:
            by: dict[tuple[str, Atom | None], list[Action]] = {}
            crit: dict[str, int] = {}
            for a in acts:
                pres = a.operator.preconditions
                top = max((p.criticality for p in pres), default=0)
                first = next((p.atom for p in pres if p.criticality == top), None)
                crit[a.operator.name] = top
                by.setdefault((a.operator.name, first.bind(a.bindings) if first is not None else None), []).append(a)
            hit = self._groups[id(acts)] = (acts, [(k, crit[name], g) for (name, k), g in by.items()])
        out: list[Action] = []
        ceiling = max([levels.top, *(lv for _, lv in levels.overrides)])  # no action's level is above it
        for key, top, group in hit[1]:
            if key is not None and ceiling < top and not holds(key):
                continue  # every action of the group keeps ``key`` (its level is below ``top``)
            out.extend(a for a in group if all(holds(p) for p in a.preconditions(levels.level(a))))
        return out


_NO_ACTIONS: list[Action] = []  # (never changed: the answer for an atom no action adds)

# the longest refinement made directly: ω with the actions before it that achieve what it exposes
DIRECT_STEPS = 4
CARRY_STEPS = 3  # chains whose steps leave atoms to earlier ones: at most CARRY_STEPS - 1 before the refined step


def direct_refinement(ex: Executive, goal: Goal, levels: LevelMap, refined: Action,
                      may_swap: bool = False) -> Plan | None:
    """A refinement of ``refined`` (ω) found without a planner call: the shortest plan ``[…, ω]``
    of at most :data:`DIRECT_STEPS` steps in which each action makes every unmet atom of its
    successor's pre-image true and needs only atoms that hold now or that its predecessor makes
    true (the cheapest such chain of the shortest length); ``None`` when there is none, or
    ``goal`` holds already (the planner refines the step).

    Under an ordered-monotonic hierarchy (``--criticality auto``) most refinements are of this
    kind: a refined step exposes one class of preconditions, which hold already (a second ball
    picked where the robot stands) or take an action or two (the truck driven to the package, an
    aircraft refuelled and flown); a planner call would set up and search the whole task for the
    same short plan.  The plan's pre-images are computed as the planner's are
    (:func:`nowplan.planning.preimage.preimage`), the preconditions of every action put before ω
    are checked in the belief, statics included, steps learnt not to start a plan for ``goal`` here
    (acting/backtrack.py) are not used first, and no action swaps in an instance more abstract
    than one refined above it (see :func:`refine_without_swaps`).  Chains longer than ``[ω]``
    need a ground, boolean domain whose belief lists its facts (the forward task's premise).

    With ``may_swap`` (``refined`` was not itself swapped in), where no chain exists the one-step
    plan with a sibling of ``refined`` ready at the refined level is tried too
    (:func:`nowplan.acting.direct_sibling.sibling_refinement`: what the planner's plan mostly is there).
    """
    paused = gc.isenabled()  # as the planner does (planning/regression.py): no collector passes mid-call
    if paused:
        gc.disable()
    try:
        return _direct(ex, goal, levels, refined, may_swap)
    finally:
        if paused:
            gc.enable()


def _direct(ex: Executive, goal: Goal, levels: LevelMap, refined: Action, may_swap: bool = False) -> Plan | None:
    from nowplan.planning.preimage import preimage, static_drop
    from nowplan.planning.task import forward_unsupported

    forbidden = ex.nogoods.forbidden(goal, levels)
    domain, belief = ex.domain, ex.belief
    drop = static_drop(domain, belief)
    seen: dict[Atom, bool] = {}

    def holds(a: Atom) -> bool:
        v = seen.get(a)
        if v is None:
            v = seen[a] = domain.holds(a, belief)
        return v

    truth = ex.truth  # (one dictionary lookup per atom where the truth is plain: Domain.satisfies)
    if refined.key in forbidden or ex.holds_goal(goal):  # (the loop's memo: it tested the step's goal)
        return None  # the goal holds: the planner's empty plan, not a step
    g1 = preimage(goal, refined, levels.level(refined), domain, drop)
    if g1 is None:
        return None
    unmet = domain.unmet(truth, g1.atoms)
    chain: list[Action] = [refined]
    if unmet:
        if domain.axioms or forward_unsupported(domain, belief) is not None:
            return None
        found = None
        index = ex.achievers.lookup(ex)
        # iterative deepening (only a chain's start must hold now), first over chains whose every step
        # adds all its successor needs, then over those of two steps before the refined one that may
        # leave atoms to the step before them (more candidates per step: tried only where the first kind
        # has no chain, and not deeper: on driverlog, deeper ones cost 3x the chain search for no chain)
        for carry in (False, True):
            for depth in (range(2, CARRY_STEPS) if carry else range(1, DIRECT_STEPS)):
                found = _chain(ex, index, levels, g1, unmet, forbidden, holds, depth, carry)
                if found is not None:
                    break
            if found is not None:
                break
        if found is None:
            if not may_swap:
                return None
            from nowplan.acting.direct_sibling import sibling_refinement

            return sibling_refinement(ex, index, goal, levels, refined, forbidden, holds, drop)
        chain = [*found, refined]
    goals = [goal, g1]
    for a in reversed(chain[:-1]):
        g = preimage(goals[-1], a, levels.level(a), domain, drop)
        if g is None:
            return None
        goals.append(g)
    goals.reverse()
    if not ex.holds_goal(goals[0]):  # (remembered: the loop tests the new plan's g0 next)
        return None
    return Plan((PlanStep(None, goals[0]), *(PlanStep(a, g) for a, g in zip(chain, goals[1:], strict=True))), levels)



def _chain(ex: Executive, index: AtomAchievers, levels: LevelMap, g: Goal, unmet: list[Atom], forbidden: frozenset[Any],
           holds: Any, depth: int, carry: bool = False) -> list[Action] | None:
    """The cheapest shortest chain ``[b, …, a]`` (at most ``depth`` actions) after which ``g``'s
    unmet atoms hold: each action's preconditions hold now or are all added by the action before it
    (with ``carry``: each atom an action needs, its preconditions not holding now and what its
    successor needs and it does not add, is added by one of the actions before it and destroyed by
    none in between); ``a`` destroys no atom of ``g``; the first needs only what holds now and may not
    be ``forbidden``.  (Satellite: ``take_image`` needs its instrument calibrated and powered on;
    ``calibrate`` adds the one and needs the other, which ``switch_on`` adds before it.)"""
    refined_ops = {key[0] for key, _ in levels.overrides}
    rows: dict[Any, tuple[frozenset[Atom], tuple[Atom, ...]]] = {}

    def row(a: Action) -> tuple[frozenset[Atom], tuple[Atom, ...]]:
        r = rows.get(a.key)
        if r is None:
            effects = a.memo.get("effect set")  # (an action's effects never change: kept on it)
            if effects is None:
                effects = a.memo["effect set"] = frozenset(a.effects())
            r = rows[a.key] = (effects, a.preconditions(levels.level(a)))
        return r

    def candidate(a: Action, need: list[Atom], table: dict[Any, Atom], carry: bool) -> list[Atom] | None:
        """What must hold before ``a``: its preconditions not holding now and, with ``carry``, the atoms
        of ``need`` it does not add (left to the actions before it; it must not destroy them or need
        their opposites); None if ``a`` adds none of ``need`` (all of it without ``carry``) or destroys
        one of ``table``'s atoms."""
        effects, pre = row(a)
        missing = [u for u in need if u not in effects]
        if missing and (not carry or len(missing) == len(need)):
            return None
        for e in effects:
            want = table.get(e.key)
            if want is not None and want.value != e.value:
                return None
        if a.key[0] in refined_ops and levels.floored([a]) is not levels:
            return None  # a swap (refine_without_swaps)
        out = [p for p in pre if not holds(p)]
        if missing:
            mine = {p.key: p for p in pre}
            for u in missing:
                other = mine.get(u.key)
                if other is None:
                    out.append(u)
                elif other.value != u.value:
                    return None  # a needs the opposite of what it must leave as it found it
        return out

    hidden: dict[Any, list[Atom]] = {}

    def hidden_now(a: Action) -> list[Atom]:
        """``a``'s preconditions hidden at its level that hold now: an action put before it must not
        destroy them (gripper: no move away before a pick that is still abstract)."""
        h = hidden.get(a.key)
        if h is None:
            kept = set(row(a)[1])
            h = hidden[a.key] = [p for p in a.preconditions(None) if p not in kept and holds(p)]
        return h

    applicable: dict[Atom, list[Action]] = {}

    def achievers(need: list[Atom], start: bool) -> list[Action]:
        """The actions adding one of ``need`` (see :meth:`AtomAchievers.one_of`), applicable now if
        ``start``; else (a step that may leave atoms to the steps before it) those adding any of them."""
        if carry and not start and len(need) > 1:
            out: dict[Any, Action] = {}
            for v in need:
                for a in index.of(v):
                    out.setdefault(a.key, a)
            return list(out.values())
        u, acts = index.one_of(need)
        if not start:
            return acts
        hit = applicable.get(u)
        if hit is None:
            hit = applicable[u] = index.applicable(acts, levels, holds)
        return hit

    table = g.by_key()
    layer: list[tuple[float, list[Action], list[Atom]]] = []  # (cost, chain, what its first action needs)
    for a in achievers(unmet, depth == 1):
        c = candidate(a, unmet, table, carry and depth > 1)
        if c is not None:
            layer.append((a.cost(ex.belief), [a], c))
    for k in range(depth):
        done = [(cost, ch) for cost, ch, need in layer if not need and ch[0].key not in forbidden]
        if done:
            return min(done, key=lambda x: (x[0], [a.pddl() for a in x[1]]))[1]
        if k == depth - 1:
            break
        nxt: list[tuple[float, list[Action], list[Atom]]] = []
        for cost, ch, need in layer:
            if not need:
                continue  # a forbidden start: longer chains before it are no shorter way round
            pre_table = {p.key: p for p in row(ch[0])[1]}
            pre_table.update((u.key, u) for u in need)  # atoms carried past ch[0] too
            if carry:  # and what the chain's abstract steps need at lower levels and have now
                for a in ch:
                    pre_table.update((h.key, h) for h in hidden_now(a) if h.key not in pre_table)
            start = k + 2 == depth
            for b in achievers(need, start):
                c = candidate(b, need, pre_table, carry and not start)
                if c is not None:
                    nxt.append((cost + b.cost(ex.belief), [b, *ch], c))
        layer = nxt
    return None
