"""``State`` against a plain dictionary model: the per-predicate store (core/state.py) answers every query
as a flat mapping of fluents would, after any sequence of effects, and equal states hash alike."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom
from nowplan.core.state import State

PREDS = ("p", "q", "r")
OBJS = ("a", "b", "c")
VALUES = st.sampled_from([True, False, 1, 2, "x"])
ATOM = st.builds(lambda p, args, v: Atom(p, args, v), st.sampled_from(PREDS),
                 st.tuples(st.sampled_from(OBJS)) | st.tuples(st.sampled_from(OBJS), st.sampled_from(OBJS)), VALUES)


def model_apply(m: dict, effects: list[Atom]) -> dict:
    out = dict(m)
    for e in effects:
        if e.value is False:
            out.pop(e.key, None)
        else:
            out[e.key] = e.value
    return out


def model_holds(m: dict, a: Atom) -> bool:
    have = m.get(a.key, False)
    if a.value is False:
        return have is False or have is None
    return have is not None and have is not False and have == a.value


@settings(max_examples=200, deadline=None)
@given(st.lists(ATOM, max_size=8), st.lists(st.lists(ATOM, max_size=4), max_size=6), st.lists(ATOM, max_size=6))
def test_state_matches_a_flat_model(init: list[Atom], steps: list[list[Atom]], probes: list[Atom]) -> None:
    s = State(init)
    hash(s)  # a known hash sum: apply then updates it per effect
    m = {a.key: a.value for a in init if a.value is not False}  # as the constructor reads its atoms
    states = [s]
    for effects in steps:
        s = s.apply(effects)
        m = model_apply(m, effects)
        states.append(s)
        fresh = State(m)  # the same fluents built at once
        assert s == fresh and hash(s) == hash(fresh)
        assert len(s) == len(m)
        for a in probes + effects:
            assert s.value(a.key) == m.get(a.key, False)
        want = [a for a in probes if not model_holds(m, a)]
        assert sorted(map(str, s.unmet(probes))) == sorted(map(str, want))
        assert s.count_holding(probes) == len(probes) - len(want)
        assert s.all_hold(probes) == (not want)
        for p in PREDS:
            assert sorted(s.facts(p)) == sorted(k[1] for k in m if k[0] == p)
        assert {(a.key, a.value) for a in s.atoms()} == set(m.items())
    for x in states:  # earlier states are not changed by later applications (immutability)
        for y in states:
            flat_x = {(a.key, a.value) for a in x.atoms()}
            flat_y = {(a.key, a.value) for a in y.atoms()}
            assert (x == y) == (flat_x == flat_y)
            assert x.differing(y) == len({k for k, _ in flat_x ^ flat_y})
