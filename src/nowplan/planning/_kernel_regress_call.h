/* One call of the regression loop (_kernel_regress.c): its scratch arrays, and what it asks of Python once per
 * fact (holds, need) or pair of facts (conflict). */
/* ------------------------------------------------------------------ one call */

typedef struct {
    Regressor *R;
    PyObject *holds_fn, *need_fn, *conflict_fn, *cost_fn;  /* cost_fn: None where the costs are the store's */
    double *hv;
    Py_ssize_t nv;
    uint32_t epoch, mk;  /* the expansion's and the successor's stamps */
    int local;           /* achievers asked per call (set_local_achievers), not the persistent ones */
    /* h2 pairs (planning/h2.py), NULL where off: per fact id below h2n its bit or -1; per bit a row of h2w
     * words (the bits reachable with it); the reachable bits */
    const int32_t *h2bit;
    const uint64_t *h2reach, *h2facts;
    Py_ssize_t h2n, h2w;
} Call;

/* does the child (cn facts) hold, with one of the new facts, a pair no reachable state holds (or a new fact
 * no state reaches)?  PairReach.excluded's check, over the facts that are new to the child */
static int h2_excluded(const Call *C, const int32_t *newf, size_t nn, const int32_t *child, int32_t cn) {
    for (size_t i = 0; i < nn; i++) {
        int32_t nf = newf[i];
        if (nf >= C->h2n) continue;
        int32_t bn = C->h2bit[nf];
        if (bn < 0) continue;
        if (!((C->h2facts[bn >> 6] >> (bn & 63)) & 1)) return 1;
        const uint64_t *row = C->h2reach + (size_t)bn * (size_t)C->h2w;
        for (int32_t j = 0; j < cn; j++) {
            int32_t x = child[j];
            if (x >= C->h2n) continue;
            int32_t bx = C->h2bit[x];
            if (bx >= 0 && !((row[bx >> 6] >> (bx & 63)) & 1)) return 1;
        }
    }
    return 0;
}

/* grow every array of a group (pointers and item sizes) from *cap to one capacity for n items */
static int grow_group(void **const *ptrs, const size_t *sizes, size_t count, size_t *cap, size_t n) {
    size_t c = *cap;
    for (size_t i = 0; i < count; i++) {
        c = *cap;  /* (each from the old capacity: they all end at the same one) */
        if (grow(ptrs[i], &c, n, sizes[i]) < 0) return -1;
    }
    *cap = c;
    return 0;
}

/* the scratch arrays sized for the facts, fluents, keys and actions known now */
static int fit(Regressor *R) {
    size_t old = R->caph;
    void **const by_fact[] = {(void **)&R->holds, (void **)&R->remmark, (void **)&R->chmark, (void **)&R->pos,
                              (void **)&R->pcmark, (void **)&R->pcstart, (void **)&R->pclen, (void **)&R->asked,
                              (void **)&R->lstart, (void **)&R->llen};
    const size_t W = sizeof(int32_t);  /* (uint32_t marks and int32_t ids alike) */
    const size_t fact_sizes[] = {1, W, W, W, W, W, W, 1, W, W};
    if (grow_group(by_fact, fact_sizes, 10, &R->caph, (size_t)R->nf + 1) < 0) return -1;
    for (size_t i = old; i < R->caph; i++) {  /* the new entries: unknown truth, in no order */
        R->holds[i] = -1;
        R->pos[i] = R->never;
    }
    void **const by_fluent[] = {(void **)&R->flmark, (void **)&R->newmark, (void **)&R->guardmark,
                                (void **)&R->flfact, (void **)&R->newfact, (void **)&R->guardfact};
    const size_t fluent_sizes[] = {W, W, W, W, W, W};
    if (grow_group(by_fluent, fluent_sizes, 6, &R->capfl, (size_t)R->nfl + 1) < 0) return -1;
    void **const by_key[] = {(void **)&R->kmark, (void **)&R->lkmark, (void **)&R->kfact, (void **)&R->lkfact};
    const size_t key_sizes[] = {W, W, W, W};
    if (grow_group(by_key, key_sizes, 4, &R->capk, (size_t)R->nkey + 1) < 0) return -1;
    void **const by_action[] = {(void **)&R->tried, (void **)&R->ccost, (void **)&R->cknown};
    const size_t action_sizes[] = {W, sizeof(double), 1};
    return grow_group(by_action, action_sizes, 3, &R->capt, (size_t)R->na + 1);
}

/* 1 if fact f holds, 0 if not, -1 with an error set */
static int holds(Call *C, int32_t f) {
    int8_t h = C->R->holds[f];
    if (h >= 0) return h;
    PyObject *r = PyObject_CallFunction(C->holds_fn, "i", (int)f);
    if (r == NULL) return -1;
    int t = PyObject_IsTrue(r);
    Py_DECREF(r);
    if (t < 0) return -1;
    C->R->holds[f] = (int8_t)t;
    return t;
}

/* action a's cost in this call: the store's, or asked of Python once (costs that read the belief) */
static int action_cost(Call *C, int32_t a, double *out) {
    Regressor *R = C->R;
    if (C->cost_fn == Py_None) { *out = R->cost[a]; return 0; }
    if (!R->cknown[a]) {
        PyObject *r = PyObject_CallFunction(C->cost_fn, "i", (int)a);
        if (r == NULL) return -1;
        double v = PyFloat_AsDouble(r);
        Py_DECREF(r);
        if (v == -1.0 && PyErr_Occurred()) return -1;
        R->ccost[a] = v;
        R->cknown[a] = 1;
    }
    *out = R->ccost[a];
    return 0;
}

/* do the plain conflict rules exclude facts x and y together?  1, 0, -1 with an error set */
static int plain_conflict(Call *C, int32_t x, int32_t y) {
    Regressor *R = C->R;
    uint64_t key = x < y ? ((uint64_t)(uint32_t)x << 32) | (uint32_t)y : ((uint64_t)(uint32_t)y << 32) | (uint32_t)x;
    if (R->cappairs) {
        size_t mask = R->cappairs - 1, i = (size_t)((key * 0x9E3779B97F4A7C15ULL) >> 17) & mask;
        for (; R->pairs[i].val; i = (i + 1) & mask)
            if (R->pairs[i].key == key) return R->pairs[i].val == 2;
    }
    PyObject *r = PyObject_CallFunction(C->conflict_fn, "ii", (int)x, (int)y);
    if (r == NULL) return -1;
    int t = PyObject_IsTrue(r);
    Py_DECREF(r);
    if (t < 0) return -1;
    if ((R->npairs + 1) * 2 > R->cappairs) {  /* grow and rehash */
        size_t cap = R->cappairs ? 2 * R->cappairs : 4096;
        PairEnt *v = PyMem_Calloc(cap, sizeof(PairEnt));
        if (v == NULL) { PyErr_NoMemory(); return -1; }
        for (size_t k = 0; k < R->cappairs; k++) {
            if (!R->pairs[k].val) continue;
            size_t i = (size_t)((R->pairs[k].key * 0x9E3779B97F4A7C15ULL) >> 17) & (cap - 1);
            while (v[i].val) i = (i + 1) & (cap - 1);
            v[i] = R->pairs[k];
        }
        PyMem_Free(R->pairs);
        R->pairs = v;
        R->cappairs = cap;
    }
    size_t mask = R->cappairs - 1, i = (size_t)((key * 0x9E3779B97F4A7C15ULL) >> 17) & mask;
    while (R->pairs[i].val) i = (i + 1) & mask;
    R->pairs[i].key = key;
    R->pairs[i].val = (uint8_t)(t ? 2 : 1);
    R->npairs++;
    return t;
}

/* does fact e plainly conflict with a fact of the node (cur, n facts) not removed in this successor? */
static int plain_clash(Call *C, int32_t e, const int32_t *cur, int32_t n, uint32_t mk) {
    Regressor *R = C->R;
    if (R->pcmark[e] != C->epoch) {  /* the node's facts e conflicts with, once per expansion */
        R->pcstart[e] = (int32_t)R->pcl.n;
        for (int32_t i = 0; i < n; i++) {
            int t = plain_conflict(C, e, cur[i]);
            if (t < 0) return -1;
            if (t && vpush(&R->pcl, cur[i]) < 0) return -1;
        }
        R->pclen[e] = (int32_t)R->pcl.n - R->pcstart[e];
        R->pcmark[e] = C->epoch;
    }
    for (int32_t i = 0; i < R->pclen[e]; i++)
        if (R->remmark[R->pcl.v[R->pcstart[e] + i]] != mk) return 1;
    return 0;
}

/* the estimate of fact f: its relaxed cost (0 where it holds), inf beyond the values */
static int hval(Call *C, int32_t f, double *out) {
    if (f < C->nv) { *out = C->hv[f]; return 0; }
    int t = holds(C, f);
    if (t < 0) return -1;
    *out = t ? 0.0 : INFINITY;
    return 0;
}

/* the achievers of f known (asked of Python once): 1, 0 where the call must run in Python, -1 error */
static int known(Call *C, int32_t f) {
    Regressor *R = C->R;
    if (C->local ? R->asked[f] : R->ach_len[f] >= 0) return 1;
    PyObject *r = PyObject_CallFunction(C->need_fn, "i", (int)f);
    if (r == NULL) return -1;
    int t = PyObject_IsTrue(r);
    Py_DECREF(r);
    if (t <= 0) return t;
    if (fit(R) < 0) return -1;
    if (C->local ? !R->asked[f] : R->ach_len[f] < 0) {
        PyErr_SetString(PyExc_RuntimeError, "need() did not set the achievers");
        return -1;
    }
    return 1;
}

/* set_local_achievers(fact, actions): the fact's templates for the running call only */
static PyObject *Regressor_set_local_achievers(Regressor *R, PyObject *args) {
    int f;
    PyObject *acts;
    if (!PyArg_ParseTuple(args, "iO", &f, &acts)) return NULL;
    if (!R->in_call) { PyErr_SetString(PyExc_RuntimeError, "set_local_achievers outside a search"); return NULL; }
    if (fit(R) < 0) return NULL;
    if (f < 0 || f >= R->nf || (size_t)f >= R->caph) { PyErr_SetString(PyExc_IndexError, "fact id not added"); return NULL; }
    int64_t a0 = read_achievers(R, acts, &R->lach);
    if (a0 < 0) return NULL;
    R->lstart[f] = (int32_t)a0;
    R->llen[f] = (int32_t)((int64_t)R->lach.n - a0);
    R->asked[f] = 1;
    Py_RETURN_NONE;
}

static inline int stamp_less(int32_t a0, int32_t a1, int32_t a2, int32_t b0, int32_t b1, int32_t b2) {
    return a0 != b0 ? a0 < b0 : a1 != b1 ? a1 < b1 : a2 < b2;
}

static void sort_by(int32_t *v, int32_t n, const int32_t *key) {
    for (int32_t i = 1; i < n; i++) {
        int32_t x = v[i], kx = key ? key[x] : x, j = i - 1;
        while (j >= 0 && (key ? key[v[j]] : v[j]) > kx) { v[j + 1] = v[j]; j--; }
        v[j + 1] = x;
    }
}

static int cmp_int(const void *a, const void *b) {
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

static PyObject *int_list(const int32_t *v, int32_t n) {
    PyObject *l = PyList_New(n);
    if (l == NULL) return NULL;
    for (int32_t i = 0; i < n; i++) {
        PyObject *x = PyLong_FromLong(v[i]);
        if (x == NULL) { Py_DECREF(l); return NULL; }
        PyList_SET_ITEM(l, i, x);
    }
    return l;
}

/* search(root, hvals, holds, need, stop, weight, max_nodes, no_rewrites, order, protect, local, conflict, cost)
 *   -> (status, [facts of the path's nodes, the solved one first], [actions], expanded, generated)
 * order: None or the serialization's fact ids; protect: the monotonic call's fact ids; local: the
 * call's achievers are asked per fact in the call (need sets them with set_local_achievers); conflict:
 * conflict(x, y) -> bool, the plain conflict rules (None where there are none); cost: cost(a) -> float,
 * an action's cost in this call where costs read the belief (None: the costs add_action stored) */
