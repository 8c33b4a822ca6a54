"""Aggressive replanning: replan from the root after every action (seed 000 IV).

With hysteresis, two kinds:

* *cost*: the plan made from the root after an action replaces the current plans only if
  it is cheaper, in the belief as it is now, than what they still cost (:func:`rest_cost`:
  the rest of the deepest plan and, above it, the steps after the one being refined).  A
  new plan that costs no less (an equally good order, another item as near as the one being
  fetched) leaves the current plans to go on, so replanning does not undo the agent's work
  on a tie (marsupial at a 50 % failure rate: after a failed loader move the root's plan put
  the package back and grasped the other one, then that one back, until the planner-call
  budget was spent).  A plan the executive can no longer follow is still replaced: its
  failure pops it as without aggressive replanning.  The root's plan is abstract, so it is
  often the cheaper (it hides what its refinement will cost): the hysteresis settles ties,
  not every detour;
* *cycles*: after the progress guard saw a cycle (:mod:`nowplan.acting.progress`, e.g. a
  replan toward another item after every action that shuttles the robot between two
  rooms) the executive is *committed* and the current plan is kept until it is finished or
  fails; replanning after every action resumes then.  A commitment ends at the first belief
  not held before, so replans that undo the agent's work can cycle again from there (a
  held-out tidy house: pick the book, put it back, four times); after ``WITHDRAW_AFTER``
  cycles the mechanism stops replanning from the root for the rest of the run (a note in the
  trace), and the executive goes on as plain HPN: the loop ends by a decision, not a budget.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.mechanisms import Mechanism, Switch, register_switch

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive
    from nowplan.acting.progress import Cycle
    from nowplan.planning.plan import Plan

TIE = 1e-6  # relative cost difference below which two plans cost the same
WITHDRAW_AFTER = 2  # cycles the guard saw after which aggressive replanning stops for the run


def rest_cost(ex: Executive) -> float:
    """What the current plans still cost in the current belief: the rest of the deepest plan (after
    the step just taken) and, in each plan above it, the steps after the one being refined (that
    one's remaining work is the plans below it)."""
    total = 0.0
    for f in ex.stack[1:]:
        total += sum(s.action.cost(ex.belief) for s in f.plan.steps[f.i + 1:] if s.action is not None)
    return total


def plan_cost(ex: Executive, plan: Plan) -> float:
    return sum(s.action.cost(ex.belief) for s in plan.steps if s.action is not None)


class AggressiveReplan(Mechanism):
    name = "aggressive"

    def __init__(self) -> None:
        self.cycles = 0  # cycles the guard saw in this run; WITHDRAW_AFTER of them end the replanning

    def after_cycle(self, ex: Executive, cycle: Cycle) -> None:
        self.cycles += 1
        if self.cycles == WITHDRAW_AFTER:
            ex.trace.emit("note", text=f"aggressive: {self.cycles} cycles ({cycle.describe()}); no more "
                                       "replanning from the root after every action in this run")

    def after_action(self, ex: Executive) -> None:
        if self.cycles >= WITHDRAW_AFTER or ex.committed or len(ex.stack) <= 1 or ex.goal_holds():
            return
        root, top = ex.stack[0], ex.stack[1]
        goal = ex.next_step(root).goal  # the first stage that does not hold yet, else the goal
        ex.request_replan("aggressive", "replan after every action")
        if top.plan.goal != goal:  # a stage was reached (or lost): the current plan is for another goal
            new = None
        else:
            new = ex.make_plan(goal, top.plan.levels, root)
            if new is None:
                return  # keep the current plans (the failure is traced); the executive goes on with them
            old_cost, new_cost = rest_cost(ex), plan_cost(ex, new)
            if new_cost >= old_cost - TIE * max(1.0, abs(old_cost)):
                ex.reject_plan(new, root, f"aggressive: costs {new_cost:g}, the current plan's rest "
                                          f"{old_cost:g}: the current plan goes on")
                return
        while len(ex.stack) > 1:
            ex.pop("replaced")
        if new is not None:
            ex._pending_trigger = None  # this replan is the one below
            ex.push(new, root)


register_switch(
    Switch("aggressive", "replan the whole goal after every action (switching plans only to a cheaper one)",
           mechanism=lambda s: AggressiveReplan())
)
