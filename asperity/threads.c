/* OpenBLAS on one thread while the library needs it (threads.h).  A file
 * of its own so that the one process-wide setting the library changes is
 * changed in one place, restored exactly, and nowhere else.
 *
 * Why at all: the Krylov kernels (precond.c) call OpenBLAS from the
 * library's own threads on one right-hand side, where OpenBLAS's threads
 * only spin (3D level 0, loaded machine: 55 ms per threaded solve against
 * 13.5 ms serial); small axisymmetric factorizations likewise (a 4.6k-DOF
 * curve: 1.7 s serial, 5.2 s with CHOLMOD's and OpenBLAS's threads); the
 * members of an ensemble and the points of a table run concurrently, one
 * BLAS thread each, and a table's numbers must not depend on how many
 * points run at once (docs/design.md §3.6).  Debian's OpenMP build of
 * OpenBLAS would run serially inside an active parallel region by itself;
 * the pthread build linked here (ldd lib/libstiction.so; the libopenblas
 * alternatives point to openblas-pthread) has only the global count. */
#include <omp.h>
#include <pthread.h>
#include <time.h>

#include "threads.h"

/* OpenBLAS extension (cblas.h of OpenBLAS is not on the default include
 * path here) */
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static int depth;  /* sections open in the process */
static int saved;  /* the count the first of them found */

void asp_blas_serial_enter(void)
{
    pthread_mutex_lock(&lock);
    if (depth++ == 0) {
        saved = openblas_get_num_threads();
        if (saved != 1) openblas_set_num_threads(1);
    }
    pthread_mutex_unlock(&lock);
}

void asp_blas_serial_leave(void)
{
    pthread_mutex_lock(&lock);
    if (--depth == 0 && saved != 1) openblas_set_num_threads(saved);
    pthread_mutex_unlock(&lock);
}

stc_status asp_run_serial(stc_status (*fn)(void *ctx), void *ctx)
{
    return asp_run_team(fn, ctx, 1);
}

stc_status asp_run_team(stc_status (*fn)(void *ctx), void *ctx, int threads)
{
    stc_status st;
    asp_blas_serial_enter();
    /* ASP_OMP_SERIAL's region, whose setting (in fn's implicit task alone)
     * leaves fn no active level, or one more than the caller's for fn's
     * own team */
#pragma omp parallel num_threads(1)
    {
        omp_set_max_active_levels(threads > 1 ? omp_get_active_level() + 1 : 0);
        st = fn(ctx);
    }
    asp_blas_serial_leave();
    return st;
}

double asp_thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
