"""ADL compilation is exact: property test against the independent interpreter of tests/pddl_sim.py.

Random actions over two objects, with preconditions built from and / or /
not / imply / exists / forall / = and effects with when / forall-when, and a
random state.  For every binding of the parameters, the original action is
applicable (per the interpreter) exactly when some compiled operator is, and
every applicable compiled operator gives the interpreter's successor state.
"""

from __future__ import annotations

import itertools
from pathlib import Path

from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Var
from nowplan.errors import UnsupportedPDDLError
from nowplan.io.pddl_read import load_pddl

from pddl_sim import Sim

OBJECTS = ("a", "b")
PREDS = {"p": 1, "q": 1, "r": 0, "s": 2}


def atoms(params: list[str]) -> st.SearchStrategy[str]:
    terms = st.sampled_from([*params, *OBJECTS])

    def atom(pred: str) -> st.SearchStrategy[str]:
        n = PREDS[pred]
        return st.tuples(*([terms] * n)).map(lambda args: "(" + " ".join((pred, *args)) + ")")

    return st.sampled_from(sorted(PREDS)).flatmap(atom)


def formulas(params: list[str], depth: int = 2) -> st.SearchStrategy[str]:
    base = st.one_of(atoms(params), st.tuples(st.sampled_from([*params, *OBJECTS]),
                                               st.sampled_from([*params, *OBJECTS])).map(lambda t: f"(= {t[0]} {t[1]})"))
    if depth == 0:
        return base
    sub = formulas(params, depth - 1)
    var = f"?v{depth}"
    inner = formulas([*params, var], depth - 1)
    return st.one_of(
        base,
        sub.map(lambda f: f"(not {f})"),
        st.lists(sub, min_size=1, max_size=3).map(lambda fs: "(and " + " ".join(fs) + ")"),
        st.lists(sub, min_size=1, max_size=3).map(lambda fs: "(or " + " ".join(fs) + ")"),
        st.tuples(sub, sub).map(lambda t: f"(imply {t[0]} {t[1]})"),
        inner.map(lambda f: f"(exists ({var}) {f})"),
        inner.map(lambda f: f"(forall ({var}) {f})"),
    )


def literal(params: list[str]) -> st.SearchStrategy[str]:
    return st.tuples(atoms(params), st.booleans()).map(lambda t: t[0] if t[1] else f"(not {t[0]})")


def effects(params: list[str]) -> st.SearchStrategy[str]:
    plain = literal(params)
    when = st.tuples(formulas(params, 1), st.lists(literal(params), min_size=1, max_size=2)).map(
        lambda t: f"(when {t[0]} (and {' '.join(t[1])}))")
    forall_when = st.tuples(formulas([*params, "?w"], 1), literal([*params, "?w"])).map(
        lambda t: f"(forall (?w) (when {t[0]} {t[1]}))")
    return st.lists(st.one_of(plain, when, forall_when), min_size=1, max_size=3).map(
        lambda es: "(and " + " ".join(es) + ")")


@st.composite
def cases(draw: st.DrawFn) -> tuple[str, str]:
    params = ["?x", "?y"][: draw(st.integers(0, 2))]
    pre = draw(formulas(params))
    eff = draw(effects(params))
    ground = [(p, args) for p, n in PREDS.items() for args in itertools.product(OBJECTS, repeat=n)]
    state = draw(st.lists(st.sampled_from(ground), unique=True, max_size=8))
    decl = " ".join("(" + " ".join([p, *(f"?a{i}" for i in range(n))]) + ")" for p, n in PREDS.items())
    domain = (f"(define (domain t) (:requirements :adl) (:constants {' '.join(OBJECTS)}) (:predicates {decl})\n"
              f"  (:action act :parameters ({' '.join(params)}) :precondition {pre} :effect {eff}))")
    init = " ".join("(" + " ".join([p, *args]) + ")" for p, args in state)
    problem = f"(define (problem t1) (:domain t) (:init {init}) (:goal (r)))"
    return domain, problem


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                    HealthCheck.too_slow])
@given(case=cases())
@example(case=("(define (domain t) (:requirements :adl) (:constants a b) (:predicates (p ?a0) (r))\n"
               "  (:action act :parameters () :precondition (not (forall (?v2) (p ?v2))) :effect (r)))",
               "(define (problem t1) (:domain t) (:init (p a)) (:goal (r)))"))
@example(case=("(define (domain t) (:requirements :adl) (:constants a b) (:predicates (p ?a0) (q ?a0))\n"
               "  (:action act :parameters (?x) :precondition (exists (?v) (and (p ?v) (not (= ?v ?x))))\n"
               "   :effect (and (not (p ?x)) (forall (?w) (when (and (p ?w) (not (q ?w))) (q ?w))))))",
               "(define (problem t1) (:domain t) (:init (p a) (p b) (q b)) (:goal (q a)))"))
def test_compiled_operators_match_the_adl_semantics(tmp_path: Path, case: tuple[str, str]) -> None:
    domain, problem = case
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    try:
        prob = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl", mutexes=False)
    except UnsupportedPDDLError as exc:  # a compilation bound: must say which
        assert "bound" in str(exc)
        return
    state = {a for a in prob.init.atoms() if a.value is True and a.predicate != "="}
    ops = [o for o in prob.domain.operators if (o.pddl_name or o.name) == "act"]
    n = domain.split(":parameters (")[1].split(")")[0].count("?")
    for args in itertools.product(OBJECTS, repeat=n):
        sim = Sim(domain, problem)
        step = "(" + " ".join(("act", *args)) + ")"
        try:
            sim.apply(step)
            expected: set[tuple[str, ...]] | None = sim.state
        except AssertionError:
            expected = None
        results = []
        for op in ops:
            act = op.instantiate(dict(zip(op.params, args, strict=True)))
            full = state | {a for a in prob.init.atoms() if a.predicate == "="}
            if all(p.negate() not in full if p.value is False else p in full for p in act.preconditions()):
                after = set(state)
                for e in act.effects():
                    if e.value is False:
                        after.discard(e.negate())
                    else:
                        after.add(e)
                results.append({(a.predicate, *map(str, a.args)) for a in after})
        if expected is None:
            assert results == [], (step, domain)
        elif not results:
            # only a variant that changes nothing may be left out
            assert expected == {(a.predicate, *map(str, a.args)) for a in state}, (step, domain)
        else:
            assert all(r == expected for r in results), (step, domain)
    assert not any(isinstance(t, Var) and t not in o.params for o in ops for p in o.preconditions
                   for t in p.atom.args)
