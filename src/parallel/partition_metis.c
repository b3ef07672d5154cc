/* superjoin: METIS k-way partition of the part graph (src/parallel/partition.f90).
 * The graph arrives 1-based in Fortran int (CSR, both directions of every
 * edge); it is copied to METIS's idx_t 0-based arrays, partitioned with a
 * fixed seed (deterministic), and the owner of each vertex returned 0-based.
 * Returns 0 on success, else METIS's status (or -1: no memory). */
#include <stdlib.h>
#include "metis.h"

int sj_metis_partition(int n, int ncon, const int *xadj, const int *adjncy, const int *vwgt,
                       const int *adjwgt, int nparts, int *part, int *cut)
{
    idx_t nv = n, nc = ncon, np = nparts, objval = 0, i;
    idx_t nadj = xadj[n] - 1;
    idx_t options[METIS_NOPTIONS];
    idx_t *x = malloc((size_t)(n + 1) * sizeof(idx_t));
    idx_t *a = malloc((size_t)(nadj > 0 ? nadj : 1) * sizeof(idx_t));
    idx_t *w = malloc((size_t)(n > 0 ? n * ncon : 1) * sizeof(idx_t));
    idx_t *ew = malloc((size_t)(nadj > 0 ? nadj : 1) * sizeof(idx_t));
    idx_t *p = malloc((size_t)(n > 0 ? n : 1) * sizeof(idx_t));
    int status = -1;
    if (x && a && w && ew && p) {
        for (i = 0; i <= nv; i++) x[i] = (idx_t)(xadj[i] - 1);
        for (i = 0; i < nadj; i++) { a[i] = (idx_t)(adjncy[i] - 1); ew[i] = (idx_t)adjwgt[i]; }
        for (i = 0; i < nv * nc; i++) w[i] = (idx_t)vwgt[i];
        METIS_SetDefaultOptions(options);
        options[METIS_OPTION_SEED] = 1;
        options[METIS_OPTION_NUMBERING] = 0;
        status = METIS_PartGraphKway(&nv, &nc, x, a, w, NULL, ew, &np, NULL, NULL, options, &objval, p);
        if (status == METIS_OK) {
            for (i = 0; i < nv; i++) part[i] = (int)p[i];
            *cut = (int)objval;
            status = 0;
        }
    }
    free(x); free(a); free(w); free(ew); free(p);
    return status;
}
