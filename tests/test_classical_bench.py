"""The classical benchmark's files and tools (issue 19), without running any planner.

Every checked-in domain and instance parses with nowplan's reader; the
generators are deterministic (the checked-in instances are exactly their
output, in another process too); plan checking, plan-file parsing and the
summary's arithmetic work on small known cases.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from benchmarks.classical.generate import DOMAINS, GENERATORS, INSTANCES, domain_file, generate, instance_files, \
    write_instances
from benchmarks.classical.harness import check_plan, fd_evaluated, fd_expansions, parse_action, read_fd_plan
from benchmarks.classical.summary import FD, OURS, markdown, read_csv, write_csv
from nowplan.io.pddl_read import load_pddl

ROOT = Path(__file__).resolve().parents[1]
CASES = [(d, p.name) for d in DOMAINS for p in instance_files(d)]


def test_thirteen_domains_with_five_instances_each() -> None:
    assert len(DOMAINS) == 13
    for d in DOMAINS:
        assert domain_file(d).is_file()
        assert [p.name for p in instance_files(d)] == [f"p{k:02d}.pddl" for k in range(1, len(INSTANCES[d]) + 1)]
        assert len(INSTANCES[d]) == 5


@pytest.mark.parametrize(("domain", "problem"), CASES)
def test_instance_parses(domain: str, problem: str) -> None:
    prob = load_pddl(domain_file(domain), domain_file(domain).parent / problem)
    assert prob.goal.atoms
    assert not prob.domain.satisfies(prob.init, prob.goal), "the goal already holds"


def test_checked_in_instances_are_the_generators_output(tmp_path: Path) -> None:
    write_instances(DOMAINS, tmp_path)
    for d in DOMAINS:
        for p in instance_files(d):
            assert (tmp_path / d / p.name).read_text() == p.read_text(), f"{d}/{p.name} differs"


@pytest.mark.parametrize("domain", DOMAINS)
def test_generator_is_deterministic(domain: str) -> None:
    params, seed = INSTANCES[domain][1]
    assert generate(domain, params, seed) == generate(domain, params, seed)
    if domain != "gripper":  # gripper has no random part
        assert any(generate(domain, params, s) != generate(domain, params, seed) for s in range(seed + 1, seed + 4))


def test_generator_is_deterministic_across_processes() -> None:
    env = {**os.environ, "PYTHONHASHSEED": "12345"}
    out = subprocess.run([sys.executable, str(ROOT / "benchmarks/classical/generate.py"), "--domain", "rovers",
                          "--seed", "3", "rovers=2", "waypoints=6"], capture_output=True, text=True, env=env,
                         check=True).stdout
    assert out == GENERATORS["rovers"](rovers=2, waypoints=6, seed=3)


def test_check_plan_replays_in_the_core_model() -> None:
    d, p = domain_file("gripper"), domain_file("gripper").parent / "p01.pddl"
    carry = ["(pick ball1 rooma left)", "(pick ball2 rooma right)", "(move rooma roomb)",
             "(drop ball1 roomb left)", "(drop ball2 roomb right)", "(move roomb rooma)"]
    plan = carry + [a.replace("ball1", "ball3").replace("ball2", "ball4") for a in carry[:-1]]
    assert check_plan(d, p, plan) == (True, "valid plan of 11 action(s)", 11.0)
    ok, msg, cost = check_plan(d, p, plan[1:])
    assert not ok and msg.startswith("step 3 (drop ball1 roomb left)") and cost is None
    ok, msg, _ = check_plan(d, p, plan[:5])
    assert not ok and "goal is not reached" in msg
    ok, msg, _ = check_plan(d, p, ["(fly ball1)"])
    assert not ok and "unknown action" in msg


def test_check_plan_uses_action_costs(tmp_path: Path) -> None:
    p = tmp_path / "one-tile.pddl"
    p.write_text("""(define (problem one-tile) (:domain floor-tile)
  (:objects robot1 - robot tile_0-1 tile_1-1 - tile white black - color)
  (:init (robot-at robot1 tile_0-1) (robot-has robot1 black) (clear tile_1-1)
         (available-color white) (available-color black) (up tile_1-1 tile_0-1) (down tile_0-1 tile_1-1)
         (= (total-cost) 0))
  (:goal (painted tile_1-1 white))
  (:metric minimize (total-cost)))
""")
    plan = ["(change-color robot1 black white)", "(paint-up robot1 tile_1-1 tile_0-1 white)"]
    assert check_plan(domain_file("floortile"), p, plan) == (True, "valid plan of 2 action(s)", 7.0)
    ok, msg, _ = check_plan(domain_file("floortile"), p, plan[1:])
    assert not ok and "robot-has(robot1, white)" in msg


def test_parsing_helpers(tmp_path: Path) -> None:
    assert parse_action("( move  rooma roomb )") == ("move", ["rooma", "roomb"])
    assert parse_action("(handempty)") == ("handempty", [])
    with pytest.raises(ValueError):
        parse_action("move a b")
    plan = tmp_path / "sas_plan"
    plan.write_text("(pick-up a)\n(stack a b)\n; cost = 7 (general cost)\n")
    assert read_fd_plan(plan) == (["(pick-up a)", "(stack a b)"], 7.0)
    assert read_fd_plan(tmp_path / "none") == ([], None)
    log = "Expanded 12 state(s).\n...\nExpanded until last jump: 3 state(s).\nExpanded 40 state(s).\n"
    assert fd_expansions(log) == 40
    assert fd_expansions("no search") is None


def test_fd_evaluated_is_read_apart_from_expanded() -> None:
    # FD's lazy search counts dead ends as evaluated, not expanded; nowplan's lazy "expanded" counts them
    # (IPC-2006 trucks p07, lama-first: benchmarks/results/trucks_hff)
    log = ("Expanded 5041 state(s).\nReopened 0 state(s).\nEvaluated 24572 state(s).\n"
           "Generated 112108 state(s).\nDead ends: 19530 state(s).\n")
    assert fd_expansions(log) == 5041
    assert fd_evaluated(log) == 24572
    assert fd_evaluated("no search") is None


def _row(inst: str, planner: str, solved: bool, wall: float, cost: float | None, exp: int | None) -> dict[str, object]:
    return {"domain": "toy", "instance": inst, "planner": planner, "solved": solved, "wall_s": wall, "cost": cost,
            "expansions": exp, "method": "x:y" if planner == OURS else "lama-first", "status": "solved",
            "planning_s": wall / 2, "valid": "True"}


def test_summary_is_computed_from_the_rows(tmp_path: Path) -> None:
    rows = [_row("p01", OURS, True, 1.0, 10, 5), _row("p01", FD, True, 1.0, 10, 50),
            _row("p02", OURS, True, 4.0, 12, 5), _row("p02", FD, True, 1.0, 10, 5000),
            _row("p03", OURS, False, 30.0, None, None), _row("p03", FD, True, 2.0, 8, 9)]
    write_csv(rows, tmp_path / "c.csv")
    back = read_csv(tmp_path / "c.csv")
    assert back[0]["solved"] is True and back[4]["cost"] is None and back[1]["expansions"] == 50
    assert back[1]["evaluated"] is None  # (no such column in the rows: read as absent)
    text = markdown(back, {"command": "x", "time_limit": 30})
    assert "| toy | 3 | 2 | 3 | 2 | 2.00× | 4.00× | 1.100 | 1.200 |" in text
    assert "nowplan solves 2 of 3, lama-first 3 — **not met**" in text
    assert "at most 2× lama-first's on 1 (worst 4.00×, geometric mean 2.00×) — **not met**" in text
    assert "within 10 % of lama-first's on 1 of 2" in text
    assert "fewer than 1,000 states on 2 instances; nowplan solves 1 of them" in text


def test_the_scale_set_is_generated_outside_the_checked_in_set(tmp_path: Path) -> None:
    """``generate.py --scale DIR`` (and ``classical.py --scale``): five sNN problems per domain, larger than
    p05, each parsed by nowplan; the checked-in pNN files are not touched."""
    from benchmarks.classical.generate import SCALE, write_instances

    before = {p: p.read_text() for d in DOMAINS for p in instance_files(d)}
    paths = write_instances(DOMAINS, tmp_path, scale=True)
    assert len(paths) == 5 * len(DOMAINS) and set(SCALE) == set(DOMAINS)
    assert {p: p.read_text() for d in DOMAINS for p in instance_files(d)} == before
    for d in DOMAINS:
        files = instance_files(d, tmp_path, "s")
        assert [f.stem for f in files] == ["s01", "s02", "s03", "s04", "s05"]
        assert instance_files(d, tmp_path) == []  # no pNN written there
        assert len(files[-1].read_text()) > len(instance_files(d)[-1].read_text())  # s05 larger than p05
        load_pddl(domain_file(d), files[-1])


def test_merged_runs_keep_every_row(tmp_path: Path) -> None:
    rows_a = [_row("s01", OURS, True, 1.0, 10, 5), _row("s01", FD, True, 0.5, 10, 4)]
    rows_b = [{**r, "domain": "other"} for r in rows_a]
    for name, rows in (("a", rows_a), ("b", rows_b)):
        (tmp_path / name).mkdir()
        write_csv(rows, tmp_path / name / "classical.csv")
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1] / "src")}
    subprocess.run([sys.executable, str(Path(__file__).resolve().parents[1] / "benchmarks" / "classical.py"),
                    "--merge", str(tmp_path / "a"), str(tmp_path / "b"), "--out", str(tmp_path / "m")],
                   check=True, capture_output=True, env=env)
    merged = read_csv(tmp_path / "m" / "classical.csv")
    assert [(r["domain"], r["planner"]) for r in merged] == [(r["domain"], r["planner"]) for r in rows_a + rows_b]
