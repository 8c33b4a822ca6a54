// nowplan trace viewer: draws the planning-and-execution tree (seed 000 Fig. 3 style),
// the timeline and the frames from the JSON model embedded in the page.
// Every string from the trace is written with textContent (never as markup).
(function () {
  'use strict';

  var data = JSON.parse(document.getElementById('trace-data').textContent);
  var plans = new Map();
  data.plans.forEach(function (p) { plans.set(p.id, p); });
  var framesByN = new Map();
  data.frames.forEach(function (f) {
    if (f.n !== null && f.n !== undefined && !framesByN.has(f.n)) { framesByN.set(f.n, f); }
  });
  var firstEventOfStep = new Map();  // "pid:index" -> seq of the first action (or step) event
  data.events.forEach(function (e) {
    if ((e.event === 'action' || e.event === 'step') && typeof e.plan_id === 'number') {
      var k = e.plan_id + ':' + e.index, cur = firstEventOfStep.get(k);
      if (!cur || (cur.kind === 'step' && e.event === 'action')) {
        firstEventOfStep.set(k, { seq: e.seq, kind: e.event });
      }
    }
  });

  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) { e.className = cls; }
    if (text !== undefined && text !== null) { e.textContent = String(text); }
    return e;
  }
  function link(href, text, cls) {
    var a = el('a', cls || '', text);
    a.href = href;
    return a;
  }
  function fmtNum(v, digits) {
    if (typeof v !== 'number') { return v === null || v === undefined ? '' : String(v); }
    return Number.isInteger(v) ? String(v) : v.toFixed(digits === undefined ? 3 : digits);
  }
  function compact(v) {
    if (v === null || v === undefined) { return ''; }
    return typeof v === 'string' ? v : JSON.stringify(v);
  }
  function stepId(pid, idx) { return 'p' + pid + '-s' + idx; }

  // -- header ----------------------------------------------------------------------------
  function renderRun() {
    var box = document.getElementById('run');
    var r = data.run || {}, end = data.end || {};
    var dl = el('dl', 'run-facts');
    function fact(k, v) {
      if (v === undefined || v === null || v === '') { return; }
      var pair = el('div', 'fact' + (String(v).length > 60 ? ' wide' : ''));
      pair.appendChild(el('dt', '', k));
      pair.appendChild(el('dd', '', v));
      dl.appendChild(pair);
    }
    fact('domain', r.domain);
    fact('problem', r.problem);
    fact('strategy', r.strategy && typeof r.strategy === 'object' ? r.strategy.name || compact(r.strategy) : r.strategy);
    fact('seed', r.seed);
    fact('goal', Array.isArray(r.goal) ? r.goal.join(' ∧ ') : compact(r.goal));
    fact('description', r.description);
    if (end.outcome) {
      fact('outcome', end.outcome + (end.reason ? ' (' + end.reason + ')' : ''));
    }
    var m = end.metrics || {};
    ['actions', 'execution_cost', 'plans_made', 'replans', 'plan_failures', 'planning_cpu_s', 'wall_s']
      .forEach(function (k) { if (k in m) { fact(k.replace(/_/g, ' '), fmtNum(m[k])); } });
    if (m.action_counts && typeof m.action_counts === 'object') {
      fact('action counts', Object.keys(m.action_counts).map(function (k) {
        return k + '=' + m.action_counts[k];
      }).join(', '));
    }
    box.appendChild(dl);
    if (end.outcome) { document.body.classList.add('outcome-' + String(end.outcome).replace(/[^a-z]/g, '')); }
  }

  function renderLegend() {
    var lg = document.getElementById('legend');
    [['node goal', 'goal / pre-image'], ['node op abstract', 'abstract operator'],
     ['node op primitive', 'primitive operator'], ['node op primitive executed', 'executed'],
     ['node op abstract refined', 'refined by a sub-plan'], ['node op abstract unselected', 'not reached'],
     ['node op primitive failed', 'failed (expected result missing)']]
      .forEach(function (pair) {
        var n = el('span', pair[0] + ' legend-item', pair[1]);
        lg.appendChild(n);
      });
  }

  // -- the tree --------------------------------------------------------------------------
  function goalNode(atoms, label) {
    var list = Array.isArray(atoms) ? atoms.map(String) : [];
    var n = el('div', 'node goal');
    if (label) { n.appendChild(el('div', 'node-label', label)); }
    var shown = list.length ? list : ['True'];
    var body = el('div', 'atoms');
    shown.forEach(function (a, i) {
      var s = el('span', 'atom' + (i >= 3 ? ' extra' : ''), a);
      body.appendChild(s);
    });
    n.appendChild(body);
    if (shown.length > 3) {
      var more = el('button', 'more', '+' + (shown.length - 3) + ' more');
      more.type = 'button';
      more.addEventListener('click', function () {
        var open = n.classList.toggle('expanded');
        more.textContent = open ? 'less' : '+' + (shown.length - 3) + ' more';
      });
      n.appendChild(more);
    }
    n.title = shown.join('\n');
    return n;
  }

  function opNode(p, s) {
    var cls = 'node op ' + (s.primitive ? 'primitive' : 'abstract');
    if (s.executed) { cls += ' executed'; }
    if (s.refined) { cls += ' refined'; }
    if (!s.selected && !s.executed && !s.refined) { cls += ' unselected'; }
    if (s.failures && s.failures.length) { cls += ' failed'; }
    var n = el('div', cls);
    n.id = stepId(p.id, s.index);
    n.appendChild(el('div', 'node-label',
      s.index + '. ' + (s.primitive ? 'primitive' : 'abstract' + (s.level !== null && s.level !== undefined ? ' · level ' + s.level : ''))));
    n.appendChild(el('div', 'action', s.action === null ? '—' : s.action));
    var marks = [];
    if (s.executed) { marks.push('✓ executed'); }
    if (s.refined) { marks.push('↓ refined'); }
    if (s.failures && s.failures.length) {
      marks.push('✗ ' + s.failures.map(function (f) { return f.reason || 'failed'; }).join('; '));
    }
    if (marks.length) { n.appendChild(el('div', 'marks', marks.join(' · '))); }
    var first = firstEventOfStep.get(p.id + ':' + s.index);
    if (first) {
      n.classList.add('clickable');
      n.addEventListener('click', function () { focusEvent(first.seq); });
    }
    return n;
  }

  function badge(text, cls) { return el('span', 'badge ' + (cls || ''), text); }

  function popBadge(pop) {
    var reason = String(pop.reason || '');
    return badge('popped: ' + reason, 'pop pop-' + reason.replace(/[^a-z]/g, ''));
  }

  // one badge per (trigger, reason), with a count: aggressive runs replan hundreds of times
  function replanBadges(list, head) {
    var groups = new Map();
    (list || []).forEach(function (r) {
      var k = (r.trigger || '?') + '\u0000' + (r.reason || '');
      if (!groups.has(k)) { groups.set(k, []); }
      groups.get(k).push(r);
    });
    groups.forEach(function (rs) {
      var r = rs[0];
      var b = badge('replan ← ' + (r.trigger || '?') + (r.reason ? ': ' + r.reason : '') +
        (rs.length > 1 ? ' ×' + rs.length : ''), 'replan');
      b.title = 'click: the first of these replans in the timeline';
      b.addEventListener('click', function () { focusEvent(r.seq); });
      head.appendChild(b);
    });
  }

  function failedPlanBox(f) {
    var box = el('div', 'plan failed-plan');
    box.appendChild(el('div', 'plan-title', 'planner failed: ' + (f.status || '') + (f.reason ? ' — ' + f.reason : '')));
    box.appendChild(goalNode(f.goal, 'goal'));
    return box;
  }

  function branch(label, content) {
    var b = el('div', 'branch');
    b.appendChild(el('div', 'branch-label', label));
    content.forEach(function (c) { b.appendChild(c); });
    return b;
  }

  function planBox(p) {
    var box = el('div', 'plan');
    box.id = 'plan-' + p.id;
    var head = el('div', 'plan-head');
    var toggle = el('button', 'toggle', '▾');
    toggle.type = 'button';
    toggle.title = 'collapse / expand the sub-plans';
    head.appendChild(toggle);
    var merged = (p.merged || []).map(function (m) { return m + ' → '; }).join('');
    head.appendChild(el('span', 'plan-title', 'Plan ' + merged + p.id));
    var meta = [];
    if (merged) { meta.push('plans ' + merged + p.id + ' share one goal; shown once'); }
    if (p.levels !== null && p.levels !== undefined) { meta.push('level ' + p.levels); }
    if (p.method) { meta.push(p.method); }
    meta.push('cost ' + fmtNum(p.cost));
    if (typeof p.cpu_s === 'number') { meta.push(fmtNum(p.cpu_s) + ' s CPU'); }
    if (typeof p.expanded === 'number') { meta.push(p.expanded + ' expanded'); }
    head.appendChild(el('span', 'plan-meta', meta.join(' · ')));
    if (p.pop) { head.appendChild(popBadge(p.pop)); }
    replanBadges(p.replans, head);
    box.appendChild(head);

    var row = el('div', 'steps');
    p.steps.forEach(function (s) {
      if (s.index === 0) {
        row.appendChild(goalNode(s.preimage, 'g0'));
      } else {
        row.appendChild(el('span', 'arrow', '→'));
        row.appendChild(opNode(p, s));
        row.appendChild(el('span', 'arrow', '→'));
        row.appendChild(goalNode(s.preimage, s.index === p.steps.length - 1 ? 'goal' : 'g' + s.index));
      }
    });
    box.appendChild(row);

    var kids = el('div', 'children');
    p.steps.forEach(function (s) {
      var content = [];
      (s.children || []).forEach(function (cid) { if (plans.has(cid)) { content.push(planBox(plans.get(cid))); } });
      (s.failed_plans || []).forEach(function (f) { content.push(failedPlanBox(f)); });
      if (content.length) {
        kids.appendChild(branch('refines step ' + s.index + ': ' + (s.action === null ? 'start' : s.action), content));
      }
    });
    if (kids.childNodes.length) {
      box.appendChild(kids);
      toggle.addEventListener('click', function () {
        var closed = box.classList.toggle('collapsed');
        toggle.textContent = closed ? '▸' : '▾';
      });
    } else {
      toggle.disabled = true;
      toggle.textContent = '·';
    }
    return box;
  }

  function renderTree() {
    var tree = document.getElementById('tree');
    var r = data.run || {};
    var root = el('div', 'plan root');
    root.id = 'plan-root';
    var head = el('div', 'plan-head');
    head.appendChild(el('span', 'plan-title', 'The run\'s goal'));
    head.appendChild(el('span', 'plan-meta', 'root: from the start (g0) to the goal; the plans made for it hang below'));
    if (data.root_pop) { head.appendChild(popBadge(data.root_pop)); }
    replanBadges(data.root_replans, head);
    root.appendChild(head);
    var row = el('div', 'steps');
    row.appendChild(goalNode([], 'g0'));
    row.appendChild(el('span', 'arrow', '→'));
    row.appendChild(goalNode(Array.isArray(r.goal) ? r.goal : [], 'goal'));
    root.appendChild(row);
    var kids = el('div', 'children');
    var content = data.roots.map(function (id) { return planBox(plans.get(id)); });
    (data.root_failed || []).forEach(function (f) { content.push(failedPlanBox(f)); });
    if (content.length) { kids.appendChild(branch('plans for the goal (each made after the previous was popped)', content)); }
    root.appendChild(kids);
    tree.appendChild(root);

    var tools = document.getElementById('tree-tools');
    [['expand all', false], ['collapse all', true]].forEach(function (pair) {
      var b = el('button', 'tool', pair[0]);
      b.type = 'button';
      b.addEventListener('click', function () {
        document.querySelectorAll('.plan').forEach(function (n) {
          var t = n.querySelector(':scope > .plan-head > .toggle');
          if (t && !t.disabled) { n.classList.toggle('collapsed', pair[1]); t.textContent = pair[1] ? '▸' : '▾'; }
        });
      });
      tools.appendChild(b);
    });
    tools.appendChild(el('span', 'count', data.plans.length + ' plans'));
  }

  // -- the timeline ----------------------------------------------------------------------
  var HIDDEN_BY_DEFAULT = { push: true, step: true };

  function describe(e, li) {
    var d = el('span', 'desc');
    function add(node) { d.appendChild(node); }
    function text(t) { add(document.createTextNode(t)); }
    switch (e.event) {
      case 'action':
        text('#' + e.n + ' ');
        add(el('code', '', e.action));
        text(' cost ' + fmtNum(e.cost) + ' ');
        add(link('#' + stepId(e.plan_id, e.index), 'plan ' + e.plan_id + ' step ' + e.index, 'ref'));
        if (framesByN.has(e.n)) { text(' '); add(link('#frame-' + framesByN.get(e.n).seq, 'frame', 'ref frame-link')); }
        break;
      case 'observation':
        text((e.success ? '✓ ' : '✗ ') + '#' + e.n + ' ');
        add(el('code', '', e.action));
        if (e.observation !== null && e.observation !== undefined) { text(' '); add(el('code', 'obs', compact(e.observation))); }
        li.classList.add(e.success ? 'ok' : 'bad');
        break;
      case 'failure':
        text('plan ' + e.plan_id + ' step ' + e.index + ': ' + (e.reason || '') + ' ');
        add(link('#' + stepId(e.plan_id, e.index), 'show', 'ref'));
        break;
      case 'replan':
        text('trigger: ' + (e.trigger || '?') + (e.reason ? ' — ' + e.reason : '') + ' (in plan ' + e.plan_id + ') ');
        if (plans.has(e.plan_id)) { add(link('#plan-' + e.plan_id, 'show', 'ref')); }
        break;
      case 'plan':
        text('plan ' + e.plan_id + ' made for ' + (e.goal || []).join(' ∧ ') + ' (' + (e.method || '') + ') ');
        add(link('#plan-' + e.plan_id, 'show', 'ref'));
        break;
      case 'plan_failed':
        text((e.status || 'failed') + ': ' + (e.reason || '') + ' — goal ' + (e.goal || []).join(' ∧ '));
        break;
      case 'pop':
        text('plan ' + e.plan_id + ' popped: ' + (e.reason || ''));
        break;
      case 'push':
        text('plan ' + e.plan_id + ' pushed (depth ' + e.depth + ')');
        break;
      case 'step':
        text('plan ' + e.plan_id + ' step ' + e.index + ': ' + (e.action === null ? 'start' : e.action) +
          (e.primitive ? ' (execute)' : ' (refine)'));
        break;
      case 'exogenous':
        text('after #' + e.n + ': ' + (Array.isArray(e.change) ? e.change.join('; ') : compact(e.change)));
        break;
      case 'frame':
        text('#' + e.n + ' ' + (e.caption || '') + ' ');
        add(link('#frame-' + e.seq, 'view frame', 'ref frame-link'));
        break;
      case 'note':
        text(compact(e.text));
        break;
      case 'run_start':
        text((e.domain || '') + ' / ' + (e.problem || '') + ', seed ' + e.seed);
        break;
      case 'run_end':
        text((e.outcome || '') + (e.reason ? ' (' + e.reason + ')' : ''));
        break;
      default:
        add(el('code', '', JSON.stringify(e)));
    }
    return d;
  }

  function renderTimeline() {
    var ol = document.getElementById('timeline');
    var kinds = [];
    data.events.forEach(function (e) {
      if (kinds.indexOf(e.event) < 0) { kinds.push(e.event); }
      var li = el('li', 'ev ev-' + String(e.event).replace(/[^a-z_]/g, ''));
      li.id = 'ev-' + e.seq;
      li.dataset.kind = e.event;
      if (HIDDEN_BY_DEFAULT[e.event]) { li.classList.add('hidden'); }
      li.appendChild(el('span', 'seq', e.seq));
      li.appendChild(el('span', 't', fmtNum(e.t, 3) + ' s'));
      li.appendChild(el('span', 'kind', e.event));
      li.appendChild(describe(e, li));
      var raw = el('button', 'raw-toggle', '{ }');
      raw.type = 'button';
      raw.title = 'show the raw event (line ' + data.lines[String(e.seq)] + ' of the trace)';
      var pre = null;
      raw.addEventListener('click', function () {
        if (!pre) { pre = el('pre', 'raw', JSON.stringify(e, null, 1)); li.appendChild(pre); } else { pre.remove(); pre = null; }
      });
      li.appendChild(raw);
      ol.appendChild(li);
    });
    var filters = document.getElementById('filters');
    kinds.forEach(function (k) {
      var label = el('label', 'filter');
      var box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = !HIDDEN_BY_DEFAULT[k];
      box.addEventListener('change', function () {
        ol.querySelectorAll('li.ev').forEach(function (li) {
          if (li.dataset.kind === k) { li.classList.toggle('hidden', !box.checked); }
        });
      });
      label.appendChild(box);
      label.appendChild(document.createTextNode(' ' + k));
      filters.appendChild(label);
    });
  }

  function focusEvent(seq) {
    var li = document.getElementById('ev-' + seq);
    if (!li) { return; }
    li.classList.remove('hidden');
    li.scrollIntoView({ block: 'center' });
    li.classList.add('flash');
    setTimeout(function () { li.classList.remove('flash'); }, 1500);
  }

  // -- frames ----------------------------------------------------------------------------
  function renderFrames() {
    var box = document.getElementById('frames');
    if (!data.frames.length) {
      box.appendChild(el('p', 'empty', 'No frames in this trace (the domain has no renderer, or rendering was off).'));
      return;
    }
    data.frames.forEach(function (f) {
      var fig = el('figure', 'frame');
      fig.id = 'frame-' + f.seq;
      if (f.src) {
        var img = document.createElement('img');
        img.alt = f.caption || ('frame ' + f.seq);
        img.src = f.src;
        fig.appendChild(img);
      } else {
        fig.appendChild(el('div', 'missing', 'image not embedded: ' + f.missing));
      }
      var cap = el('figcaption', '', (f.n !== null && f.n !== undefined ? '#' + f.n + ' ' : '') + (f.caption || ''));
      cap.appendChild(document.createTextNode(' '));
      cap.appendChild(link('#ev-' + f.seq, 'timeline', 'ref'));
      fig.appendChild(cap);
      box.appendChild(fig);
    });
  }

  renderRun();
  renderLegend();
  renderTree();
  renderTimeline();
  renderFrames();
  document.body.dataset.ready = 'true';
}());
