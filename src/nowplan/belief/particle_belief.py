"""A particle belief over symbolic states: the base for a domain with hidden or noisy facts.

The belief is a set of weighted sampled states.  After each action every
particle is moved by :meth:`ParticleBelief.predict` (default: the action's
effects when the world reports success), weighted by
:meth:`ParticleBelief.likelihood` of the observation (default: 1, or, with a
full :class:`State` observed, 1 for a particle equal to it and 0 otherwise),
normalised, and resampled (systematic, seeded) when the effective sample size
drops below half.  An observation no particle explains (all weights 0) resets
the particles to the observed state, or keeps the predicted ones with equal
weights when the observation carries no state; both are logged.

What the planner sees is the *believed* state: the fluents whose probability
reaches ``threshold`` (a fluent below it is unknown, hence not true), so the
belief has every capability of :mod:`nowplan.belief.protocols` that a point
belief has (``value``, ``facts``/``atoms``, ``state``).  Override
``likelihood`` (a sensor model) and ``predict`` (noisy actions) per domain.
"""

from __future__ import annotations

import logging
import random
from collections.abc import Hashable, Iterator, Sequence
from typing import Any

from nowplan.core.atoms import Atom, Term
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.errors import ModelError
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)

Key = tuple[str, tuple[Term, ...]]


class _Unknown:
    """The value of a fluent the belief is sure of neither way: equal to no value, not ``False``."""

    def __repr__(self) -> str:
        return "UNKNOWN"

    def __bool__(self) -> bool:
        return False

    # a value rule compares it with a wanted value: it entails none
    def __ge__(self, other: object) -> bool:
        return False

    def __le__(self, other: object) -> bool:
        return False

    def __gt__(self, other: object) -> bool:
        return False

    def __lt__(self, other: object) -> bool:
        return False


UNKNOWN = _Unknown()


class ParticleBelief:
    """Weighted sampled states; override ``likelihood`` (the sensor) and ``predict`` (noisy actions).

    ``threshold`` (in (0.5, 1]) is the probability a fluent value needs to be believed.
    """

    def __init__(
        self, particles: Sequence[State], weights: Sequence[float] | None = None, *,
        seed: int = 0, threshold: float = 0.9,
    ) -> None:
        if not particles:
            raise ModelError("a particle belief needs at least one particle")
        if weights is not None and (len(weights) != len(particles) or any(w < 0 for w in weights)):
            raise ModelError("particle weights must be one non-negative number per particle")
        if not 0.5 < threshold <= 1.0:
            raise ModelError(f"threshold must be in (0.5, 1], got {threshold}")
        self.particles = list(particles)
        w = list(weights) if weights is not None else [1.0] * len(particles)
        total = sum(w)
        if total <= 0:
            raise ModelError("particle weights sum to 0")
        self.weights = [x / total for x in w]
        self.threshold = threshold
        self.rng = random.Random(seed)
        self._believed = self._summarise()

    # -- what a domain overrides ----------------------------------------------------------
    def predict(self, state: State, action: Action, observation: Observation, rng: random.Random) -> State:
        """The particle after ``action`` (default: its effects when the world reports success)."""
        return state.apply(action.effects()) if observation.success else state

    def likelihood(self, state: State, action: Action, observation: Observation) -> float:
        """``P(observation | state)`` up to a constant (default: an observed State must match exactly)."""
        if isinstance(observation.data, State):
            return 1.0 if observation.data == state else 0.0
        return 1.0

    # -- the filter ------------------------------------------------------------------------
    def update(self, action: Action, observation: Observation) -> None:
        moved = [self.predict(s, action, observation, self.rng) for s in self.particles]
        w = [wi * self.likelihood(s, action, observation) for s, wi in zip(moved, self.weights, strict=True)]
        total = sum(w)
        if total <= 0:
            if isinstance(observation.data, State):
                log.info("particle belief: no particle explains the observation after %s; reset to it", action)
                moved, w = [observation.data], [1.0]
            else:
                # the observation is then lost on the belief: repeated, the same action learns nothing,
                # and the progress guard sees a loop (a held-out search domain: a sock moved by someone
                # into view made every look there unexplainable, and the robot looked there forever)
                log.warning("particle belief: no particle explains the observation after %s; weights reset, "
                            "so the belief learns nothing from it (give surprising observations a small "
                            "likelihood, or let predict() model what may change unseen)", action)
                w = [1.0] * len(moved)
            total = sum(w)
        self.particles = moved
        self.weights = [x / total for x in w]
        if 1.0 / sum(x * x for x in self.weights) < len(self.weights) / 2:
            self._resample()
        self._believed = self._summarise()

    def _resample(self) -> None:
        n = len(self.particles)
        step = 1.0 / n
        u = self.rng.random() * step
        out: list[State] = []
        acc, i = self.weights[0], 0
        for _ in range(n):
            while u > acc and i < n - 1:
                i += 1
                acc += self.weights[i]
            out.append(self.particles[i])
            u += step
        self.particles = out
        self.weights = [step] * n

    def _summarise(self) -> State:
        mass: dict[tuple[Key, Any], float] = {}
        for s, w in zip(self.particles, self.weights, strict=True):
            for a in s.atoms():
                mass[(a.key, a.value)] = mass.get((a.key, a.value), 0.0) + w
        # the uncertain fluent values with their probabilities (rounded): what the believed state hides
        self._uncertain = frozenset((k, v, round(m, 3)) for (k, v), m in mass.items() if m < 1.0 - 1e-9)
        believed = {k: v for (k, v), m in mass.items() if m >= self.threshold - 1e-12}
        # a fluent no value of which is believed, and that is not believed absent either, is unknown:
        # its negation does not hold (the closed-world state alone would say it does)
        present: dict[Key, float] = {}
        for (k, _), m in mass.items():
            present[k] = present.get(k, 0.0) + m
        self._unknowns = frozenset(k for k, m in present.items()
                                   if k not in believed and 1.0 - m < self.threshold - 1e-12)
        return State(believed)

    def unknowns(self) -> frozenset[Key]:
        """The fluents the belief is sure of neither way: no value reaches ``threshold``, nor does
        their absence.  Neither they nor their negations hold (:meth:`value` says :data:`UNKNOWN`)."""
        return self._unknowns

    def fingerprint(self) -> Hashable:
        """Which situation the belief is in, for the progress guard: the believed state and the
        probabilities of the uncertain fluent values (to 3 decimals).  Two beliefs with the same
        believed state but different odds (a look that missed) are different situations, so
        looking again is not a cycle; returning to the same odds is."""
        return (self._believed, self._uncertain)

    # -- what the planner reads ------------------------------------------------------------
    def probability(self, a: Atom) -> float:
        """The weight of the particles in which ``a`` holds."""
        return sum(w for s, w in zip(self.particles, self.weights, strict=True)
                   if (s.value(a.key) is False) == (a.value is False) and (a.value is False or s.holds(a)))

    @property
    def state(self) -> State:
        """The believed state: every fluent value with probability >= ``threshold``."""
        return self._believed

    def value(self, key: Key) -> Any:
        if key in self._unknowns:
            return UNKNOWN
        return self._believed.value(key)

    def facts(self, predicate: str) -> list[tuple[Term, ...]]:
        return self._believed.facts(predicate)

    def atoms(self) -> Iterator[Atom]:
        return self._believed.atoms()

    def __repr__(self) -> str:
        return f"ParticleBelief({len(self.particles)} particles, believed {self._believed!r})"
