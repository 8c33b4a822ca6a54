/* Bounded weighted A* over bitset states: anytime.py's _bounded_wastar (LAMA's later iterations).
 *
 * Included once by _kernel.c after _kernel_gbfs.h (it uses the Kernel and the Store).  Entries
 * (f = g + w h, h, tick, state) pop the lowest f, then the lowest h, then the oldest; a popped
 * state is expanded with its best g so far (stale entries are not skipped, as in the Python
 * code); successors whose g reaches the bound, or that do not improve a known g, are pruned.
 */

typedef struct { double f, h; uint64_t tick; uint32_t sid; } WEnt;
static inline int wless(const WEnt *a, const WEnt *b) {
    if (a->f != b->f) return a->f < b->f;
    if (a->h != b->h) return a->h < b->h;
    return a->tick < b->tick;
}

NP_HEAP(WHeap, WEnt, wless, wpush, wpop)

static PyObject *Kernel_bounded_wastar(Kernel *k, PyObject *args, PyObject *kwds) {
    static char *kwlist[] = {"init", "cost", "weight", "bound", "stop", NULL};
    PyObject *init, *costs, *stop = Py_None, *result = NULL;
    double weight, bound;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "OOdd|O", kwlist, &init, &costs, &weight, &bound, &stop))
        return NULL;
    int32_t ns = load_state(k, init), npref = 0, words = k->words, na = k->na;
    if (ns < 0) return NULL;
    Store st = {.words = words};
    WHeap open = {0};
    double *cost = NULL, *bestg = NULL;
    size_t gcap = 0;
    int added;
    size_t na1 = (size_t)(na ? na : 1);
    int32_t *pref = PyMem_Malloc(na1 * sizeof(int32_t)), *succ = PyMem_Malloc(na1 * sizeof(int32_t));
    int32_t *sf = PyMem_Malloc(((size_t)k->nf + 1) * sizeof(int32_t));
    uint64_t *cur = PyMem_Calloc((size_t)words + 1, sizeof(uint64_t));
    uint64_t *nxt = PyMem_Calloc((size_t)words + 1, sizeof(uint64_t));
    if (!pref || !succ || !sf || !cur || !nxt) { PyErr_NoMemory(); goto error; }
    {
        PyObject *fc = PySequence_Fast(costs, "cost");
        if (fc == NULL) goto error;
        if (PySequence_Fast_GET_SIZE(fc) != na) {
            Py_DECREF(fc);
            PyErr_SetString(PyExc_ValueError, "cost: expected one per action");
            goto error;
        }
        if (!(cost = xcalloc(na1, sizeof(double)))) { Py_DECREF(fc); goto error; }
        for (int32_t a = 0; a < na; a++) {
            cost[a] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fc, a));
            if (cost[a] == -1.0 && PyErr_Occurred()) { Py_DECREF(fc); goto error; }
        }
        Py_DECREF(fc);
    }
    memcpy(cur, k->bits, (size_t)words * sizeof(uint64_t));
    memcpy(sf, k->sf, (size_t)ns * sizeof(int32_t));
    double h0 = evaluate_core(k, cur, sf, ns, pref, &npref);
    if (isnan(h0) && PyErr_Occurred()) goto error;
    if (h0 == INFINITY) { result = Py_None; Py_INCREF(result); goto error; }
    if (store_add(&st, cur, UINT32_MAX, -1, &added) < 0) goto error;
    uint64_t tick = 0;
    gcap = st.cap;
    if (!(bestg = PyMem_Malloc(gcap * sizeof(double)))) { PyErr_NoMemory(); goto error; }
    bestg[0] = 0.0;
    if (wpush(&open, (WEnt){weight * h0, h0, tick++, 0}) < 0) goto error;
    while (open.n) {
        WEnt e = wpop(&open);
        double g = bestg[e.sid];
        memcpy(cur, st.bits + (size_t)e.sid * (size_t)words, (size_t)words * sizeof(uint64_t));
        if (goal_holds(k, cur)) {
            if (g >= bound) continue;
            result = plan_of(&st, e.sid);
            goto error;
        }
        if (PyErr_CheckSignals() < 0) goto error;
        int halt = asked_to_stop(stop);
        if (halt < 0) goto error;
        if (halt) break;
        ns = facts_of(cur, words, sf);
        int32_t n = applicable_core(k, cur, sf, ns, succ);
        for (int32_t i = 0; i < n; i++) {
            int32_t a = succ[i];
            double ng = g + cost[a];
            if (ng >= bound) continue;
            apply_action(k, nxt, cur, a);
            long long sid = store_add(&st, nxt, e.sid, a, &added);
            if (sid < 0) goto error;
            if (st.cap > gcap) {
                double *v = PyMem_Realloc(bestg, st.cap * sizeof(double));
                if (v == NULL) { PyErr_NoMemory(); goto error; }
                bestg = v;
                gcap = st.cap;
            }
            if (added) bestg[sid] = INFINITY;
            if (!(ng < bestg[sid])) continue;
            bestg[sid] = ng;
            st.parent[sid] = e.sid;
            st.action[sid] = a;
            int32_t nn = facts_of(nxt, words, sf);
            double hv = evaluate_core(k, nxt, sf, nn, pref, &npref);
            if (isnan(hv) && PyErr_Occurred()) goto error;
            if (hv == INFINITY) continue;
            if (wpush(&open, (WEnt){ng + weight * hv, hv, tick++, (uint32_t)sid}) < 0) goto error;
        }
    }
    result = Py_None;
    Py_INCREF(result);
error:
    PyMem_Free(pref);
    PyMem_Free(succ);
    PyMem_Free(sf);
    PyMem_Free(cur);
    PyMem_Free(nxt);
    PyMem_Free(cost);
    PyMem_Free(bestg);
    PyMem_Free(open.v);
    store_free(&st);
    return result;
}
