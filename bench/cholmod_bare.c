/*
 * cholmod_bare.c -- CHOLMOD on its own, as a yardstick for superjoin's solver.
 *
 * Reads a symmetric Matrix Market file, sets b = A * ones, and times
 * CHOLMOD's analyze, factorize and solve with CHOLMOD's default settings
 * (or, with --superjoin, the settings of src/solvers/cholmod_shim.c:
 * supernodal LL^T always). Prints the phase times (wall clock), the
 * CPU time of the three (user + system), the
 * ordering, nnz(L), CHOLMOD's peak memory (Common->memory_usage), the
 * process's peak resident set (VmHWM from /proc/self/status), and the
 * residual of the solution.
 *
 * It runs on the OpenBLAS kernels superjoin runs on: like superjoin's main it
 * first calls sj_blas_core_setup (src/utils/blas_core.c), which starts the
 * program again with OPENBLAS_CORETYPE set where OpenBLAS fell back to
 * kernels older than the CPU's instructions, and it prints the kernels.
 *
 * Usage:   cholmod_bare [--superjoin] matrix.mtx
 * Build:   gcc -O2 -I/usr/include/suitesparse bench/cholmod_bare.c src/utils/blas_core.c \
 *              -lcholmod -lsuitesparseconfig -lm -o build/cholmod_bare
 * Exit status: 0 solved, 1 usage, 3 not positive definite, 4 I/O or
 * CHOLMOD failure.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cholmod.h"

void sj_blas_core_setup(void);
const char *sj_blas_core_note(void);

enum { EXIT_OK_ = 0, EXIT_USAGE_ = 1, EXIT_NOT_POSDEF_ = 3, EXIT_FAIL_ = 4 };

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1.0e-9 * (double)t.tv_nsec;
}

/* CPU seconds of this process (user + system) so far. */
static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1.0e-9 * (double)t.tv_nsec;
}

/* Peak resident set size of this process in kB (VmHWM), -1 if unknown. */
static long vm_hwm_kb(void)
{
    char line[256];
    long kb = -1;
    FILE *f = fopen("/proc/self/status", "r");
    if (f == NULL) return -1;
    while (fgets(line, sizeof line, f) != NULL) {
        if (strncmp(line, "VmHWM:", 6) == 0) {
            kb = strtol(line + 6, NULL, 10);
            break;
        }
    }
    fclose(f);
    return kb;
}

static const char *ordering_name(int ordering)
{
    switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "natural (postordered)";
    default: return "unknown";
    }
}

/* Entries of L as stored (supernodal: trapezoids including amalgamation zeros). */
static double stored_nnz(const cholmod_factor *L)
{
    double nz = 0.0;
    SuiteSparse_long j, s;
    if (L->is_super) {
        const SuiteSparse_long *super = L->super, *pi = L->pi;
        for (s = 0; s < (SuiteSparse_long)L->nsuper; s++) {
            double nscol = (double)(super[s + 1] - super[s]);
            double nsrow = (double)(pi[s + 1] - pi[s]);
            nz += nscol * nsrow - nscol * (nscol - 1.0) / 2.0;
        }
    } else if (L->nz != NULL) {
        const SuiteSparse_long *cnt = L->nz;
        for (j = 0; j < (SuiteSparse_long)L->n; j++) nz += (double)cnt[j];
    }
    return nz;
}

/* Everything CHOLMOD allocates, freed in one place. */
typedef struct {
    cholmod_sparse *A;
    cholmod_factor *L;
    cholmod_dense *x, *b, *r, *ones;
} objects_t;

static void free_objects(objects_t *o, cholmod_common *cm)
{
    cholmod_l_free_dense(&o->r, cm);
    cholmod_l_free_dense(&o->x, cm);
    cholmod_l_free_dense(&o->b, cm);
    cholmod_l_free_dense(&o->ones, cm);
    cholmod_l_free_factor(&o->L, cm);
    cholmod_l_free_sparse(&o->A, cm);
}

/* Read, analyze, factorize, solve and report; returns the exit status. */
static int run(const char *path, int superjoin_settings, objects_t *o, cholmod_common *cm)
{
    double t0, t_read, t_analyze, t_factor, t_solve, c0, c_work;
    double one[2] = {1.0, 0.0}, minus_one[2] = {-1.0, 0.0}, zero[2] = {0.0, 0.0};
    FILE *f;

    t0 = wall_seconds();
    f = fopen(path, "r");
    if (f == NULL) {
        fprintf(stderr, "cholmod_bare: cannot open '%s'\n", path);
        return EXIT_FAIL_;
    }
    o->A = cholmod_l_read_sparse(f, cm);
    fclose(f);
    t_read = wall_seconds() - t0;
    if (o->A == NULL || o->A->stype == 0 || o->A->nrow != o->A->ncol) {
        fprintf(stderr, "cholmod_bare: '%s' is not a symmetric Matrix Market matrix\n", path);
        return EXIT_FAIL_;
    }

    /* b = A * ones */
    o->ones = cholmod_l_ones(o->A->nrow, 1, o->A->xtype, cm);
    o->b = cholmod_l_zeros(o->A->nrow, 1, o->A->xtype, cm);
    if (o->ones == NULL || o->b == NULL) {
        fprintf(stderr, "cholmod_bare: out of memory\n");
        return EXIT_FAIL_;
    }
    cholmod_l_sdmult(o->A, 0, one, zero, o->ones, o->b, cm);

    c0 = cpu_seconds();
    t0 = wall_seconds();
    o->L = cholmod_l_analyze(o->A, cm);
    t_analyze = wall_seconds() - t0;
    if (o->L == NULL) {
        fprintf(stderr, "cholmod_bare: analyze failed (status %d)\n", cm->status);
        return EXIT_FAIL_;
    }

    t0 = wall_seconds();
    cholmod_l_factorize(o->A, o->L, cm);
    t_factor = wall_seconds() - t0;
    if (cm->status == CHOLMOD_NOT_POSDEF) {
        SuiteSparse_long minor = (SuiteSparse_long)o->L->minor;
        const SuiteSparse_long *perm = o->L->Perm;
        fprintf(stderr, "cholmod_bare: not positive definite at column %ld\n",
                (long)((perm != NULL ? perm[minor] : minor) + 1));
        return EXIT_NOT_POSDEF_;
    }
    if (cm->status < CHOLMOD_OK) {
        fprintf(stderr, "cholmod_bare: factorize failed (status %d)\n", cm->status);
        return EXIT_FAIL_;
    }

    t0 = wall_seconds();
    o->x = cholmod_l_solve(CHOLMOD_A, o->L, o->b, cm);
    t_solve = wall_seconds() - t0;
    c_work = cpu_seconds() - c0;
    if (o->x == NULL) {
        fprintf(stderr, "cholmod_bare: solve failed (status %d)\n", cm->status);
        return EXIT_FAIL_;
    }

    /* r = b - A x */
    o->r = cholmod_l_copy_dense(o->b, cm);
    if (o->r == NULL) {
        fprintf(stderr, "cholmod_bare: out of memory\n");
        return EXIT_FAIL_;
    }
    cholmod_l_sdmult(o->A, 0, minus_one, one, o->x, o->r, cm);

    {
        const cholmod_factor *L = o->L;
        double rnorm = cholmod_l_norm_dense(o->r, 2, cm);
        double bnorm = cholmod_l_norm_dense(o->b, 2, cm);
        double rinf = cholmod_l_norm_dense(o->r, 0, cm);
        double anorm = cholmod_l_norm_sparse(o->A, 0, cm);
        double xinf = cholmod_l_norm_dense(o->x, 0, cm);
        double binf = cholmod_l_norm_dense(o->b, 0, cm);
        double err = 0.0;
        const double *xv = o->x->x;
        size_t k;
        for (k = 0; k < o->x->nrow; k++) err = fmax(err, fabs(xv[k] - 1.0));

        printf("matrix        %s\n", path);
        printf("n             %ld\n", (long)o->A->nrow);
        printf("nnz(A) stored %ld (one triangle)\n", (long)cholmod_l_nnz(o->A, cm));
        printf("settings      %s\n", superjoin_settings ? "superjoin (supernodal LL^T)" : "CHOLMOD defaults");
        printf("factor        %s %s\n", L->is_super ? "supernodal" : "simplicial", L->is_ll ? "LL^T" : "LDL^T");
        printf("ordering      %s\n", ordering_name(L->ordering));
        printf("nnz(L)        %.0f (fundamental), %.0f stored\n", cm->lnz, stored_nnz(L));
        printf("flops         %.4g\n", cm->fl);
        printf("BLAS          %s\n", sj_blas_core_note()[0] ? sj_blas_core_note() : "not OpenBLAS");
        printf("time read     %10.4f s\n", t_read);
        printf("time analyze  %10.4f s\n", t_analyze);
        printf("time factor   %10.4f s\n", t_factor);
        printf("time solve    %10.4f s\n", t_solve);
        printf("cpu analyze+factor+solve %10.4f s\n", c_work);
        printf("peak CHOLMOD  %10.2f MiB\n", (double)cm->memory_usage / 1048576.0);
        printf("peak VmHWM    %10.2f MiB\n", (double)vm_hwm_kb() / 1024.0);
        printf("residual      ||b-Ax||/||b|| = %.3e, ||b-Ax||_inf/(||A|| ||x|| + ||b||)_inf = %.3e\n",
               bnorm > 0.0 ? rnorm / bnorm : rnorm,
               (anorm * xinf + binf) > 0.0 ? rinf / (anorm * xinf + binf) : rinf);
        printf("error         max|x - 1| = %.3e\n", err);
    }
    return EXIT_OK_;
}

int main(int argc, char **argv)
{
    cholmod_common common, *cm = &common;
    objects_t o = {NULL, NULL, NULL, NULL, NULL, NULL};
    const char *path = NULL;
    int superjoin_settings = 0, status, i, bad = 0;

    sj_blas_core_setup();
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--superjoin") == 0) superjoin_settings = 1;
        else if (path == NULL) path = argv[i];
        else bad = 1;
    }
    if (path == NULL || bad) {
        fprintf(stderr, "usage: cholmod_bare [--superjoin] matrix.mtx\n");
        return EXIT_USAGE_;
    }
    if (!cholmod_l_start(cm)) {
        fprintf(stderr, "cholmod_bare: cannot start CHOLMOD\n");
        return EXIT_FAIL_;
    }
    if (superjoin_settings) {
        cm->supernodal = CHOLMOD_SUPERNODAL;
        cm->final_asis = 0;
        cm->final_ll = 1;
        cm->final_super = 1;
    }
    status = run(path, superjoin_settings, &o, cm);
    free_objects(&o, cm);
    cholmod_l_finish(cm);
    return status;
}
