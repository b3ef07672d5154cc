/*
 * cholmod_shim.c -- a thin C layer between superjoin (Fortran) and CHOLMOD.
 *
 * The cholmod_common struct is large and changes between SuiteSparse
 * versions, so it never crosses the language boundary: Fortran only holds an
 * opaque handle (void *) created by sj_cholmod_create and released by
 * sj_cholmod_free.
 *
 * Matrices come from Fortran as the upper triangle of a symmetric matrix in
 * 1-based compressed sparse column form with 64-bit indices (rows sorted,
 * diagonal present).  CHOLMOD wants 0-based indices of the same 64-bit type,
 * so during each call that reads the matrix (analyze, factorize,
 * schur_analyze) the caller's index arrays are shifted to 0-based in place and
 * the cholmod_sparse header points at them (and at the caller's values during
 * factorize); they are shifted back before the call returns.  The handle keeps
 * only a fingerprint of the pattern, which factorize checks (issue 24: a copy
 * was ~8% of the peak at 1e6).  The one copy: analyze_start's 0-based pattern
 * for the analysis on a second thread, freed when the thread is joined
 * (analyze_finish, any later entry point that reads the factor or the
 * settings, or sj_cholmod_free).
 *
 * Factorization: supernodal LL^T (Common->supernodal = CHOLMOD_SUPERNODAL,
 * final_ll = TRUE). Ordering: CHOLMOD's default strategy (nmethods = 0: AMD,
 * then METIS when AMD's fill is high; the best is kept). When a node graph
 * was given (sj_cholmod_set_node_graph), the same strategy with the METIS
 * candidate taken on the node graph (several times smaller than the column
 * graph) and expanded to columns: AMD on the columns first, METIS on the node
 * graph only where CHOLMOD's own test would try METIS, the smaller nnz(L)
 * kept (sj_analyze_grouped). From SJ_NODE_AMD_MIN columns on, with 4 or more
 * columns per node on average, AMD orders the node graph instead of the
 * columns (sj_analyze_node_amd), then the same strategy.
 *
 * Analysis beside the caller's work (sj_cholmod_analyze_start/_finish): the
 * pattern is copied (0-based) and analyzed by a second thread while the
 * caller goes on (superjoin assembles the values of K meanwhile); finish
 * waits for it. The analysis is the same as sj_cholmod_analyze's, so the
 * factor and every result are the same. Not started when one thread is asked
 * for (OMP_NUM_THREADS=1) or the process may run on one CPU only.
 *
 * Every function returns a status: SJ_OK (0), SJ_NOT_POSDEF (1), or a
 * negative code (CHOLMOD's own negative codes -2..-5, or SJ_E_* below).
 * Nothing is printed and nothing aborts: CHOLMOD's print level is 0 and its
 * error handler only records the message (sj_cholmod_message).
 */
#define _GNU_SOURCE   /* madvise's MADV_DONTNEED under a strict -std */
#include "huge_pages.h"
#include <malloc.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "amd.h"
#include "cholmod.h"
#include "metis.h"

#define SJ_OK 0
#define SJ_NOT_POSDEF 1
#define SJ_TRY_INTERIOR 2   /* sj_cholmod_schur_camd: analyze the interior first */
#define SJ_E_HANDLE (-101)   /* null or unusable handle */
#define SJ_E_ARGUMENT (-102) /* bad argument (size, index out of range) */
#define SJ_E_PATTERN (-103)  /* factorize: pattern differs from analyze */
#define SJ_E_STATE (-104)    /* wrong call order (no analysis, no factor) */
#define SJ_E_NOMEM (-105)    /* malloc failed in the shim itself */

#define SJ_MESSAGE_LEN 256
/* CHOLMOD's own test for trying METIS after AMD (cholmod_analyze defaults):
 * flops per nonzero of L, and nonzeros of L per nonzero of A. */
#define SJ_METIS_FL_PER_LNZ 500.0
#define SJ_METIS_LNZ_PER_NNZ 5.0
/* From this many columns on, AMD orders the node graph instead of the
 * columns (sj_cholmod_set_node_amd_min changes it): far above the test
 * decks, whose orderings (and results at round-off) stay column AMD's. Only
 * where the nodes hold SJ_NODE_AMD_GROUP columns or more on average: on
 * frames (6 per node) node AMD's nnz(L) was column AMD's to the entry, on
 * CPS4 panels (2 per node) 2 % above it (doc/performance.md). */
#define SJ_NODE_AMD_MIN 100000
#define SJ_NODE_AMD_GROUP 4

/* Out of memory: SuiteSparse allocates through SuiteSparse_config's
 * function pointers; sj_cholmod_create routes them through these wrappers,
 * which remember the size of the last request that failed, so the error can
 * say how many bytes CHOLMOD needed (Common->memory_inuse says how many it
 * already held). */
static _Atomic size_t sj_failed_request = 0;

/* Through src/utils/huge_pages.c, large blocks ask for huge pages (CHOLMOD's
 * factor, its permuted copy of K and its workspaces are the run's largest). */

static void *sj_malloc(size_t size)
{
    void *p = sj_malloc_huge(size);
    if (p == NULL && size > 0) sj_failed_request = size;
    return p;
}

static void *sj_calloc(size_t count, size_t size)
{
    void *p = sj_calloc_huge(count, size);
    if (p == NULL && count > 0 && size > 0)
        sj_failed_request = (count > SIZE_MAX / size) ? SIZE_MAX : count * size;
    return p;
}

static void *sj_realloc(void *old, size_t size)
{
    void *p = sj_realloc_huge(old, size);
    if (p == NULL && size > 0) sj_failed_request = size;
    return p;
}

static void sj_route_allocations(void)
{
#if SUITESPARSE_MAIN_VERSION >= 7
    SuiteSparse_config_malloc_func_set(sj_malloc);
    SuiteSparse_config_calloc_func_set(sj_calloc);
    SuiteSparse_config_realloc_func_set(sj_realloc);
#else
    SuiteSparse_config.malloc_func = sj_malloc;
    SuiteSparse_config.calloc_func = sj_calloc;
    SuiteSparse_config.realloc_func = sj_realloc;
#endif
}

_Static_assert(sizeof(SuiteSparse_long) == sizeof(int64_t),
               "SuiteSparse_long must be 64-bit");

typedef struct {
    cholmod_common common;
    cholmod_factor *L;          /* symbolic after analyze, numeric after factorize */
    cholmod_sparse A;           /* header around the caller's arrays, during a call only */
    SuiteSparse_long n;
    SuiteSparse_long nnz;
    uint64_t pattern_hash;      /* fingerprint of the analyzed pattern (sj_take_pattern) */
    int factored;               /* 1 when L holds a complete numeric factor */
    /* Optional node graph (groups of consecutive columns, e.g. the DOFs of one
     * node): METIS orders it and the expanded permutation is offered to
     * CHOLMOD next to its own AMD. */
    idx_t ngroup;
    idx_t *gxadj, *gadjncy, *gvwgt;
    SuiteSparse_long *gfirst;   /* first column (0-based) of each group, ngroup+1 */
    int given_is_node_metis;
    int given_is_amd;           /* the given permutation is CHOLMOD's AMD (sj_analyze_grouped) */
    int force_node_metis;       /* 1: offer node-graph METIS whatever AMD's fill; 2: node-graph METIS
                                 * alone, no AMD candidate (a matrix dense by blocks: the level solver's
                                 * top system, where AMD's pass over every entry costs more than it finds) */
    int given_is_node_amd;      /* the given permutation is AMD of the node graph */
    SuiteSparse_long node_amd_min;   /* AMD on the node graph from this many columns on */
    SuiteSparse_long minor;     /* permuted column where factorization stopped (n: none) */
    char message[SJ_MESSAGE_LEN];
    SuiteSparse_long nschur;    /* boundary columns ordered last by sj_cholmod_schur_analyze (0: none) */
    /* An analysis running beside the caller (sj_cholmod_analyze_start): */
    pthread_t worker;
    int pending;                /* 1 while the worker has not been joined */
    int worker_status;          /* its sj_end status */
    SuiteSparse_long *own_p, *own_i;   /* its 0-based copy of the pattern */
} sj_cholmod_t;

/* CHOLMOD's error handler has no user pointer: record the last message per
 * thread, and copy it into the handle after each CHOLMOD call. */
static _Thread_local char sj_last_message[SJ_MESSAGE_LEN];

static void sj_error_handler(int status, const char *file, int line,
                             const char *message)
{
    (void)file;
    (void)line;
    if (message == NULL) message = "";
    if (status < 0) {
        strncpy(sj_last_message, message, SJ_MESSAGE_LEN - 1);
        sj_last_message[SJ_MESSAGE_LEN - 1] = '\0';
    } else if (sj_last_message[0] == '\0') {
        /* a warning: keep it only when no error is recorded */
        strncpy(sj_last_message, message, SJ_MESSAGE_LEN - 1);
        sj_last_message[SJ_MESSAGE_LEN - 1] = '\0';
    }
}

static void sj_set_message(sj_cholmod_t *h, const char *message)
{
    strncpy(h->message, message, SJ_MESSAGE_LEN - 1);
    h->message[SJ_MESSAGE_LEN - 1] = '\0';
}

/* Start a CHOLMOD call: clear the recorded message and failed request. */
static void sj_begin(sj_cholmod_t *h)
{
    sj_failed_request = 0;
    sj_last_message[0] = '\0';
    h->message[0] = '\0';
}

/* Finish a CHOLMOD call: map Common->status to a shim status. */
static int sj_end(sj_cholmod_t *h, int ok)
{
    int status = h->common.status;
    if (sj_last_message[0] != '\0') sj_set_message(h, sj_last_message);
    if (status < CHOLMOD_OK) return status;
    if (!ok) {
        if (h->message[0] == '\0') sj_set_message(h, "CHOLMOD call failed");
        return CHOLMOD_INVALID;
    }
    return status == CHOLMOD_NOT_POSDEF ? SJ_NOT_POSDEF : SJ_OK;
}

static void sj_drop_factor(sj_cholmod_t *h)
{
    if (h->L != NULL) cholmod_l_free_factor(&h->L, &h->common);
    h->L = NULL;
    h->factored = 0;
    h->minor = h->n;
}

static void sj_drop_pattern(sj_cholmod_t *h)
{
    h->n = 0;
    h->nnz = 0;
    h->nschur = 0;
    h->pattern_hash = 0;
}

/* Shift the caller's 1-based arrays to 0-based (by = -1) or back (by = +1),
 * in place: CHOLMOD's SuiteSparse_long is int64_t (asserted below). */
static void sj_shift(int64_t *a, SuiteSparse_long len, int by)
{
    SuiteSparse_long k;
    for (k = 0; k < len; k++) a[k] += by;
}

/* FNV-1a style fingerprint of the pattern (n, column pointers, row indices,
 * 1-based), so factorize can tell a pattern that differs from the analyzed
 * one. Computed while the arrays are shifted to 0-based (sj_take_pattern,
 * sj_take_analyzed): one pass over the row indices instead of three. */
#define SJ_FNV_BASIS 1469598103934665603ULL
#define SJ_FNV_PRIME 1099511628211ULL
#define SJ_FNV(hash, v) ((hash) = ((hash) ^ (uint64_t)(v)) * SJ_FNV_PRIME)

/* Check a 1-based upper-triangle pattern (pointers from 1, monotonic, rows
 * within the upper triangle), fingerprint it into *hash and shift it to
 * 0-based in place, in one pass. NULL when valid; else the message, and the
 * arrays are left 1-based. */
static const char *sj_take_pattern(SuiteSparse_long n, int64_t *colptr, int64_t *rowind, uint64_t *hash)
{
    SuiteSparse_long j, k;
    uint64_t h = SJ_FNV_BASIS;
    if (colptr[0] != 1 || colptr[n] - 1 < 0) return "invalid column pointers";
    for (j = 1; j <= n; j++)
        if (colptr[j] < colptr[j - 1]) return "column pointers are not monotonic";
    SJ_FNV(h, n);
    for (j = 0; j <= n; j++) SJ_FNV(h, colptr[j]);
    for (j = 0; j < n; j++) {
        for (k = colptr[j] - 1; k < colptr[j + 1] - 1; k++) {
            if (rowind[k] < 1 || rowind[k] > j + 1) {
                sj_shift(rowind, k, 1);
                return "row index outside the upper triangle";
            }
            SJ_FNV(h, rowind[k]);
            rowind[k] -= 1;
        }
    }
    sj_shift(colptr, n + 1, -1);
    *hash = h;
    return NULL;
}

/* The fingerprint of a 1-based pattern of nnz entries whose pointers were
 * checked at the analysis; the arrays are shifted to 0-based in the same
 * pass. */
static uint64_t sj_take_analyzed(SuiteSparse_long n, SuiteSparse_long nnz, int64_t *colptr, int64_t *rowind)
{
    SuiteSparse_long k;
    uint64_t h = SJ_FNV_BASIS;
    SJ_FNV(h, n);
    for (k = 0; k <= n; k++) {
        SJ_FNV(h, colptr[k]);
        colptr[k] -= 1;
    }
    for (k = 0; k < nnz; k++) {
        SJ_FNV(h, rowind[k]);
        rowind[k] -= 1;
    }
    return h;
}

/* Point h->A (pattern only) at the caller's arrays, already 0-based. */
static void sj_header(sj_cholmod_t *h, SuiteSparse_long n, int64_t *colptr, int64_t *rowind)
{
    memset(&h->A, 0, sizeof(cholmod_sparse));
    h->A.nrow = (size_t)n;
    h->A.ncol = (size_t)n;
    h->A.nzmax = (size_t)(colptr[n] > 0 ? colptr[n] : 1);
    h->A.p = colptr;
    h->A.i = rowind;
    h->A.stype = 1;                 /* upper triangle stored */
    h->A.itype = CHOLMOD_LONG;
    h->A.xtype = CHOLMOD_PATTERN;   /* values not needed to analyze */
    h->A.dtype = CHOLMOD_DOUBLE;
    h->A.sorted = 1;
    h->A.packed = 1;
}

void sj_serial_regions_setup(void);   /* serial_regions.c */

/* Create a handle; NULL if out of memory or CHOLMOD cannot start. */
void *sj_cholmod_create(void)
{
    sj_cholmod_t *h;
    sj_route_allocations();
    sj_serial_regions_setup();   /* CHOLMOD's one-thread regions without a team */
    h = calloc(1, sizeof(sj_cholmod_t));
    if (h == NULL) return NULL;
    if (!cholmod_l_start(&h->common)) {
        free(h);
        return NULL;
    }
    h->common.print = 0;
    h->common.error_handler = sj_error_handler;
    h->common.supernodal = CHOLMOD_SUPERNODAL;
    h->common.final_ll = 1;
    h->common.final_asis = 0;      /* honour final_ll */
    h->common.final_super = 1;     /* keep the supernodal layout */
    h->common.final_pack = 1;
    h->common.final_monotonic = 1;
    h->common.nmethods = 0;        /* default strategy: AMD, METIS if AMD fills badly */
    h->node_amd_min = SJ_NODE_AMD_MIN;
    h->L = NULL;
    h->minor = 0;
    return h;
}

/* Release everything held by the handle (NULL is accepted). */
static void sj_drop_graph(sj_cholmod_t *h);

static int sj_join(sj_cholmod_t *h);
int sj_cholmod_analyze_finish(void *handle);

void sj_cholmod_free(void *handle)
{
    sj_cholmod_t *h = handle;
    if (h == NULL) return;
    sj_join(h);
    sj_drop_factor(h);
    sj_drop_pattern(h);
    sj_drop_graph(h);
    cholmod_l_finish(&h->common);
    free(h);
}

static void sj_drop_graph(sj_cholmod_t *h)
{
    free(h->gxadj);
    free(h->gadjncy);
    free(h->gvwgt);
    free(h->gfirst);
    h->gxadj = h->gadjncy = h->gvwgt = NULL;
    h->gfirst = NULL;
    h->ngroup = 0;
}

/* Give the node graph used for ordering: ngroup groups of consecutive
 * columns, group g holding 1-based columns first[g] .. first[g+1]-1, and the
 * group adjacency in 1-based CSR form (xadj, adjncy; no self loops). A
 * graph with ngroup = 0 removes it. The arrays are copied. */
int sj_cholmod_set_node_graph(void *handle, int64_t ngroup, const int64_t *first,
                              const int64_t *xadj, const int64_t *adjncy)
{
    sj_cholmod_t *h = handle;
    int64_t g, k, nadj;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    sj_join(h);
    sj_drop_graph(h);
    if (ngroup <= 0) return SJ_OK;
    nadj = xadj[ngroup] - 1;
    if (ngroup > INT32_MAX || nadj > INT32_MAX || nadj < 0) return SJ_E_ARGUMENT;
    h->gxadj = malloc((size_t)(ngroup + 1) * sizeof(idx_t));
    h->gadjncy = malloc((size_t)(nadj > 0 ? nadj : 1) * sizeof(idx_t));
    h->gvwgt = malloc((size_t)ngroup * sizeof(idx_t));
    h->gfirst = malloc((size_t)(ngroup + 1) * sizeof(SuiteSparse_long));
    if (!h->gxadj || !h->gadjncy || !h->gvwgt || !h->gfirst) {
        sj_drop_graph(h);
        return SJ_E_NOMEM;
    }
    for (g = 0; g <= ngroup; g++) {
        h->gxadj[g] = (idx_t)(xadj[g] - 1);
        h->gfirst[g] = first[g] - 1;
    }
    for (g = 0; g < ngroup; g++) h->gvwgt[g] = (idx_t)(first[g + 1] - first[g]);
    for (k = 0; k < nadj; k++) {
        if (adjncy[k] < 1 || adjncy[k] > ngroup) { sj_drop_graph(h); return SJ_E_ARGUMENT; }
        h->gadjncy[k] = (idx_t)(adjncy[k] - 1);
    }
    h->ngroup = (idx_t)ngroup;
    return SJ_OK;
}

/* Offer the node-graph METIS ordering even where AMD's fill is low (flag 1,
 * tests), or take it alone without AMD's candidate (flag 2). */
int sj_cholmod_force_node_metis(void *handle, int flag)
{
    sj_cholmod_t *h = handle;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    h->force_node_metis = flag == 2 ? 2 : flag != 0;
    return SJ_OK;
}

/* The column permutation of a node permutation perm (ngroup entries): each
 * node's columns in their order, node after node. */
static void sj_expand_groups(const sj_cholmod_t *h, const idx_t *perm, SuiteSparse_long *colperm)
{
    SuiteSparse_long pos = 0, c;
    idx_t k;
    for (k = 0; k < h->ngroup; k++) {
        idx_t g = perm[k];
        for (c = h->gfirst[g]; c < h->gfirst[g + 1]; c++) colperm[pos++] = c;
    }
}

/* Order the node graph with AMD from min columns on (negative: never); the
 * default is SJ_NODE_AMD_MIN. */
int sj_cholmod_set_node_amd_min(void *handle, int64_t min)
{
    sj_cholmod_t *h = handle;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    h->node_amd_min = min < 0 ? INT64_MAX : min;
    return SJ_OK;
}

/* Column permutation from a METIS nested dissection of the node graph, or
 * NULL when there is no graph or METIS fails. */
static SuiteSparse_long *sj_node_metis_perm(sj_cholmod_t *h)
{
    idx_t nv = h->ngroup, options[METIS_NOPTIONS];
    idx_t *perm, *iperm;
    SuiteSparse_long *colperm;
    if (nv <= 0 || h->gfirst[nv] != h->n) return NULL;
    perm = malloc((size_t)nv * sizeof(idx_t));
    iperm = malloc((size_t)nv * sizeof(idx_t));
    colperm = malloc((size_t)(h->n > 0 ? h->n : 1) * sizeof(SuiteSparse_long));
    if (!perm || !iperm || !colperm) { free(perm); free(iperm); free(colperm); return NULL; }
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    if (METIS_NodeND(&nv, h->gxadj, h->gadjncy, h->gvwgt, options, perm, iperm) != METIS_OK) {
        free(perm); free(iperm); free(colperm);
        return NULL;
    }
    sj_expand_groups(h, perm, colperm);
    free(perm);
    free(iperm);
    return colperm;
}

/* Column permutation from AMD of the node graph (unweighted: a node counts
 * as one vertex whatever its number of columns), with CHOLMOD's AMD
 * settings; NULL when there is no graph or AMD fails. */
static SuiteSparse_long *sj_node_amd_perm(sj_cholmod_t *h)
{
    idx_t nv = h->ngroup;
    int32_t *perm;
    SuiteSparse_long *colperm;
    double control[AMD_CONTROL];
    _Static_assert(sizeof(idx_t) == sizeof(int32_t), "METIS idx_t must be 32-bit for amd_order");
    if (nv <= 0 || h->gfirst[nv] != h->n) return NULL;
    perm = malloc((size_t)nv * sizeof(int32_t));
    colperm = malloc((size_t)(h->n > 0 ? h->n : 1) * sizeof(SuiteSparse_long));
    if (!perm || !colperm) { free(perm); free(colperm); return NULL; }
    amd_defaults(control);
    control[AMD_DENSE] = h->common.method[1].prune_dense;
    control[AMD_AGGRESSIVE] = h->common.method[1].aggressive;
    if (amd_order(nv, h->gxadj, h->gadjncy, perm, control, NULL) < AMD_OK) {
        free(perm); free(colperm);
        return NULL;
    }
    sj_expand_groups(h, perm, colperm);
    free(perm);
    return colperm;
}

/* nnz(L) of the permutation perm of h->A (CHOLMOD's column counts, as its
 * analysis of a given permutation computes them); -1 if that fails. */
static double sj_given_lnz(sj_cholmod_t *h, SuiteSparse_long *perm)
{
    size_t n = (size_t)(h->n > 0 ? h->n : 1);
    SuiteSparse_long *work = malloc(5 * n * sizeof(SuiteSparse_long));
    double lnz = -1.0;
    if (work == NULL) return lnz;
    if (cholmod_l_analyze_ordering(&h->A, CHOLMOD_GIVEN, perm, NULL, 0, work, work + n, work + 2 * n,
                                   work + 3 * n, work + 4 * n, &h->common))
        lnz = h->common.lnz;
    free(work);
    return lnz;
}

/* CHOLMOD's analysis of the given permutation perm (postordered, as its AMD
 * method analyzes AMD's permutation). */
static cholmod_factor *sj_analyze_given(sj_cholmod_t *h, SuiteSparse_long *perm)
{
    cholmod_common *cm = &h->common;
    int nm = cm->nmethods, o0 = cm->method[0].ordering;
    cholmod_factor *L;
    cm->nmethods = 1;
    cm->method[0].ordering = CHOLMOD_GIVEN;
    L = cholmod_l_analyze_p(&h->A, perm, NULL, 0, cm);
    cm->nmethods = nm;
    cm->method[0].ordering = o0;
    return L;
}

/* Is the fill of the analysis just done high by CHOLMOD's own test for
 * trying METIS after AMD (flops per nnz(L), nnz(L) per nnz(A))? */
static int sj_fill_high(const cholmod_common *cm)
{
    return !(cm->fl < SJ_METIS_FL_PER_LNZ * cm->lnz || cm->lnz < SJ_METIS_LNZ_PER_NNZ * cm->anz);
}

/* Analysis with AMD on the node graph in place of AMD on the columns (about
 * 6x fewer vertices and 36x fewer edges on a frame), then the same strategy
 * as sj_analyze_grouped's: METIS on the node graph where the fill is high by
 * CHOLMOD's test (or forced), the smaller nnz(L) kept, a tie to METIS. NULL
 * when AMD or the analysis fails (the caller falls back to column AMD). */
static cholmod_factor *sj_analyze_node_amd(sj_cholmod_t *h)
{
    cholmod_common *cm = &h->common;
    SuiteSparse_long *perm = sj_node_amd_perm(h);
    cholmod_factor *L, *M;
    double fl, lnz, anz;
    if (perm == NULL) return NULL;
    L = sj_analyze_given(h, perm);
    free(perm);
    if (L == NULL) return NULL;
    h->given_is_node_amd = 1;
    if (!sj_fill_high(cm) && !h->force_node_metis) return L;
    perm = sj_node_metis_perm(h);
    fl = cm->fl;
    lnz = cm->lnz;
    anz = cm->anz;
    M = NULL;
    if (perm != NULL) {
        double metis_lnz = sj_given_lnz(h, perm);
        if (metis_lnz >= 0.0 && metis_lnz <= lnz) M = sj_analyze_given(h, perm);
    }
    free(perm);
    cm->status = CHOLMOD_OK;
    if (M == NULL) {                 /* node AMD kept: its figures, not METIS's */
        cm->fl = fl;
        cm->lnz = lnz;
        cm->anz = anz;
        return L;
    }
    cholmod_l_free_factor(&L, cm);
    h->given_is_node_amd = 0;
    h->given_is_node_metis = 1;
    return M;
}

/* Analysis with a node graph: CHOLMOD's default strategy, with the METIS
 * candidate computed on the node graph. AMD on the columns first, as
 * CHOLMOD's default does; METIS nested dissection of the node graph only when
 * AMD's fill is high by CHOLMOD's own test (flops per nnz(L) and nnz(L) per
 * nnz(A)), or when forced; the smaller nnz(L) is kept (a tie to METIS, the
 * first candidate as before). The chosen permutation is analyzed as a given
 * one (the same factor as CHOLMOD's AMD method, which analyzes its
 * permutation the same way). With force_node_metis 2, the node graph's
 * METIS permutation alone (AMD only if METIS fails). NULL on failure. */
static cholmod_factor *sj_analyze_grouped(sj_cholmod_t *h)
{
    cholmod_common *cm = &h->common;
    SuiteSparse_long *amd, *metis = NULL, *best;
    double amd_lnz, metis_lnz;
    int high;
    cholmod_factor *L;
    if (h->force_node_metis == 2 && (metis = sj_node_metis_perm(h)) != NULL) {
        cm->status = CHOLMOD_OK;
        h->given_is_node_metis = 1;
        L = sj_analyze_given(h, metis);
        free(metis);
        return L;
    }
    if (h->n >= h->node_amd_min && h->n >= SJ_NODE_AMD_GROUP * (SuiteSparse_long)h->ngroup) {
        L = sj_analyze_node_amd(h);
        if (L != NULL) return L;
        cm->status = CHOLMOD_OK;     /* node AMD failed: column AMD as below */
    }
    amd = malloc((size_t)(h->n > 0 ? h->n : 1) * sizeof(SuiteSparse_long));
    if (amd == NULL) {
        cm->status = CHOLMOD_OUT_OF_MEMORY;
        return NULL;
    }
    cm->current = 1;                 /* AMD's method slot in the default strategy */
    if (!cholmod_l_amd(&h->A, NULL, 0, amd, cm)) {
        free(amd);
        return NULL;
    }
    amd_lnz = cm->lnz;
    high = sj_fill_high(cm);
    if (high || h->force_node_metis) metis = sj_node_metis_perm(h);
    best = amd;
    if (metis != NULL) {
        metis_lnz = sj_given_lnz(h, metis);
        if (metis_lnz >= 0.0 && metis_lnz <= amd_lnz) best = metis;
    }
    cm->status = CHOLMOD_OK;
    h->given_is_node_metis = best == metis;
    h->given_is_amd = best == amd;
    L = sj_analyze_given(h, best);
    free(amd);
    free(metis);
    return L;
}

/* The symbolic factor h->L of the pattern h->A points at (0-based). */
static void sj_analyze_now(sj_cholmod_t *h)
{
    h->given_is_node_metis = 0;
    h->given_is_amd = 0;
    h->given_is_node_amd = 0;
    if (h->ngroup > 0 && h->gfirst[h->ngroup] == h->n)
        h->L = sj_analyze_grouped(h);
    else
        h->L = cholmod_l_analyze(&h->A, &h->common);
}

/* Symbolic analysis of the upper triangle given 1-based (colptr: n+1,
 * rowind: colptr[n]-1), shifted to 0-based in place during the call. */
int sj_cholmod_analyze(void *handle, int64_t n, int64_t *colptr, int64_t *rowind)
{
    sj_cholmod_t *h = handle;
    SuiteSparse_long nnz;
    const char *bad;
    int ok, status;
    if (h == NULL) return SJ_E_HANDLE;
    sj_join(h);
    sj_begin(h);
    sj_drop_factor(h);
    sj_drop_pattern(h);
    if (n < 0 || colptr == NULL || (n > 0 && rowind == NULL)) {
        sj_set_message(h, "invalid matrix dimensions");
        return SJ_E_ARGUMENT;
    }
    nnz = colptr[n] - 1;
    bad = sj_take_pattern(n, colptr, rowind, &h->pattern_hash);
    if (bad != NULL) {
        sj_set_message(h, bad);
        return SJ_E_ARGUMENT;
    }
    h->n = n;
    h->nnz = nnz;
    sj_header(h, n, colptr, rowind);
    sj_analyze_now(h);
    sj_shift(colptr, n + 1, 1);
    sj_shift(rowind, nnz, 1);
    h->A.p = h->A.i = NULL;
    ok = h->L != NULL;
    sj_drop_graph(h);               /* only the analysis reads it; set again before the next */
    status = sj_end(h, ok);
    if (status != SJ_OK) {
        sj_drop_factor(h);
        return status < 0 ? status : CHOLMOD_INVALID;
    }
    h->minor = n;
    return SJ_OK;
}

/* May an analysis run beside the caller? Where a second thread may run at
 * all (sj_second_thread, process.c: not where one thread is asked for, nor
 * on one CPU). */
int sj_second_thread(void);
int sj_cholmod_can_overlap(void)
{
    return sj_second_thread();
}

/* The second thread: sj_analyze_now, its status and message kept in h (the
 * error handler records messages per thread). */
static void *sj_analyze_worker(void *arg)
{
    sj_cholmod_t *h = arg;
    sj_last_message[0] = '\0';
    sj_analyze_now(h);
    h->worker_status = sj_end(h, h->L != NULL);
    malloc_trim(0);   /* every arena gives back what it holds free, the analysis's included (else +4 % peak at 1e6) */
    return NULL;
}

/* Wait for the analysis started by sj_cholmod_analyze_start (if any) and
 * free its copy of the pattern; its status (SJ_OK when none was pending). */
static int sj_join(sj_cholmod_t *h)
{
    if (!h->pending) return SJ_OK;
    pthread_join(h->worker, NULL);
    h->pending = 0;
    free(h->own_p);
    free(h->own_i);
    h->own_p = h->own_i = NULL;
    h->A.p = h->A.i = NULL;
    sj_drop_graph(h);               /* only the analysis reads it */
    return h->worker_status;
}

/* Start the symbolic analysis of a 1-based upper triangle (as
 * sj_cholmod_analyze takes it) on a second thread, on a 0-based copy: the
 * caller's arrays are only read, during this call. SJ_OK: started, finish
 * with sj_cholmod_analyze_finish. Any other status: nothing started (an
 * invalid pattern, no memory for the copy, no thread), the caller analyzes
 * with sj_cholmod_analyze instead, which reports what is wrong. */
int sj_cholmod_analyze_start(void *handle, int64_t n, const int64_t *colptr, const int64_t *rowind)
{
    sj_cholmod_t *h = handle;
    SuiteSparse_long nnz;
    if (h == NULL) return SJ_E_HANDLE;
    sj_join(h);
    if (n <= 0 || colptr == NULL || rowind == NULL || colptr[0] != 1 || colptr[n] < 2) return SJ_E_ARGUMENT;
    nnz = colptr[n] - 1;
    sj_begin(h);
    sj_drop_factor(h);
    sj_drop_pattern(h);
    h->own_p = sj_malloc_huge((size_t)(n + 1) * sizeof(SuiteSparse_long));
    h->own_i = sj_malloc_huge((size_t)nnz * sizeof(SuiteSparse_long));
    if (h->own_p != NULL && h->own_i != NULL) {
        memcpy(h->own_p, colptr, (size_t)(n + 1) * sizeof(SuiteSparse_long));
        memcpy(h->own_i, rowind, (size_t)nnz * sizeof(SuiteSparse_long));
        if (sj_take_pattern(n, h->own_p, h->own_i, &h->pattern_hash) == NULL) {
            h->n = n;
            h->nnz = nnz;
            sj_header(h, n, h->own_p, h->own_i);
            h->pending = pthread_create(&h->worker, NULL, sj_analyze_worker, h) == 0;
        }
    }
    if (h->pending) return SJ_OK;
    free(h->own_p);
    free(h->own_i);
    h->own_p = h->own_i = NULL;
    h->A.p = h->A.i = NULL;
    sj_drop_pattern(h);
    return SJ_E_STATE;
}

/* Wait for the analysis sj_cholmod_analyze_start began; the status
 * sj_cholmod_analyze would have returned. */
int sj_cholmod_analyze_finish(void *handle)
{
    sj_cholmod_t *h = handle;
    int status;
    if (h == NULL) return SJ_E_HANDLE;
    if (!h->pending) {
        sj_set_message(h, "no analysis was started");
        return SJ_E_STATE;
    }
    status = sj_join(h);
    if (status != SJ_OK) {
        sj_drop_factor(h);
        return status < 0 ? status : CHOLMOD_INVALID;
    }
    h->minor = h->n;
    return SJ_OK;
}

/* The caller's row indices packed while CHOLMOD factors from its own
 * permuted copy (cholmod_l_factorize reads A only to form tril(PAP')): each
 * row of column j becomes the 16-bit gap to the next row of the column (to
 * j after the last, the diagonal) at the head of the same array, gaps of
 * 0xFFFF or more go to a list of their own, and the whole pages behind the
 * packed part go back to the system (MADV_DONTNEED: they read as zeros until
 * written again). So 3/4 of the index array (71 MB at 1e6) is not resident
 * at the factorization's peak; sj_unpack_rows writes the same indices back. */
typedef struct {
    SuiteSparse_long *far;   /* the long distances, in entry order */
    SuiteSparse_long nfar;
} sj_packed_t;

static int sj_pack_rows(const cholmod_sparse *A, sj_packed_t *pk)
{
    const SuiteSparse_long *Ap = A->p;
    SuiteSparse_long *Ai = A->i;
    uint16_t *d = (uint16_t *)A->i;
    SuiteSparse_long n = (SuiteSparse_long)A->ncol, nnz = Ap[n], j, q, nfar = 0;
    long page = sysconf(_SC_PAGESIZE);
    uintptr_t head, tail;
    for (j = 0; j < n; j++) {
        for (q = Ap[j]; q < Ap[j + 1]; q++) {
            SuiteSparse_long gap = (q + 1 < Ap[j + 1] ? Ai[q + 1] : j) - Ai[q];
            if (gap < 0 || (gap == 0 && q + 1 < Ap[j + 1])) return 0;   /* rows not ascending, or below j: left as they are */
            if (gap >= 0xFFFF) nfar++;
        }
    }
    if (nfar > nnz / 8 || page <= 0) return 0;   /* not worth it */
    pk->far = malloc((size_t)(nfar > 0 ? nfar : 1) * sizeof(SuiteSparse_long));
    if (pk->far == NULL) return 0;
    pk->nfar = 0;
    /* d[q] overwrites bytes of Ai[q / 4] only, an entry already read */
    for (j = 0; j < n; j++) {
        for (q = Ap[j]; q < Ap[j + 1]; q++) {
            SuiteSparse_long gap = (q + 1 < Ap[j + 1] ? Ai[q + 1] : j) - Ai[q];
            if (gap >= 0xFFFF) {
                pk->far[pk->nfar++] = gap;
                d[q] = 0xFFFF;
            } else {
                d[q] = (uint16_t)gap;
            }
        }
    }
    head = ((uintptr_t)(d + nnz) + (uintptr_t)page - 1) / (uintptr_t)page * (uintptr_t)page;
    tail = (uintptr_t)(Ai + nnz) / (uintptr_t)page * (uintptr_t)page;
    if (tail > head) madvise((void *)head, tail - head, MADV_DONTNEED);
    return 1;
}

static void sj_unpack_rows(const cholmod_sparse *A, sj_packed_t *pk)
{
    const SuiteSparse_long *Ap = A->p;
    SuiteSparse_long *Ai = A->i;
    const uint16_t *d = (const uint16_t *)A->i;
    SuiteSparse_long j, q, row, k = pk->nfar;
    /* backwards: Ai[q] overwrites d[4q..4q+3], entries already read */
    for (j = (SuiteSparse_long)A->ncol - 1; j >= 0; j--) {
        row = j;
        for (q = Ap[j + 1] - 1; q >= Ap[j]; q--) {
            SuiteSparse_long gap = d[q];
            if (gap == 0xFFFF) gap = pk->far[--k];
            row -= gap;
            Ai[q] = row;
        }
    }
    free(pk->far);
    pk->far = NULL;
}

/* cholmod_l_factorize_p's supernodal branch for an upper-triangle A with a
 * fill-reducing permutation (CHOLMOD 3.0's cholmod_factorize.c, step by
 * step: the same calls in the same order, so the same factor), with A's row
 * indices packed between the forming of tril(PAP') and the numeric
 * factorization (sj_pack_rows), unpacked once that copy is freed. */
static int sj_factorize_packed(sj_cholmod_t *h)
{
    cholmod_common *c = &h->common;
    cholmod_factor *L = h->L;
    cholmod_sparse *S;
    double zero[2] = {0.0, 0.0};
    sj_packed_t pk = {NULL, 0};
    int ok, packed = 0, status;
    c->status = CHOLMOD_OK;
    /* workspace s = 2 nrow + 2 nsuper, as cholmod_l_factorize_p asks */
    if (L->nsuper > SIZE_MAX / 4 || h->A.nrow > SIZE_MAX / 4)
        return cholmod_l_factorize(&h->A, L, c);   /* reports "problem too large" */
    cholmod_l_allocate_work(h->A.nrow, 2 * h->A.nrow + 2 * L->nsuper, 0, c);
    if (c->status < CHOLMOD_OK) return 0;
    S = cholmod_l_ptranspose(&h->A, 2, L->Perm, NULL, 0, c);
    if (c->status == CHOLMOD_OK) {
        packed = sj_pack_rows(&h->A, &pk);
        cholmod_l_super_numeric(S, NULL, zero, L, c);
    }
    status = c->status;
    if (c->status >= CHOLMOD_OK && !c->final_asis) {
        ok = cholmod_l_change_factor(L->xtype, c->final_ll, c->final_super, c->final_pack,
                                     c->final_monotonic, L, c);
        if (ok && c->final_resymbol && !L->is_super)
            cholmod_l_resymbol_noperm(S, NULL, 0, c->final_pack, L, c);
    }
    cholmod_l_free_sparse(&S, c);
    if (packed) sj_unpack_rows(&h->A, &pk);
    c->status = c->status > status ? c->status : status;
    return c->status >= CHOLMOD_OK;
}

/* Numeric factorization with the values val (same pattern as analyzed,
 * passed again to be checked).  On SJ_NOT_POSDEF, *failed_column is the
 * 1-based ORIGINAL column where the factorization broke down (else 0). */
int sj_cholmod_factorize(void *handle, int64_t n, int64_t *colptr, int64_t *rowind,
                         const double *val, int64_t *failed_column)
{
    sj_cholmod_t *h = handle;
    int ok, status;
    if (failed_column != NULL) *failed_column = 0;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;
    sj_begin(h);
    if (h->L == NULL) {
        sj_set_message(h, "factorize called before analyze");
        return SJ_E_STATE;
    }
    if (n != h->n || colptr == NULL || val == NULL ||
        (h->nnz > 0 && rowind == NULL) || colptr[n] - 1 != h->nnz) {
        sj_set_message(h, "matrix size differs from the analyzed one");
        return SJ_E_PATTERN;
    }
    if (sj_take_analyzed(n, h->nnz, colptr, rowind) != h->pattern_hash) {
        sj_shift(colptr, n + 1, 1);
        sj_shift(rowind, h->nnz, 1);
        sj_set_message(h, "matrix pattern differs from the analyzed one");
        return SJ_E_PATTERN;
    }
    h->factored = 0;
    h->minor = n;
    sj_header(h, n, colptr, rowind);
    h->A.x = (void *)val;            /* CHOLMOD does not modify A */
    h->A.xtype = CHOLMOD_REAL;
    malloc_trim(0);   /* the peak is the factor's: give back first what the caller freed */
    if (h->L->is_super && h->L->ordering != CHOLMOD_NATURAL && h->L->Perm != NULL && h->A.stype > 0)
        ok = sj_factorize_packed(h);
    else
        ok = cholmod_l_factorize(&h->A, h->L, &h->common);
    sj_shift(colptr, n + 1, 1);
    sj_shift(rowind, h->nnz, 1);
    h->A.p = h->A.i = h->A.x = NULL;
    h->A.xtype = CHOLMOD_PATTERN;
    status = sj_end(h, ok);
    if (status == SJ_NOT_POSDEF || (status == SJ_OK && h->L->minor < h->L->n)) {
        SuiteSparse_long minor = (SuiteSparse_long)h->L->minor;
        const SuiteSparse_long *perm = h->L->Perm;
        h->minor = minor;
        if (failed_column != NULL && minor < n)
            *failed_column = (perm != NULL ? perm[minor] : minor) + 1;
        return SJ_NOT_POSDEF;
    }
    if (status != SJ_OK) return status;
    h->factored = 1;
    return SJ_OK;
}

static int sj_schur_solve(sj_cholmod_t *h, int64_t nrhs, const double *b, int64_t ldb, double *x,
                          int64_t ldx);

/* x(n, nrhs) = A^-1 b(n, nrhs), column-major, leading dimension n (after
 * sj_cholmod_schur_analyze: the interior block, n - nschur). */
int sj_cholmod_solve_ld(void *handle, int64_t nrhs, const double *b, int64_t ldb, double *x, int64_t ldx);

int sj_cholmod_solve(void *handle, int64_t nrhs, const double *b, double *x)
{
    return sj_cholmod_solve_ld(handle, nrhs, b, -1, x, -1);
}

/* The same with the leading dimensions ldb and ldx of b and x (at least the
 * order; -1: the order): the columns are the leading rows of longer arrays,
 * read and written in place; the other rows of x are left alone. */
int sj_cholmod_solve_ld(void *handle, int64_t nrhs, const double *b, int64_t ldb, double *x, int64_t ldx)
{
    sj_cholmod_t *h = handle;
    cholmod_dense B, *X;
    SuiteSparse_long j;
    int status;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    sj_begin(h);
    if (!h->factored || h->L == NULL) {
        sj_set_message(h, "solve called without a valid factorization");
        return SJ_E_STATE;
    }
    if (nrhs < 0 || (h->n > 0 && nrhs > 0 && (b == NULL || x == NULL))) {
        sj_set_message(h, "invalid right-hand side");
        return SJ_E_ARGUMENT;
    }
    if (h->n == 0 || nrhs == 0) return SJ_OK;
    if (ldb == -1) ldb = h->n - h->nschur;
    if (ldx == -1) ldx = h->n - h->nschur;
    if (ldb < h->n - h->nschur || ldx < h->n - h->nschur) {
        sj_set_message(h, "leading dimension below the order");
        return SJ_E_ARGUMENT;
    }
    if (h->nschur > 0) return sj_schur_solve(h, nrhs, b, ldb, x, ldx);
    memset(&B, 0, sizeof(cholmod_dense));
    B.nrow = (size_t)h->n;
    B.ncol = (size_t)nrhs;
    B.nzmax = (size_t)ldb * (size_t)nrhs;
    B.d = (size_t)ldb;
    B.x = (void *)b;                 /* read only */
    B.z = NULL;
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    X = cholmod_l_solve(CHOLMOD_A, h->L, &B, &h->common);
    status = sj_end(h, X != NULL);
    if (X == NULL) return status < 0 ? status : CHOLMOD_INVALID;
    for (j = 0; j < nrhs; j++) {
        memcpy(x + (size_t)j * (size_t)ldx, (const double *)X->x + (size_t)j * X->d,
               (size_t)h->n * sizeof(double));
    }
    cholmod_l_free_dense(&X, &h->common);
    return status < 0 ? status : SJ_OK;
}

/* d[original column] = pivot of that column: L_jj^2 (LL^T) or D_jj (LDL^T).
 * Columns not reached by a failed factorization (including the failing one)
 * get 0. */
int sj_cholmod_pivots(void *handle, double *d)
{
    sj_cholmod_t *h = handle;
    cholmod_factor *L;
    const SuiteSparse_long *perm;
    SuiteSparse_long j, n;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    L = h->L;
    n = h->n - h->nschur;           /* the interior only, after sj_cholmod_schur_analyze */
    if (d == NULL) return SJ_E_ARGUMENT;
    for (j = 0; j < n; j++) d[j] = 0.0;
    if (L == NULL || L->xtype != CHOLMOD_REAL || L->x == NULL) return SJ_E_STATE;
    perm = L->Perm;
    if (L->is_super) {
        const SuiteSparse_long *super = L->super, *pi = L->pi, *px = L->px;
        const double *lx = L->x;
        SuiteSparse_long s, nsuper = (SuiteSparse_long)L->nsuper;
        for (s = 0; s < nsuper; s++) {
            SuiteSparse_long k1 = super[s], k2 = super[s + 1];
            SuiteSparse_long nsrow = pi[s + 1] - pi[s];
            for (j = k1; j < k2 && j < h->minor && j < n; j++) {
                double ljj = lx[px[s] + (j - k1) * nsrow + (j - k1)];
                d[perm != NULL ? perm[j] : j] = ljj * ljj;
            }
        }
    } else {
        const SuiteSparse_long *lp = L->p;
        const double *lx = L->x;
        for (j = 0; j < n && j < h->minor; j++) {
            double ljj = lx[lp[j]];  /* diagonal is first in each column */
            d[perm != NULL ? perm[j] : j] = L->is_ll ? ljj * ljj : ljj;
        }
    }
    return SJ_OK;
}

/* Statistics of the current analysis/factor:
 *   factor_nnz   entries of L as stored (supernodal: including the zeros of
 *                relaxed amalgamation),
 *   factor_bytes memory held by L (values and integer structure),
 *   flops        CHOLMOD's LL' flop count of the chosen ordering (Common->fl),
 *   peak_bytes   CHOLMOD's peak memory use so far (Common->memory_usage),
 *   lnz          fundamental nnz(L) (Common->lnz). */
int sj_cholmod_info(void *handle, int64_t *factor_nnz, double *factor_bytes,
                    double *flops, double *peak_bytes, double *lnz)
{
    sj_cholmod_t *h = handle;
    cholmod_factor *L;
    double entries = 0.0, bytes = 0.0;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    L = h->L;
    if (L != NULL) {
        double n = (double)L->n;
        bytes = 2.0 * n * sizeof(SuiteSparse_long);       /* Perm, ColCount */
        if (L->is_super) {
            const SuiteSparse_long *super = L->super, *pi = L->pi;
            SuiteSparse_long s, nsuper = (SuiteSparse_long)L->nsuper;
            for (s = 0; s < nsuper; s++) {
                double nscol = (double)(super[s + 1] - super[s]);
                double nsrow = (double)(pi[s + 1] - pi[s]);
                entries += nscol * nsrow - nscol * (nscol - 1.0) / 2.0;
            }
            bytes += (double)L->xsize * sizeof(double)
                   + (double)L->ssize * sizeof(SuiteSparse_long)
                   + 3.0 * ((double)L->nsuper + 1.0) * sizeof(SuiteSparse_long);
        } else {
            const SuiteSparse_long *colcount = L->ColCount;
            SuiteSparse_long j;
            if (L->xtype != CHOLMOD_PATTERN && L->nz != NULL) {
                const SuiteSparse_long *nz = L->nz;
                for (j = 0; j < (SuiteSparse_long)L->n; j++) entries += (double)nz[j];
            } else if (colcount != NULL) {
                for (j = 0; j < (SuiteSparse_long)L->n; j++) entries += (double)colcount[j];
            }
            bytes += (double)L->nzmax * (sizeof(double) + sizeof(SuiteSparse_long))
                   + 5.0 * n * sizeof(SuiteSparse_long);
        }
    }
    if (factor_nnz != NULL) *factor_nnz = (int64_t)entries;
    if (factor_bytes != NULL) *factor_bytes = bytes;
    if (flops != NULL) *flops = h->common.fl;
    if (peak_bytes != NULL) *peak_bytes = (double)h->common.memory_usage;
    if (lnz != NULL) *lnz = h->common.lnz;
    return SJ_OK;
}

/* Name of the fill-reducing ordering used by the analysis, NUL-terminated
 * into buf (len bytes). */
int sj_cholmod_ordering(void *handle, char *buf, int64_t len)
{
    sj_cholmod_t *h = handle;
    const char *name = "none";
    if (buf == NULL || len <= 0) return SJ_E_ARGUMENT;
    buf[0] = '\0';
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    if (h->L != NULL) {
        switch (h->L->ordering) {
        case CHOLMOD_NATURAL: name = "natural"; break;
        case CHOLMOD_GIVEN:
            name = h->given_is_node_metis ? "METIS (node graph)"
                 : h->given_is_node_amd ? "AMD (node graph)" : h->given_is_amd ? "AMD" : "given";
            break;
        case CHOLMOD_AMD: name = "AMD"; break;
        case CHOLMOD_METIS: name = "METIS"; break;
        case CHOLMOD_NESDIS: name = "NESDIS"; break;
        case CHOLMOD_COLAMD: name = "COLAMD"; break;
        case CHOLMOD_POSTORDERED: name = "natural (postordered)"; break;
        default: name = "unknown"; break;
        }
    }
    strncpy(buf, name, (size_t)len - 1);
    buf[len - 1] = '\0';
    return SJ_OK;
}

/* Last message recorded on the handle (CHOLMOD's or the shim's), NUL-terminated. */
int sj_cholmod_message(void *handle, char *buf, int64_t len)
{
    sj_cholmod_t *h = handle;
    if (buf == NULL || len <= 0) return SJ_E_ARGUMENT;
    buf[0] = '\0';
    if (h == NULL) return SJ_E_HANDLE;
    strncpy(buf, h->message, (size_t)len - 1);
    buf[len - 1] = '\0';
    return SJ_OK;
}

/* After an out-of-memory status: the size of the allocation that failed
 * (0 if unknown) and the bytes CHOLMOD held at that moment. */
int sj_cholmod_memory(void *handle, double *failed_request, double *inuse)
{
    sj_cholmod_t *h = handle;
    if (failed_request != NULL) *failed_request = (double)sj_failed_request;
    if (inuse != NULL) *inuse = h != NULL ? (double)h->common.memory_inuse : 0.0;
    return h != NULL ? SJ_OK : SJ_E_HANDLE;
}

/* ---- Static condensation with the boundary ordered last (issue 24) ----
 *
 * The part's matrix A (order n, its last nb columns the boundary) is ordered
 * with the interior first, in the order the analysis of the interior block
 * chose, and the boundary last in its own order. Its factor is then
 *     L = | L_ii  0    |    L_ii L_ii' = P A_ii P',  L_bb L_bb' = A_bb - L_bi L_bi',
 *         | L_bi  L_bb |
 * so one factorization gives the factor of the interior and the Schur
 * complement of the boundary. */

/* Symbolic factor of h->A with the given permutation, not postordered. */
static cholmod_factor *sj_given_symbolic(sj_cholmod_t *h, SuiteSparse_long *perm)
{
    cholmod_factor *L;
    int nm = h->common.nmethods, o0 = h->common.method[0].ordering, post = h->common.postorder;
    h->common.nmethods = 1;
    h->common.method[0].ordering = CHOLMOD_GIVEN;
    h->common.postorder = 0;
    L = cholmod_l_analyze_p(&h->A, perm, NULL, 0, &h->common);
    h->common.nmethods = nm;
    h->common.method[0].ordering = o0;
    h->common.postorder = post;
    return L;
}

/* CAMD's permutation of h->A with the boundary (columns ni..n-1) constrained
 * last, NULL on failure. *low: its fill is low by CHOLMOD's own test for
 * trying METIS after AMD (flops per nnz(L), nnz(L) per nnz(A)); then the
 * analysis of the interior alone, which orders it as cholmod_analyze would
 * (AMD, since METIS would not be tried), is not worth its cost. */
static SuiteSparse_long *sj_camd_perm(sj_cholmod_t *h, SuiteSparse_long ni, int *low)
{
    SuiteSparse_long n = h->n, j, *cmember, *perm;
    double fl, lnz;
    *low = 0;
    cmember = sj_malloc((size_t)(n > 0 ? n : 1) * sizeof(SuiteSparse_long));
    perm = sj_malloc((size_t)(n > 0 ? n : 1) * sizeof(SuiteSparse_long));
    if (cmember != NULL && perm != NULL) {
        for (j = 0; j < n; j++) cmember[j] = j < ni ? 0 : 1;
        if (!cholmod_l_camd(&h->A, NULL, 0, cmember, perm, &h->common)) {
            free(perm);
            perm = NULL;
        }
    } else {
        free(perm);
        perm = NULL;
    }
    free(cmember);
    fl = h->common.fl;
    lnz = h->common.lnz;
    *low = perm != NULL && (fl < SJ_METIS_FL_PER_LNZ * lnz || lnz < SJ_METIS_LNZ_PER_NNZ * (double)h->nnz);
    return perm;
}

/* The symbolic factor of h->A for perm if it keeps the boundary (columns
 * ni..n-1) last, else NULL. */
static cholmod_factor *sj_boundary_last(sj_cholmod_t *h, SuiteSparse_long *perm, SuiteSparse_long ni)
{
    cholmod_factor *L = sj_given_symbolic(h, perm);
    SuiteSparse_long j;
    int ok = L != NULL;
    for (j = ni; ok && j < h->n; j++) ok = ((const SuiteSparse_long *)L->Perm)[j] >= ni;
    if (!ok && L != NULL) cholmod_l_free_factor(&L, &h->common);
    return L;
}

/* The symbolic factor of the whole part with the boundary (columns ni..n-1)
 * last, the cheaper (CHOLMOD's flop count) of two orderings: perm (the
 * interior's own ordering, the boundary appended) and CAMD on the whole
 * pattern with the boundary constrained last (it sees the fill the boundary
 * brings into the interior columns). NULL on failure. */
static cholmod_factor *sj_schur_symbolic(sj_cholmod_t *h, SuiteSparse_long *perm, SuiteSparse_long ni)
{
    SuiteSparse_long *perm2;
    cholmod_factor *L1, *L2 = NULL;
    double fl1;
    int low;
    L1 = sj_given_symbolic(h, perm);
    if (L1 == NULL) return NULL;
    fl1 = h->common.fl;
    perm2 = sj_camd_perm(h, ni, &low);
    if (perm2 != NULL) L2 = sj_boundary_last(h, perm2, ni);
    free(perm2);
    if (L2 != NULL) {
        if (h->common.fl < fl1) {
            cholmod_l_free_factor(&L1, &h->common);
            return L2;
        }
        cholmod_l_free_factor(&L2, &h->common);
    }
    h->common.fl = fl1;
    h->common.status = CHOLMOD_OK;
    return L1;
}

/* Start a schur analysis of the whole part: check the pattern, shift it to
 * 0-based in place and point h->A at it (sj_schur_done shifts it back). */
static int sj_schur_begin(sj_cholmod_t *h, int64_t n, int64_t nb, int64_t *colptr, int64_t *rowind)
{
    const char *bad;
    uint64_t hash;
    if (nb <= 0 || nb > n || colptr == NULL || rowind == NULL) {
        sj_set_message(h, "invalid boundary for the schur analysis");
        return SJ_E_ARGUMENT;
    }
    bad = sj_take_pattern(n, colptr, rowind, &hash);
    if (bad != NULL) {
        sj_set_message(h, bad);
        return SJ_E_ARGUMENT;
    }
    h->pattern_hash = hash;
    h->n = n;
    h->nnz = colptr[n];             /* 0-based now */
    sj_header(h, n, colptr, rowind);
    return SJ_OK;
}

/* Finish a schur analysis: the caller's arrays back to 1-based, the status. */
static int sj_schur_done(sj_cholmod_t *h, int64_t nb, int64_t *colptr, int64_t *rowind)
{
    int status;
    sj_shift(colptr, h->n + 1, 1);
    sj_shift(rowind, h->nnz, 1);
    h->A.p = h->A.i = NULL;
    status = sj_end(h, h->L != NULL);
    if (status != SJ_OK) {
        sj_drop_factor(h);
        return status < 0 ? status : CHOLMOD_INVALID;
    }
    h->minor = h->n;
    h->nschur = nb;
    return SJ_OK;
}

/* Analyze the whole part (1-based upper triangle, rows sorted, diagonal
 * present; its last nb columns the boundary) with CAMD alone, the boundary
 * constrained last, when CAMD's fill is low by CHOLMOD's test: SJ_OK, the
 * interior's own analysis skipped. Otherwise SJ_TRY_INTERIOR and no
 * analysis: analyze the interior block, then sj_cholmod_schur_analyze. */
int sj_cholmod_schur_camd(void *handle, int64_t n, int64_t nb, int64_t *colptr, int64_t *rowind)
{
    sj_cholmod_t *h = handle;
    SuiteSparse_long *perm;
    int status, low;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    sj_begin(h);
    sj_drop_factor(h);
    sj_drop_pattern(h);
    sj_drop_graph(h);
    h->given_is_node_metis = 0;
    h->given_is_amd = 0;
    h->given_is_node_amd = 0;
    status = sj_schur_begin(h, n, nb, colptr, rowind);
    if (status != SJ_OK) return status;
    perm = sj_camd_perm(h, n - nb, &low);
    if (perm != NULL && low) h->L = sj_boundary_last(h, perm, n - nb);
    free(perm);
    if (h->L == NULL) {
        sj_shift(colptr, n + 1, 1);
        sj_shift(rowind, h->nnz, 1);
        h->A.p = h->A.i = NULL;
        sj_drop_pattern(h);
        h->common.status = CHOLMOD_OK;
        return SJ_TRY_INTERIOR;
    }
    return sj_schur_done(h, nb, colptr, rowind);
}

/* Re-analyze for the whole part: the handle holds the analysis of the
 * interior block (its first n - nb columns, by sj_cholmod_analyze); keep its
 * permutation, append the boundary, and analyze the whole pattern (1-based
 * upper triangle, rows sorted, diagonal present) with that permutation, not
 * postordered (a postorder could move interior columns behind the boundary),
 * or with CAMD's where that is cheaper (sj_schur_symbolic). Solves and
 * pivots then refer to the interior block only. */
int sj_cholmod_schur_analyze(void *handle, int64_t n, int64_t nb, int64_t *colptr, int64_t *rowind)
{
    sj_cholmod_t *h = handle;
    SuiteSparse_long ni, j, *perm;
    int status;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    sj_begin(h);
    ni = n - nb;
    if (h->L == NULL || h->L->Perm == NULL || h->n != ni || nb <= 0 || colptr == NULL ||
        rowind == NULL || colptr[ni] - 1 != h->nnz) {
        sj_set_message(h, "schur analysis without the analysis of the interior");
        return SJ_E_STATE;
    }
    perm = sj_malloc((size_t)n * sizeof(SuiteSparse_long));
    if (perm == NULL) {
        sj_set_message(h, "out of memory for the permutation");
        return SJ_E_NOMEM;
    }
    memcpy(perm, h->L->Perm, (size_t)ni * sizeof(SuiteSparse_long));
    for (j = ni; j < n; j++) perm[j] = j;
    status = sj_schur_begin(h, n, nb, colptr, rowind);
    if (status != SJ_OK) {
        free(perm);
        return status;
    }
    sj_drop_factor(h);
    h->L = sj_schur_symbolic(h, perm, ni);
    free(perm);
    return sj_schur_done(h, nb, colptr, rowind);
}


/* The end of a solve through cholmod_l_solve2's handles: the four dense
 * arrays freed, the status (SJ_OK, or the error of a failed solve). */
static int sj_solve2_end(sj_cholmod_t *h, int ok, cholmod_dense **Y, cholmod_dense **Z, cholmod_dense **W,
                         cholmod_dense **E)
{
    int status;
    cholmod_l_free_dense(Y, &h->common);
    cholmod_l_free_dense(Z, &h->common);
    cholmod_l_free_dense(W, &h->common);
    cholmod_l_free_dense(E, &h->common);
    status = sj_end(h, ok);
    if (!ok) return status < 0 ? status : CHOLMOD_INVALID;
    return status < 0 ? status : SJ_OK;
}

/* Every entry l of the trailing block L_bb of the whole part's factor (after
 * sj_cholmod_schur_analyze and sj_cholmod_factorize), read in place: fn(ctx,
 * row, col, l) with row in the part's boundary order (original index - ni)
 * and col in P's order (position - ni). The boundary columns may spread over
 * several supernodes, and the first of them may also hold interior columns.
 * SJ_E_STATE for a simplicial LDL' factor (no L_bb of L L'). */
static int sj_lbb_each(const sj_cholmod_t *h, void (*fn)(void *, SuiteSparse_long, SuiteSparse_long, double),
                       void *ctx)
{
    const cholmod_factor *L = h->L;
    const SuiteSparse_long *perm = L->Perm;
    SuiteSparse_long n = h->n, ni = h->n - h->nschur, j, r, i;
    if (L->is_super) {
        const SuiteSparse_long *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
        const double *lx = L->x;
        SuiteSparse_long s;
        for (s = (SuiteSparse_long)L->nsuper - 1; s >= 0 && super[s + 1] > ni; s--) {
            SuiteSparse_long k1 = super[s], nsrow = pi[s + 1] - pi[s];
            for (j = (k1 > ni ? k1 : ni); j < super[s + 1]; j++) {
                for (r = j - k1; r < nsrow; r++) {
                    i = ls[pi[s] + r];
                    fn(ctx, (perm != NULL ? perm[i] : i) - ni, j - ni, lx[px[s] + (j - k1) * nsrow + r]);
                }
            }
        }
    } else {
        const SuiteSparse_long *lp = L->p, *li = L->i, *lnz = L->nz;
        const double *lx = L->x;
        if (!L->is_ll) return SJ_E_STATE;
        for (j = ni; j < n; j++)
            for (r = lp[j]; r < lp[j] + lnz[j]; r++) fn(ctx, (perm != NULL ? perm[li[r]] : li[r]) - ni, j - ni, lx[r]);
    }
    return SJ_OK;
}

/* sj_lbb_each's visitors: an entry into a dense block, or into a product. */
typedef struct {
    double *lbb;
    SuiteSparse_long nb;
} sj_lbb_dense_t;

static void sj_lbb_store(void *ctx, SuiteSparse_long row, SuiteSparse_long col, double l)
{
    sj_lbb_dense_t *d = ctx;
    d->lbb[row + col * d->nb] = l;
}

typedef struct {
    int transpose;
    int64_t nrhs, ldx, ldy;
    const double *x;
    double *y;
} sj_lbb_product_t;

static void sj_lbb_add(void *ctx, SuiteSparse_long row, SuiteSparse_long col, double l)
{
    sj_lbb_product_t *p = ctx;
    int64_t c;
    for (c = 0; c < p->nrhs; c++) {
        if (p->transpose) p->y[col + c * p->ldy] += l * p->x[row + c * p->ldx];
        else p->y[row + c * p->ldy] += l * p->x[col + c * p->ldx];
    }
}

/* y = L_bb x (transpose = 0) or y = L_bb' x (transpose = 1), nrhs columns of
 * nb = nschur rows, leading dimensions ldx, ldy: rows in P's order on the
 * side of the factor's columns (x without transpose, y with) and in the
 * part's boundary order on the side of its rows. */
static int sj_lbb_apply(const sj_cholmod_t *h, int transpose, int64_t nrhs, const double *x, int64_t ldx,
                        double *y, int64_t ldy)
{
    sj_lbb_product_t p = {transpose, nrhs, ldx, ldy, x, y};
    int64_t r, c;
    for (c = 0; c < nrhs; c++)
        for (r = 0; r < h->nschur; r++) y[r + c * ldy] = 0.0;
    return sj_lbb_each(h, sj_lbb_add, &p);
}

/* The trailing block L_bb of the factor (after sj_cholmod_schur_analyze and
 * sj_cholmod_factorize), its rows in the original boundary order (the
 * ordering may permute the boundary among itself): lbb(nb, nb), column-major,
 * so that lbb lbb' = L_bb L_bb' in that order. The boundary columns may
 * spread over several supernodes, and the first of them may also hold
 * interior columns. */
int sj_cholmod_schur_block(void *handle, int64_t nb, double *lbb)
{
    sj_cholmod_t *h = handle;
    sj_lbb_dense_t d;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    if (!h->factored || h->L == NULL || nb != h->nschur || lbb == NULL) return SJ_E_STATE;
    memset(lbb, 0, (size_t)nb * (size_t)nb * sizeof(double));
    d.lbb = lbb;
    d.nb = nb;
    return sj_lbb_each(h, sj_lbb_store, &d);
}

/* Half a solve with the whole part's factor after sj_cholmod_schur_analyze and
 * sj_cholmod_factorize (P A P' = L L', the boundary last, A's boundary block
 * shifted by D: only L_bb sees it), nrhs columns, column-major:
 *   forward (backward = 0): z = L^-1 P f for in = f(n, nrhs) in the part's
 *     own order (interior rows, then boundary rows; leading dimension ldin);
 *     out(ni, nrhs) = z's interior rows (P's order, leading dimension ldout)
 *     and bnd(nb, nrhs) = L_bb z_b in the part's boundary order: f* = f_b -
 *     A_bi A_ii^-1 f_i (L_bi L_ii' = P_b A_bi P_i', so z_b = L_bb^-1 P_b f*);
 *   backward (backward = 1): in(ni, nrhs) = such interior rows z_i (P's
 *     order), bnd(nb, nrhs) = u_b (the part's boundary order); out(ni,
 *     nrhs) = the interior rows, in the part's order, of P' L'^-1 [z_i;
 *     L_bb' P_b u_b]: A_ii^-1 (f_i - A_ib u_b) for the f that gave z_i.
 * A condensation's loads and its recovery for one triangular solve each
 * instead of two; L_bb is read in place (sj_lbb_apply). */
int sj_cholmod_schur_half(void *handle, int backward, int64_t nrhs, const double *in, int64_t ldin,
                          double *bnd, double *out, int64_t ldout)
{
    sj_cholmod_t *h = handle;
    cholmod_dense *Y, *Z = NULL, *W = NULL, *E = NULL;
    const SuiteSparse_long *perm;
    SuiteSparse_long n, ni, nb, i, j, k;
    double *y, *z;
    int ok;
    if (h == NULL) return SJ_E_HANDLE;
    if (h->pending && sj_cholmod_analyze_finish(h) != SJ_OK) return SJ_E_STATE;   /* never beside the worker */
    sj_begin(h);
    if (!h->factored || h->L == NULL || h->nschur <= 0) {
        sj_set_message(h, "half solve without a boundary-last factorization");
        return SJ_E_STATE;
    }
    n = h->n;
    nb = h->nschur;
    ni = n - nb;
    if (nrhs < 0 || (nrhs > 0 && (in == NULL || out == NULL || bnd == NULL)) || ldin < (backward ? ni : n)
        || ldout < ni) {
        sj_set_message(h, "invalid right-hand side");
        return SJ_E_ARGUMENT;
    }
    if (nrhs == 0) return SJ_OK;
    perm = h->L->Perm;
    Y = cholmod_l_allocate_dense((size_t)n, (size_t)nrhs, (size_t)n, CHOLMOD_REAL, &h->common);
    if (Y == NULL) return sj_end(h, 0);
    y = Y->x;
    for (j = 0; j < nrhs; j++) {
        if (backward) {                   /* Y = [z_i; L_bb' P_b u_b] */
            for (k = 0; k < ni; k++) y[k + j * n] = in[k + j * ldin];
        } else {                          /* Y = P f */
            for (k = 0; k < n; k++) {
                i = perm != NULL ? perm[k] : k;
                y[k + j * n] = in[i + j * ldin];
            }
        }
    }
    if (backward && sj_lbb_apply(h, 1, nrhs, bnd, nb, y + ni, n) != SJ_OK) {
        cholmod_l_free_dense(&Y, &h->common);
        sj_set_message(h, "half solve: no L L' trailing block");
        return SJ_E_STATE;
    }
    ok = cholmod_l_solve2(backward ? CHOLMOD_Lt : CHOLMOD_L, h->L, Y, NULL, &Z, NULL, &W, &E, &h->common);
    if (ok) {
        SuiteSparse_long dz = (SuiteSparse_long)Z->d;
        z = Z->x;
        for (j = 0; j < nrhs; j++) {
            for (k = 0; k < n; k++) {
                if (!backward) {
                    if (k < ni) out[k + j * ldout] = z[k + j * dz];
                    continue;
                }
                i = perm != NULL ? perm[k] : k;
                if (i < ni) out[i + j * ldout] = z[k + j * dz];
            }
        }
        if (!backward && sj_lbb_apply(h, 0, nrhs, z + ni, dz, bnd, nb) != SJ_OK) ok = 0;
    }
    return sj_solve2_end(h, ok, &Y, &Z, &W, &E);
}

/* x = A_ii^-1 b for the interior block after sj_cholmod_schur_analyze:
 * forward solve with L on [P_i b; 0], the boundary part of the result set to
 * zero, backward solve with L': the boundary rows then drop out exactly.
 * The permutations are copies done here (CHOLMOD's P and P' solves copy the
 * same values); the two triangular solves share their result and workspace
 * arrays (cholmod_l_solve2's handles): three arrays of n x nrhs in all,
 * allocated once, instead of a new one per step. */
static int sj_schur_solve(sj_cholmod_t *h, int64_t nrhs, const double *b, int64_t ldb, double *x,
                          int64_t ldx)
{
    cholmod_dense *Y, *Z = NULL, *W = NULL, *E = NULL;
    const SuiteSparse_long *perm = h->L->Perm;
    SuiteSparse_long n = h->n, ni = h->n - h->nschur, i, j, k;
    double *y;
    int ok;
    Y = cholmod_l_allocate_dense((size_t)n, (size_t)nrhs, (size_t)n, CHOLMOD_REAL, &h->common);
    if (Y == NULL) return sj_end(h, 0);
    y = Y->x;
    for (j = 0; j < nrhs; j++) {          /* Y = P [b; 0] */
        for (k = 0; k < n; k++) {
            i = perm != NULL ? perm[k] : k;
            y[k + j * n] = i < ni ? b[i + j * ldb] : 0.0;
        }
    }
    ok = cholmod_l_solve2(CHOLMOD_L, h->L, Y, NULL, &Z, NULL, &W, &E, &h->common);
    if (ok) {
        double *z = Z->x;
        for (j = 0; j < nrhs; j++)
            for (i = ni; i < n; i++) z[i + j * (SuiteSparse_long)Z->d] = 0.0;
        ok = cholmod_l_solve2(CHOLMOD_Lt, h->L, Z, NULL, &Y, NULL, &W, &E, &h->common);
    }
    if (ok) {
        y = Y->x;
        for (j = 0; j < nrhs; j++) {      /* x = the interior rows of P' Y */
            for (k = 0; k < n; k++) {
                i = perm != NULL ? perm[k] : k;
                if (i < ni) x[i + j * ldx] = y[k + j * (SuiteSparse_long)Y->d];
            }
        }
    }
    return sj_solve2_end(h, ok, &Y, &Z, &W, &E);
}
