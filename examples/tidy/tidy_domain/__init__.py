"""A held-out test domain: a mobile manipulator tidies a house with a locked door, stacks, a
gripper that drops things and a cat that moves them unseen."""

from nowplan.api import DomainSpec

from tidy_domain.model import DOMAIN
from tidy_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="tidy",
    description="a mobile manipulator tidies a house: a locked door and its key under a cup, stacked things, "
                "a gripper that drops, a cat that moves things unseen (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="tidy", matrix_scenario="clumsy",
)
