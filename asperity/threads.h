/* The library's control of the threads of the libraries it calls (not
 * installed): OpenBLAS's thread count, the one process-wide setting the
 * library changes, in one place (threads.c); the nesting of OpenMP regions
 * for work that runs beside other work of its kind; a thread's CPU clock. */
#ifndef STICTION_THREADS_H
#define STICTION_THREADS_H

#include "stiction/status.h"

/* OpenBLAS on one thread between asp_blas_serial_enter and _leave.  The
 * linked OpenBLAS (Debian's pthread build) has no per-call or per-thread
 * control: its thread count is one global, seen by every thread of the
 * process.  Sections nest and may run on several threads at once: the
 * first enter of the process sets the count to 1, the last leave restores
 * exactly the count the first one found.  Thread-safe. */
void asp_blas_serial_enter(void);
void asp_blas_serial_leave(void);

/* Run `stmt` with the OpenMP regions of the libraries it calls (CHOLMOD's:
 * 4 threads compiled in) on the calling thread only, without touching the
 * caller's OpenMP settings: inside a one-thread parallel region of its own
 * whose implicit task alone gets max-active-levels 0 (a data-environment
 * ICV since OpenMP 5.0: the caller's and other threads' stay as they are).
 * The library's own regions take num_threads / if clauses instead. */
#define ASP_OMP_SERIAL(stmt)                                                   \
    do {                                                                       \
        _Pragma("omp parallel num_threads(1)")                                 \
        {                                                                      \
            omp_set_max_active_levels(0);                                      \
            stmt;                                                              \
        }                                                                      \
    } while (0)

/* fn(ctx) on the calling thread alone: OpenBLAS on one thread
 * (asp_blas_serial_enter) and the OpenMP regions of the libraries it calls
 * serial (ASP_OMP_SERIAL); returns fn's status.  For work that runs
 * beside other work of its kind (a table's points and curves), whose
 * numbers then do not depend on how many run at once. */
stc_status asp_run_serial(stc_status (*fn)(void *ctx), void *ctx);

/* The same with one team of the library's own for fn: its next OpenMP
 * region may run on up to `threads` threads (the members of an ensemble,
 * which run their libraries serially themselves, placements.c); threads 1
 * is asp_run_serial.  The numbers are the same either way (a member's do
 * not depend on how many run beside it). */
stc_status asp_run_team(stc_status (*fn)(void *ctx), void *ctx, int threads);

/* The calling thread's CPU time, s. */
double asp_thread_cpu(void);

#endif
