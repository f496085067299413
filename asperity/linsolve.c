/* The linear solver of the asperity FE model (interface: linsolve.h):
 * CHOLMOD's analysis once, numeric LL' factorizations of the SPD part K of
 * the tangent, corrections and GMRES for the rest of it (Kd + W), and
 * PCG / GMRES preconditioned by the last factor (Newton-Krylov), with the
 * kernels of precond.c.  Separate from the FE code (solver.c, newton.c):
 * it sees a matrix, a right-hand side and a mask of fixed DOFs, never an
 * element, a contact node or a load.  Design: docs/design.md §3.5, §3.6.
 *
 * Fixed DOFs: a constrained DOF gets an identity row and column in K
 * (values only), so the pattern and the symbolic analysis stay valid;
 * the right-hand side carries the prescribed value there.
 *
 * Tangent: under the midpoint return (j2.c) the consistent tangent is not
 * symmetric.  K holds an SPD approximation of it (factorized: the
 * pattern, the analysis and CHOLMOD's LLᵀ stay), Kd and W the rest
 * (symmetric, skew); Newton stays quadratic through corrections / GMRES
 * against K + Kd + W (skew_correct, gmres).
 *
 * Krylov (speed3d): a factorization costs ~50 triangular solves in 3D, so
 * a step is solved by PCG preconditioned with the LAST factor where the
 * analysis says a factorization is costly (krylov_pays).  Level-0 3D slip
 * curve to 60 ωc: the same 160 Newton iterations and answers, 160 -> 15
 * factorizations + 1334 PCG iterations, 91 -> 38 s on the shared machine
 * (CPU 96 -> 37 s).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "linsolve_impl.h"
#include "stc_check.h"
#include "threads.h"

/* ---- create / destroy ------------------------------------------------------ */

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

int asp_ls_pos(const asp_linsolve *ls, int i, int j)
{
    const int *Kp = ls->K->p, *Ki = ls->K->i;
    const int *f = bsearch(&i, Ki + Kp[j], (size_t)(Kp[j + 1] - Kp[j]), sizeof *Ki, cmp_int);
    return f ? (int)(f - Ki) : -1;
}

size_t asp_ls_nnz(const asp_linsolve *ls) { return ls->K->nzmax; }

static stc_status alloc_matrix(asp_linsolve *ls, const int *Kp, const int *Ki)
{
    size_t n = (size_t)ls->n, nnz = (size_t)Kp[ls->n];
    ls->K = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &ls->cc);
    STC_CHECK(ls->K, STC_ENOMEM, "solver: cannot allocate the %zu-entry matrix", nnz);
    ls->Kk = calloc(nnz ? nnz : 1, sizeof *ls->Kk);
    ls->Kd = calloc(nnz ? nnz : 1, sizeof *ls->Kd);
    ls->sk_k = malloc((nnz ? nnz : 1) * sizeof *ls->sk_k);
    ls->sk_j = malloc((nnz ? nnz : 1) * sizeof *ls->sk_j);
    ls->b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &ls->cc);
    ls->skew_r = malloc(n * sizeof *ls->skew_r);
    STC_CHECK(ls->Kk && ls->Kd && ls->sk_k && ls->sk_j && ls->b && ls->skew_r, STC_ENOMEM,
              "solver: cannot allocate the %zu-entry matrix", nnz);
    memcpy(ls->K->p, Kp, (n + 1) * sizeof *Kp);
    memcpy(ls->K->i, Ki, nnz * sizeof *Ki);
    return STC_OK;
}

/* 3D: METIS nested dissection (the better of it and AMD is kept): on the
 * level-0 half model (24k DOFs) it cut the factor from 1.9e7 to 1.2e7
 * nonzeros and the flops 3x (3.4 s -> 2.2 s for a Hertz point); CHOLMOD's
 * default (AMD, METIS only if the fill is extreme) kept AMD.  Supernodes
 * amalgamated twice as far as CHOLMOD's defaults (4, 16, 48 columns; 0.8,
 * 0.1, 0.05 zeros): fewer, larger dense blocks for OpenBLAS.  Measured, two
 * runs each, idle machine: graded curve n = 4 18.2 -> 17.6 s, WSP 3 / 12 ωc
 * shear 11.8 / 14.0 -> 10.8 / 13.0 s, coated stick δ = 10 shear 40.3 s
 * either way; answers equal to all printed digits (docs/design.md §3.5) */
static void nested_dissection(cholmod_common *cc)
{
    cc->nmethods = 2;
    cc->method[0].ordering = CHOLMOD_METIS;
    cc->method[1].ordering = CHOLMOD_AMD;
    cc->nrelax[0] = 8, cc->nrelax[1] = 32, cc->nrelax[2] = 96;
    cc->zrelax[0] = 0.8, cc->zrelax[1] = 0.2, cc->zrelax[2] = 0.1;
}

stc_status asp_ls_create(int n, const int *Kp, const int *Ki, const unsigned char *fixed,
                         const asp_ls_options *o, asp_linsolve **out)
{
    *out = NULL;
    asp_linsolve *ls = calloc(1, sizeof *ls);
    STC_CHECK(ls, STC_ENOMEM, "solver: out of memory");
    ls->opt = *o;
    ls->n = n;
    ls->nthr = o->threads;
    ls->fixed = fixed;
    cholmod_start(&ls->cc);
    ls->cc.print = 0;
    ls->cc.error_handler = NULL;
    stc_status st;
    STC_CALL_GOTO(alloc_matrix(ls, Kp, Ki), st, fail);
    STC_CALL_GOTO(asp_matvec_setup(ls), st, fail);
    if (o->nested_dissection) nested_dissection(&ls->cc);
    ls->L = cholmod_analyze(ls->K, &ls->cc);
    STC_CHECK_GOTO(ls->L, st, fail, STC_ESOLVER, "CHOLMOD analyze failed (status %d)",
                   ls->cc.status);
    *out = ls;
    return STC_OK;
fail:
    asp_ls_destroy(&ls);
    return st;
}

void asp_ls_destroy(asp_linsolve **lsp)
{
    if (!lsp || !*lsp) return;
    asp_linsolve *ls = *lsp;
    if (ls->L) cholmod_free_factor(&ls->L, &ls->cc);
    if (ls->K) cholmod_free_sparse(&ls->K, &ls->cc);
    cholmod_free_dense(&ls->b, &ls->cc), cholmod_free_dense(&ls->kb, &ls->cc);
    cholmod_free_dense(&ls->kx, &ls->cc), cholmod_free_dense(&ls->ky, &ls->cc);
    cholmod_free_dense(&ls->ke, &ls->cc);
    cholmod_finish(&ls->cc);
    free(ls->Kk), free(ls->Kd), free(ls->sk_k), free(ls->sk_j);
    free(ls->kv), free(ls->gv), free(ls->skew_r);
    asp_prec_free(ls);
    free(ls);
    *lsp = NULL;
}

/* ---- the values --------------------------------------------------------------- */

void asp_ls_values(asp_linsolve *ls, double **K, double **Kd, double **W)
{
    *K = ls->K->x, *Kd = ls->Kd, *W = ls->Kk;
}

void asp_ls_begin_tangent(asp_linsolve *ls, const double *K0)
{
    memcpy(ls->K->x, K0, ls->K->nzmax * sizeof(double));
    for (int l = 0; l < ls->nsk; l++) ls->Kk[ls->sk_k[l]] = ls->Kd[ls->sk_k[l]] = 0.0;
}

/* List the (few: plastic elements') entries of Kd + W, so the mat-vecs of
 * every Krylov iteration skip the zeros (3D level 0: the skew mat-vec was
 * as costly as the K mat-vec). */
void asp_ls_end_tangent(asp_linsolve *ls)
{
    const int *Kp = ls->K->p;
    ls->nsk = 0;
    for (int j = 0; j < ls->n; j++)
        for (int k = Kp[j]; k < Kp[j + 1]; k++)
            if (ls->Kk[k] != 0.0 || ls->Kd[k] != 0.0) ls->sk_k[ls->nsk] = k, ls->sk_j[ls->nsk++] = j;
    ls->skew = ls->nsk > 0;
}

double *asp_ls_rhs(asp_linsolve *ls) { return ls->b->x; }

void asp_ls_matvec(const asp_linsolve *ls, const double *x, double *y, int mode)
{
    asp_tangent_matvec(ls, x, y, mode);
}

void asp_ls_get_stats(const asp_linsolve *ls, asp_ls_stats *st)
{
    st->factorizations = ls->n_fact;
    st->krylov_iterations = ls->n_kits;
    st->last_krylov = ls->k_last;
    st->factor = ls->fact_why;
    st->minor = ls->L ? (int)ls->L->minor : 0;
    st->time_factorize_s = ls->t_fact;
    st->time_krylov_s = ls->t_pcg;
}

/* ---- factorization and the direct solve ----------------------------------- */

/* Identity rows/columns for the constrained DOFs (values only). */
static void apply_constraints(asp_linsolve *ls)
{
    const int *Kp = ls->K->p, *Ki = ls->K->i;
    const unsigned char *fixed = ls->fixed;
    double *Kx = ls->K->x;
    for (int j = 0; j < ls->n; j++)
        for (int k = Kp[j]; k < Kp[j + 1]; k++) {
            int i = Ki[k];
            if (fixed[i] || fixed[j]) Kx[k] = (i == j) ? 1.0 : 0.0;
        }
}

static stc_status factorize(asp_linsolve *ls)
{
    apply_constraints(ls);
    double t0 = omp_get_wtime();
    if (ls->opt.serial_factor) {
        /* small systems: CHOLMOD's OpenMP regions (4 threads compiled in)
         * and OpenBLAS's threads only spin (threads.c) */
        asp_blas_serial_enter();
        ASP_OMP_SERIAL(cholmod_factorize(ls->K, ls->L, &ls->cc));
        asp_blas_serial_leave();
    } else {
        cholmod_factorize(ls->K, ls->L, &ls->cc);
    }
    ls->t_fact += omp_get_wtime() - t0;
    ls->n_fact++;
    ls->have_factor = ls->cc.status == CHOLMOD_OK;
    if (ls->have_factor) STC_CALL(asp_prec_update(ls));
    else ls->fx_ok = 0;
    ls->k_last = 0;
    ls->fact_why = ls->cc.status == CHOLMOD_OK           ? ASP_OUTCOME_CONVERGED
                   : ls->cc.status == CHOLMOD_NOT_POSDEF ? ASP_OUTCOME_NOT_POSDEF
                                                         : ASP_OUTCOME_SOLVER_FAILED;
    STC_CHECK(ls->cc.status == CHOLMOD_OK, STC_ESOLVER,
              "CHOLMOD factorization: %s (column %d of %d)", asp_outcome_str(ls->fact_why),
              (int)ls->L->minor, ls->n);
    return STC_OK;
}

/* du = A^-1 b with the current factor (cholmod_solve2 reuses the solution
 * and workspace of earlier solves: no allocation per Newton step). */
static stc_status direct_solve(asp_linsolve *ls, double *du)
{
    STC_CHECK(cholmod_solve2(CHOLMOD_A, ls->L, ls->b, NULL, &ls->kx, NULL, &ls->ky, &ls->ke,
                             &ls->cc),
              STC_ESOLVER, "CHOLMOD solve failed (status %d)", ls->cc.status);
    memcpy(du, ls->kx->x, (size_t)ls->n * sizeof *du);
    return STC_OK;
}

/* ---- Krylov ------------------------------------------------------------------
 * The tangent is assembled every iteration anyway (the element loop is
 * 5-13 % of a 3D iteration), but a numeric Cholesky factorization costs
 * ~50 triangular solves (3D level 0: 0.63 s against 0.012 s).  So a Newton
 * step is solved by the preconditioned conjugate gradient on the free DOFs
 * (Saad, Iterative Methods for Sparse Linear Systems, 2nd ed. 2003,
 * alg. 9.1) with the LAST factor as the preconditioner (Newton-Krylov:
 * Knoll & Keyes, J. Comput. Phys. 193 (2004) 357).  The factor may belong
 * to an earlier tangent and an earlier active set: any SPD matrix is a
 * valid preconditioner, its distance from the current one only sets the
 * iteration count; past krylov_max iterations the tangent is refactorized
 * (and the direct solve used).  The constrained K is SPD (identity rows and
 * columns on the fixed DOFs), and the fixed DOFs are exactly the prescribed
 * jump: PCG works on the free block only, with the preconditioner
 * projected onto it (a principal block of an SPD inverse is SPD). */

static double dot(const double *a, const double *b, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) s += a[i] * b[i];
    return s;
}

/* Relative floor of the Krylov tolerance: 1e-6 of the step's right-hand
 * side, so a step near convergence still lowers the residual (the line
 * search needs it); the caller's absolute tolerance (newton.c) is the
 * other bound. */
#define KRYLOV_ETA 1e-6

/* The Krylov stopping tolerance of pcg and gmres for a start residual of
 * norm r0: the caller's absolute tol (0: none yet, relative only) capped
 * at KRYLOV_ETA r0, then loosened to the forcing term eta r0. */
static double krylov_tol(double tol, double eta, double r0)
{
    double rel = KRYLOV_ETA * r0;
    return fmax(tol > 0.0 ? fmin(tol, rel) : rel, eta * r0);
}

/* GMRES keeps at most this many basis vectors (krylov_max above it: the
 * step is refactorized after KRYLOV_MAX_CAP iterations) */
#define KRYLOV_MAX_CAP 100

/* z = P K^-1 P r with the stored factor, its float copy where there is one
 * (P: zero the fixed DOFs). */
static int precondition(asp_linsolve *ls, const double *r, double *z)
{
    const unsigned char *fixed = ls->fixed;
    if (ls->fx_ok) {
        asp_prec_solve(ls, r, z);
        for (int i = 0; i < ls->n; i++)
            if (fixed[i]) z[i] = 0.0;
        return 0;
    }
    memcpy(ls->kb->x, r, (size_t)ls->n * sizeof *r);
    if (!cholmod_solve2(CHOLMOD_A, ls->L, ls->kb, NULL, &ls->kx, NULL, &ls->ky, &ls->ke,
                        &ls->cc))
        return -1;
    const double *x = ls->kx->x;
    for (int i = 0; i < ls->n; i++) z[i] = fixed[i] ? 0.0 : x[i];
    return 0;
}

/* PCG for A du = b (A: constrained tangent in K, b in bx): du = b on the
 * fixed DOFs, the free block to |r| <= krylov_tol(tol, eta, |r0|) (eta:
 * the forcing term, 0 for none).  Returns the iterations, or -1 when it
 * needs more than kmax (or the preconditioner failed). */
static int pcg(asp_linsolve *ls, const double *bx, double *du, double tol, double eta, int kmax)
{
    int n = ls->n;
    const unsigned char *fixed = ls->fixed;
    double *r = ls->kv, *z = r + n, *p = z + n, *q = p + n;
    for (int i = 0; i < n; i++) r[i] = fixed[i] ? 0.0 : bx[i], du[i] = 0.0;
    double rz = 0.0;
    tol = krylov_tol(tol, eta, sqrt(dot(r, r, n)));
    for (int k = 0;; k++) {
        if (sqrt(dot(r, r, n)) <= tol) {
            for (int i = 0; i < n; i++)
                if (fixed[i]) du[i] = bx[i];
            return k;
        }
        if (k == kmax || precondition(ls, r, z)) return -1;
        double rz1 = dot(r, z, n), beta = k ? rz1 / rz : 0.0;
        rz = rz1;
        /* (the first direction is z itself: p holds no data yet, and 0 times
         * a stale NaN would not be 0) */
        for (int i = 0; i < n; i++) p[i] = k ? z[i] + beta * p[i] : z[i];
        asp_tangent_matvec(ls, p, q, ASP_LS_K); /* zero on the fixed DOFs: p is */
        double pq = dot(p, q, n), alpha = rz / pq;
        if (!(pq > 0.0) || !isfinite(alpha)) return -1;
        for (int i = 0; i < n; i++) du[i] += alpha * p[i], r[i] -= alpha * q[i];
    }
}

/* One Arnoldi step of gmres: w = P A M^-1 v_k orthogonalised against
 * v_0..v_k (modified Gram-Schmidt) into column k of H; v_k+1 = w / |w|.
 * Returns |w|, or NaN when the preconditioner failed. */
static double arnoldi(asp_linsolve *ls, double *V, double *w, double *z, double *H, int m,
                      int k)
{
    int n = ls->n;
    double *vk = V + (size_t)k * n, *vn = V + (size_t)(k + 1) * n;
    if (precondition(ls, vk, z)) return NAN;
    asp_tangent_matvec(ls, z, w, ASP_LS_FREE);
    for (int i = 0; i < n; i++)
        if (ls->fixed[i]) w[i] = 0.0;
    for (int j = 0; j <= k; j++) {
        const double *vj = V + (size_t)j * n;
        double h = dot(w, vj, n);
        H[j * m + k] = h;
        for (int i = 0; i < n; i++) w[i] -= h * vj[i];
    }
    double hn = sqrt(dot(w, w, n));
    if (isfinite(hn))
        for (int i = 0; i < n; i++) vn[i] = hn > 0.0 ? w[i] / hn : 0.0;
    return hn;
}

/* GMRES for the same system when the tangent has a skew part (midpoint
 * return, j2.c), PCG's contract: right-preconditioned restarted GMRES, one
 * cycle of at most kmax iterations (Saad 2003, alg. 9.5, with Givens
 * rotations; modified Gram-Schmidt).  Right preconditioning keeps the
 * true residual, which is what tol bounds.  Returns the iterations, or -1
 * when kmax do not reach tol (or the preconditioner failed). */
static int gmres(asp_linsolve *ls, const double *bx, double *du, double tol, double eta,
                 int kmax)
{
    int n = ls->n, m = kmax < KRYLOV_MAX_CAP ? kmax : KRYLOV_MAX_CAP;
    double *V = ls->gv, *w = V + (size_t)(m + 1) * n, *z = ls->kv;
    double H[(KRYLOV_MAX_CAP + 1) * KRYLOV_MAX_CAP], cs[KRYLOV_MAX_CAP], sn[KRYLOV_MAX_CAP];
    double g[KRYLOV_MAX_CAP + 1], y[KRYLOV_MAX_CAP];
    for (int i = 0; i < n; i++) V[i] = ls->fixed[i] ? 0.0 : bx[i], du[i] = 0.0;
    double beta = sqrt(dot(V, V, n));
    tol = krylov_tol(tol, eta, beta);
    int k = 0;
    if (beta > tol) {
        for (int i = 0; i < n; i++) V[i] /= beta;
        g[0] = beta;
        for (;; k++) {
            if (k == m) return -1;
            double hn = arnoldi(ls, V, w, z, H, m, k);
            if (!isfinite(hn)) return -1;
            for (int j = 0; j < k; j++) { /* earlier rotations */
                double a = H[j * m + k], b = H[(j + 1) * m + k];
                H[j * m + k] = cs[j] * a + sn[j] * b;
                H[(j + 1) * m + k] = -sn[j] * a + cs[j] * b;
            }
            double a = H[k * m + k], r = hypot(a, hn);
            if (!(r > 0.0)) return -1;
            cs[k] = a / r, sn[k] = hn / r;
            H[k * m + k] = r;
            g[k + 1] = -sn[k] * g[k];
            g[k] *= cs[k];
            if (fabs(g[k + 1]) <= tol || hn == 0.0) {
                k++;
                break;
            }
        }
        for (int j = k - 1; j >= 0; j--) { /* H y = g, upper triangular */
            double v = g[j];
            for (int l = j + 1; l < k; l++) v -= H[j * m + l] * y[l];
            y[j] = v / H[j * m + j];
        }
        for (int i = 0; i < n; i++) w[i] = 0.0;
        for (int j = 0; j < k; j++) {
            const double *vj = V + (size_t)j * n;
            for (int i = 0; i < n; i++) w[i] += y[j] * vj[i];
        }
        if (precondition(ls, w, z)) return -1;
        for (int i = 0; i < n; i++) du[i] = z[i];
    }
    for (int i = 0; i < n; i++)
        if (ls->fixed[i]) du[i] = bx[i];
    return k;
}

/* GMRES basis, allocated the first time a tangent has a skew part. */
static stc_status gmres_alloc(asp_linsolve *ls)
{
    if (ls->gv) return STC_OK;
    int m = ls->opt.krylov_max < KRYLOV_MAX_CAP ? ls->opt.krylov_max : KRYLOV_MAX_CAP;
    ls->gv = malloc((size_t)(m + 2) * (size_t)ls->n * sizeof *ls->gv);
    STC_CHECK(ls->gv, STC_ENOMEM, "solver: out of memory for the GMRES basis");
    return STC_OK;
}

static stc_status krylov_alloc(asp_linsolve *ls)
{
    if (ls->kv) return STC_OK;
    size_t n = (size_t)ls->n;
    ls->kv = calloc(4 * n, sizeof *ls->kv);
    ls->kb = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &ls->cc);
    STC_CHECK(ls->kv && ls->kb, STC_ENOMEM, "solver: out of memory for the PCG vectors");
    return STC_OK;
}

/* ---- corrections for the skew tangent --------------------------------------
 * Under the midpoint return the tangent is not symmetric (j2.c).  The
 * matrix factorized, K, is then an SPD approximation (j2's Dp: the tangent
 * of a proportional increment), and the tangent is K + Kd + W (Kd
 * symmetric, W skew).  Factorizing the symmetric part alone made Newton
 * converge linearly (residual ~x0.1 per iteration; axisymmetric level 1 at
 * 60 ωc: 380 Newton iterations against 230 with radial return), and that
 * symmetric part can be indefinite (the coated t/R .025 δ = 30 ramp at
 * 8.5 elements per contact: 20 shifted factorizations, 4 cut-backs,
 * 909 s).  After a direct solve, corrections du += K^-1 (b - (K + Kd + W)
 * du) restore the quadratic rate (243 iterations); each costs a mat-vec
 * and a triangular solve.  They converge while |K^-1 (Kd + W)| < 1; a
 * correction that does not halve the residual is undone and GMRES with the
 * same factor takes over (the Krylov path uses GMRES directly,
 * asp_ls_step).  K is the constrained (identity-row) matrix here, Kd and W
 * their free-free blocks. */
enum { SKEW_SWEEPS = 3 };

/* r = b - (K + Kd + W) du on the free DOFs (0 on the fixed); returns |r|. */
static double skew_residual(const asp_linsolve *ls, const double *bx, const double *du,
                            double *r)
{
    asp_tangent_matvec(ls, du, r, ASP_LS_FREE);
    double a = 0.0;
    for (int i = 0; i < ls->n; i++) {
        r[i] = ls->fixed[i] ? 0.0 : bx[i] - r[i];
        a += r[i] * r[i];
    }
    return sqrt(a);
}

static stc_status skew_sweeps(asp_linsolve *ls, double *du, double eta)
{
    int n = ls->n;
    double *r = ls->skew_r, *z = ls->kv + n, *bx = ls->b->x; /* gmres uses kv[0, n) */
    double rn = skew_residual(ls, bx, du, r), tol = 1e-10 * sqrt(dot(bx, bx, n));
    for (int sweep = 0; sweep < SKEW_SWEEPS && rn > tol; sweep++) {
        STC_CHECK(!precondition(ls, r, z), STC_ESOLVER, "CHOLMOD solve failed (status %d)",
                  ls->cc.status);
        for (int i = 0; i < n; i++) du[i] += z[i]; /* z is 0 on the fixed DOFs */
        double r1 = skew_residual(ls, bx, du, r);
        if (r1 < 0.5 * rn) {
            rn = r1;
            continue;
        }
        /* not contracting: undo, and GMRES preconditioned by the factor */
        for (int i = 0; i < n; i++) du[i] -= z[i];
        STC_CALL(gmres_alloc(ls));
        int k = gmres(ls, bx, r, 0.0, eta, ls->opt.krylov_max);
        if (k >= 0) memcpy(du, r, (size_t)n * sizeof *du);
        break; /* else: keep the best correction so far */
    }
    return STC_OK;
}

/* eta: the Newton step's forcing term for the fallback GMRES (0: the fixed
 * tolerance) */
static stc_status skew_correct(asp_linsolve *ls, double *du, double eta)
{
    if (!ls->skew) return STC_OK;
    STC_CALL(krylov_alloc(ls));
    asp_blas_serial_enter(); /* the Krylov kernels' OpenBLAS calls (threads.c) */
    stc_status st = skew_sweeps(ls, du, eta);
    asp_blas_serial_leave();
    return st;
}

/* ---- steps ------------------------------------------------------------------- */

/* PCG pays where a factorization costs many PCG iterations (one solve and
 * one mat-vec each): the flop ratio fl / (nnz(L) + nnz(K)) of the analysis
 * is ~700 on the 3D level-0 half model, where the measured time ratio is
 * ~50, but 60-180 on the axisymmetric meshes (levels 1-3), where a
 * factorization costs a few PCG iterations and PCG (~15 per step measured
 * at level 1) was slower than factorizing every step; 320 lies between. */
static int krylov_pays(const asp_linsolve *ls)
{
    if (ls->opt.krylov != ASP_KRYLOV_AUTO) return ls->opt.krylov == ASP_KRYLOV_ON;
    double nnzk = ((const int *)ls->K->p)[ls->n];
    return ls->cc.fl > 320.0 * (ls->cc.lnz + nnzk);
}

/* Krylov with the last factor; *ok: it converged. */
static stc_status krylov_step(asp_linsolve *ls, double *du, double tol, double eta, int *ok)
{
    STC_CALL(krylov_alloc(ls));
    if (ls->skew) STC_CALL(gmres_alloc(ls));
    asp_blas_serial_enter(); /* the Krylov kernels' OpenBLAS calls (threads.c) */
    double t0 = omp_get_wtime();
    int k = ls->skew ? gmres(ls, ls->b->x, du, tol, eta, ls->opt.krylov_max)
                     : pcg(ls, ls->b->x, du, tol, eta, ls->opt.krylov_max);
    ls->t_pcg += omp_get_wtime() - t0;
    asp_blas_serial_leave();
    ls->k_last = k;
    ls->n_kits += k >= 0 ? k : ls->opt.krylov_max;
    *ok = k >= 0;
    return STC_OK;
}

stc_status asp_ls_step(asp_linsolve *ls, double *du, double tol, double eta, int *factorized)
{
    *factorized = 0;
    apply_constraints(ls);
    /* refactorize once PCG needs half its budget: the tangent has drifted
     * (plastic zone, contact) and the count climbs from there (3D level 0,
     * curve to 30 ωc: 2 factorizations + 1754 PCG iterations with the hard
     * limit only, 11 + 939 with this rule; a factorization costs ~45).
     * Budget 50, not 30, since the Krylov kernels run on two threads (a
     * factorization now costs ~60 iterations; idle machine, whole runs):
     * graded 3D curve n = 4 20.9 -> 17.2 s, WSP 3 / 12 ωc shear 12.2 / 15.5
     * -> 10.6 / 13.8 s, coated stick δ = 10 shear 43.0 -> 37.7 s
     * (docs/design.md §3.5, §3.6) */
    if (ls->have_factor && krylov_pays(ls) && 2 * ls->k_last <= ls->opt.krylov_max) {
        int ok;
        STC_CALL(krylov_step(ls, du, tol, eta, &ok));
        if (ok) return STC_OK;
    }
    *factorized = 1;
    STC_CALL(factorize(ls));
    STC_CALL(direct_solve(ls, du));
    return skew_correct(ls, du, eta);
}

stc_status asp_ls_resolve(asp_linsolve *ls, double *du)
{
    STC_CALL(direct_solve(ls, du));
    return skew_correct(ls, du, 0.0);
}
