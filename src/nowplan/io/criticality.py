"""Criticality side files: which preconditions matter at which abstraction level.

A criticality file is plain text, one rule per line (``#`` or ``;`` start a
comment)::

    # logistics.crit
    default 2                          # preconditions not matched below
    load-truck   (at ?truck ?loc)  1   # one precondition literal, by its variables
    unload-truck at                1   # every 'at' precondition of the action
    *            (not (clear ?x))  1   # that literal in every action having it
    *            in-city           3   # every 'in-city' precondition of any action

Each rule is ``ACTION SELECTOR CRITICALITY``; ``ACTION`` is an action name or
``*``; ``SELECTOR`` is a predicate name or a precondition literal written as
in the domain file (same variable names, ``(not ...)`` for a negative one);
``CRITICALITY`` is an integer >= 1.  The most specific rule wins: a literal
before a predicate, a named action before ``*``; then ``default`` (1 if not
given).  A precondition's criticality ``c`` keeps it in ``abs(op, i)`` for
every level ``i < c``; ``domain.top_level`` is the largest criticality - 1.

Errors name the file and the line: unknown actions and predicates, literals
that are not a precondition of the action, repeated rules, bad numbers.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from pathlib import Path

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.core.operators import Operator, Precondition
from nowplan.errors import PDDLError

_TOKEN = re.compile(r"\(|\)|[^\s()]+")


@dataclass(frozen=True)
class CriticalityRule:
    action: str  # name or "*"
    predicate: str
    literal: Atom | None  # None: every precondition of the predicate
    criticality: int
    line: int

    @property
    def rank(self) -> int:
        """Specificity: higher wins."""
        return (2 if self.literal is not None else 0) + (1 if self.action != "*" else 0)

    def matches(self, op: Operator, pre: Atom) -> bool:
        # an action compiled into several operators (ADL) is named by its PDDL name too
        if self.action not in ("*", op.name, op.pddl_name) or pre.predicate != self.predicate:
            return False
        return self.literal is None or self.literal == pre


@dataclass(frozen=True)
class CriticalitySpec:
    path: str
    default: int
    rules: tuple[CriticalityRule, ...]

    def criticality(self, op: Operator, pre: Atom) -> int:
        best: CriticalityRule | None = None
        for r in self.rules:
            if r.matches(op, pre) and (best is None or r.rank > best.rank):
                best = r
        return best.criticality if best is not None else self.default


def _literal(tokens: list[str], path: str, line: int) -> Atom:
    """Parse ``( pred ?a b )`` or ``( not ( pred ... ) )`` from tokens."""
    bad = PDDLError("malformed literal; write (pred ?x ...) or (not (pred ?x ...))", path=path, line=line)
    if len(tokens) < 3 or tokens[0] != "(" or tokens[-1] != ")":
        raise bad
    inner = tokens[1:-1]
    if inner[0] == "not":
        a = _literal(inner[1:], path, line)
        if a.value is False:
            raise bad
        return a.negate()
    if any(t in "()" for t in inner):
        raise bad
    args = tuple(Var(t[1:]) if t.startswith("?") else t for t in inner[1:])
    return Atom(inner[0], args, True)


def parse_criticality(path: str | Path) -> CriticalitySpec:
    """Read a criticality file (syntax only; :func:`apply_criticality` checks names)."""
    p = Path(path)
    if not p.is_file():
        raise PDDLError("criticality file not found (check the path)", path=str(path))
    default = 1
    default_line: int | None = None
    rules: list[CriticalityRule] = []
    try:
        text_all = p.read_text(encoding="utf-8")
    except (UnicodeDecodeError, OSError) as exc:
        raise PDDLError(f"cannot read the criticality file as UTF-8 text ({exc.__class__.__name__}); "
                        "give a text file (see docs/pddl.md)", path=str(path)) from exc
    for n, raw in enumerate(text_all.splitlines(), start=1):
        text = re.split(r"[#;]", raw, maxsplit=1)[0].strip().lower()
        if not text:
            continue
        tokens = _TOKEN.findall(text)

        def number(tok: str) -> int:
            try:
                v = int(tok)
            except ValueError:
                raise PDDLError(f"criticality must be a whole number >= 1, got '{tok}'",
                                path=str(path), line=n) from None
            if v < 1:
                raise PDDLError(f"criticality must be >= 1, got {v}", path=str(path), line=n)
            return v

        if tokens[0] == "default":
            if len(tokens) != 2:
                raise PDDLError("write 'default N'", path=str(path), line=n)
            if default_line is not None:
                raise PDDLError(f"default given twice (first on line {default_line})",
                                path=str(path), line=n)
            default, default_line = number(tokens[1]), n
            continue
        if len(tokens) < 3:
            raise PDDLError("write 'ACTION PREDICATE-OR-(LITERAL) CRITICALITY'", path=str(path), line=n)
        action, sel, crit = tokens[0], tokens[1:-1], number(tokens[-1])
        if action in "()":
            raise PDDLError("a rule starts with an action name or '*'", path=str(path), line=n)
        if len(sel) == 1 and sel[0] not in "()":
            rules.append(CriticalityRule(action, sel[0], None, crit, n))
        else:
            lit = _literal(sel, str(path), n)
            rules.append(CriticalityRule(action, lit.predicate, lit, crit, n))
    return CriticalitySpec(str(path), default, tuple(rules))


def _check(spec: CriticalitySpec, domain: Domain) -> None:
    seen: dict[tuple[str, str, Atom | None], int] = {}
    for r in spec.rules:
        def err(msg: str, r: CriticalityRule = r) -> PDDLError:
            return PDDLError(msg, path=spec.path, line=r.line)

        k = (r.action, r.predicate, r.literal)
        if k in seen:
            raise err(f"the same rule is given twice (first on line {seen[k]})")
        seen[k] = r.line
        if r.predicate not in domain.predicates:
            known = ", ".join(sorted(p for p in domain.predicates if p != "="))
            raise err(f"unknown predicate '{r.predicate}'; domain predicates: {known}")
        if r.action == "*":
            if not any(r.matches(o, p.atom) for o in domain.operators for p in o.preconditions):
                raise err(f"no action has a precondition matching '{_show(r)}'")
            continue
        ops = [o for o in domain.operators if r.action in (o.name, o.pddl_name)]
        if not ops:
            raise err(f"unknown action '{r.action}'; domain actions: "
                      f"{', '.join(o.name for o in domain.operators)}")
        op = ops[0]
        if not any(r.matches(o, p.atom) for o in ops for p in o.preconditions):
            have = ", ".join(_fmt(p.atom) for p in op.preconditions) or "none"
            raise err(f"action '{op.name}' has no precondition matching '{_show(r)}'; "
                      f"its preconditions: {have}")


def _fmt(a: Atom) -> str:
    body = "(" + " ".join([a.predicate, *(f"?{t.name}" if isinstance(t, Var) else str(t) for t in a.args)]) + ")"
    return body if a.value is not False else f"(not {body})"


def _show(r: CriticalityRule) -> str:
    return _fmt(r.literal) if r.literal is not None else r.predicate


AUTO = "auto"


def apply_criticality(domain: Domain, path_or_spec: str | Path | CriticalitySpec) -> Domain:
    """A copy of ``domain`` whose preconditions have the file's criticalities.

    The string ``"auto"`` (:data:`AUTO`, not a path) derives them from the domain
    (:func:`nowplan.planning.abstraction.auto_criticality`).
    """
    if isinstance(path_or_spec, str) and path_or_spec == AUTO:
        from nowplan.planning.abstraction import auto_criticality

        return auto_criticality(domain)
    spec = path_or_spec if isinstance(path_or_spec, CriticalitySpec) else parse_criticality(path_or_spec)
    _check(spec, domain)
    ops = tuple(
        replace(
            op,
            preconditions=tuple(
                Precondition(p.atom, spec.criticality(op, p.atom)) for p in op.preconditions
            ),
        )
        for op in domain.operators
    )
    return replace(domain, operators=ops)


def criticality_text(domain: Domain) -> str:
    """A criticality file reproducing ``domain``'s criticalities exactly (one line each)."""
    lines = ["# criticalities of domain " + domain.name, "default 1"]
    for op in domain.operators:
        for p in op.preconditions:
            if p.criticality != 1:
                lines.append(f"{op.name} {_fmt(p.atom)} {p.criticality}")
    return "\n".join(lines) + "\n"


def hierarchy_text(domain: Domain) -> str:
    """The automatic hierarchy of ``domain`` as a criticality file, with its levels as comments.

    One rule per predicate when all its preconditions share a criticality,
    else one rule per action and precondition literal (a predicate split by
    argument types, e.g. ``at`` of packages and of trucks).  Loading the text
    with :func:`apply_criticality` gives exactly ``auto_criticality(domain)``.
    """
    from nowplan.planning.abstraction import derive_hierarchy

    h = derive_hierarchy(domain)
    top = h.top
    lines = [
        f"# automatic criticalities for domain {domain.name} (nowplan criticality; docs/pddl.md)",
        "# Knoblock's ordered-monotonic hierarchy: an operator's effects share one level and its",
        "# preconditions are at that level or below, so refining a step never changes a literal",
        "# of a more abstract level.  A precondition at level k below its action's effects has",
        f"# criticality k+1; one at the action's own level, or static, {top + 1} (kept at every level).",
        "# Edit freely: this file loads with --criticality FILE.",
    ]
    if h.type_sets:
        lines.append("# [p]: an untyped argument the action requires to satisfy the static predicate p; such")
        lines.append("# type sets are taken as disjoint (run: checked on the problem's objects, else without)")
    for lvl, classes in sorted(h.by_level().items(), reverse=True):
        lines.append(f"# level {lvl} (criticality {lvl + 1}): " + ", ".join(str(c) for c in classes))
    if h.derived:
        lines.append("# derived (at the highest level of the literals their rules read): " + ", ".join(
            f"{d} {'static' if lv is None else lv}" for d, lv in sorted(h.derived.items())))
    statics = sorted(h.static) + [str(c) for c in h.static_classes()]
    if statics:
        lines.append(f"# static (criticality {top + 1}): " + ", ".join(statics))
    lines.append(f"default {top + 1}")
    crit: dict[tuple[str, str], set[int]] = {}  # (action, predicate) -> criticalities
    for op in domain.operators:
        for p in op.preconditions:
            crit.setdefault((op.name, p.atom.predicate), set()).add(h.criticality(domain, op, p.atom))
    per_pred: dict[str, set[int]] = {}
    for (_, pred), cs in crit.items():
        per_pred.setdefault(pred, set()).update(cs)
    for pred in sorted(per_pred):
        if per_pred[pred] == {top + 1}:
            continue  # the default
        if len(per_pred[pred]) == 1:
            lines.append(f"* {pred} {next(iter(per_pred[pred]))}")
            continue
        for op in domain.operators:
            cs = crit.get((op.name, pred), set())
            if len(cs) == 1 and cs != {top + 1}:
                lines.append(f"{op.name} {pred} {next(iter(cs))}")
            elif len(cs) > 1:
                seen: set[Atom] = set()
                for p in op.preconditions:
                    c = h.criticality(domain, op, p.atom)
                    if p.atom.predicate == pred and p.atom not in seen and c != top + 1:
                        seen.add(p.atom)
                        lines.append(f"{op.name} {_fmt(p.atom)} {c}")
    return "\n".join(lines) + "\n"
