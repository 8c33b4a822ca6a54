"""Fuzzing the PDDL front end: mutated files give a nowplan error or a model, never another exception.

Mutations of real files (the IPC-style corpus and the shipped domains):
byte flips, deleted / duplicated tokens and parentheses, random case
changes.  Reading (``load_pddl``) and grounding the result (the reachable
actions) may only raise :class:`nowplan.errors.NowplanError`.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.errors import NowplanError
from nowplan.io.pddl_read import load_pddl

AXIOM_CASES = 4  # the last PAIRS: recursive derived predicates

ROOT = Path(__file__).resolve().parent
PAIRS = [(ROOT / "data" / "pddl_ipc_style" / f"{n}-domain.pddl", ROOT / "data" / "pddl_ipc_style" / f"{n}-p01.pddl")
         for n in ("blocks", "miconic", "transport", "zenotravel", "tidybot", "briefcase", "rooms", "floortile",
                   "miconic-adl")]
DATA = ROOT.parent / "src" / "nowplan" / "data" / "pddl"
PAIRS += [(DATA / n / "domain.pddl", DATA / n / "p01.pddl") for n in ("logistics", "lights", "gripper")]
AXIOMS = ROOT / "data" / "pddl_axioms"  # recursive derived predicates
PAIRS += [(AXIOMS / f"{n}-domain.pddl", AXIOMS / f"{n}-p02.pddl") for n in ("doors", "grid")]
AXIOMS_RUN = ROOT / "data" / "pddl_axioms_run"  # what nowplan run is tested on (tests/test_axioms_run.py)
PAIRS += [(AXIOMS_RUN / f"{n}-domain.pddl", AXIOMS_RUN / f"{n}-p01.pddl") for n in ("courier", "blocks-above")]
TOKENS = re.compile(r"\(|\)|[^\s()]+")


@st.composite
def mutated(draw: st.DrawFn, text: str) -> str:
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["flip", "delete", "duplicate", "case", "paren"]))
        spans = [m.span() for m in TOKENS.finditer(text)]
        if kind == "flip" and text:
            i = draw(st.integers(0, len(text) - 1))
            b = text[i].encode("utf-8", "replace")[0] ^ (1 << draw(st.integers(0, 7)))
            text = text[:i] + chr(b) + text[i + 1:]
        elif kind in ("delete", "duplicate") and spans:
            s, e = spans[draw(st.integers(0, len(spans) - 1))]
            text = text[:s] + (text[s:e] * 2 if kind == "duplicate" else "") + text[e:]
        elif kind == "case" and text:
            s = draw(st.integers(0, len(text) - 1))
            e = min(len(text), s + draw(st.integers(1, 200)))
            text = text[:s] + "".join(c.upper() if draw(st.booleans()) else c for c in text[s:e]) + text[e:]
        elif kind == "paren" and spans:
            parens = [sp for sp in spans if text[sp[0]] in "()"]
            if parens:
                s, e = parens[draw(st.integers(0, len(parens) - 1))]
                text = text[:s] + (text[s] * 2 if draw(st.booleans()) else "") + text[e:]
    return text


def _read_and_ground(tmp: Path, domain: str, problem: str) -> None:
    d, p = tmp / "d.pddl", tmp / "p.pddl"
    d.write_text(domain, encoding="utf-8", errors="surrogatepass")
    p.write_text(problem, encoding="utf-8", errors="surrogatepass")
    try:
        prob = load_pddl(d, p)
        from nowplan.planning.task import grounding

        grounding(prob.domain, prob.objects, prob.init, 0)
        if not prob.domain.axioms:  # the h2 table `nowplan plan --engine regression` builds (planning/h2.py)
            from nowplan.core.levels import flat_levels as _flat
            from nowplan.planning.regression import PlannerConfig
            from nowplan.planning.regression_search import _Search

            _Search(prob.domain, prob.objects, prob.init, _flat(), PlannerConfig(engine="regression", h2=True),
                    None).pairs()
        if prob.domain.axioms:  # the rules' grounding and the evaluation of the initial state
            from nowplan.core.levels import flat_levels
            from nowplan.planning.task import build_task

            build_task(prob.domain, prob.objects, prob.init, prob.goal, flat_levels(), lambda a: 1.0)
            # what `nowplan run` adds: the world's closure of the initial state, the automatic hierarchy
            from nowplan.planning.abstraction import derive_hierarchy
            from nowplan.planning.derived_state import DerivedClosure

            DerivedClosure(prob.domain, prob.objects)(prob.init)
            derive_hierarchy(prob.domain)
    except NowplanError as exc:
        assert "\n" not in str(exc)


@st.composite
def cases(draw: st.DrawFn) -> tuple[str, str]:
    dom, prob = draw(st.sampled_from(PAIRS))
    dtext, ptext = dom.read_text(), prob.read_text()
    which = draw(st.sampled_from(["domain", "problem", "both"]))
    if which in ("domain", "both"):
        dtext = draw(mutated(dtext))
    if which in ("problem", "both"):
        ptext = draw(mutated(ptext))
    return dtext, ptext


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                    HealthCheck.too_slow])
@given(case=cases())
def test_mutated_pddl_gives_only_nowplan_errors(tmp_path: Path, case: tuple[str, str]) -> None:
    _read_and_ground(tmp_path, *case)


@pytest.mark.slow
@settings(max_examples=2000, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                     HealthCheck.too_slow])
@given(case=cases())
def test_mutated_pddl_gives_only_nowplan_errors_long(tmp_path: Path, case: tuple[str, str]) -> None:
    _read_and_ground(tmp_path, *case)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                    HealthCheck.too_slow])
@given(case=st.sampled_from(PAIRS[-AXIOM_CASES:]).flatmap(
    lambda pair: st.tuples(mutated(pair[0].read_text()), mutated(pair[1].read_text()))))
def test_mutated_axiom_domains_give_only_nowplan_errors(tmp_path: Path, case: tuple[str, str]) -> None:
    _read_and_ground(tmp_path, *case)
