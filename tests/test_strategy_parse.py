"""Contradictory strategy switches are refused with a one-line reason (issue 14)."""

from __future__ import annotations

import pytest

from nowplan.acting.strategy import parse_strategy
from nowplan.errors import ScenarioError


@pytest.mark.parametrize(("spec", "message"), [
    ("flat+hpn", "'flat' and 'hpn' contradict"),
    ("hpn+aggressive+selective", "'aggressive' and 'selective' contradict"),
    ("hpn+monitor-goal+monitor-restore", "'monitor-goal' and 'monitor-restore' contradict"),
    ("online+aggressive", "'online' and 'aggressive' contradict"),
    ("hpn+flexible+flexible", "'flexible' is named twice"),
])
def test_contradictory_switches_are_refused(spec: str, message: str) -> None:
    with pytest.raises(ScenarioError, match=message):
        parse_strategy(spec)


@pytest.mark.parametrize("spec", [
    "hpn+flexible+serendipity+selective+foresight", "flat+flexible+serendipity", "online+reuse+deferred",
    "hpn+peephole+flexible", "hpn+aggressive", "hpn+monitor-rule-cost",
])
def test_the_papers_combinations_are_accepted(spec: str) -> None:
    assert parse_strategy(spec).switches == tuple(spec.split("+"))
