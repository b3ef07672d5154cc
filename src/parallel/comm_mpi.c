/* superjoin: the communication layer over MPI (built with -DSUPERJOIN_MPI=ON).
 *
 * The same functions exist in comm_serial.c for one process; the Fortran
 * module superjoin_parallel_comm (comm.f90) binds to them, so the code paths
 * are the same in both builds. MPI is started when the process was launched
 * by mpirun (or another launcher: its environment says so), or when MUMPS
 * needs a communicator (sj_comm_fortran); a plain run of the MPI build that
 * does not use MUMPS never starts MPI (an Open MPI singleton start forks a
 * daemon, slow and fragile on a loaded machine). Until MPI is started every
 * collective is the identity, as in comm_serial.c. MPI is finalized at exit
 * (atexit), so that every Fortran `stop` ends MPI cleanly and mpirun sees the
 * process's own exit status.
 *
 * Agreement (sj_comm_agree): every rank contributes its status (0 or an exit
 * status) and learns the largest one and the lowest rank that reported it
 * (the protocol around it: src/parallel/comm.f90).
 */
#define _XOPEN_SOURCE 700
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <ftw.h>

static char session_base[4096] = "";

static int launched(void);

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb; (void)flag; (void)ftw;
    remove(path);
    return 0;
}

static void finish(void)
{
    int init = 0, fin = 0;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    if (init && !fin) MPI_Finalize();
    if (session_base[0]) nftw(session_base, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* A process started without mpirun (an Open MPI singleton) gets its own
 * session directory: singletons started at the same moment otherwise race on
 * the shared /tmp/ompi.HOST.UID (one removes it while another creates in it,
 * and orte_init fails). Removed at exit. */
static void private_session_dir(void)
{
    const char *tmp = getenv("TMPDIR");
    if (launched() || getenv("OMPI_MCA_orte_tmpdir_base")) return;
    snprintf(session_base, sizeof session_base, "%s/superjoin-mpi-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(session_base)) { session_base[0] = '\0'; return; }
    setenv("OMPI_MCA_orte_tmpdir_base", session_base, 1);
}

int sj_comm_start(void)
{
    int init = 0;
    MPI_Initialized(&init);
    if (!init) {
        private_session_dir();
        atexit(finish);
        if (MPI_Init(NULL, NULL) != MPI_SUCCESS) return -1;
    }
    return 0;
}

/* Launched by mpirun (Open MPI, PMI or PMIx launchers set these). */
static int launched(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") || getenv("PMIX_RANK");
}

/* Is MPI running in this process (started by sj_comm_start)? */
static int running(void)
{
    int init = 0, fin = 0;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    if (init && !fin) return 1;
    if (!init && launched()) return sj_comm_start() == 0;
    return 0;
}

int sj_comm_rank(void)
{
    int r = 0;
    if (!running()) return 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

int sj_comm_size(void)
{
    int s = 1;
    if (!running()) return 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
}

int sj_comm_is_parallel_build(void) { return 1; }

/* The Fortran handle of the communicator, for MUMPS's comm_fortran. */
int sj_comm_fortran(void)
{
    sj_comm_start();
    return (int)MPI_Comm_c2f(MPI_COMM_WORLD);
}

/* The Fortran handle of MPI_COMM_SELF: a MUMPS instance of this process
 * alone (a part condensed where it lives). */
int sj_comm_self_fortran(void)
{
    sj_comm_start();
    return (int)MPI_Comm_c2f(MPI_COMM_SELF);
}

/* status: this rank's status (0: fine). Returns the largest status of all
 * ranks; *first = the lowest rank whose status equals it (0 if all fine). */
int sj_comm_agree(int status, int *first)
{
    int in[2], out[2], rank, size;
    int worst = status;
    if (!running()) {
        *first = 0;
        return status;
    }
    rank = sj_comm_rank();
    size = sj_comm_size();
    if (MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD) != MPI_SUCCESS) worst = status;
    in[0] = (worst != 0 && status == worst) ? rank : size;
    in[1] = 0;
    out[0] = in[0];
    out[1] = 0;
    if (MPI_Allreduce(in, out, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD) != MPI_SUCCESS) out[0] = rank;
    *first = worst != 0 ? out[0] : 0;
    return worst;
}


/* Broadcast n doubles from rank root to every rank. */
int sj_comm_bcast_real(double *x, int64_t n, int root)
{
    const int64_t chunk = 1 << 30;
    if (!running()) return 0;
    for (int64_t k = 0; k < n; k += chunk) {
        int64_t m = n - k < chunk ? n - k : chunk;
        if (MPI_Bcast(x + k, (int)m, MPI_DOUBLE, root, MPI_COMM_WORLD) != MPI_SUCCESS) return -1;
    }
    return 0;
}

/* Sum n int64 counters over the ranks, in place. */
int sj_comm_sum_i8(int64_t *x, int64_t n)
{
    if (n <= 0 || !running()) return 0;
    return MPI_Allreduce(MPI_IN_PLACE, x, (int)n, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD) == MPI_SUCCESS ? 0 : -1;
}

/* Largest of n doubles over the ranks, in place. */
int sj_comm_max_real(double *x, int64_t n)
{
    if (n <= 0 || !running()) return 0;
    return MPI_Allreduce(MPI_IN_PLACE, x, (int)n, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) == MPI_SUCCESS ? 0 : -1;
}

/* Sum n doubles over the ranks, in place (chunks of 2^30). */
int sj_comm_sum_real(double *x, int64_t n)
{
    const int64_t chunk = 1 << 30;
    if (n <= 0 || !running()) return 0;
    for (int64_t k = 0; k < n; k += chunk) {
        int64_t m = n - k < chunk ? n - k : chunk;
        if (MPI_Allreduce(MPI_IN_PLACE, x + k, (int)m, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD) != MPI_SUCCESS) return -1;
    }
    return 0;
}

/* Gather n int64 values of every rank to rank root, in rank order: rank r's
 * values go to out[displs[r] ..] (counts, displs and out: root only, the
 * caller allocates them; every rank's n is at most INT_MAX). */
int sj_comm_gather_i8(const int64_t *x, int64_t n, int64_t *out, const int *counts, const int *displs, int root)
{
    if (!running()) {
        if (n > 0) memcpy(out, x, (size_t)n * sizeof(int64_t));
        return 0;
    }
    return MPI_Gatherv(x, (int)n, MPI_INT64_T, out, counts, displs, MPI_INT64_T, root, MPI_COMM_WORLD) == MPI_SUCCESS
        ? 0 : -1;
}
