"""A held-out test domain: items at uncertain places, looks that miss (a particle belief)."""

from nowplan.api import DomainSpec

from search_domain.model import DOMAIN
from search_domain.scenarios import SCENARIOS

SPEC = DomainSpec(
    name="search",
    description="a robot finds and stores items whose places it only guesses; looks may miss (held-out test)",
    model=DOMAIN, scenarios=SCENARIOS, default_scenario="tidy", matrix_scenario="missy",
)
