"""A held-out test domain: a rover finds a gem with a detector that misses and lies, on a battery."""

from nowplan.api import DomainSpec

from mine_domain.model import DOMAIN
from mine_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="mine",
    description="a rover on a battery finds a gem with a detector that misses and lies, through a gate "
                "it must leave shut and a one-way chute (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="dig", matrix_scenario="noisy",
)
