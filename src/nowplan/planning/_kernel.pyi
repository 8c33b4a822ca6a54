"""Type stub of the compiled kernel (``_kernel.c``); the Python reference is hff.py / forward.py."""

from collections.abc import Callable, Iterable, Sequence

API: int
SOLVED: int
EXHAUSTED: int
NODE_LIMIT: int
TIME_LIMIT: int
DEAD_INIT: int

class Kernel:
    """One integer task (costs already transformed) and one heuristic kind ("ff", "add" or "max")."""

    def __init__(
        self,
        nfacts: int,
        pre: Sequence[Sequence[int]],
        add: Sequence[Sequence[int]],
        dele: Sequence[Sequence[int]],
        cost: Sequence[float],
        goal: Sequence[int],
        by_pre: Sequence[Sequence[int]],
        no_pre: Sequence[int],
        kind: str,
        nactions: int = -1,
        axioms: tuple[
            Sequence[Sequence[int]], Sequence[int], Sequence[tuple[int, int]], Sequence[Sequence[int]], Sequence[int]
        ] | None = None,
    ) -> None: ...
    @property
    def evaluations(self) -> int: ...
    def evaluate(self, state: Iterable[int], /) -> tuple[float, list[int]]: ...
    def applicable(self, state: Iterable[int], /) -> list[int]: ...
    def close(self, facts: Iterable[int], /) -> list[int]: ...
    def set_base(self, facts: Iterable[int], /) -> None: ...
    def relaxed_order(self, state: Iterable[int], /) -> tuple[list[int], list[int]]: ...
    def landmark_sets(self, state: Iterable[int], order: Sequence[int], /) -> list[frozenset[int] | None]: ...
    def first_achievers(
        self, state: Iterable[int], order: Sequence[int], families: Sequence[Sequence[int]], /
    ) -> list[list[int]]: ...
    def costs(
        self, state: Iterable[int], overrides: Sequence[tuple[int, Sequence[int]]] = (), off: Iterable[int] = (), /
    ) -> list[float]: ...
    def gbfs(
        self,
        init: Iterable[int],
        max_nodes: int,
        out_of_time: Callable[[], object] | None = None,
        boost: int = 1000,
    ) -> tuple[int, list[int] | None, int, int, int]: ...
    def lama(
        self,
        init: Iterable[int],
        max_nodes: int,
        landmarks: Sequence[Sequence[int]],
        before: Sequence[Sequence[int]],
        out_of_time: Callable[[], object] | None = None,
        boost: int = 1000,
        unreachable: bool = False,
        reasonable: Sequence[Sequence[int]] | None = None,
    ) -> tuple[int, list[int] | None, int, int, int]: ...
    def bounded_wastar(
        self,
        init: Iterable[int],
        cost: Sequence[float],
        weight: float,
        bound: float,
        stop: Callable[[], object] | None = None,
    ) -> list[int] | None: ...
    def neighborhood(
        self,
        init: Iterable[int],
        plan: Sequence[int],
        limit: int,
        cost: Sequence[float],
        stop: Callable[[], object] | None = None,
    ) -> tuple[list[int], int, bool, bool]: ...
