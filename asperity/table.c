/* Friction tables: the handle, the family, and one point's FE run
 * (include/stiction/table.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stiction/formulas.h"
#include "stc_check.h"
#include "table_impl.h"
#include "threads.h"

/* ---- family and numerics ------------------------------------------------- */

void tbl_family_default(tbl_family *f)
{
    f->E_over_Y_su = f->E_over_Y_co = 1000.0; /* thesis Table 4.1 */
    f->nu_su = f->nu_co = 0.32;
    f->contact = ASP_CONTACT_STICK;
    f->tau_c_over_Y_co = 1.0 / sqrt(3.0); /* von Mises shear strength (WSP 2012) */
    f->criterion = ASP_SHEAR_CRIT_SHEAR;
    f->alpha = 0.1; /* Brizmer, Kligerman & Etsion 2007 */
}

stc_status tbl_family_validate(const tbl_family *f)
{
    STC_CALL(stc_check_range("E-over-Y-su", f->E_over_Y_su, 10.0, 1, 1e5, 1));
    STC_CALL(stc_check_range("E-over-Y-co", f->E_over_Y_co, 10.0, 1, 1e5, 1));
    STC_CALL(stc_check_range("nu-su", f->nu_su, 0.0, 1, 0.5, 0));
    STC_CALL(stc_check_range("nu-co", f->nu_co, 0.0, 1, 0.5, 0));
    STC_CHECK(f->contact == ASP_CONTACT_SLIP || f->contact == ASP_CONTACT_STICK, STC_EINVAL,
              "contact = %d: must be slip (%d) or stick (%d)", (int)f->contact,
              (int)ASP_CONTACT_SLIP, (int)ASP_CONTACT_STICK);
    STC_CALL(stc_check_range("tau-c-over-Y-co", f->tau_c_over_Y_co, 0.0, 0, 1.0, 1));
    STC_CHECK(f->criterion == ASP_SHEAR_CRIT_SHEAR || f->criterion == ASP_SHEAR_CRIT_STIFFNESS,
              STC_EINVAL, "criterion = %d: must be shear (%d) or stiffness (%d)",
              (int)f->criterion, (int)ASP_SHEAR_CRIT_SHEAR, (int)ASP_SHEAR_CRIT_STIFFNESS);
    STC_CALL(stc_check_range("alpha", f->alpha, 0.0, 0, 1.0, 0));
    return STC_OK;
}

void tbl_family_describe(const tbl_family *f, char *buf, int n)
{
    int k = snprintf(buf, (size_t)n, "E/Y substrate %g, coating %g; nu %g, %g; %s normal step; "
                     "tau_c = %.6g Y_co; %s criterion", f->E_over_Y_su, f->E_over_Y_co,
                     f->nu_su, f->nu_co, f->contact == ASP_CONTACT_STICK ? "stick" : "slip",
                     f->tau_c_over_Y_co,
                     f->criterion == ASP_SHEAR_CRIT_SHEAR ? "shear" : "stiffness");
    if (f->criterion == ASP_SHEAR_CRIT_STIFFNESS && k > 0 && k < n)
        snprintf(buf + k, (size_t)(n - k), " (alpha %g)", f->alpha);
}

void tbl_family_of_params(const stc_params *p, const tbl_family *like, tbl_family *out)
{
    stc_material su, co;
    stc_params_materials(p, &su, &co);
    *out = *like;
    out->E_over_Y_su = su.E / su.Y;
    out->E_over_Y_co = co.E / co.Y;
    out->nu_su = su.nu;
    out->nu_co = co.nu;
}

void tbl_numerics_default(tbl_numerics *n)
{
    n->mesh_level = 0;
    n->elements_per_contact = 0.0;
    n->placements = 2;
    n->placements_max = 0;
    n->refine_err = ASP_REFINE_ERR;
    n->err_floor = ASP_MU_S_ERR_FLOOR;   /* the error model of asperity.h */
    n->err_single = ASP_MU_S_ERR_SINGLE;
    /* the axisymmetric default: a slip curve to 60 ωc within 0.29 % of the
     * converged load (docs/design.md §2.3) */
    n->normal_level = 1;
    asp_shear_options so; /* the solver's junction reading */
    asp_shear_options_default(&so);
    n->foot_rows = so.foot_rows;
}

stc_status tbl_numerics_validate(const tbl_numerics *n)
{
    STC_CHECK(n->mesh_level >= 0 && n->mesh_level <= 3, STC_EINVAL,
              "mesh-level = %d: must be in [0, 3]", n->mesh_level);
    STC_CHECK(n->placements >= 1 && n->placements <= ASP_PLACEMENTS_MAX, STC_EINVAL,
              "placements = %d: must be in [1, %d]", n->placements, ASP_PLACEMENTS_MAX);
    STC_CALL(asp_placements_refine_check(n->placements, n->placements_max, n->refine_err));
    STC_CALL(stc_check_range("refine-err", n->refine_err, 0.0, 0, 0.5, 1));
    STC_CHECK(n->elements_per_contact == 0.0 ||
                  (n->elements_per_contact >= 3.0 && n->elements_per_contact <= 200.0),
              STC_EINVAL, "elements-per-contact = %g: must be 0 (the mesh level's) or in "
              "[3, 200] (the solver's least, and room for the placements above it)",
              n->elements_per_contact);
    STC_CALL(stc_check_range("err-floor", n->err_floor, 0.0, 1, 0.5, 1));
    STC_CALL(stc_check_range("err-single", n->err_single, 0.0, 0, 0.5, 1));
    STC_CHECK(n->normal_level >= -1 && n->normal_level <= 3, STC_EINVAL,
              "normal-level = %d: must be -1 (no normal grid) or in [0, 3]", n->normal_level);
    STC_CALL(stc_check_range("foot-rows", n->foot_rows, 0.0, 1, 0.9, 1));
    return STC_OK;
}

const char *tbl_state_name(tbl_state s)
{
    switch (s) {
    case TBL_PENDING: return "pending";
    case TBL_DONE: return "done";
    case TBL_FAILED: return "failed";
    }
    return "unknown";
}

/* ---- one point --------------------------------------------------------------- */

int tbl_family_one_material(const tbl_family *f, double E_ratio)
{
    return E_ratio == 1.0 && f->E_over_Y_co == f->E_over_Y_su && f->nu_co == f->nu_su;
}

void tbl_point_params(const tbl_family *f, double t_over_R, double E_ratio, stc_params *p)
{
    stc_params_default(p);
    p->R = TBL_REF_R_MM;
    /* a coating of the substrate's material is none: the uncoated sphere, whose mesh
     * has no interface to follow (at 8 omega_c 9.6 CPU s against 16.2 at t/R 0.005) */
    p->t_over_R = tbl_family_one_material(f, E_ratio) ? 0.0 : t_over_R;
    p->E_su = TBL_REF_E_SU_MPA;
    p->E_ratio = E_ratio;
    p->Y_su = TBL_REF_E_SU_MPA / f->E_over_Y_su;
    p->Y_co = TBL_REF_E_SU_MPA * E_ratio / f->E_over_Y_co;
    p->nu = f->nu_su;
    p->nu_co = f->nu_co;
    p->nu_co_set = 1;
}

double tbl_wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The members of a finished ensemble as a point keeps them. */
static void members_of(const asp_placement_result *e, tbl_members *ens)
{
    memset(ens, 0, sizeof *ens);
    ens->k = e->k;
    ens->edge_refine = e->edge_refine;
    ens->period = e->period, ens->delta = e->delta;
    ens->delta_mesh = e->delta_mesh, ens->edge_a0 = e->edge_a0;
    for (int j = 0; j < e->k; j++) {
        const asp_placement_member *m = &e->m[j];
        tbl_member *q = &ens->m[j];
        q->elements_per_contact = m->elements_per_contact;
        q->P = m->pt.P, q->A = m->pt.A;
        q->P_slide = m->res.P_slide, q->Q_max = m->res.Q_max, q->ux_slide = m->res.ux_slide;
        q->mu_s = m->res.mu_s, q->mu_s_preload = m->res.mu_s_preload;
        q->mu_s_err = m->res.mu_s_err;
        q->cpu_s = m->cpu_s;
        q->newton_iterations = m->pt.newton_iterations + m->res.newton_iterations;
        q->factorizations = m->pt.factorizations + m->res.factorizations;
        q->mu_s_ux_slope = m->res.mu_s_ux_slope;
    }
}

/* Member j of done point p as its ensemble held it (tbl_members_unpack). */
static void member_unpack(const tbl_point *p, int j, asp_placement_member *m)
{
    const tbl_member *q = &p->ens.m[j];
    memset(m, 0, sizeof *m);
    m->elements_per_contact = q->elements_per_contact;
    m->status = STC_OK;
    m->pt.P = q->P, m->pt.A = q->A;
    m->pt.newton_iterations = q->newton_iterations, m->pt.factorizations = q->factorizations;
    m->res.converged = 1;
    m->res.P_slide = q->P_slide, m->res.Q_max = q->Q_max, m->res.ux_slide = q->ux_slide;
    m->res.mu_s = q->mu_s, m->res.mu_s_preload = q->mu_s_preload, m->res.mu_s_err = q->mu_s_err;
    m->res.mu_s_ux_slope = q->mu_s_ux_slope; /* NaN: not known */
    m->cpu_s = q->cpu_s;
    snprintf(m->res.reason, sizeof m->res.reason, "%s", p->reason);
}

void tbl_members_unpack(const tbl_point *p, asp_placement_result *e)
{
    const tbl_members *ens = &p->ens;
    memset(e, 0, sizeof *e);
    e->k = e->n_ok = ens->k;
    e->edge_refine = ens->edge_refine;
    e->period = ens->period, e->delta = ens->delta;
    e->delta_mesh = ens->delta_mesh, e->edge_a0 = ens->edge_a0;
    for (int j = 0; j < ens->k; j++) member_unpack(p, j, &e->m[j]);
}

static void fill_done(const stc_critical *c, const asp_placement_result *e,
                      const tbl_numerics *num, tbl_point *out)
{
    double P0 = 0.0, A0 = 0.0, ux = 0.0;
    double slope = 0.0; /* NaN if a member does not say (taken from an older file) */
    int k = e->k;
    for (int j = 0; j < k; j++) {
        slope += e->m[j].res.mu_s_ux_slope / k;
        P0 += e->m[j].pt.P / k;
        A0 += e->m[j].pt.A / k;
        ux += e->m[j].res.ux_slide / k;
        out->newton_iterations += e->m[j].pt.newton_iterations + e->m[j].res.newton_iterations;
        out->factorizations += e->m[j].pt.factorizations + e->m[j].res.factorizations;
    }
    out->state = TBL_DONE;
    out->P_Pc = P0 / c->P_c;
    out->A_Ac = A0 / c->A_c;
    out->P_slide_Pc = e->P_slide / c->P_c;
    out->Q_max_Pc = e->Q_max / c->P_c;
    out->mu_s = e->mu_s;
    out->mu_s_err = asp_placement_mu_s_err(e, num->err_single, num->err_floor);
    out->mu_s_preload = e->mu_s_preload;
    out->mu_s_min = e->mu_s_min;
    out->mu_s_max = e->mu_s_max;
    out->ux_slide_wc = ux / c->omega_c;
    out->members = e->n_ok;
    out->mu_s_ux_slope = slope;
    snprintf(out->reason, sizeof out->reason, "%.*s", TBL_REASON_MAX - 1, e->m[0].res.reason);
    members_of(e, &out->ens);
}

/* tbl_point_compute with the members of the point's ensemble on up to
 * `threads` threads at once (one each; the same numbers as on one), kept in
 * and taken from store (nullable). */
static stc_status point_compute(const tbl_family *f, const tbl_numerics *num, double w,
                                double t_over_R, double E_ratio, int threads,
                                const asp_placement_store *store, tbl_point *out)
{
    STC_CHECK(f && num && out, STC_EINVAL, "tbl_point_compute: NULL argument");
    STC_CALL(tbl_family_validate(f));
    STC_CALL(tbl_numerics_validate(num));
    STC_CHECK(isfinite(w) && w > 0.0, STC_EINVAL, "delta/omega_c = %g: must be > 0", w);
    stc_params p;
    tbl_point_params(f, t_over_R, E_ratio, &p);
    STC_CALL(stc_params_validate(&p));
    stc_material su, co;
    stc_critical c;
    stc_params_materials(&p, &su, &co);
    STC_CALL(stc_critical_eval(&su, p.R, &c));
    double delta = w * c.omega_c;
    STC_CHECK(delta <= 0.01 * p.R, STC_EINVAL, "delta/omega_c = %g: beyond the small-strain "
              "limit delta <= 0.01 R (delta/omega_c <= %g)", w, 0.01 * p.R / c.omega_c);

    asp_options o;
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D;
    o.contact = f->contact;
    o.mesh_level = num->mesh_level;
    o.elements_per_contact = num->elements_per_contact;
    o.threads = threads > 1 ? threads : 1;
    asp_shear_options so;
    asp_shear_options_default(&so);
    so.criterion = f->criterion;
    so.alpha = f->alpha;
    so.tau_c = f->tau_c_over_Y_co * co.Y;
    so.foot_rows = num->foot_rows;

    memset(out, 0, sizeof *out);
    asp_placement_result *e = malloc(sizeof *e);
    STC_CHECK(e, STC_ENOMEM, "tbl_point_compute: out of memory");
    double t0 = tbl_wall_now(), c0 = asp_thread_cpu();
    stc_status st = asp_shear_placements_stored(&p, &o, &so, delta, 0.0, num->placements,
                                                num->placements_max, num->refine_err, store, e);
    if (st == STC_OK) {
        fill_done(&c, e, num, out);
    } else {
        out->state = TBL_FAILED;
        out->members = e->n_ok;
        snprintf(out->reason, sizeof out->reason, "%.*s", TBL_REASON_MAX - 1, stc_errmsg());
    }
    out->wall_s = tbl_wall_now() - t0;
    /* the ensemble's threads, all of them (at least this one's, where it
     * failed before it counted them) */
    out->cpu_s = fmax(e->cpu_s, asp_thread_cpu() - c0);
    free(e);
    stc_error_clear();
    return STC_OK;
}

stc_status tbl_point_compute(const tbl_family *f, const tbl_numerics *num, double w,
                             double t_over_R, double E_ratio, tbl_point *out)
{
    return point_compute(f, num, w, t_over_R, E_ratio, 1, NULL, out);
}

/* point_compute's arguments, for asp_run_team. */
typedef struct {
    const tbl_table *t;
    double w, tR, E;
    int threads;
    const asp_placement_store *store;
    tbl_point *p;
} point_job;

static stc_status point_run(void *ctx)
{
    const point_job *j = ctx;
    return point_compute(&j->t->fam, &j->t->num, j->w, j->tR, j->E, j->threads, j->store, j->p);
}

/* One point on the calling thread alone, whichever path runs it (the
 * serial threads, rank 0's compute threads, the other ranks): the
 * solver's own regions on one thread (threads 1), CHOLMOD's OpenMP
 * regions serial in a region of this call's own (threads.h; inside a team
 * of one thread they would be the first active level, and creating a
 * nested team that often made a point 3x slower, 1.33 -> 4.0 s, same
 * numbers), OpenBLAS on one thread (threads.c), so that the table's
 * numbers do not depend on jobs, shards or ranks.  threads > 1 (fewer
 * points than threads): the point's members on that many threads, one
 * each, with the same numbers (placements.c). */
stc_status tbl_build_compute(const tbl_table *t, int i, int threads,
                             const asp_placement_store *store, tbl_point *p)
{
    double w, tR, E;
    tbl_coords(t, i, &w, &tR, &E);
    point_job j = {t, w, tR, E, threads, store, p};
    return asp_run_team(point_run, &j, threads);
}

stc_status tbl_build_item(const tbl_table *t, int item, int threads,
                          const asp_placement_store *store, tbl_point *p, tbl_curve *cv,
                          double *P, double *A)
{
    return item >= 0 ? tbl_build_compute(t, item, threads, store, p)
                     : tbl_build_curve(t, -item - 1, cv, P, A);
}

/* ---- the handle ----------------------------------------------------------------- */

static stc_status check_axis(const char *name, const double *v, int n, double lo)
{
    STC_CHECK(v && n >= 1 && n <= 10000, STC_EINVAL, "%s: %d values: must be 1 to 10000", name,
              n);
    for (int i = 0; i < n; i++) {
        STC_CHECK(isfinite(v[i]) && v[i] > lo, STC_EINVAL, "%s = %g: must be > %g", name, v[i],
                  lo);
        STC_CHECK(i == 0 || v[i] > v[i - 1], STC_EINVAL,
                  "%s = %g after %g: values must increase", name, v[i], v[i - 1]);
    }
    return STC_OK;
}

stc_status tbl_create(const tbl_family *f, const tbl_numerics *num, const double *w, int n_w,
                      const double *t_over_R, int n_tR, const double *E_ratio, int n_E,
                      tbl_table **out)
{
    STC_CHECK(out, STC_EINVAL, "tbl_create: out must not be NULL");
    *out = NULL;
    STC_CHECK(f && num, STC_EINVAL, "tbl_create: family and numerics required");
    STC_CALL(tbl_family_validate(f));
    STC_CALL(tbl_numerics_validate(num));
    STC_CALL(check_axis("delta/omega_c", w, n_w, 0.0));
    STC_CALL(check_axis("t/R", t_over_R, n_tR, 0.0));
    STC_CALL(check_axis("E-ratio", E_ratio, n_E, 0.0));
    STC_CHECK(t_over_R[n_tR - 1] < 1.0, STC_EINVAL, "t/R = %g: must be < 1", t_over_R[n_tR - 1]);
    long np = (long)n_w * n_tR * n_E;
    STC_CHECK(np <= 1000000, STC_EINVAL,
              "table of %d deltas x %d t-over-R x %d E-ratio = %ld points: at most 1000000",
              n_w, n_tR, n_E, np);
    tbl_table *t = calloc(1, sizeof *t);
    STC_CHECK(t, STC_ENOMEM, "tbl_create: out of memory");
    t->fam = *f;
    t->num = *num;
    const double *src[3] = {w, t_over_R, E_ratio};
    int n[3] = {n_w, n_tR, n_E};
    for (int k = 0; k < 3; k++) {
        t->n[k] = n[k];
        t->ax[k] = malloc((size_t)n[k] * sizeof(double));
        if (t->ax[k]) memcpy(t->ax[k], src[k], (size_t)n[k] * sizeof(double));
    }
    t->pt = calloc((size_t)np, sizeof *t->pt);
    t->nrm.level = -1;
    t->fit_npar = -1;
    if (!t->ax[0] || !t->ax[1] || !t->ax[2] || !t->pt) {
        tbl_destroy(&t);
        return STC_FAIL(STC_ENOMEM, "tbl_create: out of memory");
    }
    stc_status st = tbl_normal_init(t);
    if (st != STC_OK) {
        tbl_destroy(&t);
        return st;
    }
    *out = t;
    return STC_OK;
}

void tbl_destroy(tbl_table **pt)
{
    if (!pt || !*pt) return;
    tbl_table *t = *pt;
    for (int k = 0; k < 3; k++) free(t->ax[k]);
    free(t->pt);
    tbl_gp_destroy(&t->gp);
    tbl_normal_free(&t->nrm);
    free(t);
    *pt = NULL;
}

void tbl_get_family(const tbl_table *t, tbl_family *f) { *f = t->fam; }
void tbl_get_numerics(const tbl_table *t, tbl_numerics *n) { *n = t->num; }
int tbl_points(const tbl_table *t) { return t->n[0] * t->n[1] * t->n[2]; }

int tbl_axis(const tbl_table *t, int axis, const double **values)
{
    if (axis < 0 || axis > 2) return 0;
    if (values) *values = t->ax[axis];
    return t->n[axis];
}

void tbl_coords(const tbl_table *t, int i, double *w, double *t_over_R, double *E_ratio)
{
    int iw = i % t->n[0], it = (i / t->n[0]) % t->n[1], iE = i / (t->n[0] * t->n[1]);
    if (w) *w = t->ax[0][iw];
    if (t_over_R) *t_over_R = t->ax[1][it];
    if (E_ratio) *E_ratio = t->ax[2][iE];
}

const tbl_point *tbl_point_get(const tbl_table *t, int i)
{
    return i >= 0 && i < tbl_points(t) ? &t->pt[i] : NULL;
}

stc_status tbl_point_set(tbl_table *t, int i, const tbl_point *p)
{
    STC_CHECK(i >= 0 && i < tbl_points(t), STC_EINVAL, "point %d: must be in [0, %d)", i,
              tbl_points(t));
    STC_CHECK(p->state == TBL_PENDING || p->state == TBL_DONE || p->state == TBL_FAILED,
              STC_EINVAL, "point %d: state %d is not pending, done or failed", i, p->state);
    STC_CHECK(p->copied == 0 || (p->copied == 1 && tbl_point_source(t, i) != i), STC_EINVAL,
              "point %d: copied = %d: must be 0, or 1 where another point is its source", i,
              p->copied);
    t->pt[i] = *p;
    t->pt[i].reason[TBL_REASON_MAX - 1] = '\0';
    /* members are kept of a done point only, and all of them (a point marked
     * failed keeps its stale numbers, which are not an answer, but not them;
     * one whose member count was changed, not members of another ensemble;
     * a copy, none: its source keeps them) */
    if (p->state != TBL_DONE || p->copied || p->ens.k != p->members || p->ens.k < 0 ||
        p->ens.k > ASP_PLACEMENTS_MAX)
        memset(&t->pt[i].ens, 0, sizeof t->pt[i].ens);
    tbl_gp_destroy(&t->gp);
    return STC_OK;
}

/* ---- one material: points that another point's run gives ------------------------ */

int tbl_point_source(const tbl_table *t, int i)
{
    int nw = t->n[0], iw = i % nw, it = (i / nw) % t->n[1], iE = i / (nw * t->n[1]);
    return it > 0 && tbl_family_one_material(&t->fam, t->ax[2][iE]) ? iE * t->n[1] * nw + iw : i;
}

int tbl_point_wanted(const tbl_table *t, const unsigned char *only, int i)
{
    if (!only || only[i]) return 1;
    int nw = t->n[0], iw = i % nw, iE = i / (nw * t->n[1]);
    for (int it = 1; it < t->n[1]; it++) {
        int k = (iE * t->n[1] + it) * nw + iw;
        if (only[k] && tbl_point_source(t, k) == i) return 1;
    }
    return 0;
}

/* A point or curve (state, copied) whose source is another, in state src:
 * to be filled from it when the source has an answer and it is pending, an
 * earlier copy (its source since refined or retried), or failed where the
 * source is done. */
static int refill(int state, int copied, int src)
{
    return src != TBL_PENDING &&
           (state == TBL_PENDING || copied || (state == TBL_FAILED && src == TBL_DONE));
}

int tbl_fill_copies(tbl_table *t)
{
    int n = 0;
    for (int i = 0; i < tbl_points(t); i++) {
        int j = tbl_point_source(t, i);
        tbl_point *p = &t->pt[i];
        const tbl_point *q = &t->pt[j];
        if (j == i || !refill(p->state, p->copied, q->state)) continue;
        *p = *q; /* the same answer, which cost nothing here */
        p->copied = 1;
        p->newton_iterations = p->factorizations = 0;
        p->wall_s = p->cpu_s = 0.0;
        memset(&p->ens, 0, sizeof p->ens); /* its source keeps the members */
        n++;
    }
    if (n) tbl_gp_destroy(&t->gp);
    tbl_normal *g = &t->nrm; /* the curves the same way */
    for (int c = 0; c < tbl_curves(t); c++) {
        int j = tbl_curve_source(t, c);
        if (j == c || !refill(g->c[c].state, g->c[c].copied, g->c[j].state)) continue;
        tbl_curve cv = g->c[j];
        cv.copied = 1;
        cv.increments = cv.newton_iterations = 0;
        cv.wall_s = cv.cpu_s = 0.0;
        tbl_curve_set(t, c, &cv, g->P + (size_t)j * g->n[0], g->A + (size_t)j * g->n[0]);
    }
    return n;
}

void tbl_count(const tbl_table *t, int *done, int *failed, int *pending)
{
    int c[3] = {0, 0, 0};
    for (int i = 0; i < tbl_points(t); i++) c[t->pt[i].state]++;
    if (done) *done = c[TBL_DONE];
    if (failed) *failed = c[TBL_FAILED];
    if (pending) *pending = c[TBL_PENDING];
}

void tbl_set_provenance(tbl_table *t, const char *command, double build_wall_s)
{
    const char *c = command ? command : "";
    size_t n = strlen(c), cap = sizeof t->command;
    if (n < cap) {
        memcpy(t->command, c, n + 1);
    } else { /* cut at a character's start (UTF-8), marked */
        size_t k = cap - 4;
        while (k > 0 && ((unsigned char)c[k] & 0xC0) == 0x80) k--;
        memcpy(t->command, c, k);
        memcpy(t->command + k, "...", 4);
    }
    t->build_wall_s = build_wall_s;
}

const char *tbl_provenance(const tbl_table *t, double *build_wall_s)
{
    if (build_wall_s) *build_wall_s = t->build_wall_s;
    return t->command;
}

const char *tbl_history(const tbl_table *t)
{
    return t->history;
}

void tbl_history_carry(tbl_table *t, const char *history, const char *command)
{
    char buf[sizeof t->history + sizeof t->command + 1];
    size_t cap = sizeof t->history, n = 0;
    if (history && *history) { /* a file's fits t's; a longer one is cut, then trimmed */
        n = strnlen(history, sizeof buf - 1);
        memcpy(buf, history, n);
    }
    buf[n] = '\0';
    if (command && *command && strcmp(command, t->command) != 0) {
        char one[sizeof t->command]; /* one line: an argument's line breaks as spaces */
        snprintf(one, sizeof one, "%s", command);
        for (char *c = one; *c; c++)
            if (*c == '\n' || *c == '\r') *c = ' ';
        const char *last = strrchr(buf, '\n');
        if (strcmp(last ? last + 1 : buf, one) != 0) /* not twice in a row */
            n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%s", n ? "\n" : "", one);
    }
    const char *s = buf;
    if (n < cap) {
        memcpy(t->history, buf, n + 1);
        return;
    }
    while (strlen(s) + 4 >= cap) { /* whole lines out, oldest first */
        const char *nl = strchr(s, '\n');
        if (!nl) break;
        s = nl + 1;
    }
    snprintf(t->history, cap, "...\n%s", s);
}

/* ---- identity of a build ------------------------------------------------------- */

static unsigned long long fnv(unsigned long long h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211ULL;
    return h;
}

static unsigned long long fnv_d(unsigned long long h, double v) { return fnv(h, &v, sizeof v); }
static unsigned long long fnv_i(unsigned long long h, int v) { return fnv(h, &v, sizeof v); }

/* The build's points: family, their numerics and the axes; the refinement
 * settings too if `refine` (a table without refinement keeps its hash).  Not
 * the file format: a table keeps its build across format versions. */
static unsigned long long points_hash_of(const tbl_table *t, int refine)
{
    const tbl_family *f = &t->fam;
    const tbl_numerics *n = &t->num;
    unsigned long long h = 14695981039346656037ULL;
    h = fnv_d(h, f->E_over_Y_su), h = fnv_d(h, f->E_over_Y_co);
    h = fnv_d(h, f->nu_su), h = fnv_d(h, f->nu_co);
    h = fnv_i(h, (int)f->contact), h = fnv_d(h, f->tau_c_over_Y_co);
    h = fnv_i(h, (int)f->criterion), h = fnv_d(h, f->alpha);
    h = fnv_i(h, n->mesh_level), h = fnv_i(h, n->placements);
    h = fnv_d(h, n->elements_per_contact);
    h = fnv_d(h, n->foot_rows);
    /* only the error term the points use: err_single with one member, else
     * err_floor (a table keeps its points when the other default moves) */
    h = fnv_d(h, n->placements == 1 ? n->err_single : n->err_floor);
    if (refine && n->placements_max > 0) {
        h = fnv_i(h, n->placements_max), h = fnv_d(h, n->refine_err);
        h = fnv_d(h, n->err_floor);
    }
    for (int k = 0; k < 3; k++) {
        h = fnv_i(h, t->n[k]);
        for (int i = 0; i < t->n[k]; i++) h = fnv_d(h, t->ax[k][i]);
    }
    return h;
}

static unsigned long long points_hash(const tbl_table *t) { return points_hash_of(t, 1); }

/* The points' hash and the normal grid's level and axes. */
static unsigned long long definition_hash(const tbl_table *t)
{
    const tbl_normal *g = &t->nrm;
    unsigned long long h = fnv_i(points_hash(t), g->level);
    for (int k = 0; g->level >= 0 && k < 3; k++) {
        h = fnv_i(h, g->n[k]);
        for (int i = 0; i < g->n[k]; i++) h = fnv_d(h, g->ax[k][i]);
    }
    return h;
}

unsigned long long tbl_build_hash(const tbl_table *t)
{
    /* the journal and the MPI messages carry points and curves as bytes */
    unsigned long long h = fnv_i(definition_hash(t), TBL_FORMAT_VERSION);
    h = fnv_i(h, (int)sizeof(tbl_point));
    h = fnv_i(h, (int)sizeof(asp_placement_member)); /* the journal's member records */
    return fnv_i(h, (int)sizeof(tbl_curve));
}

int tbl_same_points(const tbl_table *a, const tbl_table *b)
{
    return points_hash(a) == points_hash(b);
}

int tbl_same_build(const tbl_table *a, const tbl_table *b)
{
    return definition_hash(a) == definition_hash(b);
}

int tbl_refines(const tbl_table *t, const tbl_table *old)
{
    const tbl_numerics *n = &t->num, *o = &old->num;
    return points_hash_of(t, 0) == points_hash_of(old, 0) && n->placements_max > 0 &&
           (o->placements_max == 0 ||
            (n->placements_max >= o->placements_max && n->refine_err <= o->refine_err &&
             n->err_floor == o->err_floor));
}

/* The relative error a single run of point i prints (its shear result's
 * mu_s_err): asp_mu_s_err_single at δ = w ωc_su over asp_omega_yield. */
static double single_run_err(const tbl_table *t, const tbl_numerics *n, int i)
{
    double w, tR, E, omega_y;
    tbl_coords(t, i, &w, &tR, &E);
    stc_params p;
    tbl_point_params(&t->fam, tR, E, &p);
    stc_material su;
    stc_critical c;
    stc_params_materials(&p, &su, NULL);
    if (stc_critical_eval(&su, p.R, &c) != STC_OK || asp_omega_yield(&p, &omega_y) != STC_OK) {
        stc_error_clear();
        return NAN;
    }
    return asp_mu_s_err_single(n->foot_rows, 0, w * c.omega_c / omega_y);
}

int tbl_point_refinable(const tbl_table *t, const tbl_numerics *n, int i)
{
    const tbl_point *p = &t->pt[i];
    if (p->state != TBL_DONE || n->placements_max == 0 || p->members < 1 ||
        2 * p->members > n->placements_max)
        return 0;
    if (p->members == 1) /* one member: its own error, as the build decides */
        return single_run_err(t, n, i) > n->refine_err;
    /* the members' standard error of the mean: the stored error without its floor */
    double fl = n->err_floor * p->mu_s, se2 = p->mu_s_err * p->mu_s_err - fl * fl;
    return se2 > 0.0 && sqrt(se2) > n->refine_err * p->mu_s;
}

stc_status tbl_refine_plan(const tbl_table *t, int placements_max, double refine_err,
                           int *points, double *cpu_s, int *unkept)
{
    STC_CHECK(t && points, STC_EINVAL, "tbl_refine_plan: NULL argument");
    const tbl_numerics *o = &t->num;
    STC_CHECK(placements_max > 0, STC_EINVAL, "placements-max = %d: a refinement needs it in "
              "[%d, %d]", placements_max, 2 * o->placements, ASP_PLACEMENTS_MAX);
    STC_CALL(asp_placements_refine_check(o->placements, placements_max, refine_err));
    STC_CHECK(o->placements_max == 0 || placements_max >= o->placements_max, STC_EINVAL,
              "placements-max = %d: the table refines up to %d already (a build with less "
              "would be another build)", placements_max, o->placements_max);
    STC_CHECK(o->placements_max == 0 || refine_err <= o->refine_err, STC_EINVAL,
              "refine-err = %g: the table refines from %g already (a build refining less "
              "would be another build)", refine_err, o->refine_err);
    tbl_numerics n = *o;
    n.placements_max = placements_max, n.refine_err = refine_err;
    int k = 0, u = 0;
    double c = 0.0;
    for (int i = 0; i < tbl_points(t); i++) /* a copy is filled again from its source */
        if (tbl_point_source(t, i) == i && tbl_point_refinable(t, &n, i)) {
            k++, c += t->pt[i].cpu_s;
            u += t->pt[i].ens.k < t->pt[i].members;
        }
    *points = k;
    if (cpu_s) *cpu_s = c;
    if (unkept) *unkept = u;
    return STC_OK;
}

stc_status tbl_merge(tbl_table *const *parts, int n, tbl_table **out)
{
    STC_CHECK(out, STC_EINVAL, "tbl_merge: out must not be NULL");
    *out = NULL;
    STC_CHECK(parts && n >= 1, STC_EINVAL, "tbl_merge: %d tables: need at least one", n);
    for (int j = 1; j < n; j++)
        STC_CHECK(tbl_same_build(parts[0], parts[j]), STC_EINVAL,
                  "merge: table %d is of another build than table 1 (family, numerics or "
                  "axes differ)", j + 1);
    const tbl_table *a = parts[0];
    STC_CALL(tbl_create(&a->fam, &a->num, a->ax[0], a->n[0], a->ax[1], a->n[1], a->ax[2],
                        a->n[2], out));
    tbl_table *m = *out;
    if (a->nrm.level >= 0) {
        stc_status st = tbl_normal_init_axes(m, a->nrm.ax, a->nrm.n); /* the parts' grid */
        if (st != STC_OK) {
            tbl_destroy(out);
            return st;
        }
    }
    double wall = 0.0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < tbl_points(m); i++) {
            const tbl_point *q = &parts[j]->pt[i];
            /* a point refined in one part (a refinement sharded onto a copy
             * of the whole table) replaces its unrefined self */
            if ((m->pt[i].state == TBL_PENDING && q->state != TBL_PENDING) ||
                (m->pt[i].state == TBL_DONE && q->state == TBL_DONE &&
                 q->members > m->pt[i].members))
                m->pt[i] = *q;
        }
        const tbl_normal *g = &parts[j]->nrm;
        for (int c = 0; c < tbl_curves(m); c++)
            if (m->nrm.c[c].state == TBL_PENDING && g->c[c].state != TBL_PENDING)
                tbl_curve_set(m, c, &g->c[c], g->P + (size_t)c * g->n[0],
                              g->A + (size_t)c * g->n[0]);
        wall = fmax(wall, parts[j]->build_wall_s); /* shards run side by side */
    }
    tbl_fill_copies(m); /* a copy whose source another shard computed */
    tbl_set_provenance(m, a->command, wall);
    tbl_history_carry(m, a->history, NULL);
    return STC_OK;
}

/* ---- axes ------------------------------------------------------------------------ */

int tbl_bracket(const double *ax, int n, double x, double *frac)
{
    if (n == 1) {
        *frac = 0.0;
        return 0;
    }
    int i = 0;
    while (i < n - 2 && x >= ax[i + 1]) i++;
    double f = (log(x) - log(ax[i])) / (log(ax[i + 1]) - log(ax[i]));
    /* a value on a node up to rounding (t/R from t and R, a resampled grid)
     * is on it: 0 or 1 exactly, so that callers skip the other side */
    if (f < 1e-9) f = 0.0;
    if (f > 1.0 - 1e-9) f = 1.0;
    *frac = f;
    return i;
}
