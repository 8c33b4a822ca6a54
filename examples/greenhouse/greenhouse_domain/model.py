"""The greenhouse: two robots water and de-pest plants on benches.

* Where a robot stands is a valued fluent ``pose(r) = "x,y"``; the poses next to a plant are
  proposed by a generator (``Generator(reads=reads_nothing)``: they depend on the plant, the robot
  and the belief, never on the goal), nearest first, skipping the pose the other robot holds.
* The water tank is shared by both robots as discrete levels (``level(l0..lN)``, one per can
  filled); a pump refills it once (``pump_ok`` is used up: irreversible), and the sprayer's
  charges (``charge(c0..cM)``) are never refilled: a leak or a wasted spray can leave no plan.
* One sprayer lies in the shed: the robot that sprays must fetch it first.
* Whether a plant is free of pests (``clean(p)``) is hidden; a particle belief weighs a noisy
  inspection, and ``maybe_clean(p)`` is a test of that belief: an inspection is worth its cost only
  when the plant may be clean.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from nowplan.api import (
    Domain, Generator, Operator, Precondition, Predicate, Var, atom, exactly_one, excludes, reads_nothing, static,
)

r, p, q, t, l, l2, c, c2 = (Var(n) for n in ("r", "p", "q", "t", "l", "l2", "c", "c2"))
# the top class decides whether a plan can work: what is clean and watered, the tank, the charges,
# the cans, who holds the sprayer; refinements add where each robot stands
TASK, REACH = 2, 1
TAPS = ("4.0,0.0", "5.0,0.0")  # the tank's two taps (the pump is at the first)
TANK = TAPS[0]
SHED = "0.0,2.0"  # where the sprayer lies at the start
MAYBE = 0.1  # an inspection is worth it when the plant is clean with at least this probability
OFFSETS = ((0.0, -0.5), (0.5, 0.0), (-0.5, 0.0), (0.0, 0.5))  # the poses around a plant a robot works from


def xy(pose: object) -> tuple[float, float]:
    a, b = str(pose).split(",")
    return float(a), float(b)


def dist(a: object, b: object) -> float:
    (xa, ya), (xb, yb) = xy(a), xy(b)
    return math.hypot(xa - xb, ya - yb)


def maybe_clean(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``maybe_clean(p)``: the belief gives the plant a chance of MAYBE or more to be free of pests."""
    prob: float = belief.probability(atom("clean", args[0]))
    return (prob >= MAYBE) == bool(value)


def vacant(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``vacant(q, r)``: no robot but ``r`` is believed to stand on pose ``q`` (the world refuses a
    drive onto a taken pose; without this the planner sent a robot to the tap the other one held,
    25 times in a row)."""
    pose, robot = args
    taken = any(belief.value(("pose", (x,))) == pose for (x,) in belief.facts("robot") if x != robot)
    return (not taken) == bool(value)


def inspect_cost(bindings: Any, belief: Any) -> float:
    """An inspection costs more the likelier the plant has pests (it will probably not settle it)."""
    prob = belief.probability(atom("clean", bindings[p])) if belief is not None and p in bindings else 0.5
    return 1.0 + 6.0 * (1.0 - prob)


def drive_cost(bindings: Any, belief: Any) -> float:
    """One plus the distance from where the robot is believed to stand (1 when that is unknown)."""
    here = belief.value(("pose", (bindings[r],))) if belief is not None and r in bindings else False
    return 1.0 + (dist(here, bindings[q]) if here and q in bindings else 0.0)


def work_pose(bindings: Any, goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """The free poses around plant ``p`` for robot ``r``, nearest to the robot first."""
    plant, robot = bindings.get(p), bindings.get(r)
    if plant is None or belief is None:
        return
    spot = next((s for (x, s) in belief.facts("spot") if x == plant), None)
    if spot is None:
        return
    taken = {str(v) for (x,) in belief.facts("robot") if x != robot
             for v in [belief.value(("pose", (x,)))] if v}
    here = belief.value(("pose", (robot,))) if robot is not None else False
    sx, sy = xy(spot)
    poses = [f"{sx + dx:.1f},{sy + dy:.1f}" for dx, dy in OFFSETS]
    poses.sort(key=lambda s: (dist(here, s) if here else 0.0, s))
    for pose in poses:
        if pose not in taken:
            yield {q: pose}


def tool_pose(bindings: Any, goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """Where the belief has tool ``t`` lie (a pose is no object: only a generator can bind it)."""
    tool = bindings.get(t)
    if belief is not None:
        yield from ({q: s} for (x, s) in belief.facts("lies") if tool is None or x == tool)


def pre(name: str, *args: object, crit: int, value: object = True) -> Precondition:
    return Precondition(atom(name, *args, value=value), crit)


POSE_NEAR_PLANT = Generator("work_pose", (q,), work_pose, (r, p), reads=reads_nothing)

PREDICATES = {x.name: x for x in (
    Predicate("pose", 1, ("robot",), boolean=False),  # pose(r) = "x,y"
    Predicate("lies", 2, ("tool", None)),  # lies(t, pose)
    Predicate("holding", 2, ("robot", "tool")),
    Predicate("full", 1, ("robot",)),  # the robot's can holds water
    Predicate("dry", 1, ("robot",)),
    Predicate("level", 1, ("level",)),  # the tank's level
    Predicate("charge", 1, ("charge",)),  # the sprayer's charges left
    Predicate("pump_ok", 0),  # the pump may still be used (once)
    Predicate("watered", 1, ("plant",)),
    Predicate("clean", 1, ("plant",)),  # hidden: no pests on the plant
    Predicate("maybe_clean", 1, ("plant",), test=maybe_clean),
    Predicate("vacant", 2, (None, "robot"), test=vacant),
    Predicate("tap", 1, (None,)),  # static: a tap of the tank
    Predicate("dec", 2, (None, None)),  # static: dec(l, l2): one level (charge) below l is l2
    Predicate("spot", 2, ("plant", None)),  # static: where the plant stands
    Predicate("robot", 1, ("robot",)),  # static
    Predicate("full_level", 1, ("level",)),  # static: the tank's top level
)}

OPERATORS = (
    Operator("drive", (r, q), (static(atom("robot", r)), pre("vacant", q, r, crit=REACH)),
             (atom("pose", r, value=q),), cost=drive_cost,
             param_types=("robot", None)),
    Operator("take", (r, t, q), (pre("lies", t, q, crit=TASK), pre("pose", r, crit=REACH, value=q)),
             (atom("holding", r, t), atom("lies", t, q, value=False)), param_types=("robot", "tool", None),
             generators=(Generator("tool_pose", (q,), tool_pose, (t,), reads=reads_nothing),)),
    Operator("fill", (r, l, l2, q),
             (pre("dry", r, crit=TASK), pre("level", l, crit=TASK), static(atom("dec", l, l2)), static(atom("tap", q)),
              pre("pose", r, crit=REACH, value=q)),
             (atom("full", r), atom("dry", r, value=False), atom("level", l2), atom("level", l, value=False)),
             param_types=("robot", "level", "level", None)),
    Operator("pump", (r, l, l2),
             (pre("pump_ok", crit=TASK), pre("level", l, crit=TASK), static(atom("full_level", l2)),
              pre("pose", r, crit=REACH, value=TANK)),
             (atom("level", l, value=False), atom("level", l2), atom("pump_ok", value=False)),
             cost=6.0, param_types=("robot", "level", "level")),
    Operator("water", (r, p, q),
             (pre("full", r, crit=TASK), pre("pose", r, crit=REACH, value=q)),
             (atom("watered", p), atom("dry", r), atom("full", r, value=False)),
             param_types=("robot", "plant", None), generators=(POSE_NEAR_PLANT,)),
    Operator("spray", (r, p, q, c, c2),
             (pre("holding", r, "sprayer", crit=TASK), pre("charge", c, crit=TASK), static(atom("dec", c, c2)),
              pre("pose", r, crit=REACH, value=q)),
             (atom("clean", p), atom("charge", c2), atom("charge", c, value=False)),
             cost=4.0, param_types=("robot", "plant", None, "charge", "charge"), generators=(POSE_NEAR_PLANT,)),
    Operator("inspect", (r, p, q), (pre("maybe_clean", p, crit=TASK), pre("pose", r, crit=REACH, value=q)),
             (atom("clean", p),), cost=inspect_cost, param_types=("robot", "plant", None),
             generators=(POSE_NEAR_PLANT,)),
)

CONFLICTS = (
    exactly_one("level", key=()),
    exactly_one("charge", key=()),
    excludes(atom("full", r), atom("dry", r)),
    excludes(atom("holding", r, t), atom("lies", t, q)),
)

DOMAIN = Domain("greenhouse", PREDICATES, OPERATORS,
                types={"robot": None, "tool": None, "plant": None, "level": None, "charge": None},
                conflicts=CONFLICTS)
