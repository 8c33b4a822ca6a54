"""The expected-vs-observed monitor (seed 003): the rule, each alternative in a situation built for it,
and the monitor on another domain (logistics) with the default distance."""

from __future__ import annotations

import random
from collections.abc import Callable

import pytest

import nowplan.domains.pieces  # noqa: F401  (registers the pieces domain's monitor support)
from nowplan.acting.hpn import Executive
from nowplan.acting.monitor import Monitor, MonitorConfig, monitor_settings
from nowplan.acting.monitor_repair import Alternative, order_to_try, seed_rule
from nowplan.acting.strategy import PLANNED, parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Atom, atom
from nowplan.core.state import State
from nowplan.domains.logistics.model import DOMAIN as LOGISTICS
from nowplan.domains.logistics.scenarios import SIZES, generate
from nowplan.domains.pieces.board import Board, Geometry
from nowplan.domains.pieces.model import DOMAIN, problem
from nowplan.errors import ScenarioError
from nowplan.trace import Trace
from nowplan.worlds.symbolic import SymbolicWorld

G4 = Geometry(4, 4)
START = Board.of(G4, {"r0c0": "pawn", "r0c1": "rook", "r0c2": "king"}, "r3c3")
GOAL = {"r3c0": "pawn", "r3c1": "rook", "r3c2": "king"}
# the means-ends plan takes the king first (nearest the arm): move_arm to r0c2, then r0c2 -> r3c2


class Person:
    """Exogenous changes after the ``at``-th action only: fixed atoms or a function of the state."""

    def __init__(self, at: int, change: list[Atom] | Callable[[State, random.Random], list[Atom]]) -> None:
        self.at, self.change, self.calls = at, change, 0

    def __call__(self, state: State, rng: random.Random) -> list[Atom]:
        self.calls += 1
        if self.calls != self.at:
            return []
        return self.change(state, rng) if callable(self.change) else list(self.change)


def carry(kind: str, src: str, dst: str) -> list[Atom]:
    return [atom("has", src, kind, value=False), atom("empty", src), atom("has", dst, kind),
            atom("empty", dst, value=False)]


def run_pieces(changes: list[Atom], switch: str = "monitor", config: MonitorConfig | None = None):
    p = problem(START, GOAL)
    world = SymbolicWorld(DOMAIN, p.init, exogenous=Person(1, changes), exogenous_prob=1.0)
    trace = Trace()
    with monitor_settings(config or MonitorConfig()):
        ex = Executive(p, world, SymbolicBelief(p.init), parse_strategy(f"hpn+{switch}"), seed=0, trace=trace)
    m = ex.run()
    mon = next(x for x in ex.mechanisms if isinstance(x, Monitor))
    assert m.outcome.value == "reached", m.reason
    assert DOMAIN.satisfies(world.state, p.goal)
    return m, mon, trace


def test_seed_rule_verbatim() -> None:
    assert seed_rule(dm=2, dm1=0, thr=4, thr1=4) is Alternative.INTERMEDIATE
    assert seed_rule(dm=2, dm1=2, thr=4, thr1=4) is Alternative.RESTORE  # dm1 must be strictly smaller
    assert seed_rule(dm=2, dm1=None, thr=4, thr1=4) is Alternative.RESTORE
    assert seed_rule(dm=4, dm1=None, thr=4, thr1=4) is Alternative.GOAL  # dm must be below thr
    assert seed_rule(dm=6, dm1=5, thr=4, thr1=4) is Alternative.GOAL  # dm1 above its threshold
    assert seed_rule(dm=6, dm1=1, thr=4, thr1=4) is Alternative.INTERMEDIATE


def test_fallback_orders() -> None:
    rule = MonitorConfig()
    assert order_to_try(rule, 2, 0) == [Alternative.INTERMEDIATE, Alternative.RESTORE, Alternative.GOAL]
    assert order_to_try(rule, 6, None) == [Alternative.GOAL]
    assert order_to_try(MonitorConfig(decision="restore"), 9, None) == [Alternative.RESTORE, Alternative.GOAL]
    assert order_to_try(MonitorConfig(decision="goal"), 1, 0) == [Alternative.GOAL]


@pytest.mark.parametrize("bad", [{"decision": "sometimes"}, {"thr": -1.0}, {"restore_target": "all"},
                                 {"library_scope": "world"}, {"planner": "magic"}, {"planning_weight": -2}])
def test_bad_monitor_settings_are_refused(bad: dict[str, object]) -> None:
    with pytest.raises(ScenarioError):
        MonitorConfig(**bad)  # type: ignore[arg-type]


def test_switches_are_registered() -> None:
    assert "monitor" not in PLANNED
    for name in ("monitor", "monitor-goal", "monitor-restore", "monitor-cost", "monitor-rule-cost"):
        assert any(isinstance(m, Monitor) for m in parse_strategy(f"hpn+{name}").mechanisms())


def test_intermediate_state_when_the_person_does_the_next_step() -> None:
    # after the arm reaches the king, the person carries the king to its goal cell: the observed
    # model is the plan's state after its next step (dm1 = 0 < dm = 2)
    m, mon, trace = run_pieces(carry("king", "r0c2", "r3c2"))
    assert dict(mon.stats.decisions) == {"intermediate": 1}
    assert m.action_counts["move_piece"] == 2  # the king's move was done for us
    note = next(e for e in trace.of("note") if e.get("alternative"))
    assert note["dm1"] < note["dm"]
    assert [r["trigger"] for r in trace.of("replan")] == ["monitor"]


def test_always_restoring_undoes_the_persons_help() -> None:
    m_rule, _, _ = run_pieces(carry("king", "r0c2", "r3c2"))
    m_restore, mon, _ = run_pieces(carry("king", "r0c2", "r3c2"), "monitor-restore")
    assert dict(mon.stats.decisions) == {"restore": 1}
    assert m_restore.execution_cost > m_rule.execution_cost


def test_restore_after_a_small_disturbance() -> None:
    # the pawn is pushed one cell: no stored state is closer than the expected one, dm = 2 < thr
    m, mon, trace = run_pieces(carry("pawn", "r0c0", "r1c0"))
    assert dict(mon.stats.decisions) == {"restore": 1}
    note = next(e for e in trace.of("note") if e.get("alternative"))
    assert note["dm"] < MonitorConfig().thr and (note["dm1"] is None or note["dm1"] >= note["dm"])


def test_goal_after_a_large_disturbance() -> None:
    m, mon, trace = run_pieces(carry("pawn", "r0c0", "r1c1") + carry("rook", "r0c1", "r2c2"))
    assert dict(mon.stats.decisions) == {"goal": 1}
    note = next(e for e in trace.of("note") if e.get("alternative"))
    assert note["dm"] >= MonitorConfig().thr


def test_thresholds_are_configurable() -> None:
    _, mon, _ = run_pieces(carry("pawn", "r0c0", "r1c0"), config=MonitorConfig(thr=1.0))
    assert dict(mon.stats.decisions) == {"goal": 1}


def test_rule_cost_orders_the_eligible_alternatives() -> None:
    cfg = MonitorConfig(decision="rule-cost")
    assert order_to_try(cfg, 2, 0) == [Alternative.INTERMEDIATE, Alternative.RESTORE, Alternative.GOAL]
    assert order_to_try(cfg, 2, None) == [Alternative.RESTORE, Alternative.GOAL]
    assert order_to_try(cfg, 2, 2) == [Alternative.RESTORE, Alternative.GOAL]  # dm1 must be below dm
    assert order_to_try(cfg, 6, 5) == [Alternative.GOAL]  # both above the threshold: only the goal
    assert cfg.compares and not MonitorConfig().compares


def test_rule_cost_does_not_restore_when_replanning_is_cheaper() -> None:
    # the pawn, not yet moved, is pushed one cell towards its goal: restoring carries it back first
    m_rule, mon_rule, _ = run_pieces(carry("pawn", "r0c0", "r1c0"))
    m_rc, mon_rc, trace = run_pieces(carry("pawn", "r0c0", "r1c0"), "monitor-rule-cost")
    assert dict(mon_rule.stats.decisions) == {"restore": 1}
    assert dict(mon_rc.stats.decisions) == {"goal": 1}
    note = next(e for e in trace.of("note") if e.get("alternative"))
    assert note["decision"] == "rule-cost"
    assert m_rc.execution_cost < m_rule.execution_cost


def test_cost_decision_takes_the_cheapest_alternative() -> None:
    _, mon, trace = run_pieces(carry("king", "r0c2", "r3c2"), "monitor-cost")
    note = next(e for e in trace.of("note") if e.get("alternative"))
    assert note["decision"] == "cost" and mon.stats.decisions[note["alternative"]] == 1
    assert note["alternative"] != "restore"  # restoring would carry the king back


def _move_one_package(state: State, rng: random.Random) -> list[Atom]:
    """A person carries a package lying somewhere to another place of its city (never a vehicle)."""
    lying = sorted((str(a[0]), str(a[1])) for a in state.facts("at") if str(a[0]).startswith("p")
                   and not str(a[0]).startswith("plane"))
    if not lying:
        return []
    pkg, loc = lying[0]
    city = next(a[1] for a in state.facts("in_city") if a[0] == loc)
    other = sorted(a[0] for a in state.facts("in_city") if a[1] == city and a[0] != loc)[0]
    return [atom("at", pkg, loc, value=False), atom("at", pkg, other)]


@pytest.mark.parametrize("switch", ["monitor", "monitor-goal", "monitor-restore"])
def test_monitor_on_logistics_with_the_default_distance(switch: str) -> None:
    prob = generate(SIZES["small"], 1)
    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=Person(2, _move_one_package), exogenous_prob=1.0)
    trace = Trace()
    with monitor_settings(MonitorConfig()):
        ex = Executive(prob, world, SymbolicBelief(prob.init), parse_strategy(f"flat+{switch}"), seed=1,
                       trace=trace)
    m = ex.run()
    mon = next(x for x in ex.mechanisms if isinstance(x, Monitor))
    assert m.outcome.value == "reached", m.reason
    assert LOGISTICS.satisfies(world.state, prob.goal)
    assert world.exogenous_events == 1 and mon.stats.surprises == 1
    assert sum(mon.stats.decisions.values()) == 1 and m.replans >= 1
    assert any(r["trigger"] == "monitor" for r in trace.of("replan"))


def test_only_tests_that_need_the_belief_refuse_the_monitor() -> None:
    """The monitor plans over States: a test reading what a State has not (AttributeError) refuses it;
    a test that works on States, or one that only fails on the probe's arguments (KeyError), does not."""
    from types import SimpleNamespace

    from nowplan.acting.monitor import _tests_not_on_states

    def odds(belief: object, args: tuple[object, ...], value: object) -> bool:
        return belief.probability(args) > 0.1  # type: ignore[attr-defined]

    def facts(belief: object, args: tuple[object, ...], value: object) -> bool:
        return isinstance(belief, State)

    def table(belief: object, args: tuple[object, ...], value: object) -> bool:
        return {("b",): True}[args]  # KeyError for the probe's first object

    preds = {n: SimpleNamespace(name=n, test=t, arg_types=("thing",), arity=1)
             for n, t in (("odds", odds), ("facts", facts), ("table", table), ("plain", None))}
    ex = SimpleNamespace(belief=SymbolicBelief(State({})), problem=SimpleNamespace(objects={"a": "thing", "b": "thing"}),
                         domain=SimpleNamespace(predicates=preds))
    assert _tests_not_on_states(ex) == ["odds"]  # type: ignore[arg-type]
