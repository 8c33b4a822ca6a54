"""Resources derived from a domain's operators, for domains that declare none (seed 002 III-C).

RCHPN's ``arrange`` compares the resources two subgoals use; a domain written
for it declares them (``Operator(resources=...)``).  A domain that declares
none (every PDDL file, and a user's domain written without the peephole in
mind) gets them from the structure of its operators, so that
``--strategy hpn+peephole`` reorders and combines there too:

* **Holders and stops.**  A *movable* fluent is one some operator changes from
  one place to another: it deletes ``P(.., a, ..)`` and adds ``P(.., b, ..)``
  with every other argument the same (PDDL's ``at ?truck ?from`` →
  ``at ?truck ?to``), or sets a valued fluent ``P(args) = a`` to ``b``.  The
  other arguments name the *holder* (the truck; the robot of gripper's
  ``at-robby ?room``, which has none).  An operator that moves a holder, or
  needs it at a place without moving it (a load needs the truck at the
  package's place), uses the holder and its *stop* (the holder at the
  destination, or at the needed place) shareably: one trip serves several
  subgoals, as seed 002's vehicle does.  Two stops of one holder at different
  places clash (one vehicle cannot be at two stops), which ``arrange`` counts
  as a resource contained by both.
* **Held resources.**  A precondition an operator deletes, of a predicate
  that another operator adds back and that is not movable (gripper's
  ``free ?g``, blocksworld's ``handempty``), is used *continually* by the
  operator that takes it (it stays taken while the goal holds) and
  *contained* by the operator that gives it back.

Every operator gets estimate order 1 (a small plan for its hidden preconditions
adds its operators' resources), as seed 002's Load and Unload.  Derived only
where the domain declares no resource and no :class:`ResourceModel`; a domain
that wants none passes ``Domain(resources=ResourceModel())``.
"""

from __future__ import annotations

from typing import Any

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.core.operators import Operator, Resource, ResourceUse

SH, CT, CN = ResourceUse.SHAREABLE, ResourceUse.CONTAINED, ResourceUse.CONTINUAL
# a movable fluent: (predicate, position of the place among its arguments), or (predicate, None)
# for a valued fluent whose value is the place
Movable = tuple[str, int | None]


def _boolean(domain: Domain, a: Atom) -> bool:
    pred = domain.predicates.get(a.predicate)
    return pred is None or pred.boolean


def movable_fluents(domain: Domain) -> frozenset[Movable]:
    """The fluents some operator moves from one place to another (see the module docstring)."""
    out: set[Movable] = set()
    for op in domain.operators:
        adds = [e for e in op.effects if e.value is True and _boolean(domain, e)]
        dels = [e for e in op.effects if e.value is False and _boolean(domain, e)]
        for d in dels:
            for a in adds:
                if a.predicate == d.predicate and len(a.args) == len(d.args):
                    diff = [i for i, (x, y) in enumerate(zip(a.args, d.args, strict=True)) if x != y]
                    if len(diff) == 1:
                        out.add((a.predicate, diff[0]))
        pre = {p.atom.key: p.atom.value for p in op.preconditions if not _boolean(domain, p.atom)}
        for e in op.effects:
            if not _boolean(domain, e) and e.key in pre and pre[e.key] != e.value:
                out.add((e.predicate, None))
    return frozenset(out)


def _held_predicates(domain: Domain, movable: frozenset[Movable]) -> frozenset[str]:
    """Predicates a precondition of which some operator deletes and some operator adds, not movable."""
    moved = {p for p, _ in movable}
    taken: set[str] = set()
    given: set[str] = set()
    for op in domain.operators:
        dels = {e.key for e in op.effects if e.value is False and _boolean(domain, e)}
        taken |= {p.atom.predicate for p in op.preconditions
                  if p.atom.value is True and p.atom.key in dels and p.atom.predicate not in moved}
        given |= {e.predicate for e in op.effects if e.value is True and _boolean(domain, e)}
    return frozenset(taken & given)


def _places(a: Atom, movable: frozenset[Movable], boolean: bool) -> list[tuple[tuple[Any, ...], Any]]:
    """(holder name, place) for each movable reading of atom ``a`` (none if it is not movable)."""
    out = []
    if not boolean:
        if (a.predicate, None) in movable:
            out.append((("holder", a.predicate, "=", *a.args), a.value))
        return out
    if a.value is not True:
        return out
    for i in range(len(a.args)):
        if (a.predicate, i) in movable:
            others = tuple(x for j, x in enumerate(a.args) if j != i)
            out.append((("holder", a.predicate, i, *others), a.args[i]))
    return out


def operator_resources(domain: Domain, op: Operator, movable: frozenset[Movable],
                       held: frozenset[str]) -> tuple[Resource, ...]:
    """``op``'s derived resource templates (see the module docstring)."""
    from nowplan.acting.resources import merge_uses  # (resources.py imports this module lazily)

    uses: dict[tuple[Any, ...], ResourceUse] = {}

    def put(name: tuple[Any, ...], use: ResourceUse) -> None:
        merge_uses(uses, {name: use})  # the stronger use wins

    dels = {e.key for e in op.effects if e.value is False}
    moved: set[tuple[Any, ...]] = set()
    for e in op.effects:  # the holders it moves: at their destination
        for holder, place in _places(e, movable, _boolean(domain, e)):
            moved.add(holder)
            put(holder, SH)
            put(("stop", *holder[1:], place), SH)
    for p in op.preconditions:
        a = p.atom
        if p.static:
            continue
        for holder, place in _places(a, movable, _boolean(domain, a)):
            if holder not in moved:  # needed at a place, not moved from it
                put(holder, SH)
                put(("stop", *holder[1:], place), SH)
        if a.predicate in held and a.value is True and a.key in dels:
            put(("held", a.predicate, *a.args), CN)
    for e in op.effects:
        if e.value is True and e.predicate in held:
            put(("held", e.predicate, *e.args), CT)
    return tuple(Resource(name, use) for name, use in uses.items())


def derive_resources(domain: Domain) -> dict[str, tuple[Resource, ...]]:
    """Per operator name its derived resource templates."""
    movable = movable_fluents(domain)
    held = _held_predicates(domain, movable)
    return {op.name: operator_resources(domain, op, movable, held) for op in domain.operators}


def stops_clash(r1: tuple[Any, ...], r2: tuple[Any, ...]) -> bool:
    """Two stops of one holder at different places (one truck at two places)."""
    return (len(r1) == len(r2) and len(r1) > 1 and r1[0] == "stop" and r2[0] == "stop"
            and r1[:-1] == r2[:-1] and r1[-1] != r2[-1])
