/* Sliding-inception detector, ramp controller and load control
 * (asperity/slide.c) on synthetic curves with known answers:
 * Cattaneo–Mindlin Q(ux) of a Hertz contact (shear and BKE stiffness
 * criteria), an asymptotic (tanh) curve, a knee onto an exact plateau, a
 * softening curve, no inception at all, a Mindlin curve whose secants jump
 * by a fixed share whatever the increment; and asp_find_delta on Hertz and
 * on a power law with a kink. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "stc_check.h"
#include "tangential.h"

/* Reference-grid steel (E = 200 GPa, ν = 0.32, Y = 200 MPa), a = 0.05 mm. */
static const double E = 200000.0, NU = 0.32, A = 0.05, P0 = 1.0;

static asp_slide_setup setup(void)
{
    asp_slide_setup s = {E / (2 * (1 + NU)), NU, A, 200.0 / sqrt(3.0), P0};
    return s;
}

/* A synthetic ramp: Q, P, slipping area fraction at ux. */
typedef struct curve {
    int kind;       /* 0 Mindlin, 1 tanh, 2 knee+plateau, 3 softening, 4 linear,
                       5 knee+plateau with a stuck core (plastic plateau),
                       6 knee, then still rising at 0.2 of the first slope,
                       7 Mindlin along a path whose secant is the tangent times
                         1 + noise, 1 - noise, ... from the second increment on */
    double Qm, us;  /* force scale (N), displacement scale (mm) */
    double noise;   /* kind 7 */
    double ux_prev, Q_prev; /* kind 7: the path so far */
    int n;
} curve;

static void eval(curve *c, double ux, double *Q, double *P, double *frac)
{
    double x = ux / c->us;
    *P = P0 * (1.0 - 0.02 * fmin(x, 1.0)); /* P changes under shear */
    switch (c->kind) {
    case 7: { /* as a node entering or sticking moves a ramp's secant by its
               * force over the increment, whatever the increment's size */
        double xm = 0.5 * (ux + c->ux_prev) / c->us;
        double kt = 1.5 * c->Qm / c->us * sqrt(fmax(1.0 - fmin(xm, 1.0), 0.0));
        double f = c->n == 0 ? 1.0 : (c->n % 2 ? 1.0 + c->noise : 1.0 - c->noise);
        *Q = c->Q_prev + kt * f * (ux - c->ux_prev);
        *frac = 1.0 - pow(fmax(1.0 - *Q / c->Qm, 0.0), 2.0 / 3.0);
        c->ux_prev = ux, c->Q_prev = *Q, c->n++;
        break;
    }
    case 0: /* Cattaneo–Mindlin (Johnson 1985 §7.2): Q = μP[1 - (1 - ux/ux_s)^{3/2}],
             * stick radius c = a (1 - Q/μP)^{1/3} */
        *Q = c->Qm * (1.0 - pow(1.0 - fmin(x, 1.0), 1.5));
        *frac = 1.0 - pow(1.0 - *Q / c->Qm, 2.0 / 3.0);
        break;
    case 1:
        *Q = c->Qm * tanh(x);
        *frac = fmin(1.0, 0.5 * x);
        break;
    case 2:
        *Q = c->Qm * (1.0 - pow(1.0 - fmin(x, 1.0), 3.0));
        *frac = fmin(1.0, x);
        break;
    case 5:
        *Q = c->Qm * (1.0 - pow(1.0 - fmin(x, 1.0), 3.0));
        *frac = 0.6 * fmin(1.0, x);
        break;
    case 6: /* initial slope 3 Qm/us; past the knee 0.6 Qm/us */
        *Q = c->Qm * (1.0 - pow(1.0 - fmin(x, 1.0), 3.0) + 0.6 * fmax(x - 1.0, 0.0));
        *frac = fmin(1.0, x);
        break;
    case 3:
        *Q = c->Qm * x * exp(1.0 - x);
        *frac = 0.5 * fmin(x, 1.0);
        break;
    default:
        *Q = c->Qm * x;
        *frac = 0.0;
    }
}

typedef struct run_out {
    asp_slide_result r;
    int n, first_within_1pc; /* increments, first increment with Q >= 0.99 Qmax_true */
    double KT1_over_KT0, ux_last, du_last, du_prev;
} run_out;

static run_out run(curve *c, const asp_slide_params *par, double Qtrue)
{
    asp_slide_setup su = setup();
    asp_slide *d = NULL;
    assert_int_equal(asp_slide_create(par, &su, &d), STC_OK);
    double ux = 0.0, Q, P, f, Q1 = 0.0, du1 = 0.0;
    run_out o = {0};
    o.first_within_1pc = -1;
    while (asp_slide_next(d) > 0.0) {
        double du = asp_slide_next(d);
        ux += du;
        eval(c, ux, &Q, &P, &f);
        if (o.n == 0) Q1 = Q, du1 = du;
        o.n++;
        if (o.first_within_1pc < 0 && Q >= 0.99 * Qtrue) o.first_within_1pc = o.n;
        o.du_prev = o.du_last, o.du_last = du;
        asp_slide_push(d, ux, Q, P, f, 100);
        assert_true(o.n < 1000);
    }
    o.ux_last = ux;
    o.KT1_over_KT0 = Q1 / du1 / asp_slide_KT0(&su);
    asp_slide_get(d, &o.r);
    asp_slide_destroy(&d);
    assert_null(d);
    return o;
}

/* Mindlin curve with μP = τc π a² (the contact's full-slip force): then
 * ux_s = 3 μP / (16 a G*) = 1.5 ux_e. */
static curve mindlin(void)
{
    asp_slide_setup su = setup();
    curve c = {.kind = 0, .Qm = su.tau_c * M_PI * A * A, .us = 1.5 * asp_slide_ux_elastic(&su)};
    return c;
}

static void test_mindlin_shear(void **state)
{
    (void)state;
    curve c = mindlin();
    run_out o = run(&c, NULL, c.Qm);
    printf("Mindlin, shear: %s\n  Qmax/muP = %.6f, ux/ux_s = %.4f, P/P0 = %.4f, %d increments "
           "(Q within 1%% of muP after %d), last ux/ux_s = %.4f, KT_1/KT0 = %.4f\n",
           o.r.reason, o.r.Q_max / c.Qm, o.r.ux / c.us, o.r.P / P0, o.n, o.first_within_1pc,
           o.ux_last / c.us, o.KT1_over_KT0);
    assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
    assert_non_null(strstr(o.r.reason, "shear criterion"));
    assert_true(fabs(o.r.Q_max / c.Qm - 1.0) < 1e-3);
    /* inception is the first full-slip point: at or just after ux_s */
    assert_true(o.r.ux >= c.us * (1 - 1e-12) && o.r.ux < 1.04 * c.us); /* 2 confirm_frac */
    assert_true(fabs(o.r.P - P0 * 0.98) < 1e-12 && fabs(o.r.mu_s - o.r.Q_max / o.r.P) < 1e-15);
    /* the flat stops soon after: no more than n_flat confirmation steps */
    assert_true(o.ux_last < 1.05 * o.r.ux);
    assert_true(o.n <= 30 && o.first_within_1pc <= 20);
    /* the first increment measures Mindlin's initial stiffness */
    assert_true(o.KT1_over_KT0 > 0.98 && o.KT1_over_KT0 <= 1.0);
}

/* BKE on the Mindlin curve: the tangent stiffness is K_T0 sqrt(1 - x), so
 * KT/KT_1 = α at x* = 1 - (α KT_1/KT_0)². */
static void test_mindlin_stiffness(void **state)
{
    (void)state;
    curve c = mindlin();
    asp_slide_params p;
    asp_slide_params_default(&p);
    p.criterion = ASP_SLIDE_STIFFNESS;
    for (int k = 0; k < 2; k++) {
        p.alpha = k == 0 ? 0.1 : 0.3;
        run_out o = run(&c, &p, c.Qm);
        double r = p.alpha * o.KT1_over_KT0, xs = 1.0 - r * r;
        double Qs = c.Qm * (1.0 - pow(1.0 - xs, 1.5));
        printf("Mindlin, stiffness alpha = %.1f: %s\n  ux/ux_s = %.4f (analytic %.4f, last "
               "increment %.4f), Q/Q(x*) = %.5f, KT_i/KT_1 = %.3f, %d increments\n",
               p.alpha, o.r.reason, o.r.ux / c.us, xs, o.du_last / c.us, o.r.Q_max / Qs,
               o.r.KT_ratio, o.n);
        assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
        assert_true(o.r.KT_ratio <= p.alpha);
        /* secants lag the tangent: KT_i <= α KT_1 puts the tangent crossing
         * before ux_i, KT_{i-1} > α KT_1 puts it after ux_{i-2} */
        double lo = (o.r.ux - o.du_last - o.du_prev) / c.us;
        printf("  crossing bracket [%.4f, %.4f]\n", lo, o.r.ux / c.us);
        assert_true(o.r.ux / c.us >= xs - 1e-9 && lo <= xs + 1e-9);
        assert_true(fabs(o.r.Q_max / Qs - 1.0) < 1e-2);
        assert_true(o.n <= 40);
    }
}

/* BKE on a ramp whose secants scatter by ±30 % whatever the increment (the
 * Mindlin tangent times 1.3, 0.7, 1.3, ...): the bracket's increments must not
 * chase that scatter down to nothing, so inception comes where a low secant
 * first reaches α, x = 1 - (α / 0.7)², in a few dozen increments. */
static void test_noisy_stiffness(void **state)
{
    (void)state;
    curve c = mindlin();
    c.kind = 7, c.noise = 0.3;
    asp_slide_params p;
    asp_slide_params_default(&p);
    p.criterion = ASP_SLIDE_STIFFNESS;
    run_out o = run(&c, &p, c.Qm);
    double xs = 1.0 - pow(p.alpha / (1.0 - c.noise), 2.0);
    printf("noisy secants, stiffness alpha = %.1f: %s\n  ux/ux_s = %.4f (a low secant reaches "
           "alpha from %.4f), KT_i/KT_1 = %.3f, %d increments, last %.4f\n", p.alpha,
           o.r.reason, o.r.ux / c.us, xs, o.r.KT_ratio, o.n, o.du_last / c.us);
    assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
    assert_true(o.r.KT_ratio <= p.alpha);
    assert_true(o.r.ux / c.us >= xs - 1e-9 && o.r.ux / c.us <= 1.0 + 0.1);
    assert_true(o.n <= 60);
}

static void test_asymptotic(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    curve c = {.kind = 1, .Qm = 0.8 * su.tau_c * M_PI * A * A, .us = asp_slide_ux_elastic(&su)};
    run_out o = run(&c, NULL, c.Qm);
    printf("tanh: %s\n  Qmax/Qm = %.5f, ux/u0 = %.3f, %d increments (1%% after %d)\n",
           o.r.reason, o.r.Q_max / c.Qm, o.r.ux / c.us, o.n, o.first_within_1pc);
    assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
    /* flat_tol = 0.01 on tanh: 1 - Q/Qm ≈ flat_tol/2 */
    assert_true(o.r.Q_max / c.Qm > 0.99 && o.r.Q_max / c.Qm <= 1.0);
    assert_true(o.n <= 30);
}

static void test_plateau(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    curve c = {.kind = 2, .Qm = 0.7 * su.tau_c * M_PI * A * A,
               .us = 2.0 * asp_slide_ux_elastic(&su)};
    run_out o = run(&c, NULL, c.Qm);
    printf("knee + plateau: %s\n  Qmax/Qm = %.6f, ux/u_knee = %.4f, last ux/u_knee = %.4f, "
           "%d increments (1%% after %d)\n",
           o.r.reason, o.r.Q_max / c.Qm, o.r.ux / c.us, o.ux_last / c.us, o.n,
           o.first_within_1pc);
    assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
    assert_true(fabs(o.r.Q_max / c.Qm - 1.0) < 1e-3);
    assert_true(o.r.ux >= c.us * (1 - 1e-12) && o.r.ux < 1.05 * c.us);
    assert_true(o.ux_last < 1.1 * c.us && o.n <= 30);
}

static void test_plastic_plateau(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    curve c = {.kind = 5, .Qm = 0.7 * su.tau_c * M_PI * A * A,
               .us = 2.0 * asp_slide_ux_elastic(&su)};
    run_out o = run(&c, NULL, c.Qm);
    printf("plastic plateau: %s\n  Qmax/Qm = %.6f, ux/u_knee = %.4f, last ux/u_knee = %.4f, "
           "%d increments\n", o.r.reason, o.r.Q_max / c.Qm, o.r.ux / c.us, o.ux_last / c.us, o.n);
    assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
    assert_non_null(strstr(o.r.reason, "plastic plateau"));
    assert_true(fabs(o.r.Q_max / c.Qm - 1.0) < 1e-3);
    assert_true(o.ux_last < 1.5 * c.us);
}

/* KT_after, the stiffness left past inception: ~0 on a flat plateau; on a
 * Q that still rises once the whole contact is at its limit (the solver's
 * full_tol 0.5, shear.c) it reads that slope, 0.2 KT_1 here.  mu_s_ux_slope,
 * d ln(Q/P) / d ln ux from inception to the last point: 0 on the plateau (P
 * is constant past the knee too); on the rising one the secant of
 * ln(1 + 0.6 (x - 1)) against ln x, 0.6 at the knee x = 1 and rising. */
static void test_rising_after(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    asp_slide_params p;
    asp_slide_params_default(&p);
    p.full_tol = 0.5;
    curve c = {.kind = 2, .Qm = 0.7 * su.tau_c * M_PI * A * A,
               .us = 2.0 * asp_slide_ux_elastic(&su)};
    run_out f = run(&c, &p, c.Qm);
    c.kind = 6;
    run_out r = run(&c, &p, c.Qm);
    printf("stiffness after inception: plateau %.4f, rising %.4f (%s)\n", f.r.KT_after,
           r.r.KT_after, r.r.reason);
    assert_int_equal(f.r.state, ASP_SLIDE_INCEPTION);
    assert_int_equal(r.r.state, ASP_SLIDE_INCEPTION);
    assert_true(fabs(f.r.KT_after) < 0.01);
    assert_true(fabs(r.r.KT_after - 0.2) < 0.02);
    assert_non_null(strstr(f.r.reason, "stopped rising"));
    assert_non_null(strstr(r.r.reason, "still rising"));
    assert_int_equal(f.r.q_rising, 0); /* the flag a caller reads */
    assert_int_equal(r.r.q_rising, 1);
    double xi = r.r.ux / c.us, xl = r.ux_last / c.us;
    double want = log((1.0 + 0.6 * (xl - 1.0)) / (1.0 + 0.6 * (xi - 1.0))) / log(xl / xi);
    printf("d ln mu_s / d ln ux past inception: plateau %.2e, rising %.6f (secant of the "
           "curve from x = %.4f to %.4f: %.6f)\n", f.r.mu_s_ux_slope, r.r.mu_s_ux_slope, xi, xl,
           want);
    assert_true(xi >= 1.0 && xl > xi);
    assert_true(fabs(f.r.mu_s_ux_slope) < 1e-9);
    assert_true(fabs(r.r.mu_s_ux_slope - want) < 1e-9);
    /* between the derivative 0.6 x / (0.4 + 0.6 x) at the two ends */
    assert_true(r.r.mu_s_ux_slope > 0.6 && r.r.mu_s_ux_slope < 0.6 * xl / (0.4 + 0.6 * xl));
}

/* The ramp's solver finds no equilibrium past a point (cut-back limit):
 * with the whole contact at its limit and Q nearly flat there, that point is
 * inception (a plastic mechanism), Q_max the largest Q so far; with part of
 * the contact stuck, or Q still rising steeply, or under the stiffness
 * criterion, nothing is declared.  The ramp of docs/design.md §4.4
 * (WSP 3 wc, N = 12, rows): limit fractions 0.95 / 0.97 / 1.00, Q 25.48 /
 * 25.57 / 25.63 N, KT/KT_1 0.006 over the last increment. */
static void test_mechanism(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    asp_slide_params p;
    asp_slide_params_default(&p);
    p.full_tol = 0.5;
    double P0 = su.P0, k1 = 1e4;
    const double fr[4][2] = {{0.95, 0.97}, {0.97, 1.0}, {0.97, 1.0}, {0.97, 1.0}};
    const double dq[4] = {0.006, 0.006, 0.8, 0.006}; /* last KT / KT_1 */
    for (int c = 0; c < 4; c++) {
        asp_slide *d = NULL;
        asp_slide_params q = p;
        if (c == 3) q.criterion = ASP_SLIDE_STIFFNESS, q.alpha = 1e-3;
        assert_int_equal(asp_slide_create(&q, &su, &d), STC_OK);
        double du = 1e-5;
        asp_slide_push(d, du, k1 * du, P0, 0.0, 10);           /* KT_1 = k1 */
        asp_slide_push(d, 2 * du, k1 * du * 1.5, P0, fr[c][0], 11);
        asp_slide_push(d, 3 * du, k1 * du * (1.5 + dq[c]), P0, fr[c][1], 12);
        int got = asp_slide_mechanism(d, "CHOLMOD factorization: matrix not positive definite");
        asp_slide_result r;
        asp_slide_get(d, &r);
        printf("mechanism case %d: %d, %s\n", c, got, r.reason);
        if (c == 1) {
            assert_int_equal(got, 1);
            assert_int_equal(r.state, ASP_SLIDE_INCEPTION);
            assert_int_equal(r.index, 3);
            assert_true(fabs(r.Q_max - k1 * du * (1.5 + dq[c])) < 1e-12);
            assert_true(fabs(r.mu_s - r.Q_max / P0) < 1e-15);
            assert_non_null(strstr(r.reason, "plastic mechanism"));
            assert_non_null(strstr(r.reason, "not positive"));
            assert_int_equal(asp_slide_mechanism(d, "again"), 0); /* once */
        } else {
            assert_int_equal(got, 0);
            assert_int_equal(r.state, ASP_SLIDE_RUNNING);
        }
        asp_slide_destroy(&d);
    }
}

static void test_softening(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    curve c = {.kind = 3, .Qm = 0.5 * su.tau_c * M_PI * A * A,
               .us = 2.0 * asp_slide_ux_elastic(&su)};
    run_out o = run(&c, NULL, c.Qm);
    printf("softening: %s\n  Qmax/Qm = %.5f at ux/u_peak = %.3f, %d increments\n", o.r.reason,
           o.r.Q_max / c.Qm, o.r.ux / c.us, o.n);
    assert_int_equal(o.r.state, ASP_SLIDE_INCEPTION);
    assert_non_null(strstr(o.r.reason, "passed a maximum"));
    assert_true(o.r.Q_max / c.Qm > 0.995 && o.r.Q_max / c.Qm <= 1.0);
}

static void test_gives_up(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    curve c = {.kind = 4, .Qm = su.tau_c * M_PI * A * A, .us = asp_slide_ux_elastic(&su)};
    run_out o = run(&c, NULL, c.Qm);
    printf("linear: %s after %d increments\n", o.r.reason, o.n);
    assert_int_equal(o.r.state, ASP_SLIDE_GAVE_UP);
    assert_non_null(strstr(o.r.reason, "ux-max"));
    assert_true(fabs(o.ux_last - 20.0 * asp_slide_ux_elastic(&su)) < 1e-9 * o.ux_last);
    /* a non-increasing ux is refused with a reason */
    asp_slide *d = NULL;
    assert_int_equal(asp_slide_create(NULL, &su, &d), STC_OK);
    assert_int_equal(asp_slide_push(d, 1e-6, 1e-3, P0, 0.0, 10), ASP_SLIDE_RUNNING);
    assert_int_equal(asp_slide_push(d, 1e-6, 2e-3, P0, 0.0, 10), ASP_SLIDE_GAVE_UP);
    asp_slide_result r;
    asp_slide_get(d, &r);
    assert_non_null(strstr(r.reason, "the ramp must increase"));
    assert_true(asp_slide_next(d) == 0.0);
    asp_slide_destroy(&d);
}

static void test_invalid(void **state)
{
    (void)state;
    asp_slide_setup su = setup();
    asp_slide_params p;
    asp_slide *d = NULL;
    asp_slide_params_default(&p);
    p.alpha = 1.5;
    stc_error_clear();
    assert_int_equal(asp_slide_create(&p, &su, &d), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "alpha = 1.5: stiffness ratio must be in (0, 1)"));
    assert_null(d);
    su.a = 0.0;
    assert_int_equal(asp_slide_create(NULL, &su, &d), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "a = 0 mm"));
    su = setup();
    su.tau_c = -1;
    assert_int_equal(asp_slide_create(NULL, &su, &d), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "tau-c = -1 MPa"));
}

/* ---- load control ---- */

typedef struct pl {
    double c, dk, m2;  /* P = c δ^1.5 below δk, continued with exponent m2 above */
    double fail_above; /* callback fails beyond this δ (0: never) */
    int calls;
} pl;

static stc_status pl_load(void *ctx, double delta, double *P)
{
    pl *p = ctx;
    p->calls++;
    if (p->fail_above > 0.0 && delta > p->fail_above)
        return STC_FAIL(STC_ENOCONV, "Newton: 30 iterations at δ = %g mm", delta);
    *P = delta < p->dk ? p->c * pow(delta, 1.5)
                       : p->c * pow(p->dk, 1.5) * pow(delta / p->dk, p->m2);
    return STC_OK;
}

static void test_find_delta_hertz(void **state)
{
    (void)state;
    double R = 10.0, Es = E / (1 - NU * NU);
    pl h = {4.0 / 3.0 * Es * sqrt(R), INFINITY, 1.5, 0.0, 0};
    asp_find_delta_opts o;
    asp_find_delta_opts_default(&o);
    o.delta_max = 0.01;
    double dtrue = 3e-4, Pt = h.c * pow(dtrue, 1.5);
    double g = asp_hertz_delta_guess(Pt, E, NU, R);
    assert_true(fabs(g / dtrue - 1.0) < 1e-12);
    asp_find_delta_result r;
    const double guesses[3] = {1.0, 5.0, 0.1};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(asp_find_delta(pl_load, &h, Pt, guesses[k] * g, &o, &r), STC_OK);
        printf("Hertz, guess x%.1f: delta/delta_true = %.6f, %d solves (%d backward)\n",
               guesses[k], r.delta / dtrue, r.solves, r.backward);
        assert_true(fabs(r.P / Pt - 1.0) <= o.tol);
        assert_true(r.solves <= (k == 0 ? 1 : 3));
    }
}

static void test_find_delta_kink(void **state)
{
    (void)state;
    double R = 10.0, Es = E / (1 - NU * NU), dk = 1e-4;
    pl p = {4.0 / 3.0 * Es * sqrt(R), dk, 1.1, 0.0, 0};
    asp_find_delta_opts o;
    asp_find_delta_opts_default(&o);
    o.delta_max = 0.01;
    const double targets[5] = {0.5, 0.999, 1.001, 3.0, 60.0}; /* δ/δk */
    int worst = 0;
    for (int k = 0; k < 5; k++) {
        double dt = targets[k] * dk, Pt;
        pl_load(&p, dt, &Pt);
        asp_find_delta_result r;
        double g = asp_hertz_delta_guess(Pt, E, NU, R);
        assert_int_equal(asp_find_delta(pl_load, &p, Pt, g, &o, &r), STC_OK);
        printf("kinked power law, delta/delta_k = %g: found %.5f (Hertz guess %.4f), "
               "%d solves (%d backward)\n", targets[k], r.delta / dk, g / dk, r.solves,
               r.backward);
        assert_true(fabs(r.P / Pt - 1.0) <= o.tol);
        worst = r.solves > worst ? r.solves : worst;
    }
    assert_true(worst <= 6);
}

static void test_find_delta_failures(void **state)
{
    (void)state;
    double R = 10.0, Es = E / (1 - NU * NU);
    pl p = {4.0 / 3.0 * Es * sqrt(R), INFINITY, 1.5, 2e-4, 0};
    asp_find_delta_opts o;
    asp_find_delta_opts_default(&o);
    o.delta_max = 0.01;
    asp_find_delta_result r;
    double Pt = p.c * pow(3e-4, 1.5);
    stc_error_clear();
    assert_int_equal(asp_find_delta(pl_load, &p, Pt, 2.5e-4, &o, &r), STC_ENOCONV);
    printf("failing callback: %s\n", stc_errmsg());
    assert_non_null(strstr(stc_errmsg(), "load control: P(delta = 0.00025 mm) failed: Newton"));
    p.fail_above = 0.0;
    o.delta_max = 1e-4;
    assert_int_equal(asp_find_delta(pl_load, &p, Pt, 1e-5, &o, &r), STC_ERANGE);
    assert_non_null(strstr(stc_errmsg(), "above P(delta_max = 0.0001 mm)"));
    assert_int_equal(asp_find_delta(pl_load, &p, -1.0, 1e-5, &o, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "load = -1 N"));
    o.delta_max = 0.0;
    assert_int_equal(asp_find_delta(pl_load, &p, Pt, 1e-5, &o, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "delta_max = 0 mm"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mindlin_shear),     cmocka_unit_test(test_mindlin_stiffness),
        cmocka_unit_test(test_noisy_stiffness),
        cmocka_unit_test(test_asymptotic),        cmocka_unit_test(test_plateau),
        cmocka_unit_test(test_plastic_plateau),   cmocka_unit_test(test_mechanism),
        cmocka_unit_test(test_softening),
        cmocka_unit_test(test_gives_up),          cmocka_unit_test(test_rising_after),
        cmocka_unit_test(test_invalid),           cmocka_unit_test(test_find_delta_hertz),
        cmocka_unit_test(test_find_delta_kink),   cmocka_unit_test(test_find_delta_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
