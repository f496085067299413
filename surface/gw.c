/* Greenwood–Williamson summation (include/stiction/gw.h; docs/design.md §5.4).
 *
 *   N/An = η ∫_d^∞ φ(z) dz,   P/An = η ∫_d^∞ P_asp(z − d) φ(z) dz,
 *   A/An, Q/An likewise;      μs = Q/P                (GW 1966; docs/design.md §5.4)
 *
 * Statistical modes integrate in standard units s = z/σs (h = d/σs) by
 * adaptive Gauss–Kronrod (srf_quad.h) between the asperity model's
 * breakpoints and over the tail; the deterministic mode sums over the
 * summits sorted by height, so a separation costs only the summits in
 * contact.
 *
 * GSL's error handler: process-wide, so this file never sets it; instead no
 * GSL call here can reach it once a handle is created.  The quadrature
 * reports by status (srf_quad.h); the KDE interpolant is evaluated inside
 * its knots only (density, contacts_stat); the root function is finite
 * (root_fn) and the bracket straddles the root (bracket), the only failures
 * Brent's solver reports; its tolerances are checked (params_check).  Left
 * to the handler: out of memory inside GSL's allocators, at creation.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_interp.h>
#include <gsl/gsl_roots.h>

#include "stiction/gw.h"
#include "stiction/parse.h"
#include "srf_impl.h"
#include "srf_quad.h"
#include "stc_check.h"

#define TABOR_H_OVER_Y 2.8 /* Tabor (1951): H = 2.8 Y; GW 1966 plasticity index */
#define INV_SQRT_2PI 0.39894228040143267794
#define KDE_SUPPORT 8.0    /* kernel cut at 8 bandwidths: exp(-32) ~ 1e-14 */
#define QUANTILE_PIECES 256 /* load quantile: cumulative on this many pieces ... */
#define QUANTILE_GL 8       /* ... each by 8-point Gauss-Legendre */
#define GAUSS_TOP 9.0       /* Gaussian heights: nothing above s = max(h,0) + 9 (phi ~ 1e-18) */
#define QUAD_ACCEPT 1e-6   /* accept a warning (e.g. roundoff) if abserr <= this × |result| */

enum { Q_P, Q_A, Q_Q }; /* which quantity an integrand returns */

struct srf_gw {
    const asp_model *m;
    srf_gw_params par;
    srf_gw_info info;
    asp_model_range range;
    srf_quad *ws;        /* quadrature workspace, par.limit subintervals */
    gsl_root_fsolver *root; /* Brent, for the pressure solve */
    double tR;           /* statistical: t/R of the single radius */
    double h_hint;       /* last solved separation (NaN: none), starts the next bracket */
    gsl_integration_glfixed_table *gl; /* fixed rule of the load quantile */
    /* KDE density in s units on [k_lo, k_hi] */
    int kn;
    double *ks, *kf;
    gsl_interp *kip;
    /* deterministic: summits sorted by height, descending */
    int n;
    double *zs;          /* [n] height above the mean summit height, mm */
    double *R;           /* [n] radius, mm */
    double *inv_wc;      /* [n] 1/ωc(R), 1/mm: precomputed for the root loop */
    double *Pc;          /* [n] Pc(R), N */
    double *tR_i;        /* [n] t/R */
};

const char *srf_gw_mode_name(srf_gw_mode m)
{
    switch (m) {
    case SRF_GW_GAUSSIAN: return "gaussian";
    case SRF_GW_KDE: return "kde";
    case SRF_GW_DETERMINISTIC: return "deterministic";
    }
    return "unknown";
}

void srf_gw_params_default(srf_gw_params *p)
{
    p->epsrel = 1e-10;
    p->limit = 1000;
    p->root_tol = 1e-11;
    p->max_iter = 200;
    p->coverage_quantile = 0.999;
    p->kde_grid = 4096;
}

static stc_status params_check(const srf_gw_params *p)
{
    STC_CALL(stc_check_range("epsrel", p->epsrel, 1e-14, 1, 0.1, 1));
    STC_CHECK(p->limit >= 10 && p->limit <= 1000000, STC_EINVAL,
              "limit = %d: must be in [10, 1000000]", p->limit);
    STC_CALL(stc_check_range("root-tol", p->root_tol, 0.0, 0, 1.0, 1));
    STC_CHECK(p->max_iter >= 1, STC_EINVAL, "max-iter = %d: must be >= 1", p->max_iter);
    STC_CALL(stc_check_range("coverage-quantile", p->coverage_quantile, 0.5, 1, 1.0, 0));
    STC_CHECK(p->kde_grid >= 64 && p->kde_grid <= 1 << 22, STC_EINVAL,
              "kde-grid = %d: must be in [64, 4194304]", p->kde_grid);
    return STC_OK;
}

/* Allocate the handle and fill what every mode shares. */
static stc_status gw_alloc(const asp_model *model, srf_gw_mode mode, const srf_gw_params *p,
                           srf_gw **out)
{
    STC_CHECK(out, STC_EINVAL, "srf_gw: out must not be NULL");
    *out = NULL;
    STC_CHECK(model, STC_EINVAL, "srf_gw: model must not be NULL");
    srf_gw *g = calloc(1, sizeof *g);
    STC_CHECK(g, STC_ENOMEM, "srf_gw: out of memory");
    g->m = model;
    if (p) g->par = *p;
    else srf_gw_params_default(&g->par);
    stc_status st = params_check(&g->par);
    if (st != STC_OK) {
        free(g);
        return st;
    }
    g->h_hint = NAN;
    g->ws = srf_quad_alloc(g->par.limit);
    g->gl = gsl_integration_glfixed_table_alloc(QUANTILE_GL);
    g->root = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!g->ws || !g->gl || !g->root) {
        srf_gw_destroy(&g);
        return STC_FAIL(STC_ENOMEM, "srf_gw: out of memory");
    }
    asp_model_get_range(model, &g->range);
    g->info.mode = mode;
    g->info.E_star_MPa = asp_model_E_star(model);
    g->info.H_MPa = TABOR_H_OVER_Y * asp_model_ref(model)->Y;
    g->info.area_mm2 = NAN;
    g->info.bandwidth_mm = NAN;
    *out = g;
    return STC_OK;
}

/* ψ = (E* / H) sqrt(σs/R): Greenwood & Williamson (1966), H = 2.8 Y (Tabor). */
static void finish_info(srf_gw *g)
{
    srf_gw_info *i = &g->info;
    i->plasticity_index = i->E_star_MPa / i->H_MPa * sqrt(i->sigma_s_mm / i->R_mm);
    g->tR = asp_model_t(g->m) / i->R_mm;
}

stc_status srf_gw_create_gaussian(const asp_model *model, double eta_per_mm2, double R_mm,
                                  double sigma_s_mm, const srf_gw_params *p, srf_gw **out)
{
    STC_CALL(stc_check_range("summit-density", eta_per_mm2, 0.0, 0, INFINITY, 0));
    STC_CALL(stc_check_range("summit-radius", R_mm, 0.0, 0, INFINITY, 0));
    STC_CALL(stc_check_range("sigma-s", sigma_s_mm, 0.0, 0, INFINITY, 0));
    STC_CALL(gw_alloc(model, SRF_GW_GAUSSIAN, p, out));
    srf_gw *g = *out;
    g->info.eta_per_mm2 = eta_per_mm2;
    g->info.R_mm = R_mm;
    g->info.sigma_s_mm = sigma_s_mm;
    finish_info(g);
    return STC_OK;
}

/* ------------------------------------------------------------ summits */

/* Per-summit normalisation of the deterministic hot loop. */
static stc_status per_summit(srf_gw *g, int k)
{
    g->inv_wc = malloc((size_t)k * sizeof *g->inv_wc);
    g->Pc = malloc((size_t)k * sizeof *g->Pc);
    g->tR_i = malloc((size_t)k * sizeof *g->tR_i);
    STC_CHECK(g->inv_wc && g->Pc && g->tR_i, STC_ENOMEM, "srf_gw: out of memory");
    for (int i = 0; i < k; i++) {
        g->inv_wc[i] = 1.0 / asp_model_omega_c(g->m, g->R[i]);
        g->Pc[i] = asp_model_P_c(g->m, g->R[i]);
        g->tR_i[i] = asp_model_t(g->m) / g->R[i];
    }
    return STC_OK;
}

/* Keep summits with 0 < R < inf, standardise heights, sort descending. */
static stc_status load_summits(srf_gw *g, const double *z, const double *R, int n)
{
    srf_zr *v = malloc((size_t)(n > 0 ? n : 1) * sizeof *v);
    STC_CHECK(v, STC_ENOMEM, "srf_gw: out of memory");
    int k = 0;
    double sum = 0, sumk = 0;
    for (int i = 0; i < n; i++) {
        if (!(R[i] > 0 && isfinite(R[i]) && isfinite(z[i]))) continue;
        v[k++] = (srf_zr){z[i], R[i]};
        sum += z[i];
        sumk += 1.0 / R[i];
    }
    g->info.n_excluded = n - k;
    if (k < 2) {
        free(v);
        return STC_FAIL(STC_EINVAL, "summits = %d usable of %d: need >= 2 with 0 < R < inf",
                        k, n);
    }
    double mean = sum / k, ss = 0;
    for (int i = 0; i < k; i++) ss += (v[i].z - mean) * (v[i].z - mean);
    stc_status st = srf_sort_desc(v, k);
    if (st != STC_OK) {
        free(v);
        return st;
    }
    g->zs = malloc((size_t)k * sizeof *g->zs);
    g->R = malloc((size_t)k * sizeof *g->R);
    if (!g->zs || !g->R) {
        free(v);
        return STC_FAIL(STC_ENOMEM, "srf_gw: out of memory");
    }
    for (int i = 0; i < k; i++) {
        g->zs[i] = v[i].z - mean;
        g->R[i] = v[i].R;
    }
    free(v);
    STC_CALL(per_summit(g, k));
    g->n = k;
    g->info.n_summits = k;
    g->info.mean_height_mm = mean;
    g->info.sigma_s_mm = sqrt(ss / k);
    g->info.R_mm = k / sumk; /* 1/<κ>: the mean-curvature convention of surface.h */
    STC_CHECK(g->info.sigma_s_mm > 0, STC_EINVAL,
              "sigma-s = 0: all %d summits have the same height", k);
    return STC_OK;
}

/* Silverman's rule in s units (std 1): b = 0.9 min(1, IQR/1.34) n^(-1/5),
 * heights z_desc in mm with standard deviation sig. */
static double silverman(const double *z_desc, int n, double sig)
{
    double q75 = z_desc[(int)(0.25 * (n - 1))], q25 = z_desc[(int)(0.75 * (n - 1))];
    double spread = fmin(1.0, (q75 - q25) / (1.34 * sig));
    if (!(spread > 0)) spread = 1.0;
    return 0.9 * spread * pow(n, -0.2);
}

/* Gaussian KDE of the standardised heights on a grid: linear binning, then a
 * direct convolution with the kernel truncated at KDE_SUPPORT bandwidths. */
static stc_status build_kde(srf_gw *g)
{
    int n = g->n, G = g->par.kde_grid;
    double sig = g->info.sigma_s_mm;
    double b = silverman(g->zs, n, sig), lo, hi;
    lo = g->zs[n - 1] / sig - KDE_SUPPORT * b;
    hi = g->zs[0] / sig + KDE_SUPPORT * b;
    double dx = (hi - lo) / (G - 1);
    double *c = calloc((size_t)G, sizeof *c);
    g->ks = malloc((size_t)G * sizeof *g->ks);
    g->kf = calloc((size_t)G, sizeof *g->kf);
    STC_CHECK(c && g->ks && g->kf, STC_ENOMEM, "srf_gw: out of memory");
    for (int i = 0; i < n; i++) {
        double u = (g->zs[i] / sig - lo) / dx;
        int j = (int)u;
        if (j >= G - 1) j = G - 2;
        c[j] += (j + 1 - u);
        c[j + 1] += (u - j);
    }
    int half = (int)ceil(KDE_SUPPORT * b / dx);
    double norm = INV_SQRT_2PI / (b * n), total = 0;
    #pragma omp parallel for reduction(+ : total) if (G > 1024)
    for (int j = 0; j < G; j++) {
        double f = 0;
        int k0 = j - half < 0 ? 0 : j - half, k1 = j + half >= G ? G - 1 : j + half;
        for (int k = k0; k <= k1; k++) {
            double u = (j - k) * dx / b;
            f += c[k] * exp(-0.5 * u * u);
        }
        g->kf[j] = f * norm;
        total += g->kf[j];
    }
    free(c);
    total *= dx; /* trapezoid: the ends are ~0 */
    for (int j = 0; j < G; j++) {
        g->ks[j] = lo + j * dx;
        g->kf[j] /= total;
    }
    g->kn = G;
    g->kip = gsl_interp_alloc(gsl_interp_steffen, (size_t)G);
    STC_CHECK(g->kip, STC_ENOMEM, "srf_gw: out of memory");
    gsl_interp_init(g->kip, g->ks, g->kf, (size_t)G);
    g->info.bandwidth_mm = b * sig;
    return STC_OK;
}

stc_status srf_gw_create_summits(const asp_model *model, srf_gw_mode mode, const double *z,
                                 const double *R, int n, double area_mm2,
                                 const srf_gw_params *p, srf_gw **out)
{
    STC_CHECK(mode == SRF_GW_KDE || mode == SRF_GW_DETERMINISTIC, STC_EINVAL,
              "mode = %s: measured summits take kde or deterministic",
              srf_gw_mode_name(mode));
    STC_CHECK(z && R, STC_EINVAL, "srf_gw: z and R arrays required");
    STC_CHECK(n >= 0, STC_EINVAL, "summits n = %d: must be >= 0", n);
    STC_CALL(stc_check_range("area", area_mm2, 0.0, 0, INFINITY, 0));
    STC_CALL(gw_alloc(model, mode, p, out));
    srf_gw *g = *out;
    stc_status st = load_summits(g, z, R, n);
    if (st == STC_OK && mode == SRF_GW_KDE) st = build_kde(g);
    if (st != STC_OK) {
        srf_gw_destroy(out);
        return st;
    }
    g->info.area_mm2 = area_mm2;
    g->info.eta_per_mm2 = g->n / area_mm2;
    finish_info(g);
    return STC_OK;
}

stc_status srf_gw_create_from_summits(const asp_model *model, srf_gw_mode mode,
                                      const srf_summits *s, const srf_gw_params *p,
                                      srf_gw **out)
{
    STC_CHECK(s, STC_EINVAL, "srf_gw: summits must not be NULL");
    return srf_gw_create_summits(model, mode, s->z, s->R, s->n, s->area, p, out);
}

stc_status srf_gw_create_like(const srf_gw *src, const asp_model *model, srf_gw **out)
{
    STC_CHECK(src, STC_EINVAL, "srf_gw_create_like: src must not be NULL");
    STC_CALL(gw_alloc(model, src->info.mode, &src->par, out));
    srf_gw *g = *out;
    srf_gw_info i = src->info; /* the population's; E* and H are the model's */
    i.E_star_MPa = g->info.E_star_MPa;
    i.H_MPa = g->info.H_MPa;
    g->info = i;
    stc_status st = STC_OK;
    if (src->n > 0) { /* measured summits, sorted and standardised */
        g->zs = malloc((size_t)src->n * sizeof *g->zs);
        g->R = malloc((size_t)src->n * sizeof *g->R);
        if (!g->zs || !g->R) st = STC_FAIL(STC_ENOMEM, "srf_gw: out of memory");
        else {
            memcpy(g->zs, src->zs, (size_t)src->n * sizeof *g->zs);
            memcpy(g->R, src->R, (size_t)src->n * sizeof *g->R);
            g->n = src->n;
            st = per_summit(g, g->n);
        }
    }
    if (st == STC_OK && src->kn > 0) { /* the KDE density */
        g->ks = malloc((size_t)src->kn * sizeof *g->ks);
        g->kf = malloc((size_t)src->kn * sizeof *g->kf);
        g->kip = gsl_interp_alloc(gsl_interp_steffen, (size_t)src->kn);
        if (!g->ks || !g->kf || !g->kip) st = STC_FAIL(STC_ENOMEM, "srf_gw: out of memory");
        else {
            memcpy(g->ks, src->ks, (size_t)src->kn * sizeof *g->ks);
            memcpy(g->kf, src->kf, (size_t)src->kn * sizeof *g->kf);
            g->kn = src->kn;
            gsl_interp_init(g->kip, g->ks, g->kf, (size_t)g->kn);
        }
    }
    if (st != STC_OK) {
        srf_gw_destroy(out);
        return st;
    }
    finish_info(g);
    return STC_OK;
}

void srf_gw_destroy(srf_gw **pg)
{
    if (!pg || !*pg) return;
    srf_gw *g = *pg;
    srf_quad_free(g->ws);
    if (g->gl) gsl_integration_glfixed_table_free(g->gl);
    if (g->root) gsl_root_fsolver_free(g->root);
    if (g->kip) gsl_interp_free(g->kip);
    free(g->ks);
    free(g->kf);
    free(g->zs);
    free(g->R);
    free(g->inv_wc);
    free(g->Pc);
    free(g->tR_i);
    free(g);
    *pg = NULL;
}

void srf_gw_get_info(const srf_gw *g, srf_gw_info *out) { *out = g->info; }

/* ------------------------------------------------------------ statistical */

/* Summit-height density in s units. */
static double density(const srf_gw *g, double s)
{
    if (g->info.mode == SRF_GW_GAUSSIAN) return INV_SQRT_2PI * exp(-0.5 * s * s);
    if (!(s > g->ks[0] && s < g->ks[g->kn - 1])) return 0.0; /* outside the knots, or NaN */
    double f = gsl_interp_eval(g->kip, g->ks, g->kf, s, NULL);
    return f > 0 ? f : 0.0;
}

typedef struct { const srf_gw *g; double h; int what; } integrand_ctx;

static double integrand(double s, void *u)
{
    const integrand_ctx *c = u;
    const srf_gw *g = c->g;
    asp_response r;
    double delta = g->info.sigma_s_mm * (s - c->h);
    if (!(delta > 0)) return 0.0;
    if (c->what == Q_P) return asp_model_load(g->m, g->info.R_mm, delta) * density(g, s);
    asp_model_eval(g->m, g->info.R_mm, delta, &r);
    return (c->what == Q_A ? r.A : r.Qmax) * density(g, s);
}

/* s of w = δ/ωc for separation h. */
static double s_of_w(const srf_gw *g, double h, double w)
{
    return h + w * asp_model_omega_c(g->m, g->info.R_mm) / g->info.sigma_s_mm;
}

/* A piece whose quadrature stopped short of its tolerance (QUADPACK's
 * roundoff or small-interval stops), judged once the whole integral is
 * known: the worst such piece. */
typedef struct {
    srf_quad_status s;
    double a, b, r, e;
} quad_short;

/* Integrate one piece.  Plain adaptive 21-point Gauss–Kronrod (QAG) on
 * every piece: for the KDE's piecewise-cubic density QAGS's extrapolation
 * misjudged the error. */
static void quad_piece(srf_gw *g, gsl_function *f, double a, double b, double *sum,
                       double *err, quad_short *worst)
{
    double r = 0, e = 0;
    srf_quad_status s = srf_quad_integrate(g->ws, f, a, b, g->par.epsrel, &r, &e);
    if (s != SRF_QUAD_OK && (worst->s == SRF_QUAD_OK || e > worst->e))
        *worst = (quad_short){s, a, b, r, e};
    *sum += r;
    *err += e;
}

/* ∫_a^b over pieces split at the model's breakpoints (b may be +inf).  A
 * piece that stopped short is accepted while its bound (summed into *err)
 * is small against the whole integral, or within `floor`, the absolute
 * error the caller can take (0: none): the pressure solve takes its own
 * relative tolerance of the target load, at which a trial separation high in
 * a KDE's tail (an integral of 1e-10 of the target, stopped at roundoff with
 * a bound of 2e-6 of itself) no longer fails the solve. */
static stc_status quad(srf_gw *g, double h, int what, double a, double b, double *res,
                       double *err, double floor)
{
    integrand_ctx c = {g, h, what};
    gsl_function f = {integrand, &c};
    const double *bw;
    int nb = asp_model_breaks(g->m, &bw);
    double top = g->info.mode == SRF_GW_GAUSSIAN ? INFINITY : g->ks[g->kn - 1];
    if (g->info.mode == SRF_GW_KDE && a < g->ks[0]) a = g->ks[0];
    if (b > top) b = top;
    *res = *err = 0.0;
    if (!(b > a)) return STC_OK;
    double lo = a;
    quad_short worst = {SRF_QUAD_OK, 0, 0, 0, 0};
    for (int i = 0; i < nb; i++) {
        double sb = s_of_w(g, h, bw[i]);
        if (sb <= lo || sb >= b) continue;
        quad_piece(g, &f, lo, sb, res, err, &worst);
        lo = sb;
    }
    quad_piece(g, &f, lo, b, res, err, &worst);
    STC_CHECK(worst.s == SRF_QUAD_OK || worst.e <= QUAD_ACCEPT * fmax(fabs(worst.r), fabs(*res)) ||
                  worst.e <= floor,
              STC_ENOCONV, "GW quadrature on [%g, %g] (units of sigma_s): %s, result %g, "
              "abserr %g", worst.a, worst.b, srf_quad_strerror(worst.s), worst.r, worst.e);
    return STC_OK;
}

static double contacts_stat(const srf_gw *g, double h)
{
    if (g->info.mode == SRF_GW_GAUSSIAN) return 0.5 * erfc(h / M_SQRT2);
    /* KDE: exact integral of the interpolated density */
    double lo = g->ks[0], hi = g->ks[g->kn - 1];
    if (h >= hi) return 0.0;
    return gsl_interp_eval_integ(g->kip, g->ks, g->kf, h > lo ? h : lo, hi, NULL);
}

/* δ/ωc below which `coverage_quantile` of the load is carried: the
 * cumulative load on QUANTILE_PIECES pieces of [h, top] by a fixed
 * Gauss–Legendre rule, interpolated linearly inside the crossing piece.  A
 * coverage indicator, accurate to about half a piece (top − h)/QUANTILE_PIECES. */
static stc_status load_quantile(srf_gw *g, double h, double *w_out)
{
    integrand_ctx c = {g, h, Q_P};
    gsl_function f = {integrand, &c};
    double top = g->info.mode == SRF_GW_GAUSSIAN ? fmax(h, 0.0) + GAUSS_TOP : g->ks[g->kn - 1];
    double lo = g->info.mode == SRF_GW_KDE ? fmax(h, g->ks[0]) : h;
    double cum[QUANTILE_PIECES + 1], ds = (top - lo) / QUANTILE_PIECES;
    cum[0] = 0;
    for (int k = 0; k < QUANTILE_PIECES; k++)
        cum[k + 1] = cum[k] + gsl_integration_glfixed(&f, lo + k * ds, lo + (k + 1) * ds, g->gl);
    double target = g->par.coverage_quantile * cum[QUANTILE_PIECES], s = top;
    for (int k = 0; k < QUANTILE_PIECES; k++)
        if (cum[k + 1] >= target) {
            s = lo + ds * (k + (target - cum[k]) / (cum[k + 1] - cum[k]));
            break;
        }
    *w_out = g->info.sigma_s_mm * (s - h) / asp_model_omega_c(g->m, g->info.R_mm);
    return STC_OK;
}

/* Share of the load from w outside the model's [w_lo, w_hi] (or all of it
 * when the single t/R is outside the model's t/R range). */
static stc_status outside_share(srf_gw *g, double h, double P, double *frac)
{
    double r1 = 0, r2 = 0, e;
    /* beyond rounding: t/R = t/R from t and R may miss an axis end in the last bit */
    if (g->tR < g->range.tR_lo * (1 - 1e-12) || g->tR > g->range.tR_hi * (1 + 1e-12)) {
        *frac = 1.0;
        return STC_OK;
    }
    double fl = g->par.epsrel * P; /* shares of the load P */
    if (g->range.w_lo > 0)
        STC_CALL(quad(g, h, Q_P, h, s_of_w(g, h, g->range.w_lo), &r1, &e, fl));
    if (isfinite(g->range.w_hi))
        STC_CALL(quad(g, h, Q_P, s_of_w(g, h, g->range.w_hi), INFINITY, &r2, &e, fl));
    *frac = P > 0 ? (r1 + r2) / P : 0.0;
    return STC_OK;
}

static stc_status stat_point(srf_gw *g, double h, srf_gw_point *o)
{
    double eta = g->info.eta_per_mm2, P, A, Q = NAN, eP, eA, eQ = NAN;
    STC_CALL(quad(g, h, Q_P, h, INFINITY, &P, &eP, 0.0));
    STC_CALL(quad(g, h, Q_A, h, INFINITY, &A, &eA, 0.0));
    if (g->range.has_friction) STC_CALL(quad(g, h, Q_Q, h, INFINITY, &Q, &eQ, 0.0));
    o->pressure_MPa = eta * P;
    o->area_fraction = eta * A;
    o->Q_MPa = eta * Q;
    o->err_P_MPa = eta * eP;
    o->err_A = eta * eA;
    o->err_Q_MPa = eta * eQ;
    o->contacts_per_mm2 = eta * contacts_stat(g, h);
    o->mu_s = P > 0 ? Q / P : NAN;
    o->tR_min = o->tR_max = g->tR;
    o->n_contacts = 0;
    o->delta_max_over_omega_c = 0.0;
    o->load_fraction_outside = 0.0;
    if (!(P > 0)) return STC_OK;
    STC_CALL(load_quantile(g, h, &o->delta_max_over_omega_c));
    return outside_share(g, h, P, &o->load_fraction_outside);
}

/* ------------------------------------------------------------ deterministic */

/* Number of summits strictly above d (zs descending). */
static int above(const srf_gw *g, double d)
{
    int lo = 0, hi = g->n; /* zs[0..lo) > d, zs[hi..n) <= d */
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (g->zs[mid] > d) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

static void det_point(const srf_gw *g, double h, srf_gw_point *o)
{
    const double d = h * g->info.sigma_s_mm, t = asp_model_t(g->m);
    const int k = above(g, d), fric = g->range.has_friction;
    double P = 0, A = 0, Q = 0, Pout = 0, wmax = 0, tmin = INFINITY, tmax = -INFINITY;
    #pragma omp parallel for reduction(+ : P, A, Q, Pout) reduction(max : wmax, tmax) \
        reduction(min : tmin) if (k > 20000) schedule(static)
    for (int i = 0; i < k; i++) {
        asp_response r;
        asp_model_eval(g->m, g->R[i], g->zs[i] - d, &r);
        P += r.P;
        A += r.A;
        if (fric) Q += r.Qmax;
        if (r.flags & (ASP_OUT_W_LOW | ASP_OUT_W_HIGH | ASP_OUT_T_OVER_R)) Pout += r.P;
        wmax = fmax(wmax, r.w);
        tmin = fmin(tmin, t / g->R[i]);
        tmax = fmax(tmax, t / g->R[i]);
    }
    double An = g->info.area_mm2;
    o->pressure_MPa = P / An;
    o->area_fraction = A / An;
    o->Q_MPa = fric ? Q / An : NAN;
    o->err_P_MPa = o->err_A = 0.0;
    o->err_Q_MPa = fric ? 0.0 : NAN;
    o->contacts_per_mm2 = k / An;
    o->n_contacts = k;
    o->mu_s = P > 0 && fric ? Q / P : NAN;
    o->delta_max_over_omega_c = wmax;
    o->tR_min = k ? tmin : NAN;
    o->tR_max = k ? tmax : NAN;
    o->load_fraction_outside = P > 0 ? Pout / P : 0.0;
}

/* ΣP/An alone: the root function's hot loop. */
static double det_load(const srf_gw *g, double h)
{
    const double d = h * g->info.sigma_s_mm;
    const int k = above(g, d);
    double P = 0;
    #pragma omp parallel for reduction(+ : P) if (k > 20000) schedule(static)
    for (int i = 0; i < k; i++)
        P += g->Pc[i] * asp_model_load_norm(g->m, (g->zs[i] - d) * g->inv_wc[i], g->tR_i[i]);
    return P / g->info.area_mm2;
}

/* ------------------------------------------------------------ load points */

static stc_status point(srf_gw *g, double h, srf_gw_point *o)
{
    memset(o, 0, sizeof *o);
    o->h = h;
    if (g->info.mode == SRF_GW_DETERMINISTIC) {
        det_point(g, h, o);
        return STC_OK;
    }
    return stat_point(g, h, o);
}

/* Nominal pressure only (the root function). */
/* P/An at separation h; floor: the absolute error of P/An (MPa) it may
 * carry where the quadrature stops short (see quad). */
static stc_status pressure(srf_gw *g, double h, double floor, double *p)
{
    if (g->info.mode == SRF_GW_DETERMINISTIC) {
        *p = det_load(g, h);
        return STC_OK;
    }
    double r, e;
    STC_CALL(quad(g, h, Q_P, h, INFINITY, &r, &e, floor / g->info.eta_per_mm2));
    *p = g->info.eta_per_mm2 * r;
    return STC_OK;
}

stc_status srf_gw_at_separation(srf_gw *g, double h, srf_gw_point *out)
{
    STC_CHECK(g && out, STC_EINVAL, "srf_gw_at_separation: NULL argument");
    STC_CHECK(isfinite(h), STC_EINVAL, "separation = %g: must be finite (units of sigma_s)", h);
    return point(g, h, out);
}

typedef struct { srf_gw *g; double target; stc_status st; double last_f; } root_ctx;
#define ROOT_LOGP_TOL 1e-12 /* |log P/target| that ends the solve early */

/* log(P(h)/target): well scaled over decades of load; -inf-safe clamp.
 * Always finite (a non-finite value is what Brent's solver reports through
 * GSL's handler): an infinite load fails the solve instead. */
static double root_fn(double h, void *u)
{
    root_ctx *c = u;
    double p = 0;
    /* the solve's own tolerance: P within epsrel of the target at the root */
    stc_status st = pressure(c->g, h, c->g->par.epsrel * c->target, &p);
    if (st == STC_OK && !(p < INFINITY))
        st = STC_FAIL(STC_ERANGE, "pressure at separation %g sigma_s: not finite", h);
    if (st != STC_OK) c->st = st;
    c->last_f = p > 0 && p < INFINITY ? log(p / c->target) : -745.0;
    return c->last_f;
}

/* Find [lo, hi] with P(lo) >= target > P(hi), stepping with doubling.  The
 * flat never goes below H_FLOOR σs under the lowest summit: every summit is
 * crushed there and GW (no interaction) has long stopped meaning anything. */
#define H_FLOOR 10.0
#define H_CEIL 40.0 /* above: no Gaussian summit in contact (e^-800 underflows) */
static stc_status bracket(srf_gw *g, root_ctx *c, double *lo, double *hi)
{
    double h0 = 0.0, step = 1.0, floor_h = -H_FLOOR;
    if (g->info.mode == SRF_GW_DETERMINISTIC) {
        h0 = g->zs[0] / g->info.sigma_s_mm;
        floor_h = g->zs[g->n - 1] / g->info.sigma_s_mm - H_FLOOR;
    }
    if (isfinite(g->h_hint)) { /* the last solution: load sweeps move in small steps */
        h0 = g->h_hint;
        step = 0.125;
    }
    double f0 = root_fn(h0, c);
    STC_CALL(c->st);
    double a = h0, fa = f0;
    for (int k = 0; k < 80; k++) {
        double b = f0 > 0 ? fmin(a + step, H_CEIL) : fmax(a - step, floor_h);
        if (b == a) break;
        double fb = root_fn(b, c);
        STC_CALL(c->st);
        if ((f0 > 0) != (fb > 0)) {
            *lo = f0 > 0 ? a : b;
            *hi = f0 > 0 ? b : a;
            return STC_OK;
        }
        a = b;
        fa = fb;
        step *= 2;
    }
    if (f0 <= 0)
        return STC_FAIL(STC_ERANGE,
                        "pressure = %g MPa: more than the summits carry (valid: 0 < pressure <= "
                        "%g MPa, the load at separation %g sigma_s, the deepest searched: "
                        "GW's independent asperities have long stopped meaning anything there)",
                        c->target, c->target * exp(fa), a);
    return STC_FAIL(STC_ERANGE,
                    "pressure = %g MPa: less than the summits carry at separation %g sigma_s "
                    "(valid: pressure < %g MPa)", c->target, a, c->target * exp(fa));
}

static stc_status solve(srf_gw *g, double p, double *h, int *iters)
{
    root_ctx c = {g, p, STC_OK, INFINITY};
    double lo = 0, hi = 0;
    STC_CALL(bracket(g, &c, &lo, &hi));
    gsl_function f = {root_fn, &c};
    gsl_root_fsolver *s = g->root;
    gsl_root_fsolver_set(s, &f, lo, hi);
    int status = GSL_CONTINUE, it = 0;
    while (status == GSL_CONTINUE && it < g->par.max_iter && c.st == STC_OK) {
        it++;
        gsl_root_fsolver_iterate(s);
        lo = gsl_root_fsolver_x_lower(s);
        hi = gsl_root_fsolver_x_upper(s);
        status = gsl_root_test_interval(lo, hi, g->par.root_tol, 0.0);
        if (fabs(c.last_f) < ROOT_LOGP_TOL) status = GSL_SUCCESS; /* P within 1e-12 */
    }
    *h = gsl_root_fsolver_root(s);
    *iters = it;
    STC_CALL(c.st);
    STC_CHECK(status == GSL_SUCCESS, STC_ENOCONV,
              "pressure = %g MPa: Brent did not converge in %d iterations (bracket [%g, %g])",
              p, it, lo, hi);
    return STC_OK;
}

stc_status srf_gw_at_pressure(srf_gw *g, double pressure_MPa, srf_gw_point *out)
{
    STC_CHECK(g && out, STC_EINVAL, "srf_gw_at_pressure: NULL argument");
    STC_CALL(stc_check_range("pressure", pressure_MPa, 0.0, 0, INFINITY, 0));
    double h = 0;
    int it = 0;
    stc_status st = solve(g, pressure_MPa, &h, &it);
    if (st == STC_OK) g->h_hint = h;
    if (st == STC_OK) st = point(g, h, out);
    if (st == STC_OK) out->iterations = it;
    return st;
}
