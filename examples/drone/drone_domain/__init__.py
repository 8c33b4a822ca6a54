"""A held-out test domain: a delivery drone with a battery, chargers and a noisy position fix."""

from nowplan.api import DomainSpec

from drone_domain.model import DOMAIN
from drone_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="drone",
    description="a drone delivers parcels from sampled poses to a depot, recharging on the way (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="deliver", matrix_scenario="windy",
)
