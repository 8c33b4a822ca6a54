/* The rules of derived predicates (axioms): axioms.py's AxiomEvaluator over bitset states.
 *
 * Included once by _kernel.c before Kernel_new.  After an action's effects, the derived
 * facts (dmask) are cleared and the rules evaluated layer by layer, each to its least
 * fixpoint, by counting each rule's unmet conditions; after a layer, "not d" is set for
 * each of its derived atoms d that stayed false.  The rules are also actions [nact, na) of
 * the relaxation (cost 0), where the search never applies them.
 */

/* axioms = (bodies, heads, layers [(lo, hi)], negs [[d, not d, ...] per layer], derived facts) */
static int build_axioms(Kernel *k, PyObject *axioms) {
    PyObject *body, *heads, *layers, *negs, *derived;
    if (!PyArg_ParseTuple(axioms, "OOOOO", &body, &heads, &layers, &negs, &derived)) return -1;
    int32_t nd = 0, *dl = NULL;
    if (build_list(heads, k->nf, "axiom head", &k->axhead, &k->nax) < 0) return -1;
    if (build_csr(body, k->nax, k->nf, "axiom body", &k->axbody) < 0) return -1;
    Py_ssize_t nl = PyObject_Length(layers);
    if (nl < 0) return -1;
    k->nlayers = (int32_t)nl;
    if (build_csr(negs, k->nlayers, k->nf, "axiom negations", &k->negs) < 0) return -1;
    if (!(k->laylo = xcalloc((size_t)nl, sizeof(int32_t))) || !(k->layhi = xcalloc((size_t)nl, sizeof(int32_t))))
        return -1;
    for (Py_ssize_t i = 0; i < nl; i++) {
        PyObject *pair = PySequence_GetItem(layers, i);
        if (pair == NULL) return -1;
        int lo, hi;
        int ok = PyArg_ParseTuple(pair, "ii", &lo, &hi);
        Py_DECREF(pair);
        if (!ok) return -1;
        if (lo < 0 || hi < lo || hi > k->nax) { PyErr_SetString(PyExc_ValueError, "axiom layer out of range"); return -1; }
        k->laylo[i] = lo;
        k->layhi[i] = hi;
    }
    if (build_list(derived, k->nf, "derived fact", &dl, &nd) < 0) return -1;
    if (!(k->dmask = xcalloc((size_t)k->words + 1, sizeof(uint64_t)))) { PyMem_Free(dl); return -1; }
    for (int32_t i = 0; i < nd; i++) SETBIT(k->dmask, dl[i]);
    PyMem_Free(dl);
    size_t nax1 = (size_t)(k->nax ? k->nax : 1);
    if (!(k->axnbody = xcalloc(nax1, sizeof(int32_t))) || !(k->axunsat = xcalloc(nax1, sizeof(int32_t))) ||
        !(k->axqueue = xcalloc(nax1, sizeof(int32_t))))
        return -1;
    /* fact -> the rules that need it (CSR) */
    if (!(k->axby.off = xcalloc((size_t)k->nf + 1, sizeof(int32_t)))) return -1;
    int32_t total = k->axbody.off[k->nax];
    if (!(k->axby.v = xcalloc((size_t)total, sizeof(int32_t)))) return -1;
    for (int32_t r = 0; r < k->nax; r++) {
        k->axnbody[r] = k->axbody.off[r + 1] - k->axbody.off[r];
        for (int32_t j = k->axbody.off[r]; j < k->axbody.off[r + 1]; j++) k->axby.off[k->axbody.v[j] + 1]++;
    }
    for (int32_t f = 0; f < k->nf; f++) k->axby.off[f + 1] += k->axby.off[f];
    int32_t *fill = xcalloc((size_t)k->nf, sizeof(int32_t));
    if (fill == NULL) return -1;
    for (int32_t r = 0; r < k->nax; r++)
        for (int32_t j = k->axbody.off[r]; j < k->axbody.off[r + 1]; j++) {
            int32_t f = k->axbody.v[j];
            k->axby.v[k->axby.off[f] + fill[f]++] = r;
        }
    PyMem_Free(fill);
    for (int32_t L = 0; L < k->nlayers; L++)
        if ((k->negs.off[L + 1] - k->negs.off[L]) % 2) {
            PyErr_SetString(PyExc_ValueError, "axiom negations: (d, not d) pairs expected");
            return -1;
        }
    return 0;
}

/* bits := its base facts closed under the rules (derived facts recomputed). */
static void axioms_eval(Kernel *k, uint64_t *bits) {
    int32_t *unsat = k->axunsat, *queue = k->axqueue, *head = k->axhead;
    const int32_t *byoff = k->axby.off, *byv = k->axby.v;
    for (int32_t w = 0; w < k->words; w++) bits[w] &= ~k->dmask[w];
    memcpy(unsat, k->axnbody, sizeof(int32_t) * (size_t)k->nax);
    for (int32_t w = 0; w < k->words; w++)
        for (uint64_t x = bits[w]; x; x &= x - 1) {
            int32_t f = w * 64 + __builtin_ctzll(x);
            for (int32_t j = byoff[f]; j < byoff[f + 1]; j++) unsat[byv[j]]--;
        }
    for (int32_t L = 0; L < k->nlayers; L++) {
        int32_t lo = k->laylo[L], hi = k->layhi[L], qn = 0;
        for (int32_t r = lo; r < hi; r++)
            if (unsat[r] == 0) queue[qn++] = head[r];
        while (qn) {
            int32_t h = queue[--qn];
            if (BIT(bits, h)) continue;
            SETBIT(bits, h);
            for (int32_t j = byoff[h]; j < byoff[h + 1]; j++) {
                int32_t r = byv[j];
                if (--unsat[r] == 0 && r >= lo && r < hi) queue[qn++] = head[r];
            }
        }
        for (int32_t i = k->negs.off[L]; i + 1 < k->negs.off[L + 1]; i += 2) {
            int32_t d = k->negs.v[i], nd = k->negs.v[i + 1];
            if (BIT(bits, d) || BIT(bits, nd)) continue;
            SETBIT(bits, nd);
            for (int32_t j = byoff[nd]; j < byoff[nd + 1]; j++) unsat[byv[j]]--;
        }
    }
}
