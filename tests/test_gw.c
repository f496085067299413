/* Greenwood–Williamson sums: elastic GW against the closed-form Gaussian
 * integrals F_n(h) = (2π)^(-1/2) ∫_h^∞ (s−h)^n e^(−s²/2) ds (GW 1966), the
 * table path, the deterministic and KDE sums, the pressure solve, μs as a
 * ratio of sums, coverage and invalid input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>

#include "stiction/gw.h"
#include "srf_impl.h"

#define ETA 2000.0     /* summits per mm² */
#define RADIUS 0.05    /* mm */
#define SIGMA_S 1e-4   /* mm: 0.1 µm, a fine-ground surface */
#define T_MM 1.5e-3    /* coating, mm */

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

/* F_0, F_1 in closed form (erfc); F_3/2 by a different method: with
 * s = h + u², F_3/2 = (2π)^(-1/2) ∫_0^∞ 2u⁴ e^(−(h+u²)²/2) du, an even smooth
 * integrand, for which the trapezoid rule converges spectrally. */
static double F0(double h) { return 0.5 * erfc(h / M_SQRT2); }
static double F1(double h) { return exp(-0.5 * h * h) / sqrt(2 * M_PI) - h * F0(h); }
static double F32(double h)
{
    double U = sqrt(fmax(0.0, -h) + 12.0), k = U / 6000, sum = 0;
    for (int j = 1; j <= 6000; j++) {
        double u = j * k, s = h + u * u;
        sum += 2 * pow(u, 4) * exp(-0.5 * s * s);
    }
    return sum * k / sqrt(2 * M_PI);
}

static void make_model(int wsp, asp_model **m)
{
    stc_params p;
    stc_params_default(&p);
    p.E_ratio = 2.0;
    p.E_over_Y = 150; /* hardened steel, Y ≈ 1.3 GPa: δ/ωc of order 1–100 */
    stc_status s = wsp ? asp_model_create_wsp(&p, T_MM, ASP_LAYER_SUBSTRATE, m)
                       : asp_model_create_hertz(&p, T_MM, ASP_LAYER_SUBSTRATE, m);
    assert_int_equal(s, STC_OK);
}

static const double H[] = {-1.5, -0.5, 0.0, 0.5, 1.0, 2.0, 3.0, 4.0};
#define NH (int)(sizeof H / sizeof *H)

/* Compare a GW handle over Hertz asperities with η F_n; returns worst error. */
static double worst_vs_Fn(srf_gw *g, const asp_model *m, int check_bound)
{
    double Es = asp_model_E_star(m), worst = 0;
    for (int i = 0; i < NH; i++) {
        srf_gw_point o;
        assert_int_equal(srf_gw_at_separation(g, H[i], &o), STC_OK);
        double N = ETA * F0(H[i]), A = ETA * M_PI * RADIUS * SIGMA_S * F1(H[i]);
        double P = ETA * 4.0 / 3.0 * Es * sqrt(RADIUS) * pow(SIGMA_S, 1.5) * F32(H[i]);
        double e = fmax(rel(o.contacts_per_mm2, N), fmax(rel(o.area_fraction, A),
                                                          rel(o.pressure_MPa, P)));
        worst = fmax(worst, e);
        if (check_bound) { /* the stated bound holds (with double rounding slack) */
            assert_true(fabs(o.pressure_MPa - P) <= o.err_P_MPa + 1e-13 * P);
            assert_true(fabs(o.area_fraction - A) <= o.err_A + 1e-13 * A);
        }
        printf("  h = %4.1f: N %.3e  A/An %.6e  P/An %.6e MPa  (+-%.1e)  max rel err %.1e\n",
               H[i], o.contacts_per_mm2, o.area_fraction, o.pressure_MPa, o.err_P_MPa, e);
        assert_true(isnan(o.mu_s)); /* Hertz has no friction law */
    }
    return worst;
}

static void test_hertz_vs_Fn(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *g = NULL;
    make_model(0, &m);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, NULL, &g), STC_OK);
    double w = worst_vs_Fn(g, m, 1);
    printf("elastic GW (Hertz, Gaussian) vs F_0, F_1, F_3/2: worst rel error %.2e\n", w);
    assert_true(w < 1e-6);
    srf_gw_destroy(&g);
    assert_null(g);
    asp_model_destroy(&m);
}

/* The tightest tolerance the parameters accept (epsrel 1e-14, below what
 * GSL's drivers take: they returned 0 with an error, and every sum was 0)
 * still integrates: the closed forms, within the stated bounds. */
static void test_tolerance_floor(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *g = NULL;
    srf_gw_params par;
    srf_gw_params_default(&par);
    par.epsrel = 1e-14;
    make_model(0, &m);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, &par, &g), STC_OK);
    double w = worst_vs_Fn(g, m, 1);
    printf("elastic GW at epsrel 1e-14: worst rel error %.2e\n", w);
    assert_true(w < 1e-6);
    srf_gw_destroy(&g);
    asp_model_destroy(&m);
}

/* The table path: Hertz sampled on a coarse δ grid and interpolated. */
static void test_sampled_hertz_vs_Fn(void **state)
{
    (void)state;
    asp_model *m = NULL, *s = NULL;
    srf_gw *g = NULL;
    make_model(0, &m);
    asp_sample_params sp;
    asp_sample_params_default(&sp);
    sp.n_w = 31; /* 7 per decade over 0.01..200 */
    assert_int_equal(asp_model_create_sampled(m, &sp, &s), STC_OK);
    assert_int_equal(srf_gw_create_gaussian(s, ETA, RADIUS, SIGMA_S, NULL, &g), STC_OK);
    double w = worst_vs_Fn(g, s, 0);
    printf("elastic GW through the table path (31 nodes): worst rel error %.2e\n", w);
    assert_true(w < 1e-3);
    srf_gw_destroy(&g);
    asp_model_destroy(&s);
    asp_model_destroy(&m);
}

/* n summits at the Gaussian quantiles (i − ½)/n: the deterministic sum is a
 * midpoint rule of the statistical integral and converges to it. */
static double *quantile_heights(int n)
{
    double *z = malloc((size_t)n * sizeof *z);
    for (int i = 0; i < n; i++) z[i] = SIGMA_S * gsl_cdf_ugaussian_Pinv((i + 0.5) / n);
    return z;
}

static double *const_radii(int n)
{
    double *R = malloc((size_t)n * sizeof *R);
    for (int i = 0; i < n; i++) R[i] = RADIUS;
    return R;
}

static void test_deterministic_converges(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *gs = NULL;
    make_model(1, &m);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, NULL, &gs), STC_OK);
    srf_gw_point ref;
    assert_int_equal(srf_gw_at_separation(gs, 1.0, &ref), STC_OK);
    double last = INFINITY;
    for (int n = 1000; n <= 100000; n *= 10) {
        double *z = quantile_heights(n), *R = const_radii(n);
        srf_gw *g = NULL;
        srf_gw_point o;
        assert_int_equal(srf_gw_create_summits(m, SRF_GW_DETERMINISTIC, z, R, n, n / ETA,
                                               NULL, &g), STC_OK);
        assert_int_equal(srf_gw_at_separation(g, 1.0, &o), STC_OK);
        double e = fmax(rel(o.pressure_MPa, ref.pressure_MPa), rel(o.mu_s, ref.mu_s));
        e = fmax(e, rel(o.area_fraction, ref.area_fraction));
        printf("deterministic n = %6d: P/An %.6e (stat %.6e) mu_s %.5f (stat %.5f) "
               "rel err %.1e\n", n, o.pressure_MPa, ref.pressure_MPa, o.mu_s, ref.mu_s, e);
        assert_true(e < last);
        last = e;
        srf_gw_destroy(&g);
        free(z);
        free(R);
    }
    assert_true(last < 2e-3);
    srf_gw_destroy(&gs);
    asp_model_destroy(&m);
}

/* A Gaussian KDE of Gaussian heights is Gaussian with variance 1 + b² (in
 * units of σs): the KDE sums must equal the Gaussian sums with that σ. */
static void test_kde_is_smoothed_gaussian(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *gk = NULL, *gg = NULL;
    make_model(1, &m);
    int n = 20000;
    double *z = quantile_heights(n), *R = const_radii(n);
    assert_int_equal(srf_gw_create_summits(m, SRF_GW_KDE, z, R, n, n / ETA, NULL, &gk), STC_OK);
    srf_gw_info in;
    srf_gw_get_info(gk, &in);
    double b = in.bandwidth_mm / in.sigma_s_mm, sig = in.sigma_s_mm * sqrt(1 + b * b);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, sig, NULL, &gg), STC_OK);
    double worst = 0;
    /* h <= 2: beyond, the load comes from the few summits near the sample's
     * top quantile (s = 4.06 for n = 20000) whose KDE tail is no longer the
     * population's (measured at h = 3: P 1.6 % low, N 3e-4) */
    for (int i = 1; i < 6; i++) {
        srf_gw_point ok, og;
        double d = H[i] * in.sigma_s_mm; /* same physical separation */
        assert_int_equal(srf_gw_at_separation(gk, H[i], &ok), STC_OK);
        assert_int_equal(srf_gw_at_separation(gg, d / sig, &og), STC_OK);
        worst = fmax(worst, fmax(rel(ok.pressure_MPa, og.pressure_MPa),
                                 rel(ok.contacts_per_mm2, og.contacts_per_mm2)));
        worst = fmax(worst, rel(ok.mu_s, og.mu_s));
        printf("  h = %4.1f: P/An %.6e vs %.6e, N %.6e vs %.6e, mu_s %.6f vs %.6f\n", H[i],
               ok.pressure_MPa, og.pressure_MPa, ok.contacts_per_mm2, og.contacts_per_mm2,
               ok.mu_s, og.mu_s);
    }
    printf("KDE (n = %d, b = %.3f sigma_s) vs Gaussian with sqrt(1+b^2) sigma_s: worst rel "
           "error %.2e\n", n, b, worst);
    assert_true(worst < 1e-3);
    srf_gw_destroy(&gk);
    srf_gw_destroy(&gg);
    asp_model_destroy(&m);
    free(z);
    free(R);
}

/* μs = ΣQmax/ΣP over summits with different radii (and so different δ/ωc
 * and different asperity μs), never the mean of the asperity μs. */
static void test_mu_ratio_of_sums(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *g = NULL;
    make_model(1, &m);
    /* at d = 0: summit 0 at δ/ωc ≈ 50 (μ ≈ 0.31), summit 1 at ≈ 0.6 (μ ≈ 0.68) */
    double z[4] = {2.4e-4, 1.1e-5, -1e-4, -4e-4}, R[4] = {0.02, 0.08, 0.05, INFINITY};
    assert_int_equal(srf_gw_create_summits(m, SRF_GW_DETERMINISTIC, z, R, 4, 0.01, NULL, &g),
                     STC_OK);
    srf_gw_info in;
    srf_gw_get_info(g, &in);
    assert_int_equal(in.n_excluded, 1); /* the flat summit */
    double mean = (z[0] + z[1] + z[2]) / 3, d = 0, P = 0, Q = 0, mu_avg = 0;
    for (int i = 0; i < 3; i++) {
        asp_response r;
        asp_model_eval(m, R[i], z[i] - d, &r);
        if (r.P > 0) {
            P += r.P;
            Q += r.Qmax;
            mu_avg += r.Qmax / r.P / 2;
        }
    }
    srf_gw_point o;
    assert_int_equal(srf_gw_at_separation(g, (d - mean) / in.sigma_s_mm, &o), STC_OK);
    printf("mu_s = %.6f = sum Q / sum P = %.6f; mean of asperity mu_s would be %.6f\n", o.mu_s,
           Q / P, mu_avg);
    assert_int_equal(o.n_contacts, 2);
    assert_true(rel(o.mu_s, Q / P) < 1e-12 && rel(o.pressure_MPa, P / 0.01) < 1e-12);
    assert_true(fabs(o.mu_s - mu_avg) > 0.1);
    srf_gw_destroy(&g);
    asp_model_destroy(&m);
}

static void test_pressure_roundtrip(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *g[2] = {NULL, NULL};
    make_model(1, &m);
    int n = 50000;
    double *z = quantile_heights(n), *R = const_radii(n);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, NULL, &g[0]), STC_OK);
    assert_int_equal(srf_gw_create_summits(m, SRF_GW_DETERMINISTIC, z, R, n, n / ETA, NULL,
                                           &g[1]), STC_OK);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < NH; i++) {
            srf_gw_point a, b;
            assert_int_equal(srf_gw_at_separation(g[k], H[i], &a), STC_OK);
            assert_int_equal(srf_gw_at_pressure(g[k], a.pressure_MPa, &b), STC_OK);
            assert_true(fabs(b.h - H[i]) < 1e-9);
            assert_true(rel(b.pressure_MPa, a.pressure_MPa) < 1e-9);
            assert_true(b.iterations > 0);
        }
    printf("pressure solve recovers h to 1e-9 (Gaussian and deterministic)\n");
    srf_gw_destroy(&g[0]);
    srf_gw_destroy(&g[1]);
    asp_model_destroy(&m);
    free(z);
    free(R);
}

/* δ/ωc below which a fraction q of the load of summits z[] (ascending) is
 * carried at separation d. */
static double load_quantile_direct(const asp_model *m, const double *z, int n, double d, double q)
{
    double total = 0, cum = 0;
    for (int i = 0; i < n; i++) total += asp_model_load(m, RADIUS, z[i] - d);
    for (int i = 0; i < n; i++) {
        if (z[i] <= d) continue;
        cum += asp_model_load(m, RADIUS, z[i] - d);
        if (cum >= q * total) return (z[i] - d) / asp_model_omega_c(m, RADIUS);
    }
    return NAN;
}

/* ψ and coverage: the statistical share of load beyond the Hertz range
 * (δ > ωc) agrees with the deterministic share over quantile summits. */
static void test_plasticity_and_coverage(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *gs = NULL, *gd = NULL;
    make_model(0, &m);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, NULL, &gs), STC_OK);
    srf_gw_info in;
    srf_gw_get_info(gs, &in);
    const stc_material *ref = asp_model_ref(m);
    double psi = asp_model_E_star(m) / (2.8 * ref->Y) * sqrt(SIGMA_S / RADIUS);
    assert_true(rel(in.plasticity_index, psi) < 1e-14);
    int n = 100000;
    double *z = quantile_heights(n), *R = const_radii(n);
    assert_int_equal(srf_gw_create_summits(m, SRF_GW_DETERMINISTIC, z, R, n, n / ETA, NULL,
                                           &gd), STC_OK);
    double lastw = INFINITY;
    for (int i = 0; i < NH; i++) {
        srf_gw_point a, b;
        assert_int_equal(srf_gw_at_separation(gs, H[i], &a), STC_OK);
        assert_int_equal(srf_gw_at_separation(gd, H[i], &b), STC_OK);
        printf("  h = %4.1f: load share beyond delta = omega_c: stat %.4f det %.4f; "
               "delta_max/omega_c (99.9 %% load) %.3g, det max %.3g\n", H[i],
               a.load_fraction_outside, b.load_fraction_outside, a.delta_max_over_omega_c,
               b.delta_max_over_omega_c);
        assert_true(fabs(a.load_fraction_outside - b.load_fraction_outside) < 5e-3);
        /* the 99.9 % load quantile of δ, directly from the quantile summits;
         * only for h <= 0.5: above, the 0.1 % tail lies beyond the sample's top
         * summit (s = 4.42 for n = 1e5), which truncates the direct value */
        if (H[i] > 0.5) continue;
        double wq = load_quantile_direct(m, z, n, H[i] * SIGMA_S, 0.999);
        printf("           99.9 %% load quantile from the summits directly: %.3g\n", wq);
        assert_true(rel(a.delta_max_over_omega_c, wq) < 0.01);
        assert_true(a.delta_max_over_omega_c < lastw);
        lastw = a.delta_max_over_omega_c;
        assert_true(rel(a.tR_min, T_MM / RADIUS) < 1e-14);
    }
    printf("plasticity index psi = %.3f (E*/H sqrt(sigma_s/R), H = 2.8 Y)\n", psi);
    srf_gw_destroy(&gs);
    srf_gw_destroy(&gd);
    asp_model_destroy(&m);
    free(z);
    free(R);
}

static void expect_fail(stc_status got, stc_status want, const char *needle)
{
    assert_int_equal(got, want);
    if (!strstr(stc_errmsg(), needle)) fail_msg("message '%s' lacks '%s'", stc_errmsg(), needle);
}

static void test_invalid(void **state)
{
    (void)state;
    asp_model *m = NULL;
    srf_gw *g = NULL;
    make_model(1, &m);
    expect_fail(srf_gw_create_gaussian(m, 0, RADIUS, SIGMA_S, NULL, &g), STC_EINVAL,
                "summit-density = 0");
    expect_fail(srf_gw_create_gaussian(m, ETA, -1, SIGMA_S, NULL, &g), STC_EINVAL,
                "summit-radius = -1");
    expect_fail(srf_gw_create_gaussian(m, ETA, RADIUS, NAN, NULL, &g), STC_EINVAL, "sigma-s");
    double z[2] = {1e-4, 2e-4}, R[2] = {INFINITY, -1};
    expect_fail(srf_gw_create_summits(m, SRF_GW_DETERMINISTIC, z, R, 2, 1, NULL, &g),
                STC_EINVAL, "usable of 2");
    expect_fail(srf_gw_create_summits(m, SRF_GW_GAUSSIAN, z, R, 2, 1, NULL, &g), STC_EINVAL,
                "mode = gaussian");
    assert_null(g);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, NULL, &g), STC_OK);
    srf_gw_point o;
    expect_fail(srf_gw_at_pressure(g, -2, &o), STC_EINVAL, "pressure = -2");
    expect_fail(srf_gw_at_separation(g, INFINITY, &o), STC_EINVAL, "separation = inf");
    srf_gw_destroy(&g);
    asp_model_destroy(&m);
}

/* Separate handles may run concurrently (gw.h), and GSL's error handler is
 * process-wide: the sums must neither depend on it nor change it.  Two
 * threads, each with its own handle, sum over and over where GSL's
 * integrators would report through the handler (a tolerance out of reach in
 * 10 subintervals).  The caller's handler (here one that counts) must never
 * be called and must still be in place afterwards, and every call must return
 * what it returns on one thread.  Turning the handler off around each call
 * and restoring it raced: a thread restored the caller's handler (by default
 * one that aborts) while the other was inside a GSL call, or restored "off"
 * last and so dropped the caller's handler for good. */
#define RACE_CALLS 1000 /* per thread and round */
#define RACE_ROUNDS 4
static int gsl_handler_calls;
static void counting_handler(const char *reason, const char *file, int line, int gsl_errno)
{
    (void)reason, (void)file, (void)line, (void)gsl_errno;
#pragma omp atomic
    gsl_handler_calls++;
}

static void test_threads_leave_gsl_handler_alone(void **state)
{
    (void)state;
    srf_gw_params par;
    srf_gw_params_default(&par);
    par.epsrel = 1e-12;
    par.limit = 10;
    asp_model *m = NULL;
    srf_gw *g = NULL;
    make_model(1, &m);
    assert_int_equal(srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, &par, &g), STC_OK);
    srf_gw_point ref[NH];
    stc_status ref_s[NH];
    for (int i = 0; i < NH; i++) ref_s[i] = srf_gw_at_separation(g, H[i], &ref[i]);
    srf_gw_destroy(&g);
    /* a round misses the race when the threads hardly overlap (a loaded
     * machine): several rounds */
    int bad = 0, calls = 0, replaced = 0;
    for (int round = 0; round < RACE_ROUNDS; round++) {
        gsl_error_handler_t *caller = gsl_set_error_handler(counting_handler);
#pragma omp parallel num_threads(2) reduction(+ : bad, calls)
        {
            srf_gw *gt = NULL;
            if (srf_gw_create_gaussian(m, ETA, RADIUS, SIGMA_S, &par, &gt) != STC_OK) bad++;
            for (int k = 0; gt && k < RACE_CALLS; k++) {
                int i = k % NH;
                srf_gw_point o;
                stc_status s = srf_gw_at_separation(gt, H[i], &o);
                calls++;
                bad += s != ref_s[i] ||
                       (s == STC_OK && (o.pressure_MPa != ref[i].pressure_MPa ||
                                        o.area_fraction != ref[i].area_fraction));
            }
            srf_gw_destroy(&gt);
        }
        replaced += gsl_set_error_handler(caller) != counting_handler;
    }
    printf("%d sums on 2 threads: %d differ from one thread's; GSL's handler called %d "
           "times, replaced in %d of %d rounds\n", calls, bad, gsl_handler_calls, replaced,
           RACE_ROUNDS);
    assert_int_equal(bad, 0);
    assert_int_equal(gsl_handler_calls, 0);
    assert_int_equal(replaced, 0);
    asp_model_destroy(&m);
}

/* The deterministic sums' height order (srf_sort_desc, a radix sort) is the
 * stable order of a height comparator, ties and -0 = +0 included: against a
 * reference that sorts (height desc, input position asc) by qsort, on
 * heights with many ties, on an already sorted input, a reversed one and
 * one of a single value. */
typedef struct {
    srf_zr v;
    int pos;
} ref_item;

static int ref_cmp(const void *a, const void *b)
{
    const ref_item *x = a, *y = b;
    if (x->v.z != y->v.z) return x->v.z < y->v.z ? 1 : -1;
    return (x->pos > y->pos) - (x->pos < y->pos);
}

static void check_sorted_like_ref(srf_zr *v, int n)
{
    ref_item *r = malloc((size_t)n * sizeof *r);
    assert_non_null(r);
    for (int i = 0; i < n; i++) r[i] = (ref_item){v[i], i};
    qsort(r, (size_t)n, sizeof *r, ref_cmp);
    assert_int_equal(srf_sort_desc(v, n), STC_OK);
    for (int i = 0; i < n; i++)
        if (memcmp(&v[i], &r[i].v, sizeof v[i]) != 0)
            fail_msg("position %d: (%g, %g) against the reference's (%g, %g)", i, v[i].z,
                     v[i].R, r[i].v.z, r[i].v.R);
    free(r);
}

static void test_height_sort(void **state)
{
    (void)state;
    enum { N = 200003 };
    srf_zr *v = malloc(N * sizeof *v);
    assert_non_null(v);
    unsigned long x = 12345;
    for (int i = 0; i < N; i++) {
        x = x * 6364136223846793005UL + 1442695040888963407UL;
        /* 4001 distinct heights, both signs, plus exact zeros of both signs */
        double z = ((double)((x >> 33) % 4001) - 2000.0) * 1e-7;
        if (i % 97 == 0) z = (i % 194 == 0) ? -0.0 : 0.0;
        v[i] = (srf_zr){z, 1.0 + i}; /* R tags the input position */
    }
    check_sorted_like_ref(v, N);
    check_sorted_like_ref(v, N); /* already in order */
    for (int i = 0; i < N / 2; i++) {
        srf_zr t = v[i];
        v[i] = v[N - 1 - i], v[N - 1 - i] = t;
    }
    check_sorted_like_ref(v, N); /* reversed */
    for (int i = 0; i < N; i++) v[i] = (srf_zr){3e-4, 1.0 + i};
    v[N / 2].z = 2e-4; /* one digit for most passes */
    check_sorted_like_ref(v, N);
    check_sorted_like_ref(v, 1);
    free(v);
}

/* srf_gw_create_like: the population of a handle made with one model (Hertz),
 * summed with another (wsp), gives what a handle made with that model gives,
 * to the bit, in every mode; its info is the population's with the model's
 * E*, H and plasticity index. */
static void test_create_like(void **state)
{
    (void)state;
    asp_model *hz = NULL, *wsp = NULL;
    make_model(0, &hz);
    make_model(1, &wsp);
    int n = 5000;
    double *z = quantile_heights(n), *R = const_radii(n);
    for (int i = 0; i < n; i++) R[i] *= 1.0 + 0.3 * sin(1.7 * i); /* radii of their own */
    for (int mode = 0; mode < 3; mode++) {
        srf_gw *src = NULL, *fresh = NULL, *like = NULL;
        if (mode == 0) {
            assert_int_equal(srf_gw_create_gaussian(hz, ETA, RADIUS, SIGMA_S, NULL, &src), 0);
            assert_int_equal(srf_gw_create_gaussian(wsp, ETA, RADIUS, SIGMA_S, NULL, &fresh), 0);
        } else {
            srf_gw_mode md = mode == 1 ? SRF_GW_KDE : SRF_GW_DETERMINISTIC;
            assert_int_equal(srf_gw_create_summits(hz, md, z, R, n, n / ETA, NULL, &src), 0);
            assert_int_equal(srf_gw_create_summits(wsp, md, z, R, n, n / ETA, NULL, &fresh), 0);
        }
        assert_int_equal(srf_gw_create_like(src, wsp, &like), STC_OK);
        srf_gw_info a, b;
        srf_gw_get_info(fresh, &a);
        srf_gw_get_info(like, &b);
        const double fa[] = {a.eta_per_mm2, a.sigma_s_mm, a.mean_height_mm, a.R_mm, a.area_mm2,
                             a.E_star_MPa, a.H_MPa, a.plasticity_index, a.bandwidth_mm};
        const double fb[] = {b.eta_per_mm2, b.sigma_s_mm, b.mean_height_mm, b.R_mm, b.area_mm2,
                             b.E_star_MPa, b.H_MPa, b.plasticity_index, b.bandwidth_mm};
        assert_memory_equal(fa, fb, sizeof fa); /* NaN where unused: bitwise */
        assert_true(a.mode == b.mode && a.n_summits == b.n_summits &&
                    a.n_excluded == b.n_excluded);
        const double H[] = {-1.0, 0.0, 1.0, 2.5};
        for (int k = 0; k < 4; k++) {
            srf_gw_point p, q;
            assert_int_equal(srf_gw_at_separation(fresh, H[k], &p), STC_OK);
            assert_int_equal(srf_gw_at_separation(like, H[k], &q), STC_OK);
            assert_memory_equal(&p, &q, sizeof p);
        }
        srf_gw_point p, q;
        assert_int_equal(srf_gw_at_pressure(fresh, 1.0, &p), STC_OK);
        assert_int_equal(srf_gw_at_pressure(like, 1.0, &q), STC_OK);
        assert_memory_equal(&p, &q, sizeof p);
        srf_gw_destroy(&src), srf_gw_destroy(&fresh), srf_gw_destroy(&like);
    }
    srf_gw *g = NULL;
    assert_int_equal(srf_gw_create_like(NULL, wsp, &g), STC_EINVAL);
    assert_null(g);
    free(z), free(R);
    asp_model_destroy(&hz), asp_model_destroy(&wsp);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hertz_vs_Fn),
        cmocka_unit_test(test_tolerance_floor),
        cmocka_unit_test(test_sampled_hertz_vs_Fn),
        cmocka_unit_test(test_deterministic_converges),
        cmocka_unit_test(test_kde_is_smoothed_gaussian),
        cmocka_unit_test(test_mu_ratio_of_sums),
        cmocka_unit_test(test_pressure_roundtrip),
        cmocka_unit_test(test_plasticity_and_coverage),
        cmocka_unit_test(test_invalid),
        cmocka_unit_test(test_threads_leave_gsl_handler_alone),
        cmocka_unit_test(test_height_sort),
        cmocka_unit_test(test_create_like),
    };
    return cmocka_run_group_tests_name("gw", tests, NULL, NULL);
}
