"""PDDL domains and problems as the front end's own syntax trees.

:func:`parse_domain` and :func:`parse_problem` read the s-expressions of
:mod:`nowplan.io.sexpr` into :class:`DomainDef` / :class:`ProblemDef`,
leniently as planners are in practice: keywords in any case, sections in
any order, ``object`` declared again in ``:types``, ``(either ...)`` types,
``:functions`` with or without ``- number``.  Constructs nowplan does not
plan for (durative actions, processes, events, constraints) are refused
with a line naming them; unknown sections are errors with their line.
"""

from __future__ import annotations

import logging
import re
from dataclasses import dataclass, field

from nowplan.io.pddl_ast import TOTAL_COST, Effect, Formula, NExpr, Reader, TypedName
from nowplan.io.sexpr import Item, SList, Token, parse_sexprs

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ActionDef:
    name: str
    params: tuple[TypedName, ...]
    precondition: Formula | None
    effect: Effect | None
    line: int


@dataclass(frozen=True)
class DerivedDef:
    pred: str
    params: tuple[TypedName, ...]
    body: Formula
    line: int


@dataclass
class DomainDef:
    path: str
    name: str
    requirements: dict[str, int] = field(default_factory=dict)  # name -> line
    types: dict[str, tuple[str, ...]] = field(default_factory=dict)  # type -> parent types (() = object)
    type_lines: dict[str, int] = field(default_factory=dict)
    constants: list[TypedName] = field(default_factory=list)
    predicates: dict[str, tuple[tuple[TypedName, ...], int]] = field(default_factory=dict)
    functions: dict[str, tuple[tuple[TypedName, ...], int]] = field(default_factory=dict)
    actions: list[ActionDef] = field(default_factory=list)
    derived: list[DerivedDef] = field(default_factory=list)
    line: int = 1
    # evaluate every derived predicate by rules, even without recursion (set by load_pddl when
    # substituting their definitions exceeds a compilation bound)
    native_axioms: bool = False


@dataclass
class ProblemDef:
    path: str
    name: str
    domain_name: str = ""
    domain_line: int = 1
    requirements: dict[str, int] = field(default_factory=dict)
    objects: list[TypedName] = field(default_factory=list)
    init: list[tuple[Item, int]] = field(default_factory=list)  # raw items, read against the domain
    goal: Formula | None = None
    goal_line: int = 1
    metric: tuple[str, NExpr] | None = None
    metric_line: int = 1


# PDDL 1.x files (IPC-1998) open with the Lisp directive (in-package "PDDL") before (define ...)
_IN_PACKAGE = re.compile(r'\(\s*in-package\s+("[^"\n]*"|[^\s()]+)\s*\)', re.IGNORECASE)


def _lisp_prefix_end(text: str) -> int:
    """Where the first form starts: past leading whitespace and ``;`` comments (a scan, no backtracking)."""
    pos, n = 0, len(text)
    while pos < n:
        if text[pos].isspace():
            pos += 1
        elif text[pos] == ";":
            end = text.find("\n", pos)
            pos = n if end < 0 else end
        else:
            break
    return pos


def _define(r: Reader, text: str, kind: str) -> tuple[SList, str, int]:
    start = _lisp_prefix_end(text)
    m = _IN_PACKAGE.match(text, start)
    if m is not None:
        line = text.count("\n", 0, start) + 1
        log.warning("%s:%d: the Lisp directive (in-package %s) before (define ...) is ignored (accepted)",
                    r.path, line, m.group(1))
        blank = "".join(c if c == "\n" else " " for c in text[start:m.end()])
        text = text[:start] + blank + text[m.end():]  # same length: the lines of the rest stay right
    items = parse_sexprs(text, r.path)
    if not items:
        raise r.error(f"the file is empty: expected (define ({kind} NAME) ...)", None)
    top = items[0]
    if not isinstance(top, SList) or top.head() != "define":
        raise r.error(f"expected (define ({kind} NAME) ...) at the start of the file", top.line)
    if len(items) > 1:
        raise r.error("text after the end of (define ...)", items[1].line)
    header = r.slist(top.items[1] if len(top) > 1 else None, f"({kind} NAME)", top.line)
    if header.head() != kind or len(header) != 2:
        other = "problem" if kind == "domain" else "domain"
        hint = f" (is this a {other} file? give the domain first, then the problem)" if \
            header.head() == other else ""
        raise r.error(f"expected ({kind} NAME) after define, got {header}{hint}", header.line)
    return top, r.token(header.items[1], f"the {kind} name", header.line), top.line


def _requirements(r: Reader, sec: SList) -> dict[str, int]:
    out = {}
    for t in sec.items[1:]:
        name = r.token(t, "a requirement such as :strips", sec.line)
        out[name.lstrip(":")] = t.line if isinstance(t, Token) else sec.line
    return out


_REFUSED_SECTIONS = {
    ":durative-action": "durative actions (temporal planning)",
    ":process": "processes (PDDL+)",
    ":event": "events (PDDL+)",
    ":constraints": "state-trajectory constraints",
}


def parse_domain(text: str, path: str) -> DomainDef:
    r = Reader(path)
    top, name, line = _define(r, text, "domain")
    d = DomainDef(path, name, line=line)
    seen: dict[str, int] = {}
    for sec in top.items[2:]:
        sec = r.slist(sec, "a section such as (:predicates ...)", top.line)
        head = sec.head()
        if head in _REFUSED_SECTIONS:
            raise r.refuse(f"{_REFUSED_SECTIONS[head]} ({head}) are not supported: nowplan plans for "
                           "classical (instantaneous, non-numeric) PDDL", sec.line)
        if head in seen and head not in (":action", ":derived"):
            raise r.error(f"the section {head} appears twice (first on line {seen[head]})", sec.line)
        seen[head] = sec.line
        if head == ":requirements":
            d.requirements = _requirements(r, sec)
        elif head == ":types":
            for tn in r.typed_list(sec.items[1:], "(:types ...)", sec.line):
                if tn.name == "object":
                    continue  # object re-declared (tidybot): it is the root anyway
                if tn.name in d.types:
                    # Declared again (IPC-2006 storage: `area - object` then `area - surface`): as
                    # Fast Downward, the later parent wins unless it is only `object`.
                    if tn.types in ((), ("object",)) or tn.types == d.types[tn.name]:
                        continue
                    if d.types[tn.name] not in ((), ("object",)):
                        log.warning("%s:%d: the type '%s' is declared again with the parent %s "
                                    "(the later parent is used)", r.path, tn.line, tn.name,
                                    " ".join(tn.types))
                d.types[tn.name] = tn.types
                d.type_lines[tn.name] = tn.line
        elif head == ":constants":
            d.constants = r.typed_list(sec.items[1:], "(:constants ...)", sec.line)
        elif head == ":predicates":
            for p in sec.items[1:]:
                p = r.slist(p, "a predicate declaration", sec.line)
                pname = r.token(p.items[0] if p.items else None, "a predicate name", p.line)
                if pname in d.predicates:
                    raise r.error(f"the predicate '{pname}' is declared twice", p.line)
                args = r.typed_list(p.items[1:], f"the predicate {pname}", p.line, True)
                d.predicates[pname] = (tuple(args), p.line)
        elif head == ":functions":
            _functions(r, sec, d)
        elif head == ":action":
            d.actions.append(_action(r, sec))
        elif head == ":derived":
            d.derived.append(_derived(r, sec))
        else:
            raise r.error(f"unknown section {head or sec} in the domain; expected :requirements, :types, "
                          ":constants, :predicates, :functions, :action or :derived", sec.line)
    return d


def _functions(r: Reader, sec: SList, d: DomainDef) -> None:
    items = sec.items[1:]
    i = 0
    while i < len(items):
        f = items[i]
        if isinstance(f, Token) and f.text == "-":
            i += 2  # "- number" (or "- object"): the value type of the functions before it
            continue
        f = r.slist(f, "a function declaration", sec.line)
        fname = r.token(f.items[0] if f.items else None, "a function name", f.line)
        args = r.typed_list(f.items[1:], f"the function {fname}", f.line, True)
        d.functions[fname] = (tuple(args), f.line)
        i += 1


def _action(r: Reader, sec: SList) -> ActionDef:
    name = r.token(sec.items[1] if len(sec) > 1 else None, "an action name", sec.line)
    where = f"action {name}"
    params: list[TypedName] = []
    pre: Formula | None = None
    eff: Effect | None = None
    rest = sec.items[2:]
    if len(rest) % 2:
        raise r.error(f"{where}: expected :parameters, :precondition and :effect, each followed by one "
                      "value", sec.line)
    for key, val in zip(rest[::2], rest[1::2], strict=True):
        k = r.token(key, "a keyword such as :parameters", sec.line)
        if k == ":parameters":
            plist = r.slist(val, f"the parameters of {where}", sec.line)
            params = r.typed_list(plist.items, f"the parameters of {where}", plist.line, True)
        elif k == ":precondition":
            pre = r.formula(val, f"the precondition of {where}")
        elif k == ":effect":
            eff = r.effect(val, f"the effect of {where}")
        elif k == ":vars":
            # PDDL 1.x (IPC-1998 ADL files): variables bound by the precondition, not listed in plans
            raise r.refuse(f"{where} declares :vars (PDDL 1.x variables bound by the precondition), which "
                           "is not supported; declare them in :parameters instead",
                           key.line if isinstance(key, Token) else sec.line)
        else:
            raise r.error(f"unknown keyword {k} in {where}; expected :parameters, :precondition or :effect",
                          key.line if isinstance(key, Token) else sec.line)
    return ActionDef(name, tuple(params), pre, eff, sec.line)


def _derived(r: Reader, sec: SList) -> DerivedDef:
    if len(sec) != 3:
        raise r.error("(:derived (predicate ?args) condition) expected", sec.line)
    head = r.slist(sec.items[1], "the derived predicate", sec.line)
    pname = r.token(head.items[0] if head.items else None, "a predicate name", head.line)
    params = r.typed_list(head.items[1:], f"the derived predicate {pname}", head.line, True)
    return DerivedDef(pname, tuple(params), r.formula(sec.items[2], f"the derived predicate {pname}"), sec.line)


def parse_problem(text: str, path: str) -> ProblemDef:
    r = Reader(path)
    top, name, _ = _define(r, text, "problem")
    p = ProblemDef(path, name)
    seen: dict[str, int] = {}
    for sec in top.items[2:]:
        sec = r.slist(sec, "a section such as (:init ...)", top.line)
        head = sec.head()
        if head in seen:
            raise r.error(f"the section {head} appears twice (first on line {seen[head]})", sec.line)
        seen[head] = sec.line
        if head == ":domain":
            p.domain_name = r.token(sec.items[1] if len(sec) > 1 else None, "the domain name", sec.line)
            p.domain_line = sec.line
        elif head == ":requirements":
            p.requirements = _requirements(r, sec)
        elif head == ":objects":
            p.objects = r.typed_list(sec.items[1:], "(:objects ...)", sec.line)
        elif head == ":init":
            p.init = [(it, it.line) for it in sec.items[1:]]
        elif head == ":goal":
            if len(sec) != 2:
                raise r.error("(:goal ...) takes one condition (use (and ...) for several)", sec.line)
            p.goal = r.formula(sec.items[1], "the goal")
            p.goal_line = sec.line
        elif head == ":metric":
            if len(sec) != 3:
                raise r.error("(:metric minimize|maximize expression) expected", sec.line)
            p.metric = (r.token(sec.items[1], "minimize or maximize", sec.line), r.numeric(sec.items[2], "the metric"))
            p.metric_line = sec.line
        elif head == ":constraints":
            raise r.refuse("state-trajectory constraints (:constraints) are not supported", sec.line)
        elif head == ":length":
            # PDDL 1.2's hint of the plan length, (:length (:serial N) (:parallel N)), in some IPC-1998
            # problems: it constrains nothing, so it is skipped
            log.warning("%s:%d: (:length ...) is a hint of PDDL 1.2 and is ignored", r.path, sec.line)
        else:
            raise r.error(f"unknown section {head or sec} in the problem; expected :domain, :objects, :init, "
                          ":goal or :metric", sec.line)
    if p.goal is None:
        raise r.error("the problem has no (:goal ...)", top.line)
    return p


__all__ = ["TOTAL_COST", "ActionDef", "DerivedDef", "DomainDef", "ProblemDef", "parse_domain", "parse_problem"]
