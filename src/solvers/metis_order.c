/* superjoin: METIS nested dissection (METIS_NodeND) of a symmetric matrix's
 * graph, for the ordering superjoin hands MUMPS (ICNTL(7) = 1, PERM_IN;
 * src/solvers/mumps_order.f90). The graph arrives 1-based with int64
 * indices (CSR, both directions of every edge, no self loops); it is copied
 * to METIS's idx_t 0-based arrays and ordered with a fixed seed
 * (deterministic). iperm(i) is the 1-based position of vertex i in the
 * elimination order (METIS's iperm, MUMPS's PERM_IN). Returns 0 on success,
 * -1 without memory, -2 when the graph exceeds idx_t, else METIS's status. */
#include <stdint.h>
#include <stdlib.h>
#include "metis.h"

int sj_metis_nested_dissection(int64_t n, const int64_t *xadj, const int64_t *adjncy, int64_t *iperm)
{
    idx_t nv, i, *x, *a, *perm, *ip;
    idx_t options[METIS_NOPTIONS];
    int64_t nadj, k;
    int status = -1;
    if (n <= 0) return 0;
    nadj = xadj[n] - 1;
    if (sizeof(idx_t) < sizeof(int64_t) && (n > INT32_MAX || nadj > INT32_MAX)) return -2;
    nv = (idx_t)n;
    x = malloc((size_t)(n + 1) * sizeof(idx_t));
    a = malloc((size_t)(nadj > 0 ? nadj : 1) * sizeof(idx_t));
    perm = malloc((size_t)n * sizeof(idx_t));
    ip = malloc((size_t)n * sizeof(idx_t));
    if (x && a && perm && ip) {
        for (i = 0; i <= nv; i++) x[i] = (idx_t)(xadj[i] - 1);
        for (k = 0; k < nadj; k++) a[k] = (idx_t)(adjncy[k] - 1);
        METIS_SetDefaultOptions(options);
        options[METIS_OPTION_SEED] = 1;
        options[METIS_OPTION_NUMBERING] = 0;
        status = METIS_NodeND(&nv, x, a, NULL, options, perm, ip);
        if (status == METIS_OK) {
            for (i = 0; i < nv; i++) iperm[i] = (int64_t)ip[i] + 1;
            status = 0;
        }
    }
    free(x); free(a); free(perm); free(ip);
    return status;
}
