"""``FactTable.plain_clash`` (kept per fact as sets) answers as asking every pair does."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom, Rules, atom
from nowplan.core.facts import FactTable


def _rule(a: Atom, b: Atom) -> bool:
    """A plain (pairwise) conflict: p(i) excludes q(j) when i + j is odd, and r(i) excludes p(i)."""
    if a.predicate == "p" and b.predicate == "q":
        return (int(a.args[0]) + int(b.args[0])) % 2 == 1
    return a.predicate == "r" and b.predicate == "p" and a.args == b.args


ATOMS = [atom(p, str(i)) for p in ("p", "q", "r") for i in range(5)]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(st.integers(0, len(ATOMS) - 1), st.sets(st.integers(0, len(ATOMS) - 1)),
                          st.sets(st.integers(0, len(ATOMS) - 1))), min_size=1, max_size=12))
def test_plain_clash_is_the_pairwise_answer(asks: list[tuple[int, set[int], set[int]]]) -> None:
    table = FactTable(Rules(conflicts=(_rule,)))
    ids = [table.id(a) for a in ATOMS]
    for e, fs, removed in asks:  # one table for all asks: the kept sets must stay right between them
        f = frozenset(ids[i] for i in fs)
        rem = {ids[i] for i in removed}
        want = any(table.plain_conflict(r, ids[e]) for r in f if r not in rem)
        assert table.plain_clash(ids[e], f, rem) is want
