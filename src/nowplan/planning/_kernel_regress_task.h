/* The regression loop's ground task (_kernel_regress.c): a problem's ground actions as fact ids, given once
 * (use_task), so that a fact whose achievers are exactly the task's actions adding it (Grounder.task_answers)
 * gets them here (task_achievers) without a Python template per action.
 *
 * A task action registered here has the facts ActionFacts gives it at the store's top level: every effect
 * (all_effs), one effect per fluent in the order of the fluents' first effects, the later effect winning
 * (eff_fl), the effects' conflict keys in that order (eff_keys), whether two effects share a key
 * (self_clash), and the kept preconditions (pre).  Profile that led here: registering a fact's achievers
 * through Python (need: the grounder's answer, one ActionFacts per action, add_action) was 78 % of a
 * compiled search's CPU on flat logistics-10. */

/* a sequence of int sequences, flattened into `flat` with each row's start and length (n rows) */
static int read_rows(PyObject *seq, const char *what, Py_ssize_t n, Vec *flat, int32_t *start, int32_t *len,
                     int32_t nf) {
    PyObject *fast = PySequence_Fast(seq, what);
    if (fast == NULL) return -1;
    if (PySequence_Fast_GET_SIZE(fast) != n) {
        Py_DECREF(fast);
        PyErr_Format(PyExc_ValueError, "%s: one row per task action", what);
        return -1;
    }
    for (Py_ssize_t k = 0; k < n; k++) {
        size_t s0 = flat->n;
        if (read_ints(PySequence_Fast_GET_ITEM(fast, k), what, flat) < 0) { Py_DECREF(fast); return -1; }
        for (size_t i = s0; i < flat->n; i++)
            if (flat->v[i] >= nf) {
                Py_DECREF(fast);
                PyErr_Format(PyExc_ValueError, "%s: fact id not added", what);
                return -1;
            }
        start[k] = (int32_t)s0;
        len[k] = (int32_t)(flat->n - s0);
    }
    Py_DECREF(fast);
    return 0;
}

/* use_task(effects, pre, cost): per task action its effects, its kept preconditions and its cost (once) */
static PyObject *Regressor_use_task(Regressor *R, PyObject *args) {
    PyObject *effs, *pre, *cost;
    if (!PyArg_ParseTuple(args, "OOO", &effs, &pre, &cost)) return NULL;
    if (R->tact != NULL) { PyErr_SetString(PyExc_RuntimeError, "use_task: the task is given once"); return NULL; }
    PyObject *cf = PySequence_Fast(cost, "cost");
    if (cf == NULL) return NULL;
    Py_ssize_t n = PySequence_Fast_GET_SIZE(cf);
    size_t cap = (size_t)n + 1;
    int32_t **arr[] = {&R->tes, &R->tel, &R->tps, &R->tpl, &R->tact};
    for (size_t i = 0; i < 5; i++) {
        *arr[i] = PyMem_Calloc(cap, sizeof(int32_t));
        if (*arr[i] == NULL) { Py_DECREF(cf); PyErr_NoMemory(); return NULL; }
    }
    R->tcost = PyMem_Calloc(cap, sizeof(double));
    R->tadd_start = PyMem_Calloc((size_t)R->nf + 2, sizeof(int32_t));
    if (R->tcost == NULL || R->tadd_start == NULL) { Py_DECREF(cf); PyErr_NoMemory(); return NULL; }
    for (Py_ssize_t k = 0; k < n; k++) {
        R->tcost[k] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(cf, k));
        if (R->tcost[k] == -1.0 && PyErr_Occurred()) { Py_DECREF(cf); return NULL; }
        R->tact[k] = -1;
    }
    Py_DECREF(cf);
    if (read_rows(effs, "effects", n, &R->teff, R->tes, R->tel, R->nf) < 0 ||
        read_rows(pre, "pre", n, &R->tpre, R->tps, R->tpl, R->nf) < 0)
        return NULL;
    /* per fact the actions that add it, ascending (counting sort) */
    int32_t nf = R->nf;
    for (size_t i = 0; i < R->teff.n; i++) R->tadd_start[R->teff.v[i] + 1]++;
    for (int32_t f = 0; f < nf; f++) R->tadd_start[f + 1] += R->tadd_start[f];
    R->tadd.n = 0;
    for (size_t i = 0; i < R->teff.n; i++)
        if (vpush(&R->tadd, 0) < 0) return NULL;
    int32_t *fill = PyMem_Calloc((size_t)nf + 1, sizeof(int32_t));
    if (fill == NULL) { PyErr_NoMemory(); return NULL; }
    for (Py_ssize_t k = 0; k < n; k++)
        for (int32_t i = 0; i < R->tel[k]; i++) {
            int32_t e = R->teff.v[R->tes[k] + i];
            R->tadd.v[R->tadd_start[e] + fill[e]++] = (int32_t)k;
        }
    PyMem_Free(fill);
    R->ntask = (int32_t)n;
    R->ntf = nf;
    Py_RETURN_NONE;
}

/* task action k registered as an action of the store (once): its index, or -1 with an error set */
static int32_t task_action(Regressor *R, int32_t k) {
    if (R->tact[k] >= 0) return R->tact[k];
    if (reserve_action(R) < 0) return -1;
    int32_t a = R->na;
    size_t e0 = R->effs.n, k0 = R->ekeys.n, p0 = R->pres.n, x0 = R->alls.n;
    const int32_t *te = R->teff.v + R->tes[k];
    for (int32_t i = 0; i < R->tel[k]; i++) {
        int32_t e = te[i], fl = R->fluent[e];
        if (vpush(&R->alls, e) < 0) return -1;
        size_t j = e0;
        while (j < R->effs.n && R->effs.v[j] != fl) j += 2;
        if (j < R->effs.n) R->effs.v[j + 1] = e;  /* a later effect on the fluent wins */
        else if (vpush(&R->effs, fl) < 0 || vpush(&R->effs, e) < 0) return -1;
    }
    int clash = 0;
    for (size_t j = e0; j < R->effs.n; j += 2) {
        int32_t f = R->effs.v[j + 1];
        for (int32_t i = 0; i < R->klen[f]; i++) {
            int32_t key = R->keys.v[R->kstart[f] + i];
            for (size_t m = k0; m < R->ekeys.n; m += 2)
                if (R->ekeys.v[m] == key && R->ekeys.v[m + 1] != f) clash = 1;
            if (vpush(&R->ekeys, key) < 0 || vpush(&R->ekeys, f) < 0) return -1;
        }
    }
    for (int32_t i = 0; i < R->tpl[k]; i++)
        if (vpush(&R->pres, R->tpre.v[R->tps[k] + i]) < 0) return -1;
    R->es[a] = (int32_t)e0; R->el[a] = (int32_t)((R->effs.n - e0) / 2);
    R->ks[a] = (int32_t)k0; R->kl[a] = (int32_t)((R->ekeys.n - k0) / 2);
    R->ps[a] = (int32_t)p0; R->pl[a] = (int32_t)(R->pres.n - p0);
    R->as[a] = (int32_t)x0; R->al[a] = (int32_t)(R->alls.n - x0);
    R->clash[a] = (uint8_t)clash;
    R->cost[a] = R->tcost[k];
    R->src[a] = k;
    R->tact[k] = a;
    R->na++;
    return a;
}

static int task_index_ok(Regressor *R, long k) {
    if (R->tact == NULL) { PyErr_SetString(PyExc_RuntimeError, "no task given (use_task)"); return 0; }
    if (k < 0 || k >= R->ntask) { PyErr_SetString(PyExc_IndexError, "task action out of range"); return 0; }
    return 1;
}

/* add_task_action(k) -> index: task action k as an action of the store (the same index each time) */
static PyObject *Regressor_add_task_action(Regressor *R, PyObject *arg) {
    long k = PyLong_AsLong(arg);
    if (k == -1 && PyErr_Occurred()) return NULL;
    if (!task_index_ok(R, k)) return NULL;
    int32_t a = task_action(R, (int32_t)k);
    return a < 0 ? NULL : PyLong_FromLong(a);
}

/* task_achievers(fact): the fact's achievers are the task actions that add it, in the task's order */
static PyObject *Regressor_task_achievers(Regressor *R, PyObject *arg) {
    long f = PyLong_AsLong(arg);
    if (f == -1 && PyErr_Occurred()) return NULL;
    if (R->tact == NULL) { PyErr_SetString(PyExc_RuntimeError, "no task given (use_task)"); return NULL; }
    if (f < 0 || f >= R->nf) { PyErr_SetString(PyExc_IndexError, "fact id not added"); return NULL; }
    size_t a0 = R->ach.n;
    if (f < R->ntf)  /* (a fact added after the task adds no task action) */
        for (int32_t i = R->tadd_start[f]; i < R->tadd_start[f + 1]; i++) {
            int32_t k = R->tadd.v[i];
            if (i > R->tadd_start[f] && R->tadd.v[i - 1] == k) continue;  /* one action adding it twice */
            int32_t a = task_action(R, k);
            if (a < 0 || vpush(&R->ach, a) < 0) { R->ach.n = a0; return NULL; }
        }
    R->ach_start[f] = (int32_t)a0;
    R->ach_len[f] = (int32_t)(R->ach.n - a0);
    Py_RETURN_NONE;
}

/* task_index(a) -> the task action behind action a, or -1 (one added by add_action) */
static PyObject *Regressor_task_index(Regressor *R, PyObject *arg) {
    long a = PyLong_AsLong(arg);
    if (a == -1 && PyErr_Occurred()) return NULL;
    if (a < 0 || a >= R->na) { PyErr_SetString(PyExc_IndexError, "action id not added"); return NULL; }
    return PyLong_FromLong(R->src[a]);
}
