"""A held-out test domain: a lab on three floors with an elevator, a sticky door, a tool and drifting samples."""

from nowplan.api import DomainSpec

from lab_domain.model import DOMAIN
from lab_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="lab",
    description="a robot scans a sample and carries it upstairs by elevator, through a sticky door (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="deliver", matrix_scenario="sticky",
)
