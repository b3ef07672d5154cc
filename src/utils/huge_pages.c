/* Transparent huge pages for superjoin's large blocks.
 *
 * A large model's run touches its memory for the first time in the
 * factorization, the assembly and the recovery: on the long 1e6-equation
 * frame about 500 000 page faults of 4 KiB, half the run's wall time in the
 * kernel (doc/performance.md, "Huge pages"). Where the kernel's transparent
 * huge pages are "madvise" (the default of several distributions), a block
 * that asks for them with madvise(MADV_HUGEPAGE) before it is first written
 * is backed by 2 MiB pages: 512 times fewer faults, and fewer TLB misses in
 * the factorization's dense kernels. Where they are "always" this changes
 * nothing, where "never" madvise is a no-op.
 *
 * sj_advise_huge(p, n) advises the whole 2 MiB pages inside [p, p + n) of a
 * block of at least SJ_HUGE_MIN_BYTES; the ragged ends keep small pages. The
 * contents are not touched. sj_huge_pages_enable(0) turns it off for the
 * rest of the run (--huge-pages no). With --reuse-memory (below) blocks up
 * to 32 MiB come from the heap: their advice splits the heap's mapping, and
 * a later smaller block that reuses an advised range sits on its huge pages. The pages only become resident when
 * written, as before: a block's untouched tail costs no memory either way,
 * a touched 2 MiB page holds 2 MiB (the peak resident set of the benchmarks
 * changed by at most 2 %: doc/performance.md, "Huge pages").
 */
#include "huge_pages.h"

#include <ISO_Fortran_binding.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#define SJ_HUGE_PAGE_BYTES ((uintptr_t)2 << 20)
/* Smaller blocks keep small pages: their faults are few, and the heap stays
 * one mapping. */
#define SJ_HUGE_MIN_BYTES ((size_t)4 << 20)

static atomic_int huge_enabled = 1;
static int keep_freed = 1;

void sj_huge_pages_enable(int on) { atomic_store(&huge_enabled, on != 0); }

void sj_advise_huge(void *p, size_t n)
{
#ifdef MADV_HUGEPAGE
    if (p == NULL || n < SJ_HUGE_MIN_BYTES || !atomic_load(&huge_enabled)) return;
    uintptr_t first = ((uintptr_t)p + SJ_HUGE_PAGE_BYTES - 1) & ~(SJ_HUGE_PAGE_BYTES - 1);
    uintptr_t last = ((uintptr_t)p + n) & ~(SJ_HUGE_PAGE_BYTES - 1);
    /* Advice only: a kernel without THP says EINVAL, the block is unchanged. */
    if (last > first) (void)madvise((void *)first, last - first, MADV_HUGEPAGE);
#else
    (void)p;
    (void)n;
#endif
}

/* Fortran's advise_huge(a): any contiguous array, by its descriptor. */
void sj_advise_huge_array(const CFI_cdesc_t *a)
{
    if (a->base_addr == NULL || (a->rank > 0 && !CFI_is_contiguous(a))) return;   /* a scalar (the deck's text) is contiguous; CFI_is_contiguous takes arrays only */
    size_t n = a->elem_len;
    for (CFI_rank_t r = 0; r < a->rank; r++) n *= (size_t)a->dim[r].extent;
    sj_advise_huge(a->base_addr, n);
}

void *sj_malloc_huge(size_t n)
{
    void *p = malloc(n);
    sj_advise_huge(p, n);
    return p;
}

void *sj_calloc_huge(size_t count, size_t size)
{
    void *p = calloc(count, size);
    /* glibc's calloc does not write the zeros of fresh memory (a mapped
     * block, the heap's new top): those pages are still untouched here.
     * Reused heap memory it clears, and it is resident already. */
    if (p != NULL && size != 0 && count <= SIZE_MAX / size) sj_advise_huge(p, count * size);
    return p;
}

void *sj_realloc_huge(void *old, size_t n)
{
    void *p = realloc(old, n);
    sj_advise_huge(p, n);
    return p;
}

/* Freed blocks kept for the next ones (--reuse-memory).
 *
 * glibc maps a block above its mmap threshold on its own and unmaps it when
 * it is freed; the threshold starts at 128 KiB and follows the freed blocks
 * up to 32 MiB, and the heap's free top goes back to the kernel past the trim
 * threshold (128 KiB at first, twice the mmap threshold once that has moved).
 * A run that forms and frees its arrays step after step (a level's local
 * matrices, the solves' work vectors, CHOLMOD's workspaces) so faults in,
 * and the kernel clears, fresh pages for each (doc/performance.md, "Freed
 * memory kept"). Here the mmap threshold is 32 MiB from the start, so that
 * every block below it comes from the heap, where a freed block is reused as
 * it is, and each arena keeps up to 16 MiB of free top before it gives the
 * rest back. That is not a bound on the peak: freed blocks inside the heap
 * stay resident until reused, and a heap fragmented by small live blocks
 * can hold more than glibc's policy would. What caps it where the peaks are
 * is the malloc_trim(0) of every arena before CHOLMOD's numeric
 * factorization (cholmod_shim.c) and in the recovery (recover.f90). Measured:
 * peaks within 2 MB of glibc's policy on the 1e6 frames and the building,
 * +15 MB (4.5 %) on an 8-floor building; a trim threshold of 1 GiB kept 20
 * MB more on a 2e5 frame. Blocks of 32 MiB and more are still mapped on
 * their own: kept in the heap they fragment it (+10 % peak on the 1e6 long
 * frame).
 *
 * Not applied when the user set glibc's allocator tunables (GLIBC_TUNABLES
 * with glibc.malloc.*, MALLOC_MMAP_THRESHOLD_, MALLOC_TRIM_THRESHOLD_):
 * theirs stand. The caller does not apply it under MPI, whose library may
 * depend on the allocator's settings (registration caches).
 */
#define SJ_KEEP_MMAP_THRESHOLD (32 << 20)
#define SJ_KEEP_TRIM_THRESHOLD (16 << 20)

void sj_reuse_memory_enable(int on) { keep_freed = on != 0; }

void sj_memory_policy(void)
{
#if defined(__GLIBC__)
    const char *tunables = getenv("GLIBC_TUNABLES");
    if (!keep_freed) return;
    if (getenv("MALLOC_MMAP_THRESHOLD_") != NULL || getenv("MALLOC_TRIM_THRESHOLD_") != NULL) return;
    if (tunables != NULL && strstr(tunables, "glibc.malloc.") != NULL) return;
    (void)mallopt(M_MMAP_THRESHOLD, SJ_KEEP_MMAP_THRESHOLD);
    (void)mallopt(M_TRIM_THRESHOLD, SJ_KEEP_TRIM_THRESHOLD);
#endif
}
