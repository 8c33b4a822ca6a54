"""The hard kitchen distribution of ``nowplan reproduce 004`` (issue 17) and its --easy fallback."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("pybullet")

from nowplan.domains.kitchen import hard, repro, tasks  # noqa: E402
from nowplan.domains.kitchen import scene as S  # noqa: E402


@pytest.mark.parametrize("task", ["inspect", "stow", "swap", "cook"])
def test_the_generator_is_deterministic_for_a_seed(task: str) -> None:
    a = hard.draw(task, 3, seed=1)
    assert hard.draw(task, 3, seed=1) == a
    assert hard.draw(task, 4, seed=1) != a and hard.draw(task, 3, seed=2) != a
    truth, prior, _goal, _bs, _ws = a
    assert set(truth) == set(hard.OBJECTS) and set(prior) == set(hard.OBJECTS)
    regs = S.regions(cabinet=True)
    for o, (frame, xy) in truth.items():  # every box inside its region, none overlapping another
        assert hard._inside(o, regs[frame], xy), (o, frame, xy)
        assert hard._clear(o, (frame, xy), truth), o


@pytest.mark.parametrize("task", ["inspect", "swap", "cook"])
def test_the_block_starts_hidden_from_the_worlds_camera(task: str) -> None:
    """The analytic test the generator uses agrees with the world's PyBullet rays: with its container
    open, the block is never seen until the object in front of it moves."""
    ep = hard.make(task, 0)
    w = ep.world
    frame = w.frames["green"]
    if frame in S.DRAWERS:
        w.drawers[frame] = S.DRAWER_OPEN
    assert not any(w.detect()[0]["green"] is not None for _ in range(15))
    hider = next(o for o, f in w.frames.items() if o != "green" and f == frame
                 and hard.hides((frame, tuple(w.rel["green"][:2])), (f, tuple(w.rel[o][:2])), "green", o))
    w.rel[hider] = w.rel[hider] + [0.0, -2.0, 0.0]  # take it away
    assert any(w.detect()[0]["green"] is not None for _ in range(15))


def test_easy_keeps_the_original_problems() -> None:
    ep = tasks.make("cook", 0)
    assert set(ep.belief.objects) == {"green", "sugar", "cracker"}
    assert not ep.belief.cabinet and S.CABINET not in ep.world.drawers and ep.world.scene.lid == -1
    assert ep.belief.regions == S.regions()
    # the hard one is a different kitchen
    h = hard.make("cook", 0)
    assert h.belief.cabinet and set(h.belief.objects) == set(hard.OBJECTS) and h.world.scene.lid >= 0
    assert h.problem.name == "cook-hard-0" and ep.problem.name == "cook-0"


def test_a_seeded_hard_problem_is_solved_by_both() -> None:
    r = repro.trial("inspect", 0, "both", repro.HARD_CAP_S)
    assert r["outcome"] == "reached", r["reason"]
    assert r["planning_s"] <= repro.HARD_CAP_S


def test_the_cabinet_opens_and_shows_its_contents() -> None:
    ep = hard.make("cook", 0)
    w = ep.world
    assert w.frames["spam"] == S.CABINET
    assert not any(w.detect()[0]["spam"] is not None for _ in range(10))  # under the closed lid
    w.drawers[S.CABINET] = S.CABINET_OPEN
    seen = [w.detect()[0]["spam"] is not None for _ in range(20)]
    assert sum(seen) >= 10
    b = ep.belief
    assert not b.frame_visible(S.CABINET)
    b.drawers[S.CABINET] = S.CABINET_OPEN
    assert b.frame_visible(S.CABINET)


def _record(task: str, k: int, variant: str, ok: bool, t: float) -> dict[str, object]:
    return {"key": repro._key(False, repro.HARD_QUICK_CAP_S, task, k, variant), "task": task, "index": k,
            "variant": variant, "outcome": "reached" if ok else "limit", "reason": "" if ok else "cap",
            "planning_s": t, "actions": 9, "motion_calls": 3}


def test_stored_runs_are_summarised_and_judged(tmp_path: Path) -> None:
    """--stored summarises a runs file; the verdicts follow issue 17's targets."""
    from nowplan.experiments.reproductions import ReproductionOptions
    from nowplan.experiments.verdicts import Verdict

    # Neither fails one of two problems on Stow and Cook; the singles sit between; Both solves all
    wins = {"neither": 1, "constraints": 1, "deferred": 2, "both": 2}
    lines = []
    for task in repro.TASK_NAMES:
        for v, n_ok in wins.items():
            for k in range(2):
                ok = k < (n_ok if task in ("stow", "cook") else 2)
                lines.append(json.dumps(_record(task, k, v, ok, 1.0 + k)))
    lines.append("not json")
    runs = tmp_path / "runs.jsonl"
    runs.write_text("\n".join(lines) + "\n", encoding="utf-8")
    res = repro.run(ReproductionOptions(quick=True, trials=2, runs_file=runs, stored_only=True))
    rows = {(r["task"], r["algorithm"]): r for r in res.rows}
    assert rows[("Stow", "neither")]["success_pct"] == 50.0 and rows[("Stow", "neither")]["planning_time_s"] == 1.0
    assert rows[("Cook", "both")]["success_pct"] == 100.0 and rows[("Cook", "both")]["planning_time_s"] == 1.5
    assert all(c.verdict is Verdict.MET for c in res.comparisons), [c.cells() for c in res.comparisons]
    # Constraints above Both on one task breaks the order; a single wide gap is not enough
    wins = {"neither": 2, "constraints": 2, "deferred": 1, "both": 1}
    lines = [json.dumps(_record(t, k, v, k < (n if t == "swap" else 2), 1.0))
             for t in repro.TASK_NAMES for v, n in wins.items() for k in range(2)]
    runs.write_text("\n".join(lines) + "\n", encoding="utf-8")
    res = repro.run(ReproductionOptions(quick=True, trials=2, runs_file=runs, stored_only=True))
    bad = [c.quantity for c in res.comparisons if c.verdict is Verdict.NOT_MET]
    assert "Swap: Both success %" in bad and any(q.startswith("Swap: success %") for q in bad)
    assert any(q.startswith("tasks where Neither") for q in bad)


def test_the_cli_passes_easy_and_reads_stored_004_runs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from nowplan.cli import main as cli_main

    recs = [{**_record(t, 0, v, True, 2.0), "key": repro._key(True, repro.QUICK_CAP_S, t, 0, v)}
            for t in repro.TASK_NAMES for v in repro.VARIANTS]
    runs = tmp_path / "runs.jsonl"
    runs.write_text("\n".join(json.dumps(r) for r in recs) + "\n", encoding="utf-8")
    assert cli_main(["reproduce", "004", "--easy", "--trials", "1", "--stored", "--runs", str(runs), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert len(doc["rows"]) == 16 and "easy set" in doc["notes"]
    # the same file read for the hard distribution holds none of its trials: nothing to tabulate
    assert cli_main(["reproduce", "004", "--trials", "1", "--stored", "--runs", str(runs), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["rows"] == [] and "hard distribution" in doc["notes"]


def _model(ep: object) -> object:
    """The KitchenModel behind an episode's domain (its place generator's owner)."""
    place = next(o for o in ep.problem.domain.operators if o.name == "place")  # type: ignore[attr-defined]
    return place.generators[0].fn.__self__


def test_a_hand_empty_subgoal_may_put_down_the_tall_box_a_closable_drawer_needs_out() -> None:
    """With one object in the hand, a ``HandEmpty`` subgoal that also wants a drawer ``Closable`` offers
    to put down the tall box in that drawer too (the plan holds it by then), not only the held object
    (hard Stow 4: green in the hand, sugar to take out of the top drawer → 'search space exhausted')."""
    from nowplan.belief.particles import PoseParticles
    from nowplan.core.atoms import Goal, atom

    ep = hard.make("stow", 4)
    b, model = ep.belief, _model(ep)
    closable = Goal.of([atom("Closable", "top"), atom("HandEmpty")])
    assert model._to_free(closable, b) == ["sugar"]  # type: ignore[attr-defined]
    b.held = "green"
    b.particles["green"] = PoseParticles.point("hand", (0.0, 0.0, 0.0), len(b.particles["green"]))
    b.version += 1
    assert model._to_free(closable, b) == ["green", "sugar"]  # type: ignore[attr-defined]
    assert model._to_free(Goal.of([atom("HandEmpty")]), b) == ["green"]  # type: ignore[attr-defined]


def test_parking_spots_respect_the_subgoal() -> None:
    """A spot where the box would hide what a later look needs, or would stand on a spot the subgoal
    keeps for another object, is not offered; the few spots offered are reachable ones."""
    from nowplan.core.atoms import Goal, Var, atom

    ep = hard.make("stow", 2)
    b, model = ep.belief, _model(ep)
    pg = b.mode_pose("green")
    cracker = b.mode_pose("cracker")
    spots = model._placements("sugar", "counter")  # type: ignore[attr-defined]
    hiding = [p for p in spots if not model._fits("sugar", p, Goal.of([atom("NotBlocks", "sugar", "green", pg)]))]  # type: ignore[attr-defined]
    assert hiding, "no sampled spot hides the block (the test needs one)"
    for p in hiding:  # the rule the planner prunes with says the same
        assert model.occludes(atom("AtPose", "sugar", value=p), atom("NotBlocks", "sugar", "green", pg))  # type: ignore[attr-defined]
    on_cracker = type(cracker)("counter", cracker.x + 0.02, cracker.y, spots[0].z)
    assert not model._fits("sugar", on_cracker, Goal.of([atom("AtPose", "cracker", value=cracker)]))  # type: ignore[attr-defined]
    far = type(cracker)("counter", cracker.x + 0.3, cracker.y, spots[0].z)
    assert model._fits("sugar", far, Goal.of([atom("AtPose", "cracker", value=cracker)]))  # type: ignore[attr-defined]
    goal = Goal.of([atom("Closable", "top"), atom("HandEmpty"), atom("NotBlocks", "sugar", "green", pg)])
    got = list(model.g_place({}, goal, b, None))  # type: ignore[attr-defined]
    assert got, "no parking spot for the sugar box"
    assert len(got) <= 2 * model._level()  # type: ignore[attr-defined]
    for vals in got:
        assert vals[Var("o")] == "sugar" and vals[Var("q")] is not None
        assert vals[Var("p")] not in hiding


def test_the_estimate_counts_a_tall_box_pick_once() -> None:
    """``Holding(sugar)`` and ``Closable(top)`` (sugar in the top drawer) are achieved by one pick: the
    estimate of the pair is not the sum of the two picks."""
    from nowplan.core.atoms import Goal, atom
    from nowplan.domains.kitchen.heuristic import atom_estimate, estimate

    ep = hard.make("stow", 2)
    b = ep.belief
    no = lambda a: False  # noqa: E731 -- nothing holds
    both = estimate(Goal.of([atom("Holding", "sugar"), atom("Closable", "top")]), b, no)
    hold = estimate(Goal.of([atom("Holding", "sugar")]), b, no)
    assert both == hold
    assert atom_estimate(atom("Closable", "top"), b) > 0  # alone, the pick is counted


@pytest.mark.slow
@pytest.mark.parametrize("index", [2, 4])
def test_hard_stow_is_solved_by_both(index: int) -> None:
    """Stow 2 and 4 failed with Both before the fixes above (a look at the counter that missed, then
    no plan within the cap; the block in the hand when the sugar box had to come out)."""
    r = repro.trial("stow", index, "both", repro.HARD_CAP_S)
    assert r["outcome"] == "reached", r["reason"]
    assert r["max_actions"] == repro.HARD_MAX_ACTIONS


def test_priors_and_placements_are_findable() -> None:
    """No prior mass where the kitchen itself hides an object with its container open (the front strip
    of a drawer's tray behind its panel), and the generator puts nothing there: otherwise every look
    that misses moves mass into that strip, which no look can reach."""
    from nowplan.belief.particles import Region
    from nowplan.domains.kitchen.belief import KitchenBelief

    regs = S.regions(cabinet=True)
    prior = {"green": [regs["top"], regs["bottom"], regs[S.CABINET]]}
    plain = KitchenBelief(prior, seed=3, cabinet=True)
    found = KitchenBelief(prior, seed=3, cabinet=True, findable=True)
    try:
        assert plain._unfindable("green", plain.particles["green"]).any()  # the strip exists
        pb = found.particles["green"]
        bad = found._unfindable("green", pb)
        assert float(pb.weights[bad].sum()) == 0.0
        assert {f for f in pb.frames[pb.weights > 0]} == {"top", "bottom", S.CABINET}
        # a prior wholly inside the strip is refused, not silently emptied
        strip = Region("top", (-0.02, regs["top"].lo[1]), (0.02, regs["top"].lo[1] + 0.01))
        with pytest.raises(Exception, match="cannot see"):
            KitchenBelief({"green": [strip]}, seed=0, cabinet=True, findable=True)
    finally:
        S.close(plain.scene)
        S.close(found.scene)
    for task in ("inspect", "swap", "stow"):
        truth = hard.draw(task, 1)[0]
        assert all(hard.findable(o, at) for o, at in truth.items()), task


def test_the_estimate_prices_a_look_behind_an_object_in_a_closed_drawer() -> None:
    """``AtPose(o) = p`` where the belief has ``o`` near ``p`` is a look: it costs more when ``p``'s drawer
    is closed and another object hides ``p``; ``NotBlocks`` counts opening the blocker's drawer."""
    from nowplan.core.atoms import atom
    from nowplan.domains.kitchen.heuristic import MOVE_ACT, atom_estimate

    ep = hard.make("swap", 0)
    b = ep.belief
    try:
        truth = ep.world.rel["green"]
        p = type(b.mode_pose("soup"))("top", float(truth[0]), float(truth[1]), float(truth[2]))
        assert b.particles["green"].mass_near("top", p.rel(), 0.04) > 0.01
        blockers = [j for j in b.objects if j != "green" and not b.not_blocks(j, "green", p)]
        assert blockers == ["soup"]
        look = atom_estimate(atom("AtPose", "green", value=p), b)
        # open the top drawer, move the soup can, look (at the look's own cost, 1/p: not 1)
        assert look == pytest.approx(b.look_cost("green", p) + MOVE_ACT + 2 * MOVE_ACT)
        assert b.look_cost("green", p) > 1.0
        far = type(p)("counter", 0.0, 0.6, p.z)  # no belief mass there: a put-down after a pick
        assert atom_estimate(atom("AtPose", "green", value=far), b) > 1.0
        assert atom_estimate(atom("NotBlocks", "soup", "green", p), b) > 2 * MOVE_ACT
    finally:
        S.close(ep.world.scene)
        S.close(ep.belief.scene)
