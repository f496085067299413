/* The normal curves of a friction table (include/stiction/table.h,
 * tbl_numerics.normal_level): which curves a build restricted to some
 * points needs, and one curve computed, the axisymmetric load curve at a
 * (t/R, Eco/Esu) node of the normal grid (table_normal.c has the grid and
 * why it exists).  Apart from table_normal.c because the grid's storage is
 * created and freed by the table handle (table.c), while these read the
 * handle's points and family: in one file the two called each other. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stiction/formulas.h"
#include "stc_check.h"
#include "table_impl.h"
#include "threads.h"

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
    for (int c = 0; c < tbl_curves(t); c++) /* a copy needs its source's run */
        if (need[c]) need[tbl_curve_source(t, c)] = 1;
}

int tbl_curves_pending(const tbl_table *t, const unsigned char *only)
{
    int n = 0, nc = tbl_curves(t);
    unsigned char *need = only ? calloc((size_t)nc + 1, 1) : NULL;
    if (only && !need) return -1;
    if (only) tbl_normal_needed(t, only, need);
    for (int c = 0; c < nc; c++)
        n += (!need || need[c]) && tbl_curve_source(t, c) == c &&
             t->nrm.c[c].state == TBL_PENDING;
    free(need);
    return n;
}

/* ---- one curve -------------------------------------------------------------------- */

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
            A_Ac[k] = pts[k].A_smooth / c->A_c;
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
    /* a curve even at one δ: it samples the elastic node entries, else a
     * single δ in the elastic range left too few increments for the
     * smoothed P and A (NaN: the curve failed at 0.5 and 1 ωc_su) */
    asp_options_for_curve(&o, n_w > 1 ? n_w : 2);

    memset(out, 0, sizeof *out);
    for (int k = 0; k < n_w; k++) P_Pc[k] = A_Ac[k] = NAN;
    double t0 = tbl_wall_now(), c0 = asp_thread_cpu();
    run_curve(&p, &o, &c, w, n_w, P_Pc, A_Ac, out);
    if (out->state != TBL_DONE)
        for (int k = 0; k < n_w; k++) P_Pc[k] = A_Ac[k] = NAN;
    out->wall_s = tbl_wall_now() - t0;
    out->cpu_s = asp_thread_cpu() - c0;
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
