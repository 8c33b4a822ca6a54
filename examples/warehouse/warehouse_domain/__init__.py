"""A held-out nowplan domain: a warehouse mobile manipulator (stacks, a battery, a noisy barcode scanner)."""

from nowplan.api import DomainSpec

from warehouse_domain.model import DOMAIN
from warehouse_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="warehouse",
    description="a mobile manipulator digs ordered boxes out of stacks and packs them; battery, noisy scanner, workers",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="small", matrix_scenario="small",
)
