"""The domain author's API (nowplan.api): conflict helpers, static preconditions, the world base,
belief capabilities, the particle belief, and the logged heuristic fallback."""

from __future__ import annotations

import inspect
import logging

import pytest

import nowplan.api as api
from nowplan.api import (
    Action, Belief, Domain, Goal, HasState, HasValues, ListsFacts, ModelError, Observation, Operator,
    ParticleBelief, Precondition, Predicate, Problem, SimulatedWorld, State, SymbolicBelief,
    SymbolicWorld, Var, at_most_one, atom, capabilities, check_belief, exactly_one, excludes, static,
)
from nowplan.errors import ContradictoryGoalError
from nowplan.belief.particle_belief import UNKNOWN

x, y, h, o = Var("x"), Var("y"), Var("h"), Var("o")


def test_every_public_name_has_a_docstring() -> None:
    for name in api.__all__:
        obj = getattr(api, name)
        if inspect.isclass(obj) or inspect.isfunction(obj):
            doc = obj.__doc__ or ""
            assert doc and not doc.startswith(f"{obj.__name__}("), name  # not dataclass's generated one


# -- conflict helpers ---------------------------------------------------------------------------

def _rules(*conflicts: object) -> Domain:
    preds = {p.name: p for p in (Predicate("robot_in", 1), Predicate("at", 2), Predicate("holding", 2),
                                 Predicate("hand_empty", 1), Predicate("edge", 3))}
    return Domain("t", preds, conflicts=conflicts)  # type: ignore[arg-type]


def test_at_most_one_keys() -> None:
    one_room = at_most_one("robot_in", key=())
    assert one_room(atom("robot_in", "a"), atom("robot_in", "b"))
    assert not one_room(atom("robot_in", "a"), atom("robot_in", "a"))
    per_item = at_most_one("at", "holding", key=0)
    assert per_item(atom("at", "cup", "k"), atom("holding", "cup", "h1"))
    assert not per_item(atom("at", "cup", "k"), atom("at", "key", "k"))
    pair = at_most_one("edge", key=(0, 1))
    assert pair(atom("edge", "a", "b", 1), atom("edge", "a", "b", 2))
    assert not pair(atom("edge", "a", "b", 1), atom("edge", "a", "c", 1))
    by_fn = at_most_one("at", key=lambda a: a.args[1] if a.args[1] != "floor" else None)  # one item per shelf
    assert by_fn(atom("at", "cup", "s1"), atom("at", "key", "s1"))
    assert not by_fn(atom("at", "cup", "floor"), atom("at", "key", "floor"))
    assert not one_room(atom("robot_in", "a", value=False), atom("robot_in", "b"))  # negative atoms: no group
    with pytest.raises(ValueError):
        at_most_one()


def test_excludes_with_shared_variables() -> None:
    free_hand = excludes(atom("hand_empty", h), atom("holding", h, o))
    assert free_hand(atom("hand_empty", "left"), atom("holding", "left", "cup"))
    assert not free_hand(atom("hand_empty", "left"), atom("holding", "right", "cup"))
    assert not free_hand(atom("holding", "left", "cup"), atom("hand_empty", "left"))  # ordered; Rules tries both
    dom = _rules(free_hand)
    assert dom.rules.atoms_conflict(atom("holding", "left", "cup"), atom("hand_empty", "left"))
    with pytest.raises(ContradictoryGoalError, match="cannot both hold"):
        Goal.of([atom("hand_empty", "left"), atom("holding", "left", "cup")], dom.rules)
    Goal.of([atom("hand_empty", "left"), atom("holding", "right", "cup")], dom.rules)


def test_goal_with_two_rooms_is_contradictory() -> None:
    dom = _rules(exactly_one("robot_in", key=()))
    with pytest.raises(ContradictoryGoalError):
        Goal.of([atom("robot_in", "a"), atom("robot_in", "b")], dom.rules)


def test_exactly_one_checks_the_initial_state_per_typed_object() -> None:
    preds = {"at": Predicate("at", 2, ("item", "room")), "holding": Predicate("holding", 1, ("item",))}
    dom = Domain("t", preds, types={"item": None, "room": None}, conflicts=(exactly_one("at", "holding", key=0),))
    objs = {"cup": "item", "key": "item", "k": "room"}
    Problem(dom, objs, State([atom("at", "cup", "k"), atom("holding", "key")]), Goal(), "ok")
    with pytest.raises(ModelError, match="no at or holding atom for 'key'"):
        Problem(dom, objs, State([atom("at", "cup", "k")]), Goal(), "missing")
    with pytest.raises(ModelError, match="at\\(cup, k\\) and holding\\(cup\\)"):
        Problem(dom, objs, State([atom("at", "cup", "k"), atom("holding", "cup"), atom("holding", "key")]),
                Goal(), "twice")


# -- static preconditions ---------------------------------------------------------------------

def test_static_preconditions_take_the_operators_top_criticality() -> None:
    preds = {"at": Predicate("at", 1), "edge": Predicate("edge", 2)}
    move = Operator("move", (x, y), (Precondition(atom("at", x), 3), static(atom("edge", x, y))),
                    (atom("at", y), atom("at", x, value=False)))
    assert [p.criticality for p in move.preconditions] == [3, 3]
    assert move.criticalities == (3,)  # no extra level for the static fact
    Domain("g", preds, (move,))
    bad = Operator("bad", (x, y), (static(atom("at", x)),), (atom("at", y),))
    with pytest.raises(ModelError, match=r"static\(at\(\?x\)\) but an operator changes 'at'"):
        Domain("g", preds, (bad,))


# -- the world base ---------------------------------------------------------------------------

class Counter(SimulatedWorld):
    """A toy world: a counter an action increments; it may jam and drift by itself."""

    def __init__(self, jam: float = 0.0, **kw: float) -> None:
        self.value = 0
        self.jam = jam
        super().__init__(**kw)  # type: ignore[arg-type]

    def apply(self, action: Action) -> None:
        self.value += 1

    def fault(self, action: Action) -> str | None:
        return "jammed" if self.rng.random() < self.jam else None

    def exogenous_change(self) -> list[str]:
        self.value -= 1
        return ["drift"]


INC = Operator("inc", ()).instantiate({})


def test_simulated_world_faults_are_constructor_options() -> None:
    assert Counter().execute(INC).success
    always = Counter(failure_prob=1.0)
    obs = always.execute(INC)
    assert not obs.success and obs.info["reason"] == "injected failure" and always.value == 0
    jammed = Counter(jam=1.0)
    assert jammed.execute(INC).info["reason"] == "jammed" and jammed.failures == 1
    drifting = Counter(exogenous_prob=1.0)
    assert drifting.execute(INC).exogenous == ("drift",) and drifting.value == 0
    for bad in (-0.1, 1.5):
        with pytest.raises(ValueError, match="must be in"):
            Counter(failure_prob=bad)


def test_set_faults_and_worlds_without_exogenous_changes() -> None:
    w = Counter()
    w.set_faults(failure_prob=1.0)
    assert not w.execute(INC).success
    dom = Domain("t", {"p": Predicate("p", 0)})
    plain = SymbolicWorld(dom, State())
    assert isinstance(plain, api.FaultInjection) and not plain.has_exogenous
    with pytest.raises(ValueError, match="makes no exogenous changes"):
        plain.set_faults(exogenous_prob=0.5)


def test_world_draws_follow_the_seed() -> None:
    def run(seed: int) -> list[bool]:
        w = Counter(seed=seed, failure_prob=0.5, jam=0.3, exogenous_prob=0.4)
        return [w.execute(INC).success for _ in range(30)]

    assert run(4) == run(4) and run(4) != run(5)


# -- belief capabilities ----------------------------------------------------------------------

class NoUpdate:
    def value(self, key: object) -> object:
        return None


class UpdateOnly:
    def update(self, action: Action, observation: Observation) -> None:
        pass


def test_check_belief_names_what_is_missing() -> None:
    dom = Domain("t", {"p": Predicate("p", 0), "q": Predicate("q", 0, test=lambda b, a, v: True)})
    with pytest.raises(ModelError, match="NoUpdate has no update"):
        check_belief(dom, NoUpdate())
    with pytest.raises(ModelError, match=r"UpdateOnly has no value\(key\).*\(p\)"):
        check_belief(dom, UpdateOnly())
    tested = Domain("t", {"q": Predicate("q", 0, test=lambda b, a, v: True)})
    check_belief(tested, UpdateOnly())  # every predicate has a test: value() is not needed
    sb = SymbolicBelief(State())
    check_belief(dom, sb)
    assert isinstance(sb, Belief) and isinstance(sb, HasValues) and isinstance(sb, ListsFacts)
    assert capabilities(sb) == ["value", "facts", "state"] and capabilities(UpdateOnly()) == []


def test_a_run_refuses_a_belief_without_update() -> None:
    from nowplan.api import Episode, parse_strategy, run_episode

    dom = Domain("t", {"p": Predicate("p", 0)}, (Operator("make", (), (), (atom("p"),)),))
    prob = Problem(dom, {}, State(), Goal.of([atom("p")]), "t")
    ep = Episode(prob, SymbolicWorld(dom, State()), NoUpdate())
    with pytest.raises(ModelError, match="has no update"):
        run_episode(ep, parse_strategy("hpn"))


# -- the particle belief ----------------------------------------------------------------------

def test_particle_belief_believes_what_is_likely_enough() -> None:
    door_open, door_shut = State([atom("open", "d"), atom("here", "r")]), State([atom("here", "r")])
    b = ParticleBelief([door_open] * 8 + [door_shut] * 2, threshold=0.9, seed=1)
    # 0.8 < 0.9 and 0.2 < 0.9: the door is unknown either way (neither open(d) nor its negation holds)
    assert b.value(("here", ("r",))) is True and b.value(("open", ("d",))) is UNKNOWN
    assert b.unknowns() == frozenset({("open", ("d",))})
    assert b.probability(atom("open", "d")) == pytest.approx(0.8)
    assert b.probability(atom("open", "d", value=False)) == pytest.approx(0.2)
    assert isinstance(b, HasState) and b.state == door_shut

    class Sensor(ParticleBelief):
        def likelihood(self, state: State, action: Action, observation: Observation) -> float:
            saw_open = bool(observation.data)
            return 0.9 if state.holds(atom("open", "d")) == saw_open else 0.1

    look = Operator("look", ()).instantiate({})
    s = Sensor([door_open] * 5 + [door_shut] * 5, threshold=0.9, seed=2)
    for _ in range(3):
        s.update(look, Observation(True, True))
    assert s.probability(atom("open", "d")) > 0.99 and s.value(("open", ("d",))) is True


def test_particle_belief_resets_to_an_observed_state_no_particle_explains() -> None:
    a, b_ = State([atom("p")]), State([atom("q")])
    b = ParticleBelief([a, a], seed=0)
    seen = State([atom("r")])
    b.update(Operator("noop", ()).instantiate({}), Observation(True, seen))
    assert b.state == seen and b.particles == [seen]
    assert ParticleBelief([a, b_], seed=0).state == State()  # 0.5 each: neither believed
    with pytest.raises(ModelError):
        ParticleBelief([])
    with pytest.raises(ModelError):
        ParticleBelief([a], threshold=0.4)


def test_particle_resampling_is_seeded() -> None:
    states = [State([atom("n", i)]) for i in range(20)]

    def run(seed: int) -> list[State]:
        b = ParticleBelief(states, [0.0] * 12 + [1.0] * 8, seed=seed)  # effective size 8 < 20 / 2
        b.update(Operator("noop", ()).instantiate({}), Observation(True, None))
        assert b.weights == [1 / 20] * 20 and set(b.particles) == set(states[12:])
        return b.particles

    assert run(3) == run(3)
    assert len({tuple(map(hash, run(s))) for s in range(10)}) > 1  # the offset follows the seed


# -- the heuristic fallback is logged ---------------------------------------------------------

def test_heuristic_fallback_says_why(caplog: pytest.LogCaptureFixture) -> None:
    from nowplan.api import PlannerConfig, plan
    from nowplan.core.levels import flat_levels

    preds = {"p": Predicate("p", 0), "q": Predicate("q", 0, test=lambda b, a, v: bool(b.value(("p", ()))))}
    dom = Domain("tested", preds, (Operator("make", (), (), (atom("p"),)),))
    caplog.set_level(logging.INFO, logger="nowplan.planning.regression")
    res = plan(dom, {}, SymbolicBelief(State()), Goal.of([atom("p")]), flat_levels(), PlannerConfig())
    assert res.solved
    # a test is all that keeps the ground relaxation away: the planner relaxes lazily, and says so
    assert "heuristic hadd relaxes lazily" in caplog.text and "predicate q has a test" in caplog.text
    # a non-boolean predicate too: it counts unmet atoms, and says why
    preds = {**preds, "v": Predicate("v", 0, boolean=False)}
    dom = Domain("tested2", preds, (Operator("make", (), (), (atom("p"),)),))
    res = plan(dom, {}, SymbolicBelief(State()), Goal.of([atom("p")]), flat_levels(), PlannerConfig())
    assert res.solved
    assert "tested2: heuristic hadd falls back to counting unmet atoms" in caplog.text
