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
NotBlocks test), ``placement``, ``grasp`` (one top grasp), ``inv-kin`` (IK;
may fail, so never deferred) and ``motion`` (RRT-Connect; expensive and
likely, so deferrable — moves carry an optimistic trajectory until bound).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from nowplan.belief.determinize import StochasticCost, epsilon_lower_bound, self_loop_cost
from nowplan.core.atoms import Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.operators import Action, Generator, Operator, Precondition
from nowplan.domains.kitchen import scene as S
from nowplan.domains.kitchen.belief import DELTA, EPSILON, Conf, KitchenBelief, Pose, Traj, pose_of
from nowplan.domains.kitchen.motion import inverse_kinematics, rrt_connect
from nowplan.planning.streams import Stream, StreamSet

O, P, F, G, Q, T, D, E, J, K = (Var(n) for n in ("o", "p", "f", "g", "q", "t", "d", "e", "j", "k"))
PICK = StochasticCost(cost=1.0, recovery=1.0, success=0.95)
GRASP = "top"


def _tests() -> dict[str, Predicate]:
    def at_conf(b: KitchenBelief, args: Any, v: Any) -> bool:
        return bool(np.max(np.abs(np.array(b.conf.q) - np.array(v.q))) < 1e-3)

    def is_open(b: KitchenBelief, args: Any, v: Any) -> bool:
        f = args[0]
        state = (b.drawers[f] > 0.2) if f in S.DRAWERS else True
        return state == v

    def in_frame(b: KitchenBelief, args: Any, v: Any) -> bool:
        return (b.particles[args[0]].frame_mass(args[1]) >= 0.95) == v

    def at_pose(b: KitchenBelief, args: Any, v: Any) -> bool:
        return b.localized_at(args[0], v)

    def closable(b: KitchenBelief, args: Any, v: Any) -> bool:
        ok = all(b.particles[o].frame_mass(args[0]) < 0.05 for o in S.TALL if o in b.particles)
        return ok == v

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
        self.domain = self._domain()

    # -- streams ------------------------------------------------------------------
    def _motion(self, belief: KitchenBelief, earlier: tuple[Action, ...], q2: Conf) -> Traj | None:
        start = belief.conf
        for a in reversed(earlier):
            if a.name == "move":
                start = a.args[0]
                break
        belief.sync_scene()
        ignore = [belief.scene.objects[belief.held]] if belief.held else []
        path = rrt_connect(belief.scene, start.q, q2.q, belief.prng, ignore=ignore)
        return None if path is None else Traj(tuple(path))

    def ik(self, target: np.ndarray, ignore: tuple[str, ...] = ()) -> Conf | None:
        key = (tuple(np.round(target, 3)), ignore, tuple(self.b.drawers.values()), self.b.version)
        if key not in self._ik:
            self.streams.calls["inv-kin"] += 1
            self.b.sync_scene(skip=ignore)
            q = inverse_kinematics(self.b.scene, target, self.b.prng)
            self._ik[key] = None if q is None else Conf(q)
        return self._ik[key]

    def grasp_target(self, o: str, pose: Pose) -> np.ndarray:
        origin = S.frame_origin(pose.frame, {d: S.DRAWER_OPEN for d in S.DRAWERS})
        return origin + pose.rel() + np.array([0.0, 0.0, S.SIZES[o][2] - 0.02])

    # -- generators ---------------------------------------------------------------
    def g_obs(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        o = b[O]
        others = [x for x in bel.objects if x != o]
        others += ["none"] * (2 - len(others))
        if P in b:
            poses = [b[P]] if isinstance(b[P], Pose) and b[P].frame != "hand" else []
        else:
            poses = bel.candidate_poses(o, b.get(F))
        for p in poses:
            yield {P: p, F: p.frame, J: others[0], K: others[1]}

    def g_pick(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if O not in b:
            return
        o = b[O]
        if bel.held == o:
            return
        poses = [bel.mode_pose(o)] + [p for p in bel.candidate_poses(o, None, 3)]
        seen = set()
        for p in poses:
            if p in seen:
                continue
            seen.add(p)
            q = self.ik(self.grasp_target(o, p), ignore=(o,))
            if q is not None:
                yield {P: p, F: p.frame, G: GRASP, Q: q}

    def _placements(self, o: str, frame: str, n: int = 6) -> list[Pose]:
        reg = S.regions()[frame]
        out = []
        for _ in range(n):
            x = self.b.prng.uniform(reg.lo[0] + 0.03, reg.hi[0] - 0.03)
            y = self.b.prng.uniform(reg.lo[1] + 0.02, reg.hi[1] - 0.02)
            p = pose_of(frame, np.array([x, y, S.SIZES[o][2]]))
            if self._free(o, p):
                out.append(p)
        return out

    def _free(self, o: str, p: Pose) -> bool:
        origins = self.b.origins()
        w = origins[p.frame] + p.rel()
        for j in self.b.objects:
            if j == o or j == self.b.held:
                continue
            m = self.b.mode_pose(j)
            if m.frame != p.frame:
                continue
            d = np.abs(origins[m.frame] + m.rel() - w)[:2]
            if np.all(d < np.array(S.SIZES[o][:2]) + np.array(S.SIZES[j][:2]) + 0.02):
                return False
        return True

    def g_place(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if O not in b:
            return
        o = b[O]
        poses = [b[P]] if P in b else self._placements(o, b[F] if F in b else "counter")
        for p in poses:
            q = self.ik(self.grasp_target(o, p) + np.array([0, 0, 0.01]), ignore=(o,))
            if q is not None:
                yield {P: p, F: p.frame, G: GRASP, Q: q}

    def g_aside(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if O not in b or J not in b:
            return
        o, target, tpose = b[O], b[J], b[K]
        if not isinstance(tpose, Pose):
            return
        region = bel.region_of(target, tpose)
        for p in self._placements(o, "counter", 10):
            xj = (bel.origins()["counter"] + p.rel())[None, :]
            if bel.blocks(target, o)(region, xj).any():
                continue
            q = self.ik(self.grasp_target(o, p) + np.array([0, 0, 0.01]), ignore=(o,))
            if q is not None:
                yield {P: p, G: GRASP, Q: q}

    def _handle(self, d: str, state: float) -> Conf | None:
        """A configuration at the drawer's handle (a few approach points are tried)."""
        for dy, dz in ((0.1, 0.22), (0.15, 0.2), (0.0, 0.2), (-0.05, 0.25), (0.05, 0.3), (-0.1, 0.3)):
            q = self.ik(np.array([0.0, S.FRONT_Y - state - dy, S.DRAWER_FLOOR[d] + dz]))
            if q is not None:
                return q
        return None

    def g_handle(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if b.get(D) not in S.DRAWERS:
            return
        q = self._handle(b[D], 0.0)
        if q is not None:
            yield {Q: q, E: "top" if b[D] == "bottom" else "bottom"}

    def g_button(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        q = self.ik(S.BUTTON + np.array([0.0, 0.0, 0.03]))
        if q is not None:
            yield {Q: q}

    def g_move(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if self.streams.has_failed("motion", b[Q]):
            return
        yield {T: self.streams.optimistic("motion", b[Q])}

    # -- costs ----------------------------------------------------------------------
    def detect_cost(self, bind: Any, bel: KitchenBelief) -> float:
        o, p = bind[O], bind[P]
        mass = bel.particles[o].mass_near(p.frame, p.rel(), DELTA)
        n = len(bel.objects)
        prob = epsilon_lower_bound(bel.sensor.p_fn, mass, EPSILON, n)
        return self_loop_cost(1.0, 1.0, prob) if prob > 0 else math.inf

    def _domain(self) -> Domain:
        pre = Precondition
        conf = atom("AtConf", value=Q)
        ops = (
            Operator("move", (Q, T), (), (atom("AtConf", value=Q),), 1.0,
                     generators=(Generator("motion", (T,), self.g_move),)),
            Operator("detect", (O, P, F, J, K),
                     (pre(atom("Open", F)), pre(atom("NotBlocks", J, O, P)), pre(atom("NotBlocks", K, O, P)),
                      pre(atom("HandEmpty"))),
                     (atom("AtPose", O, value=P), atom("In", O, F)), self.detect_cost,
                     generators=(Generator("sample-obs", (P, F, J, K), self.g_obs),)),
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
        return Domain("kitchen", _tests(), ops, types=types)

    def g_button_or_handle(self, b: dict[Var, Any], goal: Any, bel: KitchenBelief, ctx: Any) -> Any:
        if b.get(D) not in S.DRAWERS:
            return
        q = self._handle(b[D], S.DRAWER_OPEN)
        if q is not None:
            yield {Q: q}
