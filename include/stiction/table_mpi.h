/* stiction — distributed friction-table builds (asperity/table_mpi.c).
 *
 * tbl_build (include/stiction/table.h) shares its points out over MPI when
 * the process was started by `mpirun -n N` with N > 1 (or when the caller
 * initialised MPI with more than one process): every rank calls tbl_build
 * with the same table, path and options; rank 0 hands out the points one at
 * a time, computes some itself, journals each finished point and writes the
 * table; the other ranks compute the points they are given and write no
 * file.  A process not started that way never initialises MPI.
 */
#ifndef STICTION_TABLE_MPI_H
#define STICTION_TABLE_MPI_H

#include "stiction/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* This process's place in a distributed build: its rank (0: the writer,
 * which alone calls the progress callback, writes the journal and the table,
 * and returns the summary of the whole build) and the number of ranks; 0 and
 * 1 when builds in this process are not distributed.  Does not initialise
 * MPI.  Call it from the main thread. */
STC_API void tbl_build_rank(int *rank, int *size);

#ifdef __cplusplus
}
#endif
#endif
