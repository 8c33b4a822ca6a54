"""Independent plan validation with unified-planning's sequential plan validator.

``validate_plan(domain.pddl, problem.pddl, ["(move a b)", ...])`` parses the
files with UPF's own PDDL reader (not nowplan's), replays the plan and
reports whether it is applicable and reaches the goal.  unified-planning is
an optional dependency (extra ``validate``), imported on first use.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from nowplan.errors import PDDLError, require

log = logging.getLogger(__name__)


def _up() -> Any:
    up = require("unified_planning", "validate")
    shortcuts = require("unified_planning.shortcuts", "validate")
    require("unified_planning.io", "validate")
    shortcuts.get_environment().credits_stream = None  # no banner on stdout
    return up


def validate_plan(
    domain_path: str | Path, problem_path: str | Path, plan_actions: Sequence[str]
) -> tuple[bool, str]:
    """``(ok, message)``: does the plan (PDDL action strings) solve the problem?"""
    up = _up()
    from unified_planning.engines.plan_validator import SequentialPlanValidator
    from unified_planning.io import PDDLReader

    for p in (domain_path, problem_path):
        if not Path(p).is_file():
            raise PDDLError("file not found (check the path)", path=str(p))
    reader = PDDLReader()
    try:
        problem = reader.parse_problem(str(domain_path), str(problem_path))
    except Exception as exc:  # UPF's own parser errors, of many types
        raise PDDLError(f"unified-planning could not read the problem: {exc}",
                        path=str(problem_path)) from exc
    text = "\n".join(a.strip() for a in plan_actions) + "\n"
    try:
        plan = reader.parse_plan_string(problem, text) if plan_actions else require('unified_planning.plans', 'validate').SequentialPlan([])
    except Exception as exc:
        return False, f"the plan does not parse against the problem: {' '.join(str(exc).split())}"
    validator = SequentialPlanValidator()
    result = validator.validate(problem, plan)
    status = result.status
    if status == require('unified_planning.engines', 'validate').ValidationResultStatus.VALID:
        return True, f"valid plan of {len(plan_actions)} action(s)"
    reason = getattr(result, "reason", None)
    details = "; ".join(m.message for m in getattr(result, "log_messages", None) or [])
    msg = "invalid plan"
    if reason is not None:
        msg += f" ({getattr(reason, 'name', reason)})"
    if details:
        msg += f": {details}"
    log.debug("validation of %d actions: %s", len(plan_actions), msg)
    return False, msg
