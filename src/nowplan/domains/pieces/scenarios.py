"""Seeded shuffled-pieces problems and the episodes (world, camera, belief) they run in."""

from __future__ import annotations

import random
from collections.abc import Sequence
from dataclasses import dataclass

from nowplan.core.domain import Problem
from nowplan.domains.pieces.belief import LookHook, PiecesBelief
from nowplan.domains.pieces.board import KINDS, Board, Geometry
from nowplan.domains.pieces.model import problem
from nowplan.domains.pieces.render import Camera, CameraNoise
from nowplan.domains.pieces.vision import Recognizer, recognizer
from nowplan.domains.pieces.world import Disturbances, PiecesWorld
from nowplan.domains.registry import Episode
from nowplan.errors import ScenarioError


@dataclass(frozen=True)
class Size:
    rows: int
    cols: int
    pieces: int


SIZES = {
    "tiny": Size(4, 4, 4),
    "small": Size(6, 6, 6),
    "medium": Size(8, 8, 12),
    "large": Size(10, 10, 20),
}


@dataclass(frozen=True)
class PiecesProblem:
    """A shuffled-pieces task: where the pieces are, where they must go, where the arm starts."""

    init: Board
    goal: dict[str, str]
    name: str

    @property
    def geometry(self) -> Geometry:
        return self.init.geometry

    def core(self) -> Problem:
        return problem(self.init, self.goal, self.name)


def generate(size: Size, seed: int, name: str = "pieces") -> PiecesProblem:
    """``size.pieces`` pieces (the six kinds in turn) shuffled: random start and goal cells."""
    g = Geometry(size.rows, size.cols)
    if not 1 <= size.pieces <= len(g.board_cells) - 2:
        raise ScenarioError(
            f"{size.pieces} pieces do not fit a {size.rows}×{size.cols} board with room to move "
            f"(at most {len(g.board_cells) - 2})"
        )
    rng = random.Random(seed)
    kinds = [KINDS[i % len(KINDS)] for i in range(size.pieces)]
    cells = list(g.board_cells)
    start = dict(zip(rng.sample(cells, size.pieces), kinds, strict=True))
    goal = dict(zip(rng.sample(cells, size.pieces), kinds, strict=True))
    arm = rng.choice(cells)
    return PiecesProblem(Board.of(g, start, arm), goal, f"{name}-{size.rows}x{size.cols}-{size.pieces}-s{seed}")


def make_episode(
    task: PiecesProblem,
    seed: int,
    disturbance_prob: float = 0.0,
    noise: CameraNoise | None = None,
    rec: Recognizer | None = None,
    relooks: int = 2,
    on_look: LookHook | None = None,
    recognizer_seed: int = 0,
) -> Episode:
    """World (true board, camera, person) and belief (recogniser, re-looks) for one run."""
    camera = Camera(task.geometry, seed=seed * 7 + 1, noise=noise)
    world = PiecesWorld(task.init, camera, seed=seed * 7 + 2,
                        disturbances=Disturbances(prob=disturbance_prob))
    rec = rec or recognizer(recognizer_seed)
    belief = PiecesBelief(task.init, rec, relook=world.look, relooks=relooks, on_look=on_look)
    desc = (f"{task.geometry.rows}×{task.geometry.cols} board, {len(task.goal)} pieces, "
            f"disturbance p={disturbance_prob:g}, camera seed {seed * 7 + 1}")
    return Episode(task.core(), world, belief, desc)


def episode(size_name: str, seed: int, disturbance_prob: float = 0.0) -> Episode:
    if size_name not in SIZES:
        raise ScenarioError(f"unknown pieces size '{size_name}'; sizes: {', '.join(SIZES)}")
    return make_episode(generate(SIZES[size_name], seed, f"pieces-{size_name}"), seed, disturbance_prob)


def scenario_names() -> Sequence[str]:
    return [*SIZES, *(f"{s}-disturbed" for s in SIZES)]
