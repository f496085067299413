/* Runs as `stiction asperity` makes them (include/stiction/asperity.h):
 * the solver settings chosen for what is asked (a single point, a load
 * curve, a shear run at an interference or under a load), kept in the
 * library so that a C caller gets the numbers the CLI prints.  Only the
 * public solver interface is used here; the numbers behind each choice are
 * in docs/design.md (§2.4 the graded 3D core, §3.3 the elastic node entries
 * and the tail, §4.7 load control). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stc_check.h"
#include "stiction/asperity.h"

void asp_options_for_curve(asp_options *o, int n)
{
    /* a 3D normal-loading run (a point or a curve) checks the 3D mesh
     * against the axisymmetric model, so it keeps the outer shells' full
     * resolution: the coarsening's 2:1 step at 6 a_max stiffens P by
     * ~0.16-0.18 % (Hertz a/R = 0.003, level 0: +0.500 -> +0.316 % vs Hertz,
     * the converged model +0.174 %; 15780 -> 25614 DOFs); the shear runs
     * keep it for their speed */
    if (o->geom == ASP_GEOM_3D && o->shell_coarsen < 0) o->shell_coarsen = 0;
    if (n < 2) return;
    /* an axisymmetric curve samples the elastic node entries before its
     * points too, so P_smooth at a point near first yield is not a fit
     * across the bend (3D: 35 -> 24 increments on the level-0 curve, +12 %
     * run time, the 1 wc point unchanged: one contact node there) */
    if (o->geom != ASP_GEOM_3D) o->sample_elastic = 1;
    /* a 3D load curve is meshed for all its contacts, not for its largest:
     * the uniform core had 1-2 elements across the small-δ contacts (-33 %
     * at 1 ωc, -6 % at 6.4 ωc on 1:60:12) */
    else o->grade_3d = 1;
}

stc_status asp_options_for_shear(asp_options *o)
{
    STC_CHECK(o->geom != ASP_GEOM_AXISYM, STC_EINVAL,
              "model = 'axisym': the tangential step (shear) needs the 3D model (3d or auto)");
    o->geom = ASP_GEOM_3D;
    return STC_OK;
}

/* Load to one point of the curve and record what is known there. */
static void curve_point(asp_solver *s, double delta, asp_curve_point *c)
{
    c->status = asp_solver_load(s, delta, &c->pt);
    if (c->status != STC_OK) snprintf(c->reason, sizeof c->reason, "%s", stc_errmsg());
    else snprintf(c->reason, sizeof c->reason, "converged");
    for (int k = 0; k < 2; k++) asp_solver_yield(s, k, &c->yield[k]);
    asp_info now;
    asp_solver_info(s, &now);
    c->time_assembly_s = now.time_assembly_s;
    c->time_factorize_s = now.time_factorize_s;
    c->time_pcg_s = now.time_pcg_s;
}

stc_status asp_curve_run(const stc_params *p, const asp_options *o, const double *delta, int n,
                         asp_curve_fn cb, void *ctx, asp_curve_point *pts,
                         asp_curve_result *res)
{
    STC_CHECK(p && delta && pts && res && n >= 1, STC_EINVAL,
              "asp_curve_run: parameters, %d interferences and outputs required", n);
    memset(res, 0, sizeof *res);
    memset(pts, 0, (size_t)n * sizeof *pts);
    asp_solver *s = NULL;
    STC_CALL(asp_solver_create(p, o, delta[n - 1], &s));
    asp_solver_info(s, &res->info);
    stc_status st = STC_OK;
    while (res->n < n && st == STC_OK) {
        asp_curve_point *c = &pts[res->n];
        curve_point(s, delta[res->n], c);
        st = c->status;
        if (st == STC_OK && cb) cb(ctx, s, res->n);
        res->n++;
    }
    /* after the whole curve (or a point sampled as one, sample_elastic),
     * loaded on past its end (axisymmetric: +5 % of the run; the 3D curve's
     * tail costs +48 %, so it keeps the one-sided end): the estimate uses
     * increments on both sides of every point */
    if (st == STC_OK && (n > 1 || (o && o->sample_elastic)) && res->info.dim == 2) {
        res->tail = asp_solver_load_tail(s, NULL);
        if (res->tail != STC_OK)
            snprintf(res->tail_reason, sizeof res->tail_reason, "%s", stc_errmsg());
    }
    for (int i = 0; i < res->n; i++) {
        asp_solver_P_smooth(s, pts[i].pt.delta, &pts[i].P_smooth);
        asp_solver_A_smooth(s, pts[i].pt.delta, &pts[i].A_smooth);
    }
    asp_solver_destroy(&s);
    if (st != STC_OK) return STC_FAIL(st, "%s", pts[res->n - 1].reason);
    return STC_OK;
}

/* Elastic-plastic P(δ) lies below Hertz, so δ(P) above its guess: twice
 * the guess (capped at the small-strain limit) holds it. */
static double wide_delta_max(const stc_params *p, double P)
{
    stc_material su;
    stc_params_materials(p, &su, NULL);
    return fmin(2.0 * asp_hertz_delta_guess(P, su.E, su.nu, p->R), 0.01 * p->R);
}

/* The axisymmetric model (level 0) at δ or brought to P: within 0.3 % of
 * the converged load in a second or two.  It sizes a load-controlled 3D
 * run's mesh (asp_shear_preload) and places the edge band
 * (asp_options_edge). */
static stc_status axisym_preload(const stc_params *p, const asp_options *o, double delta,
                                 double P, double dmax, asp_point *pt)
{
    asp_options ao;
    asp_options_default(&ao);
    ao.geom = ASP_GEOM_AXISYM, ao.mesh_level = 0;
    ao.contact = o->contact, ao.no_separation = o->no_separation;
    ao.return_map = o->return_map, ao.threads = o->threads;
    asp_solver *a = NULL;
    stc_status st = asp_solver_create(p, &ao, dmax, &a);
    if (st == STC_OK)
        st = P > 0.0 ? asp_solver_load_to_P(a, P, 1e-3, pt) : asp_solver_load(a, delta, pt);
    asp_solver_destroy(&a);
    return st;
}

stc_status asp_options_edge(const stc_params *p, asp_options *o, double delta, double P)
{
    if (o->edge_refine <= 0 || o->edge_a0 > 0.0) return STC_OK;
    STC_CHECK((delta > 0.0) != (P > 0.0), STC_EINVAL,
              "edge band: delta = %g mm, P = %g N: give one of them (> 0)", delta, P);
    asp_point pt;
    STC_CALL(axisym_preload(p, o, delta, P, P > 0.0 ? wide_delta_max(p, P) : delta, &pt));
    o->edge_a0 = pt.a;
    return STC_OK;
}

stc_status asp_shear_preload(const stc_params *p, const asp_options *o, double delta, double P,
                             asp_solver **out, asp_point *pt)
{
    STC_CHECK(out && pt, STC_EINVAL, "asp_shear_preload: outputs required");
    *out = NULL;
    STC_CHECK((delta > 0.0) != (P > 0.0), STC_EINVAL,
              "preload: delta = %g mm, P = %g N: give one of them (> 0)", delta, P);
    double wide = P > 0.0 ? wide_delta_max(p, P) : delta, dmax = delta;
    asp_options eo = *o;
    if (P > 0.0) {
        /* A load-controlled 3D run is meshed for 1.1 times the axisymmetric
         * model's δ(P) (the 3D mesh reads P within about 1 % of it), so its
         * contact gets the elements a run at that δ gets.  Meshed for twice
         * the Hertz guess instead, the contact had about a quarter fewer
         * elements across (WSP 3 ωc: a_max / a 1.91 against 1.39).  The wide
         * size if the axisymmetric run fails.  The same run places an edge
         * band. */
        asp_point ap;
        stc_status ast = axisym_preload(p, o, 0.0, P, wide, &ap);
        int band = eo.edge_refine > 0 && !(eo.edge_a0 > 0.0);
        if (ast == STC_OK) {
            dmax = fmin(1.1 * ap.delta, wide);
            if (band) eo.edge_a0 = ap.a;
        } else if (band) {
            return ast; /* the band has no a0 to sit at: the axisymmetric run's reason */
        } else {
            stc_error_clear(); /* answered by the wide size */
            dmax = wide;
        }
    } else {
        STC_CALL(asp_options_edge(p, &eo, delta, 0.0));
    }
    o = &eo;
    asp_solver *s = NULL;
    STC_CALL(asp_solver_create(p, o, dmax, &s));
    stc_status st = P > 0.0 ? asp_solver_load_to_P(s, P, 1e-3, pt) : asp_solver_load(s, delta, pt);
    if (st != STC_OK && dmax < wide) { /* not reached within the sized mesh: the wide one */
        asp_solver_destroy(&s);
        stc_error_clear();
        STC_CALL(asp_solver_create(p, o, wide, &s));
        st = asp_solver_load_to_P(s, P, 1e-3, pt);
    }
    if (st != STC_OK) {
        asp_solver_destroy(&s);
        return st;
    }
    *out = s;
    return STC_OK;
}
