"""Static facts the world changes (acting/static_watch.py): the executive notices them and replans.

The held-out ferry (examples/ferry): a passenger's destination ``wants`` is changed by no operator,
so it is static and left out of every pre-image, yet passengers change their minds (exogenous, seen).
"""

from __future__ import annotations

import pytest

from nowplan.acting.static_watch import StaticWatch, describe
from nowplan.api import Outcome, parse_strategy, run_episode
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.state import State
from nowplan.trace import Trace

from tests.helpers import example_spec


def _ferry(monkeypatch: pytest.MonkeyPatch):  # noqa: ANN202
    example_spec(monkeypatch, "ferry")
    from ferry_domain.scenarios import episode  # noqa: PLC0415

    return episode


def test_the_watch_names_the_static_facts_an_exogenous_change_made(monkeypatch: pytest.MonkeyPatch) -> None:
    episode = _ferry(monkeypatch)
    ep = episode(seed=0)
    watch = StaticWatch(ep.problem.domain, ep.belief)
    assert "wants" in watch.predicates and "lane" in watch.predicates
    assert "boat_at" not in watch.predicates  # operators change it: its atoms are in the pre-images
    (who, dock), = [w for w in ep.belief.facts("wants") if str(w[0]) == "p1"]
    other = next(d for d in ("harbor", "pier", "cove", "isle") if d != str(dock))
    from nowplan.api import atom  # noqa: PLC0415

    moved = SymbolicBelief(ep.belief.state.apply([atom("wants", who, dock, value=False), atom("wants", who, other)]))
    assert watch.changed(moved, exogenous=False) == []  # no change reported: not looked at
    changed = watch.changed(moved, exogenous=True)
    assert {("wants", ("p1", str(dock))), ("wants", ("p1", other))} == {(p, tuple(map(str, a))) for p, a in changed}
    assert describe(changed) in (f"wants(p1, {dock}), wants(p1, {other})", f"wants(p1, {other}), wants(p1, {dock})")
    assert watch.changed(moved, exogenous=True) == []  # seen now


def test_a_valued_static_fluent_that_changes_its_value_is_seen() -> None:
    from nowplan.api import Domain, Operator, Precondition, Predicate, Var, atom  # noqa: PLC0415

    x = Var("x")
    dom = Domain("valued", {"mode": Predicate("mode", 0), "done": Predicate("done", 1)},
                 (Operator("do", (x,), (Precondition(atom("mode", value="fast"), 1),), (atom("done", x),)),))
    watch = StaticWatch(dom, SymbolicBelief(State([atom("mode", value="fast")])))
    assert watch.predicates == ("mode",)
    assert watch.changed(SymbolicBelief(State([atom("mode", value="slow")])), exogenous=True) == [("mode", ())]


def test_describe_names_three_and_counts_the_rest() -> None:
    assert describe([("a", ()), ("b", ("x",))]) == "a(), b(x)"
    assert describe([(f"f{i}", ()) for i in range(5)]) == "f0(), f1(), f2() and 2 more"


def test_a_changed_mind_is_replanned_for_not_retried_until_the_stall_guard(monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: under RCHPN the stale ``alight`` (the pre-image before it still held, since no
    pre-image names ``wants``) was chosen again and again until "stalled: ... failed 25 times"."""
    episode = _ferry(monkeypatch)
    for seed in (2, 3):
        tr = Trace()
        m = run_episode(episode(seed=seed, exogenous_prob=0.2, balk=0.1), parse_strategy("hpn+peephole", max_actions=300),
                        seed=seed, trace=tr)
        assert m.outcome is Outcome.REACHED, (seed, m.reason)
        assert m.goal_in_world is True
        notes = [e["text"] for e in tr.events if e["event"] == "note" and "static fact" in e["text"]]
        assert notes and "wants(" in notes[0]


@pytest.mark.parametrize("strategy", ["flat", "hpn"])
def test_no_step_is_run_on_a_destination_given_up(monkeypatch: pytest.MonkeyPatch, strategy: str) -> None:
    """Every strategy ran a stale ``alight`` once after a change of mind it had seen: now each of the
    four passengers gets off once, and no action fails (no balking, no faults)."""
    episode = _ferry(monkeypatch)
    for seed in range(3):
        m = run_episode(episode(seed=seed, exogenous_prob=0.15), parse_strategy(strategy, max_actions=300), seed=seed)
        assert m.outcome is Outcome.REACHED, (strategy, seed, m.reason)
        assert m.action_counts["alight"] == 4 and m.failed_actions == 0, (strategy, seed, m.action_counts)
