/* superjoin: the MUMPS C interface (dmumps_c) behind a small opaque handle,
 * compiled only when MUMPS is built in (-DSUPERJOIN_MUMPS=ON or
 * -DSUPERJOIN_MPI=ON); mumps_stub.c stands in for it otherwise.
 *
 * The Fortran side (mumps.f90) passes the upper triangle in 1-based CSC with
 * int64 indices and the range of columns whose entries this process
 * contributes; the shim converts them to MUMPS's distributed assembled input
 * (ICNTL(18) = 3: irn_loc, jcn_loc, a_loc, 1-based MUMPS_INT). Right-hand
 * side and solution are centralized on the host (rank 0). Every function is
 * collective: all processes call it in the same order.
 */
#include <dmumps_c.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <limits.h>

int sj_comm_rank(void);   /* src/parallel/comm_*.c */
int sj_comm_agree(int status, int *first);

#define JOB_INIT -1
#define JOB_END -2
#define JOB_ANALYZE 1
#define JOB_FACTORIZE 2
#define JOB_SOLVE 3
#define ICNTL(I) icntl[(I) - 1]
#define CNTL(I) cntl[(I) - 1]
#define INFOG(I) infog[(I) - 1]
#define INFO(I) info[(I) - 1]
#define RINFOG(I) rinfog[(I) - 1]

#define SJ_OK 0
#define SJ_NOMEM -105
#define SJ_TOO_LARGE -106
#define SJ_STATE -107
#define MAX_WORKSPACE_RETRIES 4

typedef struct {
    DMUMPS_STRUC_C id;
    int64_t n;
    int64_t nloc;       /* entries contributed by this process */
    int64_t first;      /* 1-based CSC position of the first local entry */
    MUMPS_INT *irn, *jcn;
    double *a;
    MUMPS_INT *perm;    /* PERM_IN on the host (ICNTL(7) = 1), else NULL */
    MUMPS_INT *schur_vars;  /* LISTVAR_SCHUR (ICNTL(19) = 1), else NULL */
    int initialized;
    int host;           /* rank 0: holds right-hand sides and solutions */
} sj_mumps_t;

int sj_mumps_built(void) { return 1; }

static void call(sj_mumps_t *h, int job)
{
    h->id.job = job;
    dmumps_c(&h->id);
}

/* Start a MUMPS instance: sym 1 (SPD) or 2 (general symmetric), comm the
 * Fortran communicator handle, null_threshold CNTL(3) of the null pivot
 * detection (ICNTL(24) = 1), ordering ICNTL(7). alone: comm is this
 * process's own (MPI_COMM_SELF), nothing is collective over the run. */
void *sj_mumps_create(int sym, int comm, double null_threshold, int ordering, int alone, int *status)
{
    sj_mumps_t *h = calloc(1, sizeof(sj_mumps_t));
    int first;
    /* JOB_INIT is collective: every process enters it or none (a failed
     * allocation on one process alone would leave the others waiting) */
    if (alone ? !h : sj_comm_agree(h ? 0 : 1, &first) != 0) { free(h); *status = SJ_NOMEM; return NULL; }
    h->id.sym = sym;
    h->id.par = 1;
    h->id.comm_fortran = comm;
    h->host = alone || sj_comm_rank() == 0;
    call(h, JOB_INIT);
    *status = h->id.INFOG(1);
    if (*status < 0) return h;
    h->initialized = 1;
    h->id.ICNTL(1) = -1;   /* no error messages on a Fortran unit */
    h->id.ICNTL(2) = -1;   /* no diagnostics */
    h->id.ICNTL(3) = -1;   /* no global information */
    h->id.ICNTL(4) = 0;
    h->id.ICNTL(5) = 0;    /* assembled input */
    h->id.ICNTL(7) = ordering;
    h->id.ICNTL(18) = 3;   /* distributed assembled input */
    h->id.ICNTL(20) = 0;   /* dense right-hand side on the host */
    h->id.ICNTL(21) = 0;   /* solution centralized on the host */
    h->id.ICNTL(24) = 1;   /* null pivot detection */
    h->id.ICNTL(28) = 1;   /* sequential analysis: the same ordering for any number of processes */
    h->id.CNTL(3) = null_threshold;
    h->id.CNTL(5) = 0.0;   /* null pivots: not fixed, listed in pivnul_list */
    h->id.ICNTL(13) = 0;
    h->id.ICNTL(26) = 0;   /* with a Schur complement: solve the interior problem only */
    return h;
}

/* The next analysis condenses the last nschur variables (1-based n-nschur+1
 * .. n) into a Schur complement: ICNTL(19) = 1, the Schur complement
 * centralized on the host; for SYM = 1 and 2 MUMPS fills one triangle of it
 * (its lower triangle by rows, which is the upper triangle of the
 * column-major SCHUR array) and zeros the other. nschur = 0: no Schur. Set
 * after sj_mumps_pattern (which sets n). Local. */
int sj_mumps_set_schur(void *vh, int64_t nschur)
{
    sj_mumps_t *h = vh;
    int64_t i;
    if (!h || !h->initialized) return SJ_STATE;
    free(h->schur_vars);
    h->schur_vars = NULL;
    h->id.listvar_schur = NULL;
    h->id.size_schur = 0;
    h->id.ICNTL(19) = 0;
    if (nschur <= 0) return SJ_OK;
    if (nschur > h->n) return SJ_STATE;
    if (nschur > 46340) return SJ_TOO_LARGE;   /* nschur^2 must be a MUMPS_INT */
    h->schur_vars = malloc((size_t)nschur * sizeof(MUMPS_INT));
    if (!h->schur_vars) return SJ_NOMEM;
    for (i = 0; i < nschur; ++i) h->schur_vars[i] = (MUMPS_INT)(h->n - nschur + 1 + i);
    h->id.ICNTL(19) = 1;
    h->id.size_schur = (MUMPS_INT)nschur;
    h->id.listvar_schur = h->schur_vars;
    return SJ_OK;
}

/* This process's share of the pattern: columns c1..c2 of the upper triangle
 * (colptr, rowind: 1-based, n+1 and nnz entries). Local only (no MUMPS
 * call), so that a failure here can be agreed on before the analysis. */
int sj_mumps_pattern(void *vh, int64_t n, const int64_t *colptr, const int64_t *rowind, int64_t c1, int64_t c2)
{
    sj_mumps_t *h = vh;
    int64_t k, j, m;
    if (!h || !h->initialized) return SJ_STATE;
    if (n > INT_MAX - 1) return SJ_TOO_LARGE;
    free(h->irn); free(h->jcn); free(h->a);
    h->irn = h->jcn = NULL; h->a = NULL;
    h->n = n;
    if (c2 < c1) { c1 = 1; c2 = 0; }
    h->first = c2 >= c1 ? colptr[c1 - 1] : 1;
    h->nloc = c2 >= c1 ? colptr[c2] - colptr[c1 - 1] : 0;
    m = h->nloc > 0 ? h->nloc : 1;
    h->irn = malloc((size_t)m * sizeof(MUMPS_INT));
    h->jcn = malloc((size_t)m * sizeof(MUMPS_INT));
    h->a = calloc((size_t)m, sizeof(double));
    if (!h->irn || !h->jcn || !h->a) return SJ_NOMEM;
    for (j = c1; j <= c2; ++j)
        for (k = colptr[j - 1]; k < colptr[j]; ++k) {
            h->irn[k - h->first] = (MUMPS_INT)rowind[k - 1];
            h->jcn[k - h->first] = (MUMPS_INT)j;
        }
    h->id.n = (MUMPS_INT)n;
    h->id.nnz_loc = h->nloc;
    h->id.nz_loc = h->nloc <= INT_MAX ? (MUMPS_INT)h->nloc : 0;
    h->id.irn_loc = h->irn;
    h->id.jcn_loc = h->jcn;
    h->id.a_loc = h->a;
    return SJ_OK;
}

/* The ordering of the next analysis: ICNTL(7) (sequential analysis), or
 * with parallel = 1 MUMPS's parallel analysis (ICNTL(28) = 2) with the
 * parallel ordering ICNTL(29) (1 PT-SCOTCH, 2 ParMETIS). Local. */
int sj_mumps_set_ordering(void *vh, int ordering, int parallel, int par_ordering)
{
    sj_mumps_t *h = vh;
    if (!h || !h->initialized) return SJ_STATE;
    h->id.ICNTL(7) = ordering;
    h->id.ICNTL(28) = parallel ? 2 : 1;
    h->id.ICNTL(29) = par_ordering;
    return SJ_OK;
}

/* The pivot order handed in (ICNTL(7) = 1): iperm(i) the 1-based position
 * of variable i, n entries, on the host (ignored elsewhere). Set after
 * sj_mumps_pattern (which sets n). Local. */
int sj_mumps_perm_in(void *vh, const int64_t *iperm)
{
    sj_mumps_t *h = vh;
    int64_t i;
    if (!h || !h->initialized) return SJ_STATE;
    free(h->perm);
    h->perm = NULL;
    h->id.perm_in = NULL;
    if (!h->host) return SJ_OK;
    h->perm = malloc((size_t)(h->n > 0 ? h->n : 1) * sizeof(MUMPS_INT));
    if (!h->perm) return SJ_NOMEM;
    for (i = 0; i < h->n; ++i) h->perm[i] = (MUMPS_INT)iperm[i];
    h->id.perm_in = h->perm;
    return SJ_OK;
}

/* Analysis (ordering, symbolic factorization) of the pattern given. */
int sj_mumps_analyze(void *vh)
{
    sj_mumps_t *h = vh;
    if (!h || !h->initialized || !h->irn) return SJ_STATE;
    call(h, JOB_ANALYZE);
    return h->id.INFOG(1);
}

/* Numeric factorization with the values val (the whole upper triangle, CSC
 * order; this process takes its share). With a Schur complement
 * (sj_mumps_set_schur) schur (nschur^2, column-major, on the host) receives
 * it; otherwise schur is not touched. A workspace too small (INFOG(1) = -9
 * or -8) is retried with a larger ICNTL(14), MUMPS's usual remedy. */
int sj_mumps_factorize(void *vh, const double *val, double *schur)
{
    sj_mumps_t *h = vh;
    int r;
    if (!h || !h->initialized || !h->a) return SJ_STATE;
    if (h->nloc > 0) memcpy(h->a, val + (h->first - 1), (size_t)h->nloc * sizeof(double));
    h->id.schur = h->id.ICNTL(19) && h->host ? schur : NULL;
    h->id.schur_lld = h->id.size_schur;
    for (r = 0; r <= MAX_WORKSPACE_RETRIES; ++r) {
        call(h, JOB_FACTORIZE);
        if (h->id.INFOG(1) != -9 && h->id.INFOG(1) != -8) break;
        h->id.ICNTL(14) = 2 * (h->id.ICNTL(14) > 0 ? h->id.ICNTL(14) : 20);
    }
    h->id.schur = NULL;
    return h->id.INFOG(1);
}

/* x = A^-1 b for nrhs columns of length n, in place: x holds b on entry and
 * the solution on return, on the host only (the caller broadcasts it). No
 * allocation here, so that no process can fail alone inside the collective. */
int sj_mumps_solve(void *vh, int64_t nrhs, double *x)
{
    sj_mumps_t *h = vh;
    if (!h || !h->initialized) return SJ_STATE;
    if (nrhs > INT_MAX) return SJ_TOO_LARGE;
    if (h->host) {
        h->id.rhs = x;
        h->id.lrhs = (MUMPS_INT)h->n;
    }
    h->id.nrhs = (MUMPS_INT)nrhs;
    call(h, JOB_SOLVE);
    h->id.rhs = NULL;
    return h->id.INFOG(1);
}

/* The diagonal of A^-1 (MUMPS's computation of selected entries of the
 * inverse, ICNTL(30) = 1) into dinv(n) on the host; ptr(n+1) and irow(n)
 * are the caller's work arrays (allocated, and agreed on, before this
 * collective call). */
int sj_mumps_inverse_diagonal(void *vh, MUMPS_INT *ptr, MUMPS_INT *irow, double *dinv)
{
    sj_mumps_t *h = vh;
    int64_t j;
    int st;
    if (!h || !h->initialized) return SJ_STATE;
    if (h->host) {
        for (j = 0; j < h->n; ++j) { ptr[j] = (MUMPS_INT)(j + 1); irow[j] = (MUMPS_INT)(j + 1); }
        ptr[h->n] = (MUMPS_INT)(h->n + 1);
        h->id.irhs_ptr = ptr;
        h->id.irhs_sparse = irow;
        h->id.rhs_sparse = dinv;
        h->id.nz_rhs = (MUMPS_INT)h->n;
    }
    h->id.nrhs = (MUMPS_INT)h->n;
    h->id.ICNTL(30) = 1;
    call(h, JOB_SOLVE);
    st = h->id.INFOG(1);
    h->id.ICNTL(30) = 0;
    h->id.irhs_ptr = NULL; h->id.irhs_sparse = NULL; h->id.rhs_sparse = NULL; h->id.nz_rhs = 0;
    return st;
}

/* The infinity norm of the matrix MUMPS factored (the sum of every
 * process's entries), RINFOG(4) of a solve with the main error statistics
 * (ICNTL(11) = 2) for the one right-hand side x(n) on the host; x becomes
 * its solution. *anorm is set on every process (RINFOG is global). */
int sj_mumps_input_norm(void *vh, double *x, double *anorm)
{
    sj_mumps_t *h = vh;
    int st;
    *anorm = 0.0;
    if (!h || !h->initialized) return SJ_STATE;
    if (h->host) {
        h->id.rhs = x;
        h->id.lrhs = (MUMPS_INT)h->n;
    }
    h->id.nrhs = 1;
    h->id.ICNTL(11) = 2;
    call(h, JOB_SOLVE);
    st = h->id.INFOG(1);
    h->id.ICNTL(11) = 0;
    h->id.rhs = NULL;
    *anorm = h->id.RINFOG(4);
    return st;
}

/* INFOG(i), RINFOG(i) and INFO(i) (1-based as in the MUMPS guide). */
int64_t sj_mumps_infog(void *vh, int i) { sj_mumps_t *h = vh; return h ? h->id.INFOG(i) : 0; }
int64_t sj_mumps_info(void *vh, int i) { sj_mumps_t *h = vh; return h ? h->id.INFO(i) : 0; }
double sj_mumps_rinfog(void *vh, int i) { sj_mumps_t *h = vh; return h ? h->id.RINFOG(i) : 0.0; }

/* The k-th (1-based) null pivot column of the last factorization (host only). */
int64_t sj_mumps_null_pivot(void *vh, int64_t k)
{
    sj_mumps_t *h = vh;
    if (!h || !h->id.pivnul_list || k < 1 || k > h->id.INFOG(28) || !h->host) return 0;
    return h->id.pivnul_list[k - 1];
}

void sj_mumps_free(void *vh)
{
    sj_mumps_t *h = vh;
    if (!h) return;
    if (h->initialized) call(h, JOB_END);
    free(h->irn); free(h->jcn); free(h->a); free(h->perm); free(h->schur_vars);
    free(h);
}

/* Free the shim's arrays without ending the MUMPS instance (no collective
 * call): for a finalizer that may run on one process only. */
void sj_mumps_forget(void *vh)
{
    sj_mumps_t *h = vh;
    if (!h) return;
    free(h->irn); free(h->jcn); free(h->a); free(h->perm); free(h->schur_vars);
    free(h);
}
