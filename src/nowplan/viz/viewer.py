"""A self-contained HTML viewer for JSONL traces (``nowplan view``).

The page shows the planning-and-execution tree in the style of seed 000
Fig. 3 — each plan a box of goal (pre-image) and operator nodes, the plans
that refine a step hung under that step, executed steps marked, pops with
their reasons and replans with their triggers — and a timeline of actions,
observations, failures, replans and frames.  Everything (CSS, JS, images)
is inlined; a Content-Security-Policy forbids any network access, and the
script writes trace strings only through ``textContent``.

The trace format is ``docs/trace-format.md``; a malformed line raises
:class:`~nowplan.errors.TraceError` naming its line number.
"""

from __future__ import annotations

import base64
import html
import json
import logging
import mimetypes
import re
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from nowplan import __version__
from nowplan.errors import TraceError
from nowplan.tree import build_tree

log = logging.getLogger(__name__)

# fields the viewer relies on, per event kind, with their JSON types
_REQUIRED: dict[str, dict[str, tuple[type, ...]]] = {
    "plan": {"plan_id": (int,), "steps": (list,)},
    "push": {"plan_id": (int,)},
    "pop": {"plan_id": (int,)},
    "step": {"plan_id": (int,), "index": (int,)},
    "action": {"plan_id": (int,), "index": (int,)},
    "failure": {"plan_id": (int,)},
    "replan": {"plan_id": (int,)},
    "frame": {"image": (str,)},
}
_IMAGE_MIME = ("image/png", "image/gif", "image/jpeg", "image/webp")
_DATA_URI = re.compile(r"^data:(image/(?:png|gif|jpeg|webp));base64,[A-Za-z0-9+/=\s]*$")
MAX_IMAGE_BYTES = 20 * 1024 * 1024


@dataclass
class Trace:
    path: Path
    events: list[dict[str, Any]]
    lines: dict[int, int] = field(default_factory=dict)  # seq -> line number


def read_trace(path: str | Path) -> Trace:
    """Parse and check a JSONL trace; :class:`TraceError` names the first bad line."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise TraceError(f"{p}: no such trace file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise TraceError(f"{p}: cannot read the trace ({exc})") from exc
    events: list[dict[str, Any]] = []
    lines: dict[int, int] = {}
    plan_lines: dict[int, int] = {}
    for lineno, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        where = f"{p}:{lineno}"
        try:
            ev = json.loads(line)
        except json.JSONDecodeError as exc:
            raise TraceError(f"{where}: malformed trace line: {exc.msg} at column {exc.colno}") from None
        if not isinstance(ev, dict):
            raise TraceError(f"{where}: malformed trace line: expected a JSON object, got {type(ev).__name__}")
        kind = ev.get("event")
        if not isinstance(kind, str):
            raise TraceError(f"{where}: malformed trace line: no 'event' field")
        for name, types in _REQUIRED.get(kind, {}).items():
            v = ev.get(name)
            if not isinstance(v, types) or isinstance(v, bool):
                want = "/".join(t.__name__ for t in types)
                raise TraceError(f"{where}: malformed '{kind}' event: field '{name}' should be {want}, got {v!r}")
        if kind == "plan":
            pid = int(ev["plan_id"])
            if pid in plan_lines:
                raise TraceError(f"{where}: plan {pid} was already made on line {plan_lines[pid]}")
            plan_lines[pid] = lineno
            for step in ev["steps"]:
                if not isinstance(step, dict) or not isinstance(step.get("index"), int):
                    raise TraceError(f"{where}: malformed 'plan' event: each step needs an integer 'index'")
        seq = ev.get("seq")
        if not isinstance(seq, int) or isinstance(seq, bool):
            seq = len(events)
            ev["seq"] = seq
        lines[seq] = lineno
        events.append(ev)
    if not events:
        raise TraceError(f"{p}: empty trace (no events)")
    return Trace(p, events, lines)


# -- the model the page's script renders ---------------------------------------------------


def _frame_src(image: str, base: Path) -> tuple[str | None, str]:
    """A data URI for a frame's image (inlined from a file if needed), or None and why not."""
    if image.startswith("data:"):
        if _DATA_URI.fullmatch(image):
            return image, ""
        return None, "unsupported data URI (PNG, GIF, JPEG or WebP only)"
    if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*://", image):
        return None, "external image not embedded (the page makes no network requests)"
    f = (base / image).resolve()
    mime = mimetypes.guess_type(f.name)[0] or ""
    if mime not in _IMAGE_MIME:
        return None, f"not an image file: {image}"
    try:
        data = f.read_bytes()
    except OSError as exc:
        log.warning("frame image %s not embedded: %s", f, exc)
        return None, f"image file not found: {image}"
    if len(data) > MAX_IMAGE_BYTES:
        return None, f"image too large to embed: {image}"
    return f"data:{mime};base64," + base64.b64encode(data).decode("ascii"), ""


def merge_same_goal(plans: list[dict[str, Any]], roots: list[int]) -> list[int]:
    """Show a plan whose single step was refined into one plan for the same goal once.

    Such a plan says nothing its sub-plan does not (``<abs-1>`` refined into ``<abs-1>``): every
    reference to it (the roots, its parent step's children) is pointed at the sub-plan, which
    lists the plans it stands for in ``merged``.  Returns the new roots.
    """
    by_id = {p["id"]: p for p in plans}

    def shown(pid: int) -> int:
        chain = []
        p = by_id.get(pid)
        while p is not None:
            real = p["steps"][1:]
            if len(real) != 1 or len(real[0]["children"]) != 1 or real[0]["failures"] or real[0]["failed_plans"]:
                break
            child = by_id.get(real[0]["children"][0])
            if child is None or child["goal"] != p["goal"] or child["id"] in chain or child["id"] == pid:
                break
            chain.append(p["id"])
            p = child
        if p is None or not chain:
            return pid
        p["merged"] = [*chain, *[m for m in p.get("merged", []) if m not in chain]]
        return int(p["id"])

    for p in plans:
        for s in p["steps"]:
            s["children"] = [shown(c) for c in s["children"]]
    return [shown(r) for r in roots]


def build_model(trace: Trace) -> dict[str, Any]:
    """Plans (with children, executed steps, pops, replans, failures), timeline and frames."""
    events = trace.events
    _, nodes = build_tree(events)
    plan_events = {int(e["plan_id"]): e for e in events if e["event"] == "plan"}
    selected: dict[int, set[int]] = {}
    acted: dict[int, set[int]] = {}
    failures: dict[tuple[int, int], list[dict[str, Any]]] = {}
    failed_plans: dict[tuple[int, int], list[dict[str, Any]]] = {}
    pops: dict[int, dict[str, Any]] = {}
    for e in events:
        kind = e["event"]
        if kind == "step":
            selected.setdefault(int(e["plan_id"]), set()).add(int(e["index"]))
        elif kind == "action":
            acted.setdefault(int(e["plan_id"]), set()).add(int(e["index"]))
        elif kind == "failure":
            failures.setdefault((int(e["plan_id"]), int(e.get("index") or 0)), []).append(e)
        elif kind == "plan_failed" and isinstance(e.get("parent"), int):
            failed_plans.setdefault((int(e["parent"]), int(e.get("parent_step") or 0)), []).append(e)
        elif kind == "pop":
            pops[int(e["plan_id"])] = e
    empty: dict[str, Any] = {}
    run_start = next((e for e in events if e["event"] == "run_start"), empty)
    run_end = next((e for e in reversed(events) if e["event"] == "run_end"), empty)

    plans: list[dict[str, Any]] = []
    for pid, node in sorted(nodes.items()):
        ev = plan_events[pid]
        steps = []
        for s in node.steps:
            i = int(s["index"])
            steps.append({
                **{k: s.get(k) for k in ("index", "action", "level", "primitive", "hidden", "preimage")},
                "selected": i in selected.get(pid, set()),
                "executed": i in acted.get(pid, set()),
                "refined": bool(node.children.get(i)),
                "failures": failures.get((pid, i), []),
                "children": [c.plan_id for c in node.children.get(i, [])],
                "failed_plans": failed_plans.get((pid, i), []),
            })
        plans.append({
            "id": pid, "parent": node.parent, "parent_step": node.parent_step, "goal": node.goal,
            "levels": ev.get("levels"), "method": node.method, "cost": node.cost,
            "cpu_s": ev.get("cpu_s"), "expanded": ev.get("expanded"), "seq": ev.get("seq"),
            "steps": steps, "pop": pops.get(pid), "replans": node.replans,
        })
    roots = [p["id"] for p in plans if p["parent"] is None or p["parent"] not in nodes]
    roots = merge_same_goal(plans, roots)
    # the executive's dummy root plan (start -> the run's goal) has no plan event of its own
    root_failed = [e for (parent, _), es in failed_plans.items() if parent not in nodes for e in es]
    root_replans = [e for e in events if e["event"] == "replan" and int(e["plan_id"]) not in nodes]

    frames = []
    for e in events:
        if e["event"] == "frame":
            src, why = _frame_src(str(e["image"]), trace.path.parent)
            frames.append({"seq": e["seq"], "n": e.get("n"), "caption": str(e.get("caption") or ""),
                           "src": src, "missing": why})
    return {
        "file": trace.path.name,
        "run": run_start,
        "end": run_end,
        "plans": plans,
        "roots": roots,
        "root_failed": root_failed,
        "root_replans": root_replans,
        "root_pop": pops.get(0) if 0 not in nodes else None,
        "events": events,
        "lines": {str(seq): line for seq, line in trace.lines.items()},
        "frames": frames,
        "version": __version__,
    }


# -- the page ------------------------------------------------------------------------------

_CSP = (
    "default-src 'none'; img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'; "
    "base-uri 'none'; form-action 'none'"
)


def _asset(name: str) -> str:
    return resources.files("nowplan.viz").joinpath(name).read_text(encoding="utf-8")


def _json_for_script(data: Any) -> str:
    """JSON that cannot close its ``<script>`` element or start markup."""
    text = json.dumps(data, default=str, ensure_ascii=False)
    return (
        text.replace("&", "\\u0026").replace("<", "\\u003c").replace(">", "\\u003e")
        .replace("\u2028", "\\u2028").replace("\u2029", "\\u2029")
    )


def render_page(model: dict[str, Any], title: str | None = None) -> str:
    t = html.escape(title or f"nowplan trace: {model.get('file', '')}")
    return (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
        f'<meta http-equiv="Content-Security-Policy" content="{_CSP}">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>{t}</title>\n<style>\n{_asset('viewer.css')}</style>\n</head>\n<body>\n"
        f'<header><h1 id="title">{t}</h1><div id="run"></div></header>\n'
        '<noscript>This page needs JavaScript to draw the trace.</noscript>\n'
        '<main><section id="tree-section"><h2>Planning and execution tree</h2>'
        '<div id="legend"></div><div id="tree-tools"></div><div id="tree"></div></section>\n'
        '<section id="timeline-section"><h2>Timeline</h2><div id="filters"></div>'
        '<ol id="timeline"></ol></section>\n'
        '<section id="frames-section"><h2>Frames</h2><div id="frames"></div></section></main>\n'
        f'<script type="application/json" id="trace-data">{_json_for_script(model)}</script>\n'
        f"<script>\n{_asset('viewer.js')}</script>\n</body></html>\n"
    )


def write_viewer(trace_path: str | Path, out_path: str | Path, title: str | None = None) -> Path:
    """``nowplan view``: read a trace and write its page."""
    trace = read_trace(trace_path)
    page = render_page(build_model(trace), title)
    out = Path(out_path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(page, encoding="utf-8")
    log.info("wrote %s (%d events)", out, len(trace.events))
    return out
