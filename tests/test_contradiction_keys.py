"""contradiction() over keyed conflict rules: keys are per rule, and remembered per atom (core/atoms.py)."""

from __future__ import annotations

from typing import Any

from nowplan.core.atoms import Atom, Rules, at_most_one, atom, contradiction
from nowplan.core.domain import Domain, Predicate
from nowplan.core.state import State


class SameKeys:
    """A keyed rule whose raw key is the atom's first argument (another rule may use the same keys)."""

    def __init__(self, predicate: str) -> None:
        self.predicate = predicate
        self.asked = 0

    def group_keys(self, a: Atom) -> list[Any]:
        self.asked += 1
        return [a.args[0]] if a.predicate == self.predicate and a.value is True else []

    def __call__(self, a: Atom, b: Atom) -> bool:
        return a != b and bool(self.group_keys(a)) and self.group_keys(a) == self.group_keys(b)


def test_equal_raw_keys_of_two_rules_do_not_clash() -> None:
    # "at(x, ...)" and "colour(x, ...)" each have one value per x, but an "at" and a "colour" of one x are fine
    at_rule, colour_rule = SameKeys("at"), SameKeys("colour")
    rules = Rules(conflicts=(at_rule, colour_rule))
    assert contradiction([atom("at", "x", "a"), atom("colour", "x", "red")], rules) is None
    clash = contradiction([atom("at", "x", "a"), atom("at", "x", "b")], rules)
    assert clash == (atom("at", "x", "a"), atom("at", "x", "b"))
    assert contradiction([atom("colour", "x", "red"), atom("colour", "x", "blue")], rules) is not None


def test_keys_are_asked_once_per_atom() -> None:
    rule = SameKeys("at")
    rules = Rules(conflicts=(rule,))
    atoms = [atom("at", f"o{i}", "a") for i in range(20)]
    assert contradiction(atoms, rules) is None
    first = rule.asked
    assert first == 20
    for _ in range(5):
        assert contradiction(atoms, rules) is None
    assert rule.asked == first  # the memo answered
    assert contradiction([*atoms, atom("at", "o3", "b")], rules) is not None
    assert rule.asked == first + 1  # only the new atom's keys were computed


def test_at_most_one_unchanged() -> None:
    rules = Rules(conflicts=(at_most_one("at", "in", key=0),))
    assert contradiction([atom("at", "p", "l1"), atom("in", "p", "t")], rules) is not None
    assert contradiction([atom("at", "p", "l1"), atom("in", "q", "t")], rules) is None
    assert contradiction([atom("at", "p", "l1", value=False), atom("in", "p", "t")], rules) is None


def test_unmet_is_what_holds_says() -> None:
    d = Domain(name="d", predicates={"on": Predicate("on", 1), "lvl": Predicate("lvl", 1)}, operators={})
    s = State([atom("on", "a"), atom("lvl", "a", value=2)])
    asked = [atom("on", "a"), atom("on", "b"), atom("on", "b", value=False), atom("on", "a", value=False),
             atom("lvl", "a", value=2), atom("lvl", "a", value=3), atom("lvl", "b", value=False)]
    want = [a for a in asked if not d.holds(a, s)]
    assert d.unmet(s, asked) == want == [atom("on", "b"), atom("on", "a", value=False), atom("lvl", "a", value=3)]
