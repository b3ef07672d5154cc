/* region_probe.c -- parallel regions for unit.test_serial_regions, opened
 * through GOMP_parallel (GCC's entry point of `#pragma omp parallel`, which
 * src/solvers/serial_regions.c defines): how many threads ran a region's
 * body, whether the opening thread was one of them, and what a one-thread
 * region opened by each thread of a two-thread team sees as its team. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <pthread.h>

void GOMP_parallel(void (*body)(void *), void *data, unsigned num_threads, unsigned flags);

typedef struct {
    pthread_t opener;
    int runs;
    int on_opener;
    int alone;   /* inner bodies that saw a team of one, themselves its thread 0 */
} sj_probe_t;

static int sj_omp_value(const char *name)
{
    int (*f)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, name);
    return f != NULL ? f() : -1;
}

static void sj_probe_body(void *data)
{
    sj_probe_t *p = data;
    __atomic_add_fetch(&p->runs, 1, __ATOMIC_RELAXED);
    if (pthread_equal(pthread_self(), p->opener)) __atomic_add_fetch(&p->on_opener, 1, __ATOMIC_RELAXED);
}

static void sj_probe_inner(void *data)
{
    sj_probe_t *p = data;
    if (sj_omp_value("omp_get_num_threads") == 1 && sj_omp_value("omp_get_thread_num") == 0)
        __atomic_add_fetch(&p->alone, 1, __ATOMIC_RELAXED);
}

static void sj_probe_outer(void *data)
{
    sj_probe_t *p = data;
    __atomic_add_fetch(&p->runs, 1, __ATOMIC_RELAXED);
    GOMP_parallel(sj_probe_inner, p, 1, 0);
}

/* A region asking for num_threads threads: *runs bodies ran, *on_opener of
 * them on the calling thread. */
void sj_probe_region(unsigned num_threads, int *runs, int *on_opener)
{
    sj_probe_t p = {pthread_self(), 0, 0, 0};
    GOMP_parallel(sj_probe_body, &p, num_threads, 0);
    *runs = p.runs;
    *on_opener = p.on_opener;
}

/* A two-thread region whose threads each open a one-thread region: *runs
 * outer bodies ran, *alone inner bodies saw a team of one (their own). */
void sj_probe_nested(int *runs, int *alone)
{
    sj_probe_t p = {pthread_self(), 0, 0, 0};
    GOMP_parallel(sj_probe_outer, &p, 2, 0);
    *runs = p.runs;
    *alone = p.alone;
}
