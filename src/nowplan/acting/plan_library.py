"""A plan library on disk (SQLite), indexed by (initial state, goal) pairs (seed 003).

Each stored plan keeps its action sequence and every intermediate state
``s0 … sn`` it passes through (the seed's "intermediate states that are
known to have a path from where they are to the final state").  Plans are
found by their exact (initial, goal) pair, for reuse without planning, or
by goal alone, for the monitor's search of the intermediate state closest
to an unexpected observation.  Keys are digests of a canonical text of the
state and the goal.  A file that is not a library of this version gives a
:class:`nowplan.errors.StoreError` that names the file and the fix.
"""

from __future__ import annotations

import hashlib
import json
import logging
import sqlite3
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.errors import StoreError

Rank = tuple[float, float, int]  # how the monitor breaks ties between equally close states

log = logging.getLogger(__name__)

SCHEMA_VERSION = "1"

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS plans (
    id INTEGER PRIMARY KEY,
    domain TEXT NOT NULL,
    init_key TEXT NOT NULL,
    goal_key TEXT NOT NULL,
    goal TEXT NOT NULL,
    actions TEXT NOT NULL,
    cost REAL NOT NULL,
    digest TEXT NOT NULL UNIQUE,
    created REAL NOT NULL
);
CREATE TABLE IF NOT EXISTS states (
    plan_id INTEGER NOT NULL REFERENCES plans(id),
    idx INTEGER NOT NULL,
    state_key TEXT NOT NULL,
    state TEXT NOT NULL,
    PRIMARY KEY (plan_id, idx)
);
CREATE INDEX IF NOT EXISTS plans_by_pair ON plans (domain, init_key, goal_key);
CREATE INDEX IF NOT EXISTS plans_by_goal ON plans (domain, goal_key);
"""


def _atom_json(a: Atom) -> list[Any]:
    return [a.predicate, list(a.args), a.value]


def _atom_of(x: Any) -> Atom:
    pred, args, value = x
    return Atom(str(pred), tuple(args), value)


def _canon(atoms: Sequence[Atom]) -> str:
    return json.dumps(sorted(_atom_json(a) for a in atoms), sort_keys=True, default=str)


def state_key(state: State) -> str:
    return hashlib.sha1(_canon(list(state.atoms())).encode()).hexdigest()


def goal_key(goal: Goal) -> str:
    return hashlib.sha1(_canon(list(goal)).encode()).hexdigest()


@dataclass(frozen=True)
class StoredPlan:
    id: int
    domain: str
    init_key: str
    goal_key: str
    actions: tuple[tuple[str, tuple[Any, ...]], ...]  # (operator name, arguments)
    states: tuple[State, ...]  # s0 … sn
    cost: float
    state_keys: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.actions)

    def suffix_cost(self, j: int, domain: Domain) -> float:
        """Cost of the stored actions after state ``s_j``."""
        return sum(a.cost() for a in self.rebuild(domain)[j:])

    def rebuild(self, domain: Domain) -> list[Action]:
        """The actions as ground instances of ``domain``'s operators."""
        out = []
        for name, args in self.actions:
            op = domain.operator_map.get(name)
            if op is None or len(op.params) != len(args):
                raise StoreError(
                    f"plan library entry {self.id} uses operator '{name}' with {len(args)} argument(s), "
                    f"which domain '{domain.name}' does not define; use a library made for this domain"
                )
            out.append(op.instantiate(dict(zip(op.params, args, strict=True))))
        return out


class PlanLibrary:
    """Plans and their intermediate states, in a SQLite file (or in memory with ``path=None``)."""

    def __init__(self, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        where = str(self.path) if self.path is not None else ":memory:"
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        try:
            self._db = sqlite3.connect(where)
            self._db.executescript(_SCHEMA)
            row = self._db.execute("SELECT value FROM meta WHERE key = 'schema_version'").fetchone()
            if row is None:
                self._db.execute("INSERT INTO meta VALUES ('schema_version', ?)", (SCHEMA_VERSION,))
                self._db.commit()
            elif row[0] != SCHEMA_VERSION:
                raise StoreError(
                    f"plan library {where} has schema version {row[0]}, this nowplan writes "
                    f"{SCHEMA_VERSION}; delete the file or pass another library path"
                )
        except (sqlite3.DatabaseError, UnicodeDecodeError) as exc:  # a damaged page can garble the error text too
            raise self._error(exc) from exc

    def _error(self, exc: Exception) -> StoreError:
        where = str(self.path) if self.path is not None else "(in memory)"
        return StoreError(
            f"plan library {where} cannot be read ({exc}); it is not a nowplan plan library or it is "
            "corrupted: delete it (a new one is created) or pass another path"
        )

    # -- writing -------------------------------------------------------------------
    def add(
        self, domain: str, init: State, goal: Goal, actions: Sequence[Action], states: Sequence[State],
    ) -> int:
        """Store a plan with its states ``s0 … sn`` (``len(states) == len(actions) + 1``).

        Returns the plan's id; storing the same plan twice returns the first id.
        """
        if len(states) != len(actions) + 1:
            raise ValueError("a stored plan needs one state more than it has actions")
        acts = [[a.name, list(a.args)] for a in actions]
        ik, gk = state_key(init), goal_key(goal)
        body = json.dumps(acts, default=str)
        digest = hashlib.sha1(f"{domain}|{ik}|{gk}|{body}".encode()).hexdigest()
        cost = sum(a.cost() for a in actions)
        try:
            old = self._db.execute("SELECT id FROM plans WHERE digest = ?", (digest,)).fetchone()
            if old is not None:
                return int(old[0])
            cur = self._db.execute(
                "INSERT INTO plans (domain, init_key, goal_key, goal, actions, cost, digest, created) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                (domain, ik, gk, _canon(list(goal)), body, cost, digest, time.time()),
            )
            pid = int(cur.lastrowid or 0)
            self._db.executemany(
                "INSERT INTO states (plan_id, idx, state_key, state) VALUES (?, ?, ?, ?)",
                [(pid, i, state_key(s), _canon(list(s.atoms()))) for i, s in enumerate(states)],
            )
            self._db.commit()
        except (sqlite3.DatabaseError, UnicodeDecodeError) as exc:  # a damaged page can garble the error text too
            raise self._error(exc) from exc
        log.debug("plan library: stored plan %d (%d actions) for %s", pid, len(actions), domain)
        return pid

    # -- reading -------------------------------------------------------------------
    def lookup(self, domain: str, init: State, goal: Goal) -> list[StoredPlan]:
        """Plans stored for exactly this (initial state, goal) pair, cheapest first."""
        return self._select(
            "domain = ? AND init_key = ? AND goal_key = ?", (domain, state_key(init), goal_key(goal))
        )

    def toward(self, domain: str, goal: Goal) -> list[StoredPlan]:
        """Every plan stored for this goal, from any initial state, cheapest first."""
        return self._select("domain = ? AND goal_key = ?", (domain, goal_key(goal)))

    def get(self, plan_id: int) -> StoredPlan:
        found = self._select("id = ?", (plan_id,))
        if not found:
            raise StoreError(f"plan library has no plan {plan_id}")
        return found[0]

    def _select(self, where: str, params: tuple[Any, ...]) -> list[StoredPlan]:
        try:
            rows = self._db.execute(
                f"SELECT id, domain, init_key, goal_key, actions, cost FROM plans WHERE {where} "
                "ORDER BY cost, id", params,
            ).fetchall()
            out = []
            for pid, dom, ik, gk, actions, cost in rows:
                srows = self._db.execute(
                    "SELECT idx, state_key, state FROM states WHERE plan_id = ? ORDER BY idx", (pid,)
                ).fetchall()
                acts = tuple((str(n), tuple(args)) for n, args in json.loads(actions))
                states = tuple(State([_atom_of(x) for x in json.loads(s)]) for _, _, s in srows)
                if len(states) != len(acts) + 1:
                    raise StoreError(
                        f"plan library entry {pid} has {len(states)} states for {len(acts)} actions; "
                        "the file is damaged: delete it or pass another path"
                    )
                out.append(StoredPlan(int(pid), str(dom), str(ik), str(gk), acts, states, float(cost),
                                      tuple(str(k) for _, k, _ in srows)))
            return out
        except (sqlite3.DatabaseError, UnicodeDecodeError) as exc:  # a damaged page can garble the error text too
            raise self._error(exc) from exc
        except (ValueError, TypeError) as exc:  # malformed JSON or rows
            raise self._error(exc) from exc

    def __len__(self) -> int:
        try:
            return int(self._db.execute("SELECT COUNT(*) FROM plans").fetchone()[0])
        except (sqlite3.DatabaseError, UnicodeDecodeError) as exc:  # a damaged page can garble the error text too
            raise self._error(exc) from exc

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> PlanLibrary:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def state_index(
    plans: list[StoredPlan],
    domain: Domain,
    into: dict[State, tuple[Rank, StoredPlan, int]] | None = None,
) -> dict[State, tuple[Rank, StoredPlan, int]]:
    """Distinct states -> (tie-break rank, plan, index).

    Among states equally close to the observed one the monitor goes to the one with the
    cheapest stored path to the goal (seed 003 keeps intermediate states "known to have the
    best path from where they are to the final state"), then the one later in its plan, then
    the lower plan id.  Preferring position alone re-entered repair plans that had detours in
    them: under faults the library fills with such plans and the runs grew 10x longer.
    """
    out = {} if into is None else into
    for sp in plans:
        costs = [a.cost() for a in sp.rebuild(domain)]
        remaining = sum(costs)
        for j, st in enumerate(sp.states):
            rank = (remaining, -j / max(len(sp.states), 1), sp.id)
            if j < len(costs):
                remaining -= costs[j]
            old = out.get(st)
            if old is None or rank < old[0]:
                out[st] = (rank, sp, j)
    return out
