"""Goal atoms an abstract plan leaves alone are owed only at its end (tidy-up goals).

A problem's goal often has atoms that hold now and that the plan's steps, at the plan's abstraction level,
neither need nor change: a robot parked at home, the machines switched off, a door closed.  Regressed
through such steps they stay in every pre-image, ``g0 … gn``, so HPN's refinement of each step must
bring them about again before the next one: the robot drives home after every delivery and the
lathe is switched off after every part (a held-out mill shop: three times flat planning's actions,
most runs at the action budget).  Nothing at the plan's level asks for that: only its goal ``gn``
does.

:func:`postpone` takes those atoms out of ``g0 … g(n-1)`` and leaves ``gn`` as it was, so the
refinement of the last step plans them (once), as a flat plan would at its end.  An atom is
postponed only if it is an atom of the problem's goal (not a subgoal an abstract plan set, such as
a package to stay in a plane), it holds now; no step of the plan adds, deletes, needs (a precondition kept at
the step's level) or conflicts with it under the domain's rules; and the hierarchy's top level does
not plan with its predicate (no operator keeps a precondition on it there).  So the atoms the
abstract plans work with stay maintained, as the seed's HPN maintains them: a piece already on its
goal cell, a package delivered (seed 003's monitors watch them); what is postponed is the detail
the top cannot see, which a refinement below may undo where that is cheaper, as a flat plan may,
and the last step's refinement restores.  A plan of one step, or whose steps are
all primitive, is left as it is (its refinement plans ``gn`` anyway, or no step can disturb the
atoms).  The ``maintain`` switch turns it off (seed 002 HPN's pre-images, exactly regressed).
"""

from __future__ import annotations

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.planning.plan import Plan, PlanStep


def postponable(plan: Plan, domain: Domain, truth: object, owed: Goal) -> frozenset[Atom]:
    """The atoms of ``plan``'s goal, of the problem's goal ``owed``, that hold in ``truth`` and that no
    step works with (see above)."""
    steps = plan.steps
    n = len(steps) - 1
    if n < 2 or all(plan.is_primitive(i) for i in range(1, n + 1)):
        return frozenset()
    seen = _top_sees(domain)
    candidates = [x for x in plan.goal.atoms
                  if x.predicate not in seen and x in owed.atoms and domain.satisfies(truth, (x,))]
    if not candidates:  # (most plans: every goal atom is one the top level plans with)
        return frozenset()
    worked: list[Atom] = []
    for s in steps[1:]:
        a = s.action
        if a is not None:
            worked.extend(a.effects())
            worked.extend(a.preconditions(plan.levels.level(a)))
    keys = {w.key for w in worked}
    rules = domain.rules
    out = []
    for x in candidates:
        if x.key in keys:
            continue
        if rules.conflicts and any(rules.atoms_conflict(x, w) for w in worked):
            continue
        out.append(x)
    return frozenset(out)


def _top_sees(domain: Domain) -> frozenset[str]:
    """The predicates of a precondition some operator keeps at the domain's top level (not a static one)."""
    hit = _SEEN.get(id(domain))
    if hit is not None and hit[0] is domain:
        return hit[1]
    top = domain.top_level
    out = frozenset(p.atom.predicate for op in domain.operators for p in op.preconditions
                    if not p.static and p.criticality > top)
    if len(_SEEN) >= 16:
        _SEEN.clear()
    _SEEN[id(domain)] = (domain, out)
    return out


_SEEN: dict[int, tuple[Domain, frozenset[str]]] = {}


def postpone(plan: Plan, domain: Domain, truth: object, owed: Goal) -> tuple[Plan, frozenset[Atom]]:
    """``plan`` with :func:`postponable` atoms taken out of ``g0 … g(n-1)``, and those atoms."""
    later = postponable(plan, domain, truth, owed)
    if not later:
        return plan, later
    n = len(plan.steps) - 1
    steps = tuple(
        PlanStep(s.action, Goal(s.goal.atoms - later)) if i < n else s for i, s in enumerate(plan.steps)
    )
    return Plan(steps, plan.levels), later
