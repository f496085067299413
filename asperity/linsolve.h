/* The linear solver of the asperity FE model (not installed): one sparse
 * symmetric pattern, analysed once, refactorized per tangent, solved many
 * times (CHOLMOD's analyse / factorize / solve, docs/design.md §3.5).
 *
 * Separate from the FE code because it knows nothing of elements, contact
 * or load: it holds a matrix K (upper triangle, CSC) that the caller fills,
 * the rest of a tangent that K does not hold (Kd symmetric + W skew, on K's
 * pattern: K is the SPD part that is factorized), and a mask of fixed DOFs
 * whose rows and columns become identity rows when a step is solved.  A
 * step is solved directly (LL' of K, then corrections and GMRES against
 * K + Kd + W) or, where a factorization costs many Krylov iterations, by
 * PCG / GMRES preconditioned with the last factor (Newton-Krylov).
 *
 * Prefix asp_ls_.  One asp_linsolve per solver; not thread-safe (its Krylov
 * kernels use opt.threads OpenMP threads of their own).
 */
#ifndef STICTION_LINSOLVE_H
#define STICTION_LINSOLVE_H

#include <stddef.h>

#include "stiction/asperity.h"
#include "stiction/status.h"

typedef struct asp_linsolve asp_linsolve;

typedef struct asp_ls_options {
    asp_krylov krylov;     /* when steps are solved by Krylov (asp_options.krylov) */
    int krylov_max;        /* Krylov iterations before refactorizing, in [1, 1000] */
    int threads;           /* threads of the Krylov kernels (at most 2 used), >= 1 */
    int serial_factor;     /* 1: factorize on one thread (small systems, see linsolve.c) */
    int nested_dissection; /* 1: METIS ordering (AMD kept if better) and supernodes
                              amalgamated twice as far as CHOLMOD's defaults (3D) */
} asp_ls_options;

/* What the solver has done since create. */
typedef struct asp_ls_stats {
    int factorizations;    /* numeric factorizations (successful or not) */
    int krylov_iterations; /* PCG / GMRES iterations (a failed solve counts krylov_max) */
    int last_krylov;       /* iterations of the last Krylov solve (-1: it failed) */
    asp_outcome factor;    /* the last factorization: ASP_OUTCOME_CONVERGED,
                              _NOT_POSDEF or _SOLVER_FAILED (NONE: none yet) */
    int minor;             /* the column where that factorization failed */
    double time_factorize_s, time_krylov_s; /* wall time, s */
} asp_ls_stats;

/* New solver for the n x n pattern Kp [n + 1], Ki [Kp[n]] (upper triangle,
 * CSC, rows sorted within each column; copied): allocates K, Kd, W and
 * runs the symbolic analysis.  fixed [n] is borrowed for the solver's
 * lifetime (1: the DOF is prescribed; the caller may change it between
 * steps).  Returns new in *out. */
stc_status asp_ls_create(int n, const int *Kp, const int *Ki, const unsigned char *fixed,
                         const asp_ls_options *o, asp_linsolve **out);
void asp_ls_destroy(asp_linsolve **ls); /* sets *ls = NULL */

/* Position of entry (i, j), i <= j, in the value arrays; -1 if not in the
 * pattern. */
int asp_ls_pos(const asp_linsolve *ls, int i, int j);
size_t asp_ls_nnz(const asp_linsolve *ls);

/* The value arrays [nnz] the caller assembles into: K (the SPD matrix
 * factorized) and the symmetric and skew parts Kd, W of the tangent's
 * rest (upper entries; W_ji = -W_ij).  Borrowed. */
void asp_ls_values(asp_linsolve *ls, double **K, double **Kd, double **W);

/* Start a new tangent: K = K0 [nnz], Kd = W = 0.  asp_ls_end_tangent after
 * the assembly lists the entries where Kd or W is not zero (the mat-vecs
 * skip the rest). */
void asp_ls_begin_tangent(asp_linsolve *ls, const double *K0);
void asp_ls_end_tangent(asp_linsolve *ls);

/* The right-hand side [n] of the next asp_ls_step / asp_ls_resolve
 * (borrowed; the caller fills it, with the prescribed values on the fixed
 * DOFs). */
double *asp_ls_rhs(asp_linsolve *ls);

/* y = A x with A = K (mode ASP_LS_K), K + Kd + W (ASP_LS_TANGENT), or K
 * plus the free-free block of Kd + W (ASP_LS_FREE).  Unconstrained K
 * before a step, the identity rows after it. */
enum { ASP_LS_K = 0, ASP_LS_TANGENT = 1, ASP_LS_FREE = 2 };
void asp_ls_matvec(const asp_linsolve *ls, const double *x, double *y, int mode);

/* Solve A du = rhs for a fresh tangent (the fixed DOFs become identity rows
 * of K first): by Krylov with the last factor when that pays and the last
 * Krylov solve took at most half of krylov_max, else (or when it fails)
 * factorize and solve directly.  tol: absolute tolerance of a Krylov solve
 * on the free DOFs' residual, loosened to the forcing term eta |rhs| (0:
 * none).  *factorized: 1 if it factorized.  STC_ESOLVER when the
 * factorization or a solve failed (asp_ls_get_stats: why). */
stc_status asp_ls_step(asp_linsolve *ls, double *du, double tol, double eta, int *factorized);

/* Solve with the factor of an earlier step (modified Newton), with the
 * corrections for the current Kd + W. */
stc_status asp_ls_resolve(asp_linsolve *ls, double *du);

void asp_ls_get_stats(const asp_linsolve *ls, asp_ls_stats *st);

#endif
