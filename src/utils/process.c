/* Process set-up for the superjoin executable (called once from the main
 * program through bind(c)):
 *
 *  - SIGXFSZ is ignored, so a write beyond the file size limit (ulimit -f)
 *    fails with EFBIG and an I/O status the program reports (exit 4) instead
 *    of killing the process with a half-written temporary file.
 *  - SIGINT, SIGTERM, SIGHUP: the handler removes the temporary output file
 *    being written (registered with sj_temp_register), then the signal is
 *    raised again with its default action, so the exit status still says
 *    which signal ended the run. unlink and raise are async-signal-safe.
 *  - SIGSEGV, SIGBUS, SIGABRT, SIGFPE (a crash, or the Fortran runtime's own
 *    error termination when even its backtrace cannot allocate memory): the
 *    temporary file is removed too (on an alternate stack: the crash is often
 *    a stack that could not grow under ulimit -v), then the handler that was
 *    installed before (the Fortran runtime's backtrace) gets the signal.
 *  - OpenBLAS's work buffer is allocated now, by a 1 x 1 dpotrf: OpenBLAS
 *    retries a failed buffer allocation forever (it spins), so when memory
 *    runs out later the failure must land in code that reports it. If even
 *    that buffer cannot be mapped (probed with mmap first, as OpenBLAS maps
 *    it; malloc would make AddressSanitizer poison and fill 129 MB at every
 *    start), the caller is told, with the size, and BLAS is not touched.
 *
 * Also the one rule for work beside the main thread (sj_second_thread): the
 * CHOLMOD analysis beside the assembly, the listing's rows formatted in pairs
 * of chunks.
 */
#define _GNU_SOURCE
#include <sched.h>
#include <stdio.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#define SJ_TEMP_PATH_MAX 4096
/* OpenBLAS's work buffer (BUFFER_SIZE, 128 MiB on x86-64) plus its
 * alignment slack, rounded up. */
#define SJ_BLAS_BUFFER_BYTES ((size_t)129 << 20)
#define SJ_SETUP_HANDLERS (-1)

extern void dpotrf_(const char *uplo, const int *n, double *a, const int *lda,
                    int *info, size_t uplo_len);

/* Path of the temporary output file being written ('' when none). The
 * handler reads it; `temp_set` is cleared before the path changes. */
static char temp_path[SJ_TEMP_PATH_MAX];
static atomic_int temp_set = 0;

static const int cleanup_signals[] = {SIGINT, SIGTERM, SIGHUP};
static const int fatal_signals[] = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE};
#define SJ_NFATAL (sizeof fatal_signals / sizeof fatal_signals[0])
static struct sigaction fatal_previous[SJ_NFATAL];
/* The fatal handler runs on a stack of its own: a stack that could not grow
 * (ulimit -v reached) is the usual way such a run ends. Static, so that
 * nothing is allocated for it. */
#define SJ_ALT_STACK_BYTES (64 * 1024)
static char alt_stack[SJ_ALT_STACK_BYTES];

static void cleanup_handler(int sig)
{
    if (atomic_load(&temp_set)) unlink(temp_path);
    signal(sig, SIG_DFL);
    raise(sig);
}

/* Remove the temporary file, put back the handler found at set-up and
 * deliver the signal to it (on return from here for a fault: the faulting
 * instruction runs again and faults into that handler). */
static void fatal_handler(int sig)
{
    size_t k;
    if (atomic_load(&temp_set)) unlink(temp_path);
    atomic_store(&temp_set, 0);
    for (k = 0; k < SJ_NFATAL; k++) {
        if (fatal_signals[k] == sig) sigaction(sig, &fatal_previous[k], NULL);
    }
    if (sig == SIGABRT) raise(sig);
}

/* Returns 0 when every handler was installed (SJ_SETUP_HANDLERS if not).
 * *blas_bytes is 0 when BLAS is ready, else the bytes its buffer needs. */
/* A run that the Fortran runtime ends (an allocation inside its I/O library
   failing, say) leaves through exit(): the temporary file goes too. */
static void remove_temp_at_exit(void)
{
    if (atomic_load(&temp_set)) unlink(temp_path);
}

int sj_process_setup(int64_t *blas_bytes)
{
    int status = 0;
    size_t k;
    struct sigaction sa;
    double one = 1.0;
    int n = 1, info = 0;
    void *probe;

    if (signal(SIGXFSZ, SIG_IGN) == SIG_ERR) status = SJ_SETUP_HANDLERS;
    if (atexit(remove_temp_at_exit) != 0) status = SJ_SETUP_HANDLERS;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = cleanup_handler;
    sigemptyset(&sa.sa_mask);
    for (k = 0; k < sizeof cleanup_signals / sizeof cleanup_signals[0]; k++) {
        struct sigaction old;
        /* keep a signal that was ignored when we started (nohup, &) ignored */
        if (sigaction(cleanup_signals[k], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        if (sigaction(cleanup_signals[k], &sa, NULL) != 0) status = SJ_SETUP_HANDLERS;
    }
    {
        stack_t ss;
        memset(&ss, 0, sizeof ss);
        ss.ss_sp = alt_stack;
        ss.ss_size = sizeof alt_stack;
        if (sigaltstack(&ss, NULL) != 0) status = SJ_SETUP_HANDLERS;
    }
    sa.sa_handler = fatal_handler;
    sa.sa_flags = SA_ONSTACK;
    for (k = 0; k < SJ_NFATAL; k++) {
        if (sigaction(fatal_signals[k], &sa, &fatal_previous[k]) != 0) status = SJ_SETUP_HANDLERS;
    }
    probe = mmap(NULL, SJ_BLAS_BUFFER_BYTES, PROT_READ | PROT_WRITE,
                 MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (probe == MAP_FAILED) {
        *blas_bytes = (int64_t)SJ_BLAS_BUFFER_BYTES;
    } else {
        munmap(probe, SJ_BLAS_BUFFER_BYTES);
        *blas_bytes = 0;
        dpotrf_("U", &n, &one, &n, &info, 1);
    }
    return status;
}

/* Register path (len bytes, not NUL-terminated) as the temporary file to
 * remove on SIGINT/SIGTERM/SIGHUP; len <= 0 unregisters. Returns -1 when
 * the path is too long to register (it is then not removed on a signal). */
int sj_temp_register(const char *path, long len)
{
    atomic_store(&temp_set, 0);
    if (len <= 0) return 0;
    if (len >= SJ_TEMP_PATH_MAX) return -1;
    memcpy(temp_path, path, (size_t)len);
    temp_path[len] = '\0';
    atomic_store(&temp_set, 1);
    return 0;
}

/* End the process at once with `status`, skipping the atexit handlers: after
 * a failed OpenBLAS buffer allocation its shutdown joins worker threads that
 * spin forever retrying the allocation. The caller flushes its own output. */
void sj_quick_exit(int status)
{
    fflush(NULL);
    _exit(status);
}

/* May work run on a second thread beside the main one? Not when one thread
 * is asked for (OMP_NUM_THREADS=1, or a list whose first value is 1, as
 * OpenMP reads it) or when the process may run on one CPU
 * only (taskset, a container's cpuset): a second thread would then only take
 * turns with the first. */
int sj_second_thread(void)
{
    const char *s = getenv("OMP_NUM_THREADS");
    cpu_set_t set;
    if (s != NULL && *s != '\0' && strtol(s, NULL, 10) == 1) return 0;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) < 2) return 0;
    return 1;
}
