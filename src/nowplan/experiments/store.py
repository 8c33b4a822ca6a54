"""A SQLite store of run records, keyed by a hash of each run's configuration.

* One row per configuration key (``PRIMARY KEY``): a resumed sweep can
  neither duplicate nor lose a finished run.
* Each record is written in its own transaction, so a process killed with
  SIGKILL leaves either the whole record or none of it (SQLite's journal
  rolls a torn write back when the file is next opened).
* The schema version is stored in the ``meta`` table; opening a store
  written with another schema raises :class:`StoreError` saying so.
"""

from __future__ import annotations

import json
import logging
import sqlite3
from collections.abc import Iterable, Iterator
from pathlib import Path
from types import TracebackType
from typing import Self

from nowplan import __version__
from nowplan.errors import StoreError
from nowplan.experiments.records import RunConfig, RunRecord, RunStatus

log = logging.getLogger(__name__)

SCHEMA_VERSION = 1
APPLICATION = "nowplan-run-store"

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (
    name  TEXT PRIMARY KEY,
    value TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS runs (
    key         TEXT PRIMARY KEY,
    domain      TEXT NOT NULL,
    scenario    TEXT NOT NULL,
    strategy    TEXT NOT NULL,
    seed        INTEGER NOT NULL,
    time_limit  REAL NOT NULL,
    status      TEXT NOT NULL,
    outcome     TEXT NOT NULL,
    reason      TEXT NOT NULL,
    metrics     TEXT NOT NULL,
    error       TEXT,
    wall_s      REAL NOT NULL,
    version     TEXT NOT NULL,
    host        TEXT NOT NULL,
    finished_at TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS runs_group ON runs (domain, scenario, strategy);
"""

_COLUMNS = (
    "key", "domain", "scenario", "strategy", "seed", "time_limit", "status", "outcome",
    "reason", "metrics", "error", "wall_s", "version", "host", "finished_at",
)


class Store:
    """Open (creating if needed) a run store at ``path``."""

    def __init__(self, path: str | Path, *, create: bool = True) -> None:
        self.path = Path(path)
        if not self.path.exists() and not create:
            raise StoreError(f"{self.path}: no such run store (run 'nowplan sweep --store {self.path}' first)")
        if self.path.exists() and self.path.is_dir():
            raise StoreError(f"{self.path}: is a directory, expected a SQLite run store file")
        if create:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        self._db = sqlite3.connect(str(self.path), timeout=30.0, isolation_level=None)
        # text that is not UTF-8 (a damaged or hand-edited store) is decoded with replacement
        # characters: such a row then fails its checks in _from_row with a StoreError, not a
        # sqlite3 error from deep inside a report
        self._db.text_factory = lambda b: b.decode("utf-8", errors="replace")
        try:
            self._check_or_init()
            # a damaged page anywhere (not only the schema's) is found now, not in the middle of a sweep
            problems = [" ".join(str(r[0]).split()) for r in self._db.execute("PRAGMA quick_check(3)")]
            if problems != ["ok"]:
                raise StoreError(
                    f"{self.path}: the run store is damaged ({'; '.join(problems)}); restore it from a copy "
                    "or give a new --store file"
                )
            self._db.execute("PRAGMA journal_mode=WAL")  # readers (a report) never block the sweep
            self._db.execute("PRAGMA synchronous=FULL")
        except (sqlite3.DatabaseError, UnicodeDecodeError) as exc:  # a damaged page can garble the error text too
            self._db.close()
            raise StoreError(f"{self.path}: not a usable nowplan run store ({exc})") from exc
        except StoreError:
            self._db.close()
            raise

    # -- schema ------------------------------------------------------------------
    def _meta(self) -> dict[str, str]:
        rows = self._db.execute("SELECT name, value FROM meta").fetchall()
        return {str(k): str(v) for k, v in rows}

    def _check_or_init(self) -> None:
        with self._transaction():  # a write lock: two sweeps creating one store do not race
            tables = {r[0] for r in self._db.execute("SELECT name FROM sqlite_master WHERE type='table'")}
            if not tables:
                for stmt in _SCHEMA.split(";"):
                    if stmt.strip():
                        self._db.execute(stmt)
                self._db.executemany(
                    "INSERT INTO meta (name, value) VALUES (?, ?)",
                    [("application", APPLICATION), ("schema_version", str(SCHEMA_VERSION)),
                     ("created_by", __version__)],
                )
                log.info("created run store %s (schema %d)", self.path, SCHEMA_VERSION)
                return
        if "meta" not in tables:
            raise StoreError(f"{self.path}: a SQLite file but not a nowplan run store (no 'meta' table); "
                             "give a new --store file, or restore the store from a copy if it was one")
        meta = self._meta()
        if meta.get("application") != APPLICATION:
            raise StoreError(f"{self.path}: a SQLite file but not a nowplan run store (its meta table names no nowplan); "
                             "give a new --store file, or restore the store from a copy if it was one")
        found = meta.get("schema_version", "?")
        if found != str(SCHEMA_VERSION):
            raise StoreError(
                f"{self.path}: incompatible run store: written with schema version {found} by nowplan "
                f"{meta.get('created_by', '?')}, but this nowplan ({__version__}) reads schema version "
                f"{SCHEMA_VERSION}; use a new --store file or the nowplan version that wrote it"
            )

    def _transaction(self) -> _Tx:
        return _Tx(self._db)

    @property
    def meta(self) -> dict[str, str]:
        return self._meta()

    # -- records -----------------------------------------------------------------
    def put(self, record: RunRecord, *, replace: bool = False) -> bool:
        """Store one record atomically; returns False if its key was already stored.

        With ``replace`` an existing record for the same configuration is
        overwritten (used to retry crashed runs); otherwise the first
        record written for a configuration wins.
        """
        d = record.to_dict()
        row = tuple(
            json.dumps(d[c], sort_keys=True) if c == "metrics" else d[c] for c in _COLUMNS
        )
        verb = "INSERT OR REPLACE" if replace else "INSERT OR IGNORE"
        with self._transaction():
            cur = self._db.execute(
                f"{verb} INTO runs ({', '.join(_COLUMNS)}) VALUES ({', '.join('?' * len(_COLUMNS))})", row
            )
            return cur.rowcount > 0

    def keys(self, statuses: Iterable[RunStatus] | None = None) -> set[str]:
        if statuses is None:
            return {r[0] for r in self._db.execute("SELECT key FROM runs")}
        wanted = [s.value for s in statuses]
        q = f"SELECT key FROM runs WHERE status IN ({', '.join('?' * len(wanted))})"
        return {r[0] for r in self._db.execute(q, wanted)}

    def get(self, key: str) -> RunRecord | None:
        cur = self._db.execute(f"SELECT {', '.join(_COLUMNS)} FROM runs WHERE key = ?", (key,))
        row = cur.fetchone()
        return self._from_row(row) if row else None

    def records(self) -> list[RunRecord]:
        return list(self.iter_records())

    def iter_records(self) -> Iterator[RunRecord]:
        try:
            rows = self._db.execute(
                f"SELECT {', '.join(_COLUMNS)} FROM runs ORDER BY domain, scenario, strategy, seed, time_limit"
            ).fetchall()
        except (sqlite3.DatabaseError, UnicodeDecodeError) as exc:  # a damaged page can garble the error text too
            raise StoreError(f"{self.path}: the run store cannot be read ({exc}); restore it from a copy") from exc
        for row in rows:
            yield self._from_row(row)

    def __len__(self) -> int:
        return int(self._db.execute("SELECT COUNT(*) FROM runs").fetchone()[0])

    def _from_row(self, row: tuple[object, ...]) -> RunRecord:
        d = dict(zip(_COLUMNS, row, strict=True))
        try:
            d["metrics"] = json.loads(str(d["metrics"]))
            rec = RunRecord.from_dict(d)
        except (ValueError, KeyError, TypeError) as exc:
            raise StoreError(f"{self.path}: run {d.get('key')} is unreadable ({exc})") from exc
        if rec.key != d["key"]:
            raise StoreError(f"{self.path}: run {d['key']} does not match its configuration hash")
        return rec

    def has(self, config: RunConfig) -> bool:
        return self._db.execute("SELECT 1 FROM runs WHERE key = ?", (config.key,)).fetchone() is not None

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close()


class _Tx:
    """``BEGIN IMMEDIATE`` … ``COMMIT`` (or ``ROLLBACK`` on error) on an autocommit connection."""

    def __init__(self, db: sqlite3.Connection) -> None:
        self._db = db

    def __enter__(self) -> None:
        self._db.execute("BEGIN IMMEDIATE")

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        if exc_type is None:
            self._db.execute("COMMIT")
        else:
            self._db.execute("ROLLBACK")
