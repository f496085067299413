/* Sliding-inception detector, ux ramp controller, and load control.
 *
 * Detector: fed with the accepted points of the tangential ramp (ux, Q, P,
 * slipping area fraction, contact nodes), it decides inception by
 *   shear (default; Wu, Shi & Polycarpou 2012): the whole contact slips
 *     (slipping AREA fraction >= 1 - slip_tol) and Q has stopped rising
 *     (|KT| / KT_1 <= flat_tol over the next n_flat increments); or
 *   stiffness (Brizmer, Kligerman & Etsion 2007, thesis eqs. 3.17–3.18):
 *     KT_i = (Q_i - Q_{i-1}) / (ux_i - ux_{i-1}),  KT_i / KT_1 <= α.
 * Either way a Q that passes a maximum and falls for n_flat increments ends
 * the ramp at the maximum; under the shear criterion a Q that stays flat
 * for n_flat + 2 increments while part of the contact still sticks (a
 * plastic plateau) ends it too, with that reason.  Qmax, ux, P at inception and the reason in
 * words come back in asp_slide_result.
 *
 * Ramp control: the first increment is a fraction of the elastic estimate
 * ux_e = τc π a² / K_T0 (Mindlin's stuck-contact stiffness K_T0 = 8 G a /
 * (2 - ν) for an elastic sphere on a rigid flat; Mindlin 1949, Johnson 1985
 * §7.2), so KT_1 measures the initial stiffness within ~first_frac/4
 * (Cattaneo–Mindlin curvature).  Then each increment is sized so that the
 * secant stiffness changes by about `bend` KT_1 per increment: large where
 * Q(ux) is linear, small where it bends.  Near the BKE threshold the
 * change per increment is held to α/10 so the crossing is bracketed
 * tightly; once the whole contact slips (shear criterion) only short
 * confirmation increments follow, so the flat is not pushed further than
 * the answer needs.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stc_check.h"
#include "tangential.h"

void asp_slide_params_default(asp_slide_params *p)
{
    p->criterion = ASP_SLIDE_SHEAR;
    p->alpha = 0.1;         /* BKE 2007 */
    p->slip_tol = 1e-3;
    p->flat_tol = 0.01;
    p->full_tol = 0.01;
    p->n_flat = 2;
    p->bend = 0.08;
    p->first_frac = 0.05;
    p->confirm_frac = 0.02;
    p->grow_max = 2.0;
    p->du_max_frac = 0.5;
    p->max_increments = 200;
    p->ux_max = 0.0;
}

double asp_slide_KT0(const asp_slide_setup *su)
{
    return 8.0 * su->G * su->a / (2.0 - su->nu); /* Johnson 1985 §7.2, rigid flat */
}

double asp_slide_ux_elastic(const asp_slide_setup *su)
{
    return su->tau_c * M_PI * su->a * su->a / asp_slide_KT0(su);
}

struct asp_slide {
    asp_slide_params par;
    asp_slide_setup su;
    double ux_e, ux_max;
    int n, cap;                  /* points stored (index 0: ux = 0) */
    double *ux, *Q, *P, *frac;   /* [cap] */
    int *nc;                     /* [cap] */
    double KT1;                  /* secant stiffness of the first increment */
    asp_slide_result res;
};

static stc_status check_params(const asp_slide_params *p)
{
    STC_CHECK(p->criterion == ASP_SLIDE_SHEAR || p->criterion == ASP_SLIDE_STIFFNESS,
              STC_EINVAL, "criterion = %d: must be shear (0) or stiffness (1)", (int)p->criterion);
    STC_CHECK(p->alpha > 0.0 && p->alpha < 1.0, STC_EINVAL,
              "alpha = %g: stiffness ratio must be in (0, 1) (BKE: 0.1)", p->alpha);
    STC_CHECK(p->slip_tol >= 0.0 && p->slip_tol < 0.5, STC_EINVAL,
              "slip-tol = %g: must be in [0, 0.5)", p->slip_tol);
    STC_CHECK(p->flat_tol > 0.0 && p->flat_tol < 0.5, STC_EINVAL,
              "flat-tol = %g: must be in (0, 0.5)", p->flat_tol);
    STC_CHECK(p->full_tol > 0.0 && p->full_tol <= 0.5, STC_EINVAL,
              "full-tol = %g: must be in (0, 0.5]", p->full_tol);
    STC_CHECK(p->n_flat >= 1 && p->n_flat <= 10, STC_EINVAL,
              "n-flat = %d: must be in [1, 10]", p->n_flat);
    STC_CHECK(p->bend > 0.0 && p->bend <= 0.5, STC_EINVAL, "bend = %g: must be in (0, 0.5]",
              p->bend);
    STC_CHECK(p->first_frac > 0.0 && p->first_frac <= 0.5, STC_EINVAL,
              "first-frac = %g: must be in (0, 0.5]", p->first_frac);
    STC_CHECK(p->confirm_frac > 0.0 && p->confirm_frac <= 0.5, STC_EINVAL,
              "confirm-frac = %g: must be in (0, 0.5]", p->confirm_frac);
    STC_CHECK(p->grow_max >= 1.0 && p->grow_max <= 10.0, STC_EINVAL,
              "grow-max = %g: must be in [1, 10]", p->grow_max);
    STC_CHECK(p->du_max_frac > 0.0 && isfinite(p->du_max_frac), STC_EINVAL,
              "du-max-frac = %g: must be > 0", p->du_max_frac);
    STC_CHECK(p->max_increments >= 3 && p->max_increments <= 100000, STC_EINVAL,
              "max-increments = %d: must be in [3, 100000]", p->max_increments);
    STC_CHECK(p->ux_max >= 0.0 && isfinite(p->ux_max), STC_EINVAL,
              "ux-max = %g mm: must be >= 0 (0 = automatic)", p->ux_max);
    return STC_OK;
}

static stc_status check_setup(const asp_slide_setup *s)
{
    STC_CHECK(s->G > 0.0 && isfinite(s->G), STC_EINVAL, "G = %g MPa: must be > 0", s->G);
    STC_CHECK(s->nu > -1.0 && s->nu < 0.5, STC_EINVAL, "nu = %g: must be in (-1, 0.5)", s->nu);
    STC_CHECK(s->a > 0.0 && isfinite(s->a), STC_EINVAL,
              "a = %g mm: contact radius after the normal step must be > 0", s->a);
    STC_CHECK(s->tau_c > 0.0 && isfinite(s->tau_c), STC_EINVAL,
              "tau-c = %g MPa: must be > 0", s->tau_c);
    STC_CHECK(s->P0 > 0.0 && isfinite(s->P0), STC_EINVAL, "P0 = %g N: preload must be > 0",
              s->P0);
    return STC_OK;
}

stc_status asp_slide_create(const asp_slide_params *par, const asp_slide_setup *su,
                            asp_slide **out)
{
    *out = NULL;
    asp_slide_params p;
    if (par) p = *par;
    else asp_slide_params_default(&p);
    STC_CALL(check_params(&p));
    STC_CALL(check_setup(su));
    asp_slide *d = calloc(1, sizeof *d);
    STC_CHECK(d, STC_ENOMEM, "slide: out of memory");
    d->par = p;
    d->su = *su;
    d->ux_e = asp_slide_ux_elastic(su);
    d->ux_max = p.ux_max > 0.0 ? p.ux_max : 20.0 * d->ux_e;
    d->cap = p.max_increments + 2;
    d->ux = malloc((size_t)d->cap * 4 * sizeof *d->ux);
    d->nc = malloc((size_t)d->cap * sizeof *d->nc);
    if (!d->ux || !d->nc) {
        asp_slide_destroy(&d);
        return STC_FAIL(STC_ENOMEM, "slide: out of memory");
    }
    d->Q = d->ux + d->cap, d->P = d->Q + d->cap, d->frac = d->P + d->cap;
    d->res.state = ASP_SLIDE_RUNNING;
    d->res.index = -1;
    snprintf(d->res.reason, sizeof d->res.reason, "ramp not started");
    *out = d;
    return STC_OK;
}

void asp_slide_destroy(asp_slide **d)
{
    if (!d || !*d) return;
    free((*d)->ux), free((*d)->nc);
    free(*d);
    *d = NULL;
}

/* Secant tangential stiffness between ramp points i < l. */
static double secant(const asp_slide *d, int i, int l)
{
    return (d->Q[l] - d->Q[i]) / (d->ux[l] - d->ux[i]);
}

/* Secant stiffness of increment i (from point i-1 to i), i >= 1. */
static double KT(const asp_slide *d, int i) { return secant(d, i - 1, i); }

static int peak_index(const asp_slide *d, int upto)
{
    int k = 0;
    for (int i = 1; i <= upto; i++)
        if (d->Q[i] > d->Q[k]) k = i;
    return k;
}

static asp_slide_state finish(asp_slide *d, asp_slide_state st, asp_outcome why, int i,
                              const char *fmt, double v)
{
    asp_slide_result *r = &d->res;
    r->state = st;
    r->outcome = why;
    r->index = i;
    r->Q_max = d->Q[peak_index(d, d->n - 1)];
    if (st == ASP_SLIDE_INCEPTION && d->par.criterion == ASP_SLIDE_STIFFNESS)
        r->Q_max = d->Q[i]; /* BKE: the force where the stiffness dropped */
    if (st == ASP_SLIDE_INCEPTION && d->frac[i] >= 1.0 - d->par.slip_tol)
        r->Q_max = d->Q[peak_index(d, i)]; /* full slip: not the confirmation steps */
    r->ux = d->ux[i];
    r->P = d->P[i];
    r->mu_s = r->P > 0.0 ? r->Q_max / r->P : NAN;
    r->mu_s_preload = r->Q_max / d->su.P0;
    r->slip_frac = d->frac[i];
    r->KT_ratio = i >= 1 && d->KT1 != 0.0 ? KT(d, i) / d->KT1 : 1.0;
    int l = d->n - 1;
    r->KT_after = l > i && d->KT1 != 0.0 ? secant(d, i, l) / d->KT1 : r->KT_ratio;
    int a = l > i ? i : i - 1, b = l > i ? l : i;
    r->mu_s_ux_slope = a >= 1 && d->Q[a] > 0.0 && d->Q[b] > 0.0 && d->P[a] > 0.0 &&
                               d->P[b] > 0.0 && d->ux[b] > d->ux[a]
                           ? log((d->Q[b] / d->P[b]) / (d->Q[a] / d->P[a])) /
                                 log(d->ux[b] / d->ux[a])
                           : NAN;
    r->n_contact = d->nc[i];
    snprintf(r->reason, sizeof r->reason, fmt, v);
    return st;
}

/* Q has fallen over the last n_flat increments after its maximum. */
static int passed_maximum(const asp_slide *d)
{
    int n = d->n, k = d->par.n_flat;
    if (n - 1 < k + 1) return 0;
    for (int i = n - k; i < n; i++)
        if (!(KT(d, i) < -d->par.flat_tol * d->KT1)) return 0;
    return 1;
}

/* Shear criterion: the first point i with full slip followed by n_flat
 * flat increments (Q stopped rising). */
static int shear_inception(const asp_slide *d)
{
    const asp_slide_params *p = &d->par;
    for (int i = 1; i + p->n_flat < d->n; i++) {
        if (d->frac[i] < 1.0 - p->slip_tol) continue;
        int flat = 1;
        for (int j = i + 1; j <= i + p->n_flat; j++)
            flat &= fabs(KT(d, j)) <= p->full_tol * d->KT1;
        if (flat) return i;
    }
    return -1;
}

/* Shear criterion fallback: Q flat over n_flat + 2 increments although part
 * of the contact still sticks (a plastic plateau: the junction shears in the
 * material, not at the interface).  Returns the start of the flat run. */
static int plastic_plateau(const asp_slide *d)
{
    int n = d->n, k = d->par.n_flat + 2;
    if (n - 1 < k + 1) return -1;
    for (int i = n - k; i < n; i++)
        if (!(fabs(KT(d, i)) <= d->par.flat_tol * d->KT1)) return -1;
    return n - k - 1;
}

static asp_slide_state evaluate(asp_slide *d)
{
    const asp_slide_params *p = &d->par;
    int last = d->n - 1;
    if (last < 1) return ASP_SLIDE_RUNNING;
    if (p->criterion == ASP_SLIDE_STIFFNESS) {
        if (last >= 2 && KT(d, last) <= p->alpha * d->KT1)
            return finish(d, ASP_SLIDE_INCEPTION, ASP_OUTCOME_CONVERGED, last,
                          "stiffness criterion: KT_i/KT_1 <= alpha = %g (BKE 2007)", p->alpha);
    } else {
        int i = shear_inception(d);
        if (i >= 0 && secant(d, i, last) <= p->flat_tol * d->KT1)
            return finish(d, ASP_SLIDE_INCEPTION, ASP_OUTCOME_CONVERGED, i,
                          "shear criterion: whole contact at its shear limit (fraction >= "
                          "1 - %g) and Q stopped rising (WSP 2012)", p->slip_tol);
        if (i >= 0) { /* full_tol > flat_tol: see KT_after */
            d->res.q_rising = 1;
            return finish(d, ASP_SLIDE_INCEPTION, ASP_OUTCOME_CONVERGED, i,
                          "shear criterion: whole contact at its shear limit (fraction >= "
                          "1 - %g), Q still rising past it (WSP 2012; KT_after)", p->slip_tol);
        }
        if ((i = plastic_plateau(d)) >= 0)
            return finish(d, ASP_SLIDE_INCEPTION, ASP_OUTCOME_CONVERGED, i,
                          "Q stopped rising (plastic plateau) with only %.3f of the contact "
                          "area at tau_c", d->frac[i]);
    }
    if (passed_maximum(d)) {
        int k = peak_index(d, last);
        return finish(d, ASP_SLIDE_INCEPTION, ASP_OUTCOME_CONVERGED, k,
                      "Q passed a maximum and fell for %g increments", (double)p->n_flat);
    }
    if (last >= p->max_increments)
        return finish(d, ASP_SLIDE_GAVE_UP, ASP_OUTCOME_MAX_ITERATIONS, peak_index(d, last),
                      "no inception after %g increments (max-increments)", (double)last);
    if (d->ux[last] >= d->ux_max * (1 - 1e-12))
        return finish(d, ASP_SLIDE_GAVE_UP, ASP_OUTCOME_GAVE_UP, peak_index(d, last),
                      "no inception up to ux-max = %g mm", d->ux_max);
    return ASP_SLIDE_RUNNING;
}

asp_slide_state asp_slide_push(asp_slide *d, double ux, double Q, double P, double slip_frac,
                               int n_contact)
{
    if (d->res.state != ASP_SLIDE_RUNNING) return d->res.state;
    if (d->n == 0 && ux > 0.0) { /* the ramp starts at the preload state */
        d->ux[0] = 0.0, d->Q[0] = 0.0, d->P[0] = d->su.P0, d->frac[0] = 0.0;
        d->nc[0] = n_contact;
        d->n = 1;
    }
    if (d->n > 0 && !(ux > d->ux[d->n - 1])) {
        d->res.state = ASP_SLIDE_GAVE_UP;
        d->res.outcome = ASP_OUTCOME_FAILED;
        snprintf(d->res.reason, sizeof d->res.reason,
                 "ux = %g mm pushed after ux = %g mm: the ramp must increase", ux,
                 d->ux[d->n - 1]);
        return d->res.state;
    }
    int i = d->n++;
    d->ux[i] = ux, d->Q[i] = Q, d->P[i] = P, d->frac[i] = slip_frac, d->nc[i] = n_contact;
    d->res.increments = i;
    if (i == 1) d->KT1 = KT(d, 1);
    if (i == 1 && !(d->KT1 > 0.0)) {
        finish(d, ASP_SLIDE_GAVE_UP, ASP_OUTCOME_GAVE_UP, 1,
               "first increment has KT_1 = %g N/mm <= 0", d->KT1);
        return d->res.state;
    }
    return evaluate(d);
}

int asp_slide_mechanism(asp_slide *d, const char *why)
{
    const asp_slide_params *p = &d->par;
    int last = d->n - 1;
    if (d->res.state != ASP_SLIDE_RUNNING || p->criterion != ASP_SLIDE_SHEAR || last < 2)
        return 0;
    if (d->frac[last] < 1.0 - p->slip_tol || !(KT(d, last) <= p->full_tol * d->KT1)) return 0;
    double kt = KT(d, last) / d->KT1;
    finish(d, ASP_SLIDE_INCEPTION, ASP_OUTCOME_MECHANISM, last, "mechanism", 0.0);
    snprintf(d->res.reason, sizeof d->res.reason,
             "whole contact at its shear limit, no equilibrium past it (plastic mechanism; "
             "KT/KT_1 = %.3g): %.50s", kt, why);
    return 1;
}

/* Target change of KT/KT_1 per increment. */
static double bend_target(const asp_slide *d, int last)
{
    const asp_slide_params *p = &d->par;
    double b = p->bend;
    if (p->criterion == ASP_SLIDE_STIFFNESS && KT(d, last) / d->KT1 < p->alpha + 3.0 * p->bend)
        b = fmin(b, p->alpha / 10.0); /* bracket the BKE crossing */
    return b;
}

/* Shear criterion: land just past the point where the whole contact slips
 * (linear trend of the slipping fraction), then confirm with short steps
 * once Q is flat.  The overshoot confirm_frac ux both bounds the error of
 * the inception ux and avoids creeping towards the full-slip point. */
static double shear_limit(const asp_slide *d, int last, double du)
{
    const asp_slide_params *p = &d->par;
    double fr = d->frac[last], ux = d->ux[last], eps = p->confirm_frac * ux;
    if (fabs(KT(d, last)) <= p->flat_tol * d->KT1) du = fmin(du, eps); /* Q flat: confirm */
    if (fr >= 1.0 - p->slip_tol) return du;
    double rate = (fr - d->frac[last - 1]) / (ux - d->ux[last - 1]);
    if (rate > 0.0) du = fmin(du, (1.0 - p->slip_tol - fr) / rate + eps);
    return du;
}

double asp_slide_next(const asp_slide *d)
{
    const asp_slide_params *p = &d->par;
    if (d->res.state != ASP_SLIDE_RUNNING) return 0.0;
    int last = d->n - 1;
    double dmax = p->du_max_frac * d->ux_e, du;
    if (last < 1) {
        du = p->first_frac * d->ux_e;
    } else {
        double prev = d->ux[last] - d->ux[last - 1];
        du = p->grow_max * prev;
        if (last >= 2) {
            /* secant change per increment ≈ Q'' (Δ_i + Δ_{i-1}) / 2: scale
             * the increment so the next change is about `bend` */
            double c = fabs(KT(d, last) - KT(d, last - 1)) / d->KT1;
            double span = 0.5 * (prev + d->ux[last - 1] - d->ux[last - 2]);
            if (c > 0.0) du = fmin(du, bend_target(d, last) / c * span);
            du = fmax(du, 0.25 * prev);
            /* A secant that rose is not Q bending but a node entering or
             * sticking: a jump of its force over the increment, which grows
             * as the increment shrinks, so the bracket would chase it down
             * to nothing (docs/design.md §4.4).  Not below the first
             * increment then. */
            if (p->criterion == ASP_SLIDE_STIFFNESS && KT(d, last) > KT(d, last - 1))
                du = fmax(du, p->first_frac * d->ux_e);
        }
        if (p->criterion == ASP_SLIDE_SHEAR) du = shear_limit(d, last, du);
    }
    du = fmin(du, dmax);
    du = fmax(du, 1e-6 * d->ux_e);
    return fmin(du, fmax(d->ux_max - (last >= 0 ? d->ux[last] : 0.0), 1e-6 * d->ux_e));
}

void asp_slide_get(const asp_slide *d, asp_slide_result *res)
{
    *res = d->res;
    if (d->res.state == ASP_SLIDE_RUNNING && d->n > 0) {
        int k = peak_index(d, d->n - 1);
        res->Q_max = d->Q[k];
        res->ux = d->ux[k], res->P = d->P[k];
        res->mu_s = res->P > 0.0 ? res->Q_max / res->P : NAN;
        res->mu_s_preload = res->Q_max / d->su.P0;
        res->index = k;
    }
}

/* ---- load control -------------------------------------------------------- */

void asp_find_delta_opts_default(asp_find_delta_opts *o)
{
    o->tol = 1e-3;
    o->max_solves = 20;
    o->delta_max = 0.0;
}

double asp_hertz_delta_guess(double P, double E, double nu, double R)
{
    /* rigid flat: P = (4/3) E* √R δ^{3/2} (docs/design.md §6.1) */
    double Es = E / (1.0 - nu * nu);
    return pow(3.0 * P / (4.0 * Es * sqrt(R)), 2.0 / 3.0);
}

typedef struct fd_ctx {
    asp_load_fn fn;
    void *ctx;
    double Pt, dmax_eval;
    asp_find_delta_result *res;
} fd_ctx;

/* Evaluate f(x) = ln P(e^x) - ln P_target. */
static stc_status fd_eval(fd_ctx *c, double x, double *f, double *P)
{
    double delta = exp(x);
    if (delta < c->dmax_eval) c->res->backward++;
    c->dmax_eval = fmax(c->dmax_eval, delta);
    c->res->solves++;
    stc_status st = c->fn(c->ctx, delta, P);
    if (st != STC_OK) {
        char why[400];
        snprintf(why, sizeof why, "%s", stc_errmsg());
        return STC_FAIL(st, "load control: P(delta = %g mm) failed: %s", delta, why);
    }
    STC_CHECK(*P > 0.0 && isfinite(*P), STC_ERANGE,
              "load control: P(delta = %g mm) = %g N: must be > 0", delta, *P);
    *f = log(*P / c->Pt);
    c->res->delta = delta, c->res->P = *P;
    return STC_OK;
}

stc_status asp_find_delta(asp_load_fn fn, void *ctx, double P_target, double delta0,
                          const asp_find_delta_opts *o, asp_find_delta_result *res)
{
    asp_find_delta_opts op;
    if (o) op = *o;
    else asp_find_delta_opts_default(&op);
    memset(res, 0, sizeof *res);
    STC_CHECK(P_target > 0.0 && isfinite(P_target), STC_EINVAL,
              "load = %g N: target normal load must be > 0", P_target);
    STC_CHECK(op.delta_max > 0.0 && isfinite(op.delta_max), STC_EINVAL,
              "delta_max = %g mm: must be > 0", op.delta_max);
    STC_CHECK(delta0 > 0.0 && isfinite(delta0), STC_EINVAL,
              "delta0 = %g mm: first guess must be > 0", delta0);
    STC_CHECK(op.tol > 0.0 && op.tol <= 0.1, STC_EINVAL, "tol = %g: must be in (0, 0.1]", op.tol);
    STC_CHECK(op.max_solves >= 2, STC_EINVAL, "max_solves = %d: must be >= 2", op.max_solves);
    fd_ctx c = {fn, ctx, P_target, 0.0, res};
    double xmax = log(op.delta_max), ftol = log1p(op.tol) * 0.999;
    double lo = -INFINITY, hi = INFINITY, flo = 0.0, fhi = 0.0; /* bracket f(lo) < 0 < f(hi) */
    double x = fmin(log(delta0), xmax), f = 0.0, P = 0.0, xp = NAN, fp = NAN, width_old = INFINITY;
    double m = 1.5; /* d ln P / d ln δ: Hertz */
    for (;;) {
        STC_CALL(fd_eval(&c, x, &f, &P));
        if (fabs(f) <= ftol) return STC_OK;
        if (f < 0.0) lo = x, flo = f;
        else hi = x, fhi = f;
        STC_CHECK(!(f < 0.0 && x >= xmax), STC_ERANGE,
                  "load = %g N: above P(delta_max = %g mm) = %g N; raise the meshed maximum",
                  P_target, op.delta_max, P);
        STC_CHECK(res->solves < op.max_solves, STC_ENOCONV,
                  "load control: %d solves, P = %g N for target %g N (tol %g)", res->solves, P,
                  P_target, op.tol);
        /* log-log secant through the last two points: exact for a power law */
        if (isfinite(xp) && x != xp && (f - fp) / (x - xp) > 0.0) m = (f - fp) / (x - xp);
        double xn = x - f / m;
        if (isfinite(lo) && isfinite(hi)) {
            /* safeguard: stay strictly inside the bracket and bisect when
             * the bracket stopped halving (Dekker/Brent) */
            double w = hi - lo, in = 0.02 * w;
            int bad = !(xn > lo + in && xn < hi - in) || w > 0.5 * width_old;
            if (!(xn > lo + in && xn < hi - in)) {
                /* false position between the bracket ends */
                xn = lo - flo * (hi - lo) / (fhi - flo);
                bad = !(xn > lo + in && xn < hi - in) || w > 0.5 * width_old;
            }
            if (bad) xn = 0.5 * (lo + hi);
            width_old = w;
        } else if (f < 0.0) {
            xn = fmin(fmin(xn, x + log(4.0)), xmax); /* at most x4 per try */
            if (xn <= x) xn = fmin(x + 0.1, xmax);
        } else {
            xn = fmax(xn, x - log(4.0));
        }
        xp = x, fp = f;
        x = xn;
    }
}
