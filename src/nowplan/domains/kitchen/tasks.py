"""The four tasks of seed 004's appendix, each with a seeded generator of problems.

* **Inspect** — goal: the green block in the bottom drawer, bottom drawer
  closed; prior uniform over both drawers; truly in the bottom drawer.
* **Stow** — goal: the block in the top drawer, top drawer closed; prior for
  the block uniform over the counter, for the sugar box over the top drawer;
  truly on the counter and in the top drawer (the tall box must come out).
* **Swap** — goal and prior as Inspect; the block is truly in the top drawer.
* **Cook** — goal: the block cooked (and the stove off); prior uniform over the
  counter; the cracker and sugar boxes are on the counter, one of them
  always hiding the block from the camera.

Problem ``k`` of a task draws the latent positions from ``seed`` and ``k``;
objects a task does not mention start on the counter at known positions.
A block hidden in a drawer is drawn from the part of the tray the camera
can see once the drawer is open (the front of the tray is behind the
drawer's front panel: no observation could ever find the block there); the
agent's prior still covers the whole tray.
"""

from __future__ import annotations

import random

import numpy as np

from nowplan.belief.particles import Region
from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Problem
from nowplan.domains.kitchen import scene as S
from nowplan.domains.kitchen.belief import KitchenBelief
from nowplan.domains.kitchen.model import KitchenModel
from nowplan.domains.kitchen.world import KitchenWorld
from nowplan.domains.registry import Episode
from nowplan.errors import ScenarioError

TASKS = ("inspect", "stow", "swap", "cook")
PROBLEMS_PER_TASK = 25
SEEN_FROM_Y = 0.1  # tray y (m) beyond which a block in an open drawer is visible (measured with the world's rays)


def _in(reg: Region, rng: random.Random, margin: float = 0.03) -> tuple[float, float]:
    return (rng.uniform(reg.lo[0] + margin, reg.hi[0] - margin), rng.uniform(reg.lo[1] + margin, reg.hi[1] - margin))


def _seen_part(reg: Region) -> Region:
    """The back of a drawer's tray, which the camera sees over the drawer's front panel when the
    drawer is open (the front ``SEEN_FROM_Y`` of the tray is hidden for the small block)."""
    return Region(reg.frame, (reg.lo[0], SEEN_FROM_Y), reg.hi)


def _known(o: str, frame: str, xy: tuple[float, float]) -> list[Region]:
    return [Region(frame, (xy[0] - 0.002, xy[1] - 0.002), (xy[0] + 0.002, xy[1] + 0.002))]


def make(task: str, index: int, seed: int = 0) -> Episode:
    if task not in TASKS:
        raise ScenarioError(f"unknown kitchen task '{task}'; valid tasks: {', '.join(TASKS)}")
    rng = random.Random(f"{task}/{seed}/{index}")
    regs = S.regions()
    side = {"sugar": (-0.38, 0.72), "cracker": (-0.2, 0.74)}
    truth: dict[str, tuple[str, tuple[float, float]]] = {}
    prior: dict[str, list[Region]] = {}
    if task in ("inspect", "swap"):
        where = "bottom" if task == "inspect" else "top"
        truth["green"] = (where, _in(_seen_part(regs[where]), rng))
        prior["green"] = [regs["top"], regs["bottom"]]
        goal = [atom("In", "green", "bottom"), atom("Open", "bottom", value=False)]
    elif task == "stow":
        truth["green"] = ("counter", _in(regs["counter"], rng))
        truth["sugar"] = ("top", _in(regs["top"], rng, 0.05))
        prior["green"] = [regs["counter"]]
        prior["sugar"] = [regs["top"]]
        goal = [atom("In", "green", "top"), atom("Open", "top", value=False)]
    else:
        gx, gy = rng.uniform(-0.35, 0.05), rng.uniform(0.68, 0.76)
        truth["green"] = ("counter", (gx, gy))
        hider = rng.choice(["cracker", "sugar"])
        # put the hider on the camera ray to the block's top, in front of it
        top = S.frame_origin("counter", {}) + np.array([gx, gy, 2 * S.SIZES["green"][2]])
        t = (top[1] - 0.12 - S.CAMERA[1]) / (top[1] - S.CAMERA[1])
        hx = float(S.CAMERA[0] + t * (top[0] - S.CAMERA[0]))
        truth[hider] = ("counter", (hx, gy - 0.12))
        other = "sugar" if hider == "cracker" else "cracker"
        truth[other] = ("counter", (0.1 if hx < -0.1 else -0.42, 0.58))
        prior["green"] = [regs["counter"]]
        goal = [atom("Cooked", "green"), atom("StoveOn", value=False)]
    for o in ("sugar", "cracker"):
        if o not in truth:
            truth[o] = ("counter", side[o])
        if o not in prior:
            prior[o] = _known(o, *truth[o])
    belief = KitchenBelief(prior, seed=rng.randrange(2**31))
    model = KitchenModel(belief)
    world = KitchenWorld(truth, seed=rng.randrange(2**31))
    objects = {"green": "short", "sugar": "tall", "cracker": "tall", "top": "drawer", "bottom": "drawer",
               "counter": None, "stove": None}
    problem = Problem(model.domain, objects, belief, Goal.of(goal), name=f"{task}-{index}")
    truth_s = ", ".join(f"{o} in {f}" for o, (f, _) in sorted(truth.items()))
    return Episode(problem, world, belief, description=f"kitchen {task} #{index} ({truth_s})")


def scenario(task: str) -> object:
    return lambda seed: make(task, seed % PROBLEMS_PER_TASK, seed // PROBLEMS_PER_TASK)
