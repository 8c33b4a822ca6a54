"""The NAMO domain: belief fluents, operators with criticalities, costs and conflicts.

Fluents (all tested on the belief):

* ``RobotAt(p)`` — ``p`` is the robot's nominal pose, or its mean pose is within
  ``at_tol`` of ``p`` by ``at_sd`` standard deviations (``NamoBelief.surely_at``);
* ``HandEmpty()`` / ``Holding(o, m)`` — what the gripper holds (``m`` is the
  :class:`~nowplan.domains.namo.geometry.Manip` it was grasped for);
* ``Observed(R)`` — no fog left in region ``R`` that a look from its view
  point could reveal;
* ``BClear(R, ex) = ε`` — with probability at least ``1 - ε`` no known
  object other than those in ``ex`` meets ``R``;
* ``BVRelPose(o) = ε`` — object ``o``'s position is known to within ``ε``;
* ``Localized() = ε`` — the robot's own position is known to within ``ε``;
* ``OutOfWay(R, o)`` — as far as the robot knows, ``o``'s body (not just its
  shadow) stays out of ``R``: a look can then shrink the shadow out of ``R``
  (``LookClear``); once looks show the body in ``R``, no look can, and the plan
  that relied on one is no longer applicable (replanning moves the object);
* ``Promising(v, o)`` — a look at ``o`` from ``v`` has not been found futile (the
  object went undetected from there) since the last perceptual event: a plan
  that looks again from there is no longer applicable once one look missed;
* ``Fits(o, m)`` — the manipulation ``m`` was planned for ``o`` where the robot
  still believes it is (its estimate within ``refit`` of ``m.obj_at``, 0.15 m): a look
  that moves the estimate further makes a plan that picks with ``m`` inapplicable,
  so the drag is planned again for where the object is, not where it was thought;
  nor does it fit once a pick with ``m`` was stopped by another object
  (``NamoBelief.blocked_picks``): the level above plans another manipulation
  instead of issuing the same pick again (issue 14);
* ``Placed(o, box)`` — an effect only: ``o`` rests as ``box`` (used by the
  conflict rule that keeps placements out of regions a plan needs clear).

Criticalities (higher = planned first, seed 000 IV-A): where the robot is
and what it holds (3); space observed before moving into it and an object
localised before it is picked (2); the swept volume clear and the robot
localised before a base move (1).  So a top-level plan is a chain of moves,
refining a move adds a look, refining it again adds clearing and
localisation.
"""

from __future__ import annotations

from typing import Any

from nowplan.core.atoms import Atom, ToleranceRule, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.operators import Generator, Operator, Precondition
from nowplan.domains.namo import generators as gens
from nowplan.domains.namo import placement
from nowplan.domains.namo.belief import NamoBelief
from nowplan.domains.namo.geometry import Box, Manip, Region
from nowplan.domains.namo.params import DEFAULT_PARAMS, Params
from nowplan.domains.namo.triggers import make_triggers

TOL = ToleranceRule()

A, B, SW = Var("a"), Var("b"), Var("sw")
V, R, O, AT, LM, E = Var("v"), Var("r"), Var("o"), Var("at"), Var("lm"), Var("e")
M, HOME, PC, EX, EXO, PLACE = Var("m"), Var("home"), Var("pc"), Var("ex"), Var("exo"), Var("place")
SPOT, ONLY, SURVEY, HIDDEN, KEEP = Var("spot"), Var("only"), Var("survey"), Var("hidden"), Var("keep")
PRE, N = Var("pre"), Var("n")

WHERE, SEE, CLEAR = 3, 2, 1


# -- tests -------------------------------------------------------------------------------
def _t_robot_at(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    return b.surely_at(args[0]) == bool(value)


def _t_hand_empty(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    return (b.held is None) == bool(value)


def _t_holding(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    """Holding ``o`` grasped from the manipulation's pick configuration (its placement may be re-planned).

    A re-placement of the held object starts where the robot stands now, which a grasp that pushed
    the robot may have moved off the pick configuration: it holds too (same home, robot at its start).
    """
    m, h = args[1], b.held_manip
    held = b.held == args[0] and h is not None and isinstance(m, Manip) and (
        h.pick_conf == m.pick_conf or (h.home == m.home and b.at(m.pick_conf)))
    return held == bool(value)


def _t_observed(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    return b.is_observed(args[0]) == bool(value)


def _t_bclear(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    if isinstance(value, bool):
        return b.clear(args[0], args[1], DEFAULT_PARAMS.eps_clear) == value
    return b.clear(args[0], args[1], float(value))


def _t_bvrelpose(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    s = b.object_sigma(args[0])
    return s is not None and s <= float(value)


def _t_localized(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    return b.robot_sigma <= float(value)


def _t_out_of_way(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    return (not b.in_the_way(args[0], args[1])) == bool(value)


def _t_promising(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    v, o = args
    return (b.futile_looks.get((v, o)) != b.percept) == bool(value)


def _t_fits(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    o, m = b.objects.get(args[0]), args[1]
    fits = (o is not None and isinstance(m, Manip) and o.center.dist(m.obj_at) <= b.params.refit
            and m not in b.blocked_picks)  # a pick this manipulation began was stopped by another object
    return fits == bool(value)


def _t_keep(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    """A reservation, not a belief condition: it only carries its regions through regression."""
    return bool(value)


def _t_placed(b: NamoBelief, args: tuple[Any, ...], value: Any) -> bool:
    o = b.objects.get(args[0])
    box: Box = args[1]
    return (o is not None and b.held != args[0] and o.center.dist(box.center) <= 0.2) == bool(value)


PREDICATES = {
    "RobotAt": Predicate("RobotAt", 1, test=_t_robot_at),
    "HandEmpty": Predicate("HandEmpty", 0, test=_t_hand_empty),
    "Holding": Predicate("Holding", 2, test=_t_holding),
    "Observed": Predicate("Observed", 1, test=_t_observed),
    "BClear": Predicate("BClear", 2, rule=TOL, test=_t_bclear, boolean=False),
    "BVRelPose": Predicate("BVRelPose", 1, rule=TOL, test=_t_bvrelpose, boolean=False),
    "Localized": Predicate("Localized", 0, rule=TOL, test=_t_localized, boolean=False),
    "Placed": Predicate("Placed", 2, test=_t_placed),
    "Keep": Predicate("Keep", 2, test=_t_keep),
    "OutOfWay": Predicate("OutOfWay", 2, test=_t_out_of_way),
    "Fits": Predicate("Fits", 2, test=_t_fits),
    "Promising": Predicate("Promising", 2, test=_t_promising),
}


# -- conflicts between different fluents ----------------------------------------------------
def _one_pose(x: Atom, y: Atom) -> bool:
    return x.predicate == y.predicate == "RobotAt" and x.value is True and y.value is True and x.args != y.args


def _one_grip(x: Atom, y: Atom) -> bool:
    if x.predicate == "HandEmpty" and y.predicate == "Holding":
        return x.value is True and y.value is True
    return x.predicate == y.predicate == "Holding" and x.value is True and y.value is True and x.args != y.args


def _placed_in_clear(x: Atom, y: Atom) -> bool:
    """Putting an object down inside a region that must be clear breaks that requirement."""
    if x.predicate != "Placed" or y.predicate != "BClear" or x.value is not True:
        return False
    obj, where = x.args
    region, ex = y.args
    if not isinstance(ex, frozenset) or obj in ex or not isinstance(region, Region) or not isinstance(where, Box):
        return False
    return region.hits_box(where)


def _placed_in_kept(x: Atom, y: Atom) -> bool:
    """Putting an object down where a later manipulation drives or drags breaks that manipulation."""
    if x.predicate != "Placed" or y.predicate != "Keep" or x.value is not True:
        return False
    obj, where = x.args
    regions, owner = y.args
    if obj == owner or not isinstance(where, Box) or not isinstance(regions, tuple):
        return False
    return any(isinstance(r, Region) and r.hits_box(where) for r in regions)


CONFLICTS = (_one_pose, _one_grip, _placed_in_clear, _placed_in_kept)


# -- costs -----------------------------------------------------------------------------------
def make_costs(params: Params) -> dict[str, Any]:
    def move_cost(b: Any, belief: Any) -> float:
        region: Region = b[SW]
        c = region.length
        if isinstance(belief, NamoBelief):
            c += params.clear_cost * len(belief.blockers(region, 0.5))
        return c

    def pick_cost(b: Any, belief: Any) -> float:
        m: Manip = b[M]
        return 1.0 + m.lengths[0]

    def place_cost(b: Any, belief: Any) -> float:
        m: Manip = b[M]
        _, carry, ret = m.lengths
        return 1.0 + carry + ret

    return {"move": move_cost, "pick": pick_cost, "place": place_cost}


def _looks_cost(b: Any, belief: Any) -> float:
    """A look action takes ``?n`` looks, each costing 1."""
    return float(b.get(N, 1))


def build_domain(params: Params = DEFAULT_PARAMS) -> Domain:
    costs = make_costs(params)
    P = Precondition
    operators = (
        Operator(
            "Move", (A, B, SW),
            (P(atom("RobotAt", A), WHERE), P(atom("HandEmpty"), WHERE),
             P(atom("Observed", SW), SEE),
             P(atom("BClear", SW, frozenset(), value=params.eps_clear), CLEAR),
             P(atom("Localized", value=params.eps_loc), CLEAR)),
            (atom("RobotAt", B), atom("RobotAt", A, value=False)),
            cost=costs["move"],
            generators=(Generator("move", (A, SW), gens.gen_move, (B,)),),
        ),
        Operator(
            "Look", (V, R),
            (P(atom("RobotAt", V), WHERE),),
            (atom("Observed", R),),
            cost=1.0,
            generators=(Generator("look", (V,), gens.gen_look, (R,)),),
        ),
        Operator(
            "LookObj", (V, O, AT, E, PRE, N),
            (P(atom("RobotAt", V), WHERE), P(atom("BVRelPose", O, value=PRE), SEE),
             P(atom("Promising", V, O), WHERE)),
            (atom("BVRelPose", O, value=E),),
            cost=_looks_cost,
            generators=(Generator("look_obj", (V, AT, PRE, N), gens.gen_look_obj, (O, E)),),
        ),
        Operator(
            "LookClear", (V, O, AT, R, EX, EXO, PRE, N),
            (P(atom("RobotAt", V), WHERE), P(atom("BClear", R, EXO, value=params.eps_clear), WHERE),
             P(atom("BVRelPose", O, value=PRE), WHERE), P(atom("OutOfWay", R, O), WHERE),
             P(atom("Promising", V, O), WHERE)),
            (atom("BClear", R, EX, value=params.eps_clear),),
            cost=_looks_cost,
            generators=(Generator("look_clear", (O, V, AT, EXO, PRE, N), gens.gen_look_clear, (R, EX)),),
        ),
        Operator(
            "LookLandmark", (V, LM, E),
            (P(atom("RobotAt", V), WHERE),),
            (atom("Localized", value=E),),
            cost=1.0,
            generators=(Generator("look_landmark", (V, LM), gens.gen_look_landmark, (E,)),),
        ),
        Operator(
            "Pick", (O, M, HOME, PC, HIDDEN),
            (P(atom("HandEmpty"), WHERE), P(atom("RobotAt", HOME), WHERE),
             P(atom("BVRelPose", O, value=params.eps_pick), SEE), P(atom("Fits", O, M), WHERE)),
            (atom("Holding", O, M), atom("HandEmpty", value=False), atom("RobotAt", HOME, value=False),
             atom("RobotAt", PC), atom("Observed", HIDDEN, value=False)),
            cost=costs["pick"],
            generators=(Generator("manip_fields", (HOME, PC, HIDDEN), placement.gen_manip_fields, (M,)),),
        ),
        Operator(
            "Place", (O, R, EX, EXO, M, HOME, PC, PLACE, SPOT, ONLY, SURVEY, KEEP),
            (P(atom("Holding", O, M), WHERE), P(atom("RobotAt", PC), WHERE), P(atom("Observed", SURVEY), WHERE),
             P(atom("BClear", SURVEY, ONLY, value=params.eps_clear), WHERE),
             P(atom("BClear", R, EXO, value=params.eps_clear), WHERE),
             P(atom("BClear", SPOT, ONLY, value=params.eps_clear), WHERE), P(atom("Keep", KEEP, O), WHERE)),
            (atom("BClear", R, EX, value=params.eps_clear), atom("HandEmpty"),
             atom("Holding", O, M, value=False), atom("RobotAt", PC, value=False),
             atom("RobotAt", HOME), atom("Placed", O, PLACE), atom("Observed", R, value=False)),
            cost=costs["place"],
            generators=(Generator("place", (O, EXO, M, HOME, PC, PLACE, SPOT, ONLY, SURVEY, KEEP), placement.gen_place,
                                  (R, EX)),),
        ),
    )
    return Domain("namo", PREDICATES, operators, conflicts=CONFLICTS, triggers=make_triggers(params))


DOMAIN = build_domain()
