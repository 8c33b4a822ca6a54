/* The relaxed cost of every fact from a state, for the regression search's h_add
 * (nowplan/planning/hadd_kernel.py; the Python reference is heuristics.hadd_ids).
 *
 * costs(state, overrides=(), off=()) explores every action once from the facts of state
 * and of the base (set_base) that are not in off, as evaluate_core does but
 * without goals (no early stop), and returns the cost of each fact (inf where the
 * relaxation does not reach it; 0 for the state's facts).  h_add sums a reached
 * action's precondition costs, h_max takes their maximum (the kernel's kind).
 * overrides = [(action, [facts]), ...] replaces those actions' preconditions for
 * this call (an action at another abstraction level than the task's). */

/* Facts added to every state costs() is given (e.g. the negations that hold unless their atom does). */
static PyObject *Kernel_set_base(Kernel *k, PyObject *facts) {
    uint64_t *base = xcalloc((size_t)k->words, sizeof(uint64_t));
    if (base == NULL) return NULL;
    PyObject *it = PyObject_GetIter(facts), *item;
    if (it == NULL) { PyMem_Free(base); return NULL; }
    while ((item = PyIter_Next(it)) != NULL) {
        int32_t f;
        int bad = as_index(item, k->nf, "fact", &f);
        Py_DECREF(item);
        if (bad) { Py_DECREF(it); PyMem_Free(base); return NULL; }
        SETBIT(base, f);
    }
    Py_DECREF(it);
    if (PyErr_Occurred()) { PyMem_Free(base); return NULL; }
    PyMem_Free(k->base);
    k->base = base;
    Py_RETURN_NONE;
}

/* Float objects for the small integer costs (and inf), shared by every costs() answer. */
#define SMALL_COSTS 4096
static PyObject *small_cost[SMALL_COSTS + 1];

static PyObject *cost_object(double c) {
    Py_ssize_t i = -1;
    if (c == INFINITY) i = SMALL_COSTS;
    else if (c >= 0.0 && c < SMALL_COSTS && c == floor(c)) i = (Py_ssize_t)c;
    if (i < 0) return PyFloat_FromDouble(c);
    if (small_cost[i] == NULL && (small_cost[i] = PyFloat_FromDouble(c)) == NULL) return NULL;
    Py_INCREF(small_cost[i]);
    return small_cost[i];
}

static PyObject *Kernel_costs(Kernel *k, PyObject *args) {
    PyObject *state, *over = NULL, *off = NULL;
    if (!PyArg_ParseTuple(args, "O|OO", &state, &over, &off)) return NULL;
    int32_t ns = load_state(k, state);
    if (ns < 0) return NULL;
    int32_t nf = k->nf, na = k->na;
    if (k->base != NULL) {
        for (int32_t w = 0; w < k->words; w++) k->bits[w] |= k->base[w];
        ns = facts_of(k->bits, k->words, k->sf);
    }
    if (off != NULL && off != Py_None) {  /* facts taken out of the state again */
        PyObject *it = PyObject_GetIter(off), *item;
        if (it == NULL) return NULL;
        while ((item = PyIter_Next(it)) != NULL) {
            int32_t f;
            int bad = as_index(item, nf, "fact", &f);
            Py_DECREF(item);
            if (bad) { Py_DECREF(it); return NULL; }
            CLRBIT(k->bits, f);
        }
        Py_DECREF(it);
        if (PyErr_Occurred()) return NULL;
        ns = facts_of(k->bits, k->words, k->sf);
    }
    PyObject *ofast = NULL, *out = NULL;
    uint8_t *repl = NULL;
    int32_t *xhead = NULL, *xact = NULL, *xnext = NULL, *ovact = NULL, *ovn = NULL;
    Py_ssize_t nov = 0, nx = 0;
    if (over != NULL && over != Py_None) {
        if (!(ofast = PySequence_Fast(over, "overrides"))) return NULL;
        nov = PySequence_Fast_GET_SIZE(ofast);
    }
    if (!(repl = xcalloc((size_t)na, 1)) || !(xhead = xcalloc((size_t)nf, sizeof(int32_t))) ||
        !(ovact = xcalloc((size_t)nov, sizeof(int32_t))) || !(ovn = xcalloc((size_t)nov, sizeof(int32_t))))
        goto done;
    memset(xhead, 0xff, sizeof(int32_t) * (size_t)nf);
    /* the overrides' preconditions: per fact a list of (action) entries */
    for (Py_ssize_t i = 0; i < nov; i++) {
        PyObject *pair = PySequence_Fast_GET_ITEM(ofast, i), *facts = NULL, *ff = NULL;
        int32_t a;
        if (!PyTuple_Check(pair) || PyTuple_GET_SIZE(pair) != 2) {
            PyErr_SetString(PyExc_TypeError, "overrides: expected (action, facts) pairs");
            goto done;
        }
        if (as_index(PyTuple_GET_ITEM(pair, 0), na, "action", &a) < 0) goto done;
        facts = PyTuple_GET_ITEM(pair, 1);
        if (!(ff = PySequence_Fast(facts, "override facts"))) goto done;
        Py_ssize_t m = PySequence_Fast_GET_SIZE(ff);
        int32_t *na_ = PyMem_Realloc(xact, sizeof(int32_t) * (size_t)(nx + m + 1));
        if (na_ == NULL) { Py_DECREF(ff); PyErr_NoMemory(); goto done; }
        xact = na_;
        int32_t *nn = PyMem_Realloc(xnext, sizeof(int32_t) * (size_t)(nx + m + 1));
        if (nn == NULL) { Py_DECREF(ff); PyErr_NoMemory(); goto done; }
        xnext = nn;
        for (Py_ssize_t j = 0; j < m; j++) {
            int32_t f;
            if (as_index(PySequence_Fast_GET_ITEM(ff, j), nf, "fact", &f) < 0) { Py_DECREF(ff); goto done; }
            xact[nx] = a;
            xnext[nx] = xhead[f];
            xhead[f] = (int32_t)nx++;
        }
        Py_DECREF(ff);
        if (repl[a]) {
            PyErr_SetString(PyExc_ValueError, "overrides: an action given twice");
            goto done;
        }
        repl[a] = 1;
        ovact[i] = a;
        ovn[i] = (int32_t)m;
    }
    double *fcost = k->fcost, *acc = k->acc, *acost = k->acost;
    int32_t *unsat = k->unsat;
    const int32_t *aoff = k->add.off, *av = k->add.v, *boff = k->bypre.off, *bv = k->bypre.v;
    for (int32_t f = 0; f < nf; f++) fcost[f] = INFINITY;
    memcpy(unsat, k->npre, sizeof(int32_t) * (size_t)na);
    memset(acc, 0, sizeof(double) * (size_t)na);
    for (Py_ssize_t i = 0; i < nov; i++) unsat[ovact[i]] = ovn[i];
    XQ q = {0, 0, 0, 0, 0};
    int err = 0, use_max = k->kind == KIND_MAX;
    for (int32_t i = 0; i < ns; i++) { fcost[k->sf[i]] = 0.0; err |= xpush(k, &q, 0.0, k->sf[i]); }
#define FIRE(a_)                                                                            \
    do {                                                                                    \
        double nc_ = acc[a_] + acost[a_];                                                   \
        for (int32_t j_ = aoff[a_]; j_ < aoff[(a_) + 1]; j_++)                              \
            if (nc_ < fcost[av[j_]]) { fcost[av[j_]] = nc_; err |= xpush(k, &q, nc_, av[j_]); } \
    } while (0)
    for (int32_t i = 0; i < k->nnopre; i++) if (!repl[k->nopre[i]]) FIRE(k->nopre[i]);
    for (Py_ssize_t i = 0; i < nov; i++) if (ovn[i] == 0) FIRE(ovact[i]);
    double c;
    int32_t f;
    while (!err && xpop(k, &q, &c, &f)) {
        if (c > fcost[f]) continue;
        for (int32_t i = boff[f]; i < boff[f + 1]; i++) {
            int32_t a = bv[i];
            if (repl[a]) continue;
            if (use_max) { if (c > acc[a]) acc[a] = c; }
            else acc[a] += c;
            if (--unsat[a] == 0) FIRE(a);
        }
        for (int32_t x = xhead[f]; x >= 0; x = xnext[x]) {
            int32_t a = xact[x];
            if (use_max) { if (c > acc[a]) acc[a] = c; }
            else acc[a] += c;
            if (--unsat[a] == 0) FIRE(a);
        }
    }
#undef FIRE
    xclear(k, &q);
    if (err) goto done;
    if (!(out = PyList_New(nf))) goto done;
    for (int32_t g = 0; g < nf; g++) {
        PyObject *v = cost_object(fcost[g]);
        if (v == NULL) { Py_CLEAR(out); goto done; }
        PyList_SET_ITEM(out, g, v);
    }
done:
    Py_XDECREF(ofast);
    PyMem_Free(repl);
    PyMem_Free(xhead);
    PyMem_Free(xact);
    PyMem_Free(xnext);
    PyMem_Free(ovact);
    PyMem_Free(ovn);
    return out;
}
