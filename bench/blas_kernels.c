/*
 * blas_kernels.c -- how fast the BLAS kernels OpenBLAS picked run here: dgemm
 * (n = 1000: the supernodal factorization's and the condensation's updates)
 * and dgemv with the transpose (n = 2000: a supernodal solve with one
 * right-hand side), best of several calls, one thread unless
 * OPENBLAS_NUM_THREADS says otherwise. It does not change the kernels:
 * compare OPENBLAS_CORETYPE=Prescott with =SkylakeX (src/utils/blas_core.c
 * explains why superjoin may choose for OpenBLAS).
 *
 * Build:  gcc -O2 bench/blas_kernels.c -lopenblas -o build/blas_kernels
 * Usage:  OPENBLAS_CORETYPE=SkylakeX build/blas_kernels
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

void dgemm_(const char *, const char *, const int *, const int *, const int *, const double *, const double *,
            const int *, const double *, const int *, const double *, double *, const int *, size_t, size_t);
void dgemv_(const char *, const int *, const int *, const double *, const double *, const int *, const double *,
            const int *, const double *, double *, const int *, size_t);

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void)
{
    const int n = 1000, m = 2000, one = 1;
    const double alpha = 1.0, beta = 0.0;
    double *a = malloc(sizeof(double) * (size_t)m * (size_t)m), *c = malloc(sizeof(double) * (size_t)n * (size_t)n);
    double *x = malloc(sizeof(double) * (size_t)m), *y = malloc(sizeof(double) * (size_t)m);
    double best_mm = 1e30, best_mv = 1e30, t;
    char *(*corename)(void) = (char *(*)(void))dlsym(RTLD_DEFAULT, "openblas_get_corename");
    long k;
    int r;
    if (a == NULL || c == NULL || x == NULL || y == NULL) return 1;
    for (k = 0; k < (long)m * m; k++) a[k] = (double)((k * 7919) % 1000) / 1000.0;
    for (k = 0; k < m; k++) x[k] = 1.0 / (double)(k + 1);
    for (r = 0; r < 5; r++) {
        t = now();
        dgemm_("N", "N", &n, &n, &n, &alpha, a, &m, a, &m, &beta, c, &n, 1, 1);
        t = now() - t;
        if (t < best_mm) best_mm = t;
    }
    for (r = 0; r < 200; r++) {
        t = now();
        dgemv_("T", &m, &m, &alpha, a, &m, x, &one, &beta, y, &one, 1);
        t = now() - t;
        if (t < best_mv) best_mv = t;
    }
    printf("kernels %s: dgemm n=%d %.4f s = %.1f GFlop/s; dgemv T n=%d %.1f us = %.2f GFlop/s (check %.6g)\n",
           corename ? corename() : "(not OpenBLAS)", n, best_mm, 2.0 * n * n * (double)n / best_mm / 1e9, m,
           best_mv * 1e6, 2.0 * m * (double)m / best_mv / 1e9, c[n + 1] + y[m - 1]);
    free(a); free(c); free(x); free(y);
    return 0;
}
