/* superjoin: the communication layer for one process (the default build).
 * Same functions as comm_mpi.c; every collective is the identity. */
#include <stdint.h>

int sj_comm_start(void) { return 0; }
int sj_comm_rank(void) { return 0; }
int sj_comm_size(void) { return 1; }
int sj_comm_is_parallel_build(void) { return 0; }

/* MUMPS's USE_COMM_WORLD: the sequential MUMPS library ignores it. */
int sj_comm_fortran(void) { return -987654; }
int sj_comm_self_fortran(void) { return -987654; }


int sj_comm_agree(int status, int *first)
{
    *first = 0;
    return status;
}

int sj_comm_bcast_real(double *x, int64_t n, int root) { (void)x; (void)n; (void)root; return 0; }
int sj_comm_sum_i8(int64_t *x, int64_t n) { (void)x; (void)n; return 0; }
int sj_comm_max_real(double *x, int64_t n) { (void)x; (void)n; return 0; }
int sj_comm_sum_real(double *x, int64_t n) { (void)x; (void)n; return 0; }

#include <string.h>
int sj_comm_gather_i8(const int64_t *x, int64_t n, int64_t *out, const int *counts, const int *displs, int root)
{
    (void)counts; (void)displs; (void)root;
    if (n > 0) memcpy(out, x, (size_t)n * sizeof(int64_t));
    return 0;
}
