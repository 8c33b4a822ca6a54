"""Automatic criticalities: Knoblock's ordered-monotonic abstraction hierarchies.

ALPINE (Knoblock 1994, "Automatically generating abstractions for planning",
AIJ 68) orders the *literals* of a domain so that refining an abstract plan
never changes a literal of a more abstract level.  This module derives such a
hierarchy from the domain alone (no problem, no goal) and turns it into
HPN criticalities (seed 002 II-B).

**Literal classes.**  Literals are grouped by predicate *and* argument types:
in typed logistics ``at(?pkg - package, ?loc)`` and ``at(?truck - truck,
?loc)`` are different classes, which is what lets packages sit above
vehicles.  An argument's type is the operator parameter's declared type (or a
constant's type; ``None`` = ``object``).  Two classes of one predicate whose
types overlap position by position (one type a subtype of the other) could
match the same ground atom, so they are merged: every ground atom belongs to
at most one class.  An untyped parameter is typed by the static unary predicates
its operator requires of it (``[truck]`` for ``(truck ?t)``,
:mod:`nowplan.planning.type_predicates`); without those either, the classes are
the predicates.

**Constraints** (Knoblock's problem-independent restriction).  For every
operator, every effect class ``e`` (added or deleted) that the operator can
change (an effect whose fluent ends at the value a precondition requires, as
rovers' ``communicate`` deletes and re-adds ``(available ?r)``, changes
nothing and constrains nothing: :func:`changing_effects`) and

* every other effect class ``e'`` of the operator: ``level(e) >= level(e')``
  (so all effects of an operator share one level), and
* every precondition class ``p`` (positive or negative) that is not static:
  ``level(e) >= level(p)``.

Static predicates and static classes (no operator changes them, e.g. ``at``
of a hoist in depots) are left out: nothing can change them, so they are
checked at every level (criticality = the top).
The constraint graph's strongly connected components must share a level;
the component DAG is layered bottom-up (a component with no constraint
below it is level 0, else one above the highest component it must dominate),
which gives as many levels as the longest chain of components.

**What this guarantees** (ordered monotonicity, Knoblock's Theorem): every
operator that changes a literal of level ``k`` changes only literals of level
``k`` and has preconditions of level ``<= k`` only.  So when a plan at level
``i`` is refined by inserting operators to achieve conditions of level
``< i`` (and, transitively, those operators' preconditions), no inserted
operator changes a literal of level ``>= i``: the refinement leaves the
abstract plan's literals as they were.  It does *not* guarantee that an
abstract plan can be refined (Knoblock's hierarchies lack the downward
refinement property): in IPC logistics the top level may load a package into
a truck of another city.  The executive's ``refine-flat`` switch handles that
(see :mod:`nowplan.acting.hpn`).

**Criticalities.**  HPN keeps every operator at every level and drops
preconditions (``abs(op, i)`` keeps criticality ``> i``), where ALPINE drops
the literals of lower levels everywhere.  For an operator ``o`` whose effects
are at level ``k``, a precondition at level ``j < k`` gets criticality
``j + 1`` (kept in ``abs(o, i)`` for ``i <= j``), and a precondition at ``o``'s
own level ``k`` or a static one gets the largest criticality ``top + 1``
(always kept).  So ``abs(o, i)`` for ``i <= k`` is ALPINE's operator at level
``i``, and above ``k`` ``o`` still needs its own level's preconditions:
refining a step only ever reveals conditions strictly below the level of its
effects, and a plan for them never needs an operator with fewer
preconditions than ALPINE's (with ``level + 1`` for every precondition, a
``drive`` at the top level would need its start position refined by another
abstract ``drive``, without end).  For logistics this gives exactly the
hand-written ``logistics.crit``.  One level only (e.g. blocksworld, where
every predicate is tied to every other) means a flat domain.

**Derived predicates** (rules, ``Domain.axioms``) are set by no operator: a
derived atom is a function of the basic literals its rules read, directly or
through other derived predicates.  An operator with a derived precondition
reads those literals, so the constraints treat it as a precondition on each of
them, and the derived predicate sits at the highest level of what it reads
(``Hierarchy.derived``; ``None``, kept at every level, when it reads static
literals only).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field, replace

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.core.operators import Operator, Precondition
from nowplan.planning.graphs import UnionFind, sccs
from nowplan.planning.type_predicates import is_type_set, may_overlap, type_set


TypeName = str | None
Meets = Callable[[str, str], bool]  # can one object be of both type sets?


@dataclass(frozen=True, order=True)
class LiteralClass:
    """A predicate with the types of its arguments (``None``: any object)."""

    predicate: str
    types: tuple[str, ...]  # "" for object/None, so classes sort

    def __str__(self) -> str:
        if not self.types:
            return self.predicate
        return f"{self.predicate}({', '.join(t or 'object' for t in self.types)})"


@dataclass(frozen=True)
class Hierarchy:
    """An ordered-monotonic hierarchy: a level per literal class, and the statics."""

    domain: str
    levels: Mapping[LiteralClass, int]  # representative class -> level (0 = most concrete)
    members: Mapping[LiteralClass, LiteralClass]  # every class -> its representative
    static: frozenset[str]  # predicates no operator changes
    edges: frozenset[tuple[LiteralClass, LiteralClass]]  # (e, p): level(e) >= level(p)
    # derived predicate -> the highest level of the basic literals its rules read (None: static ones only)
    derived: Mapping[str, int | None] = field(default_factory=dict)
    type_sets: bool = False  # untyped parameters typed by static unary predicates (planning/type_predicates.py)

    @property
    def top(self) -> int:
        """The number of levels - 1 (0: flat)."""
        return max(self.levels.values(), default=0)

    def level_of(self, domain: Domain, op: Operator, atom: Atom) -> int | None:
        """The level of ``atom`` (in ``op``); ``None`` for a static predicate."""
        if atom.predicate in self.static:
            return None
        if atom.predicate in self.derived:
            return self.derived[atom.predicate]
        return self.levels.get(self.members[literal_class(domain, op, atom, self.type_sets)])  # None: static

    def effect_level(self, domain: Domain, op: Operator) -> int | None:
        """The one level of the effects ``op`` can change (``None`` without any: :func:`changing_effects`)."""
        return max((self.level_of(domain, op, e) or 0 for e in changing_effects(op)), default=None)

    def criticality(self, domain: Domain, op: Operator, atom: Atom) -> int:
        """``top + 1`` for a static precondition, one at the level of ``op``'s effects or one of an
        operator that changes nothing, else level + 1."""
        lvl = self.level_of(domain, op, atom)
        k = self.effect_level(domain, op)
        if lvl is None or k is None or lvl == k:
            return self.top + 1
        return lvl + 1

    def by_level(self) -> dict[int, list[LiteralClass]]:
        """Level -> the classes at that level (merged classes listed once each)."""
        out: dict[int, list[LiteralClass]] = {}
        for c, rep in sorted(self.members.items()):
            if rep in self.levels:
                out.setdefault(self.levels[rep], []).append(c)
        return out

    def static_classes(self) -> list[LiteralClass]:
        """Classes of changing predicates that no operator changes (e.g. ``at`` of a hoist)."""
        return sorted(c for c, rep in self.members.items() if rep not in self.levels)


# --------------------------------------------------------------------------- classes


def _type_name(domain: Domain, op: Operator, term: object, type_sets: bool) -> TypeName:
    if isinstance(term, Var):
        t = op.type_of(term) if term in op.params else None
        if type_sets and t in (None, "object") and term in op.params:
            return type_set(domain, op, term) or None
        return t
    if isinstance(term, str):
        return domain.constants.get(term)
    return None


def literal_class(domain: Domain, op: Operator, atom: Atom, type_sets: bool = False) -> LiteralClass:
    """The (unmerged) class of a precondition or effect of ``op`` (``type_sets``: an untyped parameter
    is typed by the static unary predicates ``op`` requires of it, :mod:`nowplan.planning.type_predicates`)."""
    return LiteralClass(atom.predicate, tuple(_type_name(domain, op, a, type_sets) or "" for a in atom.args))


def _overlap(domain: Domain, a: str, b: str, meets: Meets | None = None) -> bool:
    """Can one object have both types?  (Single inheritance: one is an ancestor of the other; type sets:
    one a subset of the other; a type set and a declared type: assumed so.)"""
    if not a or not b or a == b:
        return True
    if is_type_set(a) or is_type_set(b):
        if not (is_type_set(a) and is_type_set(b)):
            return True
        return may_overlap(a, b) if meets is None else meets(a, b)
    return b in domain.subtypes(a) or a in domain.subtypes(b)


def _classes_overlap(domain: Domain, x: LiteralClass, y: LiteralClass, meets: Meets | None) -> bool:
    return x.predicate == y.predicate and all(
        _overlap(domain, a, b, meets) for a, b in zip(x.types, y.types, strict=True)
    )


def changing_effects(op: Operator) -> tuple[Atom, ...]:
    """The effects of ``op`` that can change their fluent: all but those whose fluent ends at the value a
    precondition requires of it (the last effect on a fluent wins, as in ``State.apply``; PDDL stores
    deletes first, so rovers' ``(not (available ?r)) ... (available ?r)`` under ``(available ?r)`` is
    no change).  Such an effect restates a precondition, so it constrains no level."""
    final = {(e.predicate, e.args): e.value for e in op.effects}
    required = {(p.atom.predicate, p.atom.args): p.atom.value for p in op.preconditions}
    return tuple(e for e in op.effects
                 if (e.predicate, e.args) not in required or required[(e.predicate, e.args)] != final[(e.predicate, e.args)])


def _operator_literals(domain: Domain, op: Operator, type_sets: bool) -> Iterator[LiteralClass]:
    for p in op.preconditions:
        yield literal_class(domain, op, p.atom, type_sets)
    for e in op.effects:
        yield literal_class(domain, op, e, type_sets)


# --------------------------------------------------------------------------- graph


def derive_hierarchy(domain: Domain, type_sets: bool = True) -> Hierarchy:
    """Knoblock's problem-independent ordered-monotonic hierarchy of ``domain`` (see the module doc).

    Kept per operators and types (by identity, the last few): ``--criticality auto`` asks it when
    loading and again in ``prepare_problem``, for copies of the domain with the same literals (the
    criticalities it sets and the mutexes inferred later play no part in it); a tenth of a small
    problem's whole run (rovers p05: 2 of 17 ms).  :func:`apply_hierarchy` files the hierarchy under
    the operators it makes too.  ``type_sets``: untyped parameters are typed by the static unary
    predicates their operator requires of them (``(truck ?t)``), taken as disjoint
    (:mod:`nowplan.planning.type_predicates`; ``prepare_problem`` checks a problem's objects)."""
    hit = _HIERARCHIES.get((id(domain.operators), type_sets))
    if hit is not None and hit[0] is domain.operators and hit[1] is domain.types:
        return hit[2]
    out = _derive_hierarchy(domain, type_sets)
    _keep(domain.operators, domain.types, out, type_sets)
    return out


# the last hierarchies derived: (operators, types, hierarchy) by the operators' id and the type-sets
# flag asked for (the tuple is kept, so its id is not reused while the entry lives)
_HIERARCHIES: dict[tuple[int, bool], tuple[tuple[Operator, ...], Mapping[str, str | None], Hierarchy]] = {}


def _keep(ops: tuple[Operator, ...], types: Mapping[str, str | None], hierarchy: Hierarchy, asked: bool) -> None:
    if len(_HIERARCHIES) >= 16:
        _HIERARCHIES.pop(next(iter(_HIERARCHIES)))
    _HIERARCHIES[(id(ops), asked)] = (ops, types, hierarchy)


def _derived_dependencies(domain: Domain) -> dict[str, set[tuple[Operator, Atom]]]:
    """Per derived predicate, the basic non-static literals (with the rule that reads each) its rules
    read, directly or through other derived predicates."""
    static, derived = domain.static_predicates, domain.derived
    direct: dict[str, set[tuple[Operator, Atom]]] = {d: set() for d in derived}
    uses: dict[str, set[str]] = {d: set() for d in derived}
    for rule in domain.axioms:
        head = rule.effects[0].predicate
        for p in rule.preconditions:
            q = p.atom.predicate
            if q in derived:
                uses[head].add(q)
            elif q not in static and q != "=":
                direct[head].add((rule, p.atom))
    out: dict[str, set[tuple[Operator, Atom]]] = {}
    for d in derived:  # the closure over the uses (a bounded walk: each predicate is seen once)
        seen, todo, acc = {d}, [d], set(direct[d])
        while todo:
            for q in uses[todo.pop()]:
                if q not in seen:
                    seen.add(q)
                    todo.append(q)
                    acc |= direct[q]
        out[d] = acc
    return out


def merged_hierarchy(domain: Domain, meets: Meets) -> Hierarchy:
    """The hierarchy with type sets where ``meets(a, b)`` says whether type sets ``a`` and ``b`` share an
    object (:func:`nowplan.planning.problem_hierarchy.problem_hierarchy`: a problem's objects)."""
    return _derive_hierarchy(domain, True, meets)


def _derive_hierarchy(domain: Domain, type_sets: bool, meets: Meets | None = None) -> Hierarchy:
    static = domain.static_predicates
    derived = domain.derived
    # a derived precondition stands for the basic literals its rules read: an operator reading it reads them
    deps = _derived_dependencies(domain)
    dep_classes = {d: {literal_class(domain, rule, a, type_sets) for rule, a in xs} for d, xs in deps.items()}
    raw = sorted({c for op in domain.operators for c in _operator_literals(domain, op, type_sets)
                  if c.predicate not in derived}
                 | {c for cs in dep_classes.values() for c in cs})
    uf = UnionFind(raw)
    by_pred: dict[str, list[LiteralClass]] = {}
    for c in raw:
        by_pred.setdefault(c.predicate, []).append(c)
    for group in by_pred.values():
        for i, x in enumerate(group):
            for y in group[i + 1:]:
                if _classes_overlap(domain, x, y, meets):
                    uf.union(x, y)
    members = {c: uf.find(c) for c in raw if c.predicate not in static}
    # classes no operator changes are static too (checked at every level), like static predicates
    reps = sorted({members[literal_class(domain, op, e, type_sets)] for op in domain.operators
                   for e in changing_effects(op)})
    succ: dict[LiteralClass, set[LiteralClass]] = {r: set() for r in reps}
    edges: set[tuple[LiteralClass, LiteralClass]] = set()
    for op in domain.operators:
        effs = [members[literal_class(domain, op, e, type_sets)] for e in changing_effects(op)]
        pres = [r for p in op.preconditions if p.atom.predicate not in static and p.atom.predicate not in derived
                for r in [members[literal_class(domain, op, p.atom, type_sets)]] if r in succ]
        pres += [r for p in op.preconditions if p.atom.predicate in derived
                 for r in sorted({members[c] for c in dep_classes[p.atom.predicate]}) if r in succ]
        for e in effs:
            for other in [*effs, *pres]:
                if other != e:
                    succ[e].add(other)
                    edges.add((e, other))
    comps = sccs(reps, succ)
    comp_of = {c: i for i, comp in enumerate(comps) for c in comp}
    # Tarjan emits a component after every component it reaches: layering in emission order
    comp_level: list[int] = []
    for i, comp in enumerate(comps):
        below = {comp_of[w] for v in comp for w in succ[v]} - {i}
        comp_level.append(1 + max((comp_level[j] for j in below), default=-1))
    levels = {c: comp_level[comp_of[c]] for c in reps}
    derived_levels = {d: max((levels[members[c]] for c in cs if members[c] in levels), default=None)
                      for d, cs in dep_classes.items()}
    if type_sets and not any(is_type_set(t) for c in raw for t in c.types):
        type_sets = False  # no untyped parameter has a type predicate: the hierarchy without type sets
    return Hierarchy(domain.name, levels, members, static, frozenset(edges), derived_levels, type_sets)


def apply_hierarchy(domain: Domain, hierarchy: Hierarchy) -> Domain:
    """A copy of ``domain`` whose preconditions carry the hierarchy's criticalities."""
    ops = tuple(
        replace(op, preconditions=tuple(
            Precondition(p.atom, hierarchy.criticality(domain, op, p.atom)) for p in op.preconditions
        ))
        for op in domain.operators
    )
    for asked in (False, True):
        hit = _HIERARCHIES.get((id(domain.operators), asked))
        if hit is not None and hit[0] is domain.operators and hit[1] is domain.types and hit[2] is hierarchy:
            _keep(ops, domain.types, hierarchy, asked)  # derived for these literals: the copy's hierarchy too
    return replace(domain, operators=ops)


def auto_criticality(domain: Domain) -> Domain:
    """``apply_hierarchy(domain, derive_hierarchy(domain))``: what ``--criticality auto`` does."""
    return apply_hierarchy(domain, derive_hierarchy(domain))


def violations(domain: Domain, levels_of: Mapping[tuple[str, int, str], int | None]) -> list[str]:
    """Where per-literal levels break ordered monotonicity (empty: the property holds).

    ``levels_of[(op name, index, kind)]`` is the level of the operator's
    ``index``-th precondition (kind ``"pre"``) or effect (``"eff"``), ``None``
    for a static literal.  Checked: the effects of an operator share one level,
    and no non-static precondition is above it.
    """
    out: list[str] = []
    for op in domain.operators:
        changing = changing_effects(op)
        eff = {levels_of[(op.name, i, "eff")] for i, e in enumerate(op.effects) if e in changing}
        if len(eff) > 1:
            out.append(f"{op.name}: effects at levels {sorted(x for x in eff if x is not None)}")
            continue
        if not eff:
            continue
        (k,) = eff
        for i, p in enumerate(op.preconditions):
            lv = levels_of[(op.name, i, "pre")]
            if lv is not None and k is not None and lv > k:
                out.append(f"{op.name}: precondition {p.atom} at level {lv} above its effects' {k}")
    return out


def literal_levels(domain: Domain, hierarchy: Hierarchy) -> dict[tuple[str, int, str], int | None]:
    """The hierarchy's level of every precondition and effect, keyed as :func:`violations` reads them."""
    out: dict[tuple[str, int, str], int | None] = {}
    for op in domain.operators:
        for i, p in enumerate(op.preconditions):
            out[(op.name, i, "pre")] = hierarchy.level_of(domain, op, p.atom)
        for i, e in enumerate(op.effects):
            out[(op.name, i, "eff")] = hierarchy.level_of(domain, op, e)
    return out
