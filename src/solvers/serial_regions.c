/* serial_regions.c -- OpenMP parallel regions that ask for one thread run on
 * the calling thread, without a team.
 *
 * CHOLMOD's supernodal factorization (SuiteSparse 5.12, built with GCC's
 * OpenMP) opens several parallel regions per supernode: zeroing its columns,
 * scattering its row map, copying its columns of A, each with an `if` clause
 * that makes it serial when the supernode is small. GCC passes such a region
 * to libgomp's GOMP_parallel with one thread, and libgomp still builds a team
 * for it: a memalign, the team's set-up, its end and a free. On the
 * 1e6-equation `long` frame (114 631 supernodes of 8.7 columns on average)
 * that is 805 000 regions; without their teams the factorization takes
 * 0.95e9 instructions less (5.19e9 -> 4.24e9, about 1 200 a region) and
 * 0.89-1.06 s of wall time instead of 1.25-1.52 s (doc/performance.md,
 * "Serial regions without a team").
 *
 * This file defines GOMP_parallel itself. The dynamic linker finds the
 * program's definition before libgomp's for every library of the process
 * (the program exports it because libcholmod refers to it, as cli.exports
 * checks), so CHOLMOD's regions come here. A region
 * runs its body directly, as the only thread of its team would, when its
 * thread count is one (an `if` clause that is false, num_threads(1), or no
 * clause while omp_get_max_threads() is one) and the calling thread is not
 * one of several threads of an enclosing team (omp_get_num_threads() is
 * one: otherwise the body would see that team's thread number and size, and
 * a work-sharing loop in it would be split among threads that do not run
 * it). Then omp_get_thread_num() is 0 and omp_get_num_threads() is 1 in it;
 * orphaned barriers, single and work-sharing constructs behave as libgomp
 * makes them for one thread; the arithmetic is the same, so are the results,
 * bit for bit. What differs is what no caller here reads: omp_get_level()
 * inside such a region is one less, and an omp_set_num_threads called in it
 * would outlive it. Every other region goes to libgomp's GOMP_parallel,
 * found once by dlsym(RTLD_NEXT) (sj_serial_regions_setup).
 *
 * Only the GNU runtime's entry point is defined: a build whose libraries use
 * another OpenMP runtime never calls it. superjoin's own Fortran opens one
 * kind of region, the listing's two-thread `parallel sections`
 * (src/output/rows.f90), which GCC compiles to GOMP_parallel_sections, not
 * GOMP_parallel; of the libraries it links (CHOLMOD, UMFPACK, METIS,
 * OpenBLAS, MUMPS, MPI) only CHOLMOD calls GOMP_parallel.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include <stdint.h>

typedef void (*sj_region_body)(void *);
typedef void (*sj_gomp_parallel_fn)(sj_region_body, void *, unsigned, unsigned);
typedef int (*sj_thread_count_fn)(void);

static sj_gomp_parallel_fn gomp_next = NULL;   /* libgomp's GOMP_parallel */
static sj_thread_count_fn max_threads = NULL;  /* libgomp's omp_get_max_threads */
static sj_thread_count_fn team_threads = NULL; /* libgomp's omp_get_num_threads */
static int looked_up = 0;
static int64_t serial_count = 0;               /* regions run without a team */

/* Looks up libgomp's GOMP_parallel, omp_get_max_threads and
 * omp_get_num_threads (NULL where no library of the process defines them),
 * once. The CHOLMOD shim calls it when it makes a handle, before any region
 * is opened; a region opened first looks them up itself (two threads doing
 * so find the same addresses). */
void sj_serial_regions_setup(void)
{
    if (__atomic_load_n(&looked_up, __ATOMIC_ACQUIRE)) return;
    __atomic_store_n(&gomp_next, (sj_gomp_parallel_fn)dlsym(RTLD_NEXT, "GOMP_parallel"), __ATOMIC_RELAXED);
    __atomic_store_n(&max_threads, (sj_thread_count_fn)dlsym(RTLD_DEFAULT, "omp_get_max_threads"),
                     __ATOMIC_RELAXED);
    __atomic_store_n(&team_threads, (sj_thread_count_fn)dlsym(RTLD_DEFAULT, "omp_get_num_threads"),
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
    sj_thread_count_fn count, team;
    int one;
    sj_serial_regions_setup();
    next = __atomic_load_n(&gomp_next, __ATOMIC_RELAXED);
    count = __atomic_load_n(&max_threads, __ATOMIC_RELAXED);
    team = __atomic_load_n(&team_threads, __ATOMIC_RELAXED);
    one = num_threads == 1 || (num_threads == 0 && count != NULL && count() == 1);
    if ((one && team != NULL && team() == 1) || next == NULL) {
        /* one thread, and the calling one alone in its team: it runs the
         * body (also where no runtime was found, which cannot start
         * others) */
        __atomic_add_fetch(&serial_count, 1, __ATOMIC_RELAXED);
        body(data);
        return;
    }
    next(body, data, num_threads, flags);
}
