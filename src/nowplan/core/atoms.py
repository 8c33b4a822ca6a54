"""Terms, atoms (fluents with values) and goals (conjunctions of atoms).

An :class:`Atom` is ``predicate(args) = value``.  Boolean fluents use ``True``
and ``False`` (a negative literal is the atom with value ``False``); belief
fluents carry a value such as a tolerance: ``BVRelPose(A) = 0.01``.

Entailment and contradiction between atoms of the same fluent (same predicate
and arguments) are decided by a :class:`ValueRule` that the domain chooses per
predicate; conflicts between *different* fluents are domain rules too (see
:class:`Rules`).  Everything here is immutable and hashable.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable


@dataclass(frozen=True, order=True)
class Var:
    """A schema variable, written ``?name``."""

    name: str

    def __str__(self) -> str:
        return "?" + self.name


Term = Hashable
Bindings = Mapping[Var, Any]


def substitute(term: Term, bindings: Bindings) -> Term:
    """The value bound to ``term`` if it is a bound variable, else ``term``."""
    if isinstance(term, Var):
        value: Term = bindings.get(term, term)
        return value
    return term


def fmt_term(term: Term) -> str:
    if isinstance(term, float):
        return f"{term:g}"
    return str(term)


@dataclass(frozen=True, order=True)
class Atom:
    """``predicate(*args) = value``; ``value`` defaults to ``True``."""

    predicate: str
    args: tuple[Term, ...] = ()
    value: Any = True

    def __hash__(self) -> int:
        # kept once computed: the planners key dicts by atoms everywhere (the generated hash re-hashed
        # the three fields on every lookup: 8 % of a compiled regression search's CPU on logistics-10)
        h: int | None = self.__dict__.get("_hash")
        if h is None:
            h = hash((self.predicate, self.args, self.value))
            object.__setattr__(self, "_hash", h)
        return h

    def __reduce__(self) -> tuple[Any, ...]:
        return (Atom, (self.predicate, self.args, self.value))  # (not the kept hash: it is per process)

    @property
    def key(self) -> tuple[str, tuple[Term, ...]]:
        """The fluent this atom constrains (predicate and arguments)."""
        return (self.predicate, self.args)

    @property
    def ground(self) -> bool:
        return not any(isinstance(a, Var) for a in self.args) and not isinstance(self.value, Var)

    def bind(self, bindings: Bindings) -> Atom:
        # (substitute, inlined: every ground action binds its preconditions and effects with it)
        v = self.value
        return Atom(
            self.predicate,
            tuple([bindings.get(a, a) if isinstance(a, Var) else a for a in self.args]),
            bindings.get(v, v) if isinstance(v, Var) else v,
        )

    def negate(self) -> Atom:
        if not isinstance(self.value, bool):
            raise ValueError(f"only boolean atoms can be negated, not {self}")
        return Atom(self.predicate, self.args, not self.value)

    def __str__(self) -> str:
        body = f"{self.predicate}({', '.join(fmt_term(a) for a in self.args)})"
        if self.value is True:
            return body
        if self.value is False:
            return "not " + body
        return f"{body}={fmt_term(self.value)}"


def atom(predicate: str, *args: Term, value: Any = True) -> Atom:
    """Shorthand constructor: ``atom("at", "p1", "l2")``."""
    return Atom(predicate, tuple(args), value)


# --------------------------------------------------------------------------- rules


class ValueRule:
    """How values of one fluent relate: the default is plain equality."""

    def entails(self, have: Any, want: Any) -> bool:
        """Does the fluent having value ``have`` guarantee ``want``?"""
        return bool(have == want)

    def compatible(self, a: Any, b: Any) -> bool:
        """Can a goal ask for both values at once?"""
        return bool(a == b)

    def meet(self, a: Any, b: Any) -> Any:
        """The single value that entails both (only called when compatible)."""
        return a


class ToleranceRule(ValueRule):
    """Values are tolerances: a tighter (smaller) one entails a looser one."""

    def entails(self, have: Any, want: Any) -> bool:
        return bool(have <= want)

    def compatible(self, a: Any, b: Any) -> bool:
        return True

    def meet(self, a: Any, b: Any) -> Any:
        return min(a, b)


class AtLeastRule(ValueRule):
    """Values are lower bounds (e.g. a probability): a larger one entails a smaller."""

    def entails(self, have: Any, want: Any) -> bool:
        return bool(have >= want)

    def compatible(self, a: Any, b: Any) -> bool:
        return True

    def meet(self, a: Any, b: Any) -> Any:
        return max(a, b)


EQUALITY = ValueRule()

ConflictRule = Callable[[Atom, Atom], bool]


@runtime_checkable
class KeyedRule(Protocol):
    """A conflict rule that is "at most one true atom per key": checked in linear time, not pairwise.

    ``group_keys(atom)`` lists the atom's groups (empty: none); two different
    atoms sharing a group conflict.  :class:`AtMostOne` is one.
    """

    def group_keys(self, a: Atom) -> list[Any]: ...

    def __call__(self, a: Atom, b: Atom) -> bool: ...


KeyFn = Callable[[Atom], Hashable]


@dataclass(frozen=True)
class AtMostOne:
    """A conflict rule: at most one true atom of ``predicates`` per key.

    ``key`` says which atoms share a group: an argument index (``0``: per
    first argument), a tuple of indices (``()``: all the atoms of
    ``predicates`` form one group, e.g. "the robot is in one room"), or a
    function of the atom (``None``: the atom is in no group).
    ``AtMostOne(("at", "in"))`` says an object is at one place or in one
    vehicle at a time.  It exposes ``group_keys`` so goals are checked in
    linear time.  Write it with :func:`at_most_one` or :func:`exactly_one`.
    """

    predicates: tuple[str, ...]
    key: int | tuple[int, ...] | KeyFn = 0
    # exactly_one: a problem's initial state must also have one (checked by Problem)
    at_least_one: bool = False

    def key_of(self, a: Atom) -> Hashable | None:
        """The atom's group (``None``: in no group); ignores the atom's value."""
        if a.predicate not in self.predicates:
            return None
        k = self.key
        if isinstance(k, int):
            return a.args[k] if len(a.args) > k else None
        if isinstance(k, tuple):
            if any(i >= len(a.args) for i in k):
                return None
            return tuple(a.args[i] for i in k)
        return k(a)

    def group_keys(self, a: Atom) -> list[Any]:
        if a.value is not True:
            return []
        g = self.key_of(a)
        return [] if g is None else [(self.predicates, g)]

    def __call__(self, a: Atom, b: Atom) -> bool:
        ka, kb = self.group_keys(a), self.group_keys(b)
        return bool(ka) and ka == kb and a != b

    def __str__(self) -> str:
        name = "exactly_one" if self.at_least_one else "at_most_one"
        return f"{name}({', '.join(map(repr, self.predicates))}, key={self.key!r})"


def at_most_one(*predicates: str, key: int | tuple[int, ...] | KeyFn = 0) -> AtMostOne:
    """At most one true atom of these predicates per key (a conflict rule for ``Domain(conflicts=…)``).

    ``at_most_one("at", "holding", key=0)``: an item is at one place or held,
    not both; ``at_most_one("robot_in", key=())``: the robot is in one room;
    ``key=(0, 1)`` groups by the first two arguments; ``key=fn`` by
    ``fn(atom)`` (``None``: no group).  The planner prunes every subgoal
    that asks for two atoms of one group.
    """
    if not predicates:
        raise ValueError("at_most_one needs at least one predicate name")
    return AtMostOne(tuple(predicates), key)


def exactly_one(*predicates: str, key: int | tuple[int, ...] | KeyFn = 0) -> AtMostOne:
    """Like :func:`at_most_one`, and a problem's initial state must have one true atom per group.

    The groups checked are those one can list: with ``key=()`` the single
    group; with an argument index, every object of the type the predicates
    declare at that index (``Predicate.arg_types``).  A violating initial state
    is a :class:`nowplan.errors.ModelError` naming the group.
    """
    if not predicates:
        raise ValueError("exactly_one needs at least one predicate name")
    return AtMostOne(tuple(predicates), key, at_least_one=True)


def _match(pattern: Atom, a: Atom, bound: dict[Var, Any]) -> bool:
    """Extend ``bound`` so that ``pattern`` matches ``a`` (same predicate, args and value)."""
    if pattern.predicate != a.predicate or len(pattern.args) != len(a.args) or pattern.value != a.value:
        return False
    for p, x in zip(pattern.args, a.args, strict=True):
        if isinstance(p, Var):
            have = bound.setdefault(p, x)
            if have != x:
                return False
        elif p != x:
            return False
    return True


@dataclass(frozen=True)
class Excludes:
    """A conflict rule: an atom matching ``a`` and one matching ``b`` never hold together.

    Variables shared by the two patterns must take the same value:
    ``excludes(atom("hand_empty", h), atom("holding", h, o))`` says a free
    hand holds nothing.  Write it with :func:`excludes`.
    """

    a: Atom
    b: Atom

    def __call__(self, x: Atom, y: Atom) -> bool:
        bound: dict[Var, Any] = {}
        return _match(self.a, x, bound) and _match(self.b, y, bound)

    def __str__(self) -> str:
        return f"excludes({self.a}, {self.b})"


def excludes(a: Atom, b: Atom) -> Excludes:
    """``a`` and ``b`` (patterns; shared variables must agree) cannot hold together."""
    return Excludes(a, b)


@dataclass(frozen=True)
class Rules:
    """Fluent-specific entailment (per predicate) and cross-fluent conflict rules."""

    value_rules: Mapping[str, ValueRule] = field(default_factory=dict, hash=False, compare=False)
    conflicts: tuple[ConflictRule, ...] = field(default=(), hash=False, compare=False)

    def rule(self, predicate: str) -> ValueRule:
        return self.value_rules.get(predicate, EQUALITY)

    def atom_entails(self, have: Atom, want: Atom) -> bool:
        return have.key == want.key and self.rule(have.predicate).entails(have.value, want.value)

    def atoms_conflict(self, a: Atom, b: Atom) -> bool:
        if a.key == b.key:
            return not self.rule(a.predicate).compatible(a.value, b.value)
        return any(c(a, b) or c(b, a) for c in self.conflicts)


DEFAULT_RULES = Rules()


# --------------------------------------------------------------------------- goals


@dataclass(frozen=True)
class Goal:
    """A conjunction of ground atoms, kept with at most one atom per fluent."""

    atoms: frozenset[Atom] = frozenset()

    @staticmethod
    def of(atoms: Iterable[Atom], rules: Rules = DEFAULT_RULES) -> Goal:
        """Build a goal, merging atoms of the same fluent; raises if contradictory."""
        g = conjoin(Goal(), atoms, rules)
        if g is None:
            from nowplan.errors import ContradictoryGoalError

            bad = contradiction(list(atoms), rules)
            raise ContradictoryGoalError(
                f"goal is contradictory: {bad[0]} and {bad[1]} cannot both hold"
                if bad
                else "goal is contradictory"
            )
        return g

    def __iter__(self) -> Iterator[Atom]:
        return iter(sorted(self.atoms, key=_sort_key))

    def __len__(self) -> int:
        return len(self.atoms)

    def by_key(self) -> dict[tuple[str, tuple[Term, ...]], Atom]:
        return {a.key: a for a in self.atoms}

    def get(self, key: tuple[str, tuple[Term, ...]]) -> Atom | None:
        """The atom of fluent ``key``, if the goal constrains it (an index made on the first call)."""
        table: dict[tuple[str, tuple[Term, ...]], Atom] | None = self.__dict__.get("_by_key")
        if table is None:
            table = self.by_key()
            object.__setattr__(self, "_by_key", table)
        return table.get(key)

    def with_first(self, predicate: str, first: Term) -> tuple[Atom, ...]:
        """The atoms of ``predicate`` whose first argument is ``first`` (an index made on the first call)."""
        index: dict[tuple[str, Term], tuple[Atom, ...]] | None = self.__dict__.get("_by_first")
        if index is None:
            grouped: dict[tuple[str, Term], list[Atom]] = {}
            for a in self.atoms:
                if a.args:
                    grouped.setdefault((a.predicate, a.args[0]), []).append(a)
            index = {k: tuple(v) for k, v in grouped.items()}
            object.__setattr__(self, "_by_first", index)
        return index.get((predicate, first), ())

    def __str__(self) -> str:
        if not self.atoms:
            return "True"
        return " & ".join(str(a) for a in self)


def _sort_key(a: Atom) -> tuple[str, str, str]:
    return (a.predicate, repr(a.args), repr(a.value))


def atom_order(a: Atom) -> tuple[str, str, str]:
    """The key :meth:`Goal.__iter__` sorts a goal's atoms by (for callers that keep it per atom)."""
    return _sort_key(a)


TRUE = Goal()


def conjoin(goal: Goal, extra: Iterable[Atom], rules: Rules = DEFAULT_RULES) -> Goal | None:
    """``goal ∧ extra`` simplified per fluent, or ``None`` if contradictory: only the pairs that involve
    an atom of ``extra`` are checked, against the goal's indexes (:mod:`nowplan.core.goal_index`)."""
    return _goal_index.conjoin(goal, extra, rules)


def _keyed(rules: Rules) -> tuple[list[Any], list[ConflictRule], dict[Atom, tuple[Any, ...]]]:
    """Split conflict rules into keyed ones (with ``group_keys``) and plain pairwise ones, with a memo
    of each atom's keys under all the keyed ones (a key is a function of the atom alone).

    Kept per conflicts tuple (by identity): ``isinstance`` against the runtime-checkable
    protocol inspects attributes, and the pre-image computation asks at every regression step.
    """
    conflicts = rules.conflicts
    hit = _KEYED.get(id(conflicts))
    if hit is not None and hit[0] is conflicts:
        return hit[1], hit[2], hit[3]
    keyed = [c for c in conflicts if isinstance(c, KeyedRule)]
    plain = [c for c in conflicts if not isinstance(c, KeyedRule)]
    if len(_KEYED) >= 64:
        _KEYED.clear()
    memo: dict[Atom, tuple[Any, ...]] = {}
    _KEYED[id(conflicts)] = (conflicts, keyed, plain, memo)  # the tuple is kept, so its id is not reused
    return keyed, plain, memo


_KEYED: dict[int, tuple[tuple[ConflictRule, ...], list[Any], list[ConflictRule], dict[Atom, tuple[Any, ...]]]] = {}
# atoms whose keys one memo keeps before it is emptied (a bound on its memory)
_MAX_KEYS_MEMO = 200_000


def group_keys_of(a: Atom, keyed: list[Any], memo: dict[Atom, tuple[Any, ...]]) -> tuple[Any, ...]:
    """``a``'s group keys under the keyed rules of :func:`_keyed`, tagged by rule index (memoised)."""
    keys = memo.get(a)
    if keys is None:
        if len(memo) >= _MAX_KEYS_MEMO:
            memo.clear()
        keys = memo[a] = tuple((i, k) for i, rule in enumerate(keyed) for k in rule.group_keys(a))
    return keys


def _same_fluent_clash(atoms: list[Atom], rules: Rules) -> tuple[Atom, Atom] | None:
    table: dict[tuple[str, tuple[Term, ...]], Atom] = {}
    for a in atoms:
        old = table.get(a.key)
        if old is not None and not rules.rule(a.predicate).compatible(old.value, a.value):
            return (old, a)
        table[a.key] = a
    return None


def contradiction(
    atoms: list[Atom], rules: Rules = DEFAULT_RULES, new: Iterable[Atom] | None = None
) -> tuple[Atom, Atom] | None:
    """A pair of atoms that cannot hold together, or ``None``.

    With ``new``, only pairs involving one of the new atoms are checked by the
    pairwise rules, and same-fluent clashes are left to the caller (``conjoin``
    merges atoms of one fluent itself).  Conflict rules that
    expose ``group_keys(atom)`` (at most one true atom per key) are checked
    over all atoms in linear time.
    """
    keyed, plain, memo = _keyed(rules)
    if keyed:
        seen: dict[Any, Atom] = {}
        for a in atoms:
            keys = group_keys_of(a, keyed, memo)
            for k in keys:
                other = seen.get(k)
                if other is not None and other != a:
                    return (other, a)
                seen[k] = a
    if not plain:
        return _same_fluent_clash(atoms, rules) if new is None else None
    candidates = list(new) if new is not None else atoms
    for i, a in enumerate(candidates):
        rest = atoms if new is not None else atoms[i + 1 :]
        for b in rest:
            if a == b:
                continue
            if a.key == b.key:
                if not rules.rule(a.predicate).compatible(a.value, b.value):
                    return (a, b)
            elif any(c(a, b) or c(b, a) for c in plain):
                return (a, b)
    return None


def entails(strong: Goal, weak: Goal, rules: Rules = DEFAULT_RULES) -> bool:
    """Every state satisfying ``strong`` satisfies ``weak`` (syntactically)."""
    table = strong.by_key()
    for w in weak.atoms:
        s = table.get(w.key)
        if s is None or not rules.rule(w.predicate).entails(s.value, w.value):
            return False
    return True


from nowplan.core import goal_index as _goal_index  # noqa: E402  (it builds on the names above)
