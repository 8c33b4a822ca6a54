"""The monitor's closest-state search: each distinct library state once, ties to the cheapest path."""

from __future__ import annotations

from nowplan.acting.monitor import Monitor, MonitorConfig
from nowplan.acting.monitor_support import fluent_distance, simulate
from nowplan.acting.plan_library import StoredPlan
from nowplan.core.state import State

from test_mechanisms import CHAIN, op  # noqa: F401


def _stored(pid, init, names):
    ops = {o.name: o for o in CHAIN.operators}
    actions = [ops[n].instantiate({}) for n in names]
    states = simulate(CHAIN, init, actions)
    assert states is not None
    return StoredPlan(pid, "chain", "", "", tuple((a.name, a.args) for a in actions), tuple(states),
                      float(len(actions)))


def test_fluent_distance_counts_differing_fluents():
    from nowplan.core.atoms import atom

    a = State([atom("s0"), atom("s1")])
    b = State([atom("s1"), atom("s2")])
    assert fluent_distance(a, b) == 2 and fluent_distance(a, a) == 0 and a.differing(b) == 2


def test_each_state_is_measured_once_and_ties_go_to_the_cheapest_path():
    from nowplan.core.atoms import atom

    s0 = State([atom("s0")])
    long = _stored(-1, s0, ["step1", "step2", "step3"])
    short = _stored(-2, long.states[1], ["step2", "step3"])  # its 3 states are `long`'s last 3
    detour = _stored(-4, long.states[1], ["step1", "step2", "step3"])  # step1 again: one more action
    mon = Monitor(MonitorConfig())
    mon.plans = [detour, long, short]
    calls = []

    def distance(x, y):
        calls.append(x)
        return fluent_distance(x, y)

    from dataclasses import replace

    mon.support = replace(mon.support, distance=distance)
    cand = mon._closest(long.states[1], CHAIN)
    assert cand is not None and cand.distance == 0
    assert len(calls) == len(set(long.states) | set(short.states) | set(detour.states)) == 4  # not 11
    # the observed state is state 1 of `long`, state 0 of `short`, states 0 and 1 of `detour`:
    # from `detour`'s state 0 3 actions are left to the goal, from the others 2
    assert cand.plan.suffix_cost(cand.index, CHAIN) == 2
    assert (cand.plan.id, cand.index) != (-4, 0)
    mon.plans.append(_stored(-3, s0, ["step1", "step2", "step3"]))
    calls.clear()
    mon._closest(s0, CHAIN)
    assert len(calls) == 4  # the third plan's states are all known already
