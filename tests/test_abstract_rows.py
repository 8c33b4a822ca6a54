"""Abstract rows' exclusions found per group (planning/fact_mutex.py ``Excluder.beyond``) equal the set difference.

At an abstract level an action's row deletes what its adds exclude under the inferred mutexes, but for
what a kept precondition excludes already (planning/task.py ``_Rows.row``).  ``Excluder.beyond`` finds
that difference by walking only the groups no kept precondition is in; here every task of every
shipped and classical domain's checked-in problems, at every level of its automatic hierarchy, is
built both ways (the set difference forced by a ``beyond`` that declines) and must be identical.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from nowplan.core.levels import LevelMap
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import fact_mutex
from nowplan.planning.problem_hierarchy import prepare_problem
from nowplan.planning.task import build_task
from nowplan.planning.task_grounding import clear_cache

ROOT = Path(__file__).resolve().parents[1]
CASES = sorted([*(ROOT / "src" / "nowplan" / "data" / "pddl").glob("*/p01.pddl"),
                *(ROOT / "benchmarks" / "classical").glob("*/p0[12].pddl")])


def rows(path: Path) -> list[tuple[Any, ...]]:
    clear_cache()
    prob = prepare_problem(load_pddl(path.parent / "domain.pddl", path, "auto"))
    out = []
    for level in range(prob.domain.top_level, -1, -1):
        t = build_task(prob.domain, prob.objects, prob.init, prob.goal, LevelMap(level), lambda a: 1.0)
        out.append((level, [a.key for a in t.actions], t.facts, t.pre, t.add, t.dele))
    return out


@pytest.mark.parametrize("path", CASES, ids=lambda p: f"{p.parent.name}-{p.stem}")
def test_exclusions_per_group_equal_the_set_difference(path: Path, monkeypatch: Any) -> None:
    fast = rows(path)
    monkeypatch.setattr(fact_mutex.Excluder, "beyond", lambda self, e, held: None)
    slow = rows(path)
    assert fast == slow


def test_beyond_declines_where_plain_rules_exist() -> None:
    from nowplan.core.atoms import atom
    from nowplan.core.domain import Domain

    class Plain:
        def __call__(self, a: Any, b: Any) -> bool:
            return False

    domain = Domain("d", {}, conflicts=(Plain(),))  # type: ignore[arg-type]
    ex = fact_mutex.Excluder(domain, [atom("p", "a")])
    assert ex.beyond(atom("p", "a"), []) is None


def test_the_per_group_path_is_taken_on_logistics(monkeypatch: Any) -> None:
    answered: list[int] = []
    made = fact_mutex.Excluder.beyond

    def counted(self: Any, e: Any, held: Any) -> Any:
        out = made(self, e, held)
        if out is not None:
            answered.append(len(out))
        return out

    monkeypatch.setattr(fact_mutex.Excluder, "beyond", counted)
    rows(ROOT / "benchmarks" / "classical" / "logistics" / "p01.pddl")
    assert answered  # abstract rows with exclusions, found per group
