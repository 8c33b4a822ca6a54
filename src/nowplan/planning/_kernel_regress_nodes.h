/* The regression loop's frontier (ordered as regression_astar.py's) and its nodes: (sorted facts, focus), hashed. */
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
        if (d->hash == h && d->len == n && d->focus == focus &&
            (n == 0 || memcmp(&s->facts.v[d->start], f, (size_t)n * sizeof(int32_t)) == 0))  /* (an empty child: NULL) */
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

