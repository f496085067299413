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

#include "stc_check.h"
#include "table_impl.h"

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

int tbl_curve_source(const tbl_table *t, int c)
{
    const tbl_normal *g = &t->nrm;
    int nt = g->n[1], it = c % nt, iE = c / nt;
    return it > 0 && tbl_family_one_material(&t->fam, g->ax[2][iE]) ? iE * nt : c;
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
    STC_CHECK(cv->copied == 0 || (cv->copied == 1 && tbl_curve_source(t, c) != c), STC_EINVAL,
              "curve %d: copied = %d: must be 0, or 1 where another curve is its source", c,
              cv->copied);
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
