"""Prototype (not part of the library): two changes to RCHPN on marsupial logistics, measured.

1. ``veh``: the vehicle-shareability test also counts a package named by a
   Load/Unload of *another* vehicle when it lies where this vehicle goes and
   that other vehicle cannot fetch it there (so it must ride this one first);
   the library's test (``marsupial.model._packages_for``) counts only the
   subgoals' own Load/Unload steps of this vehicle.
2. ``gather``: after SelectParallelOps (seed 002 Alg. 4) has formed a group,
   a later step that ``arrange`` would combine with it but that depends on
   steps still ahead (a package's plane leg while its truck leg is pending)
   has those prerequisite steps moved in front of the group, when the plan
   stays valid; the group is then combined at a later step.  Not in the
   paper's Alg. 3/4.

Both are applied by monkeypatching, for this script only.  Usage (one run):

    .venv/bin/python benchmarks/marsupial_gather_prototype.py REGIME N TRIAL hpn+peephole [veh] [gather]

or with ``--quick-set`` the 16 problems of ``nowplan reproduce 002 --quick``
(prints HPN, RCHPN and RCHPN with both changes).  See docs/marsupial.md.
"""

import dataclasses
import sys
from collections.abc import Sequence
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.operators import Action
from nowplan.acting import peephole as ph
from nowplan.acting.arrange import Arrange, Subgoal, depends
from nowplan.domains.marsupial import model as mm
from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.grid import Hold, can_share

VEH_FIX = "veh" in sys.argv[5:] or "--quick-set" in sys.argv
GATHER = "gather" in sys.argv[5:] or "--quick-set" in sys.argv

def shareable(resource: tuple[Any, ...], first: Sequence[Action], second: Sequence[Action], belief: Any) -> bool | None:
    if resource[0] not in ("vehicle", "space"):
        return None
    veh = str(resource[1])
    hold, door = mm._bay(belief, veh)
    if not isinstance(hold, Hold):
        return None
    shapes = dict(belief.facts("shape"))
    acts = [*first, *second]
    pk = mm._packages_for(veh, acts)
    if VEH_FIX:
        where = {str(p): str(l) for p, l in belief.facts("at")}
        reach = {str(l) for l, v in belief.facts("reachable") if str(v) == veh}
        for x in acts:
            if x.name in ("load", "unload") and x.args[1] != veh:
                p = str(x.args[0]); other = str(x.args[1])
                oreach = {str(l) for l, v in belief.facts("reachable") if str(v) == other}
                l = where.get(p)
                if l is not None and l in reach and l not in oreach:
                    if p not in pk:
                        pk.append(p)
    order = [x for x in pk if x in shapes]
    if not can_share(hold, door, {x: shapes[x] for x in order}):
        return False
    return lp.can_stow_in_turn(hold, door, [(x, shapes[x]) for x in order])  # as the library's test

mm.RESOURCES = dataclasses.replace(mm.RESOURCES, shareable=shareable)  # make_domain() gives it to each domain

orig_spo = ph.Reorderer.select_parallel_ops
def spo(self: ph.Reorderer, ops: list[Action], goals: list[Goal]) -> tuple[list[Action], list[Goal], int]:
    ops2, goals2, last = orig_spo(self, ops, goals)
    if not GATHER or last == 0 or last + 1 >= self.config.max_combined:
        return ops2, goals2, last
    group = ops2[: last + 1]
    for j in range(last + 1, len(ops2)):
        if not self.combinable(ops2[j]):
            continue
        if self.arrange(Subgoal(tuple(group), goals2[last + 1]), Subgoal((ops2[j],), goals2[j + 1])) is not Arrange.COMBINE:
            continue
        need = {j}
        for i in range(j - 1, last, -1):
            if depends(self.domain, [ops2[i]], [ops2[k] for k in need], self.levels):
                need.add(i)
        pre = sorted(need - {j})
        if not pre or any(depends(self.domain, group, [ops2[i]], self.levels) for i in pre):
            continue
        rest = [ops2[i] for i in range(last + 1, len(ops2)) if i not in need]
        new = [*(ops2[i] for i in pre), *group, ops2[j], *rest]
        res = self.valid(new, goals2[-1])
        if res is not None and res[0][:1] == new[:1]:
            self.moves.append(f"gathered {', '.join(str(ops2[i]) for i in pre)} before {group[0]} to combine {ops2[j]}")
            return res[0], res[1], 0
    return ops2, goals2, last
ph.Reorderer.select_parallel_ops = spo  # type: ignore[method-assign]

from nowplan.domains.marsupial.repro import run_one

if "--quick-set" in sys.argv:
    # HPN and plain RCHPN (changes off), then RCHPN with both changes, per problem
    for regime in ("single", "origins", "dests", "both"):
        for n in (3, 5):
            for trial in (0, 1):
                costs = []
                for strategy, on in (("hpn", False), ("hpn+peephole", False), ("hpn+peephole", True)):
                    VEH_FIX = GATHER = on
                    r = run_one((regime, n, trial, strategy, 120.0))
                    costs.append(r["cost"] if r["goal_holds"] else float("nan"))
                h, p, g = costs
                print(f"{regime} {n} {trial}: hpn {h:g} rchpn {p:g} ({100 * (1 - p / h):.1f} %) "
                      f"rchpn+veh+gather {g:g} ({100 * (1 - g / h):.1f} %)", flush=True)
else:
    regime, n, trial = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    r = run_one((regime, n, trial, sys.argv[4], 120.0))
    print(regime, n, trial, sys.argv[4], sys.argv[5:], r["outcome"], r["cost"], round(r["cpu_s"], 2))
