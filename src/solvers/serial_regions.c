/* serial_regions.c -- OpenMP parallel regions that ask for one thread run on
 * the calling thread, without a team.
 *
 * CHOLMOD's supernodal factorization (SuiteSparse 5.12, built with GCC's
 * OpenMP) opens several parallel regions per supernode: zeroing its columns,
 * scattering its row map, copying its columns of A, each with an `if` clause
 * that makes it serial when the supernode is small. GCC passes such a region
 * to libgomp's GOMP_parallel with one thread, and libgomp still builds a team
 * for it: a memalign, the team's set-up, its end and a free, about 2 100
 * instructions a region. On the 1e6-equation `long` frame (114 631
 * supernodes of 8.7 columns on average) that is 805 000 regions, 1.7e9
 * instructions, 7.6 % of the run's and a quarter of the factorization's; the
 * factorization's wall time falls from 1.3-1.5 s to 1.0-1.1 s without them
 * (doc/performance.md, "Serial regions without a team").
 *
 * This file defines GOMP_parallel itself. The dynamic linker finds the
 * program's definition before libgomp's for every library of the process
 * (the program exports it because libcholmod refers to it), so CHOLMOD's
 * regions come here. A region whose thread count is one (an `if` clause that
 * is false, num_threads(1), or no clause while the thread count of the
 * calling task, omp_get_max_threads, is one) runs its body directly, as the
 * team's only thread would: omp_get_thread_num() is 0 and
 * omp_get_num_threads() is 1 in it; orphaned barriers, single and
 * work-sharing constructs behave as libgomp makes them for one thread; the
 * arithmetic is the same, so are the results, bit for bit. What differs is
 * what no caller here reads: omp_get_level() inside such a region is one
 * less, and an omp_set_num_threads called in it would outlive it. Every
 * other region goes to libgomp's GOMP_parallel, found once by
 * dlsym(RTLD_NEXT) (sj_serial_regions_setup, called where a CHOLMOD handle is
 * made; later lookups race harmlessly to the same address).
 *
 * Only the GNU runtime's entry point is defined: a build whose libraries use
 * another OpenMP runtime never calls it. Nothing here is used by superjoin's
 * own Fortran, which has no OpenMP.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include <stdint.h>

typedef void (*sj_region_body)(void *);
typedef void (*sj_gomp_parallel_fn)(sj_region_body, void *, unsigned, unsigned);
typedef int (*sj_max_threads_fn)(void);

static sj_gomp_parallel_fn gomp_next = NULL;   /* libgomp's GOMP_parallel */
static sj_max_threads_fn max_threads = NULL;   /* libgomp's omp_get_max_threads */
static int looked_up = 0;
static int64_t serial_count = 0;               /* regions run without a team */

/* Looks up libgomp's GOMP_parallel and omp_get_max_threads (NULL where no
 * library of the process defines them), once. The CHOLMOD shim calls it
 * when it makes a handle, before any region is opened; a region opened
 * first looks them up itself (two threads doing so find the same
 * addresses). */
void sj_serial_regions_setup(void)
{
    if (__atomic_load_n(&looked_up, __ATOMIC_ACQUIRE)) return;
    __atomic_store_n(&gomp_next, (sj_gomp_parallel_fn)dlsym(RTLD_NEXT, "GOMP_parallel"), __ATOMIC_RELAXED);
    __atomic_store_n(&max_threads, (sj_max_threads_fn)dlsym(RTLD_DEFAULT, "omp_get_max_threads"),
                     __ATOMIC_RELAXED);
    __atomic_store_n(&looked_up, 1, __ATOMIC_RELEASE);
}

/* How many regions have run without a team so far (for the unit test). */
int64_t sj_serial_regions_count(void)
{
    return __atomic_load_n(&serial_count, __ATOMIC_RELAXED);
}

/* GCC's entry point of `#pragma omp parallel` (libgomp's ABI): body(data)
 * on num_threads threads (0: the calling task's default count), flags as
 * libgomp reads them (the proc_bind policy). */
void GOMP_parallel(sj_region_body body, void *data, unsigned num_threads, unsigned flags)
{
    sj_gomp_parallel_fn next;
    sj_max_threads_fn count;
    sj_serial_regions_setup();
    next = __atomic_load_n(&gomp_next, __ATOMIC_RELAXED);
    count = __atomic_load_n(&max_threads, __ATOMIC_RELAXED);
    if (num_threads == 1 || (num_threads == 0 && count != NULL && count() == 1) || next == NULL) {
        /* one thread: the calling one (also where no runtime was found,
         * which cannot start others) */
        __atomic_add_fetch(&serial_count, 1, __ATOMIC_RELAXED);
        body(data);
        return;
    }
    next(body, data, num_threads, flags);
}
