/* Nodal shear-limited stick law (asperity/friction.c): consistent tangent
 * against central finite differences in stick, slip and at the transition,
 * the slip limit |f| = τc A, objectivity, the load–unload–reload hysteresis
 * against the closed-form elastic–perfectly-plastic spring, the stick-error
 * bound, and invalid parameters. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "tangential.h"

/* Steel-like coating of the reference grid: E = 200 GPa, Y = 200 MPa. */
static const double E = 200000.0, NU = 0.32, H = 1e-3, AREA = 2.5e-6;

static asp_fric_law law(void)
{
    asp_fric_law l;
    assert_int_equal(asp_fric_law_init(&l, 200.0 / sqrt(3.0), E, NU, H, ASP_FRIC_KAPPA_DEFAULT),
                     STC_OK);
    return l;
}

/* Deterministic pseudo-random numbers in [-1, 1). */
static double rnd(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffff) / 32768.0 - 1.0;
}

/* Max |K - FD| / |K|_max for central differences with step eps. */
static double fd_error(const asp_fric_law *l, const double g[2], const double s0[2], double eps)
{
    double s1[2], f[2], K[4], fp[2], fm[2], kmax = 0.0, err = 0.0;
    asp_fric_update(l, AREA, g, s0, s1, f, K, NULL);
    for (int j = 0; j < 2; j++) {
        double gp[2] = {g[0], g[1]}, gm[2] = {g[0], g[1]};
        gp[j] += eps, gm[j] -= eps;
        asp_fric_update(l, AREA, gp, s0, s1, fp, NULL, NULL);
        asp_fric_update(l, AREA, gm, s0, s1, fm, NULL, NULL);
        for (int i = 0; i < 2; i++) {
            double fd = (fp[i] - fm[i]) / (2.0 * eps);
            err = fmax(err, fabs(fd - K[2 * i + j]));
        }
    }
    for (int k = 0; k < 4; k++) kmax = fmax(kmax, fabs(K[k]));
    return err / fmax(kmax, AREA * l->kt * 1e-12);
}

static void test_tangent_fd(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt; /* elastic slip at the limit */
    unsigned seed = 7;
    double worst_st = 0.0, worst_sl = 0.0;
    for (int k = 0; k < 200; k++) {
        double s0[2] = {rnd(&seed) * 5 * gs, rnd(&seed) * 5 * gs};
        double dir = M_PI * rnd(&seed), rho = 0.9 * fabs(rnd(&seed)); /* stick: |g-s| < 0.9 gs */
        double g[2] = {s0[0] + rho * gs * cos(dir), s0[1] + rho * gs * sin(dir)};
        worst_st = fmax(worst_st, fd_error(&l, g, s0, 1e-4 * gs));
        double rs = 1.05 + 10 * fabs(rnd(&seed)); /* slip: |g-s| > 1.05 gs */
        double g2[2] = {s0[0] + rs * gs * cos(dir), s0[1] + rs * gs * sin(dir)};
        worst_sl = fmax(worst_sl, fd_error(&l, g2, s0, 1e-4 * gs));
    }
    printf("tangent vs central FD (200 random states): stick %.2e, slip %.2e\n", worst_st,
           worst_sl);
    assert_true(worst_st < 1e-7);
    assert_true(worst_sl < 1e-6);
}

/* At |t*| = τc the tangent jumps (stick -> slip): the kernel must match the
 * one-sided derivatives, and the force must be continuous. */
static void test_tangent_transition(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt, s0[2] = {0.3 * gs, -0.2 * gs}, n[2] = {0.6, 0.8};
    double eps = 1e-7 * gs, s1[2], f[2], fa[2], fb[2], Kin[4], Kout[4];
    double gi[2] = {s0[0] + (1 - 1e-9) * gs * n[0], s0[1] + (1 - 1e-9) * gs * n[1]};
    double go[2] = {s0[0] + (1 + 1e-9) * gs * n[0], s0[1] + (1 + 1e-9) * gs * n[1]};
    assert_int_equal(asp_fric_update(&l, AREA, gi, s0, s1, fa, Kin, NULL), ASP_FRIC_STICK);
    assert_int_equal(asp_fric_update(&l, AREA, go, s0, s1, fb, Kout, NULL), ASP_FRIC_SLIP);
    double jump = hypot(fb[0] - fa[0], fb[1] - fa[1]) / (AREA * l.tau_c);
    printf("force jump across the transition: %.2e tau_c A\n", jump);
    assert_true(jump < 1e-8);
    /* outward derivative along n: backward FD from the stick side equals
     * A k_t, forward FD from the slip side equals 0 (the radial direction
     * carries no stiffness once slipping) */
    double gb[2] = {gi[0] - eps * n[0], gi[1] - eps * n[1]};
    double gf[2] = {go[0] + eps * n[0], go[1] + eps * n[1]};
    asp_fric_update(&l, AREA, gb, s0, s1, f, NULL, NULL);
    double back = ((fa[0] - f[0]) * n[0] + (fa[1] - f[1]) * n[1]) / eps;
    asp_fric_update(&l, AREA, gf, s0, s1, f, NULL, NULL);
    double fwd = ((f[0] - fb[0]) * n[0] + (f[1] - fb[1]) * n[1]) / eps;
    double kin = Kin[0] * n[0] * n[0] + 2 * Kin[1] * n[0] * n[1] + Kin[3] * n[1] * n[1];
    double kout = Kout[0] * n[0] * n[0] + 2 * Kout[1] * n[0] * n[1] + Kout[3] * n[1] * n[1];
    double ref = AREA * l.kt;
    printf("radial stiffness at transition: stick side %.6f (FD %.6f), slip side %.2e "
           "(FD %.2e), in A k_t\n", kin / ref, back / ref, kout / ref, fwd / ref);
    assert_true(fabs(kin - back) < 1e-6 * ref && fabs(kin - ref) < 1e-12 * ref);
    assert_true(fabs(kout) < 1e-6 * ref && fabs(fwd) < 1e-6 * ref);
    /* the tangential (transverse) stiffness is continuous: A k_t on both sides */
    double tr[2] = {-n[1], n[0]};
    double kt_out = Kout[0] * tr[0] * tr[0] + 2 * Kout[1] * tr[0] * tr[1] + Kout[3] * tr[1] * tr[1];
    assert_true(fabs(kt_out / ref - 1.0) < 1e-8);
}

static void test_slip_limit(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt, worst = 0.0;
    unsigned seed = 3;
    for (int k = 0; k < 1000; k++) {
        double s0[2] = {rnd(&seed) * gs, rnd(&seed) * gs};
        double g[2] = {s0[0] + 1e3 * gs * rnd(&seed), s0[1] + 1e3 * gs * rnd(&seed)};
        double s1[2], f[2], K[4], ratio;
        int r = asp_fric_update(&l, AREA, g, s0, s1, f, K, &ratio);
        if (ratio <= 1.0) continue;
        assert_int_equal(r, ASP_FRIC_SLIP);
        worst = fmax(worst, fabs(hypot(f[0], f[1]) / (AREA * l.tau_c) - 1.0));
        /* the returned state is on the limit: re-evaluating it sticks at τc */
        double s2[2], f2[2];
        asp_fric_update(&l, AREA, g, s1, s2, f2, NULL, &ratio);
        assert_true(fabs(ratio - 1.0) < 1e-9);
        /* K symmetric positive semidefinite */
        double tr = K[0] + K[3];
        assert_true(K[1] == K[2] && K[0] >= -1e-15 * tr && K[3] >= -1e-15 * tr &&
                    K[0] * K[3] - K[1] * K[2] >= -1e-12 * tr * tr);
    }
    printf("slip limit: max | |f| / (tau_c A) - 1 | = %.2e\n", worst);
    assert_true(worst < 1e-14);
}

/* Rotating g and s by Q rotates f and s_new by Q and K to Q K Qᵀ. */
static void test_objectivity(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt, worst = 0.0;
    double g[2] = {2.3 * gs, -0.7 * gs}, s0[2] = {0.4 * gs, 0.1 * gs};
    double ginner[2] = {0.9 * gs, 0.2 * gs};
    for (int pass = 0; pass < 2; pass++) {
        const double *gg = pass ? ginner : g;
        double s1[2], f[2], K[4];
        asp_fric_update(&l, AREA, gg, s0, s1, f, K, NULL);
        for (int k = 1; k < 12; k++) {
            double th = 0.53 * k, c = cos(th), s = sin(th);
            double gr[2] = {c * gg[0] - s * gg[1], s * gg[0] + c * gg[1]};
            double sr[2] = {c * s0[0] - s * s0[1], s * s0[0] + c * s0[1]};
            double s1r[2], fr[2], Kr[4];
            asp_fric_update(&l, AREA, gr, sr, s1r, fr, Kr, NULL);
            double fq[2] = {c * f[0] - s * f[1], s * f[0] + c * f[1]};
            double sq[2] = {c * s1[0] - s * s1[1], s * s1[0] + c * s1[1]};
            double Q[4] = {c, -s, s, c}, QK[4], QKQ[4];
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++) QK[2 * i + j] = Q[2 * i] * K[j] + Q[2 * i + 1] * K[2 + j];
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++)
                    QKQ[2 * i + j] = QK[2 * i] * Q[2 * j] + QK[2 * i + 1] * Q[2 * j + 1];
            for (int i = 0; i < 2; i++) {
                worst = fmax(worst, fabs(fr[i] - fq[i]) / (AREA * l.tau_c));
                worst = fmax(worst, fabs(s1r[i] - sq[i]) / gs);
            }
            for (int i = 0; i < 4; i++) worst = fmax(worst, fabs(Kr[i] - QKQ[i]) / (AREA * l.kt));
        }
    }
    printf("objectivity: max relative deviation under rotation %.2e\n", worst);
    assert_true(worst < 1e-12);
    /* half model: a node on y = 0 stays on the x axis */
    double gy0[2] = {5 * gs, 0.0}, sy0[2] = {-gs, 0.0}, s1[2], f[2], K[4];
    asp_fric_update(&l, AREA, gy0, sy0, s1, f, K, NULL);
    assert_true(f[1] == 0.0 && s1[1] == 0.0 && K[1] == 0.0);
}

/* 1D load (0 -> 3 gs) - unload (-> -3 gs) - reload (-> 3 gs) against the
 * elastic-perfectly-plastic spring in closed form: from a reversal point
 * (g_r, f_r) each monotone branch is f = clamp(f_r + A k_t (g - g_r), ±τc A). */
static void test_path_dependence(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt, fl = AREA * l.tau_c, s[2] = {0, 0};
    const double turns[4] = {0.0, 3.0, -3.0, 3.0};
    double worst = 0.0, f_at_2gs[3] = {0, 0, 0};
    double gr = 0.0, fr = 0.0;
    int nsteps = 60;
    for (int leg = 0; leg < 3; leg++) {
        for (int k = 1; k <= nsteps; k++) {
            double g1 = gs * (turns[leg] + (turns[leg + 1] - turns[leg]) * k / nsteps);
            double g[2] = {g1, 0.0}, s1[2], f[2];
            asp_fric_update(&l, AREA, g, s, s1, f, NULL, NULL);
            s[0] = s1[0], s[1] = s1[1];
            double ref = fmax(-fl, fmin(fl, fr + AREA * l.kt * (g1 - gr)));
            worst = fmax(worst, fabs(f[0] - ref) / fl);
            if (fabs(g1 - 2.0 * gs) < 1e-9 * gs) f_at_2gs[leg] = f[0] / fl;
        }
        double g1 = gs * turns[leg + 1], g[2] = {g1, 0}, s1[2], f[2];
        asp_fric_update(&l, AREA, g, s, s1, f, NULL, NULL);
        gr = g1, fr = f[0];
    }
    printf("load-unload-reload: max |f - closed form| = %.2e tau_c A; f(g = 2 gs)/(tau_c A) "
           "= %.3f loading, %.3f unloading, %.3f reloading\n",
           worst, f_at_2gs[0], f_at_2gs[1], f_at_2gs[2]);
    assert_true(worst < 1e-12);
    assert_true(fabs(f_at_2gs[0] - 1.0) < 1e-12 && fabs(f_at_2gs[1]) < 1e-9 &&
                fabs(f_at_2gs[2] - 1.0) < 1e-12);
    assert_true(fabs(s[0] - 2.0 * gs) < 1e-12 * gs);
}

/* |g - s| <= τc / k_t on every state of random 2D histories (the stick
 * error), and its size relative to the elastic slide distance for the
 * reference contact (a = 6 h, the coarsest contact the mesh resolves). */
static void test_stick_error(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt, s[2] = {0, 0}, g[2] = {0, 0}, worst = 0.0;
    unsigned seed = 11;
    for (int k = 0; k < 5000; k++) {
        g[0] += 0.7 * gs * rnd(&seed), g[1] += 0.7 * gs * rnd(&seed);
        double s1[2], f[2];
        asp_fric_update(&l, AREA, g, s, s1, f, NULL, NULL);
        s[0] = s1[0], s[1] = s1[1];
        worst = fmax(worst, hypot(g[0] - s[0], g[1] - s[1]) / gs);
    }
    double G = E / (2 * (1 + NU)), a = 6 * H;
    double ux_e = l.tau_c * M_PI * a * a / (8 * G * a / (2 - NU)); /* Mindlin stiffness */
    double kt_err = 8 * H / (M_PI * ASP_FRIC_KAPPA_DEFAULT * (2 - NU) * a);
    printf("stick error: max |g - s| = %.6f tau_c/k_t = %.3g mm; elastic slide distance "
           "ux_e = %.3g mm (ratio %.2e); KT error estimate %.2e\n",
           worst, gs, ux_e, gs / ux_e, kt_err);
    assert_true(worst <= 1.0 + 1e-12);
    assert_true(gs / ux_e < 5e-3 && kt_err < 5e-3);
}

static void expect_bad(double tc, double e, double nu, double h, double kappa, const char *needle)
{
    asp_fric_law l;
    stc_error_clear();
    assert_int_equal(asp_fric_law_init(&l, tc, e, nu, h, kappa), STC_EINVAL);
    if (!strstr(stc_errmsg(), needle)) fail_msg("message '%s' lacks '%s'", stc_errmsg(), needle);
}

static void test_invalid(void **state)
{
    (void)state;
    expect_bad(0, E, NU, H, 100, "tau-c = 0 MPa");
    expect_bad(-1, E, NU, H, 100, "must be > 0");
    expect_bad(100, -5, NU, H, 100, "E = -5 MPa");
    expect_bad(100, E, 0.5, H, 100, "nu = 0.5: must be in (-1, 0.5)");
    expect_bad(100, E, NU, 0, 100, "h = 0 mm");
    expect_bad(100, E, NU, H, NAN, "kappa = nan");
}

/* A state imposed (asp_fric_update_as, the ramp's held nodes after a Newton
 * stall): stick keeps the trial traction whatever its size, slip returns
 * onto |t| = τc along it whatever its size, with the tangent of that branch
 * (central differences); 0 is asp_fric_update to the bit; ratio says which
 * state the free law would take. */
static void test_imposed_state(void **state)
{
    (void)state;
    asp_fric_law l = law();
    double gs = l.tau_c / l.kt, s0[2] = {0.0, 0.0}, s1[2], s2[2], f[2], f2[2], K[4], K2[4], r;
    double below[2] = {0.6 * gs, 0.3 * gs}, above[2] = {2.0 * gs, -1.0 * gs};
    /* slip imposed below the limit: |f| = τc A along the trial traction */
    assert_int_equal(asp_fric_update_as(&l, ASP_FRIC_SLIP, AREA, below, s0, s1, f, K, &r),
                     ASP_FRIC_SLIP);
    assert_true(r < 1.0);
    assert_true(fabs(hypot(f[0], f[1]) / (AREA * l.tau_c) - 1.0) < 1e-14);
    assert_true(fabs(f[0] * below[1] - f[1] * below[0]) < 1e-12 * hypot(f[0], f[1]) * gs);
    /* its tangent: only rotation resists */
    double eps = 1e-6 * gs, fp[2], fm[2], err = 0.0;
    for (int j = 0; j < 2; j++) {
        double gp[2] = {below[0], below[1]}, gm[2] = {below[0], below[1]};
        gp[j] += eps, gm[j] -= eps;
        asp_fric_update_as(&l, ASP_FRIC_SLIP, AREA, gp, s0, s1, fp, NULL, NULL);
        asp_fric_update_as(&l, ASP_FRIC_SLIP, AREA, gm, s0, s1, fm, NULL, NULL);
        for (int i = 0; i < 2; i++)
            err = fmax(err, fabs((fp[i] - fm[i]) / (2.0 * eps) - K[2 * i + j]));
    }
    assert_true(err < 1e-6 * AREA * l.kt);
    /* stick imposed above the limit: the trial traction, the elastic tangent */
    assert_int_equal(asp_fric_update_as(&l, ASP_FRIC_STICK, AREA, above, s0, s1, f, K, &r),
                     ASP_FRIC_STICK);
    assert_true(r > 1.0);
    assert_true(fabs(f[0] - AREA * l.kt * above[0]) < 1e-15 * fabs(f[0]));
    assert_true(K[0] == AREA * l.kt && K[3] == AREA * l.kt && K[1] == 0.0);
    /* free: the same as asp_fric_update */
    for (int c = 0; c < 2; c++) {
        const double *g = c ? above : below;
        int a = asp_fric_update_as(&l, 0, AREA, g, s0, s1, f, K, NULL);
        int b = asp_fric_update(&l, AREA, g, s0, s2, f2, K2, NULL);
        assert_int_equal(a, b);
        assert_memory_equal(f, f2, sizeof f);
        assert_memory_equal(K, K2, sizeof K);
        assert_memory_equal(s1, s2, sizeof s1);
    }
    /* slip imposed at zero trial traction: no direction, it sticks */
    double zero[2] = {0.0, 0.0};
    assert_int_equal(asp_fric_update_as(&l, ASP_FRIC_SLIP, AREA, zero, s0, s1, f, K, NULL),
                     ASP_FRIC_STICK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tangent_fd),       cmocka_unit_test(test_tangent_transition),
        cmocka_unit_test(test_slip_limit),       cmocka_unit_test(test_objectivity),
        cmocka_unit_test(test_path_dependence),  cmocka_unit_test(test_stick_error),
        cmocka_unit_test(test_invalid),          cmocka_unit_test(test_imposed_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
