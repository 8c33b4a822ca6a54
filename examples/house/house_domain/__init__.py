"""nowplan's tutorial domain: a one-gripper robot fetches a cup through a house (docs/writing-a-domain.md)."""

from nowplan.api import DomainSpec

from house_domain.model import DOMAIN
from house_domain.render import render
from house_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="house",
    description="a one-gripper robot fetches a cup from behind a locked door (the tutorial domain)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="fetch", matrix_scenario="sticky", renderer=render,
)
