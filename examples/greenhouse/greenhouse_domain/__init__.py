"""A held-out greenhouse domain: two robots share a tank, fetch one sprayer and inspect plants for pests."""

from nowplan.api import DomainSpec

from greenhouse_domain.model import DOMAIN
from greenhouse_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="greenhouse",
    description="two robots water plants from a shared tank and rid them of pests they sense noisily",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="tend", matrix_scenario="noisy",
)
