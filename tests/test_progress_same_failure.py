"""The same action failing the same way again and again is a stall, even while the belief drifts.

Found by a held-out domain (examples/drone, failure 0.5, gusts 0.5): the drone's position estimate
spreads a little every step, so its fingerprint never repeated; gusts (exogenous changes) came every
other step; the same flight was refused 114 times ("battery too low") until the action budget ended
the run, with no stated reason.
"""

from __future__ import annotations

from nowplan.acting.progress import CycleDetector, stall_reason
from nowplan.api import Observation, Operator, Var


def test_a_drifting_situation_with_the_same_failure_counts_as_a_stall() -> None:
    det = CycleDetector()
    det.start(("belief", 0))
    for i in range(1, 31):
        det.observe(("belief", i), succeeded=False, exogenous=i % 2 == 0, failure=("fly", "battery too low"))
    assert det.stalled == 29  # (the first failure has none before it to repeat)


def test_different_failures_or_a_success_restart_the_count() -> None:
    det = CycleDetector()
    det.start(("belief", 0))
    det.observe(("belief", 1), succeeded=False, exogenous=False, failure=("fly", "battery too low"))
    det.observe(("belief", 2), succeeded=False, exogenous=False, failure=("fly", "battery too low"))
    assert det.stalled == 1
    det.observe(("belief", 3), succeeded=False, exogenous=False, failure=("pick", "slipped"))
    assert det.stalled == 0
    det.observe(("belief", 4), succeeded=True, exogenous=False)
    det.observe(("belief", 5), succeeded=False, exogenous=False, failure=("pick", "slipped"))
    assert det.stalled == 0


def test_without_a_failure_key_only_an_unchanged_situation_stalls() -> None:
    det = CycleDetector()
    det.start("s")
    for i in range(5):
        det.observe(f"s{i}", succeeded=False, exogenous=False)
    assert det.stalled == 0
    for _ in range(5):
        det.observe("same", succeeded=False, exogenous=False)
    assert det.stalled == 4


def test_the_stall_reason_says_it_failed_the_same_way() -> None:
    fly = Operator("fly", (Var("a"),)).instantiate({Var("a"): "x"})
    why = stall_reason(25, fly, Observation(False, info={"reason": "battery too low"}))
    assert why.startswith("stalled: (fly x) failed 25 times in a row") and "the same way" in why
    assert "battery too low" in why


# -- a belief with neither a fingerprint nor a state -------------------------------------------------

class Blind:
    """A belief with values only: the guard cannot tell its situations apart."""

    def __init__(self) -> None:
        self.tries = 0

    def update(self, action: object, observation: object) -> None:
        self.tries += 1

    def value(self, key: object) -> object:
        return False


def test_a_belief_without_a_fingerprint_still_stalls_with_a_reason(caplog: object) -> None:
    import logging  # noqa: PLC0415

    import pytest  # noqa: PLC0415

    from nowplan.api import (  # noqa: PLC0415
        Domain, Episode, Goal, Outcome, Precondition, Predicate, Problem, SimulatedWorld, atom,
        parse_strategy, run_episode,
    )

    class Jammed(SimulatedWorld):
        def refuse(self, action: object) -> str | None:
            return "jammed"

        def apply(self, action: object) -> None:
            pass

    dom = Domain("jam", {"done": Predicate("done", 0), "ready": Predicate("ready", 0)},
                 (Operator("push", (), (Precondition(atom("ready", value=False), 1),), (atom("done"),)),))
    prob = Problem(dom, {}, None, Goal.of([atom("done")], dom.rules), "jam")
    assert isinstance(caplog, pytest.LogCaptureFixture)
    for strategy in ("hpn", "online"):
        with caplog.at_level(logging.WARNING):
            m = run_episode(Episode(prob, Jammed(), Blind(), "jammed"),
                            parse_strategy(strategy, max_actions=200), seed=0)
        assert m.outcome is Outcome.FAILED and m.reason.startswith("stalled: (push) failed 25 times"), m.reason
        assert "progress guard sees no cycles" in caplog.text


# -- a loop the fingerprints miss: the same actions over and over ------------------------------------

def test_the_same_block_of_actions_four_times_is_a_loop() -> None:
    from nowplan.acting.progress import RepeatedActions  # noqa: PLC0415

    r = RepeatedActions(repeats=4)
    seen = [r.observe(a, succeeded=True, exogenous=False, achieved=0) for a in ["go", "back"] * 4]
    assert seen[:-1] == [None] * 7 and seen[-1] == (2, ("go", "back"))
    assert RepeatedActions().repeats == 8  # the default: 16 moves back and forth


def test_a_long_block_needs_fewer_repeats_and_a_short_one_is_not_a_long_ones_loop() -> None:
    from nowplan.acting.progress import RepeatedActions  # noqa: PLC0415

    block = [f"a{i}" for i in range(14)]  # the mine's round: 14 actions
    r = RepeatedActions()
    assert r.needed(2) == 8 and r.needed(8) == 8 and r.needed(14) == 5 and r.needed(16) == 4
    seen = [r.observe(a, succeeded=True, exogenous=False, achieved=0) for a in block * 5]
    assert seen[:-1] == [None] * (14 * 5 - 1) and seen[-1] == (14, tuple(block))
    r = RepeatedActions()
    assert all(r.observe(a, succeeded=True, exogenous=False, achieved=0) is None for a in block * 4)
    r = RepeatedActions()  # seventeen actions: past the longest block watched
    long = [f"b{i}" for i in range(17)]
    assert all(r.observe(a, succeeded=True, exogenous=False, achieved=0) is None for a in long * 9)


def test_progress_a_failure_or_the_world_restart_the_watch() -> None:
    from nowplan.acting.progress import RepeatedActions  # noqa: PLC0415

    def run(events: list[tuple[str, bool, bool, int]]) -> object:
        r = RepeatedActions(repeats=4)
        out = None
        for a, ok, exo, achieved in events:
            out = r.observe(a, succeeded=ok, exogenous=exo, achieved=achieved) or out
        return out

    loop = [("go", True, False, 0), ("back", True, False, 0)]
    assert run(loop * 4) is not None
    assert run(loop * 2 + [("go", True, False, 1), ("back", True, False, 1)] + loop * 2) is None  # a goal atom
    assert run(loop * 2 + [("go", False, False, 0)] + loop * 2) is None  # a failure
    assert run(loop * 2 + [("go", True, True, 0)] + loop * 2) is None  # the world changed
    assert run([("look", True, False, 0)] * 12) is None  # one action again and again: looks that sharpen

