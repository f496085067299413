/* Private layout of the linear solver (linsolve.c, precond.c; read by
 * tests/test_precond.c).  The interface is linsolve.h. */
#ifndef STICTION_LINSOLVE_IMPL_H
#define STICTION_LINSOLVE_IMPL_H

#include <cholmod.h>

#include "linsolve.h"

/* Single-precision BLAS, Fortran interface (precond.c's float
 * preconditioner; the C interface's header would pull in complex.h, whose I
 * clashes).  OpenBLAS is the one BLAS the project links. */
void strsv_(const char *uplo, const char *trans, const char *diag, const int *n,
            const float *a, const int *lda, float *x, const int *incx);
void sgemv_(const char *trans, const int *m, const int *n, const float *alpha,
            const float *a, const int *lda, const float *x, const int *incx,
            const float *beta, float *y, const int *incy);

struct asp_linsolve {
    asp_ls_options opt;
    int n;                /* unknowns (the caller's DOFs, fixed ones included) */
    int nthr;             /* threads of the Krylov kernels (opt.threads) */
    const unsigned char *fixed; /* [n] borrowed: 1 = prescribed (identity row) */

    cholmod_common cc;
    cholmod_sparse *K;    /* upper triangle, fixed pattern: the matrix factorized, the
                             tangent where it is symmetric, else an SPD approximation */
    double *Kk;           /* [nnz(K)] skew part W of the tangent (K's pattern, upper
                             entries; the midpoint return's, j2.c); all zero under
                             radial return */
    double *Kd;           /* [nnz(K)] symmetric part of the tangent minus K (same) */
    int skew;             /* Kk or Kd is not zero: K is not the tangent */
    int *sk_k, *sk_j, nsk; /* the entries k (in column j) where Kk or Kd is not zero */
    cholmod_factor *L;    /* analysed once */
    int have_factor;      /* L holds a numeric factor (of an earlier tangent) */

    cholmod_dense *b;     /* [n] right-hand side of the next step */
    cholmod_dense *kx, *ky, *ke; /* cholmod_solve2 solution and workspace */
    cholmod_dense *kb;    /* PCG: preconditioner right-hand side */
    double *kv;           /* [4][n] PCG vectors r, z, p, q (lazily allocated) */
    double *gv;           /* GMRES: [krylov_max + 2][n] basis and work (lazily) */
    double *skew_r;       /* [n] residual of the skew corrections */
    float *fx;            /* single-precision copy of the supernodal factor's values */
    size_t fx_size;       /* its allocated length; fx_ok: it matches the factor */
    int fx_ok;
    float *fy;            /* [n] its solve's work vector */
    struct asp_prec *prec; /* the float solve's plan (precond.c), NULL until made */
    struct asp_mvplan *mv; /* the mat-vec's plan (precond.c) */

    int n_fact;           /* factorizations (cumulative) */
    int n_kits;           /* Krylov iterations (cumulative) */
    int k_last;           /* Krylov iterations of the last solve (-1: failed) */
    asp_outcome fact_why; /* the last factorization's outcome */
    double t_fact, t_pcg; /* cumulative wall time: factorizations, Krylov, s */
};

/* precond.c: the Krylov kernels on ls->nthr threads (OpenBLAS on one
 * thread: the caller sets it).  asp_prec_update copies the factor to float
 * after each factorization (fx_ok: it succeeded for a supernodal LL'
 * factor); asp_prec_solve: out = K^-1 b with it; asp_matvec_setup once per
 * pattern, then asp_tangent_matvec: y = A x for an ASP_LS_* mode;
 * asp_prec_free frees both plans and the float factor. */
stc_status asp_prec_update(asp_linsolve *ls);
void asp_prec_solve(const asp_linsolve *ls, const double *b, double *out);
stc_status asp_matvec_setup(asp_linsolve *ls);
void asp_tangent_matvec(const asp_linsolve *ls, const double *x, double *y, int mode);
void asp_prec_free(asp_linsolve *ls);
/* The solve plan: parts that got subtrees (0: no plan, one part runs all),
 * the factor entries of the top and of each part (part_w: ASP_PREC_PARTS). */
enum { ASP_PREC_PARTS = 2 };
int asp_prec_parts(const asp_linsolve *ls, double *top_w, double *part_w);

#endif
