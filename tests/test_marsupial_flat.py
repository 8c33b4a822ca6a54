"""The flat STRIPS export of marsupial problems and the flat-planner comparison (seed 002 V-B)."""

from __future__ import annotations

import importlib.util
import random
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest

from nowplan.core.atoms import atom
from nowplan.core.domain import Problem
from nowplan.core.state import State
from nowplan.domains.marsupial.flat import flatten, rescore
from nowplan.domains.marsupial.flatcmp import pddl_cost, run_fd, speedups
from nowplan.domains.marsupial.grid import Hold
from nowplan.domains.marsupial.problems import ff_instance, generate, make_map, problem_from
from nowplan.errors import ModelError
from nowplan.io.pddl_read import load_pddl
from nowplan.io.pddl_write import write_pddl
from nowplan.planning.fd import ground_actions

HAVE_FD = importlib.util.find_spec("up_fast_downward") is not None
HAVE_UP = importlib.util.find_spec("unified_planning") is not None


def _replay(problem_path: tuple[Path, Path], steps: list[str]) -> bool:
    """Replay a flat plan in nowplan's own reading of the PDDL: every precondition holds, then the goal."""
    p = load_pddl(*problem_path)
    state = p.init
    pairs = [(s.strip("()").split()[0], s.strip("()").split()[1:]) for s in steps]
    for a in ground_actions(p, pairs):
        missing = [str(x) for x in a.preconditions() if not p.domain.holds(x, state)]
        if missing:
            return False
        state = state.apply(a.effects())
    return p.domain.satisfies(state, p.goal)


def test_export_round_trips(tmp_path: Path) -> None:
    problem, _ = ff_instance(0)
    flat = flatten(problem)
    dom, prob = write_pddl(flat, tmp_path)
    back = load_pddl(dom, prob)
    assert set(back.objects) == set(flat.objects)
    assert set(back.init.atoms()) == set(flat.init.atoms())
    assert {o.name for o in back.domain.operators} == {o.name for o in flat.domain.operators}
    assert set(back.goal.atoms) == set(flat.goal.atoms)
    # loader-level actions: the loader walks a cell at a time and grasps/places every shape
    names = {o.name for o in flat.domain.operators}
    assert {"move", "grasp-dot", "place-box", "load-ell", "unload-tall", "travel-3x6"} <= names


def test_generated_instance_exports_every_bay_size(tmp_path: Path) -> None:
    problem, spec = generate("both", 3, 1)
    flat = flatten(problem)
    cells = [o for o, t in flat.objects.items() if t == "cell"]
    assert len(cells) == sum(r * c for r, c in spec.bays.values())
    travels = {o.name for o in flat.domain.operators if o.name.startswith("travel")}
    assert travels == {f"travel-{r}x{c}" for r, c in set(spec.bays.values())}


def test_flatten_needs_empty_bays() -> None:
    problem, _ = ff_instance(0)
    loaded = Hold(3, 6, (("p0", "dot", (0, 0)),), (2, 3))
    state = problem.init.apply([atom("cargo", "truck0", value=loaded)])
    with pytest.raises(ModelError, match="empty bays"):
        flatten(replace(problem, init=state))


def test_rescore_charges_a_walk_once() -> None:
    plan = ["(load-dot p0 t l a c0 c1)", "(move t a b)", "(move t b c)", "(grasp-dot t p0 a c c1)",
            "(move t c d)", "(travel-3x6 t l m c0)", "(move u a b)", "(move t d e)"]
    # load 10 + walk 1 + grasp 1 + walk 1 + travel 10 + walk of u 1 + walk of t 1
    assert rescore(plan) == 25.0
    assert pddl_cost(plan) == 26.0  # every one of the 5 moves costs 1
    assert rescore([]) == 0.0


def test_speedups_mark_time_limits_as_lower_bounds() -> None:
    rows = [
        {"instance": "a", "packages": 5, "planner": "hpn", "status": "solved", "time_s": 2.0},
        {"instance": "a", "packages": 5, "planner": "fd lama-first", "status": "time_limit", "time_s": 60.0},
        {"instance": "b", "packages": 1, "planner": "hpn", "status": "solved", "time_s": 0.5},
        {"instance": "b", "packages": 1, "planner": "fd lama-first", "status": "solved", "time_s": 1.0},
        {"instance": "c", "packages": 1, "planner": "hpn", "status": "reached_limit", "time_s": 9.0},
        {"instance": "c", "packages": 1, "planner": "fd lama-first", "status": "solved", "time_s": 1.0},
    ]
    out = {s["instance"]: s for s in speedups(rows, "hpn")}
    assert out["a"]["ratio"] == 30.0 and out["a"]["bound"] == "lower bound"
    assert out["b"]["ratio"] == 2.0 and out["b"]["bound"] == "exact"
    assert "c" not in out  # our run did not solve it: no ratio


def _tiny() -> Problem:
    """One city (an airport and one place), 3x4 bays, a two-cell package to the airport."""
    rng = random.Random(0)
    spec = make_map(rng, n_cities=1, per_city=1, layouts=("circular",), sizes=((3, 4),))
    return problem_from(spec, rng, [("bar", "c0-l0", "c0-ap")], "tiny")


def _fd_validated(problem: Any, tmp_path: Path) -> tuple[Path, Path, list[str]]:
    """Export ``problem``, solve it with FD lama-first, and check the plan with the validator and our replay."""
    from nowplan.planning.validate import validate_plan

    dom, prob = write_pddl(flatten(problem), tmp_path)
    r = run_fd(dom, prob, "lama-first", 30.0, tmp_path)
    assert r["status"] == "solved", r
    steps = r["steps"]
    ok, msg = validate_plan(dom, prob, steps)
    assert ok, msg
    assert _replay((dom, prob), steps)
    return dom, prob, steps


@pytest.mark.skipif(not (HAVE_FD and HAVE_UP), reason="needs the fd and validate extras")
def test_fd_plan_for_a_small_export_validates(tmp_path: Path) -> None:
    dom, prob, steps = _fd_validated(_tiny(), tmp_path)
    assert not _replay((dom, prob), steps[:-1])  # the last step is needed for the goal


@pytest.mark.slow
@pytest.mark.skipif(not (HAVE_FD and HAVE_UP), reason="needs the fd and validate extras")
def test_fd_plan_for_the_ff_instance_validates(tmp_path: Path) -> None:
    from nowplan.planning.validate import validate_plan

    dom, prob, steps = _fd_validated(ff_instance(0)[0], tmp_path)
    # the validator rejects the plan without its last step (it no longer reaches the goal) ...
    assert not validate_plan(dom, prob, steps[:-1])[0]
    # ... and without its first loader step (a later step's preconditions fail)
    i = next(k for k, s in enumerate(steps) if s.startswith(("(move", "(grasp", "(place")))
    assert not validate_plan(dom, prob, steps[:i] + steps[i + 1:])[0]
    assert not _replay((dom, prob), steps[:i] + steps[i + 1:])


def test_flat_initial_state_is_a_core_state() -> None:
    problem, _ = ff_instance(0)
    flat = flatten(problem)
    assert isinstance(flat.init, State)
    assert flat.domain.satisfies(flat.init, flat.goal) is False


@pytest.mark.slow
@pytest.mark.skipif(not (HAVE_FD and HAVE_UP), reason="needs the fd and validate extras")
@pytest.mark.timeout(3600)  # three flat planners with 30-s caps (lmcut among them), then HPN twice
def test_comparison_on_the_ff_instance() -> None:
    from nowplan.domains.marsupial.flatcmp import compare

    problem, spec = ff_instance(0)
    rows = {r["planner"]: r for r in compare("ff", problem, spec, 30.0, optimal=True)}
    assert rows["hpn"]["status"] == rows["hpn+peephole"]["status"] == "solved"
    assert rows["fd lama-first"]["valid"]
    opt = rows["fd seq-opt-lmcut"]
    if opt["status"] == "solved":
        # the optimum of the flat PDDL metric, rescored, bounds no plan of ours from below by more than
        # the walk discount; ours is at most lama-first's cost here
        assert rows["hpn"]["cost"] <= rows["fd lama-first"]["cost"]
