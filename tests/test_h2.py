"""h² reachable pairs (planning/h2.py) against the reachable states enumerated by breadth-first search.

Sound: every pair of facts true together in a reachable state is an h²-reachable pair, and every
fact true in one is reachable.  Informed: on the held-out gridfix the pair "full battery away from
every dock" is found unreachable (what regression's abstract subgoals ran into), and blocksworld's
"holding a block that is on another" too.  Growth: a start with a pair the table lacks is added.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom
from nowplan.core.levels import flat_levels
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.h2 import PairReach, pair_reach
from nowplan.planning.heuristics import ground_task
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search
from strips_model import applicable, ground_actions, step
from test_planner_property import FAMILIES, Case

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"


def table_for(domain, objects, init) -> tuple[_Search, PairReach]:
    srch = _Search(domain, objects, init, flat_levels(), PlannerConfig(engine="regression", h2=True), None)
    pr = srch.pairs()
    assert pr is not None
    return srch, pr


def reachable_states(domain, objects, init: State, limit: int = 20_000) -> list[State]:
    acts = ground_actions(domain, list(objects), init)
    seen = {init}
    frontier = [init]
    while frontier and len(seen) < limit:
        nxt = []
        for s in frontier:
            for a in acts:
                if applicable(a, s):
                    s2 = step(s, a)
                    if s2 not in seen:
                        seen.add(s2)
                        nxt.append(s2)
        frontier = nxt
    return list(seen)


def check_sound(domain, objects, init: State) -> tuple[PairReach, int]:
    srch, pr = table_for(domain, objects, init)
    T = domain.facts
    pairs_seen = 0
    for s in reachable_states(domain, objects, init):
        ids = sorted({T.id(a) for a in s.atoms() if a.value is True} & set(pr.bit))
        for f in ids:
            assert (pr.facts >> pr.bit[f]) & 1, f"{T.atoms[f]} holds in a reachable state, h2 says unreachable"
        for i, f in enumerate(ids):
            for g in ids[i + 1:]:
                assert not pr.mutex(f, g), f"{T.atoms[f]} & {T.atoms[g]} hold together in {s}, h2 says never"
                pairs_seen += 1
        assert not pr.excluded(ids)
    return pr, pairs_seen


@pytest.mark.parametrize("family", sorted(set(FAMILIES) - {"hanoi"}))
@settings(max_examples=12, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_every_reachable_pair_is_kept(family: str, data: st.DataObject) -> None:
    case: Case = data.draw(FAMILIES[family], label="case")
    check_sound(case.domain, {o: None for o in case.objects}, case.init)


def test_blocksworld_pairs_sound_and_informed() -> None:
    p = load_pddl(DATA / "blocksworld" / "domain.pddl", DATA / "blocksworld" / "p02.pddl")
    pr, seen = check_sound(p.domain, p.objects, p.init)
    assert seen > 0
    T = p.domain.facts
    blocks = sorted(o for o in p.objects)
    a, b = blocks[0], blocks[1]
    assert pr.atoms_mutex(Atom("holding", (a,)), Atom("on", (a, b)))
    assert pr.atoms_mutex(Atom("holding", (a,)), Atom("handempty", ()))
    assert not pr.atoms_mutex(Atom("on", (a, b)), Atom("clear", (a,)))
    assert pr.excluded([T.id(Atom("holding", (a,))), T.id(Atom("clear", (b,))), T.id(Atom("on", (a, b)))])


def test_gridfix_full_battery_away_from_a_dock_is_unreachable() -> None:
    pytest.importorskip("gridfix_domain")
    from gridfix_domain.model import DOMAIN
    from gridfix_domain.scenarios import episode

    ep = episode(seed=0)
    srch, pr = table_for(DOMAIN, ep.problem.objects, ep.belief)
    assert pr.sweeps >= 2
    full, dock, away = Atom("batt", ("e4",)), Atom("van_at", ("sub",)), Atom("van_at", ("j2",))
    assert pr.atoms_mutex(full, away)
    assert not pr.atoms_mutex(full, dock)
    assert not pr.atoms_mutex(Atom("batt", ("e2",)), away)


def test_a_start_outside_the_table_grows_it() -> None:
    p = load_pddl(DATA / "blocksworld" / "domain.pddl", DATA / "blocksworld" / "p02.pddl")
    srch, pr = table_for(p.domain, p.objects, p.init)
    T = p.domain.facts
    a, b = sorted(p.objects)[:2]
    x, y = T.id(Atom("holding", (a,))), T.id(Atom("on", (a, b)))
    assert pr.mutex(x, y)
    assert pr.start_from([x, y])  # (a start no action reaches: a world changed by something else)
    assert not pr.mutex(x, y)
    assert not pr.start_from([x, y])  # nothing new the second time


def test_pruning_keeps_every_plan_on_blocksworld() -> None:
    """The same optimal cost with and without h2 (A* with an admissible estimate), fewer nodes."""
    p = load_pddl(DATA / "blocksworld" / "domain.pddl", DATA / "blocksworld" / "p02.pddl")
    base = PlannerConfig(engine="regression", heuristic="hmax", serialization=False, monotonic=False,
                         prune=False, max_nodes=200_000, time_limit=600.0, clock="cpu")
    off = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), base)
    on = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), replace(base, h2=True))
    assert off.plan is not None and on.plan is not None
    assert len(on.plan) == len(off.plan)  # (unit costs)
    assert on.expanded <= off.expanded


def test_the_table_is_kept_with_the_ground_task() -> None:
    p = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl")
    s1, pr1 = table_for(p.domain, p.objects, p.init)
    s2, pr2 = table_for(p.domain, p.objects, p.init)
    assert pr1 is pr2 is pair_reach(ground_task(s1.grounder, s1.drop), p.domain)


def test_a_fluent_the_belief_is_unsure_of_starts_true_with_every_fact() -> None:
    """A particle belief unsure whether the door is open: no action opens it (one shuts it, so it is no
    static), yet the table keeps it reachable with every fact the belief lists (a later belief may know
    it true: plans need it)."""
    from nowplan.belief.particle_belief import ParticleBelief
    from nowplan.core.domain import Domain, Predicate
    from nowplan.core.operators import Operator, Precondition
    from nowplan.core.atoms import Var

    x, y = Var("x"), Var("y")
    dom = Domain("unsure", {"at": Predicate("at", 1), "open": Predicate("open", 0), "road": Predicate("road", 2)},
                 (Operator("go", (x, y), (Precondition(Atom("at", (x,)), 1), Precondition(Atom("open", ()), 1),
                                          Precondition(Atom("road", (x, y)), 1)),
                           (Atom("at", (y,)), Atom("at", (x,), False))),
                  Operator("shut", (), (), (Atom("open", (), False),))))
    facts = [Atom("at", ("a",)), Atom("road", ("a", "b"))]
    belief = ParticleBelief([State(facts + [Atom("open", ())]), State(facts)])
    assert ("open", ()) in belief.unknowns()
    _, pr = table_for(dom, {"a": None, "b": None}, belief)
    T = dom.facts
    assert not pr.excluded([T.id(Atom("open", ())), T.id(Atom("at", ("b",)))])
    assert not pr.atoms_mutex(Atom("open", ()), Atom("at", ("a",)))
    assert pr.atoms_mutex(Atom("at", ("a",)), Atom("at", ("b",)))  # (go deletes where it leaves)


def test_a_fixpoint_past_its_bound_prunes_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    import nowplan.planning.h2 as h2

    monkeypatch.setattr(h2, "MAX_SWEEPS", 1)
    p = load_pddl(DATA / "blocksworld" / "domain.pddl", DATA / "blocksworld" / "p02.pddl")
    task_srch = _Search(p.domain, p.objects, p.init, flat_levels(), PlannerConfig(engine="regression"), None)
    pr = PairReach(ground_task(task_srch.grounder, task_srch.drop), p.domain)
    pr.start_from(p.domain.facts.ids_of(p.init.atoms()))
    a, b = sorted(p.objects)[:2]
    assert not pr.atoms_mutex(Atom("holding", (a,)), Atom("on", (a, b)))  # (found with the bound: see above)
    assert not pr.excluded(list(pr.bit))


def reference_pairs(pr: PairReach, start: set[int]) -> tuple[set[int], set[frozenset[int]]]:
    """h² by its definition over sets (one sweep over every action until nothing changes), from the
    table's own action model (its bits as sets): the check of the semi-naive fixpoint."""
    def bits(x: int) -> set[int]:
        return {i for i in range(x.bit_length()) if x >> i & 1}

    acts = [(bits(p), bits(a), bits(d)) for p, a, d, _ in pr._acts]
    facts = set(start)
    pairs = {frozenset((x, y)) for x in start for y in start}
    changed = True
    while changed:
        changed = False
        for pre, add, dele in acts:
            if not pre <= facts or any(frozenset((x, y)) not in pairs for x in pre for y in pre):
                continue
            new = set(add) | {q for q in facts - dele if all(frozenset((q, p)) in pairs for p in pre)}
            for e in add:
                for q in new:
                    if frozenset((e, q)) not in pairs:
                        pairs.add(frozenset((e, q)))
                        changed = True
            if not add <= facts:
                facts |= add
                changed = True
    return facts, pairs


@pytest.mark.parametrize("family", sorted(set(FAMILIES) - {"hanoi"}))
@settings(max_examples=10, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_the_fixpoint_equals_the_definition(family: str, data: st.DataObject) -> None:
    case: Case = data.draw(FAMILIES[family], label="case")
    srch = _Search(case.domain, {o: None for o in case.objects}, case.init, flat_levels(),
                   PlannerConfig(engine="regression"), None)
    pr = PairReach(ground_task(srch.grounder, srch.drop), case.domain)
    ids = {pr.bit[f] for f in case.domain.facts.ids_of(case.init.atoms()) if f in pr.bit}
    pr.start_from(pr.fact_of[b] for b in ids)
    facts, pairs = reference_pairs(pr, ids)
    assert {b for b in range(len(pr.fact_of)) if pr.facts >> b & 1} == facts
    got = {frozenset((a, b)) for a in range(len(pr.fact_of)) for b in range(len(pr.fact_of)) if pr.reach[a] >> b & 1}
    assert got == pairs
