/* Adaptive Gauss–Kronrod quadrature of the GW sums (gw.c) that reports by
 * its return value alone (not installed).
 *
 * GSL's adaptive drivers (QAG, QAGS, QAGIU) report a tolerance they could
 * not reach through gsl_error, i.e. through GSL's error handler, which is
 * process-wide and aborts by default; a library cannot switch it off around
 * its own calls without racing the other threads that do the same.  GSL's
 * Gauss–Kronrod rules themselves (gsl_integration_qk21, _qk15) evaluate and
 * report nothing, and are used here.  The driver is QUADPACK's QAG
 * (Piessens et al. 1983, dqage): bisect the subinterval with the largest
 * error estimate until the estimates sum to at most epsrel |result|, with
 * QUADPACK's roundoff and small-interval stops.  A range [a, ∞) is mapped to
 * (0, 1] by x = a + (1 − t)/t (QUADPACK's dqagi). */
#ifndef STICTION_SRF_QUAD_H
#define STICTION_SRF_QUAD_H

#include <gsl/gsl_math.h> /* gsl_function */

typedef enum srf_quad_status {
    SRF_QUAD_OK = 0,      /* error estimate within the tolerance */
    SRF_QUAD_MAXITER = 1, /* the subinterval limit was reached first */
    SRF_QUAD_ROUNDOFF = 2,/* roundoff keeps the estimate from improving */
    SRF_QUAD_SINGULAR = 3 /* a subinterval reached the resolution of doubles */
} srf_quad_status;

typedef struct srf_quad srf_quad;

/* Workspace for up to `limit` >= 1 subintervals.  Returns new, or NULL when
 * out of memory. */
srf_quad *srf_quad_alloc(int limit);
void srf_quad_free(srf_quad *w); /* NULL is allowed */

/* ∫_a^b f(x) dx for a < b, b finite (21-point rule) or +∞ (15-point rule on
 * the mapped range).  *result and *abserr (estimate and error bound) are
 * set whatever the status.  One workspace serves one call at a time. */
srf_quad_status srf_quad_integrate(srf_quad *w, const gsl_function *f, double a, double b,
                                   double epsrel, double *result, double *abserr);

/* Words for a status, e.g. "roundoff error"; a static string. */
const char *srf_quad_strerror(srf_quad_status s);

#endif
