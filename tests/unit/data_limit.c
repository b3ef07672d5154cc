/* data_limit.c -- the process's data limit (RLIMIT_DATA) for the text
 * buffer's out-of-memory paths (unit.test_text_rows_oom): memory a few
 * hundred kilobytes or a megabyte and a half beyond what the process holds,
 * so that the next megabyte block, or the one after, cannot be had.
 *
 * The headroom means what it says only where every large block is a mapping
 * of its own, counted against the limit when it is made and given back when
 * it is freed: sj_data_limit_prepare fixes glibc's thresholds (by default the
 * mapping threshold grows to the largest block freed, after which large
 * blocks come from the heap's free space, which the limit does not see), and
 * is called before the test allocates anything large. Under a memory checker
 * (AddressSanitizer, valgrind) allocation is the checker's and a failed one
 * ends the run: sj_memory_checker says so and the test is skipped. */
#define _GNU_SOURCE
#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#define SJ_MAP_THRESHOLD (64 * 1024) /* blocks from 64 KB on: a mapping each */

extern void __asan_init(void) __attribute__((weak));

static struct rlimit sj_saved;
static int sj_limited = 0;

/* 1 where AddressSanitizer or valgrind allocates the process's memory. */
int sj_memory_checker(void)
{
    const char *preload = getenv("LD_PRELOAD");
    if (__asan_init != NULL) return 1;
    return preload != NULL && strstr(preload, "vgpreload") != NULL;
}

/* Large blocks mapped one by one and unmapped when freed; 0 on success. */
int sj_data_limit_prepare(void)
{
    if (mallopt(M_MMAP_THRESHOLD, SJ_MAP_THRESHOLD) != 1) return -1;
    if (mallopt(M_TRIM_THRESHOLD, SJ_MAP_THRESHOLD) != 1) return -1;
    return 0;
}

/* The process's data (VmData of /proc/self/status) in bytes, -1 if unknown. */
static long long sj_data_bytes(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long long kb = -1;
    if (f == NULL) return -1;
    while (fgets(line, sizeof line, f) != NULL) {
        if (strncmp(line, "VmData:", 7) == 0) {
            kb = strtoll(line + 7, NULL, 10);
            break;
        }
    }
    fclose(f);
    return kb < 0 ? -1 : kb * 1024;
}

/* The data limit set to what the process holds now plus headroom bytes;
 * 0 on success. sj_data_limit_restore puts the previous limit back. */
int sj_data_limit_set(long long headroom)
{
    struct rlimit r;
    long long used;
    malloc_trim(0);
    if (getrlimit(RLIMIT_DATA, &sj_saved) != 0) return -1;
    used = sj_data_bytes();
    if (used < 0) return -1;
    r = sj_saved;
    r.rlim_cur = (rlim_t)(used + headroom);
    if (sj_saved.rlim_max != RLIM_INFINITY && r.rlim_cur > sj_saved.rlim_max) return -1;
    if (setrlimit(RLIMIT_DATA, &r) != 0) return -1;
    sj_limited = 1;
    return 0;
}

/* 1 when a block of bytes could be allocated now (it is freed again). */
int sj_data_available(long long bytes)
{
    void *p = malloc((size_t)bytes);
    if (p == NULL) return 0;
    memset(p, 1, (size_t)bytes);
    free(p);
    return 1;
}

/* The limit found by sj_data_limit_set back in force; 0 on success. */
int sj_data_limit_restore(void)
{
    if (!sj_limited) return 0;
    sj_limited = 0;
    return setrlimit(RLIMIT_DATA, &sj_saved);
}
