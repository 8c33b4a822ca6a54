from __future__ import annotations

import dataclasses
import json

import pytest

from nowplan.cli import main


def test_run_logistics_json(capsys, tmp_path):
    trace = tmp_path / "trace.jsonl"
    code = main(["run", "--domain", "logistics", "--scenario", "tiny", "--seed", "2", "--json", "--trace", str(trace)])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["outcome"] == "reached" and out["actions"] > 0
    assert trace.read_text().count("\n") > 5


def test_run_prints_tree(capsys):
    assert main(["run", "--domain", "logistics", "--scenario", "tiny", "--tree"]) == 0
    out = capsys.readouterr().out
    assert "plan 1" in out and "<prim>" in out and "outcome: reached" in out


def test_demo_runs(capsys, tmp_path):
    assert main(["demo", "--size", "small", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "plan tree" in out and "outcome: reached" in out
    assert (tmp_path / "trace.jsonl").exists()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "--domain", "nope"], "valid domains: "),
        (["run", "--domain", "logistics", "--scenario", "huge"], "valid scenarios:"),
        (["run", "--domain", "logistics", "--strategy", "zzz"], "valid strategies:"),
        (["run"], "give --domain NAME"),
    ],
)
def test_bad_input_is_one_clear_line(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run", "--bogus"], "unrecognized arguments: --bogus"),
        (["run", "--seed", "-3"], "expected a number >= 0"),
        (["run", "--failure-prob", "2"], "probability in [0, 1]"),
        (["run", "missing.pddl"], "no such file"),
        (["frobnicate"], "invalid choice"),
    ],
)
def test_bad_options_exit_2(capsys, argv, message):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err


def test_run_pddl_logistics_with_criticalities_and_failures(capsys, tmp_path):
    from importlib import resources

    data = resources.files("nowplan") / "data" / "pddl" / "logistics"
    trace = tmp_path / "t.jsonl"
    argv = ["run", str(data / "domain.pddl"), str(data / "p03.pddl"), "--criticality", str(data / "logistics.crit"),
            "--failure-prob", "0.2", "--seed", "4", "--json", "--trace", str(trace)]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["outcome"] == "reached" and out["plans_made"] > 1
    events = [json.loads(x) for x in trace.read_text().splitlines()]
    # hierarchical: the first plan is abstract (no vehicle moves), later plans refine it
    first = next(e for e in events if e["event"] == "plan")
    assert not any(s["action"] and s["action"].startswith(("(drive", "(fly")) for s in first["steps"])
    assert any(not s["primitive"] for s in first["steps"][1:])


def test_run_uses_the_domains_planner_settings(monkeypatch, capsys):
    """`nowplan run --domain marsupial` plans with marsupial's PLANNER, not the engine defaults."""
    import nowplan.commands.run as run_cmd
    from nowplan.acting.metrics import Metrics, Outcome
    from nowplan.domains.marsupial.model import PLANNER

    seen = []

    def fake_run(episode, strategy, **kw):
        seen.append(strategy)
        return Metrics(outcome=Outcome.REACHED)

    monkeypatch.setattr(run_cmd, "run_episode", fake_run)
    main(["run", "--domain", "marsupial", "--scenario", "single-2", "--strategy", "hpn+peephole"])
    # (h2 left open by the domain's settings is decided by the strategy: off with HPN)
    assert seen and seen[0].planner == dataclasses.replace(PLANNER, h2=False)
    seen.clear()
    main(["run", "--domain", "logistics", "--scenario", "tiny"])
    assert seen and seen[0].planner.heuristic != PLANNER.heuristic


def test_a_strategys_planner_switch_applies_over_the_base_planner():
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.marsupial.model import PLANNER

    s = parse_strategy("hpn+noshortcuts", base_planner=PLANNER)
    assert s.planner.heuristic == PLANNER.heuristic and s.planner.clock == "cpu"
    assert not s.planner.serialization and not s.planner.monotonic


def test_run_max_nodes_reaches_every_planner_call(capsys):
    """--max-nodes is each planner call's expansion budget: too small a budget fails with a hint."""
    argv = ["run", "--domain", "logistics", "--scenario", "tiny", "--strategy", "flat", "--json"]
    assert main([*argv, "--max-nodes", "1"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert "node_limit" in out["reason"]
    assert main([*argv, "--max-nodes", "100000"]) == 0
    capsys.readouterr()
    assert main(argv[:-1] + ["--max-nodes", "1"]) == 1
    assert "raise them with --max-nodes N" in capsys.readouterr().out


def test_a_pddl_runs_default_action_budget_grows_with_its_objects(capsys, tmp_path):
    """A large PDDL problem is not cut by a budget sized for small ones: 1,000 actions or 10 per object."""
    from nowplan.commands.run import pddl_action_budget

    assert pddl_action_budget(range(50), 1_000) == 1_000
    assert pddl_action_budget(range(304), 1_000) == 3_040  # gripper with 300 balls needs 900+ actions
    n = 120
    dom = tmp_path / "d.pddl"
    dom.write_text("(define (domain tokens) (:requirements :strips :typing) (:types token)"
                   " (:predicates (here ?t - token) (there ?t - token))"
                   " (:action push :parameters (?t - token) :precondition (here ?t)"
                   " :effect (and (there ?t) (not (here ?t)))))")
    toks = " ".join(f"t{i}" for i in range(n))
    prob = tmp_path / "p.pddl"
    prob.write_text(f"(define (problem p) (:domain tokens) (:objects {toks} - token)"
                    f" (:init {' '.join(f'(here t{i})' for i in range(n))})"
                    f" (:goal (and {' '.join(f'(there t{i})' for i in range(n))})))")
    trace = tmp_path / "t.jsonl"

    def budget(*extra: str) -> int:
        assert main(["run", str(dom), str(prob), "--strategy", "flat", "--json", "--trace", str(trace), *extra]) == 0
        capsys.readouterr()
        start = json.loads(trace.read_text().splitlines()[0])
        return int(start["strategy"]["max_actions"])

    assert budget() == 1_200
    assert budget("--max-actions", "500") == 500  # the user's budget stands
