/* Lazy greedy best-first search over bitset states: forward.py's _lazy_gbfs.
 *
 * Included once by _kernel.c (one translation unit; it uses the Kernel
 * struct and evaluate_core / applicable_core / facts_of).  States live in
 * an arena of fixed-size bitsets with a hash table over them; each queue
 * entry is (h, tick, parent state, action) and the queues pop the lowest h,
 * then the lowest tick (first in, first out).
 */

typedef struct { double h; uint64_t tick; uint32_t sid; int32_t a; } QEnt;
static inline int qless(const QEnt *a, const QEnt *b) {
    if (a->h != b->h) return a->h < b->h;
    return a->tick < b->tick;
}

NP_HEAP(Queue, QEnt, qless, qpush, qpop)

typedef struct {
    int32_t words;
    uint64_t *bits, *hash;  /* state i: bits[i * words ..], its hash */
    uint32_t *parent;       /* UINT32_MAX at the root */
    int32_t *action;
    size_t n, cap;
    uint32_t *slot;  /* open addressing: state id + 1, 0 when empty */
    size_t mask;
} Store;

static void store_free(Store *st) {
    PyMem_Free(st->bits);
    PyMem_Free(st->hash);
    PyMem_Free(st->parent);
    PyMem_Free(st->action);
    PyMem_Free(st->slot);
}

static uint64_t hash_bits(const uint64_t *b, int32_t words) {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (int32_t w = 0; w < words; w++) {
        h = (h ^ b[w]) * 0xff51afd7ed558ccdull;
        h ^= h >> 29;
    }
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    return h ^ (h >> 33);
}

static int store_grow(Store *s) {
    size_t cap = s->cap ? 2 * s->cap : 1024, w = (size_t)s->words;
    uint64_t *bits = PyMem_Realloc(s->bits, cap * w * sizeof(uint64_t) + 8);
    if (bits == NULL) goto oom;
    s->bits = bits;
    uint64_t *hash = PyMem_Realloc(s->hash, cap * sizeof(uint64_t));
    if (hash == NULL) goto oom;
    s->hash = hash;
    uint32_t *parent = PyMem_Realloc(s->parent, cap * sizeof(uint32_t));
    if (parent == NULL) goto oom;
    s->parent = parent;
    int32_t *action = PyMem_Realloc(s->action, cap * sizeof(int32_t));
    if (action == NULL) goto oom;
    s->action = action;
    size_t nslots = 4 * cap;  /* load at most 1/4 */
    uint32_t *slot = PyMem_Calloc(nslots, sizeof(uint32_t));
    if (slot == NULL) goto oom;
    PyMem_Free(s->slot);
    s->slot = slot;
    s->mask = nslots - 1;
    for (size_t i = 0; i < s->n; i++) {
        size_t j = s->hash[i] & s->mask;
        while (slot[j]) j = (j + 1) & s->mask;
        slot[j] = (uint32_t)i + 1;
    }
    s->cap = cap;
    return 0;
oom:
    PyErr_NoMemory();
    return -1;
}

/* The id of the state in bits, added with (parent, action) if new (*added = 1); -1 on error. */
static long long store_add(Store *s, const uint64_t *bits, uint32_t parent, int32_t action, int *added) {
    size_t w = (size_t)s->words;
    uint64_t h = hash_bits(bits, s->words);
    *added = 0;
    if (s->n == s->cap) {
        if (s->n >= UINT32_MAX - 1) { PyErr_SetString(PyExc_MemoryError, "too many states"); return -1; }
        if (store_grow(s) < 0) return -1;
    }
    size_t j = h & s->mask;
    for (uint32_t id; (id = s->slot[j]) != 0; j = (j + 1) & s->mask)
        if (s->hash[id - 1] == h && memcmp(s->bits + (size_t)(id - 1) * w, bits, w * sizeof(uint64_t)) == 0)
            return id - 1;
    size_t i = s->n++;
    memcpy(s->bits + i * w, bits, w * sizeof(uint64_t));
    s->hash[i] = h;
    s->parent[i] = parent;
    s->action[i] = action;
    s->slot[j] = (uint32_t)i + 1;
    *added = 1;
    return (long long)i;
}

static int goal_holds(const Kernel *k, const uint64_t *bits) {
    for (int32_t i = 0; i < k->ngoal; i++)
        if (!BIT(bits, k->goal[i])) return 0;
    return 1;
}

static PyObject *plan_of(const Store *s, uint32_t sid) {
    Py_ssize_t n = 0;
    for (uint32_t i = sid; s->parent[i] != UINT32_MAX; i = s->parent[i]) n++;
    PyObject *out = PyList_New(n);
    if (out == NULL) return NULL;
    for (uint32_t i = sid; s->parent[i] != UINT32_MAX; i = s->parent[i]) {
        PyObject *a = PyLong_FromLong(s->action[i]);
        if (a == NULL) { Py_DECREF(out); return NULL; }
        PyList_SET_ITEM(out, --n, a);
    }
    return out;
}

typedef struct {
    Kernel *k;
    Queue reg, prf;
    uint8_t *prefmark;
    int32_t *succ;
    uint64_t tick;
    long long generated;
} Expander;

/* Every applicable action of the state goes into the regular queue, the preferred ones into both. */
static int expand(Expander *x, uint32_t sid, const uint64_t *bits, const int32_t *sf, int32_t ns, double h,
                  const int32_t *pref, int32_t npref) {
    for (int32_t i = 0; i < npref; i++) x->prefmark[pref[i]] = 1;
    int32_t n = applicable_core(x->k, bits, sf, ns, x->succ);
    int rc = 0;
    for (int32_t i = 0; i < n && rc == 0; i++) {
        int32_t a = x->succ[i];
        QEnt e = {h, x->tick++, sid, a};
        x->generated++;
        rc = qpush(&x->reg, e);
        if (rc == 0 && x->prefmark[a]) rc = qpush(&x->prf, e);
    }
    for (int32_t i = 0; i < npref; i++) x->prefmark[pref[i]] = 0;
    return rc;
}

static PyObject *Kernel_gbfs(Kernel *k, PyObject *args, PyObject *kwds) {
    static char *kwlist[] = {"init", "max_nodes", "out_of_time", "boost", NULL};
    PyObject *init, *out_of_time = Py_None, *plan = NULL, *result = NULL;
    long long max_nodes, boost = 1000;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "OL|OL", kwlist, &init, &max_nodes, &out_of_time, &boost))
        return NULL;
    int32_t ns = load_state(k, init), npref = 0, words = k->words;
    if (ns < 0) return NULL;
    long long evals0 = k->evaluations, expanded = 0;
    int status = ST_EXHAUSTED, added;
    Store st = {.words = words};
    Expander x = {.k = k};
    size_t na1 = (size_t)(k->na ? k->na : 1);
    int32_t *pref = PyMem_Malloc(na1 * sizeof(int32_t)), *sf = PyMem_Malloc(((size_t)k->nf + 1) * sizeof(int32_t));
    uint64_t *cur = PyMem_Calloc((size_t)words + 1, sizeof(uint64_t));
    x.succ = PyMem_Malloc(na1 * sizeof(int32_t));
    x.prefmark = PyMem_Calloc(na1, 1);
    if (!pref || !sf || !cur || !x.succ || !x.prefmark) { PyErr_NoMemory(); goto error; }
    memcpy(cur, k->bits, (size_t)words * sizeof(uint64_t));
    memcpy(sf, k->sf, (size_t)ns * sizeof(int32_t));
    double best = evaluate_core(k, cur, sf, ns, pref, &npref);
    if (isnan(best) && PyErr_Occurred()) goto error;
    if (best == INFINITY) { status = ST_DEAD_INIT; goto done; }
    if (store_add(&st, cur, UINT32_MAX, -1, &added) < 0) goto error;
    if (goal_holds(k, cur)) { status = ST_SOLVED; plan = PyList_New(0); if (!plan) goto error; goto done; }
    if (expand(&x, 0, cur, sf, ns, best, pref, npref) < 0) goto error;
    long long prio_reg = 0, prio_prf = 0;  /* the queue with the lower number is served next */
    while (x.reg.n || x.prf.n) {
        QEnt e;
        if (x.prf.n && (!x.reg.n || prio_prf <= prio_reg)) { e = qpop(&x.prf); prio_prf++; }
        else { e = qpop(&x.reg); prio_reg++; }
        apply_action(k, cur, st.bits + (size_t)e.sid * (size_t)words, e.a);
        long long sid = store_add(&st, cur, e.sid, e.a, &added);
        if (sid < 0) goto error;
        if (!added) continue;
        if (++expanded > max_nodes) { status = ST_NODE_LIMIT; break; }
        if (PyErr_CheckSignals() < 0) goto error;
        int stop = asked_to_stop(out_of_time);
        if (stop < 0) goto error;
        if (stop) { status = ST_TIME_LIMIT; break; }
        if (goal_holds(k, cur)) {
            status = ST_SOLVED;
            if (!(plan = plan_of(&st, (uint32_t)sid))) goto error;
            break;
        }
        ns = facts_of(cur, words, sf);
        double h = evaluate_core(k, cur, sf, ns, pref, &npref);
        if (isnan(h) && PyErr_Occurred()) goto error;
        if (h == INFINITY) continue;
        if (h < best) {
            best = h;
            prio_prf -= boost;
        }
        if (expand(&x, (uint32_t)sid, cur, sf, ns, h, pref, npref) < 0) goto error;
    }
done:
    if (plan == NULL) { plan = Py_None; Py_INCREF(plan); }
    result = Py_BuildValue("(iNLLL)", status, plan, expanded, x.generated, k->evaluations - evals0);
error:
    PyMem_Free(pref);
    PyMem_Free(sf);
    PyMem_Free(cur);
    PyMem_Free(x.succ);
    PyMem_Free(x.prefmark);
    PyMem_Free(x.reg.v);
    PyMem_Free(x.prf.v);
    store_free(&st);
    return result;
}
