"""The automatic hierarchy is derived once per domain's literals (planning/abstraction.py ``derive_hierarchy``).

``--criticality auto`` asked for it when loading and again in ``prepare_problem``, on copies of the
domain with the same operators' literals (the criticalities it sets and the mutexes inferred later
differ); the second ask now returns the hierarchy already made, and domains whose literals differ
still get their own.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

from nowplan.io.pddl_read import load_pddl
from nowplan.planning import abstraction
from nowplan.planning.abstraction import apply_hierarchy, derive_hierarchy
from nowplan.planning.problem_hierarchy import prepare_problem

SHIPPED = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"


def counting(monkeypatch: Any) -> list[str]:
    calls: list[str] = []
    made = abstraction._derive_hierarchy

    def counted(domain: Any, *args: Any) -> Any:  # (domain, type_sets[, meets])
        calls.append(domain.name)
        return made(domain, *args)

    monkeypatch.setattr(abstraction, "_derive_hierarchy", counted)
    return calls


def test_loading_and_preparing_derive_the_hierarchy_once(monkeypatch: Any) -> None:
    calls = counting(monkeypatch)
    d = SHIPPED / "logistics"
    prob = load_pddl(d / "domain.pddl", d / "p01.pddl", "auto")
    prepared = prepare_problem(prob)
    assert calls == ["logistics"]
    assert prepared.domain.top_level == prob.domain.top_level > 0


def test_the_copy_with_criticalities_has_the_same_hierarchy(monkeypatch: Any) -> None:
    d = SHIPPED / "gripper"
    domain = load_pddl(d / "domain.pddl", d / "p01.pddl").domain
    calls = counting(monkeypatch)
    h = derive_hierarchy(domain)
    applied = apply_hierarchy(domain, h)
    assert derive_hierarchy(applied) is h
    assert derive_hierarchy(replace(applied, conflicts=())) is h  # other conflicts, the same literals
    assert len(calls) == 1


def test_other_literals_get_their_own_hierarchy(monkeypatch: Any) -> None:
    d = SHIPPED / "gripper"
    domain = load_pddl(d / "domain.pddl", d / "p01.pddl").domain
    h = derive_hierarchy(domain)
    fewer = replace(domain, operators=tuple(o for o in domain.operators if o.name != "move"))
    calls = counting(monkeypatch)
    other = derive_hierarchy(fewer)
    assert len(calls) == 1
    assert other is not h
    # a hierarchy handed in from elsewhere is not filed under the copy's operators
    applied = apply_hierarchy(fewer, h)
    assert derive_hierarchy(applied) is not h
