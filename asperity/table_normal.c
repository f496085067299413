/* The normal grid of a friction table (include/stiction/table.h,
 * tbl_numerics.normal_level): the preload's P and A from axisymmetric load
 * curves, one per (t/R, Eco/Esu) node of a grid denser than the points'.
 *
 * Why: the normal step is axisymmetric, so its response needs no 3D mesh.
 * A curve on the axisymmetric mesh (level 1: within 0.3 % of the converged
 * load, docs/design.md §2.3) costs 3-5 CPU s for every δ of a column, a
 * 3D point 20-250 CPU s for one.  The 3D points' own P and A carry the
 * coarse 3D mesh's noise (on the thesis table P within ±2 % and the
 * preload area -5 ... +16 % of the axisymmetric curves: the 3D radius is
 * read on one line of nodes, one phase of the node-entry sawtooth), and
 * three t/R nodes a factor 5 apart left P 3 % off between them.  μs and the
 * load at inception relative to the preload stay with the 3D points. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stiction/formulas.h"
#include "stc_check.h"
#include "table_impl.h"
#include "threads.h"

/* Samples per factor 2 of each axis: a Steffen cubic through P(δ) in ln–ln
 * at 4 per octave, or through P(t/R) at fixed δ, is well below the curves'
 * own mesh error; P is nearly linear in ln Eco/Esu (held-out points between
 * the thesis's Eco/Esu nodes a factor 2 apart: within 0.5 %). */
static const double PER_OCTAVE[3] = {4.0, 4.0, 2.0};

/* The nodes ax[0..n-1] with each interval divided evenly in ln into
 * ceil(per_octave log2(ratio)) parts; new in *out, its length returned
 * (-1: out of memory).  The nodes stay exactly as they are. */
static int dense_axis(const double *ax, int n, double per_octave, double **out)
{
    int m = 1;
    for (int i = 0; i + 1 < n; i++) {
        int k = (int)ceil(per_octave * log2(ax[i + 1] / ax[i]) - 1e-9);
        m += k < 1 ? 1 : k;
    }
    double *v = malloc((size_t)m * sizeof *v);
    if (!v) return -1;
    int j = 0;
    for (int i = 0; i + 1 < n; i++) {
        int k = (int)ceil(per_octave * log2(ax[i + 1] / ax[i]) - 1e-9);
        if (k < 1) k = 1;
        v[j++] = ax[i];
        for (int s = 1; s < k; s++) {
            double f = (double)s / k;
            v[j++] = exp((1 - f) * log(ax[i]) + f * log(ax[i + 1]));
        }
    }
    v[j++] = ax[n - 1];
    *out = v;
    return m;
}

void tbl_normal_free(tbl_normal *g)
{
    for (int k = 0; k < 3; k++) free(g->ax[k]);
    free(g->c);
    free(g->P);
    free(g->A);
    memset(g, 0, sizeof *g);
    g->level = -1;
}

/* Allocate the curves and values of g on its axes: every curve pending. */
static stc_status alloc_values(tbl_normal *g)
{
    size_t nc = (size_t)g->n[1] * g->n[2], nv = nc * g->n[0];
    g->c = calloc(nc, sizeof *g->c);
    g->P = malloc(nv * sizeof *g->P);
    g->A = malloc(nv * sizeof *g->A);
    if (!g->c || !g->P || !g->A) {
        tbl_normal_free(g);
        return STC_FAIL(STC_ENOMEM, "normal grid: out of memory");
    }
    for (size_t i = 0; i < nv; i++) g->P[i] = g->A[i] = NAN;
    return STC_OK;
}

stc_status tbl_normal_init(tbl_table *t)
{
    tbl_normal *g = &t->nrm;
    tbl_normal_free(g);
    if (t->num.normal_level < 0) return STC_OK;
    for (int k = 0; k < 3; k++) {
        g->n[k] = dense_axis(t->ax[k], t->n[k], PER_OCTAVE[k], &g->ax[k]);
        if (g->n[k] < 0) {
            tbl_normal_free(g);
            return STC_FAIL(STC_ENOMEM, "normal grid: out of memory");
        }
    }
    g->level = t->num.normal_level;
    return alloc_values(g);
}

stc_status tbl_normal_init_axes(tbl_table *t, double *const ax[3], const int n[3])
{
    tbl_normal *g = &t->nrm;
    tbl_normal_free(g);
    STC_CHECK(t->num.normal_level >= 0, STC_EINVAL, "normal grid: the table's numerics have "
              "none (normal level -1)");
    for (int k = 0; k < 3; k++) {
        STC_CHECK(n[k] >= 1 && n[k] <= 10000, STC_EINVAL, "normal grid: axis %d has %d values: "
                  "must be 1 to 10000", k, n[k]);
        for (int i = 0; i < n[k]; i++)
            STC_CHECK(isfinite(ax[k][i]) && ax[k][i] > 0 && (i == 0 || ax[k][i] > ax[k][i - 1]),
                      STC_EINVAL, "normal grid: axis %d value %d = %g: must be > 0 and "
                      "increasing", k, i, ax[k][i]);
        g->ax[k] = malloc((size_t)n[k] * sizeof(double));
        if (!g->ax[k]) {
            tbl_normal_free(g);
            return STC_FAIL(STC_ENOMEM, "normal grid: out of memory");
        }
        memcpy(g->ax[k], ax[k], (size_t)n[k] * sizeof(double));
        g->n[k] = n[k];
    }
    g->level = t->num.normal_level;
    return alloc_values(g);
}

int tbl_same_normal(const tbl_table *a, const tbl_table *b)
{
    const tbl_normal *x = &a->nrm, *y = &b->nrm;
    if (x->level != y->level) return 0;
    if (x->level < 0) return 1;
    for (int k = 0; k < 3; k++) {
        if (x->n[k] != y->n[k]) return 0;
        if (memcmp(x->ax[k], y->ax[k], (size_t)x->n[k] * sizeof(double)) != 0) return 0;
    }
    return 1;
}

int tbl_curves(const tbl_table *t)
{
    return t->nrm.level < 0 ? 0 : t->nrm.n[1] * t->nrm.n[2];
}

int tbl_normal_axis(const tbl_table *t, int axis, const double **values)
{
    if (axis < 0 || axis > 2 || t->nrm.level < 0) return 0;
    if (values) *values = t->nrm.ax[axis];
    return t->nrm.n[axis];
}

const tbl_curve *tbl_curve_get(const tbl_table *t, int c)
{
    return c >= 0 && c < tbl_curves(t) ? &t->nrm.c[c] : NULL;
}

void tbl_curve_values(const tbl_table *t, int c, int k, double *P_Pc, double *A_Ac)
{
    const tbl_normal *g = &t->nrm;
    int ok = c >= 0 && c < tbl_curves(t) && k >= 0 && k < g->n[0];
    size_t i = ok ? (size_t)c * g->n[0] + k : 0;
    if (P_Pc) *P_Pc = ok ? g->P[i] : NAN;
    if (A_Ac) *A_Ac = ok ? g->A[i] : NAN;
}

stc_status tbl_curve_set(tbl_table *t, int c, const tbl_curve *cv, const double *P_Pc,
                         const double *A_Ac)
{
    tbl_normal *g = &t->nrm;
    STC_CHECK(c >= 0 && c < tbl_curves(t), STC_EINVAL, "curve %d: must be in [0, %d)", c,
              tbl_curves(t));
    STC_CHECK(cv->state == TBL_PENDING || cv->state == TBL_DONE || cv->state == TBL_FAILED,
              STC_EINVAL, "curve %d: state %d is not pending, done or failed", c, cv->state);
    int nw = g->n[0];
    for (int k = 0; cv->state == TBL_DONE && k < nw; k++)
        STC_CHECK(isfinite(P_Pc[k]) && P_Pc[k] > 0 && isfinite(A_Ac[k]) && A_Ac[k] > 0,
                  STC_EINVAL, "curve %d is done but its P or A at delta node %d is not a "
                  "positive number", c, k);
    g->c[c] = *cv;
    g->c[c].reason[TBL_REASON_MAX - 1] = '\0';
    for (int k = 0; k < nw; k++) {
        int keep = cv->state == TBL_DONE;
        g->P[(size_t)c * nw + k] = keep ? P_Pc[k] : NAN;
        g->A[(size_t)c * nw + k] = keep ? A_Ac[k] : NAN;
    }
    return STC_OK;
}

void tbl_curve_count(const tbl_table *t, int *done, int *failed, int *pending)
{
    int n[3] = {0, 0, 0};
    for (int c = 0; c < tbl_curves(t); c++) n[t->nrm.c[c].state]++;
    if (done) *done = n[TBL_DONE];
    if (failed) *failed = n[TBL_FAILED];
    if (pending) *pending = n[TBL_PENDING];
}

void tbl_normal_needed(const tbl_table *t, const unsigned char *only, unsigned char *need)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {0, 0, 0};
    for (int i = 0; i < tbl_points(t); i++) {
        if (!only[i]) continue;
        double x[3];
        tbl_coords(t, i, &x[0], &x[1], &x[2]);
        for (int k = 1; k < 3; k++) lo[k] = fmin(lo[k], x[k]), hi[k] = fmax(hi[k], x[k]);
    }
    const tbl_normal *g = &t->nrm;
    for (int c = 0; c < tbl_curves(t); c++) {
        double tR = g->ax[1][c % g->n[1]], E = g->ax[2][c / g->n[1]];
        need[c] = tR >= lo[1] * (1 - 1e-12) && tR <= hi[1] * (1 + 1e-12) &&
                  E >= lo[2] * (1 - 1e-12) && E <= hi[2] * (1 + 1e-12);
    }
}

int tbl_curves_pending(const tbl_table *t, const unsigned char *only)
{
    int n = 0, nc = tbl_curves(t);
    unsigned char *need = only ? calloc((size_t)nc + 1, 1) : NULL;
    if (only && !need) return -1;
    if (only) tbl_normal_needed(t, only, need);
    for (int c = 0; c < nc; c++) n += (!need || need[c]) && t->nrm.c[c].state == TBL_PENDING;
    free(need);
    return n;
}

/* ---- one curve -------------------------------------------------------------------- */

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The solver run of one curve (as `stiction asperity` runs a load curve):
 * out->state set, values written when done. */
static void run_curve(const stc_params *p, const asp_options *o, const stc_critical *c,
                      const double *w, int n_w, double *P_Pc, double *A_Ac, tbl_curve *out)
{
    double *d = malloc((size_t)n_w * sizeof *d);
    asp_curve_point *pts = malloc((size_t)n_w * sizeof *pts);
    asp_curve_result res;
    if (!d || !pts) {
        out->state = TBL_FAILED;
        snprintf(out->reason, sizeof out->reason, "out of memory");
        free(d), free(pts);
        return;
    }
    for (int k = 0; k < n_w; k++) d[k] = w[k] * c->omega_c;
    if (asp_curve_run(p, o, d, n_w, NULL, NULL, pts, &res) != STC_OK) {
        out->state = TBL_FAILED;
        if (res.n > 0)
            snprintf(out->reason, sizeof out->reason, "at delta/omega_c = %g: %.*s",
                     w[res.n - 1], TBL_REASON_MAX - 40, stc_errmsg());
        else snprintf(out->reason, sizeof out->reason, "%.*s", TBL_REASON_MAX - 1, stc_errmsg());
    } else {
        /* a tail that stopped early (res.tail) leaves the last nodes' smoothed
         * load one-sided, not wrong */
        out->state = TBL_DONE;
        out->increments = pts[n_w - 1].pt.increments;
        out->newton_iterations = pts[n_w - 1].pt.newton_iterations;
        for (int k = 0; k < n_w; k++) {
            P_Pc[k] = pts[k].P_smooth / c->P_c;
            A_Ac[k] = pts[k].pt.A / c->A_c;
            if (!(isfinite(P_Pc[k]) && P_Pc[k] > 0 && isfinite(A_Ac[k]) && A_Ac[k] > 0)) {
                out->state = TBL_FAILED;
                snprintf(out->reason, sizeof out->reason, "at delta/omega_c = %g: no smoothed "
                         "load or contact area (P/Pc %g, A/Ac %g)", w[k], P_Pc[k], A_Ac[k]);
                break;
            }
        }
    }
    free(d);
    free(pts);
}

stc_status tbl_curve_compute(const tbl_family *f, int level, double t_over_R, double E_ratio,
                             const double *w, int n_w, double *P_Pc, double *A_Ac,
                             tbl_curve *out)
{
    STC_CHECK(f && w && P_Pc && A_Ac && out, STC_EINVAL, "tbl_curve_compute: NULL argument");
    STC_CALL(tbl_family_validate(f));
    STC_CHECK(level >= 0 && level <= 3, STC_EINVAL, "normal-level = %d: must be in [0, 3]",
              level);
    STC_CHECK(n_w >= 1, STC_EINVAL, "tbl_curve_compute: %d delta values: need at least 1", n_w);
    for (int k = 0; k < n_w; k++)
        STC_CHECK(isfinite(w[k]) && w[k] > 0 && (k == 0 || w[k] > w[k - 1]), STC_EINVAL,
                  "delta/omega_c = %g: must be > 0 and increasing", w[k]);
    stc_params p;
    tbl_point_params(f, t_over_R, E_ratio, &p);
    STC_CALL(stc_params_validate(&p));
    stc_material su;
    stc_critical c;
    stc_params_materials(&p, &su, NULL);
    STC_CALL(stc_critical_eval(&su, p.R, &c));
    STC_CHECK(w[n_w - 1] * c.omega_c <= 0.01 * p.R, STC_EINVAL, "delta/omega_c = %g: beyond "
              "the small-strain limit delta <= 0.01 R (delta/omega_c <= %g)", w[n_w - 1],
              0.01 * p.R / c.omega_c);

    asp_options o;
    asp_options_default(&o);
    o.geom = ASP_GEOM_AXISYM;
    o.contact = f->contact;
    o.mesh_level = level;
    o.threads = 1;
    asp_options_for_curve(&o, n_w);

    memset(out, 0, sizeof *out);
    for (int k = 0; k < n_w; k++) P_Pc[k] = A_Ac[k] = NAN;
    double t0 = wall_now(), c0 = cpu_now();
    run_curve(&p, &o, &c, w, n_w, P_Pc, A_Ac, out);
    if (out->state != TBL_DONE)
        for (int k = 0; k < n_w; k++) P_Pc[k] = A_Ac[k] = NAN;
    out->wall_s = wall_now() - t0;
    out->cpu_s = cpu_now() - c0;
    stc_error_clear();
    return STC_OK;
}

/* tbl_curve_compute's arguments, for asp_run_serial. */
typedef struct {
    const tbl_table *t;
    int c;
    tbl_curve *out;
    double *P, *A;
} curve_job;

static stc_status curve_run(void *ctx)
{
    const curve_job *j = ctx;
    const tbl_normal *g = &j->t->nrm;
    return tbl_curve_compute(&j->t->fam, g->level, g->ax[1][j->c % g->n[1]],
                             g->ax[2][j->c / g->n[1]], g->ax[0], g->n[0], j->P, j->A, j->out);
}

/* On the calling thread alone (asp_run_serial, as a point: tbl_build_compute),
 * so the curves' numbers do not depend on how many run at once either. */
stc_status tbl_build_curve(const tbl_table *t, int c, tbl_curve *out, double *P, double *A)
{
    STC_CHECK(c >= 0 && c < tbl_curves(t), STC_EINVAL, "curve %d: must be in [0, %d)", c,
              tbl_curves(t));
    curve_job j = {t, c, out, P, A};
    return asp_run_serial(curve_run, &j);
}
