"""Formulas, effects and numeric expressions of PDDL, parsed from s-expressions.

The trees here are the front end's own (see :mod:`nowplan.io.pddl_syntax`
for domains and problems).  Parsing is lenient where planners are in
practice (every keyword case-insensitive, ``(and)`` and ``()`` as "true")
and refuses what nowplan cannot plan for with one line naming the
construct and its line: numeric conditions, numeric effects other than
``(increase (total-cost) ...)``, ``oneof``, temporal annotations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from nowplan.errors import PDDLError, UnsupportedPDDLError
from nowplan.io.sexpr import Item, SList, Token

TOTAL_COST = "total-cost"

# --------------------------------------------------------------------------- formulas


@dataclass(frozen=True)
class FAtom:
    pred: str
    args: tuple[str, ...]  # "?x" for a variable, else an object or constant name
    line: int


@dataclass(frozen=True)
class FNot:
    arg: Formula


@dataclass(frozen=True)
class FAnd:
    parts: tuple[Formula, ...]


@dataclass(frozen=True)
class FOr:
    parts: tuple[Formula, ...]


@dataclass(frozen=True)
class FQuant:
    kind: str  # "forall" or "exists"
    params: tuple[TypedName, ...]
    body: Formula
    line: int


Formula = FAtom | FNot | FAnd | FOr | FQuant
TRUE = FAnd(())


@dataclass(frozen=True)
class TypedName:
    name: str
    types: tuple[str, ...]  # () = object; more than one = (either ...)
    line: int


# --------------------------------------------------------------------------- effects and numbers


@dataclass(frozen=True)
class NConst:
    value: float


@dataclass(frozen=True)
class NFunc:
    name: str
    args: tuple[str, ...]
    line: int


@dataclass(frozen=True)
class NOp:
    op: str
    args: tuple[NExpr, ...]


NExpr = NConst | NFunc | NOp


@dataclass(frozen=True)
class ELit:
    atom: FAtom
    value: bool


@dataclass(frozen=True)
class EAnd:
    parts: tuple[Effect, ...]


@dataclass(frozen=True)
class EWhen:
    cond: Formula
    effect: Effect
    line: int


@dataclass(frozen=True)
class EForall:
    params: tuple[TypedName, ...]
    effect: Effect
    line: int


@dataclass(frozen=True)
class ECost:
    amount: NExpr
    line: int


Effect = ELit | EAnd | EWhen | EForall | ECost


# --------------------------------------------------------------------------- helpers


class Reader:
    """Errors of one file, with its path."""

    def __init__(self, path: str) -> None:
        self.path = path

    def error(self, msg: str, line: int | None) -> PDDLError:
        return PDDLError(msg, path=self.path, line=line)

    def refuse(self, msg: str, line: int | None) -> UnsupportedPDDLError:
        return UnsupportedPDDLError(msg, path=self.path, line=line)

    def token(self, item: Item | None, what: str, line: int) -> str:
        if not isinstance(item, Token):
            raise self.error(f"expected {what}, got {item if item is not None else 'nothing'}",
                             item.line if item is not None else line)
        return item.text

    def slist(self, item: Item | None, what: str, line: int) -> SList:
        if not isinstance(item, SList):
            raise self.error(f"expected {what} in parentheses, got {item if item is not None else 'nothing'}",
                             item.line if item is not None else line)
        return item

    # ------------------------------------------------------------------ typed lists

    def typed_list(self, items: tuple[Item, ...], what: str, line: int, variables: bool = False) -> list[TypedName]:
        """``a b - t c - (either u v) d`` as names with their types."""
        out: list[TypedName] = []
        pending: list[Token] = []
        i = 0
        while i < len(items):
            it = items[i]
            if isinstance(it, Token) and it.text == "-":
                if not pending:
                    raise self.error(f"'-' without names before it in {what}", it.line)
                if i + 1 >= len(items):
                    raise self.error(f"'-' without a type after it in {what}", it.line)
                types = self.type_spec(items[i + 1], what)
                out.extend(TypedName(t.text, types, t.line) for t in pending)
                pending = []
                i += 2
                continue
            if isinstance(it, SList):
                raise self.error(f"unexpected {it} in {what}: expected names", it.line)
            if variables and not it.text.startswith("?"):
                raise self.error(f"'{it.text}' in {what} is not a variable (variables start with '?')", it.line)
            if not variables and it.text.startswith("?"):
                raise self.error(f"the variable '{it.text}' cannot appear in {what}", it.line)
            pending.append(it)
            i += 1
        out.extend(TypedName(t.text, (), t.line) for t in pending)
        return out

    def type_spec(self, item: Item, what: str) -> tuple[str, ...]:
        if isinstance(item, Token):
            return () if item.text == "object" else (item.text,)
        if item.head() != "either" or len(item) < 2:
            raise self.error(f"bad type {item} in {what}: expected a name or (either ...)", item.line)
        names = tuple(sorted({self.token(t, "a type name", item.line) for t in item.items[1:]}))
        return () if "object" in names else names

    # ------------------------------------------------------------------ formulas

    def atom(self, lst: SList, where: str) -> FAtom:
        head = lst.head()
        if not head:
            raise self.error(f"expected a predicate name at the start of {lst} in {where}", lst.line)
        args = []
        for a in lst.items[1:]:
            if isinstance(a, SList):
                if a.head() in _NUMERIC_HEADS or head in _COMPARISONS:
                    raise self.refuse(f"{where} uses the numeric condition {lst}; numeric planning is "
                                      "not supported (only action costs are)", lst.line)
                raise self.error(f"unexpected {a} as an argument of '{head}' in {where}", a.line)
            args.append(a.text)
        if head in _COMPARISONS and head != "=":
            raise self.refuse(f"{where} uses the numeric condition {lst}; numeric planning is not "
                              "supported (only action costs are)", lst.line)
        return FAtom(head, tuple(args), lst.line)

    def formula(self, item: Item, where: str) -> Formula:
        if isinstance(item, Token):
            raise self.error(f"expected a condition in parentheses in {where}, got '{item.text}'", item.line)
        head = item.head()
        if not item.items or (head == "and" and len(item) == 1):
            return TRUE
        rest = item.items[1:]
        if head == "and":
            return FAnd(tuple(self.formula(x, where) for x in rest))
        if head == "or":
            return FOr(tuple(self.formula(x, where) for x in rest))
        if head == "not":
            if len(rest) != 1:
                raise self.error(f"(not ...) takes one condition in {where}", item.line)
            return FNot(self.formula(rest[0], where))
        if head == "imply":
            if len(rest) != 2:
                raise self.error(f"(imply ...) takes two conditions in {where}", item.line)
            return FOr((FNot(self.formula(rest[0], where)), self.formula(rest[1], where)))
        if head in ("forall", "exists"):
            if len(rest) != 2:
                raise self.error(f"({head} (variables) condition) expected in {where}", item.line)
            params = self.slist(rest[0], f"the variables of {head}", item.line)
            tl = self.typed_list(params.items, f"the variables of {head} in {where}", item.line, True)
            return FQuant(head, tuple(tl), self.formula(rest[1], where), item.line)
        if head in ("at", "over") and rest and isinstance(rest[0], Token) and rest[0].text in (
                "start", "end", "all"):
            raise self.refuse(f"{where} uses the temporal condition ({head} {rest[0].text} ...); durative "
                              "(temporal) planning is not supported", item.line)
        if head in ("preference",):
            raise self.refuse(f"{where} uses a preference; preferences are not supported", item.line)
        if not isinstance(item.items[0], Token):
            raise self.error(f"unexpected {item} in {where}", item.line)
        return self.atom(item, where)

    # ------------------------------------------------------------------ effects

    def effect(self, item: Item, where: str) -> Effect:
        if isinstance(item, Token):
            raise self.error(f"expected an effect in parentheses in {where}, got '{item.text}'", item.line)
        head = item.head()
        if not item.items or (head == "and" and len(item) == 1):
            return EAnd(())
        rest = item.items[1:]
        if head == "and":
            return EAnd(tuple(self.effect(x, where) for x in rest))
        if head == "not":
            if len(rest) != 1:
                raise self.error(f"(not ...) takes one atom in {where}", item.line)
            inner = self.slist(rest[0], "an atom", item.line)
            if inner.head() in _CONNECTIVES:
                raise self.error(f"(not {inner.head()} ...) is not an effect ({where}): negate atoms only",
                                 item.line)
            return ELit(self.atom(inner, where), False)
        if head == "when":
            if len(rest) != 2:
                raise self.error(f"(when condition effect) expected in {where}", item.line)
            return EWhen(self.formula(rest[0], where), self.effect(rest[1], where), item.line)
        if head == "forall":
            if len(rest) != 2:
                raise self.error(f"(forall (variables) effect) expected in {where}", item.line)
            params = self.slist(rest[0], "the variables of forall", item.line)
            tl = self.typed_list(params.items, f"the variables of forall in {where}", item.line, True)
            return EForall(tuple(tl), self.effect(rest[1], where), item.line)
        if head in ("increase", "decrease", "assign", "scale-up", "scale-down"):
            target = rest[0] if rest else None
            if (head == "increase" and len(rest) == 2 and isinstance(target, SList)
                    and target.head() == TOTAL_COST and len(target) == 1):
                return ECost(self.numeric(rest[1], where), item.line)
            raise self.refuse(f"{where} uses the numeric effect {item}; only (increase (total-cost) ...) "
                              "is supported (numeric fluents that change are numeric planning)", item.line)
        if head == "oneof":
            raise self.refuse(f"{where} uses a non-deterministic effect (oneof ...), which is not supported",
                              item.line)
        if head in ("at", "over") and rest and isinstance(rest[0], Token) and rest[0].text in ("start", "end"):
            raise self.refuse(f"{where} uses the temporal effect ({head} {rest[0].text} ...); durative "
                              "(temporal) planning is not supported", item.line)
        if head in _CONNECTIVES:
            raise self.error(f"({head} ...) is not an effect ({where})", item.line)
        if head == "=":
            raise self.error(f"{where} has an equality in its effect", item.line)
        if not isinstance(item.items[0], Token):
            raise self.error(f"unexpected {item} in {where}", item.line)
        return ELit(self.atom(item, where), True)

    def numeric(self, item: Item, where: str) -> NExpr:
        if isinstance(item, Token):
            try:
                value = float(item.text)
            except ValueError:
                raise self.error(f"expected a number or a function term in {where}, got '{item.text}'",
                                 item.line) from None
            if not math.isfinite(value):
                raise self.error(f"'{item.text}' in {where} is not a finite number", item.line)
            return NConst(value)
        head = item.head()
        if head in ("+", "-", "*", "/") and len(item) >= 2:
            return NOp(head, tuple(self.numeric(x, where) for x in item.items[1:]))
        if not head:
            raise self.error(f"expected a numeric expression in {where}, got {item}", item.line)
        args = []
        for a in item.items[1:]:
            if isinstance(a, SList):
                raise self.error(f"unexpected {a} as an argument of the function '{head}' in {where}", a.line)
            args.append(a.text)
        return NFunc(head, tuple(args), item.line)


_COMPARISONS = frozenset({"=", "<", ">", "<=", ">="})
_NUMERIC_HEADS = frozenset({"+", "-", "*", "/"})
_CONNECTIVES = frozenset({"and", "or", "imply", "exists", "forall", "not"})
