"""Streams: declared sampling procedures whose values may stay hypothetical (seed 004 IV, VII).

A :class:`Stream` declares what it certifies (the static facts its outputs
satisfy), a cost, and whether it is *expensive* and *likely* to succeed.
Cheap streams run inside the planner as ordinary generators; a stream that
is expensive and likely (and not ``never_defer``) may instead contribute an
:class:`Optimistic` placeholder — a hypothetical value — which is bound after
a candidate plan is found, PDDLStream-style.  :class:`StreamSet` evaluates
streams, counts calls and time, and remembers failed inputs so generators
can avoid them on the next planning call.

Sampling generators draw from per-planning-call *pools* (memoised, so the
search sees the same samples at every node) whose size is ``level`` times a
base size; the online policy calls :meth:`StreamSet.grow` when a search fails
for want of samples and :meth:`StreamSet.reset_level` before each new
planning call (the adaptive/incremental scheme of seed 004 IV).
"""

from __future__ import annotations

import logging
import time
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, ClassVar

from nowplan.errors import ModelError

log = logging.getLogger(__name__)

# fn(belief, earlier_actions, *inputs) -> a value, or None when it finds none
StreamFn = Callable[..., Any]


@dataclass(frozen=True)
class Stream:
    name: str
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    certifies: tuple[str, ...]
    fn: StreamFn = field(compare=False, hash=False, repr=False)
    cost: float = 0.0
    expensive: bool = False
    likely: bool = True
    never_defer: bool = False

    @property
    def deferrable(self) -> bool:
        """Section VII: only expensive streams that almost always succeed are deferred."""
        return self.expensive and self.likely and not self.never_defer


@dataclass(frozen=True)
class Optimistic:
    """A hypothetical output of ``stream`` for ``inputs`` (not computed yet)."""

    stream: str
    inputs: tuple[Any, ...]
    constant: ClassVar[bool] = False  # never a constant for plan reuse (seed 004 VI-A)

    def __str__(self) -> str:
        return f"#{self.stream}({', '.join(str(i) for i in self.inputs)})"


class StreamSet:
    """The streams of a domain, with call counts, time spent and failed inputs."""

    def __init__(self, streams: Iterable[Stream]) -> None:
        self.streams = {s.name: s for s in streams}
        self.calls: Counter[str] = Counter()
        self.seconds = 0.0
        self.failed: set[tuple[str, tuple[Any, ...]]] = set()
        self._cache: dict[tuple[str, tuple[Any, ...], tuple[Any, ...]], Any] = {}
        self.level = 1  # multiplier of the sampling generators' pool sizes
        self.max_level = 4

    def grow(self) -> bool:
        """Allow larger sample pools; False when :attr:`max_level` is reached."""
        if self.level >= self.max_level:
            return False
        self.level += 1
        log.info("stream sample pools grow to level %d", self.level)
        return True

    def reset_level(self) -> None:
        self.level = 1

    def __getitem__(self, name: str) -> Stream:
        s = self.streams.get(name)
        if s is None:
            raise ModelError(f"unknown stream '{name}'; known: {', '.join(sorted(self.streams))}")
        return s

    def optimistic(self, name: str, *inputs: Any) -> Optimistic:
        self[name]
        return Optimistic(name, tuple(inputs))

    def evaluate(self, name: str, belief: Any, earlier: tuple[Any, ...], *inputs: Any) -> Any:
        """Call the stream; ``None`` marks ``inputs`` as failed for later planning calls."""
        stream = self[name]
        t0 = time.perf_counter()
        self.calls[name] += 1
        try:
            value = stream.fn(belief, earlier, *inputs)
        finally:
            self.seconds += time.perf_counter() - t0
        if value is None:
            self.failed.add((name, tuple(inputs)))
            log.info("stream %s failed for %s", name, inputs)
        return value

    def has_failed(self, name: str, *inputs: Any) -> bool:
        return (name, tuple(inputs)) in self.failed
