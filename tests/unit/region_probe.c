/* region_probe.c -- a parallel region's body for unit.test_serial_regions:
 * opens a region through GOMP_parallel (GCC's entry point of
 * `#pragma omp parallel`, which src/solvers/serial_regions.c defines) and
 * counts the threads that ran its body and whether the opening thread was
 * one of them. */
#include <pthread.h>

void GOMP_parallel(void (*body)(void *), void *data, unsigned num_threads, unsigned flags);

typedef struct {
    pthread_t opener;
    int runs;
    int on_opener;
} sj_probe_t;

static void sj_probe_body(void *data)
{
    sj_probe_t *p = data;
    __atomic_add_fetch(&p->runs, 1, __ATOMIC_RELAXED);
    if (pthread_equal(pthread_self(), p->opener)) __atomic_add_fetch(&p->on_opener, 1, __ATOMIC_RELAXED);
}

/* A region asking for num_threads threads: *runs bodies ran, *on_opener of
 * them on the calling thread. */
void sj_probe_region(unsigned num_threads, int *runs, int *on_opener)
{
    sj_probe_t p;
    p.opener = pthread_self();
    p.runs = 0;
    p.on_opener = 0;
    GOMP_parallel(sj_probe_body, &p, num_threads, 0);
    *runs = p.runs;
    *on_opener = p.on_opener;
}
