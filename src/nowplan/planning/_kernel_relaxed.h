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

/* first_achievers(state, order, families) -> for each fact set, its first achievers ascending
 * (mirrors nowplan/planning/lm_orders.py prime_first_achievers: the labelled propagation, a bit per
 * set, over the actions of order, the relaxation's breadth-first order from state). */
static PyObject *Kernel_first_achievers(Kernel *k, PyObject *args) {
    PyObject *state, *order_o, *fams_o, *out = NULL;
    if (!PyArg_ParseTuple(args, "OOO", &state, &order_o, &fams_o)) return NULL;
    int32_t ns = load_state(k, state);
    if (ns < 0) return NULL;
    int32_t na = k->na, nf = k->nf, norder = 0;
    Py_ssize_t nfam_s = PyObject_Length(fams_o);
    if (nfam_s < 0) return NULL;
    if (nfam_s >= INT32_MAX / 2) { PyErr_SetString(PyExc_ValueError, "too many fact sets"); return NULL; }
    int32_t nfam = (int32_t)nfam_s, W = (nfam + 63) / 64;
    size_t w = (size_t)(W ? W : 1);
    int32_t *order = NULL, *queue = NULL;
    CSR fam = {NULL, NULL};
    uint64_t *bitof = NULL, *amask = NULL, *need = NULL, *u = NULL;
    uint8_t *has = NULL, *reach = NULL, *pend = NULL;
    if (build_list(order_o, na, "order", &order, &norder) < 0) goto done;
    if (build_csr(fams_o, nfam, nf, "families", &fam) < 0) goto done;
    if (!(bitof = xcalloc((size_t)nf * w, 8)) || !(amask = xcalloc((size_t)na * w, 8)) ||
        !(need = xcalloc((size_t)nf * w, 8)) || !(u = xcalloc(w, 8)) || !(has = xcalloc((size_t)nf, 1)) ||
        !(reach = xcalloc((size_t)na, 1)) || !(pend = xcalloc((size_t)na, 1)) ||
        !(queue = xcalloc((size_t)na, sizeof(int32_t))))
        goto done;
    for (int32_t q = 0; q < nfam; q++)
        for (int32_t j = fam.off[q]; j < fam.off[q + 1]; j++) bitof[(size_t)fam.v[j] * w + (q >> 6)] |= (uint64_t)1 << (q & 63);
    for (int32_t a = 0; a < na; a++)
        for (int32_t j = k->add.off[a]; j < k->add.off[a + 1]; j++)
            for (size_t x = 0; x < w; x++) amask[(size_t)a * w + x] |= bitof[(size_t)k->add.v[j] * w + x];
    for (int32_t i = 0; i < ns; i++) {
        int32_t f = k->sf[i];
        has[f] = 1;
        memcpy(&need[(size_t)f * w], &bitof[(size_t)f * w], w * 8);
    }
    /* the queue: a ring of at most na pending actions, first in first out */
    int32_t head = 0, count = 0;
    for (int32_t i = 0; i < norder; i++) {
        int32_t a = order[i];
        reach[a] = 1;
        if (!pend[a]) { pend[a] = 1; queue[(head + count++) % na] = a; }
    }
    while (count > 0) {
        int32_t a = queue[head];
        head = (head + 1) % na;
        count--;
        pend[a] = 0;
        memcpy(u, &amask[(size_t)a * w], w * 8);
        int unreached = 0;
        for (int32_t j = k->pre.off[a]; j < k->pre.off[a + 1]; j++) {
            int32_t p = k->pre.v[j];
            if (!has[p]) { unreached = 1; break; }
            for (size_t x = 0; x < w; x++) u[x] |= need[(size_t)p * w + x];
        }
        if (unreached) continue;
        for (int32_t j = k->add.off[a]; j < k->add.off[a + 1]; j++) {
            int32_t e = k->add.v[j];
            if (BIT(k->bits, e)) continue;  /* true now: its label stays */
            uint64_t *ne = &need[(size_t)e * w];
            int changed = 0;
            if (!has[e]) { has[e] = 1; memcpy(ne, u, w * 8); changed = 1; }
            else
                for (size_t x = 0; x < w; x++) {
                    uint64_t v = ne[x] & u[x];
                    if (v != ne[x]) { ne[x] = v; changed = 1; }
                }
            if (!changed) continue;
            for (int32_t t = k->bypre.off[e]; t < k->bypre.off[e + 1]; t++) {
                int32_t b = k->bypre.v[t];
                if (!pend[b] && reach[b]) { pend[b] = 1; queue[(head + count++) % na] = b; }
            }
        }
    }
    if (!(out = PyList_New(nfam))) goto done;
    for (int32_t q = 0; q < nfam; q++) {
        PyObject *l = PyList_New(0);
        if (l == NULL) { Py_CLEAR(out); goto done; }
        PyList_SET_ITEM(out, q, l);
    }
    for (int32_t a = 0; a < na; a++) {
        if (!reach[a]) continue;
        for (int32_t q = 0; q < nfam; q++) {
            if (!((amask[(size_t)a * w + (q >> 6)] >> (q & 63)) & 1u)) continue;
            int needs = 0;
            for (int32_t j = k->pre.off[a]; j < k->pre.off[a + 1] && !needs; j++)
                needs = (int)((need[(size_t)k->pre.v[j] * w + (q >> 6)] >> (q & 63)) & 1u);
            if (needs) continue;
            PyObject *x = PyLong_FromLong(a);
            if (x == NULL || PyList_Append(PyList_GET_ITEM(out, q), x) < 0) { Py_XDECREF(x); Py_CLEAR(out); goto done; }
            Py_DECREF(x);
        }
    }
done:
    free_csr(&fam);
    PyMem_Free(order);
    PyMem_Free(queue);
    PyMem_Free(bitof);
    PyMem_Free(amask);
    PyMem_Free(need);
    PyMem_Free(u);
    PyMem_Free(has);
    PyMem_Free(reach);
    PyMem_Free(pend);
    return out;
}

/* landmark_sets(state, order) -> LM(f) for every fact: a frozenset, or None where the propagation over
 * the actions of order (the relaxation's breadth-first order, or a part of it) never reaches f.
 * Mirrors nowplan/planning/landmarks.py landmark_sets (Zhu and Givan's fixpoint; sorted arrays). */
static PyObject *Kernel_landmark_sets(Kernel *k, PyObject *args) {
    PyObject *state, *order_o, *out = NULL;
    if (!PyArg_ParseTuple(args, "OO", &state, &order_o)) return NULL;
    int32_t ns = load_state(k, state);
    if (ns < 0) return NULL;
    int32_t na = k->na, nf = k->nf, norder = 0;
    int32_t *order = NULL, *queue = NULL, *len = NULL, *buf = NULL, **set = NULL;
    uint32_t *stamp = NULL, cur = 0;
    uint8_t *has = NULL, *pend = NULL, *inorder = NULL;
    if (build_list(order_o, na, "order", &order, &norder) < 0) goto done;
    if (!(set = xcalloc((size_t)nf, sizeof(int32_t *))) || !(len = xcalloc((size_t)nf, sizeof(int32_t))) ||
        !(buf = xcalloc((size_t)nf + 1, sizeof(int32_t))) || !(stamp = xcalloc((size_t)nf, sizeof(uint32_t))) ||
        !(has = xcalloc((size_t)nf, 1)) || !(pend = xcalloc((size_t)na, 1)) || !(inorder = xcalloc((size_t)na, 1)) ||
        !(queue = xcalloc((size_t)na, sizeof(int32_t))))
        goto done;
    for (int32_t i = 0; i < ns; i++) {
        int32_t f = k->sf[i];
        if (!(set[f] = PyMem_Malloc(sizeof(int32_t)))) { PyErr_NoMemory(); goto done; }
        set[f][0] = f;
        len[f] = 1;
        has[f] = 1;
    }
    int32_t head = 0, count = 0;
    for (int32_t i = 0; i < norder; i++) {
        int32_t a = order[i];
        inorder[a] = 1;
        if (!pend[a]) { pend[a] = 1; queue[(head + count++) % na] = a; }
    }
    while (count > 0) {
        int32_t a = queue[head];
        head = (head + 1) % na;
        count--;
        pend[a] = 0;
        int ready = 1;
        for (int32_t j = k->pre.off[a]; j < k->pre.off[a + 1] && ready; j++) ready = has[k->pre.v[j]];
        if (!ready) continue;
        if (++cur == 0) { memset(stamp, 0, sizeof(uint32_t) * (size_t)nf); cur = 1; }
        int32_t nb = 0;  /* the union of the preconditions' sets, marked with cur */
        for (int32_t j = k->pre.off[a]; j < k->pre.off[a + 1]; j++) {
            int32_t p = k->pre.v[j];
            for (int32_t i = 0; i < len[p]; i++) {
                int32_t x = set[p][i];
                if (stamp[x] != cur) { stamp[x] = cur; buf[nb++] = x; }
            }
        }
        for (int32_t j = k->add.off[a]; j < k->add.off[a + 1]; j++) {
            int32_t e = k->add.v[j];
            if (BIT(k->bits, e)) continue;  /* true now: LM(e) = {e} */
            int changed;
            if (!has[e]) {
                int32_t n = nb + (stamp[e] != cur);
                int32_t *arr = PyMem_Malloc(sizeof(int32_t) * (size_t)(n ? n : 1));
                if (arr == NULL) { PyErr_NoMemory(); goto done; }
                memcpy(arr, buf, sizeof(int32_t) * (size_t)nb);
                if (n > nb) arr[nb] = e;
                qsort(arr, (size_t)n, sizeof(int32_t), cmp_i32);
                set[e] = arr;
                len[e] = n;
                has[e] = 1;
                changed = 1;
            } else {  /* LM(e) & (union | {e}): shrinks in place, stays sorted */
                int32_t m = 0, *old = set[e];
                for (int32_t i = 0; i < len[e]; i++)
                    if (stamp[old[i]] == cur || old[i] == e) old[m++] = old[i];
                changed = m != len[e];
                len[e] = m;
            }
            if (!changed) continue;
            for (int32_t t = k->bypre.off[e]; t < k->bypre.off[e + 1]; t++) {
                int32_t b = k->bypre.v[t];
                if (!pend[b] && inorder[b]) { pend[b] = 1; queue[(head + count++) % na] = b; }
            }
        }
    }
    if (!(out = PyList_New(nf))) goto done;
    for (int32_t f = 0; f < nf; f++) {
        PyObject *item;
        if (!has[f]) {
            item = Py_None;
            Py_INCREF(item);
        } else {
            PyObject *ids = id_list(set[f], len[f]);
            if (ids == NULL) { Py_CLEAR(out); goto done; }
            item = PyFrozenSet_New(ids);
            Py_DECREF(ids);
            if (item == NULL) { Py_CLEAR(out); goto done; }
        }
        PyList_SET_ITEM(out, f, item);
    }
done:
    if (set != NULL)
        for (int32_t f = 0; f < nf; f++) PyMem_Free(set[f]);
    PyMem_Free(set);
    PyMem_Free(order);
    PyMem_Free(queue);
    PyMem_Free(len);
    PyMem_Free(buf);
    PyMem_Free(stamp);
    PyMem_Free(has);
    PyMem_Free(pend);
    PyMem_Free(inorder);
    return out;
}
