"""The incremental conjunction and regression of core/goal_index.py against a check of every pair.

Random consistent goals over a small vocabulary with a keyed rule (an object is at one place or in one
vehicle) and a pairwise rule (a free hand holds nothing), regressed through random steps one after
the other (so every goal after the first uses indexes derived from its parent's): each step's answer
(None, or the atoms) equals the reference's, which merges per fluent and then tests all pairs."""

from __future__ import annotations

from hypothesis import example, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom, Goal, Rules, Var, at_most_one, atom, conjoin, excludes
from nowplan.core.goal_index import regress_step

RULES = Rules(conflicts=(at_most_one("at", "in", key=0), excludes(atom("free", Var("h")), atom("holds", Var("h"), Var("o")))))
OBJS, PLACES = ("a", "b", "c"), ("p", "q", "r")
ATOM = st.one_of(
    st.builds(lambda o, p, v: Atom("at", (o, p), v), st.sampled_from(OBJS), st.sampled_from(PLACES), st.booleans()),
    st.builds(lambda o, p, v: Atom("in", (o, p), v), st.sampled_from(OBJS), st.sampled_from(PLACES), st.booleans()),
    st.builds(lambda h, v: Atom("free", (h,), v), st.sampled_from(("h1", "h2")), st.booleans()),
    st.builds(lambda h, o, v: Atom("holds", (h, o), v), st.sampled_from(("h1", "h2")), st.sampled_from(OBJS), st.booleans()),
)
STEP = st.tuples(st.lists(ATOM, max_size=3), st.lists(ATOM, max_size=3))


def clash(atoms: list[Atom]) -> bool:
    return any(x != y and RULES.atoms_conflict(x, y) for i, x in enumerate(atoms) for y in atoms[i + 1:])


def ref_conjoin(atoms: frozenset[Atom], extra: list[Atom]) -> frozenset[Atom] | None:
    table = {a.key: a for a in atoms}
    for a in extra:
        old = table.get(a.key)
        if old is not None and old.value != a.value:
            return None
        table[a.key] = a
    out = list(table.values())
    return None if clash(out) else frozenset(out)


def ref_regress(atoms: frozenset[Atom], effects: dict, pre: list[Atom]) -> frozenset[Atom] | None:
    rest = []
    for a in atoms:
        e = effects.get(a.key)
        if e is None:
            rest.append(a)
        elif e.value != a.value:
            return None
    effs = list(effects.values())
    if rest and any(x != y and RULES.atoms_conflict(x, y) for x in effs for y in effs + rest):
        return None
    return ref_conjoin(frozenset(rest), pre)


@settings(max_examples=300, deadline=None)
@given(st.lists(ATOM, max_size=6), st.lists(STEP, min_size=1, max_size=6))
# an atom an effect achieves leaves the goal, and with it its group: an earlier step may then put the
# object elsewhere
@example([Atom("at", ("a", "p"), True), Atom("at", ("b", "p"), True)], [([Atom("at", ("a", "p"), True)], []), ([Atom("in", ("a", "q"), True)], [])])
def test_regression_and_conjunction_match_the_full_check(start: list[Atom], steps: list[tuple[list[Atom], list[Atom]]]) -> None:
    g = conjoin(Goal(), start, RULES)
    want = ref_conjoin(frozenset(), start)
    assert (g is None) == (want is None)
    if g is None:
        return
    assert g.atoms == want
    for effs, pre in steps:
        effects = {e.key: e for e in effs}
        got = regress_step(g, effects, pre, RULES)
        ref = ref_regress(g.atoms, effects, pre)
        assert (got is None) == (ref is None), (g, effs, pre)
        if got is None:
            continue
        assert got.atoms == ref
        for a in got.atoms:  # its fluent index is the goal's
            assert got.get(a.key) == a
        joined = conjoin(got, pre + effs, RULES)  # conjunction on a derived goal
        ref_j = ref_conjoin(got.atoms, pre + effs)
        assert (joined is None) == (ref_j is None)
        if joined is not None:
            assert joined.atoms == ref_j
        g = got
