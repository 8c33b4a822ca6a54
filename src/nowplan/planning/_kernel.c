/* The forward engine's compiled kernel: h_FF / h_add / h_max with preferred
 * operators, the successor generator, lazy GBFS, LAMA's first iteration
 * (_kernel_lama.h), the bounded weighted A* of the anytime improvement
 * (_kernel_wastar.h) and the plan neighborhood graph search (_kernel_pngs.h)
 * over bitset states, the stratified evaluation of the rules of derived
 * predicates after every action (_kernel_axioms.h, axioms.py),
 * every fact's relaxed cost for the regression search's h_add (_kernel_costs.h)
 * and the relaxation's breadth-first action order, fact landmarks and first achievers for the landmark
 * graph (_kernel_relaxed.h).
 *
 * It mirrors nowplan/planning/hff.py, forward.py, lama.py, anytime.py and pngs.py (the reference: both
 * paths must give the same h, the same preferred operators, the same plan
 * and the same counters).  The exploration pops the lowest cost and, among
 * equal costs, the most recently pushed entry (a push counter stands in for
 * the Python heap's -tick); the state's facts are pushed in ascending order.
 * The search queues pop the lowest h and, among equal h, the oldest entry.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define KERNEL_API 9
#define BIT(b, f) (((b)[(f) >> 6] >> ((f) & 63)) & 1u)
#define SETBIT(b, f) ((b)[(f) >> 6] |= (uint64_t)1 << ((f) & 63))
#define CLRBIT(b, f) ((b)[(f) >> 6] &= ~((uint64_t)1 << ((f) & 63)))

enum { KIND_FF, KIND_ADD, KIND_MAX };
enum { ST_SOLVED, ST_EXHAUSTED, ST_NODE_LIMIT, ST_TIME_LIMIT, ST_DEAD_INIT };

typedef struct { int32_t *off, *v; } CSR; /* row i: v[off[i] .. off[i+1]) */
typedef struct { double c; uint64_t tick; int32_t f; } HEnt;
typedef struct { int32_t f, next; } BEnt;  /* a bucket entry: a fact and the entry below it */
#define BUCKETS_MAX (1 << 20)  /* integer costs below this go to buckets, the others to the heap */

typedef struct {
    PyObject_HEAD
    int32_t nf, na, ngoal, nnopre, words, kind;
    CSR pre, add, del, bypre, trig;
    int32_t *nopre, *goal, *npre, *chosen, *stack, *sf;
    uint8_t *isgoal, *marked, *chmark;
    double *acost, *fcost, *acc;
    int32_t *sup, *unsat;
    HEnt *heap;
    int bucketed;     /* every cost a non-negative integer (or inf): a bucket queue, else the heap */
    int32_t *bhead;   /* cost -> its last entry in bpool, -1 when empty */
    size_t nbuckets;
    BEnt *bpool;
    uint64_t *bits;
    uint64_t *base;   /* facts costs() adds to every state (set_base), or NULL */
    long long evaluations;
    int32_t nact;     /* actions [0, nact) are applicable; the others are rules, relaxed only */
    int32_t nax, nlayers;  /* the rules of derived predicates (axioms) and their layers */
    CSR axbody, axby, negs;  /* rule -> conditions; fact -> rules needing it; layer -> (d, not d) pairs */
    int32_t *axhead, *axnbody, *axunsat, *axqueue, *laylo, *layhi;
    uint64_t *dmask;  /* the facts the evaluation recomputes (derived facts and their "not" facts) */
} Kernel;

/* ------------------------------------------------------------------ building */

static void *xcalloc(size_t n, size_t size) {
    void *p = PyMem_Calloc(n ? n : 1, size);
    if (p == NULL) PyErr_NoMemory();
    return p;
}

static int as_index(PyObject *o, int32_t bound, const char *what, int32_t *out) {
    long v = PyLong_AsLong(o);
    if (v == -1 && PyErr_Occurred()) return -1;
    if (v < 0 || v >= bound) {
        PyErr_Format(PyExc_IndexError, "%s id %ld out of range [0, %d)", what, v, (int)bound);
        return -1;
    }
    *out = (int32_t)v;
    return 0;
}

/* A sequence of n rows of ids below bound, as CSR. */
static int build_csr(PyObject *rows, int32_t n, int32_t bound, const char *what, CSR *out) {
    PyObject *fast = PySequence_Fast(rows, what), *row = NULL;
    if (fast == NULL) return -1;
    if (PySequence_Fast_GET_SIZE(fast) != n) {
        PyErr_Format(PyExc_ValueError, "%s: expected %d rows", what, (int)n);
        goto fail;
    }
    size_t cap = 64, k = 0;
    if (!(out->off = xcalloc((size_t)n + 1, sizeof(int32_t))) || !(out->v = xcalloc(cap, sizeof(int32_t))))
        goto fail;
    for (int32_t i = 0; i < n; i++) {
        if (!(row = PySequence_Fast(PySequence_Fast_GET_ITEM(fast, i), what))) goto fail;
        size_t m = (size_t)PySequence_Fast_GET_SIZE(row);
        if (k + m > cap) {
            while (k + m > cap) cap *= 2;
            int32_t *v = PyMem_Realloc(out->v, cap * sizeof(int32_t));
            if (v == NULL) { PyErr_NoMemory(); goto fail; }
            out->v = v;
        }
        for (size_t j = 0; j < m; j++)
            if (as_index(PySequence_Fast_GET_ITEM(row, j), bound, what, &out->v[k++]) < 0) goto fail;
        Py_CLEAR(row);
        if (k >= INT32_MAX) { PyErr_SetString(PyExc_ValueError, "task too large"); goto fail; }
        out->off[i + 1] = (int32_t)k;
    }
    Py_DECREF(fast);
    return 0;
fail:
    Py_XDECREF(row);
    Py_DECREF(fast);
    return -1;
}

static int build_list(PyObject *seq, int32_t bound, const char *what, int32_t **out, int32_t *n) {
    PyObject *fast = PySequence_Fast(seq, what);
    if (fast == NULL) return -1;
    Py_ssize_t m = PySequence_Fast_GET_SIZE(fast);
    *n = (int32_t)m;
    if (!(*out = xcalloc((size_t)m, sizeof(int32_t)))) goto fail;
    for (Py_ssize_t j = 0; j < m; j++)
        if (as_index(PySequence_Fast_GET_ITEM(fast, j), bound, what, &(*out)[j]) < 0) goto fail;
    Py_DECREF(fast);
    return 0;
fail:
    Py_DECREF(fast);
    return -1;
}

static void free_csr(CSR *c) { PyMem_Free(c->off); PyMem_Free(c->v); }

static void Kernel_dealloc(Kernel *k) {
    CSR *csrs[] = {&k->pre, &k->add, &k->del, &k->bypre, &k->trig, &k->axbody, &k->axby, &k->negs};
    for (size_t i = 0; i < sizeof csrs / sizeof *csrs; i++) free_csr(csrs[i]);
    void *arrs[] = {k->nopre, k->goal, k->npre, k->chosen, k->stack, k->sf, k->isgoal, k->marked, k->chmark,
                    k->acost, k->fcost, k->acc, k->sup, k->unsat, k->heap, k->bhead, k->bpool, k->bits,
                    k->axhead, k->axnbody, k->axunsat, k->axqueue, k->laylo, k->layhi, k->dmask, k->base};
    for (size_t i = 0; i < sizeof arrs / sizeof *arrs; i++) PyMem_Free(arrs[i]);
    Py_TYPE(k)->tp_free((PyObject *)k);
}

/* Actions filed under their precondition with the fewest consumers (ties: the first). */
static int build_triggers(Kernel *k) {
    int32_t na = k->na, nf = k->nf;
    if (!(k->trig.off = xcalloc((size_t)nf + 1, sizeof(int32_t))) ||
        !(k->trig.v = xcalloc((size_t)na, sizeof(int32_t))))
        return -1;
    int32_t *of = PyMem_Malloc(sizeof(int32_t) * (size_t)(na ? na : 1));
    if (of == NULL) { PyErr_NoMemory(); return -1; }
    for (int32_t a = 0; a < na; a++) {
        int32_t best = -1, bestn = 0;
        if (a >= k->nact) { of[a] = -1; continue; }  /* a rule: never applied by the search */
        for (int32_t j = k->pre.off[a]; j < k->pre.off[a + 1]; j++) {
            int32_t f = k->pre.v[j], n = k->bypre.off[f + 1] - k->bypre.off[f];
            if (best < 0 || n < bestn) { best = f; bestn = n; }
        }
        of[a] = best;
        if (best >= 0) k->trig.off[best + 1]++;
    }
    for (int32_t f = 0; f < nf; f++) k->trig.off[f + 1] += k->trig.off[f];
    int32_t *fill = xcalloc((size_t)nf, sizeof(int32_t));
    if (fill == NULL) { PyMem_Free(of); return -1; }
    for (int32_t a = 0; a < na; a++)
        if (of[a] >= 0) k->trig.v[k->trig.off[of[a]] + fill[of[a]]++] = a;
    PyMem_Free(fill);
    PyMem_Free(of);
    return 0;
}

#include "_kernel_axioms.h"

/* dst := the successor of state src by action a (deletes, then adds, then the derived facts) */
static inline void apply_action(Kernel *k, uint64_t *dst, const uint64_t *src, int32_t a) {
    memcpy(dst, src, (size_t)k->words * sizeof(uint64_t));
    for (int32_t j = k->del.off[a]; j < k->del.off[a + 1]; j++) CLRBIT(dst, k->del.v[j]);
    for (int32_t j = k->add.off[a]; j < k->add.off[a + 1]; j++) SETBIT(dst, k->add.v[j]);
    if (k->dmask) axioms_eval(k, dst);
}

static PyObject *Kernel_new(PyTypeObject *type, PyObject *args, PyObject *kwds) {
    static char *kwlist[] = {"nfacts", "pre", "add", "dele", "cost", "goal", "by_pre", "no_pre", "kind",
                             "nactions", "axioms", NULL};
    int nf, nactions = -1;
    PyObject *pre, *add, *dele, *cost, *goal, *bypre, *nopre, *axioms = Py_None;
    const char *kind;
    if (!PyArg_ParseTupleAndKeywords(args, kwds, "iOOOOOOOs|iO", kwlist, &nf, &pre, &add, &dele, &cost, &goal,
                                     &bypre, &nopre, &kind, &nactions, &axioms))
        return NULL;
    Kernel *k = (Kernel *)type->tp_alloc(type, 0);
    if (k == NULL) return NULL;
    if (strcmp(kind, "ff") == 0) k->kind = KIND_FF;
    else if (strcmp(kind, "add") == 0) k->kind = KIND_ADD;
    else if (strcmp(kind, "max") == 0) k->kind = KIND_MAX;
    else { PyErr_Format(PyExc_ValueError, "unknown heuristic kind %s", kind); goto fail; }
    Py_ssize_t na = PyObject_Length(pre);
    if (na < 0) goto fail;
    if (nf < 0 || nf >= INT32_MAX - 64 || na >= INT32_MAX) { PyErr_SetString(PyExc_ValueError, "task too large"); goto fail; }
    k->nf = nf;
    k->na = (int32_t)na;
    k->nact = nactions < 0 || nactions > na ? (int32_t)na : nactions;
    k->words = (nf + 63) / 64;
    if (build_csr(pre, k->na, nf, "pre", &k->pre) || build_csr(add, k->na, nf, "add", &k->add) ||
        build_csr(dele, k->na, nf, "dele", &k->del) || build_csr(bypre, nf, k->na, "by_pre", &k->bypre) ||
        build_list(goal, nf, "goal", &k->goal, &k->ngoal) || build_list(nopre, k->na, "no_pre", &k->nopre, &k->nnopre))
        goto fail;
    PyObject *fc = PySequence_Fast(cost, "cost");
    if (fc == NULL) goto fail;
    if (PySequence_Fast_GET_SIZE(fc) != na) {
        Py_DECREF(fc);
        PyErr_SetString(PyExc_ValueError, "cost: expected one per action");
        goto fail;
    }
    if (!(k->acost = xcalloc((size_t)na, sizeof(double)))) { Py_DECREF(fc); goto fail; }
    for (Py_ssize_t a = 0; a < na; a++) {
        k->acost[a] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fc, a));
        if (k->acost[a] == -1.0 && PyErr_Occurred()) { Py_DECREF(fc); goto fail; }
    }
    Py_DECREF(fc);
    size_t npush = (size_t)nf + (size_t)k->add.off[na];  /* each action fires at most once */
    size_t nstack = (size_t)k->ngoal + (size_t)k->pre.off[na];
    if (!(k->npre = xcalloc(na, sizeof(int32_t))) || !(k->chosen = xcalloc(na, sizeof(int32_t))) ||
        !(k->stack = xcalloc(nstack, sizeof(int32_t))) || !(k->sf = xcalloc(nf, sizeof(int32_t))) ||
        !(k->isgoal = xcalloc(nf, 1)) || !(k->marked = xcalloc(nf, 1)) || !(k->chmark = xcalloc(na, 1)) ||
        !(k->fcost = xcalloc(nf, sizeof(double))) || !(k->acc = xcalloc(na, sizeof(double))) ||
        !(k->sup = xcalloc(nf, sizeof(int32_t))) || !(k->unsat = xcalloc(na, sizeof(int32_t))) ||
        !(k->heap = xcalloc(npush, sizeof(HEnt))) || !(k->bits = xcalloc(k->words, sizeof(uint64_t))))
        goto fail;
    k->bucketed = 1;
    for (Py_ssize_t a = 0; a < na; a++) {
        double c = k->acost[a];
        if (!(c == INFINITY || (c >= 0.0 && c == floor(c) && c < BUCKETS_MAX))) k->bucketed = 0;
    }
    if (k->bucketed) {
        k->nbuckets = 64;
        if (!(k->bpool = xcalloc(npush, sizeof(BEnt))) || !(k->bhead = xcalloc(k->nbuckets, sizeof(int32_t))))
            goto fail;
        memset(k->bhead, 0xff, k->nbuckets * sizeof(int32_t));
    }
    for (int32_t a = 0; a < k->na; a++) k->npre[a] = k->pre.off[a + 1] - k->pre.off[a];
    for (int32_t i = 0; i < k->ngoal; i++) k->isgoal[k->goal[i]] = 1;
    if (build_triggers(k) < 0) goto fail;
    if (axioms != Py_None && build_axioms(k, axioms) < 0) goto fail;
    return (PyObject *)k;
fail:
    Py_DECREF(k);
    return NULL;
}

/* ------------------------------------------------------------------ the heuristic */

static inline int hless(const HEnt *a, const HEnt *b) {
    if (a->c != b->c) return a->c < b->c;
    return a->tick > b->tick;  /* equal costs: the latest push first */
}

static inline void hpush(HEnt *h, size_t *n, double c, uint64_t tick, int32_t f) {
    size_t i = (*n)++;
    HEnt e = {c, tick, f};
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!hless(&e, &h[p])) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = e;
}

static inline HEnt hpop(HEnt *h, size_t *n) {
    HEnt top = h[0], last = h[--(*n)];
    size_t i = 0, m = *n;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= m) break;
        if (c + 1 < m && hless(&h[c + 1], &h[c])) c++;
        if (!hless(&h[c], &last)) break;
        h[i] = h[c];
        i = c;
    }
    if (m) h[i] = last;
    return top;
}

/* The exploration queue: the order of (cost, -push count).  With non-negative integer costs
 * the exploration is monotone (no push below the cost last popped), so buckets that pop
 * their last entry first give that order; costs from BUCKETS_MAX on, and any other
 * costs, go to the binary heap (popped after every bucket: they are higher). */
typedef struct { size_t n, np, cur, top; uint64_t tick; } XQ;

static inline int xpush(Kernel *k, XQ *q, double c, int32_t f) {
    if (k->bucketed && c < BUCKETS_MAX) {
        size_t b = (size_t)c;
        if (b >= k->nbuckets) {
            size_t nb = k->nbuckets;
            while (nb <= b) nb *= 2;
            int32_t *h = PyMem_Realloc(k->bhead, nb * sizeof(int32_t));
            if (h == NULL) { PyErr_NoMemory(); return -1; }
            memset(h + k->nbuckets, 0xff, (nb - k->nbuckets) * sizeof(int32_t));
            k->bhead = h;
            k->nbuckets = nb;
        }
        k->bpool[q->np] = (BEnt){f, k->bhead[b]};
        k->bhead[b] = (int32_t)q->np++;
        if (b >= q->top) q->top = b + 1;
    } else {
        hpush(k->heap, &q->n, c, ++q->tick, f);
    }
    return 0;
}

static inline int xpop(Kernel *k, XQ *q, double *c, int32_t *f) {
    if (k->bucketed) {
        while (q->cur < q->top && k->bhead[q->cur] < 0) q->cur++;
        if (q->cur < q->top) {
            BEnt e = k->bpool[k->bhead[q->cur]];
            k->bhead[q->cur] = e.next;
            *c = (double)q->cur;
            *f = e.f;
            return 1;
        }
    }
    if (q->n == 0) return 0;
    HEnt e = hpop(k->heap, &q->n);
    *c = e.c;
    *f = e.f;
    return 1;
}

static inline void xclear(Kernel *k, XQ *q) {
    if (k->bucketed && q->top > q->cur) memset(k->bhead + q->cur, 0xff, (q->top - q->cur) * sizeof(int32_t));
}

static int cmp_i32(const void *a, const void *b) {
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* h of the state (bits, with its facts sf[0..ns) ascending); the preferred operators,
 * ascending, into pref (room for na).  INFINITY at a dead end; NAN (exception set) when
 * out of memory. */
static double evaluate_core(Kernel *k, const uint64_t *bits, const int32_t *sf, int32_t ns,
                            int32_t *pref, int32_t *npref) {
    k->evaluations++;
    *npref = 0;
    int32_t left = 0, nf = k->nf, na = k->na;
    for (int32_t i = 0; i < k->ngoal; i++) left += !BIT(bits, k->goal[i]);
    if (left == 0) return 0.0;
    double *fcost = k->fcost, *acc = k->acc, *acost = k->acost;
    int32_t *sup = k->sup, *unsat = k->unsat;
    const int32_t *aoff = k->add.off, *av = k->add.v, *boff = k->bypre.off, *bv = k->bypre.v;
    for (int32_t f = 0; f < nf; f++) { fcost[f] = INFINITY; sup[f] = -1; }
    memcpy(unsat, k->npre, sizeof(int32_t) * (size_t)na);
    memset(acc, 0, sizeof(double) * (size_t)na);
    XQ q = {0, 0, 0, 0, 0};
    int err = 0;
    for (int32_t i = 0; i < ns; i++) { fcost[sf[i]] = 0.0; err |= xpush(k, &q, 0.0, sf[i]); }
    for (int32_t i = 0; i < k->nnopre; i++) {
        int32_t a = k->nopre[i];
        double c = acost[a];
        for (int32_t j = aoff[a]; j < aoff[a + 1]; j++)
            if (c < fcost[av[j]]) { fcost[av[j]] = c; sup[av[j]] = a; err |= xpush(k, &q, c, av[j]); }
    }
    int use_max = k->kind == KIND_MAX;
    double c;
    int32_t f;
    while (!err && xpop(k, &q, &c, &f)) {
        if (c > fcost[f]) continue;
        if (k->isgoal[f] && !BIT(bits, f) && --left == 0) break;
        for (int32_t i = boff[f]; i < boff[f + 1]; i++) {
            int32_t a = bv[i];
            if (use_max) { if (c > acc[a]) acc[a] = c; }
            else acc[a] += c;
            if (--unsat[a] == 0) {
                double nc = acc[a] + acost[a];
                for (int32_t j = aoff[a]; j < aoff[a + 1]; j++)
                    if (nc < fcost[av[j]]) { fcost[av[j]] = nc; sup[av[j]] = a; err |= xpush(k, &q, nc, av[j]); }
            }
        }
    }
    xclear(k, &q);
    if (err) return NAN;
    if (left) return INFINITY;
    double h = 0.0;
    if (k->kind == KIND_ADD) {
        for (int32_t i = 0; i < k->ngoal; i++) h += fcost[k->goal[i]];
        return h;
    }
    if (use_max) {
        h = fcost[k->goal[0]];
        for (int32_t i = 1; i < k->ngoal; i++) if (fcost[k->goal[i]] > h) h = fcost[k->goal[i]];
        return h;
    }
    /* h_FF: the relaxed plan from the best supporters, chosen in the Python order */
    memset(k->marked, 0, (size_t)nf);
    memset(k->chmark, 0, (size_t)na);
    int32_t *stack = k->stack, sp = 0, nch = 0;
    const int32_t *poff = k->pre.off, *pv = k->pre.v;
    for (int32_t i = 0; i < k->ngoal; i++) if (!BIT(bits, k->goal[i])) stack[sp++] = k->goal[i];
    while (sp) {
        int32_t f = stack[--sp];
        if (k->marked[f]) continue;
        k->marked[f] = 1;
        int32_t a = sup[f];
        if (a < 0 || k->chmark[a]) continue;
        k->chmark[a] = 1;
        k->chosen[nch++] = a;
        for (int32_t j = poff[a]; j < poff[a + 1]; j++)
            if (!BIT(bits, pv[j]) && !k->marked[pv[j]]) stack[sp++] = pv[j];
    }
    for (int32_t i = 0; i < nch; i++) {
        int32_t a = k->chosen[i], ok = 1;
        h += acost[a];
        for (int32_t j = poff[a]; j < poff[a + 1] && ok; j++) ok = BIT(bits, pv[j]);
        if (ok && a < k->nact) pref[(*npref)++] = a;
    }
    qsort(pref, (size_t)*npref, sizeof(int32_t), cmp_i32);
    return h;
}

/* The applicable actions of the state, ascending, into out (room for na). */
static int32_t applicable_core(Kernel *k, const uint64_t *bits, const int32_t *sf, int32_t ns, int32_t *out) {
    int32_t n = 0;
    const int32_t *poff = k->pre.off, *pv = k->pre.v;
    for (int32_t i = 0; i < k->nnopre; i++) if (k->nopre[i] < k->nact) out[n++] = k->nopre[i];
    for (int32_t i = 0; i < ns; i++) {
        int32_t f = sf[i];
        for (int32_t t = k->trig.off[f]; t < k->trig.off[f + 1]; t++) {
            int32_t a = k->trig.v[t], ok = 1;
            for (int32_t j = poff[a]; j < poff[a + 1] && ok; j++) ok = BIT(bits, pv[j]);
            if (ok) out[n++] = a;
        }
    }
    qsort(out, (size_t)n, sizeof(int32_t), cmp_i32);
    return n;
}

/* The facts of a bitset, ascending. */
static int32_t facts_of(const uint64_t *bits, int32_t words, int32_t *out) {
    int32_t n = 0;
    for (int32_t w = 0; w < words; w++)
        for (uint64_t x = bits[w]; x; x &= x - 1) out[n++] = w * 64 + __builtin_ctzll(x);
    return n;
}

/* A Python iterable of fact ids into k->bits and k->sf; the number of facts or -1. */
static int32_t load_state(Kernel *k, PyObject *state) {
    memset(k->bits, 0, sizeof(uint64_t) * (size_t)k->words);
    PyObject *it = PyObject_GetIter(state), *item;
    if (it == NULL) return -1;
    while ((item = PyIter_Next(it)) != NULL) {
        int32_t f;
        int bad = as_index(item, k->nf, "fact", &f);
        Py_DECREF(item);
        if (bad) { Py_DECREF(it); return -1; }
        SETBIT(k->bits, f);
    }
    Py_DECREF(it);
    if (PyErr_Occurred()) return -1;
    return facts_of(k->bits, k->words, k->sf);
}

static PyObject *id_list(const int32_t *v, int32_t n) {
    PyObject *out = PyList_New(n);
    if (out == NULL) return NULL;
    for (int32_t i = 0; i < n; i++) {
        PyObject *x = PyLong_FromLong(v[i]);
        if (x == NULL) { Py_DECREF(out); return NULL; }
        PyList_SET_ITEM(out, i, x);
    }
    return out;
}

static PyObject *Kernel_evaluate(Kernel *k, PyObject *state) {
    int32_t ns = load_state(k, state), np;
    if (ns < 0) return NULL;
    int32_t *pref = PyMem_Malloc(sizeof(int32_t) * (size_t)(k->na ? k->na : 1));
    if (pref == NULL) return PyErr_NoMemory();
    double h = evaluate_core(k, k->bits, k->sf, ns, pref, &np);
    if (isnan(h) && PyErr_Occurred()) { PyMem_Free(pref); return NULL; }
    PyObject *lst = id_list(pref, np);
    PyMem_Free(pref);
    if (lst == NULL) return NULL;
    return Py_BuildValue("(dN)", h, lst);
}

static PyObject *Kernel_applicable(Kernel *k, PyObject *state) {
    int32_t ns = load_state(k, state);
    if (ns < 0) return NULL;
    int32_t *out = PyMem_Malloc(sizeof(int32_t) * (size_t)(k->na ? k->na : 1));
    if (out == NULL) return PyErr_NoMemory();
    PyObject *lst = id_list(out, applicable_core(k, k->bits, k->sf, ns, out));
    PyMem_Free(out);
    return lst;
}

static PyObject *Kernel_close(Kernel *k, PyObject *state) {
    int32_t ns = load_state(k, state);
    if (ns < 0) return NULL;
    if (k->dmask) axioms_eval(k, k->bits);
    return id_list(k->sf, facts_of(k->bits, k->words, k->sf));
}

#include "_kernel_heap.h"
#include "_kernel_gbfs.h"
#include "_kernel_lama.h"
#include "_kernel_wastar.h"
#include "_kernel_pngs.h"
#include "_kernel_costs.h"
#include "_kernel_relaxed.h"

static PyMethodDef Kernel_methods[] = {
    {"evaluate", (PyCFunction)Kernel_evaluate, METH_O,
     "evaluate(state) -> (h, preferred action ids ascending); h is inf at a dead end"},
    {"applicable", (PyCFunction)Kernel_applicable, METH_O, "applicable(state) -> action ids ascending"},
    {"close", (PyCFunction)Kernel_close, METH_O,
     "close(facts) -> the state's fact ids ascending, derived facts recomputed by the rules (axioms)"},
    {"gbfs", (PyCFunction)(void (*)(void))Kernel_gbfs, METH_VARARGS | METH_KEYWORDS,
     "gbfs(init, max_nodes, out_of_time) -> (status, plan action ids or None, expanded, generated, evaluations)"},
    {"lama", (PyCFunction)(void (*)(void))Kernel_lama, METH_VARARGS | METH_KEYWORDS,
     "lama(init, max_nodes, landmarks, before, out_of_time, boost, unreachable) -> as gbfs (h_FF evaluations)"},
    {"set_base", (PyCFunction)Kernel_set_base, METH_O,
     "set_base(facts): facts that costs() adds to every state it is given"},
    {"costs", (PyCFunction)Kernel_costs, METH_VARARGS,
     "costs(state, overrides=(), off=()) -> the relaxed cost of every fact from state minus off (inf: not reached); overrides = [(action, facts)]"},
    {"bounded_wastar", (PyCFunction)(void (*)(void))Kernel_bounded_wastar, METH_VARARGS | METH_KEYWORDS,
     "bounded_wastar(init, cost, weight, bound, stop) -> a plan (action ids) cheaper than bound, or None"},
    {"neighborhood", (PyCFunction)(void (*)(void))Kernel_neighborhood, METH_VARARGS | METH_KEYWORDS,
     "neighborhood(init, plan, limit, cost, stop) -> (cheapest plan in the plan's neighborhood graph of at most "
     "limit states, states, complete, stopped)"},
    {"relaxed_order", (PyCFunction)Kernel_relaxed_order, METH_O,
     "relaxed_order(state) -> (actions in the delete relaxation's breadth-first order, reached facts ascending)"},
    {"first_achievers", (PyCFunction)Kernel_first_achievers, METH_VARARGS,
     "first_achievers(state, order, families) -> each fact set's first achievers ascending (order: relaxed_order's)"},
    {"landmark_sets", (PyCFunction)Kernel_landmark_sets, METH_VARARGS,
     "landmark_sets(state, order) -> every fact's landmark set (frozenset, None: not reached) over order's actions"},
    {NULL, NULL, 0, NULL},
};

static PyObject *Kernel_get_evaluations(Kernel *k, void *closure) {
    (void)closure;
    return PyLong_FromLongLong(k->evaluations);
}

static PyGetSetDef Kernel_getset[] = {
    {"evaluations", (getter)Kernel_get_evaluations, NULL, "heuristic evaluations so far", NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

static PyTypeObject KernelType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "nowplan.planning._kernel.Kernel",
    .tp_doc = "Kernel(nfacts, pre, add, dele, cost, goal, by_pre, no_pre, kind): one task, compiled",
    .tp_basicsize = sizeof(Kernel),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_new = Kernel_new,
    .tp_dealloc = (destructor)Kernel_dealloc,
    .tp_methods = Kernel_methods,
    .tp_getset = Kernel_getset,
};

static struct PyModuleDef kernel_module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_kernel",
    .m_doc = "The forward engine's compiled kernel (see hff.py and forward.py).",
    .m_size = -1,
};

PyMODINIT_FUNC PyInit__kernel(void) {
    if (PyType_Ready(&KernelType) < 0) return NULL;
    PyObject *m = PyModule_Create(&kernel_module);
    if (m == NULL) return NULL;
    if (PyModule_AddIntConstant(m, "API", KERNEL_API) < 0 ||
        PyModule_AddIntConstant(m, "SOLVED", ST_SOLVED) < 0 ||
        PyModule_AddIntConstant(m, "EXHAUSTED", ST_EXHAUSTED) < 0 ||
        PyModule_AddIntConstant(m, "NODE_LIMIT", ST_NODE_LIMIT) < 0 ||
        PyModule_AddIntConstant(m, "TIME_LIMIT", ST_TIME_LIMIT) < 0 ||
        PyModule_AddIntConstant(m, "DEAD_INIT", ST_DEAD_INIT) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    Py_INCREF(&KernelType);
    if (PyModule_AddObject(m, "Kernel", (PyObject *)&KernelType) < 0) {
        Py_DECREF(&KernelType);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
