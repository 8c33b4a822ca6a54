/* The regression search's compiled loop: regression_astar.py's eager A* over subgoals as sets of
 * fact ids, for the calls whose estimate is a fixed value per fact (the ground h_add of
 * hadd_kernel.py) and whose facts are plain values (a fluent's facts exclude each other).
 *
 * It mirrors the Python loop exactly: the same pre-images (subgoals.regress), the same frontier
 * order (f, h, r, idle, stamp, seq) of rewrites.py, the same bookkeeping of the best cost, the
 * stamp a child was first made with and its parent, so both give the same plan and the same
 * counters (tests/test_regression_native.py).  What it cannot decide alone it asks Python, once per
 * fact and call: whether a fact holds (`holds(f)`), and a fact's achievers the first time the
 * search meets it (`need(f)`, which registers them with add_action / set_achievers and returns
 * False where the call must run in Python instead).  The facts, actions and achievers persist
 * across calls (one object per ground task and level, regression_native.py); a call whose level map
 * puts some actions at other levels (`local`) asks every fact's achievers once in the call instead
 * (set_local_achievers), since its templates of those actions differ.  Plain (pairwise) conflict
 * rules are asked of Python once per pair of facts (`conflict(x, y)`), the answers kept here.  A serialized call
 * (seed 002 V-B: `order`, a node is its facts and its focus) and a monotonic one (`protect`: no
 * step may change those facts' fluents) run here too.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "_kernel_heap.h"

#define REGRESS_API 6
enum { RS_SOLVED, RS_EXHAUSTED, RS_NODE_LIMIT, RS_TIME_LIMIT, RS_UNSUPPORTED };

#include "_kernel_regress_store.h"
#include "_kernel_regress_task.h"
#include "_kernel_regress_nodes.h"
#include "_kernel_regress_call.h"

static PyObject *Regressor_search(Regressor *R, PyObject *args) {
    PyObject *root, *hvals, *holds_fn, *need_fn, *stop, *order, *protect, *conflict_fn, *cost_fn, *h2 = Py_None;
    double weight;
    long long max_nodes;
    int no_rewrites, local;
    if (!PyArg_ParseTuple(args, "OOOOOdLpOOpOO|O", &root, &hvals, &holds_fn, &need_fn, &stop, &weight, &max_nodes,
                          &no_rewrites, &order, &protect, &local, &conflict_fn, &cost_fn, &h2))
        return NULL;
    const char *h2b = NULL, *h2r = NULL, *h2f = NULL;
    Py_ssize_t h2bl = 0, h2rl = 0, h2fl = 0, h2w = 0;
    if (h2 != Py_None) {  /* (bits: int32 per fact, reach: h2w words per bit, facts: h2w words, h2w) */
        if (!PyArg_ParseTuple(h2, "y#y#y#n", &h2b, &h2bl, &h2r, &h2rl, &h2f, &h2fl, &h2w)) return NULL;
        if (h2w < 1 || h2fl != h2w * 8 || h2rl % (h2w * 8) != 0 || h2bl % 4 != 0) {
            PyErr_SetString(PyExc_ValueError, "h2: bits, reach rows and facts of inconsistent sizes");
            return NULL;
        }
    }
    if (R->has_plain && conflict_fn == Py_None) {
        PyErr_SetString(PyExc_ValueError, "plain conflict rules need conflict(x, y)");
        return NULL;
    }
    if (R->in_call) { PyErr_SetString(PyExc_RuntimeError, "search() is not re-entrant"); return NULL; }
    int has_order = order != Py_None;
    int32_t focus0 = 0;
    Vec ov = {0};
    Call C = {R, holds_fn, need_fn, conflict_fn, cost_fn, NULL, 0, 0, 0, local,
              (const int32_t *)h2b, (const uint64_t *)h2r, (const uint64_t *)h2f, h2bl / 4, h2w};
    Nodes S = {0};
    RQueue Q = {0};
    Vec cur = {0}, allowed = {0}, child = {0}, newl = {0};
    PyObject *out = NULL;
    int status = RS_EXHAUSTED;
    long long exp = 0, generated = 0;
    uint64_t seq = 0;
    int32_t solved = -1;

    if (fit(R) < 0) goto done;
    R->in_call = 1;
    R->lach.n = 0;
    memset(R->asked, 0, R->caph);
    for (int32_t f = 0; f < R->nf; f++) R->holds[f] = -1;
    memset(R->flmark, 0, R->capfl * sizeof(uint32_t));
    memset(R->newmark, 0, R->capfl * sizeof(uint32_t));
    memset(R->kmark, 0, R->capk * sizeof(uint32_t));
    memset(R->lkmark, 0, R->capk * sizeof(uint32_t));
    memset(R->remmark, 0, R->caph * sizeof(uint32_t));
    memset(R->chmark, 0, R->caph * sizeof(uint32_t));
    memset(R->tried, 0, R->capt * sizeof(uint32_t));
    memset(R->cknown, 0, R->capt);
    memset(R->pcmark, 0, R->caph * sizeof(uint32_t));
    memset(R->guardmark, 0, R->capfl * sizeof(uint32_t));
    if (has_order) {
        if (read_ints(order, "order", &ov) < 0) goto done;
        focus0 = (int32_t)ov.n;
    }
    R->never = focus0 + 1;
    for (size_t f = 0; f < R->caph; f++) R->pos[f] = R->never;
    for (size_t i = 0; i < ov.n; i++) {
        int32_t f = ov.v[i];
        if (f >= R->nf) { PyErr_SetString(PyExc_ValueError, "order fact not added"); goto done; }
        if (R->pos[f] == R->never) R->pos[f] = (int32_t)i;
    }
    {
        Vec pv = {0};
        if (read_ints(protect, "protect", &pv) < 0) { PyMem_Free(pv.v); goto done; }
        for (size_t i = 0; i < pv.n; i++) {
            int32_t f = pv.v[i];
            if (f >= R->nf) { PyMem_Free(pv.v); PyErr_SetString(PyExc_ValueError, "protect fact not added"); goto done; }
            R->guardmark[R->fluent[f]] = 1;
            R->guardfact[R->fluent[f]] = f;
        }
        PyMem_Free(pv.v);
    }
    {
        PyObject *fast = PySequence_Fast(hvals, "hvals");
        if (fast == NULL) goto done;
        C.nv = PySequence_Fast_GET_SIZE(fast);
        C.hv = PyMem_Malloc((size_t)(C.nv ? C.nv : 1) * sizeof(double));
        if (C.hv == NULL) { Py_DECREF(fast); PyErr_NoMemory(); goto done; }
        for (Py_ssize_t i = 0; i < C.nv; i++) {
            double v = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fast, i));
            if (v == -1.0 && PyErr_Occurred()) { Py_DECREF(fast); goto done; }
            if (isfinite(v) && v != floor(v)) status = RS_UNSUPPORTED;  /* sums must not depend on order */
            C.hv[i] = v;
        }
        Py_DECREF(fast);
        if (status == RS_UNSUPPORTED) goto finish;
    }
    if (read_ints(root, "root", &cur) < 0) goto done;
    for (size_t i = 0; i < cur.n; i++)
        if (cur.v[i] >= R->nf) { PyErr_SetString(PyExc_ValueError, "root fact not added"); goto done; }
    qsort(cur.v, cur.n, sizeof(int32_t), cmp_int);
    {
        double h0 = 0.0, x;
        for (size_t i = 0; i < cur.n; i++) {
            if (hval(&C, cur.v[i], &x) < 0) goto done;
            h0 += x;
        }
        int32_t s = nodes_add(&S, cur.v, (int32_t)cur.n, focus0, hash_facts(cur.v, (int32_t)cur.n, focus0));
        if (s < 0) goto done;
        RNode *d = &S.v[s];
        d->g = 0.0; d->h = h0; d->r = 0; d->has_tail = 1;
        d->b0 = d->t0 = -1;
        REnt e = {weight * h0, h0, 0, 0, -1, 0, 0, s, seq++};
        if (rq_push(&Q, e) < 0) goto done;
    }

    while (Q.n) {
        REnt top = rq_pop(&Q);
        int32_t node = top.node;
        if (S.v[node].closed) continue;
        S.v[node].closed = 1;
        int32_t n = S.v[node].len, focus = S.v[node].focus;
        cur.n = 0;
        for (int32_t i = 0; i < n; i++)
            if (vpush(&cur, S.facts.v[S.v[node].start + i]) < 0) goto done;
        if (has_order && focus > 0) {  /* the focus shifts down once the atoms it hides all hold */
            int32_t last = -1;
            for (int32_t i = 0; i < n; i++) {
                int t = holds(&C, cur.v[i]);
                if (t < 0) goto done;
                if (!t && R->pos[cur.v[i]] > last) last = R->pos[cur.v[i]];
            }
            if (last < focus - 1) focus = last + 1;
        }
        int sat = 1;
        for (int32_t i = 0; i < n && sat; i++) {
            int t = holds(&C, cur.v[i]);
            if (t < 0) goto done;
            sat = t;
        }
        if (sat) { status = RS_SOLVED; solved = node; break; }
        exp++;
        if (exp > max_nodes) { status = RS_NODE_LIMIT; break; }
        if ((exp & 15) == 1) {
            int t = asked_to_stop(stop);
            if (t < 0) goto done;
            if (t) { status = RS_TIME_LIMIT; break; }
        }
        double gcost = S.v[node].g, hnode = S.v[node].h;
        int32_t rnode = S.v[node].r;
        uint32_t ep = ++C.epoch;
        R->pcl.n = 0;
        /* the node's index: its facts by fluent and by conflict key */
        for (int32_t i = 0; i < n; i++) {
            int32_t f = cur.v[i], fl = R->fluent[f];
            R->flmark[fl] = ep;
            R->flfact[fl] = f;
            for (int32_t k = 0; k < R->klen[f]; k++) {
                int32_t key = R->keys.v[R->kstart[f] + k];
                R->kmark[key] = ep;
                R->kfact[key] = f;
            }
        }
        allowed.n = 0;
        for (int32_t i = 0; i < n; i++)
            if (!(has_order && focus > 1 && R->pos[cur.v[i]] < focus - 1) && vpush(&allowed, cur.v[i]) < 0) goto done;
        int32_t nal = (int32_t)allowed.n;
        sort_by(allowed.v, nal, R->rank);
        for (int32_t ti = 0; ti < nal; ti++) {
            int32_t target = allowed.v[ti];
            int kn = known(&C, target);
            if (kn < 0) goto done;
            if (kn == 0) { status = RS_UNSUPPORTED; goto finish; }
            int32_t a0 = local ? R->lstart[target] : R->ach_start[target];
            int32_t alen = local ? R->llen[target] : R->ach_len[target];
            for (int32_t j = 0; j < alen; j++) {
                int32_t a = local ? R->lach.v[a0 + j] : R->ach.v[a0 + j];
                if (R->tried[a] == ep) continue;
                R->tried[a] = ep;
                /* ---- make: regress the node through a (subgoals.regress) */
                uint32_t mk = ++C.mk;
                int32_t nrem = 0, ok = 1;
                for (int32_t i = 0; i < R->al[a]; i++) {  /* monotonic: no step changes a protected fluent */
                    int32_t e = R->alls.v[R->as[a] + i], fl = R->fluent[e];
                    if (R->guardmark[fl] && R->guardfact[fl] != e) { ok = 0; break; }
                }
                if (!ok) continue;
                const int32_t *E = &R->effs.v[R->es[a]];
                int32_t ne = R->el[a];
                for (int32_t i = 0; i < ne && ok; i++) {
                    int32_t fl = E[2 * i], e = E[2 * i + 1];
                    if (R->flmark[fl] == ep) {
                        int32_t o = R->flfact[fl];
                        if (o != e) ok = 0;  /* plain values: only the fact itself entails it */
                        else if (R->remmark[o] != mk) { R->remmark[o] = mk; nrem++; }
                    }
                }
                if (!ok) continue;
                if (R->has_conflicts && n > nrem) {
                    if (R->clash[a]) continue;
                    const int32_t *K = &R->ekeys.v[R->ks[a]];
                    for (int32_t i = 0; i < R->kl[a] && ok; i++) {
                        int32_t key = K[2 * i], e = K[2 * i + 1];
                        if (R->kmark[key] == ep) {
                            int32_t o = R->kfact[key];
                            if (o != e && R->remmark[o] != mk) ok = 0;
                        }
                    }
                    if (!ok) continue;
                    for (int32_t i = 0; i < ne && R->has_plain; i++) {  /* FactTable.plain_clash */
                        int t = plain_clash(&C, E[2 * i + 1], cur.v, n, mk);
                        if (t < 0) goto done;
                        if (t) { ok = 0; break; }
                    }
                    if (!ok) continue;
                }
                const int32_t *P = &R->pres.v[R->ps[a]];
                int32_t np = R->pl[a];
                newl.n = 0;
                for (int32_t i = 0; i < np && ok; i++) {
                    int32_t p = P[i], fl = R->fluent[p];
                    if (R->newmark[fl] == mk) {
                        if (R->newfact[fl] != p) ok = 0;
                        continue;
                    }
                    if (R->flmark[fl] == ep && R->remmark[R->flfact[fl]] != mk) {
                        if (R->flfact[fl] != p) ok = 0;
                        continue;
                    }
                    R->newmark[fl] = mk;
                    R->newfact[fl] = p;
                    if (vpush(&newl, p) < 0) goto done;
                }
                if (!ok) continue;
                if (R->has_conflicts && newl.n) {
                    for (size_t i = 0; i < newl.n && ok; i++) {
                        int32_t nf = newl.v[i];
                        for (int32_t k = 0; k < R->klen[nf] && ok; k++) {
                            int32_t key = R->keys.v[R->kstart[nf] + k];
                            if (R->kmark[key] == ep) {
                                int32_t x = R->kfact[key];
                                if (x != nf && R->remmark[x] != mk) { ok = 0; break; }
                            }
                            if (R->lkmark[key] == mk && R->lkfact[key] != nf) { ok = 0; break; }
                            R->lkmark[key] = mk;
                            R->lkfact[key] = nf;
                        }
                    }
                    if (!ok) continue;
                    for (size_t i = 0; i < newl.n && R->has_plain && ok; i++) {
                        int t = plain_clash(&C, newl.v[i], cur.v, n, mk);
                        for (size_t j = i + 1; j < newl.n && t == 0; j++) t = plain_conflict(&C, newl.v[i], newl.v[j]);
                        if (t < 0) goto done;
                        if (t) ok = 0;
                    }
                    if (!ok) continue;
                }
                /* the child: the node's facts not removed merged with the new ones (both ascending) */
                sort_by(newl.v, (int32_t)newl.n, NULL);
                child.n = 0;
                {
                    size_t q = 0;
                    for (int32_t i = 0; i < n; i++) {
                        int32_t x = cur.v[i];
                        if (R->remmark[x] == mk) continue;
                        while (q < newl.n && newl.v[q] < x)
                            if (vpush(&child, newl.v[q++]) < 0) goto done;
                        if (vpush(&child, x) < 0) goto done;
                    }
                    while (q < newl.n)
                        if (vpush(&child, newl.v[q++]) < 0) goto done;
                }
                int32_t cn = (int32_t)child.n;
                if (C.h2bit != NULL && h2_excluded(&C, newl.v, newl.n, child.v, cn)) continue;  /* planning/h2.py */
                double cost;
                if (action_cost(&C, a, &cost) < 0) goto done;
                /* a pure rewrite (rewrites.pure_rewrite): held facts traded for new held facts at no cost */
                int rewrite = 0;
                if (cost == 0.0) {
                    for (int32_t i = 0; i < cn; i++) R->chmark[child.v[i]] = mk;
                    int anynew = 0, all = 1;
                    for (size_t i = 0; i < newl.n && all; i++) {
                        int32_t x = newl.v[i];
                        if (R->flmark[R->fluent[x]] == ep && R->flfact[R->fluent[x]] == x) continue;  /* in the node */
                        anynew = 1;
                        int t = holds(&C, x);
                        if (t < 0) goto done;
                        all = t;
                    }
                    for (int32_t i = 0; i < n && all && anynew; i++) {
                        if (R->chmark[cur.v[i]] == mk) continue;
                        int t = holds(&C, cur.v[i]);
                        if (t < 0) goto done;
                        all = t;
                    }
                    rewrite = anynew && all;
                }
                if (rewrite && no_rewrites) continue;
                uint64_t h = hash_facts(child.v, cn, focus);
                int32_t ci = nodes_find(&S, child.v, cn, focus, h);
                double ng = gcost + cost, old = ci >= 0 ? S.v[ci].g : INFINITY;
                if (ng > old || isinf(ng)) continue;
                int32_t r = rnode + rewrite, idl = 1;
                for (int32_t i = 0; i < ne; i++) {
                    int32_t fl = E[2 * i];
                    if (R->flmark[fl] == ep) {
                        int t = holds(&C, R->flfact[fl]);
                        if (t < 0) goto done;
                        if (!t) { idl = 0; break; }
                    }
                }
                double hh;
                if (ci >= 0 && ng == old) {
                    RNode *d = &S.v[ci];
                    if (stamp_less((int32_t)exp, ti, j, d->b0, d->b1, d->b2)) {
                        d->b0 = (int32_t)exp; d->b1 = ti; d->b2 = j;
                        d->parent = node; d->act = a;
                    }
                    if (d->closed || !d->has_tail) continue;
                    /* tail >= tails[child]: skip */
                    if (r != d->t_r ? r > d->t_r : idl != d->t_idle ? idl > d->t_idle :
                        !stamp_less((int32_t)exp, ti, j, d->t0, d->t1, d->t2))
                        continue;
                    hh = d->h;
                } else if (ci >= 0 && S.v[ci].closed) {
                    continue;
                } else {
                    if (ci < 0 && (ci = nodes_add(&S, child.v, cn, focus, h)) < 0) goto done;
                    RNode *d = &S.v[ci];
                    d->g = ng;
                    d->b0 = (int32_t)exp; d->b1 = ti; d->b2 = j;
                    d->parent = node; d->act = a;
                    generated++;
                    if (rewrite) {
                        hh = hnode;
                    } else {
                        hh = 0.0;
                        double x;
                        for (int32_t i = 0; i < cn; i++) {
                            if (hval(&C, child.v[i], &x) < 0) goto done;
                            hh += x;
                        }
                    }
                    if (isinf(hh)) continue;
                }
                RNode *d = &S.v[ci];
                d->h = hh; d->r = r; d->has_tail = 1;
                d->t_r = r; d->t_idle = idl; d->t0 = (int32_t)exp; d->t1 = ti; d->t2 = j;
                REnt e = {ng + weight * hh, hh, r, idl, (int32_t)exp, ti, j, ci, seq++};
                if (rq_push(&Q, e) < 0) goto done;
            }
        }
    }
finish:
    {
        PyObject *paths = Py_None, *acts = Py_None;
        Py_INCREF(Py_None);
        Py_INCREF(Py_None);
        if (status == RS_SOLVED) {
            Py_DECREF(paths);
            Py_DECREF(acts);
            paths = PyList_New(0);
            acts = PyList_New(0);
            if (paths == NULL || acts == NULL) { Py_XDECREF(paths); Py_XDECREF(acts); goto done; }
            for (int32_t x = solved; x >= 0; x = S.v[x].parent) {
                PyObject *l = int_list(&S.facts.v[S.v[x].start], S.v[x].len);
                if (l == NULL || PyList_Append(paths, l) < 0) { Py_XDECREF(l); Py_DECREF(paths); Py_DECREF(acts); goto done; }
                Py_DECREF(l);
                if (S.v[x].parent >= 0) {
                    PyObject *ai = PyLong_FromLong(S.v[x].act);
                    if (ai == NULL || PyList_Append(acts, ai) < 0) { Py_XDECREF(ai); Py_DECREF(paths); Py_DECREF(acts); goto done; }
                    Py_DECREF(ai);
                }
            }
        }
        out = Py_BuildValue("(iNNLL)", status, paths, acts, exp, generated);
    }
done:
    R->in_call = 0;
    PyMem_Free(C.hv);
    PyMem_Free(cur.v);
    PyMem_Free(allowed.v);
    PyMem_Free(child.v);
    PyMem_Free(newl.v);
    PyMem_Free(ov.v);
    PyMem_Free(Q.v);
    nodes_free(&S);
    return out;
}

static PyObject *Regressor_get_facts(Regressor *R, void *closure) { return PyLong_FromLong(R->nf); }
static PyObject *Regressor_get_actions(Regressor *R, void *closure) { return PyLong_FromLong(R->na); }

static PyMethodDef Regressor_methods[] = {
    {"add_fact", (PyCFunction)Regressor_add_fact, METH_VARARGS, "add_fact(fluent, keys): the next fact id"},
    {"set_rank", (PyCFunction)Regressor_set_rank, METH_VARARGS, "set_rank(rank, start=0): the sort positions of facts start.."},
    {"add_action", (PyCFunction)Regressor_add_action, METH_VARARGS,
     "add_action(effects, effect_keys, self_clash, pre, cost) -> index"},
    {"set_achievers", (PyCFunction)Regressor_set_achievers, METH_VARARGS, "set_achievers(fact, actions)"},
    {"use_task", (PyCFunction)Regressor_use_task, METH_VARARGS,
     "use_task(effects, pre, cost): the ground task's actions (once)"},
    {"add_task_action", (PyCFunction)Regressor_add_task_action, METH_O, "add_task_action(k) -> index"},
    {"task_achievers", (PyCFunction)Regressor_task_achievers, METH_O,
     "task_achievers(fact): its achievers are the task actions adding it"},
    {"task_index", (PyCFunction)Regressor_task_index, METH_O, "task_index(action) -> task action or -1"},
    {"set_local_achievers", (PyCFunction)Regressor_set_local_achievers, METH_VARARGS,
     "set_local_achievers(fact, actions): for the running call only"},
    {"search", (PyCFunction)Regressor_search, METH_VARARGS,
     "search(root, hvals, holds, need, stop, weight, max_nodes, no_rewrites, order, protect, local, conflict, cost)"},
    {NULL, NULL, 0, NULL},
};

static PyGetSetDef Regressor_getset[] = {
    {"facts", (getter)Regressor_get_facts, NULL, "facts added", NULL},
    {"actions", (getter)Regressor_get_actions, NULL, "actions added", NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyTypeObject RegressorType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "nowplan.planning._kernel_regress.Regressor",
    .tp_doc = "Regressor(has_conflicts, has_plain=False): the regression A*'s loop over one ground task's facts and actions",
    .tp_basicsize = sizeof(Regressor),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_new = Regressor_new,
    .tp_dealloc = (destructor)Regressor_dealloc,
    .tp_methods = Regressor_methods,
    .tp_getset = Regressor_getset,
};

static struct PyModuleDef regress_module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_kernel_regress",
    .m_doc = "The regression search's compiled loop (see regression_astar.py and regression_native.py).",
    .m_size = -1,
};

PyMODINIT_FUNC PyInit__kernel_regress(void) {
    if (PyType_Ready(&RegressorType) < 0) return NULL;
    PyObject *m = PyModule_Create(&regress_module);
    if (m == NULL) return NULL;
    if (PyModule_AddIntConstant(m, "API", REGRESS_API) < 0 || PyModule_AddIntConstant(m, "SOLVED", RS_SOLVED) < 0 ||
        PyModule_AddIntConstant(m, "EXHAUSTED", RS_EXHAUSTED) < 0 ||
        PyModule_AddIntConstant(m, "NODE_LIMIT", RS_NODE_LIMIT) < 0 ||
        PyModule_AddIntConstant(m, "TIME_LIMIT", RS_TIME_LIMIT) < 0 ||
        PyModule_AddIntConstant(m, "UNSUPPORTED", RS_UNSUPPORTED) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    Py_INCREF(&RegressorType);
    if (PyModule_AddObject(m, "Regressor", (PyObject *)&RegressorType) < 0) {
        Py_DECREF(&RegressorType);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}

