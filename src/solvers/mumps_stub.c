/* superjoin: stand-in for mumps_shim.c in a build without MUMPS. Creating a
 * solver fails with SJ_NOT_BUILT; mumps.f90 turns that into a usage error
 * naming the cmake option. */
#include <stdint.h>
#include <stddef.h>

#define SJ_NOT_BUILT -108

int sj_mumps_built(void) { return 0; }

void *sj_mumps_create(int sym, int comm, double null_threshold, int ordering, int alone, int *status)
{
    (void)sym; (void)comm; (void)null_threshold; (void)ordering; (void)alone;
    *status = SJ_NOT_BUILT;
    return NULL;
}
int sj_mumps_pattern(void *h, int64_t n, const int64_t *colptr, const int64_t *rowind, int64_t c1, int64_t c2)
{ (void)h; (void)n; (void)colptr; (void)rowind; (void)c1; (void)c2; return SJ_NOT_BUILT; }
int sj_mumps_analyze(void *h) { (void)h; return SJ_NOT_BUILT; }
int sj_mumps_factorize(void *h, const double *val, double *schur)
{ (void)h; (void)val; (void)schur; return SJ_NOT_BUILT; }
int sj_mumps_set_schur(void *h, int64_t nschur) { (void)h; (void)nschur; return SJ_NOT_BUILT; }
int sj_mumps_solve(void *h, int64_t nrhs, double *x) { (void)h; (void)nrhs; (void)x; return SJ_NOT_BUILT; }
int sj_mumps_inverse_diagonal(void *h, int *ptr, int *irow, double *dinv)
{ (void)h; (void)ptr; (void)irow; (void)dinv; return SJ_NOT_BUILT; }
int sj_mumps_input_norm(void *h, double *x, double *anorm)
{ (void)h; (void)x; *anorm = 0.0; return SJ_NOT_BUILT; }
int64_t sj_mumps_infog(void *h, int i) { (void)h; (void)i; return 0; }
int64_t sj_mumps_info(void *h, int i) { (void)h; (void)i; return 0; }
double sj_mumps_rinfog(void *h, int i) { (void)h; (void)i; return 0.0; }
int64_t sj_mumps_null_pivot(void *h, int64_t k) { (void)h; (void)k; return 0; }
void sj_mumps_free(void *h) { (void)h; }
void sj_mumps_forget(void *h) { (void)h; }
int sj_mumps_set_ordering(void *h, int ordering, int parallel, int par_ordering)
{ (void)h; (void)ordering; (void)parallel; (void)par_ordering; return SJ_NOT_BUILT; }
int sj_mumps_perm_in(void *h, const int64_t *iperm) { (void)h; (void)iperm; return SJ_NOT_BUILT; }
