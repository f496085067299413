/* Surface synthesis, Johnson translator, import and file formats: checks of
 * mathematical properties (Parseval, Hermitian symmetry, exact spectral
 * moments, exact RMS, reproducibility, ACF of the exponential spectrum),
 * statistical bounds for random amplitudes, and every malformed-input path. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>
#include <png.h>

#include <fftw3.h>
#include <hdf5.h>

#include "stiction/surface.h"
#include "tmp_util.h"

#define PI 3.14159265358979323846

static double relerr(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* Forward FFT of a map: |Z|² on the half spectrum [ny][nx/2+1]. */
static double *power_of(const srf_map *m)
{
    int nx = m->nx, ny = m->ny, nxh = nx / 2 + 1;
    double *in = fftw_malloc((size_t)nx * ny * sizeof *in);
    fftw_complex *out = fftw_malloc((size_t)ny * nxh * sizeof *out);
    double *pw = malloc((size_t)ny * nxh * sizeof *pw);
    fftw_plan p = fftw_plan_dft_r2c_2d(ny, nx, in, out, FFTW_ESTIMATE);
    memcpy(in, m->z, (size_t)nx * ny * sizeof *in);
    fftw_execute(p);
    for (size_t k = 0; k < (size_t)ny * nxh; k++) pw[k] = out[k][0] * out[k][0] + out[k][1] * out[k][1];
    fftw_destroy_plan(p);
    fftw_free(in);
    fftw_free(out);
    return pw;
}

static double qy_of(int ky, int ny, double ly) { return 2 * PI * (ky <= ny / 2 ? ky : ky - ny) / ly; }
static double colw(int kx, int nx) { return (kx == 0 || (nx % 2 == 0 && kx == nx / 2)) ? 1 : 2; }

static srf_synth_params self_affine(int nx, int ny)
{
    srf_synth_params p;
    srf_synth_params_default(&p);
    p.nx = nx;
    p.ny = ny;
    p.lx = 1.0;
    p.ly = (double)ny / nx;
    p.spectrum = SRF_SPECTRUM_SELF_AFFINE;
    p.hurst = 0.7;
    p.lambda_long = 0.5;
    p.lambda_rolloff = 0.25;
    p.lambda_cutoff = 8.0 / nx;
    return p;
}

static srf_synth_params exponential(int nx, int ny, double bx, double by)
{
    srf_synth_params p;
    srf_synth_params_default(&p);
    p.nx = nx;
    p.ny = ny;
    p.ly = (double)ny / nx;
    p.beta_x = bx;
    p.beta_y = by;
    return p;
}

/* Parseval (Σz² = Σ_full|Z|²/N) and, mode by mode, |Z(k)|² ∝ C(q_k): this
 * holds in the self-conjugate columns/rows only if Hermitian symmetry was
 * enforced (c2r silently drops the anti-Hermitian part otherwise).  Odd and
 * even sizes. */
static void check_modes(srf_synth_params p)
{
    srf_map *m = NULL;
    assert_int_equal(srf_synthesize(&p, 42, &m), STC_OK);
    int nx = p.nx, ny = p.ny, nxh = nx / 2 + 1;
    double *pw = power_of(m), sz = 0, sp = 0, ratio = -1, worst = 0;
    for (size_t k = 0; k < (size_t)nx * ny; k++) sz += m->z[k] * m->z[k];
    for (int ky = 0; ky < ny; ky++)
        for (int kx = 0; kx < nxh; kx++) {
            double w = pw[(size_t)ky * nxh + kx];
            sp += colw(kx, nx) * w;
            double c = (kx || ky) ? srf_psd_eval(&p, 2 * PI * kx / p.lx, qy_of(ky, ny, p.ly)) : 0;
            if (c <= 0) { worst = fmax(worst, w / (sz + 1e-300)); continue; }
            if (ratio < 0) ratio = w / c;
            worst = fmax(worst, relerr(w / c, ratio));
        }
    double parseval = relerr(sz, sp / ((double)nx * ny));
    print_message("  %d x %d %s: Parseval rel. error %.2e, worst |Z|²/C deviation %.2e\n", nx, ny,
                  srf_spectrum_name(p.spectrum), parseval, worst);
    assert_true(parseval < 1e-12);
    assert_true(worst < 1e-10);
    free(pw);
    srf_map_destroy(&m);
}

static void test_parseval_hermitian(void **state)
{
    (void)state;
    check_modes(self_affine(128, 96));
    check_modes(self_affine(127, 65)); /* odd: no Nyquist column/row */
    check_modes(exponential(96, 128, 0.05, 0.02));
    check_modes(exponential(65, 64, 0.05, 0.05));
}

/* Target discrete moments computed here from srf_psd_eval, independently. */
static void target_moments(const srf_synth_params *p, srf_moments *t)
{
    int nx = p->nx, ny = p->ny, nxh = nx / 2 + 1;
    double s = 0, a20 = 0, a02 = 0, a40 = 0, a04 = 0, a22 = 0;
    for (int ky = 0; ky < ny; ky++)
        for (int kx = 0; kx < nxh; kx++) {
            if (!kx && !ky) continue;
            double qx = 2 * PI * kx / p->lx, qy = qy_of(ky, ny, p->ly);
            double c = colw(kx, nx) * srf_psd_eval(p, qx, qy);
            s += c;
            a20 += c * qx * qx;
            a02 += c * qy * qy;
            a40 += c * qx * qx * qx * qx;
            a04 += c * qy * qy * qy * qy;
            a22 += c * qx * qx * qy * qy;
        }
    double f = p->rms * p->rms / s;
    t->m0 = p->rms * p->rms;
    t->m20 = a20 * f;
    t->m02 = a02 * f;
    t->m40 = a40 * f;
    t->m04 = a04 * f;
    t->m22 = a22 * f;
    t->m2 = 0.5 * (t->m20 + t->m02);
    t->m4 = 3 * (t->m40 + 2 * t->m22 + t->m04) / 8;
}

static void check_moments(srf_synth_params p)
{
    srf_synth *s = NULL;
    srf_map *m = NULL;
    srf_moments t, ts, mm;
    assert_int_equal(srf_synth_create(&p, &s), STC_OK);
    assert_int_equal(srf_map_create(p.nx, p.ny, p.lx, p.ly, &m), STC_OK);
    target_moments(&p, &t);
    assert_int_equal(srf_synth_target_moments(s, &ts), STC_OK);
    double e = 0;
    for (unsigned long seed = 1; seed <= 3; seed++) {
        assert_int_equal(srf_synth_run(s, seed, m), STC_OK);
        assert_int_equal(srf_map_moments(m, &mm), STC_OK);
        double v[][2] = {{mm.m0, t.m0},   {mm.m20, t.m20}, {mm.m02, t.m02}, {mm.m40, t.m40},
                         {mm.m04, t.m04}, {mm.m22, t.m22}, {mm.m2, t.m2},   {mm.m4, t.m4},
                         {ts.m2, t.m2},   {ts.m4, t.m4}};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) e = fmax(e, relerr(v[k][0], v[k][1]));
    }
    print_message("  %s %d x %d: m0 %.4g m2 %.4g m4 %.4g (m20 %.4g m02 %.4g), worst rel. error %.2e\n",
                  srf_spectrum_name(p.spectrum), p.nx, p.ny, t.m0, t.m2, t.m4, t.m20, t.m02, e);
    assert_true(e < 1e-10);
    srf_map_destroy(&m);
    srf_synth_destroy(&s);
    assert_null(s);
}

static void test_moments_exact(void **state)
{
    (void)state;
    check_moments(self_affine(128, 128));
    check_moments(exponential(128, 64, 0.08, 0.02)); /* anisotropic */
}

/* σ exact and mean zero after synthesis, for every mode. */
static void test_rms_exact(void **state)
{
    (void)state;
    srf_synth_params ps[3] = {exponential(64, 64, 0.1, 0.1), self_affine(64, 64),
                              exponential(64, 64, 0.1, 0.1)};
    ps[1].amplitude = SRF_AMP_RAYLEIGH;
    ps[2].non_gaussian = 1;
    ps[2].skewness = 0.5;
    ps[2].kurtosis = 4.0;
    for (int c = 0; c < 3; c++) {
        srf_map *m = NULL;
        ps[c].rms = 2.5e-4;
        assert_int_equal(srf_synthesize(&ps[c], 9, &m), STC_OK);
        double s = 0, ss = 0;
        for (int k = 0; k < 64 * 64; k++) s += m->z[k];
        for (int k = 0; k < 64 * 64; k++) ss += m->z[k] * m->z[k];
        double rms = sqrt(ss / (64 * 64));
        print_message("  case %d: rms rel. error %.1e, mean/rms %.1e\n", c, relerr(rms, 2.5e-4),
                      s / (64 * 64) / rms);
        assert_true(relerr(rms, 2.5e-4) < 1e-13);
        assert_true(fabs(s / (64 * 64)) < 1e-13 * rms);
        srf_map_destroy(&m);
    }
}

static void test_reproducible(void **state)
{
    (void)state;
    srf_synth_params p = self_affine(96, 64);
    p.amplitude = SRF_AMP_RAYLEIGH;
    srf_synth *s = NULL;
    srf_map *a = NULL, *b = NULL, *c = NULL;
    assert_int_equal(srf_synth_create(&p, &s), STC_OK);
    assert_int_equal(srf_map_create(96, 64, p.lx, p.ly, &a), STC_OK);
    assert_int_equal(srf_synth_run(s, 1234, a), STC_OK);
    assert_int_equal(srf_synth_run(s, 99, a), STC_OK); /* plan reuse, other seed */
    assert_int_equal(srf_synth_run(s, 1234, a), STC_OK);
    assert_int_equal(srf_synthesize(&p, 1234, &b), STC_OK);
    assert_int_equal(srf_synthesize(&p, 1235, &c), STC_OK);
    assert_memory_equal(a->z, b->z, 96 * 64 * sizeof(double));
    assert_memory_not_equal(a->z, c->z, 96 * 64 * sizeof(double));
    assert_true(b->seed == 1234 && b->origin == SRF_ORIGIN_SYNTH);
    srf_map_destroy(&a);
    srf_map_destroy(&b);
    srf_map_destroy(&c);
    srf_synth_destroy(&s);
}

/* Random (Rayleigh) amplitudes: |Z_k|² = C_k E_k with E_k ~ Exp(1) per
 * independent mode pair (χ²₁ for self-conjugate modes, variance 2).  For a
 * ratio R = Σ x_k E_k / Σ y_k E_k the delta method gives
 * Var R / R² = Σ v_k (x_k/X - y_k/Y)².  Bound: every seed within 5 sd, the
 * mean over 24 seeds within 4 sd/√24. */
static void test_rayleigh_bounds(void **state)
{
    (void)state;
    srf_synth_params p = exponential(64, 64, 0.1, 0.1);
    p.amplitude = SRF_AMP_RAYLEIGH;
    int nx = 64, ny = 64, nxh = nx / 2 + 1;
    double X2 = 0, X4 = 0, Y = 0, v2 = 0, v4 = 0;
    srf_moments t;
    target_moments(&p, &t);
    /* pass 1: totals; pass 2: variance sums (each pair once: kx < nx/2, or
     * kx ∈ {0, nx/2} with ky <= partner) */
    for (int pass = 0; pass < 2; pass++)
        for (int ky = 0; ky < ny; ky++)
            for (int kx = 0; kx < nxh; kx++) {
                int special = kx == 0 || kx == nx / 2, partner = (ny - ky) % ny;
                if ((!kx && !ky) || (special && ky > partner)) continue;
                double qx = 2 * PI * kx / p.lx, qy = qy_of(ky, ny, p.ly), q2 = qx * qx + qy * qy;
                double c = srf_psd_eval(&p, qx, qy) * (special && ky == partner ? 1 : 2);
                double m2d = 0.5 * q2, m4d = 3 * q2 * q2 / 8; /* direction-averaged weights */
                if (pass == 0) {
                    Y += c;
                    X2 += c * m2d;
                    X4 += c * m4d;
                } else {
                    double var = special && ky == partner ? 2 : 1;
                    v2 += var * pow(c * m2d / X2 - c / Y, 2);
                    v4 += var * pow(c * m4d / X4 - c / Y, 2);
                }
            }
    double sd2 = sqrt(v2), sd4 = sqrt(v4), mean2 = 0, mean4 = 0;
    const int nseed = 24;
    for (int s = 1; s <= nseed; s++) {
        srf_map *m = NULL;
        srf_moments mm;
        assert_int_equal(srf_synthesize(&p, (unsigned long)s, &m), STC_OK);
        assert_int_equal(srf_map_moments(m, &mm), STC_OK);
        double r2 = mm.m2 / t.m2 - 1, r4 = mm.m4 / t.m4 - 1;
        assert_true(fabs(r2) < 5 * sd2 && fabs(r4) < 5 * sd4);
        mean2 += r2 / nseed;
        mean4 += r4 / nseed;
        srf_map_destroy(&m);
    }
    print_message("  Rayleigh: predicted sd m2 %.3f m4 %.3f; mean deviation over %d seeds "
                  "m2 %+.4f m4 %+.4f (bounds ±%.4f, ±%.4f)\n", sd2, sd4, nseed, mean2, mean4,
                  4 * sd2 / sqrt(nseed), 4 * sd4 / sqrt(nseed));
    assert_true(fabs(mean2) < 4 * sd2 / sqrt(nseed));
    assert_true(fabs(mean4) < 4 * sd4 / sqrt(nseed));
    assert_true(sd2 > 0.005); /* the bound is not vacuous: amplitudes really vary */
}

/* Exponential ACF.  The circular autocorrelation of an exact-amplitude map
 * depends on |Z|² only, so it must equal Σ C cos(q·r) / Σ C over the grid
 * (DC excluded) to round-off.  That discrete value in turn approximates the
 * continuous target R(β*) = 0.1 σ²: measured 0.0967 here, the difference
 * being the zero-mean constraint (the DC mode carries 2π ℓx ℓy σ² = 0.6 % of
 * the variance on this 1 mm domain) and the Nyquist truncation; tolerance
 * 0.005 σ². */
static void test_exponential_acf(void **state)
{
    (void)state;
    int n = 500; /* dx = 0.002 mm: the lags β* = 0.05, 0.1 mm are whole pixels */
    srf_synth_params p = exponential(n, n, 0.05, 0.1);
    srf_map *m = NULL;
    assert_int_equal(srf_synthesize(&p, 3, &m), STC_OK);
    double dx = p.lx / n;
    int lx = (int)lround(0.05 / dx), ly = (int)lround(0.1 / dx);
    double ax = 0, ay = 0, a0 = 0, cx = 0, cy = 0, c0 = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double z = m->z[(size_t)j * n + i];
            a0 += z * z;
            ax += z * m->z[(size_t)j * n + (i + lx) % n];
            ay += z * m->z[(size_t)((j + ly) % n) * n + i];
            if (!i && !j) continue;
            double qx = 2 * PI * (i <= n / 2 ? i : i - n) / p.lx, qy = qy_of(j, n, p.ly);
            double c = srf_psd_eval(&p, qx, qy);
            c0 += c;
            cx += c * cos(qx * 0.05);
            cy += c * cos(qy * 0.1);
        }
    print_message("  exponential ACF at beta*: x %.5f, y %.5f; discrete expectation %.5f, %.5f; "
                  "continuous 0.1\n", ax / a0, ay / a0, cx / c0, cy / c0);
    assert_true(fabs(ax / a0 - cx / c0) < 1e-10 && fabs(ay / a0 - cy / c0) < 1e-10);
    assert_true(fabs(ax / a0 - 0.1) < 0.005);
    assert_true(fabs(ay / a0 - 0.1) < 0.005);
    srf_map_destroy(&m);
}

/* Self-affine spectrum exactly as specified: zero beyond λL and below λs,
 * flat between λL and λr, slope -2(1+H) between λr and λs. */
static void test_self_affine_psd(void **state)
{
    (void)state;
    srf_synth_params p = self_affine(256, 256);
    double qL = 2 * PI / p.lambda_long, qr = 2 * PI / p.lambda_rolloff, qs = 2 * PI / p.lambda_cutoff;
    double c0 = srf_psd_eval(&p, qL, 0);
    assert_true(c0 > 0);
    assert_true(srf_psd_eval(&p, 0.99 * qL, 0) == 0);
    assert_true(srf_psd_eval(&p, 0, 1.01 * qs) == 0);
    assert_true(srf_psd_eval(&p, 0.5 * (qL + qr), 0) == c0);
    double q = 2 * qr, ratio = srf_psd_eval(&p, 2 * q * 0.6, 2 * q * 0.8) / srf_psd_eval(&p, q, 0);
    assert_true(relerr(ratio, pow(2.0, -2 * (1 + p.hurst))) < 1e-13);
    p.lambda_rolloff = 0; /* = λL: no plateau */
    assert_true(relerr(srf_psd_eval(&p, 2 * qL, 0) / srf_psd_eval(&p, qL, 0),
                       pow(2.0, -2 * (1 + p.hurst))) < 1e-13);
}

static void expect_invalid(srf_synth_params p, const char *needle)
{
    srf_synth *s = (srf_synth *)&p; /* must be reset to NULL on failure */
    stc_error_clear();
    assert_int_not_equal(srf_synth_create(&p, &s), STC_OK);
    assert_null(s);
    if (!strstr(stc_errmsg(), needle)) fail_msg("message '%s' lacks '%s'", stc_errmsg(), needle);
}

static double user_psd(double qx, double qy, void *u)
{
    (void)u;
    return qx > 0 ? 1.0 / (1 + qx * qx + qy * qy) : 0.0; /* deliberately not even */
}

static void test_invalid_params(void **state)
{
    (void)state;
    srf_synth_params p = self_affine(64, 64);
    p.hurst = 1.5;
    expect_invalid(p, "hurst = 1.5");
    p = self_affine(64, 64);
    p.lambda_cutoff = 1.0 / 64;
    expect_invalid(p, "cutoff-wavelength = 0.015625 mm: must be >= 2 pixels");
    p = self_affine(64, 64);
    p.lambda_rolloff = 0.6;
    expect_invalid(p, "rolloff-wavelength = 0.6 mm: must be <= long-wavelength");
    p = self_affine(64, 64);
    /* |q|/2π = 1/λ in [2.326, 2.381]: no lattice vector length sqrt(kx²+ky²) */
    p.lambda_long = 0.43;
    p.lambda_rolloff = 0.43;
    p.lambda_cutoff = 0.42;
    expect_invalid(p, "no Fourier mode");
    p = exponential(64, 64, -1, 0.1);
    expect_invalid(p, "beta_x = -1");
    p = exponential(2, 64, 0.1, 0.1);
    expect_invalid(p, "nx = 2");
    p = exponential(64, 64, 0.1, 0.1);
    p.rms = 0;
    expect_invalid(p, "rms = 0");
    p.rms = 1e-3;
    p.non_gaussian = 1;
    p.skewness = 2;
    p.kurtosis = 4;
    expect_invalid(p, "kurtosis = 4: must be > skewness");
    p = exponential(64, 64, 0.1, 0.1);
    p.spectrum = SRF_SPECTRUM_USER;
    expect_invalid(p, "PSD callback");
    /* a user PSD that is not even is symmetrised, so moments still match */
    p.psd = user_psd;
    check_moments(p);
    check_modes(p);
}

/* ------------------------------------------------------------ Johnson */

/* Moments of srf_johnson_apply(u), u ~ N(0,1), by Simpson on [-12, 12]. */
static void js_moments(const srf_johnson *j, double *mean, double *var, double *sk, double *ku)
{
    const int n = 24000;
    double h = 24.0 / n, r[5] = {0};
    for (int i = 0; i <= n; i++) {
        double u = -12 + i * h, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        double y = srf_johnson_apply(j, u), p = w * exp(-0.5 * u * u) / sqrt(2 * PI);
        for (int k = 1; k <= 4; k++) r[k] += (p *= y);
    }
    for (int k = 1; k <= 4; k++) r[k] *= h / 3;
    double m = r[1], v = r[2] - m * m;
    *mean = m;
    *var = v;
    *sk = (r[3] - 3 * m * r[2] + 2 * m * m * m) / pow(v, 1.5);
    *ku = (r[4] - 4 * m * r[3] + 6 * m * m * r[2] - 3 * m * m * m * m) / (v * v);
}

static void test_johnson_fit(void **state)
{
    (void)state;
    /* SU (above the lognormal line), SB (below), symmetric ones, Gaussian */
    const double cases[][3] = {{0.5, 4.0, 'U'}, {-0.8, 5.0, 'U'}, {0, 6, 'U'}, {1.0, 4.4, 'B'},
                               {0.3, 2.5, 'B'}, {0, 2.2, 'B'}, {-0.5, 3.0, 'B'}, {0, 3, 'N'}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        srf_johnson j;
        double m, v, sk, ku;
        stc_error_clear();
        stc_status st = srf_johnson_fit(cases[c][0], cases[c][1], &j);
        if (st != STC_OK) fail_msg("fit (%g, %g): %s", cases[c][0], cases[c][1], stc_errmsg());
        js_moments(&j, &m, &v, &sk, &ku);
        print_message("  target (%+.2f, %.2f) -> S%c gamma %+.4f delta %.4f: mean %.1e var %.8f "
                      "skew %+.6f kurt %.6f\n", cases[c][0], cases[c][1], j.family, j.gamma,
                      j.delta, m, v, sk, ku);
        assert_int_equal(j.family, (int)cases[c][2]);
        assert_true(fabs(m) < 1e-6 && fabs(v - 1) < 1e-6);
        assert_true(fabs(sk - cases[c][0]) < 1e-5 && fabs(ku - cases[c][1]) < 1e-5);
    }
    srf_johnson j;
    stc_error_clear();
    assert_int_equal(srf_johnson_fit(1.0, 1.9, &j), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "kurtosis = 1.9: must be > skewness"));
}

/* A translated map reports the moments it actually reached; with ~1000
 * correlation areas the sample skewness/kurtosis scatter by ~0.1/0.3, so the
 * bound is statistical (0.15, 0.6), the report exact (recomputed here). */
static void test_johnson_map(void **state)
{
    (void)state;
    srf_synth_params p = exponential(256, 256, 0.03, 0.03);
    p.non_gaussian = 1;
    p.skewness = 0.6;
    p.kurtosis = 4.5;
    srf_map *m = NULL;
    assert_int_equal(srf_synthesize(&p, 5, &m), STC_OK);
    double s3 = 0, s4 = 0, n = 256.0 * 256.0;
    for (int k = 0; k < 256 * 256; k++) {
        double u = m->z[k] / p.rms;
        s3 += u * u * u;
        s4 += u * u * u * u;
    }
    print_message("  Johnson %s map: skewness %.4f kurtosis %.4f (targets 0.6, 4.5)\n", m->johnson,
                  m->skewness_reached, m->kurtosis_reached);
    assert_string_equal(m->johnson, "SU");
    assert_true(relerr(m->skewness_reached, s3 / n) < 1e-10);
    assert_true(relerr(m->kurtosis_reached, s4 / n) < 1e-10);
    assert_true(fabs(m->skewness_reached - 0.6) < 0.15);
    assert_true(fabs(m->kurtosis_reached - 4.5) < 0.6);
    srf_map_destroy(&m);
}

/* ------------------------------------------------------------ files */

static char tmpdir[256];

static void path_in(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/%s", tmpdir, name);
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_import_text_detrend(void **state)
{
    (void)state;
    char path[512];
    path_in(path, sizeof path, "plane.txt");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "# tilted plane, um\n");
    for (int j = 0; j < 7; j++) {
        for (int i = 0; i < 9; i++) fprintf(f, "%s%.17g", i ? (i % 2 ? "\t" : ", ") : "", 3.0 + 0.2 * i - 0.5 * j);
        fprintf(f, "   \n");
    }
    fclose(f);
    srf_map *m = NULL;
    assert_int_equal(srf_map_import_text(path, 0.01, 0.02, 1e-3, &m), STC_OK);
    assert_int_equal(m->nx, 9);
    assert_int_equal(m->ny, 7);
    assert_true(relerr(m->lx, 0.09) < 1e-15 && relerr(m->ly, 0.14) < 1e-15);
    double worst = 0;
    for (int k = 0; k < 63; k++) worst = fmax(worst, fabs(m->z[k]));
    print_message("  tilted plane after detrend: max |z| = %.2e mm; tilt %.6g, %.6g\n", worst,
                  m->tilt_x, m->tilt_y);
    assert_true(worst < 1e-15);
    /* slopes: 0.2 um per 0.01 mm and -0.5 um per 0.02 mm */
    assert_true(relerr(m->tilt_x, 0.2e-3 / 0.01) < 1e-12);
    assert_true(relerr(m->tilt_y, -0.5e-3 / 0.02) < 1e-12);
    assert_int_equal(m->origin, SRF_ORIGIN_IMPORT);
    srf_map_destroy(&m);
}

static void expect_bad_text(const char *text, const char *needle)
{
    char path[512];
    path_in(path, sizeof path, "bad.txt");
    write_text(path, text);
    srf_map *m = (srf_map *)path;
    stc_error_clear();
    stc_status st = srf_map_import_text(path, 0.01, 0.01, 1, &m);
    assert_int_equal(st, STC_EFORMAT);
    assert_null(m);
    if (!strstr(stc_errmsg(), needle)) fail_msg("message '%s' lacks '%s'", stc_errmsg(), needle);
}

static void test_import_malformed(void **state)
{
    (void)state;
    expect_bad_text("1 2 3\n4 5 6\n7 x8 9\n", "line 3, column 2");
    expect_bad_text("1 2 3\n4 5 6\n7 8\n", "line 3 has 2 values, expected 3");
    expect_bad_text("1 2 3\n4 nan 6\n7 8 9\n", "line 2, column 2");
    expect_bad_text("1 2 3\n4 1e999 6\n7 8 9\n", "'1e999' is not a finite number");
    expect_bad_text("1 2 3 4\n5 6 7 8\n", "at least 3 x 3");
    expect_bad_text("", "0 rows");
    expect_bad_text("1 2 3\n4 5 6\n7 8 9 # ok\n\x01\x02\n", "line 4, column 1");
    srf_map *m = NULL;
    stc_error_clear();
    assert_int_equal(srf_map_import_text("/nonexistent/x.txt", 0.01, 0.01, 1, &m), STC_EIO);
    assert_non_null(strstr(stc_errmsg(), "/nonexistent/x.txt"));
    char path[512];
    path_in(path, sizeof path, "ok.txt");
    write_text(path, "1 2 3\n4 5 6\n7 8 9\n");
    assert_int_equal(srf_map_import_text(path, -1, 0.01, 1, &m), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "pixel-size dx = -1"));
    assert_int_equal(srf_map_read(path, &m), STC_EFORMAT); /* text is not HDF5 */
    assert_non_null(strstr(stc_errmsg(), "not an HDF5 file"));
    assert_int_equal(srf_map_read("/nonexistent/x.h5", &m), STC_EIO);
    assert_non_null(strstr(stc_errmsg(), "No such file"));
}

static void test_h5_roundtrip(void **state)
{
    (void)state;
    char path[512];
    path_in(path, sizeof path, "map.h5");
    srf_synth_params p = self_affine(64, 48);
    p.non_gaussian = 1;
    p.skewness = -0.3;
    p.kurtosis = 3.5;
    srf_map *a = NULL, *b = NULL;
    assert_int_equal(srf_synthesize(&p, 77, &a), STC_OK);
    assert_int_equal(srf_map_write_h5(a, path), STC_OK);
    assert_int_equal(srf_map_read(path, &b), STC_OK);
    assert_int_equal(b->nx, 64);
    assert_int_equal(b->ny, 48);
    assert_memory_equal(a->z, b->z, 64 * 48 * sizeof(double));
    assert_true(b->origin == SRF_ORIGIN_SYNTH && b->seed == 77);
    assert_true(b->synth.spectrum == SRF_SPECTRUM_SELF_AFFINE && b->synth.hurst == p.hurst);
    assert_true(b->synth.lambda_cutoff == p.lambda_cutoff && b->synth.skewness == -0.3);
    assert_true(b->skewness_reached == a->skewness_reached);
    assert_string_equal(b->johnson, a->johnson);
    /* the stored parameters re-synthesize the same map */
    srf_map *c = NULL;
    assert_int_equal(srf_synthesize(&b->synth, b->seed, &c), STC_OK);
    assert_memory_equal(a->z, c->z, 64 * 48 * sizeof(double));
    srf_map_destroy(&c);
    srf_map_destroy(&b);

    /* import the dataset of that file as a "measured" map: detrended copy */
    assert_int_equal(srf_map_import_h5(path, "/height", 1.0 / 64, 1.0 / 64, 1, &c), STC_OK);
    assert_true(c->origin == SRF_ORIGIN_IMPORT);
    double worst = 0;
    for (int j = 0; j < 48; j++)
        for (int i = 0; i < 64; i++)
            worst = fmax(worst, fabs(c->z[j * 64 + i] + c->tilt_x * i / 64.0 + c->tilt_y * j / 64.0 +
                                     c->offset - a->z[j * 64 + i]));
    assert_true(worst < 1e-17);
    /* an imported map stays non-periodic through a write/read cycle */
    char path2[512];
    srf_map *d = NULL;
    path_in(path2, sizeof path2, "imported.h5");
    assert_int_equal(srf_map_write_h5(c, path2), STC_OK);
    assert_int_equal(srf_map_read(path2, &d), STC_OK);
    assert_true(d->periodic == 0 && d->origin == SRF_ORIGIN_IMPORT && d->tilt_x == c->tilt_x);
    assert_memory_equal(c->z, d->z, 64 * 48 * sizeof(double));
    srf_map_destroy(&d);
    assert_int_equal(srf_map_import_h5(path, "/nothere", 0.1, 0.1, 1, &b), STC_EFORMAT);
    assert_non_null(strstr(stc_errmsg(), "no dataset '/nothere'"));
    srf_map_destroy(&c);
    srf_map_destroy(&a);

    /* a failed write leaves nothing behind */
    char bad[512];
    path_in(bad, sizeof bad, "nodir/x.h5");
    assert_int_equal(srf_synthesize(&p, 1, &a), STC_OK);
    assert_int_equal(srf_map_write_h5(a, bad), STC_EIO);
    assert_int_equal(access(bad, F_OK), -1);
    srf_map_destroy(&a);
}

/* The PNG: the map one grey pixel a point (black = lowest, white = highest,
 * y up) at its top left, a caption below it. */
static void test_png(void **state)
{
    (void)state;
    char path[512];
    path_in(path, sizeof path, "map.png");
    srf_synth_params p = exponential(40, 30, 0.1, 0.1);
    srf_map *m = NULL;
    assert_int_equal(srf_synthesize(&p, 1, &m), STC_OK);
    assert_int_equal(srf_map_write_png(m, path), STC_OK);
    unsigned char h[8];
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    assert_int_equal(fread(h, 1, 8, f), 8);
    fclose(f);
    assert_memory_equal(h, "\x89PNG\r\n\x1a\n", 8);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    assert_true(png_image_begin_read_from_file(&img, path));
    img.format = PNG_FORMAT_GRAY;
    assert_true(img.width >= 40 && img.height > 30);
    unsigned char *px = malloc(PNG_IMAGE_SIZE(img));
    assert_non_null(px);
    assert_true(png_image_finish_read(&img, NULL, px, 0, NULL));
    double lo = m->z[0], hi = m->z[0];
    for (int k = 0; k < 40 * 30; k++) lo = fmin(lo, m->z[k]), hi = fmax(hi, m->z[k]);
    int lo_seen = 0, hi_seen = 0, ink = 0;
    for (int r = 0; r < 30; r++)
        for (int i = 0; i < 40; i++) {
            double z = m->z[(29 - r) * 40 + i]; /* row 0 of the picture: the highest y */
            unsigned char v = px[(size_t)r * img.width + i];
            assert_int_equal(v, (int)lrint((z - lo) * 255.0 / (hi - lo)));
            lo_seen += v == 0, hi_seen += v == 255;
        }
    assert_true(lo_seen >= 1 && hi_seen >= 1);
    for (size_t k = (size_t)31 * img.width; k < (size_t)img.width * img.height; k++) ink += px[k] == 0;
    assert_true(ink > 200); /* the caption's text */
    free(px);
    srf_map_destroy(&m);
}

static int setup(void **state)
{
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "%s/stiction-synth-XXXXXX", test_tmpdir());
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

/* The library leaves its caller's settings alone: FFTW's planner thread
 * count (process-wide) is what the caller set after a synthesis planned on
 * two threads, and the files it writes get the caller's umask (no umask()
 * round trip inside). */
static void test_caller_settings(void **state)
{
    (void)state;
    assert_int_not_equal(fftw_init_threads(), 0);
    fftw_plan_with_nthreads(3);
    srf_synth_params p = self_affine(64, 48);
    p.threads = 2;
    srf_map *m = NULL;
    assert_int_equal(srf_synthesize(&p, 5, &m), STC_OK);
    assert_int_equal(fftw_planner_nthreads(), 3);
    fftw_plan_with_nthreads(1);
    mode_t old = umask(027);
    char h5[512], png[512];
    path_in(h5, sizeof h5, "mode.h5");
    path_in(png, sizeof png, "mode.png");
    assert_int_equal(srf_map_write_h5(m, h5), STC_OK);
    assert_int_equal(srf_map_write_png(m, png), STC_OK);
    umask(old);
    struct stat a, b;
    assert_int_equal(stat(h5, &a), 0);
    assert_int_equal(stat(png, &b), 0);
    assert_int_equal(a.st_mode & 0777, 0640);
    assert_int_equal(b.st_mode & 0777, 0640);
    remove(h5);
    remove(png);
    srf_map_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parseval_hermitian), cmocka_unit_test(test_moments_exact),
        cmocka_unit_test(test_rms_exact),          cmocka_unit_test(test_reproducible),
        cmocka_unit_test(test_rayleigh_bounds),    cmocka_unit_test(test_exponential_acf),
        cmocka_unit_test(test_self_affine_psd),    cmocka_unit_test(test_invalid_params),
        cmocka_unit_test(test_johnson_fit),        cmocka_unit_test(test_johnson_map),
        cmocka_unit_test(test_import_text_detrend), cmocka_unit_test(test_import_malformed),
        cmocka_unit_test(test_h5_roundtrip),       cmocka_unit_test(test_png),
        cmocka_unit_test(test_caller_settings),
    };
    return cmocka_run_group_tests_name("synth", tests, setup, teardown);
}
