/* Interpolation of a friction table with error bars, and the asperity model
 * the surface prediction sums (include/stiction/table.h).
 *
 * P and A come from the normal grid where it has them (axisymmetric load
 * curves, table_normal.c), else from the 3D points; the load at inception
 * is the preload times the points' ratio of the two.  Both grids are read
 * alike.  P, A and P at inception are nearly free of numerical noise: along
 * δ they follow monotone Steffen (1990) cubics in ln P versus ln w through
 * each (t/R, Eco/Esu) column's done points (exact for power laws such as
 * Hertz), across the t/R columns the same cubic in ln t/R (3 or more
 * columns; else linear), linear in ln Eco/Esu.  Their error bar is the
 * difference between each cubic and the straight line in ln–ln between the
 * same two points, along δ and along t/R in quadrature: zero on a power law,
 * the curvature's share where the response bends.  (Measured on the thesis
 * table at held-out t/R: linear in ln t/R missed P by up to 5.2 %.)
 *
 * μs carries a few per cent of node-placement noise per point, so it is not
 * interpolated but smoothed: a Gaussian process (asperity/table_fit.h) on
 * r = ln μs − ln μs_WSP(w), the Wu–Shi–Polycarpou (2012) curve as the trend,
 * in (ln w, ln t/R − ½ ln w, ln Eco/Esu), each point weighted by its own
 * error estimate.  The second input is the coating thickness over the
 * contact's size, ln(t / √(R δ)) up to a constant: a layered contact
 * responds to t/a, so a feature that moves to larger δ on a thicker coating
 * lies along one input instead of across two (docs/table-format.md has the
 * measurements that chose it).  The query returns the posterior mean and
 * standard deviation. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include "stiction/formulas.h"
#include "stc_check.h"
#include "table_impl.h"

/* ln μs_WSP(w): the trend the surrogate smooths the residual of */
static double trend(double w)
{
    unsigned fl;
    return log(stc_wsp_mu(w, &fl));
}

/* The surrogate's inputs at (w, t/R, Eco/Esu).  With one t/R value the
 * second input is that constant (the fit then ignores it) rather than a
 * copy of the first. */
static void gp_inputs(const tbl_table *t, double w, double tR, double E, double *x)
{
    x[0] = log(w);
    x[1] = t->n[1] > 1 ? log(tR) - 0.5 * log(w) : log(tR);
    x[2] = log(E);
}

/* The surrogate's model: part of the hash its stored hyperparameters are
 * kept under, so that a change of model (inputs, trend, kernel) here makes
 * stored ones stale.  Raise it with any such change. */
#define FIT_MODEL 3

/* FNV-1a (Fowler, Noll & Vo) over n bytes, continuing from h. */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * UINT64_C(1099511628211);
    return h;
}

/* Hash of what the fit sees: the model, the kernel options and the n
 * points' inputs, values and errors, bit for bit. */
static uint64_t fit_hash(int n, const double *x, const double *y, const double *sy,
                         const tbl_gp_kernel *k)
{
    int head[5] = {FIT_MODEL, n, k->mod_dim, k->scale_dim, (int)k->base_dims};
    uint64_t h = fnv1a(UINT64_C(14695981039346656037), head, sizeof head);
    h = fnv1a(h, x, (size_t)n * 3 * sizeof *x);
    h = fnv1a(h, y, (size_t)n * sizeof *y);
    return fnv1a(h, sy, (size_t)n * sizeof *sy);
}

stc_status tbl_fit(tbl_table *t)
{
    STC_CHECK(t, STC_EINVAL, "tbl_fit: table required");
    tbl_gp_destroy(&t->gp);
    int np = tbl_points(t), n = 0;
    double *x = malloc((size_t)np * 3 * sizeof *x);
    double *y = malloc((size_t)np * sizeof *y), *sy = malloc((size_t)np * sizeof *sy);
    double *lm = malloc((size_t)np * sizeof *lm), *ls = malloc((size_t)np * sizeof *ls);
    stc_status st = STC_OK;
    STC_CHECK_GOTO(x && y && sy && lm && ls, st, done, STC_ENOMEM, "tbl_fit: out of memory");
    for (int i = 0; i < np; i++) {
        const tbl_point *p = &t->pt[i];
        if (p->state != TBL_DONE || p->copied) continue; /* each answer once */
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        gp_inputs(t, w, tR, E, x + 3 * n);
        y[n] = log(p->mu_s) - trend(w);
        sy[n] = p->mu_s_err / p->mu_s; /* relative error = error of ln μs */
        n++;
    }
    STC_CHECK_GOTO(n >= 3, st, done, STC_ERANGE, "table fit: %d done points: need at least 3",
                   n);
    /* The uncoated sphere (ln Eco/Esu = 0) is one curve in δ whatever t/R: a
     * base term in ln δ, plus the coating's effect in proportion to
     * ln Eco/Esu; its length scales modulated along t/a, the coating's
     * response turning more sharply where it is thin against the contact
     * (docs/table-format.md). */
    tbl_gp_kernel k = {.mod_dim = t->n[1] > 1 ? 1 : -1, .scale_dim = t->n[2] > 1 ? 2 : -1,
                       .base_dims = 1u << 0};
    uint64_t hash = fit_hash(n, x, y, sy, &k);
    int reused = 0;
    if (t->fit_npar >= 0 && t->fit_hash == hash) /* the data of the stored fit */
        reused = tbl_gp_fit_at(n, 3, x, y, sy, &k, t->fit_npar, t->fit_par, &t->gp) == STC_OK;
    if (!reused) STC_CALL_GOTO(tbl_gp_fit_kernel(n, 3, x, y, sy, &k, &t->gp), st, done);
    tbl_gp_info gi;
    tbl_gp_get_info(t->gp, &gi);
    t->fit_hash = hash;
    t->fit_npar = gi.npar;
    memcpy(t->fit_par, gi.par, sizeof t->fit_par);
    tbl_gp_loo(t->gp, lm, ls);
    double ss = 0.0, mx = 0.0;
    int in2 = 0;
    for (int i = 0; i < n; i++) {
        double rel = expm1(y[i] - lm[i]); /* μs / μs_LOO − 1 */
        ss += rel * rel;
        mx = fmax(mx, fabs(rel));
        in2 += fabs(y[i] - lm[i]) <= 2.0 * ls[i];
    }
    t->fit = (tbl_fit_info){n, {gi.ell[0], gi.ell[1], gi.ell[2]}, gi.gamma, gi.base_ell[0],
                            gi.noise_scale, sqrt(ss / n), mx, (double)in2 / n, reused};
done:
    free(x), free(y), free(sy), free(lm), free(ls);
    return st;
}

stc_status tbl_get_fit_info(const tbl_table *t, tbl_fit_info *out)
{
    STC_CHECK(t && t->gp, STC_EINVAL, "table fit: not fitted (no done points, or tbl_fit not "
              "called)");
    *out = t->fit;
    return STC_OK;
}

/* ---- P, A, P at inception along one column ---------------------------------- */

enum { F_P = 0, F_A = 1, F_PS = 2 };

/* A grid to interpolate on: the 3D points, or the normal grid's curves. */
typedef struct grid {
    const int *n;            /* [3] axis lengths: w, t/R, Eco/Esu */
    double *const *ax;       /* [3] */
    const tbl_table *t;
    int normal;              /* 0: t->pt, 1: t->nrm */
} grid;

static grid points_grid(const tbl_table *t) { return (grid){t->n, t->ax, t, 0}; }
static grid normal_grid(const tbl_table *t) { return (grid){t->nrm.n, t->nrm.ax, t, 1}; }

/* Field f at flat index i of g; NaN unless done. */
static double value_at(const grid *g, int f, int i)
{
    if (g->normal) {
        const double *v = f == F_A ? g->t->nrm.A : g->t->nrm.P; /* NaN unless done */
        return v[i];
    }
    const tbl_point *p = &g->t->pt[i];
    if (p->state != TBL_DONE) return NAN;
    return f == F_P ? p->P_Pc : f == F_A ? p->A_Ac : p->P_slide_Pc;
}

/* ln of field f at ln w = lw in column (iE, it): the monotone cubic (*cub)
 * and the straight ln–ln line between the bracketing points (*lin).  Beyond
 * the column's done points both continue the end interval's power law.
 * Returns 0, or -1 when fewer than 2 points of the column are done; *gap
 * set when a grid point of the column inside the bracket is not done. */
static int column_eval(const grid *g, int iE, int it, int f, double lw, double *cub,
                       double *lin, int *gap)
{
    int nw = g->n[0], n = 0, base = (iE * g->n[1] + it) * nw;
    const double *ax = g->ax[0];
    double xs[64], ys[64];
    double *xa = nw <= 64 ? xs : malloc((size_t)nw * sizeof *xa);
    double *ya = nw <= 64 ? ys : malloc((size_t)nw * sizeof *ya);
    if (!xa || !ya) {
        if (xa != xs) free(xa);
        if (ya != ys) free(ya);
        return -1;
    }
    for (int i = 0; i < nw; i++) {
        double v = value_at(g, f, base + i);
        if (!isfinite(v)) {
            if ((i == 0 || log(ax[i - 1]) < lw) && (i == nw - 1 || lw < log(ax[i + 1])))
                *gap = 1;
            continue;
        }
        xa[n] = log(ax[i]);
        ya[n] = log(v);
        n++;
    }
    int rc = 0;
    if (n < 2) {
        rc = -1;
    } else {
        int k = 0;
        while (k < n - 2 && lw >= xa[k + 1]) k++;
        double s = (ya[k + 1] - ya[k]) / (xa[k + 1] - xa[k]);
        *lin = ya[k] + s * (lw - xa[k]);
        *cub = *lin;
        if (n >= 3 && lw > xa[0] && lw < xa[n - 1]) {
            gsl_interp *ip = gsl_interp_alloc(gsl_interp_steffen, (size_t)n);
            if (ip && gsl_interp_init(ip, xa, ya, (size_t)n) == GSL_SUCCESS)
                *cub = gsl_interp_eval(ip, xa, ya, lw, NULL);
            gsl_interp_free(ip);
        }
    }
    if (xa != xs) free(xa);
    if (ya != ys) free(ya);
    return rc;
}

/* ln of field f at ln w = lw along the t/R axis at Eco/Esu column iE: the
 * monotone Steffen cubic in ln t/R through the columns' values when the axis
 * has 3 or more columns that answer (*cub; a column without 2 done points is
 * left out), and the straight line between the two bracketing columns
 * (*lin); *err the δ-direction error (cubic − line along δ, interpolated
 * linearly).  Returns -1 when a bracketing column has fewer than 2 done
 * points. */
static int tr_eval(const grid *g, int iE, int f, double lw, double tR, double *cub,
                   double *lin, double *err, int *gap)
{
    int nt = g->n[1];
    double ft;
    int it = tbl_bracket(g->ax[1], nt, tR, &ft);
    double xs[64], ys[64], lt = log(tR), cb[2] = {0, 0}, eb[2] = {0, 0};
    int n = 0;
    for (int j = 0; j < nt; j++) {
        double c, l;
        int gj = 0, side = j == it ? 0 : j == it + 1 ? 1 : -1;
        int needed = (side == 0 && ft < 1.0) || (side == 1 && ft > 0.0);
        if (column_eval(g, iE, j, f, lw, &c, &l, &gj) != 0) {
            if (needed) return -1;
            continue; /* a column without points: the cubic runs over the others */
        }
        if (needed) *gap |= gj;
        if (side >= 0) cb[side] = c, eb[side] = fabs(c - l);
        if (n < 64) xs[n] = log(g->ax[1][j]), ys[n] = c, n++;
    }
    *lin = (1 - ft) * cb[0] + ft * cb[1];
    *err = (1 - ft) * eb[0] + ft * eb[1];
    *cub = *lin;
    if (n >= 3 && ft > 0.0 && ft < 1.0 && lt > xs[0] && lt < xs[n - 1]) {
        gsl_interp *ip = gsl_interp_alloc(gsl_interp_steffen, (size_t)n);
        if (ip && gsl_interp_init(ip, xs, ys, (size_t)n) == GSL_SUCCESS)
            *cub = gsl_interp_eval(ip, xs, ys, lt, NULL);
        gsl_interp_free(ip);
    }
    return 0;
}

/* Field f at (ln w, t/R, Eco/Esu): along δ the monotone cubic of each column,
 * along t/R the monotone cubic across the columns (tr_eval), linear in ln
 * Eco/Esu.  The error bar: the δ cubic against the δ line and the t/R cubic
 * against the t/R line, in quadrature.  Returns -1 when a column it needs
 * has < 2 points.  t/R and Eco/Esu within the grid's axes. */
static int field_eval(const grid *g, int f, double lw, double tR, double E, double *val,
                      double *err, int *gap)
{
    double fe;
    int iE = tbl_bracket(g->ax[2], g->n[2], E, &fe);
    double c = 0.0, l = 0.0, ew = 0.0;
    for (int b = 0; b < 2; b++) {
        double wgt = b ? fe : 1.0 - fe;
        if (wgt == 0.0) continue;
        double cc, ll, ee;
        if (tr_eval(g, iE + b, f, lw, tR, &cc, &ll, &ee, gap) != 0) return -1;
        c += wgt * cc, l += wgt * ll, ew += wgt * ee;
    }
    *val = exp(c);
    /* the δ error (|cubic − line| in ln) and the t/R one (same), as relative errors */
    *err = *val * hypot(ew, fabs(c - l));
    return 0;
}

static int near(double a, double b) { return fabs(a - b) <= 1e-6 * fabs(b); }

int tbl_is_homogeneous(const tbl_table *t)
{
    const tbl_family *f = &t->fam;
    return t->n[2] == 1 && t->ax[2][0] == 1.0 && t->n[1] == 1 &&
           near(f->E_over_Y_co, f->E_over_Y_su) && near(f->nu_co, f->nu_su);
}

static unsigned range_flags(const tbl_table *t, double w, double tR, double E)
{
    const double eps = 1e-9;
    unsigned fl = 0;
    if (w < t->ax[0][0] * (1 - eps)) fl |= TBL_OUT_W_LOW;
    if (w > t->ax[0][t->n[0] - 1] * (1 + eps)) fl |= TBL_OUT_W_HIGH;
    if ((tR < t->ax[1][0] * (1 - eps) || tR > t->ax[1][t->n[1] - 1] * (1 + eps)) &&
        !tbl_is_homogeneous(t))
        fl |= TBL_OUT_T_OVER_R;
    if (E < t->ax[2][0] * (1 - eps) || E > t->ax[2][t->n[2] - 1] * (1 + eps))
        fl |= TBL_OUT_E_RATIO;
    return fl;
}

static double clamp_axis(const tbl_table *t, int k, double v)
{
    return fmin(fmax(v, t->ax[k][0]), t->ax[k][t->n[k] - 1]);
}

/* The done points around (w, tR, E), on the axes, weighted as multilinear
 * interpolation in the logarithms weighs them: their mu_s_ux_slope (NaN if
 * one does not say). */
static double slope_around(const tbl_table *t, double w, double tR, double E)
{
    double x[3] = {w, tR, E}, f[3];
    int i0[3];
    for (int k = 0; k < 3; k++) i0[k] = tbl_bracket(t->ax[k], t->n[k], x[k], &f[k]);
    double s = 0.0, sw = 0.0;
    for (int c = 0; c < 8; c++) {
        double wgt = 1.0;
        int idx[3];
        for (int k = 0; k < 3; k++) {
            int b = (c >> k) & 1;
            wgt *= b ? f[k] : 1.0 - f[k];
            idx[k] = i0[k] + b;
        }
        if (wgt == 0.0) continue;
        const tbl_point *p = &t->pt[(idx[2] * t->n[1] + idx[1]) * t->n[0] + idx[0]];
        if (p->state != TBL_DONE) continue;
        s += wgt * p->mu_s_ux_slope, sw += wgt;
    }
    return sw > 0.0 ? s / sw : NAN;
}

stc_status tbl_query(const tbl_table *t, double w, double t_over_R, double E_ratio,
                     tbl_value *out)
{
    STC_CHECK(t && out, STC_EINVAL, "tbl_query: table and out required");
    STC_CHECK(isfinite(w) && w > 0, STC_EINVAL, "delta/omega_c = %g: must be > 0", w);
    STC_CHECK(isfinite(t_over_R) && t_over_R > 0, STC_EINVAL, "t/R = %g: must be > 0",
              t_over_R);
    STC_CHECK(isfinite(E_ratio) && E_ratio > 0, STC_EINVAL, "E-ratio = %g: must be > 0",
              E_ratio);
    STC_CHECK(t->gp, STC_ERANGE, "table query: the table has no fitted points (fewer than 3 "
              "done)");
    memset(out, 0, sizeof *out);
    out->flags = range_flags(t, w, t_over_R, E_ratio);
    double tR = clamp_axis(t, 1, t_over_R), E = clamp_axis(t, 2, E_ratio), lw = log(w);
    int gap = 0, bad = 0;
    double P3, eP3, PS3, e_ps;
    grid pg = points_grid(t);
    bad |= field_eval(&pg, F_P, lw, tR, E, &P3, &eP3, &gap);
    bad |= field_eval(&pg, F_PS, lw, tR, E, &PS3, &e_ps, &gap);
    STC_CHECK(!bad, STC_ERANGE, "table query at t/R = %g, E-ratio = %g: a neighbouring "
              "(t/R, E-ratio) column has fewer than 2 done points", t_over_R, E_ratio);
    /* P and A from the normal grid where the curves around the query are done
     * (no gap), else from the points; the load at inception keeps the
     * points' ratio to the preload */
    int ngap = 0;
    grid ng = normal_grid(t);
    if (tbl_curves(t) > 0 &&
        field_eval(&ng, F_P, lw, tR, E, &out->P_Pc, &out->P_Pc_err, &ngap) == 0 &&
        field_eval(&ng, F_A, lw, tR, E, &out->A_Ac, &out->A_Ac_err, &ngap) == 0 && !ngap) {
        out->from_normal = 1;
        out->P_slide_Pc = out->P_Pc * (PS3 / P3);
    } else {
        out->P_Pc = P3, out->P_Pc_err = eP3;
        bad |= field_eval(&pg, F_A, lw, tR, E, &out->A_Ac, &out->A_Ac_err, &gap);
        out->P_slide_Pc = PS3;
    }
    STC_CHECK(!bad, STC_ERANGE, "table query at t/R = %g, E-ratio = %g: a neighbouring "
              "(t/R, E-ratio) column has fewer than 2 done points", t_over_R, E_ratio);
    if (gap) out->flags |= TBL_GAP;
    double xq[3], m, sd;
    gp_inputs(t, clamp_axis(t, 0, w), tR, E, xq);
    tbl_gp_predict(t->gp, xq, &m, &sd);
    out->mu_s = exp(trend(w) + m);
    out->mu_s_err = out->mu_s * sd;
    out->Q_max_Pc = out->mu_s * out->P_slide_Pc;
    out->Q_max_Pc_err = out->mu_s_err * out->P_slide_Pc;
    out->mu_s_ux_slope = slope_around(t, clamp_axis(t, 0, w), tR, E);
    return STC_OK;
}

/* Node range [*lo, *hi] of axis k that interpolation over [a, b] reads. */
static void axis_nodes(const tbl_table *t, int k, double a, double b, int *lo, int *hi)
{
    double fa, fb;
    int ia = tbl_bracket(t->ax[k], t->n[k], clamp_axis(t, k, a), &fa);
    int ib = tbl_bracket(t->ax[k], t->n[k], clamp_axis(t, k, b), &fb);
    *lo = fa >= 1.0 ? ia + 1 : ia;
    *hi = fb > 0.0 ? ib + 1 : ib;
    if (*hi > t->n[k] - 1) *hi = t->n[k] - 1;
}

int tbl_mark_needed(const tbl_table *t, double w_lo, double w_hi, double tR_lo, double tR_hi,
                    double E_ratio, unsigned char *need)
{
    if (!t || !need || !(w_lo > 0) || !(w_hi >= w_lo) || !(tR_lo > 0) || !(tR_hi >= tR_lo) ||
        !(E_ratio > 0) || !isfinite(w_hi) || !isfinite(tR_hi) || !isfinite(E_ratio))
        return -1;
    int lo[3], hi[3], pending = 0;
    axis_nodes(t, 0, w_lo, w_hi, &lo[0], &hi[0]);
    axis_nodes(t, 1, tR_lo, tR_hi, &lo[1], &hi[1]);
    axis_nodes(t, 2, E_ratio, E_ratio, &lo[2], &hi[2]);
    if (lo[0] > 0) lo[0]--;
    if (hi[0] < t->n[0] - 1) hi[0]++;
    for (int e = lo[2]; e <= hi[2]; e++)
        for (int r = lo[1]; r <= hi[1]; r++)
            for (int w = lo[0]; w <= hi[0]; w++) {
                int i = (e * t->n[1] + r) * t->n[0] + w, j = tbl_point_source(t, i);
                /* a point another run gives needs that run: counted once */
                pending += !need[j] && t->pt[j].state == TBL_PENDING;
                need[i] = need[j] = 1;
            }
    return pending;
}

/* ---- the asperity model ---------------------------------------------------------- */

static stc_status check_family(const tbl_table *t, const stc_params *p)
{
    tbl_family pf;
    tbl_family_of_params(p, &t->fam, &pf);
    const tbl_family *f = &t->fam;
    if (near(pf.E_over_Y_su, f->E_over_Y_su) && near(pf.E_over_Y_co, f->E_over_Y_co) &&
        near(pf.nu_su, f->nu_su) && near(pf.nu_co, f->nu_co))
        return STC_OK;
    char a[256], b[256];
    tbl_family_describe(&pf, a, sizeof a);
    tbl_family_describe(f, b, sizeof b);
    return STC_FAIL(STC_EINVAL, "the materials are of another family than the table's: "
                    "materials: %s; table: %s", a, b);
}

stc_status tbl_check_params(const tbl_table *t, const stc_params *p)
{
    STC_CHECK(t && p, STC_EINVAL, "tbl_check_params: table and parameters required");
    STC_CALL(check_family(t, p));
    STC_CHECK(!(range_flags(t, t->ax[0][0], t->ax[1][0], p->E_ratio) & TBL_OUT_E_RATIO),
              STC_ERANGE, "E-ratio = %g: outside the table's [%g, %g]", p->E_ratio, t->ax[2][0],
              t->ax[2][t->n[2] - 1]);
    return STC_OK;
}

/* The part of the table a model at Eco/Esu = E can use: the longest run of
 * t/R columns [*t0, *t1] whose (one or two) Eco/Esu neighbours each have at
 * least 2 done points, and the δ nodes [*w0, *w1] done in all of them (the
 * first to the last done node).  Returns 0, or -1 when there is none. */
static int usable_block(const tbl_table *t, double E, int *t0, int *t1, int *w0, int *w1)
{
    double fe;
    int iE = tbl_bracket(t->ax[2], t->n[2], E, &fe), nw = t->n[0], best = 0;
    int e0 = fe >= 1.0 ? iE + 1 : iE, e1 = fe > 0.0 && fe < 1.0 ? iE + 1 : e0;
    int run = 0, lo = 0, hi = nw - 1, blo = 0, bhi = 0;
    for (int it = 0; it < t->n[1]; it++) {
        int first = nw, last = -1, ok = 1;
        for (int e = e0; e <= e1; e++) {
            int f = -1, l = -1, n = 0;
            for (int i = 0; i < nw; i++)
                if (t->pt[(e * t->n[1] + it) * nw + i].state == TBL_DONE) {
                    if (f < 0) f = i;
                    l = i, n++;
                }
            if (n < 2) ok = 0;
            if (f < first || e == e0) first = e == e0 ? f : (f > first ? f : first);
            if (l < last || e == e0) last = e == e0 ? l : (l < last ? l : last);
        }
        if (!ok || last - first < 1) {
            run = 0;
            continue;
        }
        if (run == 0) lo = first, hi = last;
        else lo = first > lo ? first : lo, hi = last < hi ? last : hi;
        if (hi - lo < 1) { /* the run's common δ range closed: start again here */
            run = 0, lo = first, hi = last;
        }
        run++;
        if (run > best) best = run, *t0 = it - run + 1, *t1 = it, blo = lo, bhi = hi;
    }
    *w0 = blo, *w1 = bhi;
    return best > 0 ? 0 : -1;
}

/* Samples per table interval of the dense resampling (the data model
 * interpolates between them: Steffen in ln w, linear in t/R). */
enum { DENSE_W = 8, DENSE_TR = 4 };

/* TBL_MODEL_SLOPE's least slope: the data model interpolates ln Q, and a
 * slope near 0 next to one of 0.1 would make its power law in δ steep (and
 * the extrapolation below the table's first δ run away); 0.01, a per cent
 * of μs per doubling of ux at most, reads as none. */
#define SLOPE_FLOOR 0.01

stc_status tbl_model_create(const tbl_table *t, const stc_params *p, double t_mm,
                            tbl_model_kind kind, asp_model **out)
{
    STC_CHECK(out, STC_EINVAL, "tbl_model_create: out must not be NULL");
    *out = NULL;
    STC_CHECK(t && p, STC_EINVAL, "tbl_model_create: table and parameters required");
    STC_CHECK(kind >= TBL_MODEL_PRELOAD && kind <= TBL_MODEL_SLOPE, STC_EINVAL,
              "tbl_model_create: kind = %d: must be preload, slide, err or slope", (int)kind);
    STC_CHECK(t->gp, STC_ERANGE, "the table has fewer than 3 done points: no model");
    STC_CALL(tbl_check_params(t, p));
    STC_CHECK(t->n[0] >= 2, STC_ERANGE, "the table has one delta value: no model along delta");
    int t0, t1, w0, w1;
    STC_CHECK(usable_block(t, p->E_ratio, &t0, &t1, &w0, &w1) == 0, STC_ERANGE,
              "E-ratio = %g: no t/R column of the table has 2 done points there: no model",
              p->E_ratio);
    int nw = (w1 - w0) * DENSE_W + 1, nt = (t1 - t0) * DENSE_TR + 1;
    double *w = malloc((size_t)nw * sizeof *w), *tR = malloc((size_t)nt * sizeof *tR);
    double *P = malloc((size_t)nw * nt * sizeof *P), *A = malloc((size_t)nw * nt * sizeof *A);
    double *Q = malloc((size_t)nw * nt * sizeof *Q);
    stc_status st = STC_OK;
    STC_CHECK_GOTO(w && tR && P && A && Q, st, done, STC_ENOMEM, "tbl_model_create: out of "
                   "memory");
    for (int i = 0; i < nw; i++) {
        int k = w0 + i / DENSE_W;
        double f = (double)(i % DENSE_W) / DENSE_W;
        w[i] = k >= w1 || f == 0.0 ? t->ax[0][k >= w1 ? w1 : k] /* nodes exactly */
                                   : exp((1 - f) * log(t->ax[0][k]) + f * log(t->ax[0][k + 1]));
    }
    for (int j = 0; j < nt; j++) {
        int k = t0 + j / DENSE_TR;
        double f = (double)(j % DENSE_TR) / DENSE_TR;
        tR[j] = k >= t1 || f == 0.0
                    ? t->ax[1][k >= t1 ? t1 : k]
                    : exp((1 - f) * log(t->ax[1][k]) + f * log(t->ax[1][k + 1]));
    }
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < nw; i++) {
            tbl_value v;
            STC_CALL_GOTO(tbl_query(t, w[i], tR[j], p->E_ratio, &v), st, done);
            size_t k = (size_t)j * nw + i;
            P[k] = kind == TBL_MODEL_SLIDE ? v.P_slide_Pc : v.P_Pc;
            A[k] = v.A_Ac;
            Q[k] = kind == TBL_MODEL_ERR ? v.Q_max_Pc_err : v.Q_max_Pc;
            if (kind == TBL_MODEL_SLOPE) {
                STC_CHECK_GOTO(isfinite(v.mu_s_ux_slope), st, done, STC_ERANGE, "the table "
                               "keeps no d ln mu_s / d ln ux at delta/omega_c = %g, t/R = %g "
                               "(a point written before format 7, or refined from one)", w[i],
                               tR[j]);
                Q[k] *= fmax(v.mu_s_ux_slope, SLOPE_FLOOR);
            }
        }
    stc_material su;
    stc_params_materials(p, &su, NULL);
    static const char *const kname[4] = {"table", "table (P at inception)", "table (error)",
                                         "table (d ln mu_s / d ln ux)"};
    asp_model_data d = {kname[kind], su, t_mm, nw, nt, w, tR, P, A, Q, !tbl_is_homogeneous(t)};
    st = asp_model_create_data(&d, out);
done:
    free(w), free(tR), free(P), free(A), free(Q);
    return st;
}
