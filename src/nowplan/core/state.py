"""A symbolic (fully known) state: a mapping from fluents to values.

Boolean fluents are closed-world: a fluent that is absent is ``False``.  A
state is immutable; :meth:`State.apply` returns a new one.  Belief states of
other kinds need not subclass this: the planner only asks a belief to *test*
atoms (through the domain's predicates) and, for static predicates, to list
the true facts of a predicate when it can (:meth:`State.facts`).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from typing import Any

from nowplan.core.atoms import Atom, Term

Key = tuple[str, tuple[Term, ...]]
_MASK = (1 << 64) - 1


class State:
    """An immutable assignment of values to fluents (closed world for booleans).

    The fluents are kept per predicate (predicate -> argument tuple -> value), so :meth:`apply` copies
    only the predicates its effects touch: the static facts of a PDDL problem (thousands of them) are
    shared by every state of a run, not copied, hashed or traversed by the garbage collector again
    after each action (a 150-floor miconic run: 11.8k fluents, of which the actions touch a few)."""

    __slots__ = ("_map", "_hash", "_sum", "_by_pred", "_atoms")

    def __init__(self, values: Mapping[Key, Any] | Iterable[Atom] = ()) -> None:
        m: dict[str, dict[tuple[Term, ...], Any]] = {}
        pairs = values.items() if isinstance(values, Mapping) else ((a.key, a.value) for a in values)
        for (p, args), v in pairs:
            if v is not False:
                inner = m.get(p)
                if inner is None:
                    inner = m[p] = {}
                inner[args] = v
        self._map = m  # no False values, no empty inner mapping: equal states have equal maps
        self._hash: int | None = None
        # the sum of the fluents' hashes (mod 2**64), once known: :meth:`apply` updates it per
        # effect, so a run's states (hashed after every action) are not rehashed fluent by fluent
        self._sum: int | None = None
        self._by_pred: dict[str, list[tuple[Term, ...]]] | None = None
        self._atoms: tuple[Atom, ...] | None = None

    # -- queries -------------------------------------------------------------
    def value(self, key: Key) -> Any:
        """The fluent's value; ``False`` when absent (closed world)."""
        inner = self._map.get(key[0])
        return False if inner is None else inner.get(key[1], False)

    def holds(self, a: Atom) -> bool:
        return bool(self.value(a.key) == a.value)

    def count_holding(self, atoms: Iterable[Atom]) -> int:
        """How many of ``atoms`` hold here under plain truth (as :meth:`all_hold`, atom by atom)."""
        get = self._map.get
        n = 0
        for a in atoms:
            inner = get(a.predicate)
            have = False if inner is None else inner.get(a.args, False)
            if a.value is False:
                n += have is False or have is None
            else:
                n += not (have is None or have is False or not have == a.value)
        return n

    def unmet(self, atoms: Iterable[Atom]) -> list[Atom]:
        """The atoms that do not hold here under plain truth (as :meth:`all_hold`, atom by atom)."""
        get = self._map.get
        out = []
        for a in atoms:
            inner = get(a.predicate)
            have = False if inner is None else inner.get(a.args, False)
            if a.value is False:
                if have is not False and have is not None:
                    out.append(a)
            elif have is None or have is False or not have == a.value:
                out.append(a)
        return out

    def all_hold(self, atoms: Iterable[Atom]) -> bool:
        """Every atom holds here under plain truth (no tests, equality rules): what ``Domain.holds``
        answers atom by atom, with two dictionary lookups each (``Domain.satisfies`` asks it)."""
        get = self._map.get
        for a in atoms:
            inner = get(a.predicate)
            have = False if inner is None else inner.get(a.args, False)
            if a.value is False:
                if have is not False and have is not None:
                    return False
            elif have is None or have is False or not have == a.value:
                return False
        return True

    def facts(self, predicate: str) -> list[tuple[Term, ...]]:
        """Argument tuples of the true (non-False) fluents of ``predicate``."""
        if self._by_pred is None:
            self._by_pred = {}
        out = self._by_pred.get(predicate)
        if out is None:
            out = self._by_pred[predicate] = list(self._map.get(predicate, ()))
        return out

    def differing(self, other: State) -> int:
        """How many fluents have different values here and in ``other`` (absent = False)."""
        n = 0
        empty: dict[tuple[Term, ...], Any] = {}
        for p in self._map.keys() | other._map.keys():
            mine, theirs = self._map.get(p, empty), other._map.get(p, empty)
            if mine is not theirs:
                n += len({k for k, _ in mine.items() ^ theirs.items()})
        return n

    def _items(self) -> Iterator[tuple[Key, Any]]:
        for p, inner in self._map.items():
            for args, v in inner.items():
                yield (p, args), v

    def atoms(self) -> Iterator[Atom]:
        """The true fluents as atoms, sorted by predicate and arguments (made once: a state is immutable)."""
        if self._atoms is None:
            self._atoms = tuple(Atom(p, args, v) for (p, args), v in
                                sorted(self._items(), key=lambda kv: (kv[0][0], repr(kv[0][1]))))
        return iter(self._atoms)

    # -- updates -------------------------------------------------------------
    def apply(self, effects: Iterable[Atom]) -> State:
        m = dict(self._map)  # the outer mapping only; an inner one is copied when an effect first touches it
        copied: set[str] = set()
        total = self._sum
        for e in effects:
            p, args = e.predicate, e.args
            inner = m.get(p)
            if inner is None:
                if e.value is False:
                    continue
                inner = m[p] = {}
                copied.add(p)
            elif p not in copied:
                inner = m[p] = dict(inner)
                copied.add(p)
            if total is not None and args in inner:
                total -= hash(((p, args), inner[args]))
            if e.value is False:
                inner.pop(args, None)
                if not inner:
                    del m[p]
                    copied.discard(p)
            else:
                inner[args] = e.value
                if total is not None:
                    total += hash(((p, args), e.value))
        out = State.__new__(State)  # (no False values in ``m``: the constructor's filter is not needed)
        out._map = m
        out._hash = None
        out._sum = None if total is None else total & _MASK
        out._by_pred = None
        out._atoms = None
        return out

    # -- protocol ------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        return isinstance(other, State) and self._map == other._map

    def __hash__(self) -> int:
        if self._hash is None:
            if self._sum is None:
                # a sum of the fluents' hashes: the same for equal states, updated per effect by apply
                self._sum = sum(map(hash, self._items())) & _MASK
            self._hash = hash(self._sum)
        return self._hash

    def __len__(self) -> int:
        return sum(map(len, self._map.values()))

    def __repr__(self) -> str:
        return "State({" + ", ".join(str(a) for a in self.atoms()) + "})"
