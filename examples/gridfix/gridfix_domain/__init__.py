"""A held-out test domain: a line crew restores a storm-damaged feeder whose broken segments it must find."""

from nowplan.api import DomainSpec

from gridfix_domain.model import DOMAIN
from gridfix_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="gridfix",
    description="a line crew finds and replaces broken feeder segments with a noisy detector, a battery and spares (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="storm", matrix_scenario="noisy",
)
