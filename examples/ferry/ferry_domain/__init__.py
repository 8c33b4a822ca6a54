"""A held-out test domain: two ferries carry passengers between islands through a one-boat channel."""

from nowplan.api import DomainSpec

from ferry_domain.model import DOMAIN
from ferry_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="ferry",
    description="two ferries of two seats carry passengers through a channel one boat at a time, on fuel "
                "sold at one dock; passengers balk and change their minds (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="ferry", matrix_scenario="balky",
)
