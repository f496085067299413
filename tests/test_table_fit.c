/* Gaussian-process smoothing surrogate (asperity/table_fit.c): smoothing of
 * a noisy 1D curve (coverage of the truth, error below the noise), an
 * understated noise recovered by the noise scale, held-out points of a 3D
 * grid, a constant input dimension, interpolation at tiny noise, the
 * closed-form leave-one-out against refits without each point, the
 * likelihood against a direct computation and its optimality, length
 * scales modulated along one input (Gibbs's kernel), a main term scaled by
 * one input over a base term, invalid input, and
 * bit-identical refits, searched again or at the found hyperparameters. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include <gsl/gsl_linalg.h>

#include "table_fit.h"
#include "rand_util.h"

/* ---- deterministic noise --------------------------------------------- */

/* Standard normal by Box-Muller. */
static double gauss(uint64_t *s)
{
    double u = unif(s), v = unif(s);
    return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void check_ok(stc_status st, const char *what)
{
    if (st != STC_OK) fail_msg("%s: %s: %s", what, stc_strerror(st), stc_errmsg());
}

static tbl_gp *fit_ok(int n, int dim, const double *x, const double *y, const double *sy)
{
    tbl_gp *g = NULL;
    check_ok(tbl_gp_fit(n, dim, x, y, sy, &g), "tbl_gp_fit");
    assert_non_null(g);
    return g;
}

static void print_info(const char *what, const tbl_gp_info *in);

/* A fit with kernel options, its summary in *in, printed as what. */
static tbl_gp *fit_kernel_ok(int n, int dim, const double *x, const double *y, const double *sy,
                             const tbl_gp_kernel *kernel, const char *what, tbl_gp_info *in)
{
    tbl_gp *g = NULL;
    stc_error_clear();
    check_ok(tbl_gp_fit_kernel(n, dim, x, y, sy, kernel, &g), "tbl_gp_fit_kernel");
    assert_non_null(g);
    tbl_gp_get_info(g, in);
    print_info(what, in);
    return g;
}

static void print_info(const char *what, const tbl_gp_info *in)
{
    printf("%s: ell = (", what);
    for (int d = 0; d < in->dim; d++) printf("%s%.4g", d ? ", " : "", in->ell[d]);
    printf("), sf = %.4g, c = %.4f, mean = %.4g, log_ml = %.4f, LOO rms %.4g max %.4g cover2 "
           "%.3f, %d evaluations%s, jitter %g\n",
           in->sf, in->noise_scale, in->mean, in->log_ml, in->loo_rms, in->loo_max,
           in->loo_cover2, in->evaluations, in->converged ? "" : " (NOT converged)", in->jitter);
}

/* ---- 1D smoothing -------------------------------------------------------- */

#define N1 30
#define SD1 0.1

static double f1(double x) { return sin(2.0 * M_PI * x) + 0.5 * x; }

/* 30 points on [0, 1] with noise of sd SD1 (a fixed draw). */
static void data1(double *x, double *y)
{
    uint64_t s = 20240601u;
    for (int i = 0; i < N1; i++) {
        x[i] = (double)i / (N1 - 1);
        y[i] = f1(x[i]) + SD1 * gauss(&s);
    }
}

/* Fraction of 200 test points with |mu - f| <= k sd, and the rms of mu - f. */
static void score1(const tbl_gp *g, double k, double *frac, double *rms)
{
    int in = 0, m = 200;
    double ss = 0.0;
    for (int j = 0; j < m; j++) {
        double x = (j + 0.5) / m, mu, sd;
        tbl_gp_predict(g, &x, &mu, &sd);
        double e = mu - f1(x);
        ss += e * e;
        in += fabs(e) <= k * sd;
    }
    *frac = (double)in / m;
    *rms = sqrt(ss / m);
}

static void test_smooth_1d(void **state)
{
    (void)state;
    double x[N1], y[N1], sy[N1];
    data1(x, y);
    for (int i = 0; i < N1; i++) sy[i] = SD1;
    double t0 = now();
    tbl_gp *g = fit_ok(N1, 1, x, y, sy);
    double dt = now() - t0;
    tbl_gp_info in;
    tbl_gp_get_info(g, &in);
    print_info("1D, n = 30, noise sd 0.1", &in);
    double frac, rms;
    score1(g, 3.0, &frac, &rms);
    printf("1D: truth within 3 posterior sd at %.1f %% of 200 test points; rms(mean - truth) = "
           "%.4f = %.2f x noise sd; noise scale c = %.3f; fit %.1f ms\n",
           100 * frac, rms, rms / SD1, in.noise_scale, 1e3 * dt);
    assert_true(frac >= 0.95);
    assert_true(rms < 0.5 * SD1);
    assert_true(in.noise_scale >= 1.0 && in.noise_scale < 1.5);
    assert_true(in.converged);
    tbl_gp_destroy(&g);
    assert_null(g);
}

/* The same data with sy = true sd / 4: c must make up the difference. */
static void test_understated_noise(void **state)
{
    (void)state;
    double x[N1], y[N1], sy[N1];
    data1(x, y);
    for (int i = 0; i < N1; i++) sy[i] = SD1 / 4;
    tbl_gp *g = fit_ok(N1, 1, x, y, sy);
    tbl_gp_info in;
    tbl_gp_get_info(g, &in);
    print_info("1D, sy = true sd / 4", &in);
    double frac, rms;
    score1(g, 3.0, &frac, &rms);
    printf("understated noise: c = %.3f (true 4), LOO 2-sd coverage %.3f, truth within 3 sd at "
           "%.1f %%, rms(mean - truth) = %.2f x noise sd\n",
           in.noise_scale, in.loo_cover2, 100 * frac, rms / SD1);
    assert_true(in.noise_scale > 2.0);
    assert_true(in.loo_cover2 >= 0.85);
    tbl_gp_destroy(&g);
}

/* ---- 3D grid --------------------------------------------------------------- */

static double f3(const double *x)
{
    return exp(-x[0]) * (1.0 + 0.5 * x[1]) + 0.3 * sin(2.0 * x[2]) * x[0];
}

static void test_grid_3d(void **state)
{
    (void)state;
    enum { NA = 6, NB = 3, NC = 3, N = NA * NB * NC };
    double x[N][3], y[N], sy[N], sd_noise = 0.01;
    uint64_t s = 77u;
    int n = 0;
    for (int a = 0; a < NA; a++)
        for (int b = 0; b < NB; b++)
            for (int c = 0; c < NC; c++, n++) {
                x[n][0] = 2.0 * a / (NA - 1); /* inputs on different scales */
                x[n][1] = 10.0 * b / (NB - 1);
                x[n][2] = 0.5 * c / (NC - 1);
                double u[3] = {x[n][0], x[n][1] / 10.0, x[n][2] * 2.0};
                sy[n] = sd_noise * (1.0 + 0.5 * unif(&s)); /* per-point error estimates */
                y[n] = f3(u) + sy[n] * gauss(&s);
            }
    tbl_gp *g = fit_ok(N, 3, &x[0][0], y, sy);
    tbl_gp_info in;
    tbl_gp_get_info(g, &in);
    print_info("3D 6x3x3 grid", &in);
    /* held out: every cell centre */
    int inside = 0, m = 0;
    double worst = 0.0;
    for (int a = 0; a < NA - 1; a++)
        for (int b = 0; b < NB - 1; b++)
            for (int c = 0; c < NC - 1; c++, m++) {
                double q[3] = {2.0 * (a + 0.5) / (NA - 1), 10.0 * (b + 0.5) / (NB - 1),
                               0.5 * (c + 0.5) / (NC - 1)};
                double u[3] = {q[0], q[1] / 10.0, q[2] * 2.0}, mu, sd;
                tbl_gp_predict(g, q, &mu, &sd);
                double z = fabs(mu - f3(u)) / sd;
                worst = fmax(worst, z);
                inside += z <= 2.0;
            }
    printf("3D: %d of %d cell centres within 2 posterior sd (worst %.2f sd); LOO 2-sd coverage "
           "%.3f\n", inside, m, worst, in.loo_cover2);
    assert_true(inside >= 0.9 * m);
    assert_true(in.loo_cover2 >= 0.85);
    tbl_gp_destroy(&g);
}

/* x_2 equal everywhere: the dimension is ignored, ell[1] = inf. */
static void test_constant_dim(void **state)
{
    (void)state;
    enum { N = 12 };
    double x[N][2], y[N], sy[N];
    uint64_t s = 5u;
    for (int i = 0; i < N; i++) {
        x[i][0] = (double)i / (N - 1);
        x[i][1] = 0.7;
        sy[i] = 0.05;
        y[i] = f1(x[i][0]) + sy[i] * gauss(&s);
    }
    tbl_gp *g = fit_ok(N, 2, &x[0][0], y, sy);
    tbl_gp_info in;
    tbl_gp_get_info(g, &in);
    print_info("2D with x_2 constant", &in);
    double q1[2] = {0.33, 0.7}, q2[2] = {0.33, 5.0}, m1, s1, m2, s2;
    tbl_gp_predict(g, q1, &m1, &s1);
    tbl_gp_predict(g, q2, &m2, &s2);
    printf("constant x_2: ell[1] = %g (bounds %g..%g); prediction at x_2 = 0.7 and 5: "
           "%.6f +- %.6f, %.6f +- %.6f\n",
           in.ell[1], in.ell_lo[1], in.ell_hi[1], m1, s1, m2, s2);
    assert_true(isinf(in.ell[1]) && in.ell[1] > 0 && isfinite(in.ell[0]));
    assert_true(m1 == m2 && s1 == s2);
    tbl_gp_destroy(&g);

    /* every input equal: repeated measurements of one value; the mean is the
     * inverse-variance weighted mean, its sd c / sqrt(sum 1/sy^2) */
    double xr[5] = {3, 3, 3, 3, 3}, yr[5] = {1.0, 1.2, 0.9, 1.1, 1.0};
    double sr[5] = {0.1, 0.1, 0.2, 0.1, 0.05}, sw = 0, swy = 0, mr, sdr;
    for (int i = 0; i < 5; i++) sw += 1 / (sr[i] * sr[i]), swy += yr[i] / (sr[i] * sr[i]);
    g = fit_ok(5, 1, xr, yr, sr);
    tbl_gp_get_info(g, &in);
    tbl_gp_predict(g, &xr[0], &mr, &sdr);
    printf("all inputs equal: mean %.12f (weighted mean %.12f), sd %.6g (c / sqrt(sum sy^-2) "
           "= %.6g), c = %.4f, sf = %g\n",
           mr, swy / sw, sdr, in.noise_scale / sqrt(sw), in.noise_scale, in.sf);
    assert_true(isinf(in.ell[0]) && in.sf == 0.0);
    assert_true(fabs(mr - swy / sw) < 1e-12 && fabs(sdr - in.noise_scale / sqrt(sw)) < 1e-12);
    tbl_gp_destroy(&g);
}

/* ---- exactness ------------------------------------------------------------ */

static void test_interpolation(void **state)
{
    (void)state;
    enum { N = 15 };
    double x[N], y[N], sy[N], worst = 0.0, sdmax = 0.0;
    for (int i = 0; i < N; i++) {
        x[i] = 3.0 * i / (N - 1);
        y[i] = f1(x[i] / 3.0);
        sy[i] = 1e-7;
    }
    tbl_gp *g = fit_ok(N, 1, x, y, sy);
    tbl_gp_info in;
    tbl_gp_get_info(g, &in);
    print_info("tiny noise (sy = 1e-7)", &in);
    for (int i = 0; i < N; i++) {
        double mu, sd;
        tbl_gp_predict(g, &x[i], &mu, &sd);
        worst = fmax(worst, fabs(mu - y[i]));
        sdmax = fmax(sdmax, sd);
    }
    printf("tiny noise: max |mean(x_i) - y_i| = %.2e, max sd(x_i) = %.2e (c sy = %.1e)\n", worst,
           sdmax, in.noise_scale * 1e-7);
    assert_true(worst < 1e-5);
    assert_true(sdmax < 1e-5);
    tbl_gp_destroy(&g);
}

/* Direct computation with the fitted hyperparameters (GSL Cholesky):
 * covariance of the points in keep[0..m), kernel to a point, restricted log
 * likelihood, universal-kriging prediction. */
typedef struct direct {
    int dim, mod, scale;
    double ell[3], sf, c, jitter, gamma, centre, bell[3], bsd;
} direct;

/* Gibbs's kernel dimension by dimension, l = ell_d r(x) at each end (for
 * gamma = 0 the squared exponential). */
static double dk_main(const direct *p, const double *a, const double *b)
{
    double ra = 1.0, rb = 1.0, v = 1.0;
    if (p->mod >= 0) {
        ra = exp(p->gamma * (a[p->mod] - p->centre));
        rb = exp(p->gamma * (b[p->mod] - p->centre));
    }
    for (int d = 0; d < p->dim; d++) {
        if (!isfinite(p->ell[d])) continue;
        double la = p->ell[d] * ra, lb = p->ell[d] * rb, q = la * la + lb * lb;
        v *= sqrt(2.0 * la * lb / q) * exp(-pow(a[d] - b[d], 2) / q);
    }
    return v;
}

/* With a scaled main term: the base term's squared exponential plus the
 * scaled main term. */
static double dk(const direct *p, const double *a, const double *b)
{
    if (p->scale < 0) return p->sf * p->sf * dk_main(p, a, b);
    double s = 0.0;
    for (int d = 0; d < p->dim; d++)
        if (isfinite(p->bell[d])) s += pow((a[d] - b[d]) / p->bell[d], 2);
    return p->bsd * p->bsd * exp(-0.5 * s) +
           p->sf * p->sf * a[p->scale] * b[p->scale] * dk_main(p, a, b);
}

/* K of the m points idx[] (factorised), K^-1 y, K^-1 1. */
static void direct_factor(const direct *p, int m, const int *idx, const double *x, const double *y,
                          const double *sy, gsl_matrix *K, gsl_vector *ky, gsl_vector *k1)
{
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            gsl_matrix_set(K, i, j, dk(p, x + idx[i] * p->dim, x + idx[j] * p->dim));
    for (int i = 0; i < m; i++)
        *gsl_matrix_ptr(K, i, i) += pow(p->c * sy[idx[i]], 2) + p->jitter;
    assert_int_equal(gsl_linalg_cholesky_decomp1(K), GSL_SUCCESS);
    for (int i = 0; i < m; i++) {
        gsl_vector_set(ky, i, y[idx[i]]);
        gsl_vector_set(k1, i, 1.0);
    }
    gsl_linalg_cholesky_svx(K, ky);
    gsl_linalg_cholesky_svx(K, k1);
}

static double direct_reml(const direct *p, int n, const double *x, const double *y,
                          const double *sy)
{
    int idx[64];
    gsl_matrix *K = gsl_matrix_alloc(n, n);
    gsl_vector *ky = gsl_vector_alloc(n), *k1 = gsl_vector_alloc(n);
    for (int i = 0; i < n; i++) idx[i] = i;
    direct_factor(p, n, idx, x, y, sy, K, ky, k1);
    double yky = 0, oky = 0, ok1 = 0, logdet = 0;
    for (int i = 0; i < n; i++) {
        yky += y[i] * gsl_vector_get(ky, i);
        oky += gsl_vector_get(ky, i);
        ok1 += gsl_vector_get(k1, i);
        logdet += 2 * log(gsl_matrix_get(K, i, i));
    }
    gsl_matrix_free(K);
    gsl_vector_free(ky);
    gsl_vector_free(k1);
    return -0.5 * (yky - oky * oky / ok1) - 0.5 * logdet - 0.5 * log(ok1) -
           0.5 * (n - 1) * log(2 * M_PI);
}

/* Refit without point i (hyperparameters fixed, GLS mean re-estimated):
 * mean and sd of y_i. */
static void direct_loo(const direct *p, int n, const double *x, const double *y, const double *sy,
                       int i, double *mu, double *sd)
{
    int idx[64], m = 0;
    for (int j = 0; j < n; j++)
        if (j != i) idx[m++] = j;
    gsl_matrix *K = gsl_matrix_alloc(m, m);
    gsl_vector *ky = gsl_vector_alloc(m), *k1 = gsl_vector_alloc(m), *ks = gsl_vector_alloc(m);
    direct_factor(p, m, idx, x, y, sy, K, ky, k1);
    double ok1 = 0, oky = 0;
    for (int j = 0; j < m; j++) ok1 += gsl_vector_get(k1, j), oky += gsl_vector_get(ky, j);
    double mhat = oky / ok1, f = mhat, kKk = 0, kK1 = 0;
    for (int j = 0; j < m; j++) {
        double kj = dk(p, x + i * p->dim, x + idx[j] * p->dim);
        gsl_vector_set(ks, j, kj);
        f += kj * (gsl_vector_get(ky, j) - mhat * gsl_vector_get(k1, j));
        kK1 += kj * gsl_vector_get(k1, j);
    }
    gsl_vector *v = gsl_vector_alloc(m);
    gsl_vector_memcpy(v, ks);
    gsl_linalg_cholesky_svx(K, v);
    for (int j = 0; j < m; j++) kKk += gsl_vector_get(ks, j) * gsl_vector_get(v, j);
    double var = p->sf * p->sf - kKk + (1 - kK1) * (1 - kK1) / ok1 + pow(p->c * sy[i], 2) +
                 p->jitter;
    *mu = f;
    *sd = sqrt(var);
    gsl_matrix_free(K);
    gsl_vector_free(ky);
    gsl_vector_free(k1);
    gsl_vector_free(ks);
    gsl_vector_free(v);
}

static direct direct_from(const tbl_gp_info *in)
{
    direct p = {.dim = in->dim, .sf = in->sf, .c = in->noise_scale, .jitter = in->jitter,
                .mod = in->mod_dim, .gamma = in->gamma, .centre = in->mod_centre,
                .scale = in->scale_dim, .bsd = in->base_sd};
    for (int d = 0; d < 3; d++) p.ell[d] = in->ell[d], p.bell[d] = in->base_ell[d];
    return p;
}

/* Closed-form LOO against refits without each point, log_ml against the
 * direct computation, and optimality of the fitted hyperparameters. */
static void check_exact(const char *what, int n, int dim, const double *x, const double *y,
                        const double *sy, const tbl_gp_kernel *kernel)
{
    tbl_gp_info in;
    tbl_gp *g = fit_kernel_ok(n, dim, x, y, sy, kernel, what, &in);
    direct p = direct_from(&in);
    double mu[64], sd[64], emu = 0, esd = 0;
    tbl_gp_loo(g, mu, sd);
    for (int i = 0; i < n; i++) {
        double m, v;
        direct_loo(&p, n, x, y, sy, i, &m, &v);
        emu = fmax(emu, fabs(m - mu[i]));
        esd = fmax(esd, fabs(v - sd[i]));
    }
    double lml = direct_reml(&p, n, x, y, sy);
    printf("%s: LOO closed form vs %d refits without the point: max |d mean| = %.2e, "
           "max |d sd| = %.2e; log_ml %.10f vs direct %.10f\n",
           what, n, emu, esd, in.log_ml, lml);
    assert_true(emu < 1e-8 && esd < 1e-8);
    assert_true(fabs(lml - in.log_ml) < 1e-8 * fmax(1.0, fabs(lml)));

    /* optimality: +-5 % in each interior hyperparameter (gamma: +-0.05 / half
     * the modulating input's range) lowers the likelihood */
    double worst_gain = -INFINITY;
    for (int k = 0; k < 2 * dim + 4; k++) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            direct q = p;
            double fac = exp(0.05 * sgn);
            if (k < dim) {
                if (in.ell_at_bound[k] || !isfinite(q.ell[k])) continue;
                q.ell[k] *= fac;
            } else if (k == dim) {
                q.sf *= fac;
                q.bsd *= fac; /* both terms: sf^2 is the profiled common scale */
            } else if (k == dim + 2) {
                if (in.mod_dim < 0 || in.gamma_at_bound) continue;
                q.gamma += 0.02 * sgn;
            } else if (k == dim + 3) {
                if (in.scale_dim < 0) continue;
                q.bsd *= fac;
            } else if (k > dim + 3) {
                if (!isfinite(q.bell[k - dim - 4])) continue;
                q.bell[k - dim - 4] *= fac;
            } else {
                if (q.c * fac < 1.0 || q.c * fac > 10.0) continue;
                q.c *= fac;
            }
            worst_gain = fmax(worst_gain, direct_reml(&q, n, x, y, sy) - lml);
        }
    }
    printf("%s: best change of log_ml under +-5 %% steps in ell, sf, c (gamma, base sd and ell): "
           "%.3e (must be <= 0)\n",
           what, worst_gain);
    assert_true(worst_gain <= 1e-9);
    tbl_gp_destroy(&g);
}

static void test_loo_and_likelihood(void **state)
{
    (void)state;
    enum { N = 24, NA = 6, NB = 3, NC = 3, NG = NA * NB * NC };
    double x[N][2], y[N], sy[N];
    uint64_t s = 99u;
    for (int i = 0; i < N; i++) {
        x[i][0] = unif(&s);
        x[i][1] = 4.0 * unif(&s);
        sy[i] = 0.05 * (1 + unif(&s));
        y[i] = sin(3 * x[i][0]) * cos(x[i][1]) + sy[i] * gauss(&s);
    }
    check_exact("2D scattered, n = 24", N, 2, &x[0][0], y, sy, NULL);
    /* a grid: K is built from per-dim tables of kernel factors */
    double xg[NG][3], yg[NG], sg[NG];
    int k = 0;
    for (int a = 0; a < NA; a++)
        for (int b = 0; b < NB; b++)
            for (int c = 0; c < NC; c++, k++) {
                xg[k][0] = 0.2 * a, xg[k][1] = 0.5 * b, xg[k][2] = 0.5 * c;
                sg[k] = 0.02;
                yg[k] = f3(xg[k]) + sg[k] * gauss(&s);
            }
    check_exact("3D grid 6x3x3", NG, 3, &xg[0][0], yg, sg, NULL);
}

/* ---- length scales modulated along one input ------------------------------ */

/* Rough at small x_1, smooth at large: sin(2 pi x_0 nu(x_1)), nu from 2
 * cycles to 0.4 over x_1 in [0, 2]. */
static double frough(const double *x) { return sin(2.0 * M_PI * x[0] * 2.0 * exp(-0.8 * x[1])); }

/* On a function whose roughness changes along x_1 the modulated kernel
 * finds it (gamma > 0: longer scales where it is smoother), fits better and
 * predicts better between the nodes than the stationary one; its closed
 * forms hold as the stationary kernel's do. */
static void test_modulated(void **state)
{
    (void)state;
    enum { NA = 12, NB = 9, N = NA * NB, NS = 40 };
    double x[N][2], y[N], sy[N];
    uint64_t s = 4242u;
    for (int a = 0, k = 0; a < NA; a++)
        for (int b = 0; b < NB; b++, k++) {
            x[k][0] = (double)a / (NA - 1);
            x[k][1] = 2.0 * b / (NB - 1);
            sy[k] = 0.03;
            y[k] = frough(x[k]) + sy[k] * gauss(&s);
        }
    const tbl_gp_kernel km = {.mod_dim = 1, .scale_dim = -1};
    tbl_gp_info is, im;
    tbl_gp *gs = fit_kernel_ok(N, 2, &x[0][0], y, sy, NULL, "rough-to-smooth 12x9, stationary", &is);
    tbl_gp *gm = fit_kernel_ok(N, 2, &x[0][0], y, sy, &km, "rough-to-smooth 12x9, modulated", &im);
    double ss[2] = {0, 0};
    int m = 0, inside = 0;
    for (int a = 0; a + 1 < NA; a++)
        for (int b = 0; b + 1 < NB; b++, m++) {
            double q[2] = {(a + 0.5) / (NA - 1), 2.0 * (b + 0.5) / (NB - 1)}, mu, sd;
            tbl_gp_predict(gs, q, &mu, NULL);
            ss[0] += pow(mu - frough(q), 2);
            tbl_gp_predict(gm, q, &mu, &sd);
            ss[1] += pow(mu - frough(q), 2);
            inside += fabs(mu - frough(q)) <= 2.0 * sd;
        }
    double rs = sqrt(ss[0] / m), rm = sqrt(ss[1] / m);
    printf("modulated: gamma %.3f (centre %.2f), log_ml %.2f vs stationary %.2f; cell centres: "
           "rms error %.4f vs %.4f, %d of %d within 2 sd\n", im.gamma, im.mod_centre, im.log_ml,
           is.log_ml, rm, rs, inside, m);
    assert_int_equal(im.mod_dim, 1);
    assert_int_equal(is.mod_dim, -1);
    assert_true(im.gamma > 0.0 && !im.gamma_at_bound);
    assert_true(im.log_ml > is.log_ml + 2.0);
    assert_true(rm < 0.8 * rs);
    assert_true(inside >= 0.9 * m);
    tbl_gp_destroy(&gs);
    tbl_gp_destroy(&gm);

    /* closed-form LOO and likelihood against direct computation */
    double xs[NS][2], ys[NS], ss2[NS];
    for (int i = 0; i < NS; i++) {
        xs[i][0] = unif(&s);
        xs[i][1] = 2.0 * unif(&s);
        ss2[i] = 0.03 * (1 + unif(&s));
        ys[i] = frough(xs[i]) + ss2[i] * gauss(&s);
    }
    check_exact("2D scattered, modulated along x_1, n = 40", NS, 2, &xs[0][0], ys, ss2, &km);

    /* a constant modulating input modulates nothing; a bad index is refused */
    for (int i = 0; i < NS; i++) xs[i][1] = 1.0;
    assert_int_equal(tbl_gp_fit_kernel(NS, 2, &xs[0][0], ys, ss2, &km, &gm), STC_OK);
    tbl_gp_get_info(gm, &im);
    assert_int_equal(im.mod_dim, -1);
    assert_true(im.gamma == 0.0);
    tbl_gp_destroy(&gm);
    stc_error_clear();
    const tbl_gp_kernel bad = {.mod_dim = 2, .scale_dim = -1};
    assert_int_equal(tbl_gp_fit_kernel(NS, 2, &xs[0][0], ys, ss2, &bad, &gm), STC_EINVAL);
    assert_null(gm);
    printf("refused: %s\n", stc_errmsg());
    assert_non_null(strstr(stc_errmsg(), "mod_dim = 2"));
}

/* ---- a main term scaled by one input over a base term ------------------- */

/* A base curve in x_0 plus an effect in proportion to x_2 that depends on
 * x_0 and x_1, as a table's uncoated curve (ln Eco/Esu = 0) and its
 * coating's effect. */
static double base0(double u) { return 0.5 * sin(2.0 * u) - 0.3 * u; }
static double fscaled(const double *x)
{
    return base0(x[0]) + x[2] * (0.4 + 0.3 * x[0] * x[1] - 0.2 * x[1] * x[1]);
}

/* The scaled kernel fits such data better than the stationary one, reads
 * the same at x_2 = 0 whatever x_1 (the base term alone), and its closed
 * forms hold. */
static void test_scaled(void **state)
{
    (void)state;
    enum { NA = 5, NB = 3, NC = 3, N = NA * NB * NC };
    double x[N][3], y[N], sy[N];
    const double cv[NC] = {0.0, log(2.0), log(4.0)};
    uint64_t s = 515u;
    int k = 0;
    for (int a = 0; a < NA; a++)
        for (int b = 0; b < NB; b++)
            for (int c = 0; c < NC; c++, k++) {
                x[k][0] = 0.5 * a, x[k][1] = 0.5 * b, x[k][2] = cv[c];
                sy[k] = 0.02;
                y[k] = fscaled(x[k]) + sy[k] * gauss(&s);
            }
    const tbl_gp_kernel ks = {.mod_dim = -1, .scale_dim = 2, .base_dims = 1u};
    tbl_gp_info is, ik;
    tbl_gp *gs = fit_kernel_ok(N, 3, &x[0][0], y, sy, NULL, "base + x_2 effect 5x3x3, stationary",
                               &is);
    tbl_gp *gk = fit_kernel_ok(N, 3, &x[0][0], y, sy, &ks, "base + x_2 effect 5x3x3, scaled", &ik);
    assert_int_equal(ik.scale_dim, 2);
    assert_true(isfinite(ik.base_ell[0]) && !isfinite(ik.base_ell[1]) && !isfinite(ik.base_ell[2]));
    assert_true(ik.log_ml > is.log_ml + 2.0);
    /* at x_2 = 0 the prediction does not depend on x_1 */
    double spread = 0.0, ss[2] = {0, 0};
    int m = 0;
    for (int a = 0; a + 1 < NA; a++) {
        double q0[3] = {0.5 * a + 0.25, 0.0, 0.0}, q1[3] = {0.5 * a + 0.25, 1.0, 0.0}, m0, m1;
        tbl_gp_predict(gk, q0, &m0, NULL);
        tbl_gp_predict(gk, q1, &m1, NULL);
        spread = fmax(spread, fabs(m1 - m0));
        for (int b = 0; b + 1 < NB; b++, m++) {
            double q[3] = {0.5 * a + 0.25, 0.5 * b + 0.25, log(1.4)}, mu;
            tbl_gp_predict(gs, q, &mu, NULL);
            ss[0] += pow(mu - fscaled(q), 2);
            tbl_gp_predict(gk, q, &mu, NULL);
            ss[1] += pow(mu - fscaled(q), 2);
        }
    }
    printf("scaled: at x_2 = 0 the prediction moves by %.1e from x_1 = 0 to 1; log_ml %.2f vs "
           "stationary %.2f; between the nodes at x_2 = ln 1.4: rms error %.4f vs %.4f\n", spread,
           ik.log_ml, is.log_ml, sqrt(ss[1] / m), sqrt(ss[0] / m));
    assert_true(spread < 1e-12);
    assert_true(ss[1] < ss[0]);
    tbl_gp_destroy(&gs);
    tbl_gp_destroy(&gk);
    /* closed forms, on a subset small enough for the direct refits */
    check_exact("base + x_2 effect, scaled, n = 45", N, 3, &x[0][0], y, sy, &ks);
    const tbl_gp_kernel both = {.mod_dim = 1, .scale_dim = 2, .base_dims = 1u};
    check_exact("base + x_2 effect, scaled and modulated, n = 45", N, 3, &x[0][0], y, sy, &both);
}

/* ---- invalid input and determinism ------------------------------------------ */

static void expect_bad(int n, int dim, const double *x, const double *y, const double *sy,
                       const char *needle)
{
    tbl_gp *g = (tbl_gp *)&g; /* must be reset to NULL */
    stc_error_clear();
    assert_int_equal(tbl_gp_fit(n, dim, x, y, sy, &g), STC_EINVAL);
    assert_null(g);
    printf("refused: %s\n", stc_errmsg());
    if (!strstr(stc_errmsg(), needle)) fail_msg("message '%s' lacks '%s'", stc_errmsg(), needle);
}

static void test_invalid(void **state)
{
    (void)state;
    double x[6] = {0, 1, 2, 3, 4, 5}, y[6] = {1, 2, 3, 4, 5, 6}, sy[6] = {1, 1, 1, 1, 1, 1};
    expect_bad(1, 1, x, y, sy, "n = 1: must be >= 2");
    expect_bad(6, 0, x, y, sy, "dim = 0: must be in 1..3");
    expect_bad(6, 4, x, y, sy, "dim = 4");
    expect_bad(6, 1, NULL, y, sy, "x = NULL");
    double xb[6] = {0, 1, 2, 3, 4, 5};
    xb[3] = NAN;
    expect_bad(3, 2, xb, y, sy, "x[1][1] = nan: must be finite");
    double yb[6] = {1, 2, 3, 4, 5, 6};
    yb[2] = INFINITY;
    expect_bad(6, 1, x, yb, sy, "y[2] = inf: must be finite");
    double sb[6] = {1, 1, 1, 1, -1, 1};
    expect_bad(6, 1, x, y, sb, "sy[4] = -1: must be finite and > 0");
    sb[4] = 0;
    expect_bad(6, 1, x, y, sb, "sy[4] = 0");
    assert_int_equal(tbl_gp_fit(6, 1, x, y, sy, NULL), STC_EINVAL);
}

/* Every field but the search's record (evaluations, converged, subset_n),
 * bit for bit. */
static int same_result(const tbl_gp_info *a, const tbl_gp_info *b)
{
    return a->n == b->n && a->dim == b->dim && !memcmp(a->ell, b->ell, sizeof a->ell) &&
           !memcmp(&a->sf, &b->sf, sizeof a->sf) &&
           !memcmp(&a->noise_scale, &b->noise_scale, sizeof a->sf) &&
           !memcmp(&a->mean, &b->mean, sizeof a->sf) && !memcmp(&a->log_ml, &b->log_ml, sizeof a->sf) &&
           !memcmp(&a->loo_rms, &b->loo_rms, sizeof a->sf) &&
           !memcmp(&a->loo_max, &b->loo_max, sizeof a->sf) &&
           !memcmp(&a->loo_cover2, &b->loo_cover2, sizeof a->sf) &&
           !memcmp(a->ell_lo, b->ell_lo, sizeof a->ell_lo) &&
           !memcmp(a->ell_hi, b->ell_hi, sizeof a->ell_hi) &&
           !memcmp(a->ell_at_bound, b->ell_at_bound, sizeof a->ell_at_bound) &&
           !memcmp(&a->jitter, &b->jitter, sizeof a->sf) && a->mod_dim == b->mod_dim &&
           !memcmp(&a->gamma, &b->gamma, sizeof a->sf) && a->scale_dim == b->scale_dim &&
           !memcmp(a->base_ell, b->base_ell, sizeof a->base_ell) &&
           !memcmp(&a->base_sd, &b->base_sd, sizeof a->sf) && a->npar == b->npar &&
           !memcmp(a->par, b->par, (size_t)a->npar * sizeof *a->par);
}

static int same_info(const tbl_gp_info *a, const tbl_gp_info *b)
{
    return same_result(a, b) && a->evaluations == b->evaluations &&
           a->converged == b->converged && a->subset_n == b->subset_n;
}

/* Info, LOO and a prediction of a and b bit-identical (all of the info, or
 * with whole = 0 all but the search's record). */
static int same_fit(const tbl_gp *a, const tbl_gp *b, int n, int whole)
{
    tbl_gp_info ia, ib;
    tbl_gp_get_info(a, &ia);
    tbl_gp_get_info(b, &ib);
    double q[3] = {0.3, 0.6, 0.9}, ma, sa, mb, sb;
    tbl_gp_predict(a, q, &ma, &sa);
    tbl_gp_predict(b, q, &mb, &sb);
    double *la = malloc(4 * (size_t)n * sizeof *la), *lb = la + 2 * n;
    tbl_gp_loo(a, la, la + n);
    tbl_gp_loo(b, lb, lb + n);
    int same = (whole ? same_info(&ia, &ib) : same_result(&ia, &ib)) &&
               !memcmp(&ma, &mb, sizeof ma) && !memcmp(&sa, &sb, sizeof sa) &&
               !memcmp(la, lb, 2 * (size_t)n * sizeof *la);
    free(la);
    return same;
}

/* Two fits of the same data bit-identical; the fit at the first's
 * hyperparameters (tbl_gp_fit_at) too, in a fraction of the time; the
 * hyperparameters refused for a wrong count or out of their bounds. */
static void check_same(const char *what, int n, const double *x, const double *y,
                       const double *sy, const tbl_gp_kernel *k)
{
    double t0 = now();
    tbl_gp *a = NULL, *b = NULL, *c = NULL;
    check_ok(tbl_gp_fit_kernel(n, 3, x, y, sy, k, &a), "fit");
    double dt = now() - t0;
    check_ok(tbl_gp_fit_kernel(n, 3, x, y, sy, k, &b), "fit again");
    tbl_gp_info ia, ic;
    tbl_gp_get_info(a, &ia);
    print_info(what, &ia);
    t0 = now();
    check_ok(tbl_gp_fit_at(n, 3, x, y, sy, k, ia.npar, ia.par, &c), "tbl_gp_fit_at");
    double dc = now() - t0;
    tbl_gp_get_info(c, &ic);
    int same = same_fit(a, b, n, 1), same_at = same_fit(a, c, n, 0);
    printf("determinism, %s (fit %.0f ms, subset stage %d points): info, LOO and prediction "
           "%s; at its %d hyperparameters (%.1f ms, %d evaluations) %s\n", what, 1e3 * dt,
           ia.subset_n, same ? "bit-identical" : "DIFFER", ia.npar, 1e3 * dc, ic.evaluations,
           same_at ? "bit-identical" : "DIFFER");
    assert_true(same && same_at);
    assert_true(ia.converged);
    assert_int_equal(ic.evaluations, 0);
    assert_true(ia.npar >= 4 && dc < dt);

    double bad[TBL_GP_MAXPAR];
    memcpy(bad, ia.par, sizeof bad);
    tbl_gp *d = NULL;
    assert_int_equal(tbl_gp_fit_at(n, 3, x, y, sy, k, ia.npar - 1, bad, &d), STC_EINVAL);
    assert_null(d);
    assert_non_null(strstr(stc_errmsg(), "hyperparameters"));
    bad[0] = ia.ell_hi[0] > 0 ? 1e3 : 0.0; /* log ell far above its bound */
    assert_int_equal(tbl_gp_fit_at(n, 3, x, y, sy, k, ia.npar, bad, &d), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "par[0] = 1000"));
    tbl_gp_destroy(&a);
    tbl_gp_destroy(&b);
    tbl_gp_destroy(&c);
}

static void test_determinism(void **state)
{
    (void)state;
    enum { N = 100, NA = 10, NB = 6, NC = 5, NG = NA * NB * NC };
    static double x[NG * 3], y[NG], sy[NG];
    uint64_t s = 4242u;
    for (int i = 0; i < N; i++) { /* scattered: kernel evaluated directly */
        double *xi = x + 3 * i;
        for (int d = 0; d < 3; d++) xi[d] = unif(&s);
        sy[i] = 0.02;
        y[i] = f3(xi) + sy[i] * gauss(&s);
    }
    check_same("3D scattered, n = 100", N, x, y, sy, NULL);
    const tbl_gp_kernel both = {.mod_dim = 1, .scale_dim = 2, .base_dims = 1u};
    check_same("3D scattered, n = 100, scaled and modulated", N, x, y, sy, &both);
    int k = 0; /* a grid above the subset size: subset stage, kernel tables */
    for (int a = 0; a < NA; a++)
        for (int b = 0; b < NB; b++)
            for (int c = 0; c < NC; c++, k++) {
                double *xk = x + 3 * k;
                xk[0] = a / (NA - 1.0), xk[1] = b / (NB - 1.0), xk[2] = c / (NC - 1.0);
                sy[k] = 0.02 * (1 + unif(&s));
                y[k] = f3(xk) + sy[k] * gauss(&s);
            }
    check_same("3D grid 10x6x5, n = 300", NG, x, y, sy, NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_smooth_1d),          cmocka_unit_test(test_understated_noise),
        cmocka_unit_test(test_grid_3d),            cmocka_unit_test(test_constant_dim),
        cmocka_unit_test(test_interpolation),      cmocka_unit_test(test_loo_and_likelihood),
        cmocka_unit_test(test_modulated),          cmocka_unit_test(test_scaled),
        cmocka_unit_test(test_invalid),
        cmocka_unit_test(test_determinism),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
