/* Adaptive Gauss–Kronrod quadrature without GSL's error handler (srf_quad.h).
 * QUADPACK's QAG (Piessens, de Doncker-Kapenga, Überhuber & Kahaner 1983,
 * routine dqage) around GSL's Gauss–Kronrod rules. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_integration.h>

#include "srf_quad.h"

/* QUADPACK's roundoff tests: a bisection that leaves the estimate unchanged
 * (relative 1e-5) but not its error (>= 99 %) ROUND_SAME times, or that
 * increases the error ROUND_UP times after the first ROUND_UP_FROM. */
#define ROUND_SAME 6
#define ROUND_UP 20
#define ROUND_UP_FROM 10

struct srf_quad {
    int limit;
    double *lo, *hi, *r, *e; /* [limit] subintervals: bounds, estimate, error */
};

typedef void qk_rule(const gsl_function *f, double a, double b, double *result,
                     double *abserr, double *resabs, double *resasc);

srf_quad *srf_quad_alloc(int limit)
{
    srf_quad *w = limit >= 1 ? calloc(1, sizeof *w) : NULL;
    if (!w) return NULL;
    w->limit = limit;
    w->lo = malloc((size_t)limit * sizeof *w->lo);
    w->hi = malloc((size_t)limit * sizeof *w->hi);
    w->r = malloc((size_t)limit * sizeof *w->r);
    w->e = malloc((size_t)limit * sizeof *w->e);
    if (!w->lo || !w->hi || !w->r || !w->e) srf_quad_free(w), w = NULL;
    return w;
}

void srf_quad_free(srf_quad *w)
{
    if (!w) return;
    free(w->lo);
    free(w->hi);
    free(w->r);
    free(w->e);
    free(w);
}

const char *srf_quad_strerror(srf_quad_status s)
{
    switch (s) {
    case SRF_QUAD_OK: return "success";
    case SRF_QUAD_MAXITER: return "exceeded max number of iterations";
    case SRF_QUAD_ROUNDOFF: return "roundoff error";
    case SRF_QUAD_SINGULAR: return "apparent singularity detected";
    }
    return "unknown status";
}

/* f on [a, ∞) as a function of t in (0, 1]: x = a + (1 − t)/t, dx = dt/t². */
typedef struct { const gsl_function *f; double a; } tail_ctx;

static double tail(double t, void *u)
{
    const tail_ctx *c = u;
    double x = c->a + (1 - t) / t;
    return (GSL_FN_EVAL(c->f, x) / t) / t;
}

/* A bisection [a1, b2] at a2 at the resolution of doubles (dqage). */
static int too_small(double a1, double a2, double b2)
{
    double tmp = (1 + 100 * DBL_EPSILON) * (fabs(a2) + 1000 * DBL_MIN);
    return fabs(a1) <= tmp && fabs(b2) <= tmp;
}

static int worst(const srf_quad *w, int n)
{
    int k = 0;
    for (int i = 1; i < n; i++)
        if (w->e[i] > w->e[k]) k = i;
    return k;
}

srf_quad_status srf_quad_integrate(srf_quad *w, const gsl_function *f, double a, double b,
                                   double epsrel, double *result, double *abserr)
{
    qk_rule *rule = gsl_integration_qk21;
    tail_ctx tc = {f, a};
    gsl_function ft = {tail, &tc};
    if (isinf(b)) f = &ft, a = 0.0, b = 1.0, rule = gsl_integration_qk15;

    double r0, e0, resabs, resasc;
    rule(f, a, b, &r0, &e0, &resabs, &resasc);
    *result = r0;
    *abserr = e0;
    double tol = epsrel * fabs(r0);
    if (e0 <= 50 * DBL_EPSILON * resabs && e0 > tol) return SRF_QUAD_ROUNDOFF;
    if ((e0 <= tol && e0 != resasc) || e0 == 0.0) return SRF_QUAD_OK;
    if (w->limit == 1) return SRF_QUAD_MAXITER;

    srf_quad_status st = SRF_QUAD_OK;
    double area = r0, errsum = e0;
    int n = 1, k = 0, round_same = 0, round_up = 0;
    w->lo[0] = a, w->hi[0] = b, w->r[0] = r0, w->e[0] = e0;
    for (int it = 1; it < w->limit; it++) {
        double a1 = w->lo[k], b2 = w->hi[k], m = 0.5 * (a1 + b2), ri = w->r[k], ei = w->e[k];
        double r1, e1, abs1, asc1, r2, e2, abs2, asc2;
        rule(f, a1, m, &r1, &e1, &abs1, &asc1);
        rule(f, m, b2, &r2, &e2, &abs2, &asc2);
        double r12 = r1 + r2, e12 = e1 + e2;
        /* the change of each sum, then the sum (GSL's QAG rounds alike) */
        errsum += e12 - ei;
        area += r12 - ri;
        if (asc1 != e1 && asc2 != e2) {
            if (fabs(ri - r12) <= 1e-5 * fabs(r12) && e12 >= 0.99 * ei) round_same++;
            if (it >= ROUND_UP_FROM && e12 > ei) round_up++;
        }
        tol = epsrel * fabs(area);
        if (errsum > tol) {
            if (round_same >= ROUND_SAME || round_up >= ROUND_UP) st = SRF_QUAD_ROUNDOFF;
            if (too_small(a1, m, b2)) st = SRF_QUAD_SINGULAR;
        }
        /* the half with the larger error takes slot k, the other is appended
         * (QUADPACK's order, which the final sum follows) */
        int big = e2 > e1;
        w->lo[k] = big ? m : a1, w->hi[k] = big ? b2 : m;
        w->r[k] = big ? r2 : r1, w->e[k] = big ? e2 : e1;
        w->lo[n] = big ? a1 : m, w->hi[n] = big ? m : b2;
        w->r[n] = big ? r1 : r2, w->e[n] = big ? e1 : e2;
        n++;
        if (st != SRF_QUAD_OK || errsum <= tol) break;
        k = worst(w, n);
    }
    double sum = 0.0;
    for (int i = 0; i < n; i++) sum += w->r[i];
    *result = sum;
    *abserr = errsum;
    if (st == SRF_QUAD_OK && errsum > tol) st = SRF_QUAD_MAXITER;
    return st;
}
