"""Look again before giving up: no plan for the goal from a belief that can take a fresh look.

A perceived model can make the goal unreachable by a misreading alone (the pieces domain's camera at
high noise reads a piece as another kind, and no plan exists for the goal's pieces).  Before a strategy
gives up with "no plan for the goal", a belief that offers ``reobserve()``
(:class:`~nowplan.belief.protocols.Reobserves`) is asked to look again, up to ``LOOKS`` times in a row
without a plan in between; each look is a new sample, so a misreading by chance is corrected, and a goal
still unreachable after them is given up as before, with its reason.  (The monitor strategies do the
same when no repair can be planned: :mod:`nowplan.acting.monitor`.)
"""

from __future__ import annotations

from typing import Any

from nowplan.belief.protocols import Reobserves
from nowplan.trace import Trace

LOOKS = 3  # fresh looks in a row, without a plan in between, before "no plan for the goal" stands


def look_again(belief: Any, trace: Trace, looks: int, why: str) -> bool:
    """Take a fresh look (and say so in the trace) unless ``looks`` reached ``LOOKS`` or the belief
    cannot look again; True when it looked."""
    if looks >= LOOKS or not isinstance(belief, Reobserves):
        return False
    trace.emit("note", text=f"executive: no plan for the goal ({why}); observing again ({looks + 1} of {LOOKS})")
    belief.reobserve()
    return True
