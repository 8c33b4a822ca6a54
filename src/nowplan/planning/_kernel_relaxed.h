/* The delete relaxation's breadth-first action order from a state, for the landmark graph
 * (mirrors nowplan/planning/lm_orders.py relaxed_order: the same order, the same reached facts).
 * Every action counts, the rules of derived predicates too (the landmark graph's relaxed task). */

static PyObject *Kernel_relaxed_order(Kernel *k, PyObject *state) {
    int32_t ns = load_state(k, state);
    if (ns < 0) return NULL;
    int32_t na = k->na, nf = k->nf, norder = 0, nfront = 0, nreached = 0;
    int32_t *missing = PyMem_Malloc(sizeof(int32_t) * (size_t)(na ? na : 1));
    int32_t *order = PyMem_Malloc(sizeof(int32_t) * (size_t)(na ? na : 1));
    int32_t *front = PyMem_Malloc(sizeof(int32_t) * (size_t)(nf ? nf : 1));
    uint8_t *reached = xcalloc((size_t)nf, 1);
    PyObject *out = NULL, *ol = NULL, *rl = NULL;
    if (missing == NULL || order == NULL || front == NULL || reached == NULL) { PyErr_NoMemory(); goto done; }
    for (int32_t a = 0; a < na; a++) {
        missing[a] = k->npre[a];
        if (missing[a] == 0) order[norder++] = a;
    }
    for (int32_t i = 0; i < ns; i++) {  /* the state's facts, ascending */
        reached[k->sf[i]] = 1;
        front[nfront++] = k->sf[i];
    }
    int32_t i = 0;
    while (nfront > 0 || i < norder) {
        for (; i < norder; i++) {
            int32_t a = order[i];
            for (int32_t j = k->add.off[a]; j < k->add.off[a + 1]; j++) {
                int32_t e = k->add.v[j];
                if (!reached[e]) { reached[e] = 1; front[nfront++] = e; }
            }
        }
        for (int32_t q = 0; q < nfront; q++) {
            int32_t f = front[q];
            for (int32_t j = k->bypre.off[f]; j < k->bypre.off[f + 1]; j++) {
                int32_t a = k->bypre.v[j];
                if (--missing[a] == 0) order[norder++] = a;
            }
        }
        nfront = 0;
    }
    for (int32_t f = 0; f < nf; f++)
        if (reached[f]) front[nreached++] = f;
    if ((ol = id_list(order, norder)) == NULL || (rl = id_list(front, nreached)) == NULL) goto done;
    out = PyTuple_Pack(2, ol, rl);
done:
    Py_XDECREF(ol);
    Py_XDECREF(rl);
    PyMem_Free(missing);
    PyMem_Free(order);
    PyMem_Free(front);
    PyMem_Free(reached);
    return out;
}
