/* The regression loop's store (_kernel_regress.c): the Regressor's facts, actions and achievers, kept across
 * calls, and the methods that register them (add_fact, set_rank, add_action, set_achievers). */
typedef struct { int32_t *v; size_t n, cap; } Vec;

static int vpush(Vec *a, int32_t x) {
    if (a->n == a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 256;
        int32_t *v = PyMem_Realloc(a->v, cap * sizeof(int32_t));
        if (v == NULL) { PyErr_NoMemory(); return -1; }
        a->v = v;
        a->cap = cap;
    }
    a->v[a->n++] = x;
    return 0;
}

/* grow an array of `size`-byte items from *cap to at least n items, zero-filled */
static int grow(void **p, size_t *cap, size_t n, size_t size) {
    if (n <= *cap) return 0;
    size_t c = *cap ? *cap : 64;
    while (c < n) c *= 2;
    char *q = PyMem_Realloc(*p, c * size);
    if (q == NULL) { PyErr_NoMemory(); return -1; }
    memset(q + *cap * size, 0, (c - *cap) * size);
    *p = q;
    *cap = c;
    return 0;
}

typedef struct { uint64_t key; uint8_t val; } PairEnt;  /* val 0 empty, 1 no conflict, 2 conflict */

typedef struct {
    PyObject_HEAD
    int has_conflicts, has_plain;
    PairEnt *pairs;       /* plain conflict answers by (min, max) fact pair, open addressing */
    size_t npairs, cappairs;
    /* facts: fluent, sort rank, conflict keys (kstart/klen into keys) */
    int32_t nf;
    size_t capf;
    int32_t *fluent, *rank, *kstart, *klen, *ach_start, *ach_len;  /* ach_len -1: not asked yet */
    Vec keys, ach;
    int32_t nfl, nkey;  /* fluent and key ids below these */
    /* actions: effects as (fluent, fact) pairs, effect keys as (key, fact) pairs, kept preconditions */
    int32_t na;
    size_t capa;
    int32_t *es, *el, *ks, *kl, *ps, *pl, *as, *al;  /* as/al: every effect (all_effs), for protect */
    uint8_t *clash;
    double *cost;
    Vec effs, ekeys, pres, alls;
    int32_t *src;         /* by action: its index in the ground task (use_task), -1 for one added by add_action */
    /* the ground task (_kernel_regress_task.h): per task action its effects and kept preconditions (start,
     * length into teff/tpre), its cost and its action here (-1: not registered yet); per fact below ntf the
     * task actions that add it (tadd_start, ntf + 1 entries, into tadd) */
    int32_t ntask, ntf;
    int32_t *tes, *tel, *tps, *tpl, *tact, *tadd_start;
    double *tcost;
    Vec teff, tpre, tadd;
    /* one call's scratch, by fact / fluent / key / action (stamps tell which entries are current) */
    size_t caph, capfl, capk, capt;
    int8_t *holds;        /* -1 unknown, 0, 1 */
    int32_t *pos, never;  /* a fact's first position in the call's order, `never` when not in it */
    uint8_t *asked;       /* by fact: its call-local achievers are set (lstart/llen into lach) */
    double *ccost;        /* by action: its cost in this call, where costs read the belief (cknown) */
    uint32_t *pcmark;     /* by fact: its plain conflicts with the expanded node are listed (== the stamp) */
    int32_t *pcstart, *pclen;
    Vec pcl;              /* those lists, one expansion's */
    uint8_t *cknown;
    int32_t *lstart, *llen;
    Vec lach;
    int in_call;
    uint32_t *guardmark;  /* by fluent: 1 where the call protects a fact of it (guardfact) */
    int32_t *guardfact;
    uint32_t *flmark, *newmark, *kmark, *lkmark, *remmark, *chmark, *tried;
    int32_t *flfact, *newfact, *kfact, *lkfact;
} Regressor;


/* ------------------------------------------------------------------ building */

static void Regressor_dealloc(Regressor *R) {
    void *ps[] = {R->fluent, R->rank, R->kstart, R->klen, R->ach_start, R->ach_len, R->keys.v, R->ach.v,
                  R->es, R->el, R->ks, R->kl, R->ps, R->pl, R->clash, R->cost, R->effs.v, R->ekeys.v, R->pres.v,
                  R->holds, R->flmark, R->newmark, R->kmark, R->lkmark, R->remmark, R->chmark, R->tried,
                  R->flfact, R->newfact, R->kfact, R->lkfact, R->as, R->al, R->alls.v, R->pos, R->guardmark,
                  R->guardfact, R->asked, R->lstart, R->llen, R->lach.v, R->pairs, R->ccost, R->cknown, R->pcmark,
                  R->pcstart, R->pclen, R->pcl.v, R->src, R->tes, R->tel, R->tps, R->tpl, R->tact, R->tadd_start,
                  R->tcost, R->teff.v, R->tpre.v, R->tadd.v};
    for (size_t i = 0; i < sizeof(ps) / sizeof(ps[0]); i++) PyMem_Free(ps[i]);
    Py_TYPE(R)->tp_free((PyObject *)R);
}

static PyObject *Regressor_new(PyTypeObject *type, PyObject *args, PyObject *kwds) {
    static char *kw[] = {"has_conflicts", "has_plain", NULL};
    int conflicts = 0, plain = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "p|p", kw, &conflicts, &plain)) return NULL;
    Regressor *R = (Regressor *)type->tp_alloc(type, 0);
    if (R == NULL) return NULL;
    R->has_conflicts = conflicts || plain;
    R->has_plain = plain;
    return (PyObject *)R;
}

static int read_ints(PyObject *seq, const char *what, Vec *out) {
    PyObject *fast = PySequence_Fast(seq, what);
    if (fast == NULL) return -1;
    Py_ssize_t m = PySequence_Fast_GET_SIZE(fast);
    for (Py_ssize_t j = 0; j < m; j++) {
        long v = PyLong_AsLong(PySequence_Fast_GET_ITEM(fast, j));
        if ((v == -1 && PyErr_Occurred()) || vpush(out, (int32_t)v) < 0) { Py_DECREF(fast); return -1; }
        if (v < 0 || v > INT32_MAX) {
            PyErr_Format(PyExc_ValueError, "%s: id %ld out of range", what, v);
            Py_DECREF(fast);
            return -1;
        }
    }
    Py_DECREF(fast);
    return 0;
}

/* add_fact(fluent, keys): the next fact id's fluent and conflict key ids */
static PyObject *Regressor_add_fact(Regressor *R, PyObject *args) {
    int fl;
    PyObject *keys;
    if (!PyArg_ParseTuple(args, "iO", &fl, &keys)) return NULL;
    if (fl < 0) { PyErr_SetString(PyExc_ValueError, "negative fluent id"); return NULL; }
    size_t n = (size_t)R->nf + 1, c = R->capf;
    if (n > c) {
        size_t c0 = c;
        if (grow((void **)&R->fluent, &c0, n, sizeof(int32_t)) < 0) return NULL;
        int32_t **arr[] = {&R->rank, &R->kstart, &R->klen, &R->ach_start, &R->ach_len};
        for (size_t i = 0; i < 5; i++) {
            size_t ci = c;
            if (grow((void **)arr[i], &ci, n, sizeof(int32_t)) < 0) return NULL;
        }
        R->capf = c0;
    }
    int32_t f = R->nf;
    size_t k0 = R->keys.n;
    if (read_ints(keys, "keys", &R->keys) < 0) { R->keys.n = k0; return NULL; }
    for (size_t i = k0; i < R->keys.n; i++)
        if (R->keys.v[i] + 1 > R->nkey) R->nkey = R->keys.v[i] + 1;
    R->fluent[f] = fl;
    R->kstart[f] = (int32_t)k0;
    R->klen[f] = (int32_t)(R->keys.n - k0);
    R->ach_len[f] = -1;
    R->rank[f] = f;
    if (fl + 1 > R->nfl) R->nfl = fl + 1;
    R->nf++;
    Py_RETURN_NONE;
}

/* set_rank(rank, start=0): the sort positions of facts start.. (as FactTable.sorted orders their atoms;
 * only their order matters, so the caller may leave gaps and rank new facts without moving the others) */
static PyObject *Regressor_set_rank(Regressor *R, PyObject *args) {
    PyObject *rank;
    int start = 0;
    if (!PyArg_ParseTuple(args, "O|i", &rank, &start)) return NULL;
    PyObject *fast = PySequence_Fast(rank, "rank");
    if (fast == NULL) return NULL;
    if (start < 0 || start + PySequence_Fast_GET_SIZE(fast) != R->nf) {
        Py_DECREF(fast);
        PyErr_SetString(PyExc_ValueError, "rank: one entry per fact from start");
        return NULL;
    }
    for (int32_t f = start; f < R->nf; f++) {
        long v = PyLong_AsLong(PySequence_Fast_GET_ITEM(fast, f - start));
        if (v == -1 && PyErr_Occurred()) { Py_DECREF(fast); return NULL; }
        if (v < INT32_MIN || v > INT32_MAX) {
            Py_DECREF(fast);
            PyErr_SetString(PyExc_ValueError, "rank: out of the int32 range");
            return NULL;
        }
        R->rank[f] = (int32_t)v;
    }
    Py_DECREF(fast);
    Py_RETURN_NONE;
}

static int check_facts(Regressor *R, Vec *v, size_t from, int step) {
    for (size_t i = from + (step == 2); i < v->n; i += (size_t)step)
        if (v->v[i] >= R->nf) { PyErr_SetString(PyExc_ValueError, "fact id not added"); return -1; }
    return 0;
}

/* room for one more action */
static int reserve_action(Regressor *R) {
    size_t n = (size_t)R->na + 1;
    if (n <= R->capa) return 0;
    int32_t **arr[] = {&R->es, &R->el, &R->ks, &R->kl, &R->ps, &R->pl, &R->as, &R->al, &R->src};
    for (size_t i = 0; i < 9; i++) {
        size_t c = R->capa;
        if (grow((void **)arr[i], &c, n, sizeof(int32_t)) < 0) return -1;
    }
    size_t c = R->capa;
    if (grow((void **)&R->clash, &c, n, sizeof(uint8_t)) < 0) return -1;
    c = R->capa;
    if (grow((void **)&R->cost, &c, n, sizeof(double)) < 0) return -1;
    R->capa = c;
    return 0;
}

/* add_action(effects, effect_keys, self_clash, pre, cost, all_effects) -> index; effects and effect_keys
 * flat pairs (fluent, fact) and (key, fact); all_effects every effect's fact (ActionFacts.all_effs) */
static PyObject *Regressor_add_action(Regressor *R, PyObject *args) {
    PyObject *effs, *ekeys, *pre, *alls;
    int clash;
    double cost;
    if (!PyArg_ParseTuple(args, "OOpOdO", &effs, &ekeys, &clash, &pre, &cost, &alls)) return NULL;
    if (reserve_action(R) < 0) return NULL;
    int32_t a = R->na;
    size_t e0 = R->effs.n, k0 = R->ekeys.n, p0 = R->pres.n, x0 = R->alls.n;
    if (read_ints(effs, "effects", &R->effs) < 0 || read_ints(ekeys, "effect keys", &R->ekeys) < 0 ||
        read_ints(pre, "pre", &R->pres) < 0 || read_ints(alls, "all effects", &R->alls) < 0 ||
        (R->effs.n - e0) % 2 || (R->ekeys.n - k0) % 2 ||
        check_facts(R, &R->effs, e0, 2) < 0 || check_facts(R, &R->ekeys, k0, 2) < 0 ||
        check_facts(R, &R->pres, p0, 1) < 0 || check_facts(R, &R->alls, x0, 1) < 0) {
        if (!PyErr_Occurred()) PyErr_SetString(PyExc_ValueError, "effects and keys are flat pairs");
        R->effs.n = e0; R->ekeys.n = k0; R->pres.n = p0; R->alls.n = x0;
        return NULL;
    }
    for (size_t i = e0; i < R->effs.n; i += 2)
        if (R->effs.v[i] + 1 > R->nfl) R->nfl = R->effs.v[i] + 1;
    for (size_t i = k0; i < R->ekeys.n; i += 2)
        if (R->ekeys.v[i] + 1 > R->nkey) R->nkey = R->ekeys.v[i] + 1;
    R->es[a] = (int32_t)e0; R->el[a] = (int32_t)((R->effs.n - e0) / 2);
    R->ks[a] = (int32_t)k0; R->kl[a] = (int32_t)((R->ekeys.n - k0) / 2);
    R->ps[a] = (int32_t)p0; R->pl[a] = (int32_t)(R->pres.n - p0);
    R->as[a] = (int32_t)x0; R->al[a] = (int32_t)(R->alls.n - x0);
    R->clash[a] = (uint8_t)clash;
    R->cost[a] = cost;
    R->src[a] = -1;
    R->na++;
    return PyLong_FromLong(a);
}

/* append the action ids of `acts` to `into` (each below na): their start, or -1 with an error set */
static int64_t read_achievers(Regressor *R, PyObject *acts, Vec *into) {
    size_t a0 = into->n;
    if (read_ints(acts, "achievers", into) < 0) { into->n = a0; return -1; }
    for (size_t i = a0; i < into->n; i++)
        if (into->v[i] >= R->na) {
            into->n = a0;
            PyErr_SetString(PyExc_IndexError, "action id not added");
            return -1;
        }
    return (int64_t)a0;
}

/* set_achievers(fact, actions): the fact's successor templates in the search's order */
static PyObject *Regressor_set_achievers(Regressor *R, PyObject *args) {
    int f;
    PyObject *acts;
    if (!PyArg_ParseTuple(args, "iO", &f, &acts)) return NULL;
    if (f < 0 || f >= R->nf) { PyErr_SetString(PyExc_IndexError, "fact id not added"); return NULL; }
    int64_t a0 = read_achievers(R, acts, &R->ach);
    if (a0 < 0) return NULL;
    R->ach_start[f] = (int32_t)a0;
    R->ach_len[f] = (int32_t)((int64_t)R->ach.n - a0);
    Py_RETURN_NONE;
}

