"""A held-out test domain: two AGVs carry blanks through a lathe and a paint booth to fill orders."""

from nowplan.api import DomainSpec

from millshop_domain.model import DOMAIN
from millshop_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="millshop",
    description="two AGVs carry blanks through a lathe and a paint booth to fill six orders; a spoilt turn "
                "scraps a blank for good, a spoilt coat smudges, machines trip, reports come late (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="shop", matrix_scenario="small",
)
