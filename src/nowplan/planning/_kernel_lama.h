/* LAMA's first iteration over bitset states: lama.py's lama_search.
 *
 * Included once by _kernel.c after _kernel_gbfs.h (it uses the Kernel, the
 * Store and the Queue).  Four queues of (h, tick, parent state, action):
 * every successor by h_FF, preferred ones by h_FF, every successor by the
 * landmark count, preferred ones by the landmark count; the queue with the
 * lowest priority number is served next (ties: the lower index) and the
 * preferred queues (h_FF's preferred operators) gain BOOST at the initial
 * state and on progress of either heuristic.  Each state
 * keeps the accepted landmarks of the path that first reached it, as a
 * bitset over landmark indices; a landmark (one fact or a disjunction) is
 * accepted once one of its facts holds.
 */

typedef struct {
    int32_t nlm, lwords;
    CSR facts;            /* landmark index -> its facts (one, or a disjunction) */
    CSR of;               /* fact -> the landmarks it is a fact of */
    uint8_t *isgoal;      /* landmark index -> a single goal fact */
    CSR before;           /* landmark index -> the landmark indices it comes before */
    CSR reasonable;       /* landmark index -> its reasonable predecessors (empty rows without them) */
    uint64_t *acc;        /* state id -> accepted bitset (lwords words each) */
    size_t acccap;        /* states with room in acc */
} Landmarks;

static void lm_free(Landmarks *L) {
    free_csr(&L->facts);
    free_csr(&L->of);
    PyMem_Free(L->isgoal);
    free_csr(&L->before);
    free_csr(&L->reasonable);
    PyMem_Free(L->acc);
}

static int lm_build(Kernel *k, PyObject *landmarks, PyObject *before, PyObject *reasonable, Landmarks *L) {
    Py_ssize_t n = PyObject_Length(landmarks);
    if (n < 0) return -1;
    if (n >= INT32_MAX - 64) { PyErr_SetString(PyExc_ValueError, "too many landmarks"); return -1; }
    L->nlm = (int32_t)n;
    L->lwords = (L->nlm + 63) / 64;
    if (build_csr(landmarks, L->nlm, k->nf, "landmark", &L->facts) < 0) return -1;
    if (!(L->isgoal = xcalloc((size_t)L->nlm, 1))) return -1;
    if (!(L->of.off = xcalloc((size_t)k->nf + 1, sizeof(int32_t)))) return -1;
    if (!(L->of.v = xcalloc((size_t)L->facts.off[L->nlm], sizeof(int32_t)))) return -1;
    for (int32_t i = 0; i < L->nlm; i++) {
        int32_t lo = L->facts.off[i], hi = L->facts.off[i + 1];
        if (lo == hi) { PyErr_SetString(PyExc_ValueError, "a landmark without facts"); return -1; }
        L->isgoal[i] = hi - lo == 1 && k->isgoal[L->facts.v[lo]];
        for (int32_t j = lo; j < hi; j++) L->of.off[L->facts.v[j] + 1]++;
    }
    for (int32_t f = 0; f < k->nf; f++) L->of.off[f + 1] += L->of.off[f];
    int32_t *fill = xcalloc((size_t)k->nf, sizeof(int32_t));
    if (fill == NULL) return -1;
    for (int32_t i = 0; i < L->nlm; i++)
        for (int32_t j = L->facts.off[i]; j < L->facts.off[i + 1]; j++) {
            int32_t f = L->facts.v[j];
            L->of.v[L->of.off[f] + fill[f]++] = i;
        }
    PyMem_Free(fill);
    if (build_csr(before, L->nlm, L->nlm > 0 ? L->nlm : 1, "before", &L->before) < 0) return -1;
    if (reasonable == Py_None) {  /* none: an empty row per landmark */
        if (!(L->reasonable.off = xcalloc((size_t)L->nlm + 1, sizeof(int32_t))) ||
            !(L->reasonable.v = xcalloc(1, sizeof(int32_t))))
            return -1;
        return 0;
    }
    return build_csr(reasonable, L->nlm, L->nlm > 0 ? L->nlm : 1, "reasonable", &L->reasonable);
}

/* Room for the accepted set of state sid; its words (zeroed when new). */
static uint64_t *lm_acc(Landmarks *L, size_t sid) {
    size_t w = (size_t)(L->lwords ? L->lwords : 1);
    if (sid >= L->acccap) {
        size_t cap = L->acccap ? 2 * L->acccap : 1024;
        while (cap <= sid) cap *= 2;
        uint64_t *acc = PyMem_Realloc(L->acc, cap * w * sizeof(uint64_t));
        if (acc == NULL) { PyErr_NoMemory(); return NULL; }
        memset(acc + L->acccap * w, 0, (cap - L->acccap) * w * sizeof(uint64_t));
        L->acc = acc;
        L->acccap = cap;
    }
    return L->acc + sid * w;
}

/* acc := parent's accepted set plus the landmarks with a fact true now (facts sf[0..ns); parent NULL: none). */
static void lm_accept(const Landmarks *L, const uint64_t *parent, const int32_t *sf, int32_t ns, uint64_t *acc) {
    if (parent != NULL) memcpy(acc, parent, (size_t)L->lwords * sizeof(uint64_t));
    for (int32_t i = 0; i < ns; i++)
        for (int32_t j = L->of.off[sf[i]]; j < L->of.off[sf[i] + 1]; j++) SETBIT(acc, L->of.v[j]);
}

static inline int lm_holds(const Landmarks *L, int32_t i, const uint64_t *bits) {
    for (int32_t j = L->facts.off[i]; j < L->facts.off[i + 1]; j++)
        if (BIT(bits, L->facts.v[j])) return 1;
    return 0;
}

/* The landmark count: landmarks not accepted, plus accepted ones false now that are a goal or
 * come before a landmark not accepted; 1 (not 0) when the goal does not hold. */
static double lm_count(const Kernel *k, const Landmarks *L, const uint64_t *acc, const uint64_t *bits) {
    int32_t todo = 0, again = 0;
    for (int32_t i = 0; i < L->nlm; i++) {
        if (!BIT(acc, i)) { todo++; continue; }
        int early = 0;  /* reached before a reasonable predecessor: to be reached again */
        for (int32_t j = L->reasonable.off[i]; j < L->reasonable.off[i + 1] && !early; j++)
            early = !BIT(acc, L->reasonable.v[j]);
        if (early) { again++; continue; }
        if (lm_holds(L, i, bits)) continue;
        if (L->isgoal[i]) { again++; continue; }
        for (int32_t j = L->before.off[i]; j < L->before.off[i + 1]; j++)
            if (!BIT(acc, L->before.v[j])) { again++; break; }
    }
    int32_t h = todo + again;
    if (h == 0 && !goal_holds(k, bits)) h = 1;
    return (double)h;
}

typedef struct {
    Kernel *k;
    Queue q[4];  /* ff, ff preferred, lm, lm preferred */
    uint8_t *prefmark;
    int32_t *succ;
    uint64_t tick;
    long long generated;
} LamaExpander;

static int lama_expand(LamaExpander *x, uint32_t sid, const uint64_t *bits, const int32_t *sf, int32_t ns,
                       double hf, double hl, const int32_t *pref, int32_t npref) {
    for (int32_t i = 0; i < npref; i++) x->prefmark[pref[i]] = 1;
    int32_t n = applicable_core(x->k, bits, sf, ns, x->succ);
    int rc = 0;
    for (int32_t i = 0; i < n && rc == 0; i++) {
        int32_t a = x->succ[i];
        QEnt ef = {hf, x->tick, sid, a}, el = {hl, x->tick, sid, a};
        x->tick++;
        x->generated++;
        rc = qpush(&x->q[0], ef);
        if (rc == 0) rc = qpush(&x->q[2], el);
        if (rc == 0 && x->prefmark[a]) {
            rc = qpush(&x->q[1], ef);
            if (rc == 0) rc = qpush(&x->q[3], el);
        }
    }
    for (int32_t i = 0; i < npref; i++) x->prefmark[pref[i]] = 0;
    return rc;
}

static PyObject *Kernel_lama(Kernel *k, PyObject *args, PyObject *kwds) {
    static char *kwlist[] = {"init", "max_nodes", "landmarks", "before", "out_of_time", "boost", "unreachable",
                             "reasonable", NULL};
    PyObject *init, *landmarks, *before, *out_of_time = Py_None, *plan = NULL, *result = NULL;
    PyObject *reasonable = Py_None;
    long long max_nodes, boost = 1000;
    int unreachable = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "OLOO|OLpO", kwlist, &init, &max_nodes, &landmarks, &before,
                                     &out_of_time, &boost, &unreachable, &reasonable))
        return NULL;
    Landmarks L = {0};
    Store st = {.words = k->words};
    LamaExpander x = {.k = k};
    int32_t *pref = NULL, *sf = NULL;
    uint64_t *cur = NULL, *acc;
    long long evals0 = k->evaluations, expanded = 0;
    int status = ST_EXHAUSTED, added;
    if (lm_build(k, landmarks, before, reasonable, &L) < 0) goto error;
    int32_t ns = load_state(k, init), npref = 0, words = k->words;
    if (ns < 0) goto error;
    size_t na1 = (size_t)(k->na ? k->na : 1);
    pref = PyMem_Malloc(na1 * sizeof(int32_t));
    sf = PyMem_Malloc(((size_t)k->nf + 1) * sizeof(int32_t));
    cur = PyMem_Calloc((size_t)words + 1, sizeof(uint64_t));
    x.succ = PyMem_Malloc(na1 * sizeof(int32_t));
    x.prefmark = PyMem_Calloc(na1, 1);
    if (!pref || !sf || !cur || !x.succ || !x.prefmark) { PyErr_NoMemory(); goto error; }
    memcpy(cur, k->bits, (size_t)words * sizeof(uint64_t));
    memcpy(sf, k->sf, (size_t)ns * sizeof(int32_t));
    double best_f = evaluate_core(k, cur, sf, ns, pref, &npref);
    if (isnan(best_f) && PyErr_Occurred()) goto error;
    if (best_f == INFINITY || unreachable) { status = ST_DEAD_INIT; goto done; }
    if (store_add(&st, cur, UINT32_MAX, -1, &added) < 0) goto error;
    if (!(acc = lm_acc(&L, 0))) goto error;
    lm_accept(&L, NULL, sf, ns, acc);
    if (goal_holds(k, cur)) { status = ST_SOLVED; plan = PyList_New(0); if (!plan) goto error; goto done; }
    double best_l = lm_count(k, &L, acc, cur);
    if (lama_expand(&x, 0, cur, sf, ns, best_f, best_l, pref, npref) < 0) goto error;
    long long prio[4] = {0, -boost, 0, -boost};  /* the non-empty queue with the lowest number is served
                                                  * next; the initial state is progress */
    for (;;) {
        int q = -1;
        for (int i = 0; i < 4; i++)
            if (x.q[i].n && (q < 0 || prio[i] < prio[q])) q = i;
        if (q < 0) break;
        prio[q]++;
        QEnt e = qpop(&x.q[q]);
        apply_action(k, cur, st.bits + (size_t)e.sid * (size_t)words, e.a);
        long long sid = store_add(&st, cur, e.sid, e.a, &added);
        if (sid < 0) goto error;
        if (!added) continue;
        if (!(acc = lm_acc(&L, (size_t)sid))) goto error;
        ns = facts_of(cur, words, sf);
        lm_accept(&L, L.acc + (size_t)e.sid * (size_t)(L.lwords ? L.lwords : 1), sf, ns, acc);
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
        double hf = evaluate_core(k, cur, sf, ns, pref, &npref);
        if (isnan(hf) && PyErr_Occurred()) goto error;
        if (hf == INFINITY) continue;
        double hl = lm_count(k, &L, acc, cur);
        int progress = 0;
        if (hf < best_f) { best_f = hf; progress = 1; }
        if (hl < best_l) { best_l = hl; progress = 1; }
        if (progress) { prio[1] -= boost; prio[3] -= boost; }
        if (lama_expand(&x, (uint32_t)sid, cur, sf, ns, hf, hl, pref, npref) < 0) goto error;
    }
done:
    if (plan == NULL) { plan = Py_None; Py_INCREF(plan); }
    result = Py_BuildValue("(iNLLL)", status, plan, expanded, x.generated, k->evaluations - evals0);
error:
    lm_free(&L);
    PyMem_Free(pref);
    PyMem_Free(sf);
    PyMem_Free(cur);
    PyMem_Free(x.succ);
    PyMem_Free(x.prefmark);
    for (int i = 0; i < 4; i++) PyMem_Free(x.q[i].v);
    store_free(&st);
    return result;
}
