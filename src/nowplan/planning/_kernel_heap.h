/* A binary min-heap over entries of type ENT ordered by LESS: push and pop (PyMem, grows by doubling).
 * NP_HEAP(Queue, QEnt, qless, qpush, qpop) defines `Queue` with `qpush(&q, e)` (-1 with
 * MemoryError set) and `qpop(&q)` (q.n > 0).  One definition serves every search's open list. */
#define NP_HEAP(HEAP, ENT, LESS, PUSH, POP)                                    \
typedef struct { ENT *v; size_t n, cap; } HEAP;                                \
static int PUSH(HEAP *q, ENT e) {                                              \
    if (q->n == q->cap) {                                                      \
        size_t cap = q->cap ? 2 * q->cap : 1024;                               \
        ENT *v = PyMem_Realloc(q->v, cap * sizeof(ENT));                       \
        if (v == NULL) { PyErr_NoMemory(); return -1; }                        \
        q->v = v;                                                              \
        q->cap = cap;                                                          \
    }                                                                          \
    size_t i = q->n++;                                                         \
    while (i > 0) {                                                            \
        size_t p = (i - 1) / 2;                                                \
        if (!LESS(&e, &q->v[p])) break;                                        \
        q->v[i] = q->v[p];                                                     \
        i = p;                                                                 \
    }                                                                          \
    q->v[i] = e;                                                               \
    return 0;                                                                  \
}                                                                              \
static ENT POP(HEAP *q) {                                                      \
    ENT *h = q->v, top = h[0], last = h[--q->n];                               \
    size_t i = 0, m = q->n;                                                    \
    for (;;) {                                                                 \
        size_t c = 2 * i + 1;                                                  \
        if (c >= m) break;                                                     \
        if (c + 1 < m && LESS(&h[c + 1], &h[c])) c++;                          \
        if (!LESS(&h[c], &last)) break;                                        \
        h[i] = h[c];                                                           \
        i = c;                                                                 \
    }                                                                          \
    if (m) h[i] = last;                                                        \
    return top;                                                                \
}

/* The searches' time check: call `stop()` (None: never stop).  1 stop, 0 go on, -1 error set. */
static int asked_to_stop(PyObject *stop) {
    if (stop == Py_None) return 0;
    PyObject *r = PyObject_CallNoArgs(stop);
    if (r == NULL) return -1;
    int t = PyObject_IsTrue(r);
    Py_DECREF(r);
    return t;
}
