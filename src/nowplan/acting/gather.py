"""Gather: do a combinable step's prerequisites before the group it would join (RCHPN, ours).

SelectParallelOps (seed 002 Alg. 4) pulls a later step next to the chosen
one only when the plan stays valid *now*.  A step that ``arrange`` would
combine with the group but that needs steps still ahead — a package's plane
leg while its truck leg is pending — is left for a later trip of the same
vehicle, although that vehicle could have waited for it.

:func:`gather` moves such a step's prerequisites (the steps between the
group and it that it needs, transitively) in front of the group, and the
step itself right behind the group, when

* the group is below the complexity limit (there is room to combine),
* ``arrange`` says *combine* for the group and the step, in the now,
* the step declares a resource the group's operators declare, the group
  needs none of the prerequisites' effects and the prerequisites declare
  none of the group's resources (doing them first does not take the
  group's vehicle away), the prerequisites that declare resources all
  declare one in common (they can be taken as one combined step: a package's
  truck leg, not its truck and plane legs, which would take the plane away
  from its own groups), and
* the reordered plan is still valid.

The prerequisites then come first (SelectParallelOps runs on them, so they
are combined among themselves as usual) and the group is formed again, with
the step, once they are done.  All steps are still taken, so with costs that
do not depend on when a step is taken the reordering only changes what is
combined.  Not in the paper's Alg. 3/4.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.arrange import Arrange, Subgoal, depends
from nowplan.core.atoms import Goal
from nowplan.core.operators import Action

if TYPE_CHECKING:
    from nowplan.acting.reorder import Reorderer


def prerequisites(r: Reorderer, ops: list[Action], start: int, j: int) -> list[int]:
    """Indices in ``start..j-1`` of the steps ``ops[j]`` needs, directly or through each other."""
    need = {j}
    for i in range(j - 1, start - 1, -1):
        if depends(r.domain, [ops[i]], [ops[k] for k in sorted(need)], r.levels):
            need.add(i)
    return sorted(need - {j})


def gather(
    r: Reorderer, ops: list[Action], goals: list[Goal], last: int
) -> tuple[list[Action], list[Goal], int]:
    """After SelectParallelOps: gather a combinable step's prerequisites first (see the module)."""
    if not r.config.gather or not ops or last + 1 >= r.config.max_combined or not r.combinable(ops[0]):
        return ops, goals, last
    group = Subgoal(tuple(ops[: last + 1]), goals[last + 1])
    # the cheap tests first, on the declared (0th-order) resources; ``arrange`` last
    declared = {res.name for a in group.actions for res in r.model.uses(a)}
    for j in range(last + 1, len(ops)):
        step = ops[j]
        if not r.combinable(step) or not declared & {res.name for res in r.model.uses(step)}:
            continue
        if r.failed_within([*group.actions, step]):
            continue
        pre = prerequisites(r, ops, last + 1, j)
        if not pre or depends(r.domain, group.actions, [ops[i] for i in pre], r.levels):
            continue  # movable now (SelectParallelOps refused it), or the group comes first
        held = [{res.name for res in r.model.uses(ops[i])} for i in pre]
        if any(declared & h for h in held):
            continue  # the prerequisites would use the group's vehicle (resources) first
        held = [h for h in held if h]
        if held and not set.intersection(*held):
            continue  # prerequisites on several resource holders (legs of different vehicles): not one step
        if r.arrange(group, Subgoal((step,), goals[j + 1]), Arrange.COMBINE) is not Arrange.COMBINE:
            continue
        moved = set(pre) | {j}
        new = [*(ops[i] for i in pre), *group.actions, step,
               *(ops[i] for i in range(last + 1, len(ops)) if i not in moved)]
        res = r.valid(new, goals[-1])
        if res is None or res[0][: len(pre)] != new[: len(pre)]:
            continue
        r.moves.append(f"gathered {', '.join(str(ops[i]) for i in pre)} before {group} to combine {step}")
        r.note_dropped(new, res[0])
        return r.select_parallel_ops(*res)
    return ops, goals, last
