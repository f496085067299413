/* Load stepping of the asperity FE model: the flat advanced in increments
 * of δ to a requested interference (asp_solver_load), on past the meshed
 * maximum (asp_solver_load_tail), or to a requested normal load
 * (asp_solver_load_to_P, with checkpoints); the step limits, the commit of
 * a converged increment and the cut-back of a failed one.  Separate from
 * the increment itself (newton.c) and from the tangential ramp (shear.c),
 * which steps ux instead of δ.  Design: docs/design.md §3.3, §4.7.
 *
 * Loading: increments in δ; while all is elastic under slip they jump to
 * the predicted first yield and just past it; past yield at least four per
 * surface node entering the contact (so the sawtooth of P(δ) is sampled
 * evenly for asp_solver_P_smooth), stick at most one element of contact
 * growth; grown after easy convergence and halved on failure (cut-back).
 * Predictor: the last converged increment, scaled; nodes the predicted
 * surface pushes through the flat are all made active before the first
 * solve.  Every failure ends with a reason in the message.
 *
 * Target for the axisymmetric slip curve to 60 ωc: P_smooth within 0.5 % of
 * the level-3 curve in < 1 s.  The P_smooth error is set by how the
 * node-entry sawtooth is sampled, not monotone in n, and has three parts
 * (curve3d helper, against level 3, n = 6..12):
 *   - a mid-curve (22-38 ωc) bias, the same for every n and ~1/steps per
 *     node (-1.1 | -0.55 | -0.35 | -0.2 % at 2 | 4 | 6 | 8): the radial
 *     return's first-order error in the increment, not the sampling; the
 *     midpoint return (the default, j2.c) leaves -0.15 .. -0.2 %;
 *   - the end point, -0.8 .. +1.9 % at 60 ωc whatever the steps with a
 *     one-sided window: loading on to 1.5 δ_max (asp_solver_load_tail, the
 *     CLI does it for axisymmetric curves) gives it a two-sided one (against
 *     a level-3 curve loaded to 120 ωc, 60 ωc: +0.21 .. +0.32 %);
 *   - 1 ωc, +0.46 .. +0.80 % without the next two measures: first yield,
 *     ~6 elements across that contact (+0.33 % on a mesh sized to it alone)
 *     plus where its edge falls.  The elastic node entries are sampled
 *     before a curve point (asp_options.sample_elastic, step_limit) and the
 *     surface between a_min and a_max is sized to arc length / n (mesh.c).
 * With all of them the max error over the 12 points for n = 6..12 is 0.29
 * 0.46 0.26 0.22 0.23 0.16 0.24 % (1 ωc +0.10 .. +0.26 %), level 0 in 0.6 s:
 * the target is met (docs/design.md §2.3, §3.3).  Tried and not robust:
 * windows 1.5x and 3x, loading 15 % past the end (0.37-0.86 %), dithered
 * steps (0.52-1.37 %).
 *
 * 3D (speed3d): a factorization costs ~50 triangular solves there, so the
 * Newton steps are solved by PCG preconditioned with the last factor
 * (Newton-Krylov, linsolve.c); level-0 slip curve to 60 ωc: the same
 * 160 Newton iterations and answers, 160 -> 15 factorizations + 1334 PCG
 * iterations, 91 -> 38 s on the shared machine (CPU 96 -> 37 s).  With 2
 * increments per node entry in 3D (steps_per_node): 31 increments, 126
 * Newton, 15 factorizations, 1113 PCG, 157 element loops, 33 s wall, 32 s
 * CPU (OMP_WAIT_POLICY=passive: 29-31 s, the idle thread stops spinning
 * during the serial PCG).  The level-0 3D curve is 1.2-6 % below the
 * converged one (4 elements across the final contact, no small-δ grading;
 * 1 contact node at 1 ωc: -33 %).
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"

/* Increments per surface node entering the contact past yield (step_limit;
 * asp_options.steps_per_node overrides).  Stick: 1 (P at 10 ωc, t/R 0.025,
 * Eco/Esu 2, level 1 moved 0.27 % from 1 to 4 per node, at 1.8x the cost).
 * Slip, 3D: 2.  Level-0 curve 1:60:12 ωc against the axisymmetric level-3
 * P_smooth, steps/node 4 | 2 | 1.5: 49 | 31 | 20 increments, 37 | 31 | 21 s
 * CPU on the shared 2-core machine; max |P_smooth| shift from 4 to 2 is
 * 0.55 % (6 ωc; 0.3-0.4 % elsewhere), to 1.5 2.1 %, against a level-0
 * discretization error of -1.2 % (60 ωc) to -6 % (6 ωc) (curve3d helper). */
#define ASP_STEPS_PER_NODE 4.0
#define ASP_STEPS_PER_NODE_3D 2.0
#define ASP_STEPS_PER_NODE_STICK 1.0

/* Increment that lands just below (σvm/Y < 0.97) or just past the first
 * yield of layer k predicted by its elastic trend σvm ∝ δ^m: m = ½ exactly
 * for a homogeneous elastic sphere (Hertz; Johnson, Contact Mechanics,
 * 1985, §4.2), otherwise the local exponent of the last two elastic
 * increments.  Brackets the yield within about 2.5 % in two increments
 * instead of creeping up on it. */
static double yield_aim(const asp_solver *s, int k)
{
    const asp_ytrack *t = &s->yt[k];
    double f = s->pt.vm_over_Y[k];
    if (t->y.reached || f <= 0.0 || s->delta <= 0.0) return INFINITY;
    double m = 0.5;
    if (t->n == 2 && t->f[1] > t->f[0] && t->d[1] > t->d[0])
        m = fmin(fmax(log(t->f[1] / t->f[0]) / log(t->d[1] / t->d[0]), 0.25), 1.0);
    double dy = s->delta * pow(1.0 / f, 1.0 / m);
    if (f < 0.97) return 0.985 * dy - s->delta;
    return fmax(1.01 * dy - s->delta, 0.005 * s->delta);
}

/* Largest increment from δ.  Elastic frictionless contact is path
 * independent, so while everything is elastic it jumps (the active set does
 * the rest): first to half the closed-form first-yield estimate, then to the
 * predicted yield (yield_aim).  Otherwise the contact may grow by about one
 * surface element per increment under stick (a node's stick position is
 * taken when it touches) and three under slip. */
static double steps_per_node(const asp_solver *s)
{
    if (s->opt.steps_per_node > 0.0) return s->opt.steps_per_node;
    if (s->opt.contact == ASP_CONTACT_STICK) return ASP_STEPS_PER_NODE_STICK;
    return s->dim == 3 ? ASP_STEPS_PER_NODE_3D : ASP_STEPS_PER_NODE;
}

/* Element size at the contact edge of radius a: two zones (axisymmetric),
 * or growing with the distance (graded 3D shells). */
static double edge_size(const asp_solver *s, double a)
{
    return s->graded ? fmin(fmax(a * s->h / s->a_max, s->h0), s->h) : a < s->a_min ? s->h0 : s->h;
}

/* target: the δ asp_solver_load is loading to. */
static double step_limit(const asp_solver *s, double target, int *aimed)
{
    int elastic = s->pt.plastic_points == 0;
    double lim = INFINITY;
    for (int k = 0; k < 2; k++) lim = fmin(lim, yield_aim(s, k));
    *aimed = lim < INFINITY;
    if (s->opt.contact == ASP_CONTACT_SLIP && elastic) {
        /* sample_elastic: from the start of the target's P_smooth window on,
         * steps_per_node increments per node entry (Hertz: a² = R' δ, a node
         * enters every Δδ = 2 a h / R') */
        if (s->delta <= 0.0) {
            double first = 0.5 * s->omega_est;
            return s->opt.sample_elastic ? fmin(first, target / (1.05 * ASP_SMOOTH_W)) : first;
        }
        if (s->opt.sample_elastic) {
            double w0 = target / (1.05 * ASP_SMOOTH_W);
            double a = s->pt.a > 0.0 ? s->pt.a : sqrt(s->Rp * s->delta);
            lim = fmin(lim, s->delta < w0 * (1 - 1e-9)
                                ? w0 - s->delta
                                : 2.0 * a * edge_size(s, a) / (steps_per_node(s) * s->Rp));
        }
        /* at most x4 per step: the trend is unreliable on a few-node contact */
        return fmax(fmin(lim, 3.0 * s->delta), 0.005 * s->delta);
    }
    /* past yield: P(δ) is a sawtooth with one tooth per surface node that
     * enters (asp_contact.c); a node enters every Δδ ≈ a h / R' (a² ∝ R' δ).
     * steps_per_node() increments per tooth sample it evenly for
     * asp_solver_P_smooth (fewer, landing just after the entries where
     * Newton is slow, biased it by -1.5 % on mesh level 0; with 4: within
     * 0.4 % of the finest mesh at level 1) */
    double a = fmin(fmax(s->pt.a, 0.0), sqrt(2.0 * s->Rp * s->delta));
    double hc = edge_size(s, a);
    double spn = steps_per_node(s);
    if (!elastic) lim = fmin(lim, a * hc / (spn * s->Rp));
    /* stick: the contact grows by at most about one surface element */
    if (s->opt.contact == ASP_CONTACT_STICK) {
        double ag = sqrt(2.0 * s->Rp * s->delta);
        lim = fmin(lim, ((ag + hc) * (ag + hc) - ag * ag) / (2.0 * s->Rp));
    }
    return lim;
}

static void commit(asp_solver *s, double delta, const asp_nstat *ns)
{
    size_t nq = (size_t)s->mesh->nelem * s->nqp;
    for (int i = 0; i < s->ndof; i++) s->du_last[i] = s->u[i] - s->u_conv[i];
    memcpy(s->u_conv, s->u, (size_t)s->ndof * sizeof *s->u);
    memcpy(s->st_old, s->st_new, nq * sizeof *s->st_old);
    s->dlast = delta - s->delta;
    s->delta = delta;
    s->pt.increments++;
    s->pt.newton_iterations += ns->iters;
    s->pt.factorizations += ns->facts;
    s->pt.active_set_passes += ns->passes;
    asp_contact_results(s, &s->pt);
    asp_yield_track(s, &s->pt);
    asp_history_push(s, delta, s->pt.P, s->pt.A);
}

/* The next increment's end: the step (grown or halved so far) within the
 * step limit, no sliver before the target unless the step brackets a
 * first yield (*at_yield). */
static double next_delta(asp_solver *s, double target, int *at_yield)
{
    int aimed;
    double lim = step_limit(s, target, &aimed);
    if (s->step <= 0.0) s->step = lim;
    double dnew = fmin(target, s->delta + fmin(s->step, lim));
    *at_yield = aimed && lim < s->step;
    if (target - dnew < 0.2 * fmin(s->step, lim) && !*at_yield) dnew = target;
    return dnew;
}

/* A failed increment to dnew: its work counted, the converged state and
 * the active set (cs0, cst0) restored, the step halved. */
static void cut_back(asp_solver *s, double dnew, const asp_nstat *ns, const unsigned char *cs0,
                     const double *cst0)
{
    s->pt.newton_iterations += ns->iters;
    s->pt.factorizations += ns->facts;
    s->pt.active_set_passes += ns->passes;
    memcpy(s->u, s->u_conv, (size_t)s->ndof * sizeof *s->u);
    memcpy(s->cs, cs0, (size_t)s->ncand);
    memcpy(s->cstick, cst0, (size_t)s->ncand * 2 * sizeof *cst0);
    s->step = 0.5 * (dnew - s->delta);
    s->pt.cutbacks++;
}

/* The cumulative counters of the element loop and the linear solver into
 * the converged point. */
static void count_work(asp_solver *s)
{
    double t_asm;
    asp_asm_work(s->as, &s->pt.assemblies, &t_asm);
    asp_ls_stats ls;
    asp_ls_get_stats(s->ls, &ls);
    s->pt.krylov_iterations = ls.krylov_iterations;
}

stc_status asp_solver_load(asp_solver *s, double delta, asp_point *out)
{
    STC_CHECK(delta >= s->delta && delta <= s->delta_max * (1 + 1e-12), STC_EINVAL,
              "delta = %g mm: must be in [%g, %g] (current, meshed maximum)", delta, s->delta,
              s->delta_max);
    unsigned char *cs0 = malloc((size_t)s->ncand);
    double *cst0 = malloc((size_t)s->ncand * 2 * sizeof *cst0);
    if (!cs0 || !cst0) {
        free(cs0), free(cst0);
        return STC_FAIL(STC_ENOMEM, "solver: out of memory");
    }
    double t0 = omp_get_wtime();
    stc_status st = STC_OK;
    int cuts = 0;
    while (s->delta < delta * (1 - 1e-14)) {
        int at_yield;
        double dnew = next_delta(s, delta, &at_yield);
        asp_nstat ns = {0, 0, 0, ASP_OUTCOME_NONE};
        memcpy(cs0, s->cs, (size_t)s->ncand);
        memcpy(cst0, s->cstick, (size_t)s->ncand * 2 * sizeof *cst0);
        /* predictor: the last increment scaled to this Δδ */
        double pred = s->dlast > 0.0 ? (dnew - s->delta) / s->dlast : 0.0;
        st = asp_newton_increment(s, dnew, pred, &ns);
        if (st == STC_OK) {
            commit(s, dnew, &ns);
            /* a step shortened to bracket a yield does not shrink the next */
            if (!at_yield) s->step = ns.iters <= 6 ? 1.5 * s->dlast : s->dlast;
            cuts = 0;
            continue;
        }
        cut_back(s, dnew, &ns, cs0, cst0);
        if (++cuts > s->opt.max_cutbacks) {
            char why[512];
            snprintf(why, sizeof why, "%s", stc_errmsg());
            st = STC_FAIL(STC_ENOCONV, "%s (%d halvings) reached at δ = %g mm: %s",
                          asp_outcome_str(ASP_OUTCOME_CUTBACK_LIMIT), s->opt.max_cutbacks,
                          s->delta, why);
            break;
        }
        st = STC_OK;
    }
    free(cs0), free(cst0);
    s->pt.wall_s += omp_get_wtime() - t0;
    count_work(s);
    if (out) *out = s->pt;
    return st;
}

/* How far asp_solver_load_tail loads past the meshed maximum.  At the end of
 * a curve the P_smooth window (δ/2 .. 2 δ) is one-sided and its estimate
 * takes the phase of the last node-entry tooth.  Measured on the slip curve
 * 1:60:12 ωc, level 0 (n = 6), against level 3 loaded to 120 ωc (two level-3
 * meshes agree within 0.06 %): error at 60 / 54.6 ωc +0.69 / +0.56 % without
 * a tail; with a tail to 1.25 / 1.5 / 1.75 / 2 x: -0.31 / +0.31 / +0.14 /
 * +0.15 % at 60 ωc, 42 -> 46 / 49 / 51 / 54 increments.  1.5 keeps the
 * contact inside the fine zone (a ~ 1.22 a(δ_max) < 1.25 a_max axisymmetric)
 * and the tooth phase averaged (n = 6..12: +0.19 .. +0.35 % at 60 ωc). */
#define ASP_SMOOTH_TAIL 1.5

stc_status asp_solver_load_tail(asp_solver *s, asp_point *out)
{
    double target = fmin(ASP_SMOOTH_TAIL * s->delta_max, 0.01 * s->par.R);
    if (!(target > s->delta)) {
        if (out) *out = s->pt;
        return STC_OK;
    }
    double meshed = s->delta_max;
    s->delta_max = target;
    stc_status st = asp_solver_load(s, target, out);
    s->delta_max = meshed;
    return st;
}

/* ---- load control ---------------------------------------------------------- */

/* A copy of the converged normal-step state (the solver loads forward only). */
typedef struct ckpt {
    int valid;
    double delta, dlast, step;
    asp_point pt;
    asp_ytrack yt[2];
    int nh;
    double *u, *du, *cst;
    asp_qp_state *st;
    unsigned char *cs;
} ckpt;

static stc_status ck_save(asp_solver *s, ckpt *c)
{
    size_t nq = (size_t)s->mesh->nelem * s->nqp, nd = (size_t)s->ndof, nc = (size_t)s->ncand;
    if (!c->u) {
        c->u = malloc(nd * sizeof *c->u), c->du = malloc(nd * sizeof *c->u);
        c->cst = malloc(2 * nc * sizeof *c->u), c->st = malloc(nq * sizeof *c->st);
        c->cs = malloc(nc);
    }
    STC_CHECK(c->u && c->du && c->cst && c->st && c->cs, STC_ENOMEM,
              "load control: out of memory for a checkpoint");
    memcpy(c->u, s->u_conv, nd * sizeof *c->u);
    memcpy(c->du, s->du_last, nd * sizeof *c->u);
    memcpy(c->cst, s->cstick, 2 * nc * sizeof *c->u);
    memcpy(c->st, s->st_old, nq * sizeof *c->st);
    memcpy(c->cs, s->cs, nc);
    c->delta = s->delta, c->dlast = s->dlast, c->step = s->step;
    c->pt = s->pt, c->nh = s->nh;
    memcpy(c->yt, s->yt, sizeof c->yt);
    c->valid = 1;
    return STC_OK;
}

/* Back to the checkpoint; the cumulative counters keep the work done since. */
static void ck_restore(asp_solver *s, const ckpt *c)
{
    size_t nq = (size_t)s->mesh->nelem * s->nqp, nd = (size_t)s->ndof, nc = (size_t)s->ncand;
    memcpy(s->u_conv, c->u, nd * sizeof *c->u);
    memcpy(s->u, c->u, nd * sizeof *c->u);
    memcpy(s->du_last, c->du, nd * sizeof *c->u);
    memcpy(s->cstick, c->cst, 2 * nc * sizeof *c->u);
    memcpy(s->st_old, c->st, nq * sizeof *c->st);
    memcpy(s->cs, c->cs, nc);
    asp_point keep = s->pt;
    s->delta = c->delta, s->dlast = c->dlast, s->step = c->step;
    s->pt = c->pt, s->nh = c->nh;
    memcpy(s->yt, c->yt, sizeof s->yt);
    s->pt.increments = keep.increments, s->pt.cutbacks = keep.cutbacks;
    s->pt.newton_iterations = keep.newton_iterations;
    s->pt.factorizations = keep.factorizations;
    s->pt.active_set_passes = keep.active_set_passes, s->pt.wall_s = keep.wall_s;
    s->k_fresh = 0;
}

static void ck_free(ckpt *c)
{
    free(c->u), free(c->du), free(c->cst), free(c->st), free(c->cs);
    memset(c, 0, sizeof *c);
}

typedef struct lctx {
    asp_solver *s;
    ckpt lo;       /* largest δ evaluated with P below the target */
    double target; /* N */
    int backward;
} lctx;

/* Go to δ (restoring the checkpoint if δ is behind the solver), return P. */
static stc_status load_at(lctx *c, double delta)
{
    asp_solver *s = c->s;
    if (delta < s->delta) {
        STC_CHECK(c->lo.valid && c->lo.delta <= delta, STC_ENOCONV,
                  "load control: delta = %g mm is below the checkpoint (%g mm)", delta,
                  c->lo.valid ? c->lo.delta : 0.0);
        ck_restore(s, &c->lo);
        c->backward++;
    }
    STC_CALL(asp_solver_load(s, delta, NULL));
    if (s->pt.P < c->target && s->delta > c->lo.delta) STC_CALL(ck_save(s, &c->lo));
    return STC_OK;
}

static stc_status load_cb(void *ctx, double delta, double *P)
{
    lctx *c = ctx;
    STC_CALL(load_at(c, delta));
    *P = c->s->pt.P;
    return STC_OK;
}

stc_status asp_solver_load_to_P(asp_solver *s, double P_target, double rel_tol, asp_point *out)
{
    STC_CHECK(P_target > 0.0 && isfinite(P_target), STC_EINVAL,
              "load = %g N: target normal load must be > 0", P_target);
    STC_CHECK(rel_tol > 0.0 && rel_tol < 0.1, STC_EINVAL,
              "load tolerance = %g: must be in (0, 0.1)", rel_tol);
    STC_CHECK(!s->hooks, STC_EINVAL, "load control: not after a tangential ramp");
    STC_CHECK(s->pt.P < P_target, STC_EINVAL,
              "load = %g N: the solver is already at P = %g N (it loads forward only)",
              P_target, s->pt.P);
    stc_material su;
    stc_params_materials(&s->par, &su, NULL);
    lctx c = {s, {0}, P_target, 0};
    asp_find_delta_opts fo;
    asp_find_delta_opts_default(&fo);
    fo.tol = rel_tol;
    fo.delta_max = s->delta_max;
    asp_find_delta_result fr;
    stc_status st = ck_save(s, &c.lo);
    double guess = fmin(asp_hertz_delta_guess(P_target, su.E, su.nu, s->Rp), s->delta_max);
    if (st == STC_OK) st = asp_find_delta(load_cb, &c, P_target, guess, &fo, &fr);
    /* the last evaluation need not be the answer's */
    if (st == STC_OK && s->delta != fr.delta) st = load_at(&c, fr.delta);
    ck_free(&c.lo);
    if (out) *out = s->pt;
    return st;
}
