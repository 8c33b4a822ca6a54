"""A held-out test domain: a hospital courier among doors that staff open and close (partial view)."""

from nowplan.api import DomainSpec

from ward_domain.model import DOMAIN
from ward_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="ward",
    description="a courier brings medication to a ward, clears the corridor and shuts the isolation door (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="round", matrix_scenario="busy",
)
