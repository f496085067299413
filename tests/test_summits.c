/* Summits and surface statistics: closed-form maps (exact curvature of the
 * finite-difference stencil, periodic wrap, the two neighbour rules, the
 * moment convention on a sinusoid) and Nayak's summit density for a
 * well-sampled Gaussian surface averaged over seeds. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "stiction/surface.h"

#define PI 3.14159265358979323846

static double relerr(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* z = A cos(kx x) cos(ky y): maxima at (0,0) and (L/2, L/2) — the first sits
 * on the corner, so it is only found with periodic edges.  The stencil's
 * curvature is exactly (1 - cos(k h))·2/h² per axis. */
static void test_cosine_summits(void **state)
{
    (void)state;
    int nx = 64, ny = 48;
    double lx = 2.0, ly = 1.5, A = 1e-3, kx = 2 * PI / lx, ky = 2 * PI / ly;
    srf_map *m = NULL;
    assert_int_equal(srf_map_create(nx, ny, lx, ly, &m), STC_OK);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            m->z[j * nx + i] = A * cos(kx * i * lx / nx) * cos(ky * j * ly / ny);
    double dx = lx / nx, dy = ly / ny;
    double kap = 0.5 * A * (2 * (1 - cos(kx * dx)) / (dx * dx) + 2 * (1 - cos(ky * dy)) / (dy * dy));
    for (int rule = 4; rule <= 8; rule += 4) {
        srf_summits *s = NULL;
        assert_int_equal(srf_summits_find(m, rule, &s), STC_OK);
        assert_int_equal(s->n, 2);
        assert_true(s->x[0] == 0 && s->y[0] == 0);
        assert_true(relerr(s->x[1], lx / 2) < 1e-15 && relerr(s->y[1], ly / 2) < 1e-15);
        for (int k = 0; k < 2; k++) {
            assert_true(relerr(s->z[k], A) < 1e-12); /* the map mean is 0 */
            assert_true(relerr(s->kappa[k], kap) < 1e-10);
            assert_true(relerr(s->R[k], 1 / kap) < 1e-10);
        }
        /* continuous mean curvature A (kx² + ky²)/2; the stencil is within O(k²h²) */
        assert_true(relerr(s->kappa[0], 0.5 * A * (kx * kx + ky * ky)) < 0.01);
        assert_true(s->area == lx * ly && s->rule == rule);
        srf_summits_destroy(&s);
        assert_null(s);
    }
    srf_map_destroy(&m);
}

/* A point higher than its 4 edge neighbours but lower than a diagonal one is
 * a 4-rule summit only; a plateau (tie) is no summit under either rule. */
static void test_rules_and_ties(void **state)
{
    (void)state;
    srf_map *m = NULL;
    assert_int_equal(srf_map_create(8, 8, 1, 1, &m), STC_OK);
    srf_summits *s4 = NULL, *s8 = NULL;
    assert_int_equal(srf_summits_find(m, SRF_RULE_8, &s8), STC_OK); /* flat: all ties */
    assert_int_equal(s8->n, 0);
    srf_summits_destroy(&s8);
    m->z[3 * 8 + 3] = 1.0;  /* peak at (3,3) */
    m->z[4 * 8 + 4] = 2.0;  /* higher diagonal neighbour at (4,4) */
    m->z[0 * 8 + 7] = 0.5;  /* corner point: neighbours wrap around */
    m->z[6 * 8 + 1] = 0.25; /* tie with its right neighbour: not a summit */
    m->z[6 * 8 + 2] = 0.25;
    assert_int_equal(srf_summits_find(m, SRF_RULE_8, &s8), STC_OK);
    assert_int_equal(srf_summits_find(m, SRF_RULE_4, &s4), STC_OK);
    assert_int_equal(s8->n, 2); /* (4,4) and (7,0) */
    assert_int_equal(s4->n, 3); /* + (3,3) */
    assert_true(s8->x[0] == 7.0 / 8 && s8->y[0] == 0);
    assert_true(s8->x[1] == 4.0 / 8 && s8->y[1] == 4.0 / 8);
    srf_summits_destroy(&s4);
    srf_summits_destroy(&s8);
    stc_error_clear();
    assert_int_equal(srf_summits_find(m, 6, &s8), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "rule = 6: must be 8 or 4"));
    srf_map_destroy(&m);
}

/* The moment convention on z = A sin(k x): m0 = A²/2, x-profile m2 = A²k²/2,
 * m4 = A²k⁴/2, y-profile 0; direction-averaged m2 = A²k²/4, m4 = 3A²k⁴/16.
 * Heights: skewness 0, kurtosis 3/2. */
static void test_moment_convention(void **state)
{
    (void)state;
    int n = 32;
    double A = 2e-3, k = 2 * PI * 3;
    srf_map *m = NULL;
    srf_summits *s = NULL;
    srf_stats st;
    assert_int_equal(srf_map_create(n, n, 1, 1, &m), STC_OK);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) m->z[j * n + i] = A * sin(k * i / n);
    assert_int_equal(srf_summits_find(m, SRF_RULE_8, &s), STC_OK);
    assert_int_equal(s->n, 0); /* ridges: ties along y */
    assert_int_equal(srf_stats_compute(m, s, &st), STC_OK);
    assert_true(relerr(st.m0, A * A / 2) < 1e-12);
    assert_true(relerr(st.m20, A * A * k * k / 2) < 1e-12 && fabs(st.m02) < 1e-20);
    assert_true(relerr(st.m40, A * A * k * k * k * k / 2) < 1e-12);
    assert_true(relerr(st.m2, A * A * k * k / 4) < 1e-12);
    assert_true(relerr(st.m4, 3 * A * A * k * k * k * k / 16) < 1e-12);
    assert_true(relerr(st.sigma, A / sqrt(2)) < 1e-12);
    assert_true(fabs(st.skewness) < 1e-12 && relerr(st.kurtosis, 1.5) < 1e-12);
    assert_true(relerr(st.alpha, st.m0 * st.m4 / (st.m2 * st.m2)) < 1e-15);
    srf_summits_destroy(&s);
    srf_map_destroy(&m);
}

/* Nayak (1971): an isotropic Gaussian surface has m4/(6π√3 m2) summits per
 * unit area.  Self-affine spectrum (H = 0.8) cut off at λs = 16 pixels, 8
 * seeds of 1024² (~900 summits each; Poisson scatter of the mean ~1.2 %):
 * the 8-neighbour density must be within 3 %.  The 4-neighbour rule also
 * accepts points that are maxima only along the axes; measured here ~29 %
 * more summits (asserted > 15 %).  Mean radius, σs and mean summit height
 * vs McCool (1986) within 5 % (his relations are fits to Nayak's integrals;
 * the 3-point curvature at 16 points per wavelength is ~1.3 % low). */
static void test_nayak_density(void **state)
{
    (void)state;
    srf_synth_params p;
    srf_synth_params_default(&p);
    p.nx = p.ny = 1024;
    p.spectrum = SRF_SPECTRUM_SELF_AFFINE;
    p.hurst = 0.8;
    p.lambda_long = 0.25;
    p.lambda_cutoff = 16.0 / 1024;
    srf_synth *sy = NULL;
    srf_map *m = NULL;
    assert_int_equal(srf_synth_create(&p, &sy), STC_OK);
    assert_int_equal(srf_map_create(p.nx, p.ny, p.lx, p.ly, &m), STC_OK);
    double d8 = 0, d4 = 0, dn = 0, r = 0, rm = 0, ss = 0, ssm = 0, off = 0, offm = 0;
    const int nseed = 8;
    for (int seed = 1; seed <= nseed; seed++) {
        srf_summits *s8 = NULL, *s4 = NULL;
        srf_stats a, b;
        assert_int_equal(srf_synth_run(sy, (unsigned long)seed, m), STC_OK);
        assert_int_equal(srf_summits_find(m, SRF_RULE_8, &s8), STC_OK);
        assert_int_equal(srf_summits_find(m, SRF_RULE_4, &s4), STC_OK);
        assert_int_equal(srf_stats_compute(m, s8, &a), STC_OK);
        assert_int_equal(srf_stats_compute(m, s4, &b), STC_OK);
        d8 += a.summit_density_per_mm2;
        d4 += b.summit_density_per_mm2;
        dn += a.summit_density_nayak_per_mm2;
        r += a.mean_summit_radius_mm;
        rm += a.mean_summit_radius_mccool_mm;
        ss += a.sigma_s_mm;
        ssm += a.sigma_s_mccool_mm;
        off += a.summit_mean_offset_mm;
        offm += a.summit_mean_offset_mccool_mm;
        if (seed == 1)
            print_message("  alpha %.2f, %d summits (8-rule), %d (4-rule) on seed 1\n", a.alpha,
                          a.summits, b.summits);
        srf_summits_destroy(&s8);
        srf_summits_destroy(&s4);
    }
    print_message("  density / Nayak: 8-rule %.4f, 4-rule %.4f; radius / McCool %.4f; "
                  "sigma_s / McCool %.4f; offset / McCool %.4f\n", d8 / dn, d4 / dn, r / rm,
                  ss / ssm, off / offm);
    assert_true(fabs(d8 / dn - 1) < 0.03);
    assert_true(d4 / d8 > 1.15);
    assert_true(fabs(r / rm - 1) < 0.05);
    assert_true(fabs(ss / ssm - 1) < 0.05);
    assert_true(fabs(off / offm - 1) < 0.05);
    srf_map_destroy(&m);
    srf_synth_destroy(&sy);
}

/* Non-periodic (imported) maps: the edge rows/columns are not searched and
 * moments come from finite differences, exact for a quadratic surface
 * z = a x² + b y² + c xy (z_xx = 2a, z_yy = 2b, z_xy = c everywhere). */
static void test_nonperiodic(void **state)
{
    (void)state;
    int nx = 40, ny = 30;
    srf_map *m = NULL;
    srf_summits *s = NULL;
    assert_int_equal(srf_map_create(nx, ny, 0.4, 0.3, &m), STC_OK);
    /* a ramp in x with a ridge cap in y: the only maximum is on the last column */
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) m->z[j * nx + i] = i - 0.001 * (j - ny / 2) * (j - ny / 2);
    assert_int_equal(srf_summits_find(m, SRF_RULE_8, &s), STC_OK);
    assert_int_equal(s->n, 1); /* periodic: the wrap makes (nx-1, ny/2) a summit */
    srf_summits_destroy(&s);
    m->periodic = 0;
    assert_int_equal(srf_summits_find(m, SRF_RULE_8, &s), STC_OK);
    assert_int_equal(s->n, 0);
    assert_true(relerr(s->area, 38 * 0.01 * 28 * 0.01) < 1e-12);
    srf_summits_destroy(&s);

    double a = 2.0, b = -0.5, c = 1.5, dx = 0.01, dy = 0.01;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double x = i * dx, y = j * dy;
            m->z[j * nx + i] = a * x * x + b * y * y + c * x * y;
        }
    srf_moments mo;
    assert_int_equal(srf_map_moments(m, &mo), STC_OK);
    assert_true(relerr(mo.m40, 4 * a * a) < 1e-9 && relerr(mo.m04, 4 * b * b) < 1e-9);
    assert_true(relerr(mo.m22, c * c) < 1e-9);
    assert_true(relerr(mo.m4, 3 * (4 * a * a + 2 * c * c + 4 * b * b) / 8) < 1e-9);
    srf_map_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cosine_summits),
        cmocka_unit_test(test_rules_and_ties),
        cmocka_unit_test(test_moment_convention),
        cmocka_unit_test(test_nayak_density),
        cmocka_unit_test(test_nonperiodic),
    };
    return cmocka_run_group_tests_name("summits", tests, NULL, NULL);
}
