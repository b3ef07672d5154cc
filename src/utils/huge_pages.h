/* Transparent huge pages for superjoin's large blocks (huge_pages.c). */
#ifndef SUPERJOIN_HUGE_PAGES_H
#define SUPERJOIN_HUGE_PAGES_H
#include <stddef.h>

/* Huge pages for the whole 2 MiB pages inside [p, p + n), a block of 4 MiB or more. */
void sj_advise_huge(void *p, size_t n);
/* malloc, calloc and realloc whose large blocks ask for huge pages. */
void *sj_malloc_huge(size_t n);
void *sj_calloc_huge(size_t count, size_t size);
void *sj_realloc_huge(void *old, size_t n);
/* Whether large blocks ask for huge pages from now on (--huge-pages). */
void sj_huge_pages_enable(int on);
/* Whether freed large blocks stay with the process (--reuse-memory), and that policy applied once. */
void sj_reuse_memory_enable(int on);
void sj_memory_policy(void);

#endif
