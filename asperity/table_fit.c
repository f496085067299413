/* Gaussian-process smoothing surrogate for noisy table values
 * (asperity/table_fit.h).
 *
 * Fit: the covariance is written K = s^2 A with A = R + lambda^2 S (R the
 * correlation matrix, S = diag(sy_i^2), lambda = c / sf, s = sf).  For fixed
 * ell and lambda the restricted likelihood is maximised by s^2 in closed
 * form (the "concentrated" likelihood, Santner, Williams & Notz 2003,
 * ch. 3), so Nelder-Mead (GSL nmsimplex2) searches only log ell_d per
 * varying input and log lambda, each confined to its interval by MINUIT's
 * sine transform (James & Roos 1975).  The search starts from a
 * deterministic point and restarts from its own optimum until a restart
 * gains nothing; for many points it first runs on a well-spread subset.
 * Each evaluation builds A and factorises it (blocked Cholesky on
 * OpenBLAS).  Nothing is random: the same input gives bit-identical output.
 * After the fit the handle keeps L = chol(K), K^-1 (y - m 1) and K^-1 1, so
 * a prediction costs one kernel row and one triangular solve.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_cblas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>

#include "stc_check.h"
#include "table_fit.h"

#define MAXDIM 3
#define MAXPAR (2 * MAXDIM + 3)
_Static_assert(MAXPAR == TBL_GP_MAXPAR, "table_fit.h's TBL_GP_MAXPAR");

/* ell >= 0.25 x the smallest spacing: the kernel between neighbours is then
 * at most exp(-8), below which the fit would only interpolate noise. */
#define ELL_LO_SPACING 0.25
/* ell <= 20 x the range: beyond it f is a linear trend over the table and
 * a longer scale changes nothing but the conditioning of K. */
#define ELL_HI_RANGE 20.0
#define ELL_START_RANGE 0.5 /* start: ell = half the range */
#define C_MAX 10.0          /* noise scale c in [1, C_MAX] */
/* Modulated length scales: |gamma| x half the range of the modulating
 * input <= MOD_MAX, i.e. ell varies at most e^1.5 = 4.5-fold either way
 * from its value at the middle of that range. */
#define MOD_MAX 1.5
/* The base term's sd over the main term's, rho, in [RHO_LO, RHO_HI]. */
#define RHO_LO 1e-3
#define RHO_HI 1e3
/* sf in [SF_LO, SF_HI] x s0, s0 = max(sd(y), rms(sy)): from "no signal" to
 * far beyond any variation the data can show. */
#define SF_LO 1e-3
#define SF_HI 1e2
#define NM_STEP 0.6         /* initial simplex step in the transformed (angle) variables, rad */
#define NM_RESTART_STEP 0.05 /* step of a restart, and of the all-points run after a subset */
#define NM_TOL 1e-3         /* simplex size (rad) that ends a Nelder-Mead run */
#define NM_MAXEVAL 150      /* evaluations per run and searched parameter, at least 600 */
#define NM_RESTARTS 2       /* restarts from the optimum: a collapsed simplex can stall */
/* Log-likelihood gain under which restarting stops: far below the ~0.5
 * that separates statistically distinguishable hyperparameters. */
#define NM_RESTART_GAIN 1e-3
/* Above this many points the search first runs on a farthest-point subset
 * of this size, then once more on all points from there: each evaluation
 * costs O(n^3), and the subset finds the way for a fraction of it. */
#define SUBSET_N 256
/* Jitter, relative to sf^2, tried in turn when K is numerically not
 * positive definite (0 first). */
#define JITTER_FIRST 1e-12
#define JITTER_GROWTH 100.0
#define JITTER_LAST 1e-4
/* Grid-like inputs (at most this many distinct values in every varying
 * dim, as in a lookup table) build K from per-dim tables of kernel factors
 * instead of one exp per entry: the fill then costs a few multiplications
 * per entry, a third of an evaluation at n = 1000 otherwise. */
#define GRID_MAX 64
#define CHOL_BLOCK 64        /* panel width of the blocked Cholesky */
#define PREDICT_STACK_N 1024 /* tbl_gp_predict's scratch lives on the stack up to this n */
#define AT_BOUND_TOL 1e-3    /* ell within this fraction of its log interval is "at a bound" */
#define PENALTY 1e100        /* -log likelihood reported when K cannot be factorised */

struct tbl_gp {
    int n, dim, nact;
    int act[MAXDIM];          /* input dims that vary */
    int mod;                  /* input dim modulating the length scales, -1: none */
    double gam, mcen;         /* ell_d(x) = ell_d r(x), r(x) = exp(gam (x[mod] - mcen)) */
    double *r;                /* [n] r(x_i) of the current shape (1 without modulation) */
    int scale;                /* input dim whose value multiplies the main term, -1: none */
    int nbase, bact[MAXDIM];  /* with scale: the base term's varying dims (index into act) */
    double inv_bell2[MAXDIM]; /* 1/ell^2 of the base term per entry of bact */
    double rho2;              /* base term's variance over the main term's */
    double *x;                /* [n][dim] inputs */
    double *y, *sy;           /* [n] values, given noise sd */
    double inv_ell2[MAXDIM];  /* 1/ell^2 per varying dim (index into act) */
    double sf2, c2;           /* sf^2, c^2 (during the search: 1, lambda^2) */
    double *L;                /* [n][n] row-major; lower triangle = chol(K) */
    double *alpha;            /* [n] K^-1 (y - m 1) */
    double *w;                /* [n] K^-1 1 */
    double wsum;              /* 1' K^-1 1 */
    double *loo_mu, *loo_sd;  /* [n] */
    struct grid *grid;        /* during the fit of grid-like inputs, else NULL */
    int *gidx;                /* [n][nact] with grid: index of each input among its dim's values */
    tbl_gp_info info;
};

/* Distinct input values per varying dim and their kernel factors
 * tab[a][p u + q] = exp(-1/2 (val[a][p] - val[a][q])^2 / ell_a^2). */
typedef struct grid {
    int u[MAXDIM];
    double val[MAXDIM][GRID_MAX];
    double tab[MAXDIM][GRID_MAX * GRID_MAX];
} grid;

/* Searched parameters: log ell per varying dim, log lambda = log(c / sf),
 * with modulation gamma x half the modulating input's range, with a scaled
 * main term log ell of each base dim and log rho. */
typedef struct hyp {
    double lell[MAXDIM], llam, gmod, lbell[MAXDIM], lrho;
} hyp;

typedef struct fit_ctx {
    tbl_gp *g;
    int np;                        /* searched parameters: nact + 1 (+ 1 with modulation,
                                      + nbase + 1 with a scaled term), or 0 if nact = 0 */
    int kmod, kbase;               /* index of gmod and of the first lbell among them, -1 */
    double mhalf;                  /* half the range of the modulating input */
    double lo[MAXPAR], hi[MAXPAR]; /* bounds of the searched parameters, order lell.., llam,
                                      gmod, lbell.., lrho */
    double sf_lo, sf_hi;           /* bounds of sf */
    double inv_range[MAXDIM];      /* 1 / range per varying dim */
    double *a, *b;                 /* [n] scratch: L^-1 y, L^-1 1 */
    double jitter;                 /* jitter (relative to s^2) of the last factorisation */
    int evals;
} fit_ctx;

/* ---- bounded parameters ---------------------------------------------- */

/* MINUIT's transform (James & Roos 1975): p = lo + (hi - lo)(1 + sin t)/2
 * maps all real t onto [lo, hi], so the simplex needs no constraints. */
static double from_angle(double t, double lo, double hi)
{
    return lo + (hi - lo) * 0.5 * (1.0 + sin(t));
}

static double to_angle(double p, double lo, double hi)
{
    double u = 2.0 * (p - lo) / (hi - lo) - 1.0;
    return asin(fmin(1.0, fmax(-1.0, u)));
}

/* h as the plain vector of the searched parameters, in the order of lo[]
 * and hi[]: the form info.par carries. */
static void hyp_to_par(const fit_ctx *c, const hyp *h, double *p)
{
    int k = 0;
    for (; k < c->g->nact; k++) p[k] = h->lell[k];
    if (c->np > 0) p[k] = h->llam;
    if (c->kmod >= 0) p[c->kmod] = h->gmod;
    if (c->kbase >= 0) {
        int b = c->kbase;
        for (int j = 0; j < c->g->nbase; j++, b++) p[b] = h->lbell[j];
        p[b] = h->lrho;
    }
}

static void par_to_hyp(const fit_ctx *c, const double *p, hyp *h)
{
    int k = 0;
    for (; k < c->g->nact; k++) h->lell[k] = p[k];
    if (c->np > 0) h->llam = p[k];
    if (c->kmod >= 0) h->gmod = p[c->kmod];
    if (c->kbase >= 0) {
        int b = c->kbase;
        for (int j = 0; j < c->g->nbase; j++, b++) h->lbell[j] = p[b];
        h->lrho = p[b];
    }
}

/* The search's variables t (angles) to h and back. */
static void unpack(const fit_ctx *c, const double *t, hyp *h)
{
    double p[MAXPAR];
    for (int k = 0; k < c->np; k++) p[k] = from_angle(t[k], c->lo[k], c->hi[k]);
    par_to_hyp(c, p, h);
}

static void pack(const fit_ctx *c, const hyp *h, double *t)
{
    hyp_to_par(c, h, t);
    for (int k = 0; k < c->np; k++) t[k] = to_angle(t[k], c->lo[k], c->hi[k]);
}

/* r(x) of the modulated length scales: 1 without modulation. */
static double mod_factor(const tbl_gp *g, const double *x)
{
    return g->mod >= 0 && g->gam != 0.0 ? exp(g->gam * (x[g->mod] - g->mcen)) : 1.0;
}

/* K = A = R + lambda^2 S (s = 1); with no varying input A = S (sf = 0).
 * mhalf: half the modulating input's range (unused without modulation). */
static void set_shape(tbl_gp *g, const hyp *h, double mhalf)
{
    for (int a = 0; a < g->nact; a++) g->inv_ell2[a] = exp(-2.0 * h->lell[a]);
    g->gam = g->mod >= 0 ? h->gmod / mhalf : 0.0;
    for (int i = 0; i < g->n; i++) g->r[i] = mod_factor(g, g->x + (size_t)i * g->dim);
    for (int j = 0; j < g->nbase; j++) g->inv_bell2[j] = exp(-2.0 * h->lbell[j]);
    g->rho2 = g->scale >= 0 ? exp(2.0 * h->lrho) : 0.0;
    g->sf2 = g->nact > 0 ? 1.0 : 0.0;
    g->c2 = g->nact > 0 ? exp(2.0 * h->llam) : 1.0;
    grid *G = g->grid;
    if (!G) return;
    for (int a = 0; a < g->nact; a++)
        for (int p = 0; p < G->u[a]; p++)
            for (int q = 0; q < G->u[a]; q++) {
                double d = G->val[a][p] - G->val[a][q];
                G->tab[a][p * G->u[a] + q] = exp(-0.5 * d * d * g->inv_ell2[a]);
            }
}

/* ---- covariance and its factorisation --------------------------------- */

/* The main term's correlation: exp(-1/2 sum_d (dx_d / ell_d)^2) over the
 * varying dims; with modulation, every ell_d scaled by r(x) at each end
 * (ra = r(xa), rb = r(xb): mod_factor; Gibbs 1997; Paciorek & Schervish
 * 2004, eq. 3):
 *   prod_d (2 r r' / (r^2 + r'^2))^(1/2) exp(-sum_d dx_d^2 / (ell_d^2 (r^2 + r'^2))),
 * positive definite for any r(x) > 0 and equal to the stationary kernel
 * at gam = 0. */
static double kern_main(const tbl_gp *g, const double *xa, double ra, const double *xb, double rb)
{
    double s = 0.0;
    for (int a = 0; a < g->nact; a++) {
        double d = xa[g->act[a]] - xb[g->act[a]];
        s += d * d * g->inv_ell2[a];
    }
    if (g->mod < 0 || g->gam == 0.0) return exp(-0.5 * s);
    double q = ra * ra + rb * rb;
    return pow(2.0 * ra * rb / q, 0.5 * g->nact) * exp(-s / q);
}

/* The covariance of f at xa and xb (r(xa) = ra, r(xb) = rb); with a scaled
 * main term (tbl_gp_kernel.scale_dim):
 *   sf^2 (rho^2 exp(-1/2 sum_base (dx_d / bell_d)^2) + x[scale] x'[scale] main(x, x')). */
static double kern(const tbl_gp *g, const double *xa, double ra, const double *xb, double rb)
{
    if (g->scale < 0) return g->sf2 * kern_main(g, xa, ra, xb, rb);
    double s = 0.0;
    for (int j = 0; j < g->nbase; j++) {
        double d = xa[g->act[g->bact[j]]] - xb[g->act[g->bact[j]]];
        s += d * d * g->inv_bell2[j];
    }
    return g->sf2 * (g->rho2 * exp(-0.5 * s) +
                     xa[g->scale] * xb[g->scale] * kern_main(g, xa, ra, xb, rb));
}

/* Lower triangle of K = sf^2 R + diag(c^2 sy_i^2 + jitter) into K [n][n]. */
static void fill_cov(const tbl_gp *g, double jitter, double *K)
{
    int n = g->n, dim = g->dim, na = g->nact;
    const grid *G = g->grid;
    for (int i = 0; i < n; i++) {
        double *Ki = K + (size_t)i * n;
        const double *xi = g->x + (size_t)i * dim;
        if (G) {
            const int *ii = g->gidx + (size_t)i * na;
            for (int j = 0; j < i; j++) {
                const int *jj = g->gidx + (size_t)j * na;
                double v = g->sf2;
                for (int a = 0; a < na; a++) v *= G->tab[a][ii[a] * G->u[a] + jj[a]];
                Ki[j] = v;
            }
        } else {
            for (int j = 0; j < i; j++)
                Ki[j] = kern(g, xi, g->r[i], g->x + (size_t)j * dim, g->r[j]);
        }
        Ki[i] = kern(g, xi, g->r[i], xi, g->r[i]) + g->c2 * g->sy[i] * g->sy[i] + jitter;
    }
}

/* In-place Cholesky A = L L' of the lower triangle of the row-major [n][n]
 * A: right-looking, panels of CHOL_BLOCK (Golub & Van Loan 2013, §4.2),
 * the trailing update on level-3 BLAS.  Returns 0, or -1 when a pivot is
 * not positive (K not numerically positive definite); never aborts. */
static int chol_lower(int n, double *A)
{
    for (int k = 0; k < n; k += CHOL_BLOCK) {
        int nb = n - k < CHOL_BLOCK ? n - k : CHOL_BLOCK;
        double *A11 = A + (size_t)k * n + k;
        for (int j = 0; j < nb; j++) {
            double *rj = A11 + (size_t)j * n;
            double d = rj[j];
            for (int p = 0; p < j; p++) d -= rj[p] * rj[p];
            if (!(d > 0.0)) return -1;
            rj[j] = sqrt(d);
            for (int i = j + 1; i < nb; i++) {
                double *ri = A11 + (size_t)i * n, s = ri[j];
                for (int p = 0; p < j; p++) s -= ri[p] * rj[p];
                ri[j] = s / rj[j];
            }
        }
        int m = n - k - nb;
        if (m == 0) break;
        double *A21 = A11 + (size_t)nb * n, *A22 = A21 + nb;
        cblas_dtrsm(CblasRowMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, m, nb, 1.0,
                    A11, n, A21, n);
        cblas_dsyrk(CblasRowMajor, CblasLower, CblasNoTrans, m, nb, -1.0, A21, n, 1.0, A22, n);
    }
    return 0;
}

/* K into g->L and factorised, adding jitter x sf^2 to the diagonal only
 * when needed.  Returns that relative jitter, or -1 when even the largest
 * fails. */
static double factor(tbl_gp *g)
{
    double rel = 0.0;
    for (;;) {
        fill_cov(g, rel * g->sf2, g->L);
        if (chol_lower(g->n, g->L) == 0) return rel;
        if (g->sf2 == 0.0 || rel >= JITTER_LAST) return -1.0;
        rel = rel == 0.0 ? JITTER_FIRST : rel * JITTER_GROWTH;
    }
}

static double dot(int n, const double *u, const double *v)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) s += u[i] * v[i];
    return s;
}

/* a = L^-1 y, b = L^-1 1 from the factor in g->L. */
static void half_solves(const tbl_gp *g, double *a, double *b)
{
    int n = g->n;
    memcpy(a, g->y, (size_t)n * sizeof *a);
    for (int i = 0; i < n; i++) b[i] = 1.0;
    cblas_dtrsv(CblasRowMajor, CblasLower, CblasNoTrans, CblasNonUnit, n, g->L, n, a, 1);
    cblas_dtrsv(CblasRowMajor, CblasLower, CblasNoTrans, CblasNonUnit, n, g->L, n, b, 1);
}

/* GLS pieces of the factorised K: Q = r'K^-1 r with r = y - m 1 and
 * m = 1'K^-1 y / 1'K^-1 1, log|K|, 1'K^-1 1. */
typedef struct gls {
    double Q, logdet, bb;
} gls;

static gls gls_parts(const tbl_gp *g, double *a, double *b)
{
    int n = g->n;
    half_solves(g, a, b);
    double aa = dot(n, a, a), ab = dot(n, a, b), bb = dot(n, b, b), logdet = 0.0;
    for (int i = 0; i < n; i++) logdet += 2.0 * log(g->L[(size_t)i * n + i]);
    return (gls){.Q = aa - ab * ab / bb, .logdet = logdet, .bb = bb};
}

/* Restricted log likelihood of s^2 K given the pieces of K (R&W eq. 2.45
 * with H = 1', i.e. REML):
 *   -1/2 r'(s^2 K)^-1 r - 1/2 log|s^2 K| - 1/2 log(1'(s^2 K)^-1 1) - (n-1)/2 log 2pi. */
static double reml(int n, gls p, double s2)
{
    return -0.5 * p.Q / s2 - 0.5 * (n - 1) * log(s2) - 0.5 * p.logdet - 0.5 * log(p.bb) -
           0.5 * (n - 1) * log(2.0 * M_PI);
}

/* The s^2 maximising reml(): Q / (n-1), clamped to the interval allowed by
 * sf in [sf_lo, sf_hi] and c = lambda sf in [1, C_MAX] (with no varying
 * input: s = c in [1, C_MAX]).  The profile is unimodal in log s^2, so the
 * clamped value is the constrained optimum. */
static double best_scale(const fit_ctx *c, const hyp *h, gls p)
{
    double lo2 = 1.0, hi2 = C_MAX * C_MAX;
    if (c->g->nact > 0) {
        double lam2 = exp(2.0 * h->llam);
        lo2 = fmax(c->sf_lo * c->sf_lo, 1.0 / lam2);
        hi2 = fmin(c->sf_hi * c->sf_hi, C_MAX * C_MAX / lam2);
    }
    return fmin(hi2, fmax(lo2, p.Q / (c->g->n - 1)));
}

/* Nelder-Mead objective: -(log likelihood maximised over s) at angles t. */
static double objective(const gsl_vector *t, void *p)
{
    fit_ctx *c = p;
    hyp h;
    c->evals++;
    unpack(c, t->data, &h);
    set_shape(c->g, &h, c->mhalf);
    c->jitter = factor(c->g);
    if (c->jitter < 0.0) return PENALTY;
    gls q = gls_parts(c->g, c->a, c->b);
    double v = -reml(c->g->n, q, best_scale(c, &h, q));
    return isfinite(v) ? v : PENALTY;
}

/* ---- optimisation ------------------------------------------------------ */

/* One Nelder-Mead run from t (updated to the best vertex) with initial
 * simplex step h.  Ends on the simplex size (*converged = 1) or the
 * evaluation limit (0). */
static stc_status nm_run(fit_ctx *c, gsl_multimin_fminimizer *s, gsl_vector *t, double h,
                         gsl_vector *step, double *fmin, int *converged)
{
    gsl_multimin_function F = {.f = objective, .n = (size_t)c->np, .params = c};
    gsl_vector_set_all(step, h);
    STC_CHECK(gsl_multimin_fminimizer_set(s, &F, t, step) == GSL_SUCCESS, STC_ESOLVER,
              "Nelder-Mead set-up failed");
    int start = c->evals, limit = NM_MAXEVAL * (c->np > 4 ? c->np : 4);
    *converged = 0;
    for (;;) {
        if (gsl_multimin_fminimizer_iterate(s) != GSL_SUCCESS) break; /* no progress possible */
        if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s), NM_TOL) == GSL_SUCCESS) {
            *converged = 1;
            break;
        }
        if (c->evals - start >= limit) break;
    }
    gsl_vector_memcpy(t, gsl_multimin_fminimizer_x(s));
    *fmin = gsl_multimin_fminimizer_minimum(s);
    return STC_OK;
}

/* A run from t with step h, then up to `restarts` restarts from the
 * optimum (a fresh simplex: Nelder-Mead can stall on a collapsed one,
 * Press et al. 2007 §10.5) while they still gain.  *converged is cleared
 * if a run stops at its evaluation limit. */
static stc_status optimise(fit_ctx *c, gsl_vector *t, double h, int restarts, double *fbest,
                           int *converged)
{
    stc_status st = STC_OK;
    gsl_multimin_fminimizer *s =
        gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, (size_t)c->np);
    gsl_vector *step = gsl_vector_alloc((size_t)c->np);
    STC_CHECK_GOTO(s && step, st, done, STC_ENOMEM, "tbl_gp_fit: out of memory (optimiser)");
    int conv;
    STC_CALL_GOTO(nm_run(c, s, t, h, step, fbest, &conv), st, done);
    *converged = *converged && conv;
    for (int r = 0; r < restarts; r++) {
        double f;
        STC_CALL_GOTO(nm_run(c, s, t, NM_RESTART_STEP, step, &f, &conv), st, done);
        *converged = *converged && conv;
        double gain = *fbest - f;
        if (f < *fbest) *fbest = f;
        if (gain < NM_RESTART_GAIN) break;
    }
done:
    gsl_vector_free(step);
    gsl_multimin_fminimizer_free(s);
    return st;
}

/* Farthest-point sample (Gonzalez 1985) of m of the n points in
 * range-scaled varying inputs, from point 0, first index on ties: spread
 * over the table like the full set.  idx: [m] out; mind: [n] scratch. */
static void farthest_points(const fit_ctx *c, int m, int *idx, double *mind)
{
    const tbl_gp *g = c->g;
    for (int i = 0; i < g->n; i++) mind[i] = INFINITY;
    idx[0] = 0;
    for (int k = 1; k < m; k++) {
        const double *xl = g->x + (size_t)idx[k - 1] * g->dim;
        int far = 0;
        for (int i = 0; i < g->n; i++) {
            const double *xi = g->x + (size_t)i * g->dim;
            double s = 0.0;
            for (int a = 0; a < g->nact; a++) {
                double d = (xi[g->act[a]] - xl[g->act[a]]) * c->inv_range[a];
                s += d * d;
            }
            mind[i] = fmin(mind[i], s);
            if (mind[i] > mind[far]) far = i;
        }
        idx[k] = far;
    }
}

/* The search with restarts on SUBSET_N points, leaving its optimum in t:
 * a view of the handle holding the subset's data, g->L its workspace. */
static stc_status optimise_subset(fit_ctx *c, gsl_vector *t, double *fbest, int *converged)
{
    tbl_gp *g = c->g;
    int m = SUBSET_N, dim = g->dim;
    stc_status st = STC_OK;
    int *idx = malloc((size_t)m * sizeof *idx);
    int na = g->nact, *gs = g->gidx ? malloc((size_t)m * na * sizeof *gs) : NULL;
    double *xs = malloc((size_t)m * dim * sizeof *xs), *ys = malloc((size_t)m * sizeof *ys),
           *ss = malloc((size_t)m * sizeof *ss), *mind = malloc((size_t)g->n * sizeof *mind);
    STC_CHECK_GOTO(idx && xs && ys && ss && mind && (gs || !g->gidx), st, done, STC_ENOMEM,
                   "tbl_gp_fit: out of memory (subset of %d points)", m);
    farthest_points(c, m, idx, mind);
    for (int k = 0; k < m; k++) {
        memcpy(xs + (size_t)k * dim, g->x + (size_t)idx[k] * dim, (size_t)dim * sizeof *xs);
        ys[k] = g->y[idx[k]];
        ss[k] = g->sy[idx[k]];
        if (gs) memcpy(gs + (size_t)k * na, g->gidx + (size_t)idx[k] * na, (size_t)na * sizeof *gs);
    }
    tbl_gp sub = *g;
    sub.n = m, sub.x = xs, sub.y = ys, sub.sy = ss, sub.gidx = gs;
    fit_ctx cs = *c;
    cs.g = &sub;
    st = optimise(&cs, t, NM_STEP, NM_RESTARTS, fbest, converged);
    c->evals = cs.evals;
done:
    free(idx);
    free(gs);
    free(xs);
    free(ys);
    free(ss);
    free(mind);
    return st;
}

/* ---- set-up -------------------------------------------------------------- */

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Range and smallest nonzero spacing of dim d; leaves its distinct values
 * sorted in scratch[0..count) and returns count (scratch [n]). */
static int dim_spread(const tbl_gp *g, int d, double *scratch, double *range, double *spacing)
{
    int n = g->n, u = 1;
    for (int i = 0; i < n; i++) scratch[i] = g->x[(size_t)i * g->dim + d];
    qsort(scratch, (size_t)n, sizeof *scratch, cmp_double);
    *range = scratch[n - 1] - scratch[0];
    *spacing = INFINITY;
    for (int i = 1; i < n; i++)
        if (scratch[i] > scratch[u - 1]) {
            *spacing = fmin(*spacing, scratch[i] - scratch[u - 1]);
            scratch[u++] = scratch[i];
        }
    return u;
}

/* With at most GRID_MAX distinct values in every varying dim: g->grid and
 * g->gidx for the table-based fill.  Without them (other inputs, or no
 * memory) the fill evaluates the kernel directly; same model either way. */
static void grid_setup(tbl_gp *g, grid *G)
{
    if (!G) return;
    for (int a = 0; a < g->nact; a++)
        if (G->u[a] > GRID_MAX) {
            free(G);
            return;
        }
    g->gidx = malloc((size_t)g->n * g->nact * sizeof *g->gidx);
    if (!g->gidx) {
        free(G);
        return;
    }
    for (int i = 0; i < g->n; i++)
        for (int a = 0; a < g->nact; a++) {
            double v = g->x[(size_t)i * g->dim + g->act[a]];
            const double *p = bsearch(&v, G->val[a], (size_t)G->u[a], sizeof v, cmp_double);
            g->gidx[(size_t)i * g->nact + a] = (int)(p - G->val[a]);
        }
    g->grid = G;
}

static stc_status check_args(int n, int dim, const double *x, const double *y, const double *sy,
                             tbl_gp **out)
{
    STC_CHECK(out, STC_EINVAL, "tbl_gp_fit: out = NULL: must point to a handle pointer");
    *out = NULL;
    STC_CHECK(n >= 2, STC_EINVAL, "n = %d: must be >= 2 points", n);
    STC_CHECK(dim >= 1 && dim <= MAXDIM, STC_EINVAL, "dim = %d: must be in 1..%d", dim, MAXDIM);
    STC_CHECK(x && y && sy, STC_EINVAL, "tbl_gp_fit: %s = NULL: must point to %s values",
              !x ? "x" : !y ? "y" : "sy", !x ? "n*dim" : "n");
    for (int i = 0; i < n; i++) {
        for (int d = 0; d < dim; d++)
            STC_CHECK(isfinite(x[(size_t)i * dim + d]), STC_EINVAL,
                      "x[%d][%d] = %g: must be finite", i, d, x[(size_t)i * dim + d]);
        STC_CHECK(isfinite(y[i]), STC_EINVAL, "y[%d] = %g: must be finite", i, y[i]);
        STC_CHECK(isfinite(sy[i]) && sy[i] > 0.0, STC_EINVAL, "sy[%d] = %g: must be finite and > 0",
                  i, sy[i]);
    }
    return STC_OK;
}

static tbl_gp *alloc_handle(int n, int dim)
{
    tbl_gp *g = calloc(1, sizeof *g);
    if (!g) return NULL;
    size_t nn = (size_t)n;
    g->x = malloc(nn * (size_t)dim * sizeof *g->x);
    g->y = malloc(nn * sizeof *g->y);
    g->sy = malloc(nn * sizeof *g->sy);
    g->L = malloc(nn * nn * sizeof *g->L);
    g->r = malloc(nn * sizeof *g->r);
    g->alpha = malloc(nn * sizeof *g->alpha);
    g->w = malloc(nn * sizeof *g->w);
    g->loo_mu = malloc(nn * sizeof *g->loo_mu);
    g->loo_sd = malloc(nn * sizeof *g->loo_sd);
    if (!g->x || !g->y || !g->sy || !g->r || !g->L || !g->alpha || !g->w || !g->loo_mu || !g->loo_sd)
        tbl_gp_destroy(&g);
    return g;
}

/* Bounds and deterministic start (ell = half the range, sf = sd(y), c = 1)
 * of the searched parameters; the input part of g->info.  scratch: [n]. */
static void setup(fit_ctx *c, hyp *h, double *scratch, unsigned base_dims)
{
    tbl_gp *g = c->g;
    int n = g->n;
    g->nact = 0;
    grid *G = malloc(sizeof *G);
    for (int d = 0; d < MAXDIM; d++) g->info.ell[d] = g->info.ell_lo[d] = g->info.ell_hi[d] = INFINITY;
    int mod = g->mod, scale = g->scale;
    g->mod = g->scale = -1;
    g->nbase = 0;
    for (int d = 0; d < g->dim; d++) {
        double range, spacing;
        int u = dim_spread(g, d, scratch, &range, &spacing);
        if (!(range > 0.0)) continue; /* constant input: ignored */
        if (d == mod) { /* a constant modulating input modulates nothing */
            g->mod = d;
            c->mhalf = 0.5 * range;
            g->mcen = scratch[0] + c->mhalf;
        }
        if (d == scale) g->scale = d; /* a constant scale would only rescale sf */
        int k = g->nact++;
        g->act[k] = d;
        if (G) {
            G->u[k] = u;
            if (u <= GRID_MAX) memcpy(G->val[k], scratch, (size_t)u * sizeof *scratch);
        }
        c->inv_range[k] = 1.0 / range;
        c->lo[k] = log(ELL_LO_SPACING * spacing);
        c->hi[k] = log(ELL_HI_RANGE * range);
        g->info.ell_lo[d] = exp(c->lo[k]);
        g->info.ell_hi[d] = exp(c->hi[k]);
        h->lell[k] = log(ELL_START_RANGE * range);
    }
    /* the modulated or scaled kernel is not a product of per-dim factors */
    if (g->nact > 0 && g->mod < 0 && g->scale < 0) grid_setup(g, G);
    else free(G);
    double ym = 0.0, yv = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) ym += g->y[i] / n;
    for (int i = 0; i < n; i++) {
        yv += (g->y[i] - ym) * (g->y[i] - ym) / (n - 1);
        s2 += g->sy[i] * g->sy[i] / n;
    }
    double s0 = fmax(sqrt(yv), sqrt(s2));
    c->sf_lo = SF_LO * s0;
    c->sf_hi = SF_HI * s0;
    c->np = 0;
    h->llam = 0.0;
    if (g->nact > 0) {
        int k = g->nact;
        double sf = fmin(c->sf_hi, fmax(c->sf_lo, yv > 0.0 ? sqrt(yv) : s0));
        c->lo[k] = -log(c->sf_hi);       /* lambda = c / sf >= 1 / sf_hi */
        c->hi[k] = log(C_MAX / c->sf_lo); /* lambda <= C_MAX / sf_lo */
        h->llam = -log(sf);
        c->np = k + 1;
        h->gmod = 0.0;
        c->kmod = c->kbase = -1;
        if (g->mod >= 0) {
            c->kmod = c->np++;
            c->lo[c->kmod] = -MOD_MAX;
            c->hi[c->kmod] = MOD_MAX;
        }
        if (g->scale >= 0) {
            c->kbase = c->np;
            for (int a = 0; a < g->nact; a++) {
                if (!(base_dims & 1u << g->act[a])) continue;
                int b = c->np++;
                g->bact[g->nbase] = a;
                c->lo[b] = c->lo[a];
                c->hi[b] = c->hi[a];
                h->lbell[g->nbase++] = h->lell[a];
            }
            c->lo[c->np] = log(RHO_LO);
            c->hi[c->np] = log(RHO_HI);
            c->np++;
            h->lrho = 0.0;
        }
    } else {
        g->mod = g->scale = -1;
        c->kmod = c->kbase = -1;
    }
}

/* With the optimum's factor in g->L: GLS mean, alpha, w, the closed-form
 * leave-one-out values and their summary. */
static stc_status finish(fit_ctx *c)
{
    tbl_gp *g = c->g;
    int n = g->n;
    double *a = c->a, *b = c->b;
    half_solves(g, a, b);
    g->wsum = dot(n, b, b);
    double m = dot(n, a, b) / g->wsum;
    for (int i = 0; i < n; i++) {
        g->alpha[i] = a[i] - m * b[i];
        g->w[i] = b[i];
    }
    cblas_dtrsv(CblasRowMajor, CblasLower, CblasTrans, CblasNonUnit, n, g->L, n, g->alpha, 1);
    cblas_dtrsv(CblasRowMajor, CblasLower, CblasTrans, CblasNonUnit, n, g->L, n, g->w, 1);
    g->info.mean = m;

    /* diag(K^-1) = squared column norms of L^-1 */
    double *Li = calloc((size_t)n * n, sizeof *Li);
    STC_CHECK(Li, STC_ENOMEM, "tbl_gp_fit: out of memory (%d x %d inverse factor)", n, n);
    for (int i = 0; i < n; i++) Li[(size_t)i * n + i] = 1.0;
    cblas_dtrsm(CblasRowMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, n, n, 1.0, g->L,
                n, Li, n);
    for (int i = 0; i < n; i++) a[i] = 0.0;
    for (int k = 0; k < n; k++)
        for (int i = 0; i <= k; i++) a[i] += Li[(size_t)k * n + i] * Li[(size_t)k * n + i];
    free(Li);

    /* LOO with the mean re-estimated: R&W eq. 5.12 applied to the limit of
     * (K + s^2 1 1')^-1 as s -> inf, P = K^-1 - w w' / 1'w (Dubrule 1983):
     * mu_-i = y_i - [P y]_i / P_ii, var_-i = 1 / P_ii, and P y = alpha. */
    double ss = 0.0, big = 0.0;
    int cover = 0;
    for (int i = 0; i < n; i++) {
        double Pii = a[i] - g->w[i] * g->w[i] / g->wsum, r = g->alpha[i] / Pii;
        g->loo_mu[i] = g->y[i] - r;
        g->loo_sd[i] = 1.0 / sqrt(Pii);
        ss += r * r;
        big = fmax(big, fabs(r));
        cover += fabs(r) <= 2.0 * g->loo_sd[i];
    }
    g->info.loo_rms = sqrt(ss / n);
    g->info.loo_max = big;
    g->info.loo_cover2 = (double)cover / n;
    return STC_OK;
}

/* Sets sf and c at the optimum h, factorises the final K into g->L and
 * fills the summary.  Fails only if K cannot be factorised. */
static stc_status apply(fit_ctx *c, const hyp *h, int converged)
{
    tbl_gp *g = c->g;
    tbl_gp_info *in = &g->info;
    set_shape(g, h, c->mhalf);
    double rel = factor(g);
    STC_CHECK(rel >= 0.0, STC_ESOLVER,
              "tbl_gp_fit: covariance not positive definite at the optimum even with jitter "
              "%g x sf^2", JITTER_LAST);
    double s2 = best_scale(c, h, gls_parts(g, c->a, c->b));
    if (g->nact > 0) {
        g->sf2 = s2;
        g->c2 = fmax(1.0, s2 * exp(2.0 * h->llam)); /* c = lambda sf >= 1, up to rounding */
    } else {
        g->c2 = s2;
    }
    rel = factor(g);
    STC_CHECK(rel >= 0.0, STC_ESOLVER,
              "tbl_gp_fit: covariance not positive definite at the optimum even with jitter "
              "%g x sf^2", JITTER_LAST);
    in->n = g->n;
    in->dim = g->dim;
    for (int a = 0; a < g->nact; a++) {
        int d = g->act[a];
        double tol = AT_BOUND_TOL * (c->hi[a] - c->lo[a]);
        in->ell[d] = exp(h->lell[a]);
        in->ell_at_bound[d] = h->lell[a] <= c->lo[a] + tol ? -1 : h->lell[a] >= c->hi[a] - tol;
    }
    in->sf = sqrt(g->sf2);
    in->mod_dim = g->mod;
    in->scale_dim = g->scale;
    for (int d = 0; d < MAXDIM; d++) in->base_ell[d] = INFINITY;
    for (int j = 0; j < g->nbase; j++) in->base_ell[g->act[g->bact[j]]] = exp(h->lbell[j]);
    in->base_sd = sqrt(g->rho2 * g->sf2);
    in->gamma = g->gam;
    in->mod_centre = g->mod >= 0 ? g->mcen : 0.0;
    if (c->kmod >= 0) {
        int k = c->kmod;
        double tol = AT_BOUND_TOL * (c->hi[k] - c->lo[k]);
        in->gamma_at_bound = h->gmod <= c->lo[k] + tol ? -1 : h->gmod >= c->hi[k] - tol;
    }
    in->noise_scale = sqrt(g->c2);
    in->log_ml = reml(g->n, gls_parts(g, c->a, c->b), 1.0);
    in->evaluations = c->evals;
    in->converged = converged;
    in->jitter = rel * g->sf2;
    in->npar = c->np;
    hyp_to_par(c, h, in->par);
    return STC_OK;
}

stc_status tbl_gp_fit(int n, int dim, const double *x, const double *y, const double *sy,
                      tbl_gp **out)
{
    return tbl_gp_fit_kernel(n, dim, x, y, sy, NULL, out);
}

/* The fit of tbl_gp_fit_kernel, or with at = 1 the one at the npar
 * hyperparameters par instead of searched. */
static stc_status fit(int n, int dim, const double *x, const double *y, const double *sy,
                      const tbl_gp_kernel *kernel, int at, int npar, const double *par,
                      tbl_gp **out)
{
    STC_CALL(check_args(n, dim, x, y, sy, out));
    tbl_gp_kernel kd = kernel ? *kernel : (tbl_gp_kernel){-1, -1, 0};
    STC_CHECK(kd.mod_dim >= -1 && kd.mod_dim < dim, STC_EINVAL,
              "mod_dim = %d: must be -1 (none) or an input dim in 0..%d", kd.mod_dim, dim - 1);
    STC_CHECK(kd.scale_dim >= -1 && kd.scale_dim < dim, STC_EINVAL,
              "scale_dim = %d: must be -1 (none) or an input dim in 0..%d", kd.scale_dim,
              dim - 1);
    STC_CHECK(kd.base_dims < 1u << dim, STC_EINVAL,
              "base_dims = %#x: must name input dims 0..%d only (bits below %#x)", kd.base_dims,
              dim - 1, 1u << dim);
    stc_status st = STC_OK;
    /* GSL's error handler is process-wide, so it is left alone: no GSL call
     * of the fit can reach it but an allocation failure.  Nelder-Mead
     * reports only non-finite objective values (objective returns PENALTY
     * for those) and size mismatches (every vector has c.np elements); the
     * size test only a negative tolerance (NM_TOL > 0). */
    fit_ctx c = {0};
    gsl_vector *t = NULL;
    tbl_gp *g = alloc_handle(n, dim);
    c.g = g;
    c.a = malloc((size_t)n * sizeof *c.a);
    c.b = malloc((size_t)n * sizeof *c.b);
    STC_CHECK_GOTO(g && c.a && c.b, st, done, STC_ENOMEM,
                   "tbl_gp_fit: out of memory (n = %d points)", n);
    g->n = n, g->dim = dim, g->mod = kd.mod_dim, g->scale = kd.scale_dim;
    memcpy(g->x, x, (size_t)n * dim * sizeof *x);
    memcpy(g->y, y, (size_t)n * sizeof *y);
    memcpy(g->sy, sy, (size_t)n * sizeof *sy);

    hyp h;
    setup(&c, &h, c.a, kd.base_dims);
    int converged = 1;
    if (at) {
        STC_CHECK_GOTO(npar == c.np, st, done, STC_EINVAL,
                       "tbl_gp_fit_at: npar = %d: these data and kernel have %d hyperparameters",
                       npar, c.np);
        for (int k = 0; k < npar; k++)
            STC_CHECK_GOTO(isfinite(par[k]) && par[k] >= c.lo[k] && par[k] <= c.hi[k], st, done,
                           STC_EINVAL,
                           "tbl_gp_fit_at: par[%d] = %g: must lie in [%g, %g] for these data",
                           k, par[k], c.lo[k], c.hi[k]);
        par_to_hyp(&c, par, &h);
    } else if (c.np > 0) {
        t = gsl_vector_alloc((size_t)c.np);
        STC_CHECK_GOTO(t, st, done, STC_ENOMEM, "tbl_gp_fit: out of memory (optimiser)");
        pack(&c, &h, t->data);
        double fbest;
        if (n > SUBSET_N) {
            /* the all-points run from the subset's optimum is itself the restart */
            STC_CALL_GOTO(optimise_subset(&c, t, &fbest, &converged), st, done);
            STC_CALL_GOTO(optimise(&c, t, NM_RESTART_STEP, 0, &fbest, &converged), st, done);
            g->info.subset_n = SUBSET_N;
        } else {
            STC_CALL_GOTO(optimise(&c, t, NM_STEP, NM_RESTARTS, &fbest, &converged), st, done);
        }
        unpack(&c, t->data, &h);
    } /* else no varying input: only c, in closed form */
    STC_CALL_GOTO(apply(&c, &h, converged), st, done);
    STC_CALL_GOTO(finish(&c), st, done);
    free(g->grid); /* the fit's alone: predictions evaluate the kernel directly */
    free(g->gidx);
    g->grid = NULL;
    g->gidx = NULL;
    *out = g;
    g = NULL;
done:
    gsl_vector_free(t);
    free(c.a);
    free(c.b);
    tbl_gp_destroy(&g);
    return st;
}

stc_status tbl_gp_fit_kernel(int n, int dim, const double *x, const double *y, const double *sy,
                             const tbl_gp_kernel *kernel, tbl_gp **out)
{
    return fit(n, dim, x, y, sy, kernel, 0, 0, NULL, out);
}

stc_status tbl_gp_fit_at(int n, int dim, const double *x, const double *y, const double *sy,
                         const tbl_gp_kernel *kernel, int npar, const double *par, tbl_gp **out)
{
    if (out) *out = NULL;
    STC_CHECK(par || npar == 0, STC_EINVAL, "tbl_gp_fit_at: par must not be NULL (npar = %d)",
              npar);
    return fit(n, dim, x, y, sy, kernel, 1, npar, par, out);
}

/* ---- queries --------------------------------------------------------------- */

void tbl_gp_predict(const tbl_gp *g, const double *x, double *mean, double *sd)
{
    int n = g->n;
    double stack[PREDICT_STACK_N];
    double *k = NULL;
    if (sd) k = n <= PREDICT_STACK_N ? stack : malloc((size_t)n * sizeof *k);
    double ka = 0.0, kw = 0.0, rx = mod_factor(g, x);
    for (int i = 0; i < n; i++) {
        double ki = kern(g, x, rx, g->x + (size_t)i * g->dim, g->r[i]);
        ka += ki * g->alpha[i];
        kw += ki * g->w[i];
        if (k) k[i] = ki;
    }
    if (mean) *mean = g->info.mean + ka;
    if (!sd) return;
    if (!k) {
        *sd = NAN;
        return;
    }
    /* R&W eq. 2.42 with h = 1: sf^2 - k'K^-1 k + (1 - 1'K^-1 k)^2 / 1'K^-1 1 */
    cblas_dtrsv(CblasRowMajor, CblasLower, CblasNoTrans, CblasNonUnit, n, g->L, n, k, 1);
    double var = kern(g, x, rx, x, rx) - dot(n, k, k) + (1.0 - kw) * (1.0 - kw) / g->wsum;
    *sd = sqrt(fmax(var, 0.0));
    if (k != stack) free(k);
}

void tbl_gp_loo(const tbl_gp *g, double *mean, double *sd)
{
    memcpy(mean, g->loo_mu, (size_t)g->n * sizeof *mean);
    memcpy(sd, g->loo_sd, (size_t)g->n * sizeof *sd);
}

void tbl_gp_get_info(const tbl_gp *g, tbl_gp_info *info) { *info = g->info; }

void tbl_gp_destroy(tbl_gp **g)
{
    if (!g || !*g) return;
    tbl_gp *p = *g;
    free(p->x);
    free(p->y);
    free(p->sy);
    free(p->L);
    free(p->alpha);
    free(p->w);
    free(p->loo_mu);
    free(p->loo_sd);
    free(p->r);
    free(p->grid);
    free(p->gidx);
    free(p);
    *g = NULL;
}
