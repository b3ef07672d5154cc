/*
 * umfpack_shim.c -- a thin C layer between superjoin (Fortran) and UMFPACK.
 *
 * umfpack_dl_get_numeric takes twelve arguments: the factors L and U, the
 * permutations, the diagonal of U, the row scaling and the Numeric object.
 * superjoin only reads the permutations, the diagonal and the scaling, so
 * its Fortran interface goes through sj_umfpack_get_diagonal, which passes
 * NULL for L and U (UMFPACK then leaves them out).
 */
#include <stddef.h>

#include "umfpack.h"

/* P, Q, Dx, *do_recip and Rs of the factorization held by numeric, as
 * umfpack_dl_get_numeric returns them; any of the five may be NULL (not
 * wanted). Returns UMFPACK's status (UMFPACK_OK = 0). */
SuiteSparse_long sj_umfpack_get_diagonal(void *numeric, SuiteSparse_long *p, SuiteSparse_long *q,
                                         double *dx, SuiteSparse_long *do_recip, double *rs)
{
    return umfpack_dl_get_numeric(NULL, NULL, NULL, NULL, NULL, NULL, p, q, dx, do_recip, rs, numeric);
}
