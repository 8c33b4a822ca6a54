"""The kitchen's belief-space planning model: fluents tested on the belief, operators, streams.

Fluents (each a test on :class:`~nowplan.domains.kitchen.belief.KitchenBelief`):
``AtConf = q``, ``Open(d)``, ``HandEmpty``, ``Holding(o)``, ``In(o, f)``
(mass of o in frame f ≥ 0.95), ``AtPose(o) = p`` (mass within δ/2 of p ≥
0.9), ``NotBlocks(j, o, p)`` (the ε condition for j against the
δ-neighbourhood of p: ``BOccluded`` expanded over the other objects),
``Closable(d)``, ``StoveOn``, ``Cooked(o)``.

``detect(o, p, f, j, k)`` determinizes observing o near p: its cost is the
self-loop cost ``c + c'/p − c'`` with p the ε-form of eq. (2).  ``pick``
has a declared success probability.  Continuous values come from streams:
``sample-obs`` (candidate poses from the particles), ``test-vis`` (the
NotBlocks test), ``placement``, ``grasp`` (two top-down grasps 90° apart), ``inv-kin`` (IK;
may fail, so never deferred) and ``motion`` (RRT-Connect; expensive and
likely, so deferrable — moves carry an optimistic trajectory until bound).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from nowplan.belief.determinize import StochasticCost
from nowplan.core.atoms import Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.operators import Action, Generator, Operator, Precondition
from nowplan.domains.kitchen import scene as S
from nowplan.domains.kitchen.conflicts import CONFLICTS, Occludes
from nowplan.domains.kitchen.heuristic import estimate
from nowplan.domains.kitchen.belief import Conf, KitchenBelief, Pose, Traj, pose_of
from nowplan.domains.kitchen.motion import DOWN, DOWN_TURNED, inverse_kinematics, rrt_connect, touching
from nowplan.planning.streams import Stream, StreamSet

O, P, F, G, Q, T, D, E, J, K = (Var(n) for n in ("o", "p", "f", "g", "q", "t", "d", "e", "j", "k"))
PICK = StochasticCost(cost=1.0, recovery=1.0, success=0.95)
GRASPS = {"top": DOWN, "top90": DOWN_TURNED}  # top-down grasps, the second turned 90° about the vertical
OVERLAP_MASS = 0.5  # belief mass of another object at a placement that makes it taken
MOTION_ATTEMPTS = 3  # RRT-Connect runs (fresh random samples) before a motion counts as failed


def _opened(container: str) -> float:
    """A container's joint when open: a drawer's travel, or the cabinet lid's slide."""
    return S.CABINET_OPEN if container == S.CABINET else S.DRAWER_OPEN


def _tests() -> dict[str, Predicate]:
    def at_conf(b: KitchenBelief, args: Any, v: Any) -> bool:
        return bool(np.max(np.abs(np.array(b.conf.q) - np.array(v.q))) < 1e-3)

    def is_open(b: KitchenBelief, args: Any, v: Any) -> bool:
        f = args[0]
        state = (b.drawers[f] > 0.2) if f in b.drawers else True
        return bool(state == v)

    def in_frame(b: KitchenBelief, args: Any, v: Any) -> bool:
        return bool((b.particles[args[0]].frame_mass(args[1]) >= 0.95) == v)

    def at_pose(b: KitchenBelief, args: Any, v: Any) -> bool:
        return b.localized_at(args[0], v)

    def closable(b: KitchenBelief, args: Any, v: Any) -> bool:
        ok = args[0] == S.CABINET or all(b.particles[o].frame_mass(args[0]) < 0.05 for o in S.TALL if o in b.particles)
        return bool(ok == v)

    return {
        "AtConf": Predicate("AtConf", 0, boolean=False, test=at_conf),
        "Open": Predicate("Open", 1, test=is_open),
        "HandEmpty": Predicate("HandEmpty", 0, test=lambda b, a, v: (b.held is None) == v),
        "Holding": Predicate("Holding", 1, test=lambda b, a, v: (b.held == a[0]) == v),
        "In": Predicate("In", 2, test=in_frame),
        "AtPose": Predicate("AtPose", 1, boolean=False, test=at_pose),
        "NotBlocks": Predicate("NotBlocks", 3, test=lambda b, a, v: b.not_blocks(a[0], a[1], a[2]) == v),
        "Closable": Predicate("Closable", 1, test=closable),
        "StoveOn": Predicate("StoveOn", 0, test=lambda b, a, v: b.stove_on == v),
        "Cooked": Predicate("Cooked", 1, test=lambda b, a, v: (a[0] in b.cooked) == v),
    }


class KitchenModel:
    """Builds the domain and streams for one belief (generators read it and its model scene)."""

    def __init__(self, belief: KitchenBelief) -> None:
        self.b = belief
        self._ik: dict[tuple[Any, ...], Conf | None] = {}
        self._pools: dict[tuple[Any, ...], list[Any]] = {}  # raw samples, kept across beliefs
        self._memo: dict[tuple[Any, ...], list[Any]] = {}  # belief-dependent results, per version
        self._pool_version = -1
        self._motion_failed: set[tuple[Conf, int]] = set()  # RRT targets that failed, per belief version
        self.streams = StreamSet([
            Stream("sample-obs", ("o", "pb"), ("obs",), ("Obs",), lambda b, e, o: None),
            Stream("test-vis", ("o", "obs", "o2", "pb2"), (), ("BVis",), lambda b, e, *a: None),
            Stream("placement", ("o", "f"), ("p",), ("Pose",), lambda b, e, *a: None),
            Stream("grasp", ("o",), ("g",), ("Grasp",), lambda b, e, *a: None),
            Stream("inv-kin", ("o", "p", "g"), ("q",), ("Kin",), lambda b, e, *a: None, cost=1.0,
                   expensive=True, likely=False),
            Stream("motion", ("q1", "q2"), ("t",), ("Motion",), self._motion, cost=1.0,
                   expensive=True, likely=True),
        ])
        belief.streams = self.streams
        belief.planning_heuristic = estimate
        # detect's BOccluded test, expanded: one NotBlocks precondition per other object (J, K, J2, …)
        extra = [Var(f"j{i}") for i in range(2, len(belief.objects) - 1)]
        self.others: tuple[Var, ...] = (J, K, *extra)
        self.occludes = Occludes(belief)
        self.domain = self._domain()

    # -- streams ------------------------------------------------------------------
    def _motion(self, belief: KitchenBelief, earlier: tuple[Action, ...], q2: Conf) -> Traj | None:
        """RRT-Connect to ``q2`` in the state the plan predicts after ``earlier`` (its start configuration,
        drawers, held and placed objects), so a later move of a plan bound all at once is checked in the
        kitchen it will run in, not in today's.  RRT-Connect gets ``MOTION_ATTEMPTS`` runs; a failure is
        remembered for this belief version only."""
        start, drawers, held, placed = self.predicted(earlier)
        belief.sync_scene(skip=(held,) if held else (), drawers=drawers)
        sc = belief.scene
        origins = {f: S.frame_origin(f, drawers) for f in belief.frames}
        for o, p in placed.items():
            if o != held:
                S.set_object(sc, o, origins[p.frame] + p.rel())
        ignore = [sc.objects[held]] if held else []
        # the ends of a move grasp or release an object: the gripper may touch it there
        movable = [sc.objects[o] for o in belief.objects if o != held]
        ignore += touching(sc, start.q, movable) + touching(sc, q2.q, movable)
        path = None
        for _ in range(MOTION_ATTEMPTS):  # a likely stream: a miss of the randomised search is retried
            path = rrt_connect(sc, start.q, q2.q, belief.prng, ignore=ignore)
            if path is not None:
                break
        if path is None:
            self._motion_failed.add((q2, belief.version))
            return None
        return Traj(tuple(path))

    def predicted(self, earlier: tuple[Action, ...]) -> tuple[Conf, dict[str, float], str | None, dict[str, Pose]]:
        """The robot configuration, drawer positions, held object and newly placed objects after ``earlier``
        (executed from the current belief)."""
        conf, drawers, held = self.b.conf, dict(self.b.drawers), self.b.held
        placed: dict[str, Pose] = {}
        for a in earlier:
            args: tuple[Any, ...] = a.args
            if a.name == "move":
                conf = args[0]
            elif a.name in ("pull", "push"):
                drawers[str(args[0])] = _opened(str(args[0])) if a.name == "pull" else 0.0
                conf = Conf(S.HOME)  # the arm retracts after moving the handle
            elif a.name in ("pick", "pick_tall"):
                held = str(args[0])
                placed.pop(held, None)
            elif a.name in ("place", "place_aside"):
                held = None
                placed[str(args[0])] = args[1]
        return conf, drawers, held, placed

    def _fresh(self) -> None:
        """Drop the memoised belief-dependent results when the belief has changed."""
        if self._pool_version != self.b.version:
            self._memo.clear()
            self._pool_version = self.b.version

    def _pool(self, key: tuple[Any, ...], size: int, draw: Any) -> list[Any]:
        """A persistent pool of samples for ``key``, grown to at least ``size`` draws.

        ``draw()`` returns one new sample (seeded by the belief's RNG).  The
        pool survives belief updates — so a replanning call sees the previous
        plan's placements again and can keep them — and the search sees the
        same samples at every node; a larger :attr:`StreamSet.level` adds new
        ones.  Callers filter the samples against the current belief.
        """
        pool = self._pools.setdefault(key, [])
        while len(pool) < size:
            pool.append(draw())
        return pool

    def _level(self) -> int:
        return int(getattr(self.streams, "level", 1))

    def candidates(self, o: str, frame: str | None, k: int) -> list[Pose]:
        """Up to ``k × level`` sampled poses of ``o`` where the camera could see it (best-supported first),
        fixed within a belief version.

        Spots the kitchen itself hides (the front of a drawer's tray behind its front panel) are left
        out before the list is cut: an object is looked for before it is picked, and no look can ever
        find it there, so such spots would crowd out the observable ones once negative evidence has
        moved the belief's mass into them.
        """
        self._fresh()
        n = k * self._level()
        key = ("obs", o, frame, n)
        if key not in self._memo:
            self._memo[key] = [p for p in self.b.candidate_poses(o, frame, 3 * n) if not self._hidden(o, p)][:n]
        return list(self._memo[key])

    def _hidden(self, o: str, p: Pose) -> bool:
        """Is ``o`` at ``p`` hidden from the camera by the kitchen itself (its drawer open, the other closed)?"""
        state = self._reaching_into(p.frame)
        return bool(self.b.statically_hidden(o, (S.frame_origin(p.frame, state) + p.rel())[None, :], state)[0])

    def ik(self, target: np.ndarray, ignore: tuple[str, ...] = (), frame: str | None = None,
           grasp: str = "top", drawers: dict[str, float] | None = None) -> Conf | None:
        """A configuration reaching ``target`` with ``grasp`` (cached per belief version); reaching into
        drawer ``frame``, the scene has that drawer open and the other closed (the action needs it so);
        ``drawers`` sets the drawers' state outright."""
        if drawers is None and frame in self.b.containers:
            drawers = self._reaching_into(frame)
        state = tuple((drawers or self.b.drawers).values())
        key = (tuple(np.round(target, 3)), ignore, state, grasp, self.b.version)
        if key not in self._ik:
            self.streams.calls["inv-kin"] += 1
            self.b.sync_scene(skip=ignore, drawers=drawers)
            q = inverse_kinematics(self.b.scene, target, self.b.prng, orientation=GRASPS[grasp])
            self._ik[key] = None if q is None else Conf(q)
        return self._ik[key]

    def _reaching_into(self, frame: str) -> dict[str, float]:
        """The containers' state for acting in ``frame``: it open, the others closed."""
        return {d: (_opened(d) if d == frame else 0.0) for d in self.b.containers}

    def _reach(self, target: np.ndarray, ignore: tuple[str, ...], frame: str) -> tuple[Conf | None, str]:
        """The first grasp with an IK solution at ``target``, and that solution."""
        for g in GRASPS:
            q = self.ik(target, ignore=ignore, frame=frame, grasp=g)
            if q is not None:
                return q, g
        return None, ""

    def grasp_target(self, o: str, pose: Pose) -> np.ndarray:
        origin = S.frame_origin(pose.frame, {d: S.DRAWER_OPEN for d in S.DRAWERS})
        target: np.ndarray = origin + pose.rel() + np.array([0.0, 0.0, S.SIZES[o][2] - 0.02])
        return target

    # -- generators ---------------------------------------------------------------
    def g_obs(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        o = b[O]
        others = [x for x in bel.objects if x != o]
        others += ["none"] * (len(self.others) - len(others))
        if P in b:
            poses = [b[P]] if isinstance(b[P], Pose) and b[P].frame != "hand" else []
        else:
            poses = self.candidates(o, b.get(F), 4)
        for p in poses:
            if p.frame in bel.containers and self._hidden(o, p):  # looking into a drawer needs it open
                continue
            yield {P: p, F: p.frame, **dict(zip(self.others, others, strict=True))}

    def g_pick(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        """Grasp poses and IK for picking ``o``; with ``o`` unbound (``Closable(f)``), each object in ``f``."""
        if O in b:
            objs = [b[O]]
        elif F in b:
            objs = [o for o in bel.objects if bel.particles[o].frame_mass(b[F]) >= 0.05]
        else:
            return
        for o in objs:
            seen = set()
            poses = [] if bel.held == o else [bel.mode_pose(o)]
            if (bel.held == o or poses[0].frame in bel.containers) and b.get(F, "counter") == "counter":
                # o may be picked where it will have been set down (to switch drawers, say)
                poses += self._placements(o, "counter")[: 2 * self._level()]
            if bel.held != o:
                poses += self.candidates(o, None, 3)
            for p in poses:
                if p in seen or (F in b and p.frame != b[F]):
                    continue
                seen.add(p)
                # an object believed to overlap o at p must have moved away by the time o is picked there
                # (if only neighbouring objects are in the way, the gripper is allowed to brush them:
                # the planner has no fluent for clearing a reach, and the world checks no arm contacts)
                for away in ((o, *self._overlapping(o, p)), tuple(bel.objects)):
                    q, g = self._reach(self.grasp_target(o, p), away, p.frame)
                    if q is not None:
                        yield {O: o, P: p, F: p.frame, G: g, Q: q}
                        break

    def _to_free(self, goal: Any, bel: KitchenBelief) -> list[str]:
        """Which object a ``HandEmpty`` subgoal should put down: the held one, else tall objects that
        a ``Closable`` subgoal needs out of their drawer (an object put down to be picked up again is
        placed through the pick's ``AtPose`` subgoal instead)."""
        want = [a.args[0] for a in getattr(goal, "atoms", ()) if a.predicate == "Closable" and a.value is True]
        tall = [o for o in bel.objects if o in S.TALL and any(bel.particles[o].frame_mass(f) >= 0.05 for f in want)]
        return ([bel.held] if bel.held is not None else []) + [o for o in tall if o != bel.held]

    def _gone(self, goal: Any, frame: str) -> tuple[str, ...]:
        """Objects that will have left ``frame`` when a subgoal wants it ``Closable`` (tall ones in it)."""
        if not any(a.predicate == "Closable" and a.args == (frame,) and a.value is True
                   for a in getattr(goal, "atoms", ())):
            return ()
        return tuple(o for o in self.b.objects if o in S.TALL and self.b.particles[o].frame_mass(frame) >= 0.05)

    def _placements(self, o: str, frame: str, n: int = 6, gone: tuple[str, ...] = ()) -> list[Pose]:
        """Placements of ``o`` in ``frame`` from a pool of ``n × level`` draws, free of the objects
        believed there (except those ``gone`` by then)."""
        reg = self.b.regions[frame]
        if frame == S.CABINET and o in S.TALL:
            return []  # a tall box does not fit under the cabinet's lid

        def draw() -> Pose:
            x = self.b.prng.uniform(reg.lo[0] + 0.03, reg.hi[0] - 0.03)
            y = self.b.prng.uniform(reg.lo[1] + 0.02, reg.hi[1] - 0.02)
            return pose_of(frame, np.array([x, y, S.SIZES[o][2]]))

        self._fresh()
        key = ("place", o, frame, n * self._level(), gone)
        if key not in self._memo:
            pool = self._pool(key[:3], n * self._level(), draw)
            self._memo[key] = [p for p in pool if not set(self._overlapping(o, p)) - set(gone)]
        return list(self._memo[key])

    def _overlapping(self, o: str, p: Pose, mass: float = OVERLAP_MASS) -> list[str]:
        """Objects with at least ``mass`` of belief overlapping ``o`` at ``p`` (2 cm margin)."""
        out = []
        for j in self.b.objects:
            if j == o or j == self.b.held:
                continue
            pb = self.b.particles[j]
            reach = np.array(S.SIZES[o][:2]) + np.array(S.SIZES[j][:2]) + 0.02
            inside = (pb.frames == p.frame) & np.all(np.abs(pb.poses[:, :2] - p.rel()[:2]) < reach, axis=1)
            if float(pb.weights[inside].sum()) >= mass:
                out.append(j)
        return out

    def g_place(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        """Placements and IK for putting ``o`` down; with ``o`` unbound (``HandEmpty``), see :meth:`_to_free`."""
        for o in [b[O]] if O in b else self._to_free(goal, bel):
            frame = b[F] if F in b else "counter"
            gone = self._gone(goal, frame)
            poses = [b[P]] if P in b else [p for p in self._placements(o, frame, gone=gone) if self._fits(o, p, goal)]
            # a few parking spots each (counted among the reachable ones: a spot out of the arm's reach
            # must not take the place of one within it)
            left = 2 * self._level() if O not in b else len(poses)
            for p in poses:
                if left <= 0:
                    break
                for g in GRASPS:
                    q = self.ik(self.grasp_target(o, p) + np.array([0, 0, 0.01]), ignore=(o, *gone), frame=p.frame,
                                grasp=g)
                    if q is not None:
                        left -= 1
                        yield {O: o, P: p, F: p.frame, G: g, Q: q}
                        break

    def _fits(self, o: str, p: Pose, goal: Any) -> bool:
        """Can ``o`` be set down at ``p`` for the subgoal ``goal``?  Not where it would hide what a later
        look needs to see (``NotBlocks(o, j, q)``, the :class:`Occludes` rule) nor on a spot the subgoal
        holds for another object (``AtPose(j) = q`` overlapping ``p``).  Sampled spots are filtered
        before they are cut to a few, so that spots the subgoal rules out do not crowd out the rest."""
        at = atom("AtPose", o, value=p)
        for a in getattr(goal, "atoms", ()):
            if a.predicate == "NotBlocks" and self.occludes(at, a):
                return False
            if a.predicate == "AtPose" and a.args[0] != o and isinstance(a.value, Pose) and a.value.frame == p.frame:
                j = str(a.args[0])
                reach = np.array(S.SIZES[o][:2]) + np.array(S.SIZES[j][:2])
                if np.all(np.abs(a.value.rel()[:2] - p.rel()[:2]) < reach):
                    return False
        return True

    def g_aside(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if O not in b or J not in b:
            return
        o, target, tpose = b[O], b[J], b[K]
        if not isinstance(tpose, Pose):
            return
        self._fresh()
        key = ("aside", o, target, tpose, self._level())
        if key not in self._memo:
            out = []
            region = bel.region_of(target, tpose)
            for p in self._placements(o, "counter", 10):
                xj = (bel.origins()["counter"] + p.rel())[None, :]
                if bel.blocks(target, o)(region, xj).any():
                    continue
                for g in GRASPS:
                    q = self.ik(self.grasp_target(o, p) + np.array([0, 0, 0.01]), ignore=(o,), grasp=g)
                    if q is not None:
                        out.append({P: p, G: g, Q: q})
                        break
            self._memo[key] = out
        for vals in self._memo[key]:
            if self._fits(o, vals[P], goal):
                yield dict(vals)

    def _handle(self, d: str, state: float) -> Conf | None:
        """A configuration at the drawer's handle (a few approach points are tried), or at the
        cabinet lid's edge."""
        if d == S.CABINET:
            for dz in (0.0, 0.04, -0.03):
                q = self.ik(S.cabinet_handle(state) + np.array([0.0, 0.0, dz]),
                            drawers={e: (state if e == d else 0.0) for e in self.b.containers})
                if q is not None:
                    return q
            return None
        for dy, dz in ((0.1, 0.22), (0.15, 0.2), (0.0, 0.2), (-0.05, 0.25), (0.05, 0.3), (-0.1, 0.3)):
            q = self.ik(np.array([0.0, S.FRONT_Y - state - dy, S.DRAWER_FLOOR[d] + dz]),
                        drawers={e: (state if e == d else 0.0) for e in self.b.containers})
            if q is not None:
                return q
        return None

    def g_handle(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        """The handle's configuration; ``E`` is the drawer that must be closed first (the stacked
        drawers open one at a time; the cabinet names itself: nothing else has to be closed)."""
        if b.get(D) not in bel.containers:
            return
        q = self._handle(b[D], 0.0)
        if q is not None:
            yield {Q: q, E: b[D] if b[D] == S.CABINET else "top" if b[D] == "bottom" else "bottom"}

    def g_button(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        q = self.ik(S.BUTTON + np.array([0.0, 0.0, 0.03]))
        if q is not None:
            yield {Q: q}

    def g_move(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if (b[Q], self.b.version) in self._motion_failed:
            return
        yield {T: self.streams.optimistic("motion", b[Q])}

    # -- costs ----------------------------------------------------------------------
    def detect_cost(self, bind: Any, bel: KitchenBelief) -> float:
        return bel.look_cost(bind[O], bind[P])

    def _domain(self) -> Domain:
        pre = Precondition
        conf = atom("AtConf", value=Q)
        ops = (
            Operator("move", (Q, T), (), (atom("AtConf", value=Q),), 1.0,
                     generators=(Generator("motion", (T,), self.g_move),)),
            Operator("detect", (O, P, F, *self.others),
                     (pre(atom("Open", F)), *(pre(atom("NotBlocks", j, O, P)) for j in self.others),
                      pre(atom("HandEmpty"))),
                     (atom("AtPose", O, value=P), atom("In", O, F)), self.detect_cost,
                     generators=(Generator("sample-obs", (P, F, *self.others), self.g_obs),)),
            Operator("pick", (O, P, F, G, Q),
                     (pre(atom("AtPose", O, value=P)), pre(atom("Open", F)), pre(atom("HandEmpty")), pre(conf)),
                     (atom("Holding", O), atom("HandEmpty", value=False), atom("In", O, F, value=False)),
                     PICK.determinized, param_types=("short", None, None, None, None),
                     generators=(Generator("inv-kin", (P, F, G, Q), self.g_pick),)),
            Operator("pick_tall", (O, P, F, G, Q),
                     (pre(atom("AtPose", O, value=P)), pre(atom("Open", F)), pre(atom("HandEmpty")), pre(conf)),
                     (atom("Holding", O), atom("HandEmpty", value=False), atom("In", O, F, value=False),
                      atom("Closable", F)),
                     PICK.determinized, param_types=("tall", None, None, None, None),
                     generators=(Generator("inv-kin", (P, F, G, Q), self.g_pick),)),
            Operator("place", (O, P, F, G, Q),
                     (pre(atom("Holding", O)), pre(atom("Open", F)), pre(conf)),
                     (atom("In", O, F), atom("AtPose", O, value=P), atom("HandEmpty"),
                      atom("Holding", O, value=False)), 1.0,
                     param_types=("movable", None, None, None, None),
                     generators=(Generator("placement", (P, F, G, Q), self.g_place),)),
            Operator("place_aside", (O, P, G, Q, J, K),
                     (pre(atom("Holding", O)), pre(conf)),
                     (atom("NotBlocks", O, J, K), atom("AtPose", O, value=P), atom("HandEmpty"),
                      atom("Holding", O, value=False)), 1.0,
                     param_types=("movable", None, None, None, None, None),
                     generators=(Generator("placement", (P, G, Q), self.g_aside),)),
            Operator("pull", (D, E, Q),
                     (pre(atom("Open", D, value=False)), pre(atom("Open", E, value=False)), pre(atom("HandEmpty")),
                      pre(conf)),
                     (atom("Open", D), atom("AtConf", value=Conf(S.HOME))), 1.0, param_types=("drawer", None, None),
                     generators=(Generator("inv-kin", (Q, E), self.g_handle),)),
            Operator("push", (D, Q),
                     (pre(atom("Open", D)), pre(atom("Closable", D)), pre(atom("HandEmpty")), pre(conf)),
                     (atom("Open", D, value=False), atom("AtConf", value=Conf(S.HOME))), 1.0,
                     param_types=("drawer", None),
                     generators=(Generator("inv-kin", (Q,), self.g_button_or_handle),)),
            Operator("cook", (O, Q),
                     (pre(atom("In", O, "stove")), pre(atom("StoveOn", value=False)), pre(atom("HandEmpty")), pre(conf)),
                     (atom("Cooked", O), atom("StoveOn")), 1.0, param_types=("movable", None),
                     generators=(Generator("inv-kin", (Q,), self.g_button),)),
            Operator("stove_off", (Q,), (pre(atom("StoveOn")), pre(atom("HandEmpty")), pre(conf)),
                     (atom("StoveOn", value=False),), 1.0,
                     generators=(Generator("inv-kin", (Q,), self.g_button),)),
        )
        types = {"movable": None, "short": "movable", "tall": "movable", "drawer": None}
        return Domain("kitchen", _tests(), ops, types=types, conflicts=(*CONFLICTS, self.occludes))

    def g_button_or_handle(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if b.get(D) not in bel.containers:
            return
        q = self._handle(b[D], _opened(b[D]))
        if q is not None:
            yield {Q: q}
