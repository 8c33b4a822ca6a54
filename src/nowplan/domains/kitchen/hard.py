"""The hard problem distribution of ``nowplan reproduce 004`` (the default; ``--easy`` is :mod:`tasks`).

Every hard problem has five objects — the green block (the target), two
tall boxes (sugar, cracker: too tall for a closed drawer or the cabinet), a
soup can (tall enough to hide the block, short enough for a drawer) and a
spam tin — in a kitchen with both drawers and a **cabinet** (a box with a
sliding lid on the left of the counter), and the counter between the cabinet
and the stove is a 0.54 × 0.28 m strip, so set-aside places are few.  Per
task (the goals are the paper's):

* **Inspect** — goal: the block in the bottom drawer, bottom drawer closed.
  Prior: uniform over both drawers and the cabinet.  Truth: in the bottom
  drawer, hidden from the camera by the soup can standing in front of it
  (the can's place is known): where the block's belief is densest the can
  has to be moved before the block can be seen.
* **Stow** — goal: the block in the top drawer, top drawer closed.  Prior for
  the block: uniform over the counter (where it is, at a random spot; the
  cracker box stands at another and may hide it).  The sugar box and the
  soup can are in the top drawer (priors uniform over it): the sugar box must
  come out before the drawer closes, the can stays and takes room.
* **Swap** — goal and prior as Inspect; the block is in the *top* drawer,
  hidden behind the soup can there, and the spam tin is in the bottom
  drawer (prior uniform over it), where the block must be put.
* **Cook** — goal: the block cooked, stove off.  Prior: uniform over the
  counter.  The two tall boxes stand on the counter, one of them always
  hiding the block, the other at a random spot (it may hide more of the
  counter); the spam tin is in the cabinet (prior over it).

Objects whose place is not stated above are in the cabinet (the soup can
and the spam tin) or on the counter (the tall boxes), at known places.  Problem ``k`` of a task is drawn from ``random.Random(f"hard/{task}/{seed}/{k}")``
alone: positions are rejection-sampled (at most :data:`MAX_DRAWS` draws, then
:class:`~nowplan.errors.ScenarioError`) until the hiding object hides all
five of the points the world's detector looks at and no two boxes overlap.
"""

from __future__ import annotations

import random

import numpy as np

from nowplan.belief.particles import Region
from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Problem
from nowplan.domains.kitchen import scene as S
from nowplan.domains.kitchen.belief import KitchenBelief, kitchen_hides, segments_blocked
from nowplan.domains.kitchen.model import KitchenModel
from nowplan.domains.kitchen.world import KitchenWorld
from nowplan.domains.registry import Episode
from nowplan.errors import ScenarioError

OBJECTS = ("green", "sugar", "cracker", "soup", "spam")
MAX_DRAWS = 2000
GAP = 0.01  # the least clearance between two boxes (m)
SEEN_FROM_Y = 0.1  # as in tasks: the front of a tray is behind the drawer's front panel


Placement = tuple[str, tuple[float, float]]


def _world(frame: str, xy: tuple[float, float], o: str, open_: str | None) -> np.ndarray:
    state = {d: (S.DRAWER_OPEN if d == open_ else 0.0) for d in S.DRAWERS}
    out: np.ndarray = S.frame_origin(frame, state) + np.array([xy[0], xy[1], S.SIZES[o][2]])
    return out


def hides(target: Placement, blocker: Placement, o: str, j: str) -> bool:
    """Does ``j`` at ``blocker`` hide all five top points of ``o`` at ``target`` (its frame open)?"""
    open_ = target[0] if target[0] in S.DRAWERS else None
    c = _world(*target, o, open_)
    hx, hy, hz = S.SIZES[o]
    pts = np.array([c + np.array([dx * hx * 0.6, dy * hy * 0.6, hz - 0.002])
                    for dx, dy in ((0, 0), (1, 1), (1, -1), (-1, 1), (-1, -1))])
    cj = _world(*blocker, j, open_)
    return bool(segments_blocked(S.CAMERA, pts, cj[None, :], np.array(S.SIZES[j]))[:, 0].all())


def findable(o: str, at: Placement) -> bool:
    """Can the camera see ``o`` at ``at`` with its container open, the kitchen alone in the way?  (Not in
    the front strip of a drawer's tray, behind its front panel.)  The belief's priors are conditioned on
    it (``KitchenBelief(findable=True)``), so every placement the generator draws satisfies it too."""
    frame, xy = at
    if frame not in S.containers(True):
        return True
    state = {d: ((S.CABINET_OPEN if d == S.CABINET else S.DRAWER_OPEN) if d == frame else 0.0)
             for d in S.containers(True)}
    base = S.frame_origin(frame, state) + np.array([xy[0], xy[1], S.SIZES[o][2]])
    return not bool(kitchen_hides(o, base, state, True)[0])


def _clear(o: str, at: Placement, placed: dict[str, Placement]) -> bool:
    for j, (f, xy) in placed.items():
        if f != at[0] or j == o:
            continue
        reach = np.array(S.SIZES[o][:2]) + np.array(S.SIZES[j][:2]) + GAP
        if np.all(np.abs(np.array(at[1]) - np.array(xy)) < reach):
            return False
    return True


def _inside(o: str, reg: Region, xy: tuple[float, float]) -> bool:
    hx, hy = S.SIZES[o][:2]
    return bool(reg.lo[0] + hx <= xy[0] <= reg.hi[0] - hx and reg.lo[1] + hy <= xy[1] <= reg.hi[1] - hy)


def _uniform(o: str, reg: Region, rng: random.Random) -> tuple[float, float]:
    hx, hy = S.SIZES[o][:2]
    return (rng.uniform(reg.lo[0] + hx, reg.hi[0] - hx), rng.uniform(reg.lo[1] + hy, reg.hi[1] - hy))


def _behind(o: str, j: str, target: Placement, rng: random.Random) -> tuple[float, float]:
    """A spot for ``j`` between the camera and ``o`` at ``target`` (in the same frame)."""
    frame, (x, y) = target
    gap = S.SIZES[o][1] + S.SIZES[j][1] + rng.uniform(GAP, 0.03)
    c = _world(frame, (x, y), o, frame if frame in S.DRAWERS else None)
    # shift x along the camera's ray so the blocker sits on the line of sight
    t = (c[1] - gap - S.CAMERA[1]) / (c[1] - S.CAMERA[1])
    dx = (S.CAMERA[0] + t * (c[0] - S.CAMERA[0])) - c[0]
    return (float(x + dx + rng.uniform(-0.01, 0.01)), float(y - gap))


def _place_hidden(o: str, j: str, reg: Region, rng: random.Random, placed: dict[str, Placement],
                  seen_from: float | None = None) -> tuple[Placement, Placement]:
    """``o`` uniformly in ``reg`` (beyond ``seen_from`` in y) with ``j`` hiding it, both clear of ``placed``."""
    lo_y = reg.lo[1] if seen_from is None else max(reg.lo[1], seen_from)
    part = Region(reg.frame, (reg.lo[0], lo_y), reg.hi)
    for _ in range(MAX_DRAWS):
        t = (reg.frame, _uniform(o, part, rng))
        b = (reg.frame, _behind(o, j, t, rng))
        if (_inside(j, reg, b[1]) and findable(o, t) and findable(j, b) and _clear(o, t, placed)
                and _clear(j, b, {**placed, o: t}) and hides(t, b, o, j)):
            return t, b
    raise ScenarioError(f"no spot for {j} hiding {o} in {reg.frame} after {MAX_DRAWS} draws")


def _place_free(o: str, reg: Region, rng: random.Random, placed: dict[str, Placement]) -> Placement:
    for _ in range(MAX_DRAWS):
        at = (reg.frame, _uniform(o, reg, rng))
        if findable(o, at) and _clear(o, at, placed):
            return at
    raise ScenarioError(f"no free spot for {o} in {reg.frame} after {MAX_DRAWS} draws")


def draw(task: str, index: int, seed: int = 0) -> tuple[dict[str, Placement], dict[str, list[Region]], list[object], int, int]:
    """The latent placements, the priors, the goal atoms and the belief's and world's seeds of a hard problem."""
    rng = random.Random(f"hard/{task}/{seed}/{index}")
    regs = S.regions(cabinet=True)
    truth: dict[str, Placement] = {}
    prior: dict[str, list[Region]] = {}
    containers = [regs["top"], regs["bottom"], regs[S.CABINET]]
    if task in ("inspect", "swap"):
        where = "bottom" if task == "inspect" else "top"
        truth["green"], truth["soup"] = _place_hidden("green", "soup", regs[where], rng, truth, SEEN_FROM_Y)
        prior["green"] = containers
        if task == "swap":
            truth["spam"] = _place_free("spam", regs["bottom"], rng, truth)
            prior["spam"] = [regs["bottom"]]
        goal = [atom("In", "green", "bottom"), atom("Open", "bottom", value=False)]
    elif task == "stow":
        for o in ("sugar", "soup"):
            truth[o] = _place_free(o, regs["top"], rng, truth)
            prior[o] = [regs["top"]]
        truth["green"] = _place_free("green", regs["counter"], rng, truth)
        prior["green"] = [regs["counter"]]
        goal = [atom("In", "green", "top"), atom("Open", "top", value=False)]
    elif task == "cook":
        hider = rng.choice(["sugar", "cracker"])
        truth["green"], truth[hider] = _place_hidden("green", hider, regs["counter"], rng, truth)
        truth["spam"] = _place_free("spam", regs[S.CABINET], rng, truth)
        prior["green"] = [regs["counter"]]
        prior["spam"] = [regs[S.CABINET]]
        goal = [atom("Cooked", "green"), atom("StoveOn", value=False)]
    else:
        raise ScenarioError(f"unknown kitchen task '{task}'; valid tasks: inspect, stow, swap, cook")
    for o in OBJECTS:  # the rest: known, tall boxes on the counter, the others in the cabinet
        if o not in truth:
            reg = regs["counter"] if o in S.TALL else regs[S.CABINET]
            truth[o] = _place_free(o, reg, rng, truth)
    for o, (frame, xy) in truth.items():
        if o not in prior:
            prior[o] = [Region(frame, (xy[0] - 0.002, xy[1] - 0.002), (xy[0] + 0.002, xy[1] + 0.002))]
    order = {o: i for i, o in enumerate(OBJECTS)}
    truth = dict(sorted(truth.items(), key=lambda kv: order[kv[0]]))
    prior = dict(sorted(prior.items(), key=lambda kv: order[kv[0]]))
    return truth, prior, list(goal), rng.randrange(2**31), rng.randrange(2**31)


def make(task: str, index: int, seed: int = 0) -> Episode:
    truth, prior, goal, bseed, wseed = draw(task, index, seed)
    belief = KitchenBelief(prior, seed=bseed, cabinet=True, findable=True)
    model = KitchenModel(belief)
    world = KitchenWorld(truth, seed=wseed, cabinet=True)
    objects: dict[str, str | None] = {o: ("tall" if o in S.TALL else "short") for o in OBJECTS}
    objects.update({"top": "drawer", "bottom": "drawer", S.CABINET: "drawer", "counter": None, "stove": None})
    problem = Problem(model.domain, objects, belief, Goal.of(goal), name=f"{task}-hard-{index}")  # type: ignore[arg-type]
    truth_s = ", ".join(f"{o} in {f}" for o, (f, _) in sorted(truth.items()))
    return Episode(problem, world, belief, description=f"kitchen hard {task} #{index} ({truth_s})")
