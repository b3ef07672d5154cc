/* blas_core.c -- OpenBLAS's kernels for the CPU the run is on.
 *
 * OpenBLAS built for several CPUs (Debian's libopenblas, a DYNAMIC_ARCH
 * build) picks its kernels once, when it is loaded, from the CPU's model
 * number. A CPU newer than the library is not in its table, and Debian 12's
 * OpenBLAS 0.3.21 then falls back to its "Prescott" kernels (SSE3): on an
 * Intel Xeon of family 6, model 207 it runs dgemm, dgemv and dtrsm with
 * 2004's instructions although the CPU has AVX-512: dgemm at 12-16 GFlop/s
 * where the SkylakeX kernels do 72 (bench/blas_kernels.c). Measured on such
 * a CPU (doc/performance.md, "OpenBLAS's kernels"): a 218 000-DOF C3D20R
 * block solves in 21-24 s instead of 58-60 s.
 *
 * OpenBLAS reads OPENBLAS_CORETYPE (its documented override) only when it
 * is loaded, before main. So sj_blas_core_setup, the first thing main does,
 * starts the program once more with OPENBLAS_CORETYPE set when, and only
 * when, all of these hold:
 *   - the BLAS is OpenBLAS built for several CPUs (openblas_get_corename is
 *     found, openblas_get_config names DYNAMIC_ARCH: a build for one CPU
 *     ignores the override) and OPENBLAS_CORETYPE is not set (a user's
 *     choice stands, even an empty one, which OpenBLAS acts on; and the
 *     second start does not start a third);
 *   - OpenBLAS chose a core without AVX2 kernels (Prescott, Nehalem,
 *     Sandybridge, ...) while the CPU and the operating system support
 *     AVX-512 (F, CD, BW, DQ, VL: the SkylakeX kernels) or AVX2 with FMA
 *     (the Haswell kernels); it is never moved to an older core;
 *   - the run is not under valgrind, whose tools would not follow the new
 *     start (valgrind's own CPU is one OpenBLAS knows).
 * The new start is the same program file (/proc/self/exe, which still names
 * it if the file was replaced meanwhile) with the same arguments and
 * environment (plus OPENBLAS_CORETYPE, which the processes it starts
 * inherit), process number and open files, as a wrapper script's `exec`
 * would make it: also under mpirun, before MPI is started (main calls this
 * before comm_world). The new start takes back the process's name (ps, top,
 * pkill), which exec through /proc/self/exe would leave as "exe": that of
 * its first argument, as the shell gave it (a `ccx` link stays `ccx`). If
 * the new start cannot be made, the run goes on as it is and -v says what
 * to set. Nothing has been read or written by then. Results differ from the
 * fallback kernels' in round-off only, as they do between two CPUs.
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <dirent.h>
#include <dlfcn.h>
#include <sys/prctl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#define SJ_BLAS_FROM_ENV "SUPERJOIN_BLAS_CORE_FROM"
#define SJ_CMDLINE_MAX (1 << 20)
#define SJ_NOTE_MAX 256

static char note[SJ_NOTE_MAX] = "";

/* The core to ask for instead of `current` (OpenBLAS's name of its choice),
 * on a CPU with AVX-512 (avx512 != 0) or AVX2 and FMA (avx2fma != 0), or
 * NULL to keep current. Only cores without AVX2 kernels are replaced. */
const char *sj_blas_core_choice(const char *current, int avx512, int avx2fma)
{
    static const char *const older[] = {
        "Katmai", "Coppermine", "Northwood", "Prescott", "Banias", "Atom", "Core2",
        "Penryn", "Dunnington", "Nehalem", "Athlon", "Opteron", "Opteron_SSE3",
        "Barcelona", "Nano", "Sandybridge", "Bobcat", "Bulldozer", "Piledriver",
        "Steamroller", "Unknown"};
    size_t k;
    if (current == NULL) return NULL;
    for (k = 0; k < sizeof older / sizeof older[0]; k++)
        if (strcasecmp(current, older[k]) == 0) return avx512 ? "SkylakeX" : avx2fma ? "Haswell" : NULL;
    return NULL;
}

static void advise(const char *current, const char *want)
{
    snprintf(note, sizeof note, "OpenBLAS kernels %s (this CPU has %s's instructions: set OPENBLAS_CORETYPE=%s)",
             current, want, want);
}

static void free_arguments(char **argv)
{
    if (argv == NULL) return;
    free(argv[0]);
    free(argv);
}

static int under_valgrind(void)
{
    const char *preload = getenv("LD_PRELOAD");
    return preload != NULL && strstr(preload, "vgpreload") != NULL;
}

static int cpu_avx512(void)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl");
#else
    return 0;
#endif
}

static int cpu_avx2fma(void)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return 0;
#endif
}

/* argv of this process from /proc/self/cmdline (NULL if unreadable). */
static char **own_arguments(void)
{
    FILE *f = fopen("/proc/self/cmdline", "rb");
    char *buf, **argv;
    size_t n, k, argc = 0, i = 0;
    if (f == NULL) return NULL;
    buf = malloc(SJ_CMDLINE_MAX);
    if (buf == NULL) {
        fclose(f);
        return NULL;
    }
    n = fread(buf, 1, SJ_CMDLINE_MAX - 1, f);
    fclose(f);
    if (n == 0 || n >= SJ_CMDLINE_MAX - 1) {   /* empty, or maybe cut short */
        free(buf);
        return NULL;
    }
    if (buf[n - 1] != '\0') buf[n++] = '\0';
    for (k = 0; k < n; k++)
        if (buf[k] == '\0') argc++;
    argv = malloc((argc + 1) * sizeof *argv);
    if (argv == NULL) {
        free(buf);
        return NULL;
    }
    argv[i++] = buf;
    for (k = 0; k + 1 < n; k++)
        if (buf[k] == '\0') argv[i++] = buf + k + 1;
    argv[i] = NULL;
    return argv;
}

/* The name of the process and of its threads (ps, top -H, pkill) from its
 * first argument's last component, as a start through /proc/self/exe left
 * them "exe": the main thread by prctl, the threads OpenBLAS started when it
 * was loaded through their /proc/self/task/TID/comm. */
static void take_back_name(void)
{
    char **argv = own_arguments();
    const char *base;
    DIR *tasks;
    struct dirent *t;
    char path[sizeof "/proc/self/task//comm" + sizeof t->d_name];
    FILE *f;
    if (argv == NULL) return;
    base = strrchr(argv[0], '/');
    base = base != NULL ? base + 1 : argv[0];
    if (*base != '\0') {
        (void)prctl(PR_SET_NAME, base, 0, 0, 0);
        tasks = opendir("/proc/self/task");
        while (tasks != NULL && (t = readdir(tasks)) != NULL) {
            if (t->d_name[0] == '.') continue;
            snprintf(path, sizeof path, "/proc/self/task/%s/comm", t->d_name);
            f = fopen(path, "w");
            if (f == NULL) continue;
            fputs(base, f);
            fclose(f);
        }
        if (tasks != NULL) closedir(tasks);
    }
    free_arguments(argv);
}

void sj_blas_core_setup(void)
{
    typedef char *(*text_t)(void);
    text_t corename, config;
    const char *current, *want;
    char **argv, from[SJ_NOTE_MAX / 4] = "";

    corename = (text_t)dlsym(RTLD_DEFAULT, "openblas_get_corename");
    config = (text_t)dlsym(RTLD_DEFAULT, "openblas_get_config");
    if (corename == NULL) return;   /* not OpenBLAS: nothing to say */
    current = corename();
    if (getenv(SJ_BLAS_FROM_ENV) != NULL) {   /* the new start */
        snprintf(from, sizeof from, "%s", getenv(SJ_BLAS_FROM_ENV));
        take_back_name();
        unsetenv(SJ_BLAS_FROM_ENV);
    }
    if (config == NULL || strstr(config(), "DYNAMIC_ARCH") == NULL) {
        snprintf(note, sizeof note, "OpenBLAS kernels %s (built for this one CPU type)", current);
        return;
    }
    if (getenv("OPENBLAS_CORETYPE") != NULL) {   /* even empty: OpenBLAS acts on it */
        if (from[0] != '\0')
            snprintf(note, sizeof note, "OpenBLAS kernels %s (set by superjoin: OpenBLAS took this CPU for %s)",
                     current, from);
        else
            snprintf(note, sizeof note, "OpenBLAS kernels %s (OPENBLAS_CORETYPE)", current);
        return;
    }
    want = sj_blas_core_choice(current, cpu_avx512(), cpu_avx2fma());
    if (want == NULL) {
        snprintf(note, sizeof note, "OpenBLAS kernels %s", current);
        return;
    }
    if (under_valgrind()) {
        advise(current, want);
        return;
    }
    argv = own_arguments();
    if (argv != NULL && setenv(SJ_BLAS_FROM_ENV, current, 1) == 0 && setenv("OPENBLAS_CORETYPE", want, 1) == 0) {
        fflush(NULL);
        execv("/proc/self/exe", argv);
    }
    /* not started again: go on with the kernels there are */
    free_arguments(argv);
    unsetenv("OPENBLAS_CORETYPE");
    unsetenv(SJ_BLAS_FROM_ENV);
    advise(current, want);
}

/* The kernels in use, for -v: a NUL-terminated text ("" when the BLAS is
 * not OpenBLAS). */
const char *sj_blas_core_note(void) { return note; }

/* Let OpenBLAS's worker threads go (blas_thread_shutdown_, found at run time:
 * nothing with another BLAS). After each threaded call they spin on
 * sched_yield for about 2^28 cycles (0.1 s) before they sleep, and a thread
 * of the program's own that runs meanwhile shares a CPU with that spin: the
 * listing's rows formatted on two threads took as long as on one. OpenBLAS
 * starts its workers again at its next threaded call (exec_blas). Only
 * where no BLAS call is running on another thread. */
void sj_blas_threads_rest(void)
{
    typedef int (*shutdown_t)(void);
    static shutdown_t shutdown = NULL;
    static int looked = 0;
    if (!looked) {
        shutdown = (shutdown_t)dlsym(RTLD_DEFAULT, "blas_thread_shutdown_");
        looked = 1;
    }
    if (shutdown != NULL) shutdown();
}
