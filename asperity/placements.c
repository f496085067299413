/* Node-placement ensemble of the combined-loading run (include/stiction/asperity.h,
 * asp_shear_placements; docs/design.md §4.5).
 *
 * A single mesh reads the junction growth in steps of whole node closures:
 * where the surface nodes sit relative to the contact edge moves a level-0 μs
 * by up to ±12 % (docs/design.md §4.5), while the preload is smooth.  The
 * members here are the same model on meshes with elements_per_contact
 * N_j = N_0 + j T / k, j = 0 … k-1, where T = a_max / a0 is the shift that
 * moves the surface grid by one node spacing at the preload contact edge
 * (h = a_max / N, so the edge sits at a0 N / a_max spacings from the axis):
 * the members sample the node-entry sawtooth at k evenly spaced phases of one
 * period, and their mean is the stratified average over it.  Member 0's
 * normal step gives a0; the other members then run concurrently with it, one
 * thread each.  A store (asp_shear_placements_stored) keeps each finished
 * member and hands it back to a later run of the same ensemble, which then
 * does not run it. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"
#include "threads.h"

/* Normal step of one member (its solver is kept for the ramp): meshed for
 * dmesh (mm) and loaded to delta, or with P > 0 (member 0 under load
 * control) brought to P as asp_shear_preload does. */
static void member_load(const stc_params *p, const asp_options *o, double dmesh, double delta,
                        double P, asp_placement_member *m, asp_solver **sv)
{
    asp_options mo = *o;
    mo.elements_per_contact = m->elements_per_contact;
    mo.threads = 1;
    *sv = NULL;
    if (P > 0.0) {
        m->status = asp_shear_preload(p, &mo, 0.0, P, sv, &m->pt);
    } else {
        m->status = asp_solver_create(p, &mo, dmesh, sv);
        if (m->status == STC_OK) m->status = asp_solver_load(*sv, delta, &m->pt);
    }
    if (m->status != STC_OK) snprintf(m->message, sizeof m->message, "%s", stc_errmsg());
}

static void member_shear(const asp_shear_options *so, asp_placement_member *m,
                         asp_solver **sv)
{
    if (m->status == STC_OK) {
        m->status = asp_solver_shear(*sv, so, NULL, NULL, &m->res);
        if (m->status != STC_OK) { /* two fields of *m: a bounded copy */
            size_t n = strnlen(m->res.reason, sizeof m->message - 1);
            memcpy(m->message, m->res.reason, n);
            m->message[n] = '\0';
        }
    }
    asp_solver_destroy(sv);
}

stc_status asp_shear_placements(const stc_params *p, const asp_options *o,
                                const asp_shear_options *so, double delta, int k,
                                asp_placement_result *out)
{
    return asp_shear_placements_preload(p, o, so, delta, 0.0, k, out);
}

/* Load and shear the members todo[n] of out concurrently, one thread each,
 * at most o->threads (0: all cores) at a time; sv[j] already holds a loaded
 * solver where it is not NULL (member 0 of a new ensemble).  Each member's
 * CPU time is added to its cpu_s, and it goes to store (nullable) when
 * done.  Adds to out->cpu_s the CPU time of the team's threads other than
 * the caller's (the caller counts its own). */
static void run_members(const stc_params *p, const asp_options *o, const asp_shear_options *so,
                        const asp_placement_store *store, asp_placement_result *out,
                        asp_solver **sv, const int *todo, int n)
{
    int nt = o->threads > 0 ? o->threads : omp_get_max_threads();
    if (nt > n) nt = n;
    if (nt < 1) return;
    /* one BLAS thread per member (threads.c), also when it runs alone, so
     * that a member's numbers do not depend on how many run beside it (a
     * refined ensemble is the one made at once, to the bit); CHOLMOD's
     * regions on the member's thread, whatever the caller's
     * max-active-levels (this team's own setting, threads.h) */
    asp_blas_serial_enter();
#pragma omp parallel num_threads(nt)
    {
        omp_set_max_active_levels(0);
        double c0 = asp_thread_cpu();
#pragma omp for schedule(dynamic, 1)
        for (int i = 0; i < n; i++) {
            int j = todo[i];
            double cm = asp_thread_cpu();
            if (!sv[j]) member_load(p, o, out->delta_mesh, out->delta, 0.0, &out->m[j], &sv[j]);
            member_shear(so, &out->m[j], &sv[j]);
            out->m[j].cpu_s += asp_thread_cpu() - cm;
            if (store && store->put) store->put(store->ctx, out, j);
        }
        if (omp_get_thread_num() != 0) {
            double c = asp_thread_cpu() - c0;
#pragma omp atomic update
            out->cpu_s += c;
        }
    }
    asp_blas_serial_leave();
}

/* Member j of out (its elements_per_contact set) from store, if an earlier
 * run finished it; 1 if taken.  For member 0 (ensemble_start) the
 * geometry is taken too; for the others it must be the ensemble's own. */
static int member_take(const asp_placement_store *store, asp_placement_result *out, int j)
{
    if (!store || !store->get) return 0;
    asp_placement_result *g = malloc(sizeof *g);
    asp_placement_member *m = malloc(sizeof *m);
    int got = g && m && store->get(store->ctx, asp_placement_slot(j, out->k), g, m);
    if (got && j > 0) /* a member of another ensemble: computed, not taken */
        got = m->elements_per_contact == out->m[j].elements_per_contact &&
              g->period == out->period && g->delta == out->delta &&
              g->delta_mesh == out->delta_mesh && g->edge_a0 == out->edge_a0 &&
              g->edge_refine == out->edge_refine;
    if (got) {
        out->m[j] = *m;
        out->cpu_s += m->cpu_s; /* what it cost, when it ran */
        if (j == 0) {
            out->period = g->period, out->edge_refine = g->edge_refine;
            out->delta = g->delta, out->delta_mesh = g->delta_mesh, out->edge_a0 = g->edge_a0;
        }
    }
    free(g);
    free(m);
    return got;
}

/* The means, extremes and error of out's k members, and its status. */
static stc_status summarize(asp_placement_result *out, double t0)
{
    int k = out->k;
    const asp_placement_member *m = out->m;
    out->n_ok = 0;
    out->mu_s = out->mu_s_preload = out->Q_max = out->P_slide = 0.0;
    out->mu_s_min = INFINITY, out->mu_s_max = -INFINITY;
    for (int j = 0; j < k; j++) {
        if (m[j].status != STC_OK || !m[j].res.converged) continue;
        const asp_shear_result *r = &m[j].res;
        out->n_ok++;
        out->mu_s += r->mu_s, out->mu_s_preload += r->mu_s_preload;
        out->Q_max += r->Q_max, out->P_slide += r->P_slide;
        out->mu_s_min = fmin(out->mu_s_min, r->mu_s);
        out->mu_s_max = fmax(out->mu_s_max, r->mu_s);
    }
    out->wall_s += omp_get_wtime() - t0;
    if (out->n_ok < k) {
        int j = 0;
        while (m[j].status == STC_OK && m[j].res.converged) j++;
        return STC_FAIL(STC_ENOCONV, "placements: %d of %d members did not reach inception; "
                        "member %d (elements per contact %g): %s", k - out->n_ok, k, j,
                        m[j].elements_per_contact, m[j].message);
    }
    out->mu_s /= k, out->mu_s_preload /= k, out->Q_max /= k, out->P_slide /= k;
    /* one member: its own error, the single mesh's at this δ */
    out->mu_s_err = asp_placement_mu_s_err(out, m[0].res.mu_s_err / m[0].res.mu_s,
                                           ASP_MU_S_ERR_FLOOR);
    return STC_OK;
}

/* asp_shear_placements_preload with the members kept in store (nullable). */
static stc_status ensemble_start(const stc_params *p, const asp_options *o,
                                 const asp_shear_options *so, double delta, double P, int k,
                                 const asp_placement_store *store, asp_placement_result *out)
{
    memset(out, 0, sizeof *out);
    STC_CHECK(k >= 1 && k <= ASP_PLACEMENTS_MAX, STC_EINVAL,
              "placements = %d: must be in [1, %d]", k, ASP_PLACEMENTS_MAX);
    STC_CHECK(o && o->geom == ASP_GEOM_3D, STC_EINVAL,
              "placements: the tangential step needs the 3D model");
    STC_CHECK((delta > 0.0) != (P > 0.0), STC_EINVAL,
              "placements: delta = %g mm, P = %g N: give one of them (> 0)", delta, P);
    double t0 = omp_get_wtime(), c0 = asp_thread_cpu();
    /* an edge band: placed once for all members (under load control by
     * member 0's preload, which finds it on the way) */
    asp_options eo = *o;
    if (delta > 0.0) STC_CALL(asp_options_edge(p, &eo, delta, 0.0));
    o = &eo;
    asp_solver *sv[ASP_PLACEMENTS_MAX] = {NULL};
    asp_placement_member *m = out->m;
    out->k = k;
    int todo[ASP_PLACEMENTS_MAX], n = 0;
    if (member_take(store, out, 0)) { /* finished before: its geometry too */
        eo.edge_a0 = out->edge_a0;
    } else {
        m[0].elements_per_contact = o->elements_per_contact; /* 0: the level's */
        double cm = asp_thread_cpu(); /* its own: the edge band's placement is the ensemble's */
        asp_blas_serial_enter(); /* member 0's normal step on one BLAS thread as the rest */
        member_load(p, o, delta, delta, P, &m[0], &sv[0]);
        asp_blas_serial_leave();
        m[0].cpu_s = asp_thread_cpu() - cm;
        asp_info in;
        if (sv[0]) { /* the mesh resolves the level into elements per contact */
            asp_solver_info(sv[0], &in);
            m[0].elements_per_contact = in.elements_per_contact;
        }
        if (m[0].status != STC_OK) {
            asp_solver_destroy(&sv[0]);
            out->cpu_s = asp_thread_cpu() - c0;
            return STC_FAIL(m[0].status, "placements: member 0 (elements per contact %g): %s",
                            m[0].elements_per_contact, m[0].message);
        }
        /* under load control the others run at member 0's interference, on
         * meshes sized as its own (for the same delta_max), so the phases stay
         * evenly spaced; their loads differ from P by their meshes' */
        out->delta_mesh = delta > 0.0 ? delta : sv[0]->delta_max;
        out->delta = P > 0.0 ? m[0].pt.delta : delta;
        out->edge_a0 = eo.edge_a0 = sv[0]->opt.edge_a0;
        /* the shift that moves the surface nodes at the edge by one spacing: the
         * coarse one, or the band's, 2^K times finer (a coarse shift moves the
         * band's nodes by whole spacings: every member at one phase) */
        out->period = in.a_max / m[0].pt.a / (1 << in.edge_refine);
        out->edge_refine = in.edge_refine;
        todo[n++] = 0;
    }
    for (int j = 1; j < k; j++) {
        m[j].elements_per_contact = m[0].elements_per_contact + j * out->period / k;
        if (!member_take(store, out, j)) todo[n++] = j;
    }
    run_members(p, o, so, store, out, sv, todo, n);
    out->cpu_s += asp_thread_cpu() - c0;
    return summarize(out, t0);
}

stc_status asp_shear_placements_preload(const stc_params *p, const asp_options *o,
                                        const asp_shear_options *so, double delta, double P,
                                        int k, asp_placement_result *out)
{
    return ensemble_start(p, o, so, delta, P, k, NULL, out);
}

/* asp_shear_placements_refine with the members kept in store (nullable). */
static stc_status ensemble_refine(const stc_params *p, const asp_options *o,
                                  const asp_shear_options *so, const asp_placement_store *store,
                                  asp_placement_result *out)
{
    int k = out->k;
    STC_CHECK(k >= 1 && 2 * k <= ASP_PLACEMENTS_MAX, STC_EINVAL,
              "placements refine: %d members: twice that must be at most %d", k,
              ASP_PLACEMENTS_MAX);
    STC_CHECK(out->n_ok == k, STC_EINVAL,
              "placements refine: %d of %d members reached inception: not an ensemble to refine",
              out->n_ok, k);
    STC_CHECK(o && o->geom == ASP_GEOM_3D, STC_EINVAL,
              "placements: the tangential step needs the 3D model");
    double t0 = omp_get_wtime(), c0 = asp_thread_cpu();
    asp_options eo = *o;
    eo.edge_a0 = out->edge_a0;
    /* members in phase order: the old ones at the even places, the new
     * ones half a step after each */
    for (int j = k - 1; j >= 0; j--) out->m[2 * j] = out->m[j];
    out->k = 2 * k;
    int todo[ASP_PLACEMENTS_MAX], n = 0;
    for (int j = 1; j < 2 * k; j += 2) {
        memset(&out->m[j], 0, sizeof out->m[j]);
        out->m[j].elements_per_contact = out->m[0].elements_per_contact + j * out->period / (2 * k);
        if (!member_take(store, out, j)) todo[n++] = j;
    }
    asp_solver *sv[ASP_PLACEMENTS_MAX] = {NULL};
    run_members(p, &eo, so, store, out, sv, todo, n);
    out->cpu_s += asp_thread_cpu() - c0;
    return summarize(out, t0);
}

stc_status asp_shear_placements_refine(const stc_params *p, const asp_options *o,
                                       const asp_shear_options *so, asp_placement_result *out)
{
    return ensemble_refine(p, o, so, NULL, out);
}

int asp_placement_slot(int j, int k)
{
    return j * (ASP_PLACEMENTS_MAX / k);
}

stc_status asp_placements_refine_check(int k, int k_max, double rel_err)
{
    STC_CHECK(k_max == 0 || 2 * k <= ASP_PLACEMENTS_MAX, STC_EINVAL,
              "placements-max = %d: must be 0 (no refinement) with placements = %d, which "
              "leaves no room to refine (twice it exceeds %d, ASP_PLACEMENTS_MAX)", k_max, k,
              ASP_PLACEMENTS_MAX);
    STC_CHECK(k_max == 0 || (k_max >= 2 * k && k_max <= ASP_PLACEMENTS_MAX), STC_EINVAL,
              "placements-max = %d: must be 0 (no refinement) or in [%d, %d] (twice "
              "placements = %d, ASP_PLACEMENTS_MAX)", k_max, 2 * k, ASP_PLACEMENTS_MAX, k);
    STC_CHECK(k_max == 0 || (rel_err > 0.0 && rel_err <= 0.5), STC_EINVAL,
              "refine-err = %g: must be in (0, 0.5]", rel_err);
    return STC_OK;
}

stc_status asp_shear_placements_stored(const stc_params *p, const asp_options *o,
                                       const asp_shear_options *so, double delta, double P,
                                       int k, int k_max, double rel_err,
                                       const asp_placement_store *store,
                                       asp_placement_result *out)
{
    memset(out, 0, sizeof *out);
    STC_CALL(asp_placements_refine_check(k, k_max, rel_err));
    STC_CALL(ensemble_start(p, o, so, delta, P, k, store, out));
    /* the members' standard error without the floor; one member: its own */
    while (2 * out->k <= k_max &&
           asp_placement_mu_s_err(out, out->m[0].res.mu_s_err / out->m[0].res.mu_s, 0.0) >
               rel_err * out->mu_s)
        STC_CALL(ensemble_refine(p, o, so, store, out));
    return STC_OK;
}

stc_status asp_shear_placements_adaptive(const stc_params *p, const asp_options *o,
                                         const asp_shear_options *so, double delta, double P,
                                         int k, int k_max, double rel_err,
                                         asp_placement_result *out)
{
    return asp_shear_placements_stored(p, o, so, delta, P, k, k_max, rel_err, NULL, out);
}

double asp_mu_s_err_single(double foot_rows, int edge_refine, double delta_over_omega)
{
    /* the axis lines' scatter rises with the plastic junction growth: 1.2-2.6 %
     * up to first yield, 3.8 % at 1.4, 5.8 % at 2, 6.3-10.1 % from 3 on (over
     * 8 placements; two band levels: 1.3-6.8 % over 4, docs/design.md §4.5) */
    double x = delta_over_omega;
    double hi = edge_refine >= 2 ? ASP_MU_S_ERR_BAND : ASP_MU_S_ERR_SINGLE, e = hi;
    if (!(x >= 3.0))
        e = !(x > 1.0) ? ASP_MU_S_ERR_ELASTIC
                       : ASP_MU_S_ERR_ELASTIC * pow(hi / ASP_MU_S_ERR_ELASTIC, log(x) / log(3.0));
    return foot_rows > 0.0 ? fmin(ASP_MU_S_ERR_ROWS, e) : e;
}

double asp_placement_mu_s_err(const asp_placement_result *e, double err_single,
                              double err_floor)
{
    int k = e->k;
    if (k < 1 || e->n_ok < k) return NAN;
    if (k == 1) return err_single * e->mu_s;
    double ss = 0.0;
    for (int j = 0; j < k; j++) ss += pow(e->m[j].res.mu_s - e->mu_s, 2);
    double se2 = ss / (k - 1) / k; /* standard error of the mean, squared */
    return sqrt(se2 + pow(err_floor * e->mu_s, 2));
}
