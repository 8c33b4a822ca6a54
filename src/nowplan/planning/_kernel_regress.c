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

#define REGRESS_API 4
enum { RS_SOLVED, RS_EXHAUSTED, RS_NODE_LIMIT, RS_TIME_LIMIT, RS_UNSUPPORTED };

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
    /* one call's scratch, by fact / fluent / key / action (stamps tell which entries are current) */
    size_t caph, capfl, capk, capt;
    int8_t *holds;        /* -1 unknown, 0, 1 */
    int32_t *pos, never;  /* a fact's first position in the call's order, `never` when not in it */
    uint8_t *asked;       /* by fact: its call-local achievers are set (lstart/llen into lach) */
    int32_t *lstart, *llen;
    Vec lach;
    int in_call;
    uint32_t *guardmark;  /* by fluent: 1 where the call protects a fact of it (guardfact) */
    int32_t *guardfact;
    uint32_t *flmark, *newmark, *kmark, *lkmark, *remmark, *chmark, *tried;
    int32_t *flfact, *newfact, *kfact, *lkfact;
} Regressor;

/* ------------------------------------------------------------------ nodes and the frontier */

typedef struct {
    double f, h;
    int32_t r, idle, s0, s1, s2, node;
    uint64_t seq;
} REnt;

static inline int rless(const REnt *a, const REnt *b) {
    if (a->f != b->f) return a->f < b->f;
    if (a->h != b->h) return a->h < b->h;
    if (a->r != b->r) return a->r < b->r;
    if (a->idle != b->idle) return a->idle < b->idle;
    if (a->s0 != b->s0) return a->s0 < b->s0;
    if (a->s1 != b->s1) return a->s1 < b->s1;
    if (a->s2 != b->s2) return a->s2 < b->s2;
    return a->seq < b->seq;
}

NP_HEAP(RQueue, REnt, rless, rq_push, rq_pop)

typedef struct {
    double g, h;
    int32_t start, len, focus, parent, act, r;
    int32_t b0, b1, b2;            /* born: the stamp of the path kept */
    int32_t t_r, t_idle, t0, t1, t2;  /* tails: the least (r, idle, stamp) of its paths of cost g */
    uint64_t hash;
    uint8_t closed, has_tail;
} RNode;

typedef struct {
    RNode *v;
    size_t n, cap;
    Vec facts;
    int32_t *table;  /* open addressing: node index + 1, 0 empty */
    size_t tcap;
} Nodes;

static uint64_t hash_facts(const int32_t *f, int32_t n, int32_t focus) {
    uint64_t h = (1469598103934665603ULL ^ (uint64_t)n) + 0x9E3779B97F4A7C15ULL * (uint64_t)(uint32_t)focus;
    for (int32_t i = 0; i < n; i++) {
        h ^= (uint64_t)(uint32_t)f[i];
        h *= 1099511628211ULL;
        h ^= h >> 29;
    }
    return h;
}

static int32_t nodes_find(Nodes *s, const int32_t *f, int32_t n, int32_t focus, uint64_t h) {
    size_t mask = s->tcap - 1, i = (size_t)h & mask;
    for (;;) {
        int32_t x = s->table[i];
        if (x == 0) return -1;
        RNode *d = &s->v[x - 1];
        if (d->hash == h && d->len == n && d->focus == focus && memcmp(&s->facts.v[d->start], f, (size_t)n * sizeof(int32_t)) == 0)
            return x - 1;
        i = (i + 1) & mask;
    }
}

static int nodes_rehash(Nodes *s, size_t cap) {
    int32_t *t = PyMem_Calloc(cap, sizeof(int32_t));
    if (t == NULL) { PyErr_NoMemory(); return -1; }
    for (size_t k = 0; k < s->n; k++) {
        size_t i = (size_t)s->v[k].hash & (cap - 1);
        while (t[i]) i = (i + 1) & (cap - 1);
        t[i] = (int32_t)k + 1;
    }
    PyMem_Free(s->table);
    s->table = t;
    s->tcap = cap;
    return 0;
}

static int32_t nodes_add(Nodes *s, const int32_t *f, int32_t n, int32_t focus, uint64_t h) {
    if ((s->n + 1) * 2 > s->tcap && nodes_rehash(s, s->tcap ? 2 * s->tcap : 1024) < 0) return -1;
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 1024;
        RNode *v = PyMem_Realloc(s->v, cap * sizeof(RNode));
        if (v == NULL) { PyErr_NoMemory(); return -1; }
        s->v = v;
        s->cap = cap;
    }
    RNode *d = &s->v[s->n];
    memset(d, 0, sizeof(RNode));
    d->start = (int32_t)s->facts.n;
    d->len = n;
    d->focus = focus;
    d->hash = h;
    d->parent = d->act = -1;
    d->g = INFINITY;
    for (int32_t i = 0; i < n; i++)
        if (vpush(&s->facts, f[i]) < 0) return -1;
    size_t i = (size_t)h & (s->tcap - 1);
    while (s->table[i]) i = (i + 1) & (s->tcap - 1);
    s->table[i] = (int32_t)s->n + 1;
    return (int32_t)s->n++;
}

static void nodes_free(Nodes *s) {
    PyMem_Free(s->v);
    PyMem_Free(s->facts.v);
    PyMem_Free(s->table);
}

/* ------------------------------------------------------------------ building */

static void Regressor_dealloc(Regressor *R) {
    void *ps[] = {R->fluent, R->rank, R->kstart, R->klen, R->ach_start, R->ach_len, R->keys.v, R->ach.v,
                  R->es, R->el, R->ks, R->kl, R->ps, R->pl, R->clash, R->cost, R->effs.v, R->ekeys.v, R->pres.v,
                  R->holds, R->flmark, R->newmark, R->kmark, R->lkmark, R->remmark, R->chmark, R->tried,
                  R->flfact, R->newfact, R->kfact, R->lkfact, R->as, R->al, R->alls.v, R->pos, R->guardmark,
                  R->guardfact, R->asked, R->lstart, R->llen, R->lach.v, R->pairs};
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

/* set_rank(rank): every fact's position in the order of its atom (FactTable.sorted) */
static PyObject *Regressor_set_rank(Regressor *R, PyObject *rank) {
    PyObject *fast = PySequence_Fast(rank, "rank");
    if (fast == NULL) return NULL;
    if (PySequence_Fast_GET_SIZE(fast) != R->nf) {
        Py_DECREF(fast);
        PyErr_SetString(PyExc_ValueError, "rank: one entry per fact");
        return NULL;
    }
    for (int32_t f = 0; f < R->nf; f++) {
        long v = PyLong_AsLong(PySequence_Fast_GET_ITEM(fast, f));
        if (v == -1 && PyErr_Occurred()) { Py_DECREF(fast); return NULL; }
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

/* add_action(effects, effect_keys, self_clash, pre, cost, all_effects) -> index; effects and effect_keys
 * flat pairs (fluent, fact) and (key, fact); all_effects every effect's fact (ActionFacts.all_effs) */
static PyObject *Regressor_add_action(Regressor *R, PyObject *args) {
    PyObject *effs, *ekeys, *pre, *alls;
    int clash;
    double cost;
    if (!PyArg_ParseTuple(args, "OOpOdO", &effs, &ekeys, &clash, &pre, &cost, &alls)) return NULL;
    size_t n = (size_t)R->na + 1;
    if (n > R->capa) {
        int32_t **arr[] = {&R->es, &R->el, &R->ks, &R->kl, &R->ps, &R->pl, &R->as, &R->al};
        for (size_t i = 0; i < 8; i++) {
            size_t c = R->capa;
            if (grow((void **)arr[i], &c, n, sizeof(int32_t)) < 0) return NULL;
        }
        size_t c = R->capa;
        if (grow((void **)&R->clash, &c, n, sizeof(uint8_t)) < 0) return NULL;
        c = R->capa;
        if (grow((void **)&R->cost, &c, n, sizeof(double)) < 0) return NULL;
        R->capa = c;
    }
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
    R->na++;
    return PyLong_FromLong(a);
}

/* set_achievers(fact, actions): the fact's successor templates in the search's order */
static PyObject *Regressor_set_achievers(Regressor *R, PyObject *args) {
    int f;
    PyObject *acts;
    if (!PyArg_ParseTuple(args, "iO", &f, &acts)) return NULL;
    if (f < 0 || f >= R->nf) { PyErr_SetString(PyExc_IndexError, "fact id not added"); return NULL; }
    size_t a0 = R->ach.n;
    if (read_ints(acts, "achievers", &R->ach) < 0) { R->ach.n = a0; return NULL; }
    for (size_t i = a0; i < R->ach.n; i++)
        if (R->ach.v[i] >= R->na) {
            R->ach.n = a0;
            PyErr_SetString(PyExc_IndexError, "action id not added");
            return NULL;
        }
    R->ach_start[f] = (int32_t)a0;
    R->ach_len[f] = (int32_t)(R->ach.n - a0);
    Py_RETURN_NONE;
}

/* ------------------------------------------------------------------ one call */

typedef struct {
    Regressor *R;
    PyObject *holds_fn, *need_fn, *conflict_fn;
    double *hv;
    Py_ssize_t nv;
    uint32_t epoch, mk;  /* the expansion's and the successor's stamps */
    int local;           /* achievers asked per call (set_local_achievers), not the persistent ones */
} Call;

/* the scratch arrays sized for the facts, fluents, keys and actions known now */
static int fit(Regressor *R) {
    size_t c;
    c = R->caph;
    if (grow((void **)&R->holds, &c, (size_t)R->nf + 1, 1) < 0) return -1;
    for (size_t i = R->caph; i < c; i++) R->holds[i] = -1;
    c = R->caph;
    if (grow((void **)&R->remmark, &c, (size_t)R->nf + 1, sizeof(uint32_t)) < 0) return -1;
    c = R->caph;
    if (grow((void **)&R->chmark, &c, (size_t)R->nf + 1, sizeof(uint32_t)) < 0) return -1;
    c = R->caph;
    if (grow((void **)&R->pos, &c, (size_t)R->nf + 1, sizeof(int32_t)) < 0) return -1;
    for (size_t i = R->caph; i < c; i++) R->pos[i] = R->never;
    c = R->caph;
    if (grow((void **)&R->asked, &c, (size_t)R->nf + 1, 1) < 0) return -1;
    c = R->caph;
    if (grow((void **)&R->lstart, &c, (size_t)R->nf + 1, sizeof(int32_t)) < 0) return -1;
    c = R->caph;
    if (grow((void **)&R->llen, &c, (size_t)R->nf + 1, sizeof(int32_t)) < 0) return -1;
    R->caph = c;
    uint32_t **flm[] = {&R->flmark, &R->newmark, &R->guardmark};
    int32_t **flf[] = {&R->flfact, &R->newfact, &R->guardfact};
    for (int i = 0; i < 3; i++) {
        c = R->capfl;
        if (grow((void **)flm[i], &c, (size_t)R->nfl + 1, sizeof(uint32_t)) < 0) return -1;
        c = R->capfl;
        if (grow((void **)flf[i], &c, (size_t)R->nfl + 1, sizeof(int32_t)) < 0) return -1;
    }
    R->capfl = c;
    uint32_t **km[] = {&R->kmark, &R->lkmark};
    int32_t **kf[] = {&R->kfact, &R->lkfact};
    for (int i = 0; i < 2; i++) {
        c = R->capk;
        if (grow((void **)km[i], &c, (size_t)R->nkey + 1, sizeof(uint32_t)) < 0) return -1;
        c = R->capk;
        if (grow((void **)kf[i], &c, (size_t)R->nkey + 1, sizeof(int32_t)) < 0) return -1;
    }
    R->capk = c;
    c = R->capt;
    if (grow((void **)&R->tried, &c, (size_t)R->na + 1, sizeof(uint32_t)) < 0) return -1;
    R->capt = c;
    return 0;
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
    for (int32_t i = 0; i < n; i++) {
        if (C->R->remmark[cur[i]] == mk) continue;
        int t = plain_conflict(C, e, cur[i]);
        if (t) return t;
    }
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
    size_t a0 = R->lach.n;
    if (read_ints(acts, "achievers", &R->lach) < 0) { R->lach.n = a0; return NULL; }
    for (size_t i = a0; i < R->lach.n; i++)
        if (R->lach.v[i] >= R->na) {
            R->lach.n = a0;
            PyErr_SetString(PyExc_IndexError, "action id not added");
            return NULL;
        }
    R->lstart[f] = (int32_t)a0;
    R->llen[f] = (int32_t)(R->lach.n - a0);
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

/* search(root, hvals, holds, need, stop, weight, max_nodes, no_rewrites, order, protect, local, conflict)
 *   -> (status, [facts of the path's nodes, the solved one first], [actions], expanded, generated)
 * order: None or the serialization's fact ids; protect: the monotonic call's fact ids; local: the
 * call's achievers are asked per fact in the call (need sets them with set_local_achievers); conflict:
 * conflict(x, y) -> bool, the plain conflict rules (None where there are none) */
static PyObject *Regressor_search(Regressor *R, PyObject *args) {
    PyObject *root, *hvals, *holds_fn, *need_fn, *stop, *order, *protect, *conflict_fn;
    double weight;
    long long max_nodes;
    int no_rewrites, local;
    if (!PyArg_ParseTuple(args, "OOOOOdLpOOpO", &root, &hvals, &holds_fn, &need_fn, &stop, &weight, &max_nodes,
                          &no_rewrites, &order, &protect, &local, &conflict_fn))
        return NULL;
    if (R->has_plain && conflict_fn == Py_None) {
        PyErr_SetString(PyExc_ValueError, "plain conflict rules need conflict(x, y)");
        return NULL;
    }
    if (R->in_call) { PyErr_SetString(PyExc_RuntimeError, "search() is not re-entrant"); return NULL; }
    int has_order = order != Py_None;
    int32_t focus0 = 0;
    Vec ov = {0};
    Call C = {R, holds_fn, need_fn, conflict_fn, NULL, 0, 0, 0, local};
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
                double cost = R->cost[a];
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
    {"set_rank", (PyCFunction)Regressor_set_rank, METH_O, "set_rank(rank): each fact's sort position"},
    {"add_action", (PyCFunction)Regressor_add_action, METH_VARARGS,
     "add_action(effects, effect_keys, self_clash, pre, cost) -> index"},
    {"set_achievers", (PyCFunction)Regressor_set_achievers, METH_VARARGS, "set_achievers(fact, actions)"},
    {"set_local_achievers", (PyCFunction)Regressor_set_local_achievers, METH_VARARGS,
     "set_local_achievers(fact, actions): for the running call only"},
    {"search", (PyCFunction)Regressor_search, METH_VARARGS,
     "search(root, hvals, holds, need, stop, weight, max_nodes, no_rewrites, order, protect, local, conflict)"},
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
