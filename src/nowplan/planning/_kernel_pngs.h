/* Plan neighborhood graph search over bitset states: pngs.py's neighborhood_plan.
 *
 * Included once by _kernel.c after _kernel_gbfs.h (it uses the Kernel and the Store).  The
 * plan's states get the first ids; the graph grows breadth-first (a FIFO over the ids, successors
 * in ascending action order) until it holds `limit` states; then Dijkstra from the initial state
 * over the graph's states pops the lowest g, then the oldest entry, and stops at a goal state or
 * when g reaches the plan's cost (ties keep the plan).  The time callback is asked every
 * PNGS_CHECK expanded states of either phase.
 */

#define PNGS_CHECK 1024

typedef struct { double g; uint64_t tick; uint32_t sid; } DEnt;
static inline int dless(const DEnt *a, const DEnt *b) {
    if (a->g != b->g) return a->g < b->g;
    return a->tick < b->tick;
}

NP_HEAP(DHeap, DEnt, dless, dpush, dpop)

/* The id of the state in bits, or -1 if the store does not hold it. */
static long long store_find(const Store *s, const uint64_t *bits) {
    if (s->cap == 0) return -1;
    size_t w = (size_t)s->words;
    uint64_t h = hash_bits(bits, s->words);
    for (size_t j = h & s->mask;; j = (j + 1) & s->mask) {
        uint32_t id = s->slot[j];
        if (id == 0) return -1;
        if (s->hash[id - 1] == h && memcmp(s->bits + (size_t)(id - 1) * w, bits, w * sizeof(uint64_t)) == 0)
            return (long long)id - 1;
    }
}

static PyObject *Kernel_neighborhood(Kernel *k, PyObject *args, PyObject *kwds) {
    static char *kwlist[] = {"init", "plan", "limit", "cost", "stop", NULL};
    PyObject *init, *plan, *costs, *stop = Py_None, *result = NULL, *found = NULL;
    long long limit;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "OOLO|O", kwlist, &init, &plan, &limit, &costs, &stop))
        return NULL;
    int32_t ns = load_state(k, init), words = k->words, na = k->na, np = 0;
    if (ns < 0) return NULL;
    Store st = {.words = words};
    DHeap open = {0};
    int32_t *steps = NULL, *succ = NULL, *sf = NULL, *act = NULL;
    uint64_t *cur = NULL, *nxt = NULL;
    double *cost = NULL, *g = NULL, best = 0.0;
    uint32_t *par = NULL;
    uint8_t *closed = NULL;
    int added, complete = 1, stopped = 0;
    size_t na1 = (size_t)(na ? na : 1);
    if (build_list(plan, k->nact, "plan action", &steps, &np) < 0) goto error;
    succ = PyMem_Malloc(na1 * sizeof(int32_t));
    sf = PyMem_Malloc(((size_t)k->nf + 1) * sizeof(int32_t));
    cur = PyMem_Calloc((size_t)words + 1, sizeof(uint64_t));
    nxt = PyMem_Calloc((size_t)words + 1, sizeof(uint64_t));
    if (!succ || !sf || !cur || !nxt) { PyErr_NoMemory(); goto error; }
    {
        PyObject *fc = PySequence_Fast(costs, "cost");
        if (fc == NULL) goto error;
        if (PySequence_Fast_GET_SIZE(fc) < k->nact) {
            Py_DECREF(fc);
            PyErr_SetString(PyExc_ValueError, "cost: expected one per action");
            goto error;
        }
        if (!(cost = xcalloc(na1, sizeof(double)))) { Py_DECREF(fc); goto error; }
        for (int32_t a = 0; a < k->nact; a++) {
            cost[a] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fc, a));
            if (cost[a] == -1.0 && PyErr_Occurred()) { Py_DECREF(fc); goto error; }
        }
        Py_DECREF(fc);
    }
    /* the plan's states */
    memcpy(cur, k->bits, (size_t)words * sizeof(uint64_t));
    if (store_add(&st, cur, UINT32_MAX, -1, &added) < 0) goto error;
    for (int32_t i = 0; i < np; i++) {
        int32_t a = steps[i];
        for (int32_t j = k->pre.off[a]; j < k->pre.off[a + 1]; j++)
            if (!BIT(cur, k->pre.v[j])) {
                PyErr_Format(PyExc_ValueError, "the plan's action %d is not applicable where it stands", (int)a);
                goto error;
            }
        best += cost[a];
        apply_action(k, nxt, cur, a);
        memcpy(cur, nxt, (size_t)words * sizeof(uint64_t));
        if (store_add(&st, cur, UINT32_MAX, -1, &added) < 0) goto error;
    }
    /* breadth-first from all of them */
    for (size_t i = 0; i < st.n && complete;) {
        memcpy(cur, st.bits + i * (size_t)words, (size_t)words * sizeof(uint64_t));
        i++;
        if (i % PNGS_CHECK == 0) {
            if (PyErr_CheckSignals() < 0) goto error;
            int halt = asked_to_stop(stop);
            if (halt < 0) goto error;
            if (halt) { stopped = 1; complete = 0; break; }
        }
        ns = facts_of(cur, words, sf);
        int32_t n = applicable_core(k, cur, sf, ns, succ);
        for (int32_t j = 0; j < n; j++) {
            apply_action(k, nxt, cur, succ[j]);
            if (store_find(&st, nxt) >= 0) continue;
            if ((long long)st.n >= limit) { complete = 0; break; }
            if (store_add(&st, nxt, UINT32_MAX, -1, &added) < 0) goto error;
        }
    }
    if (!stopped) {
        /* Dijkstra from the initial state (id 0) over the graph */
        size_t n = st.n;
        g = PyMem_Malloc(n * sizeof(double));
        par = PyMem_Malloc(n * sizeof(uint32_t));
        act = PyMem_Malloc(n * sizeof(int32_t));
        closed = PyMem_Calloc(n, 1);
        if (!g || !par || !act || !closed) { PyErr_NoMemory(); goto error; }
        for (size_t i = 0; i < n; i++) g[i] = INFINITY;
        g[0] = 0.0;
        par[0] = UINT32_MAX;
        uint64_t tick = 0;
        size_t nclosed = 0;
        if (dpush(&open, (DEnt){0.0, tick++, 0}) < 0) goto error;
        while (open.n) {
            DEnt e = dpop(&open);
            if (closed[e.sid]) continue;
            closed[e.sid] = 1;
            nclosed++;
            if (e.g >= best) break;
            memcpy(cur, st.bits + (size_t)e.sid * (size_t)words, (size_t)words * sizeof(uint64_t));
            if (goal_holds(k, cur)) {
                Py_ssize_t len = 0;
                for (uint32_t i = e.sid; par[i] != UINT32_MAX; i = par[i]) len++;
                if (!(found = PyList_New(len))) goto error;
                for (uint32_t i = e.sid; par[i] != UINT32_MAX; i = par[i]) {
                    PyObject *x = PyLong_FromLong(act[i]);
                    if (x == NULL) goto error;
                    PyList_SET_ITEM(found, --len, x);
                }
                break;
            }
            if (nclosed % PNGS_CHECK == 0) {
                if (PyErr_CheckSignals() < 0) goto error;
                int halt = asked_to_stop(stop);
                if (halt < 0) goto error;
                if (halt) { stopped = 1; complete = 0; break; }
            }
            ns = facts_of(cur, words, sf);
            int32_t m = applicable_core(k, cur, sf, ns, succ);
            for (int32_t j = 0; j < m; j++) {
                int32_t a = succ[j];
                apply_action(k, nxt, cur, a);
                long long t = store_find(&st, nxt);
                if (t < 0 || closed[t]) continue;
                double ng = e.g + cost[a];
                if (ng < g[t]) {
                    g[t] = ng;
                    par[t] = e.sid;
                    act[t] = a;
                    if (dpush(&open, (DEnt){ng, tick++, (uint32_t)t}) < 0) goto error;
                }
            }
        }
    }
    if (found == NULL || stopped) {
        Py_CLEAR(found);
        if (!(found = id_list(steps, np))) goto error;
    }
    result = Py_BuildValue("(NnNN)", found, (Py_ssize_t)st.n, PyBool_FromLong(complete), PyBool_FromLong(stopped));
    found = NULL;
error:
    Py_XDECREF(found);
    PyMem_Free(steps);
    PyMem_Free(succ);
    PyMem_Free(sf);
    PyMem_Free(cur);
    PyMem_Free(nxt);
    PyMem_Free(cost);
    PyMem_Free(g);
    PyMem_Free(par);
    PyMem_Free(act);
    PyMem_Free(closed);
    PyMem_Free(open.v);
    store_free(&st);
    return result;
}
