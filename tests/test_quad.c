/* Adaptive Gauss–Kronrod quadrature of the GW sums (surface/quad.c):
 * closed-form integrals within the returned error bound (finite, endpoint
 * singularity, semi-infinite), the same answers as GSL's QAG on finite
 * ranges (the algorithm it replaces), failure statuses with the estimate
 * still set, and GSL's error handler never called. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "srf_quad.h"

#define LIMIT 1000

static int handler_calls;
static void counting_handler(const char *reason, const char *file, int line, int gsl_errno)
{
    (void)reason, (void)file, (void)line, (void)gsl_errno;
    handler_calls++;
}

static int setup(void **state)
{
    (void)state;
    handler_calls = 0;
    gsl_set_error_handler(counting_handler);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    gsl_set_error_handler(NULL);
    return handler_calls != 0; /* a GSL call reported through the handler */
}

static double f_sqrt(double x, void *p) { (void)p; return sqrt(x); }
static double f_gauss(double x, void *p) { (void)p; return exp(-0.5 * x * x); }
static double f_power(double x, void *p) { return pow(x, -*(double *)p); }
/* a peak and a kink, like a GW integrand at a model breakpoint */
static double f_peak(double x, void *p)
{
    (void)p;
    return 1.0 / (1e-3 + (x - 0.3) * (x - 0.3)) + fabs(x - 0.71) * exp(x);
}

typedef struct {
    const char *name;
    gsl_function f;
    double a, b, exact;
} case_t;

static double five_halves = 2.5;

static void test_closed_forms(void **state)
{
    (void)state;
    const case_t cases[] = {
        {"x^(1/2) on [0, 1]", {f_sqrt, NULL}, 0.0, 1.0, 2.0 / 3.0},
        {"exp(-x^2/2) on [0, inf)", {f_gauss, NULL}, 0.0, INFINITY, sqrt(M_PI / 2)},
        {"exp(-x^2/2) on [-1.5, inf)", {f_gauss, NULL}, -1.5, INFINITY,
         sqrt(M_PI / 2) * (1.0 + erf(1.5 / M_SQRT2))},
        {"x^(-5/2) on [1, inf)", {f_power, &five_halves}, 1.0, INFINITY, 1.0 / 1.5},
    };
    srf_quad *w = srf_quad_alloc(LIMIT);
    assert_non_null(w);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const case_t *c = &cases[i];
        double r, e;
        srf_quad_status s = srf_quad_integrate(w, &c->f, c->a, c->b, 1e-10, &r, &e);
        double err = fabs(r - c->exact);
        printf("  %-28s %.15g (exact %.15g): error %.1e <= bound %.1e, %s\n", c->name, r,
               c->exact, err, e, srf_quad_strerror(s));
        assert_int_equal(s, SRF_QUAD_OK);
        assert_true(err <= e + 4e-16 * fabs(c->exact));
        assert_true(e <= 1e-10 * fabs(r));
    }
    srf_quad_free(w);
}

/* On a finite range the driver is QUADPACK's QAG with the 21-point rule, as
 * gsl_integration_qag(GSL_INTEG_GAUSS21) was for the KDE sums: the same
 * bisections and the same roundings, hence the same numbers. */
static void test_same_as_gsl_qag(void **state)
{
    (void)state;
    const case_t cases[] = {
        {"x^(1/2) on [0, 1]", {f_sqrt, NULL}, 0.0, 1.0, 0},
        {"exp(-x^2/2) on [-3, 2]", {f_gauss, NULL}, -3.0, 2.0, 0},
        {"peak and kink on [0, 1]", {f_peak, NULL}, 0.0, 1.0, 0},
    };
    srf_quad *w = srf_quad_alloc(LIMIT);
    gsl_integration_workspace *gw = gsl_integration_workspace_alloc(LIMIT);
    assert_true(w && gw);
    gsl_error_handler_t *old = gsl_set_error_handler_off(); /* GSL's QAG may report */
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const case_t *c = &cases[i];
        for (double eps = 1e-6; eps >= 1e-12; eps *= 1e-3) {
            double r, e, rg, eg;
            srf_quad_status s = srf_quad_integrate(w, &c->f, c->a, c->b, eps, &r, &e);
            int sg = gsl_integration_qag(&c->f, c->a, c->b, 0.0, eps, LIMIT, GSL_INTEG_GAUSS21,
                                         gw, &rg, &eg);
            printf("  %-24s epsrel %.0e: %.17g (%s) vs GSL %.17g (%s), %zu subintervals\n",
                   c->name, eps, r, srf_quad_strerror(s), rg, gsl_strerror(sg), gw->size);
            assert_true((s == SRF_QUAD_OK) == (sg == GSL_SUCCESS));
            assert_true(r == rg && e == eg);
        }
    }
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(gw);
    srf_quad_free(w);
}

/* Out of reach: a status, with the estimate and its bound still honest. */
static void test_failure_statuses(void **state)
{
    (void)state;
    gsl_function f = {f_sqrt, NULL};
    double r, e;
    srf_quad *w1 = srf_quad_alloc(1), *w = srf_quad_alloc(LIMIT);
    assert_true(w1 && w);
    assert_int_equal(srf_quad_integrate(w1, &f, 0.0, 1.0, 1e-10, &r, &e), SRF_QUAD_MAXITER);
    assert_true(fabs(r - 2.0 / 3.0) <= e);
    srf_quad_status s = srf_quad_integrate(w, &f, 0.0, 1.0, 1e-15, &r, &e);
    printf("  x^(1/2) at epsrel 1e-15: %s, error %.1e <= bound %.1e\n", srf_quad_strerror(s),
           fabs(r - 2.0 / 3.0), e);
    assert_int_not_equal(s, SRF_QUAD_OK);
    assert_true(fabs(r - 2.0 / 3.0) <= e + 4e-16);
    double p = 1.0; /* ∫_1^∞ 1/x diverges */
    gsl_function inv = {f_power, &p};
    s = srf_quad_integrate(w, &inv, 1.0, INFINITY, 1e-10, &r, &e);
    printf("  1/x on [1, inf): %s, result %g, bound %g\n", srf_quad_strerror(s), r, e);
    assert_int_not_equal(s, SRF_QUAD_OK);
    assert_null(srf_quad_alloc(0));
    srf_quad_free(NULL);
    srf_quad_free(w1);
    srf_quad_free(w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_closed_forms, setup, teardown),
        cmocka_unit_test(test_same_as_gsl_qag),
        cmocka_unit_test_setup_teardown(test_failure_statuses, setup, teardown),
    };
    return cmocka_run_group_tests_name("quad", tests, NULL, NULL);
}
