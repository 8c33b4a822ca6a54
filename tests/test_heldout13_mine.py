"""The held-out mine example (examples/mine) through the public API: a couple of seeded runs."""

from __future__ import annotations

import pytest

from nowplan.api import Outcome, parse_strategy, run_episode

from tests.helpers import example_spec


@pytest.mark.parametrize("seed", [0, 1])
def test_flat_finds_and_stores_the_gem_with_a_noisy_detector(monkeypatch: pytest.MonkeyPatch, seed: int) -> None:
    spec = example_spec(monkeypatch, "mine")
    m = run_episode(spec.scenario("noisy")(seed), parse_strategy("flat", max_actions=150), seed=seed)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True


def test_refine_flat_plans_concretely_when_the_root_step_refines_without_an_action(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """The mine's hierarchy (route and battery in one class) is not downward refinable: HPN's root
    step is refined again and again without an action (``dig`` seed 0: "no progress").  With
    refine-flat the executive plans that goal concretely instead of giving up."""
    spec = example_spec(monkeypatch, "mine")
    plain = run_episode(spec.scenario("dig")(0), parse_strategy("hpn+nofallback", max_actions=150), seed=0)
    assert plain.outcome is Outcome.FAILED and "no progress" in plain.reason
    assert "refine-flat" in plain.reason and "nofallback" in plain.reason  # the switches that go on
    m = run_episode(spec.scenario("dig")(0), parse_strategy("hpn+refine-flat", max_actions=150), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
    assert m.flat_fallbacks == 0  # refine-flat's own fallback, before the last resort


def test_plain_hpn_plans_the_goal_concretely_as_a_last_resort(monkeypatch: pytest.MonkeyPatch) -> None:
    """Without refine-flat, where HPN would end "no progress" the root goal is planned concretely
    once (FlatSteps.last_resort), and the run says so."""
    spec = example_spec(monkeypatch, "mine")
    m = run_episode(spec.scenario("dig")(0), parse_strategy("hpn", max_actions=150), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
    assert m.flat_fallbacks == 1
    assert "last resort: 1 root goal" in m.summary()


def test_a_livelock_of_the_abstract_plans_gets_the_last_resort(monkeypatch: pytest.MonkeyPatch) -> None:
    """``noisy`` seed 2 under RCHPN: a 14-action round (tow home, charge, gate, three moves, twice)
    the particle belief hides from the cycle count; the repeated-actions watch sees it after five
    rounds and the root goal is planned concretely (before: the 1,000-action budget, cost 4,694)."""
    spec = example_spec(monkeypatch, "mine")
    m = run_episode(spec.scenario("noisy")(2), parse_strategy("hpn+peephole", max_actions=300), seed=2)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
    assert m.flat_fallbacks == 1
    assert m.actions < 150
    off = run_episode(spec.scenario("noisy")(2), parse_strategy("hpn+peephole+nofallback", max_actions=300),
                      seed=2)
    assert off.outcome is not Outcome.REACHED and off.flat_fallbacks == 0


def test_refine_flat_plans_concretely_when_the_guard_sees_a_cycle_of_a_particle_belief(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """``dig`` seed 1: the abstract plans close the gate the goal wants shut, the next refinement
    opens it again, fails deeper and pops back, so the gate toggles.  The belief is a particle belief,
    which refine-flat's own symbolic-state count cannot see; the progress guard's cycle (its
    fingerprint and the stack's goals) now makes refine-flat plan the goal concretely (before: a
    livelock after 11 actions).  With the regression plans pruned (planning/prune.py) the plans no longer
    toggle the gate there (14 actions, no cycle): ``noprune`` keeps the scenario of this guard."""
    spec = example_spec(monkeypatch, "mine")
    m = run_episode(spec.scenario("dig")(1), parse_strategy("hpn+refine-flat+noprune", max_actions=150), seed=1)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
    assert m.cycles >= 1  # the fallback came from a cycle, not from the other two triggers


def test_a_step_backtracked_again_and_again_gets_the_last_resort(monkeypatch: pytest.MonkeyPatch) -> None:
    """Exogenous changes (the battery drains, the draught opens the gate) end every cycle and every
    repeated block the guard counts, so under RCHPN the abstract plans proposed the same unrefinable
    ``charge`` round after round until the 300-action budget (x0.2-m0.2-fp0.1, seed 3).  The same step
    backtracked 8 times with no goal atom gained is the last resort's cue.  (Pruned plans, planning/prune.py,
    reach the last resort there through the no-progress count instead: ``noprune`` keeps the scenario.)"""
    from nowplan.trace import Trace  # noqa: PLC0415

    example_spec(monkeypatch, "mine")
    from mine_domain.scenarios import episode  # noqa: PLC0415  (the benchmark's fault levels)

    tr = Trace()
    m = run_episode(episode(seed=3, exogenous_prob=0.2, miss=0.2, fp=0.1),
                    parse_strategy("hpn+peephole+noprune", max_actions=300), seed=3, trace=tr)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True and m.flat_fallbacks == 1
    notes = [e["text"] for e in tr.events if e["event"] == "note" and "last resort" in e["text"]]
    assert len(notes) == 1 and "could not be refined 8 times" in notes[0], notes


def test_the_last_resort_starts_the_guards_count_again(monkeypatch: pytest.MonkeyPatch) -> None:
    """``dig`` seed 0 under RCHPN: the gate toggled by plans whose ``charge`` never refines; the backtrack
    count takes the last resort one action before the repeated-actions watch would have ended the run.
    The concrete plans' first action must not complete the abstract plans' loop (before: a livelock
    after 18 actions with the last resort taken)."""
    spec = example_spec(monkeypatch, "mine")
    m = run_episode(spec.scenario("dig")(0), parse_strategy("hpn+peephole", max_actions=150), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True and m.flat_fallbacks == 1


def test_no_last_resort_where_the_domain_cannot_be_planned_flat() -> None:
    """Marsupial refuses the flat strategy (its loader is planned in the now): the last resort, which
    plans the root goal at the flat level, is not taken there, and the run ends as the seed's would."""
    from types import SimpleNamespace  # noqa: PLC0415

    from nowplan.acting.refine_flat import FlatSteps  # noqa: PLC0415
    from nowplan.domains.marsupial.model import UNSUPPORTED  # noqa: PLC0415

    assert "flat" in UNSUPPORTED
    root = SimpleNamespace(root=True)
    ex = SimpleNamespace(strategy=parse_strategy("hpn"), single_level=False, stack=[root],
                         domain=SimpleNamespace(unsupported=UNSUPPORTED))
    steps = FlatSteps()
    assert steps.last_resort(ex, "no progress") is False  # type: ignore[arg-type]
    assert steps.after_backtrack(ex, "k", "(travel)") is False  # type: ignore[arg-type]
    assert not steps.steps
    from nowplan.acting.refine_flat import flat_hint  # noqa: PLC0415

    ex.strategy, ex._flat_steps = parse_strategy("hpn+nofallback"), steps
    hint = flat_hint(ex, ("root", 1))  # type: ignore[arg-type]
    assert "downward refinable" in hint and "switch" not in hint  # no switch plans marsupial flat
