/* Elastic half-space contact by FFT-accelerated boundary elements
 * (include/stiction/halfspace.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stiction/halfspace.h"
#include "srf_impl.h"
#include "stc_check.h"

struct srf_halfspace {
    int n, m;              /* grid n × n; padded m = 2n */
    double h;
    double k0;             /* self-influence of a cell's pressure, mm/MPa */
    fftw_complex *kp, *kq; /* spectra of the influence kernels, m × (m/2 + 1) */
    double *buf;           /* m × m real work array */
    fftw_complex *spec;    /* m × (m/2 + 1) */
    fftw_plan fwd, inv;
};

/* ln(b + sqrt(a² + b²)) without the cancellation for b < 0, |a| << |b|. */
static double log_sum(double a, double b, double r)
{
    return b >= 0.0 ? log(b + r) : log(a * a / (r - b));
}

/* Antiderivative of 1/ρ over the rectangle corner (X, Y) (Love 1929). */
static double love(double X, double Y)
{
    double r = hypot(X, Y), v = 0.0;
    if (r == 0.0) return 0.0;
    if (X != 0.0) v += X * log_sum(X, Y, r);
    if (Y != 0.0) v += Y * log_sum(Y, X, r);
    return v;
}

/* Antiderivative of X/ρ² in X and Y: ½ Y ln(X² + Y²) + X atan(Y/X). */
static double cerruti(double X, double Y)
{
    double r2 = X * X + Y * Y, v = 0.0;
    if (r2 == 0.0) return 0.0;
    if (Y != 0.0) v += 0.5 * Y * log(r2);
    if (X != 0.0) v += X * atan(Y / X);
    return v;
}

static double cell(double (*F)(double, double), double x, double y, double h)
{
    double e = 0.5 * h;
    return F(x + e, y + e) - F(x - e, y + e) - F(x + e, y - e) + F(x - e, y - e);
}

/* Spectrum of a kernel sampled at the wrapped offsets of the padded grid. */
static void kernel(srf_halfspace *hs, double (*F)(double, double), double c, fftw_complex *dst)
{
    int m = hs->m;
    for (int i = 0; i < m; i++) {
        double x = (i < hs->n ? i : i - m) * hs->h;
        for (int j = 0; j < m; j++) {
            double y = (j < hs->n ? j : j - m) * hs->h;
            hs->buf[(size_t)i * m + j] = c * cell(F, x, y, hs->h);
        }
    }
    fftw_execute_dft_r2c(hs->fwd, hs->buf, dst);
}

stc_status srf_halfspace_create(srf_halfspace **out, int n, double h, double E, double nu)
{
    *out = NULL;
    STC_CHECK(n >= 8 && n <= 4096, STC_EINVAL, "halfspace: n = %d cells: must be in [8, 4096]",
              n);
    STC_CHECK(h > 0.0 && isfinite(h), STC_EINVAL, "halfspace: h = %g mm: must be > 0", h);
    STC_CHECK(E > 0.0 && isfinite(E), STC_EINVAL, "halfspace: E = %g MPa: must be > 0", E);
    STC_CHECK(nu > -1.0 && nu <= 0.5, STC_EINVAL, "halfspace: nu = %g: must be in (-1, 0.5]",
              nu);
    srf_halfspace *hs = calloc(1, sizeof *hs);
    STC_CHECK(hs, STC_ENOMEM, "halfspace: out of memory");
    hs->n = n, hs->m = 2 * n, hs->h = h;
    size_t nr = (size_t)hs->m * hs->m, nc = (size_t)hs->m * (hs->m / 2 + 1);
    hs->buf = fftw_malloc(nr * sizeof *hs->buf);
    hs->spec = fftw_malloc(nc * sizeof *hs->spec);
    hs->kp = fftw_malloc(nc * sizeof *hs->kp);
    hs->kq = fftw_malloc(nc * sizeof *hs->kq);
    if (!hs->buf || !hs->spec || !hs->kp || !hs->kq) {
        srf_halfspace_destroy(&hs);
        return STC_FAIL(STC_ENOMEM, "halfspace: out of memory (n = %d)", n);
    }
    hs->fwd = srf_plan_r2c(hs->m, hs->m, hs->buf, hs->spec, 1);
    hs->inv = srf_plan_c2r(hs->m, hs->m, hs->spec, hs->buf, 1);
    if (!hs->fwd || !hs->inv) {
        srf_halfspace_destroy(&hs);
        return STC_FAIL(STC_ENOMEM, "halfspace: FFTW plan failed (n = %d)", n);
    }
    double G = E / (2.0 * (1.0 + nu));
    kernel(hs, love, (1.0 - nu * nu) / (M_PI * E), hs->kp);
    hs->k0 = (1.0 - nu * nu) / (M_PI * E) * cell(love, 0.0, 0.0, h);
    kernel(hs, cerruti, (1.0 - 2.0 * nu) / (4.0 * M_PI * G), hs->kq);
    *out = hs;
    return STC_OK;
}

void srf_halfspace_destroy(srf_halfspace **hsp)
{
    srf_halfspace *hs = *hsp;
    if (!hs) return;
    if (hs->fwd) srf_plan_destroy(hs->fwd);
    if (hs->inv) srf_plan_destroy(hs->inv);
    fftw_free(hs->buf);
    fftw_free(hs->spec);
    fftw_free(hs->kp);
    fftw_free(hs->kq);
    free(hs);
    *hsp = NULL;
}

/* w += K * f on the n × n grid. */
static void convolve(srf_halfspace *hs, const fftw_complex *k, const double *f, double *w)
{
    int n = hs->n, m = hs->m;
    size_t nc = (size_t)m * (m / 2 + 1);
    memset(hs->buf, 0, (size_t)m * m * sizeof *hs->buf);
    for (int i = 0; i < n; i++) memcpy(hs->buf + (size_t)i * m, f + (size_t)i * n, n * sizeof *f);
    fftw_execute_dft_r2c(hs->fwd, hs->buf, hs->spec);
    double s = 1.0 / ((double)m * m);
    for (size_t j = 0; j < nc; j++) {
        double a = hs->spec[j][0], b = hs->spec[j][1];
        hs->spec[j][0] = s * (a * k[j][0] - b * k[j][1]);
        hs->spec[j][1] = s * (a * k[j][1] + b * k[j][0]);
    }
    fftw_execute_dft_c2r(hs->inv, hs->spec, hs->buf);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) w[(size_t)i * n + j] += hs->buf[(size_t)i * m + j];
}

stc_status srf_halfspace_disp(srf_halfspace *hs, const double *p, const double *qx, double *w)
{
    size_t nn = (size_t)hs->n * hs->n;
    memset(w, 0, nn * sizeof *w);
    if (p) convolve(hs, hs->kp, p, w);
    if (qx) convolve(hs, hs->kq, qx, w);
    return STC_OK;
}

stc_status srf_halfspace_contact(srf_halfspace *hs, const double *h0, const double *qx,
                                 const unsigned char *bond, double tol, int maxit, double *p,
                                 int *iterations)
{
    size_t nn = (size_t)hs->n * hs->n;
    STC_CHECK(tol > 0.0 && maxit >= 1, STC_EINVAL,
              "halfspace contact: tol = %g, maxit = %d: must be > 0 and >= 1", tol, maxit);
    double *base = malloc(nn * sizeof *base), *g = malloc(nn * sizeof *g),
           *t = calloc(nn, sizeof *t), *r = malloc(nn * sizeof *r);
    unsigned char *in = malloc(nn);
    stc_status st = STC_OK;
    if (!base || !g || !t || !r || !in) {
        st = STC_FAIL(STC_ENOMEM, "halfspace contact: out of memory");
        goto done;
    }
    memset(base, 0, nn * sizeof *base);
    if (qx) convolve(hs, hs->kq, qx, base);
    double scale = 0.0;
    for (size_t k = 0; k < nn; k++) {
        base[k] += h0[k];
        scale = fmax(scale, fabs(h0[k]));
        if (p[k] < 0.0 && !(bond && bond[k])) p[k] = 0.0;
    }
    if (!(scale > 0.0)) scale = 1.0; /* a flat start: judge the gaps in mm */
    double Gold = 1.0;
    int conj = 0, it;
    for (it = 0; it < maxit; it++) {
        memcpy(g, base, nn * sizeof *g);
        convolve(hs, hs->kp, p, g);
        double Gs = 0.0;
        size_t nin = 0;
        for (size_t k = 0; k < nn; k++) {
            in[k] = p[k] > 0.0 || (bond && bond[k]);
            if (in[k]) Gs += g[k] * g[k], nin++;
        }
        double beta = conj ? Gs / Gold : 0.0;
        for (size_t k = 0; k < nn; k++) t[k] = in[k] ? g[k] + beta * t[k] : 0.0;
        Gold = Gs;
        memset(r, 0, nn * sizeof *r);
        convolve(hs, hs->kp, t, r);
        double num = 0.0, den = 0.0;
        for (size_t k = 0; k < nn; k++)
            if (in[k]) num += g[k] * t[k], den += r[k] * t[k];
        int overlap = 0, clipped = 0;
        double tau = den > 0.0 ? num / den : 0.0;
        for (size_t k = 0; k < nn; k++) {
            if (in[k]) {
                p[k] -= tau * t[k];
                if (p[k] < 0.0 && !(bond && bond[k])) p[k] = 0.0, clipped = 1;
            } else if (g[k] < 0.0) {
                /* an overlapping cell enters with the step's pressure rate */
                p[k] -= (tau > 0.0 ? tau : 1.0 / hs->k0) * g[k];
                overlap = 1;
            }
        }
        conj = !overlap;
        double err = nin ? sqrt(Gs / nin) / scale : 0.0;
        if (err < tol && !overlap && !clipped) break;
    }
    if (iterations) *iterations = it;
    if (it == maxit)
        st = STC_FAIL(STC_ENOCONV, "halfspace contact: no convergence in %d iterations "
                      "(tol %g)", maxit, tol);
done:
    free(base), free(g), free(t), free(r), free(in);
    return st;
}

/* Extents of the bonded set along +x, −x and +y from the axis (outer cell edges). */
static void extents(const unsigned char *c, int n, double h, double *lead, double *trail,
                    double *side)
{
    *lead = *trail = *side = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            if (!c[(size_t)i * n + j]) continue;
            double x = (i - 0.5 * (n - 1)) * h, y = (j - 0.5 * (n - 1)) * h;
            *lead = fmax(*lead, x + 0.5 * h);
            *trail = fmax(*trail, -x + 0.5 * h);
            *side = fmax(*side, y + 0.5 * h);
        }
}

stc_status srf_halfspace_sphere_slide(double R, double delta, double E, double nu, double tau_c,
                                      int n, double span, int steps, srf_slide_result *out)
{
    memset(out, 0, sizeof *out);
    STC_CHECK(R > 0.0 && isfinite(R), STC_EINVAL, "sphere slide: R = %g mm: must be > 0", R);
    STC_CHECK(delta > 0.0 && delta < R, STC_EINVAL,
              "sphere slide: delta = %g mm: must be in (0, R)", delta);
    STC_CHECK(tau_c >= 0.0 && isfinite(tau_c), STC_EINVAL,
              "sphere slide: tau_c = %g MPa: must be >= 0", tau_c);
    STC_CHECK(n >= 16 && n <= 4096, STC_EINVAL, "sphere slide: n = %d: must be in [16, 4096]", n);
    STC_CHECK(span >= 1.05 && span <= 4.0, STC_EINVAL,
              "sphere slide: span = %g: must be in [1.05, 4]", span);
    STC_CHECK(steps >= 1 && steps <= 1000, STC_EINVAL,
              "sphere slide: steps = %d: must be in [1, 1000]", steps);
    double aH = sqrt(R * delta), h = 2.0 * span * aH / n, Es = E / (1.0 - nu * nu);
    srf_halfspace *hs;
    STC_CALL(srf_halfspace_create(&hs, n, h, E, nu));
    size_t nn = (size_t)n * n;
    double *h0 = malloc(nn * sizeof *h0), *p = malloc(nn * sizeof *p),
           *q = malloc(nn * sizeof *q);
    unsigned char *c = calloc(nn, 1);
    stc_status st = STC_OK;
    STC_CHECK_GOTO(h0 && p && q && c, st, done, STC_ENOMEM, "sphere slide: out of memory");
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double x = (i - 0.5 * (n - 1)) * h, y = (j - 0.5 * (n - 1)) * h;
            size_t k = (size_t)i * n + j;
            h0[k] = (x * x + y * y) / (2.0 * R) - delta;
            p[k] = fmax(0.0, -h0[k]) * Es / aH; /* any positive start on the overlap */
        }
    double tol = 1e-10;
    int its, maxit = 20 * n + 500;
    STC_CALL_GOTO(srf_halfspace_contact(hs, h0, NULL, NULL, tol, maxit, p, &its), st, done);
    out->iterations = its;
    double dA = h * h;
    for (size_t k = 0; k < nn; k++)
        if (p[k] > 0.0) c[k] = 1, out->P0 += p[k] * dA, out->A0 += dA;
    for (int step = 1; step <= steps; step++) {
        double tq = tau_c * step / steps;
        for (int sweep = 0;; sweep++) {
            STC_CHECK_GOTO(sweep < 100, st, done, STC_ENOCONV,
                           "sphere slide: the contact set did not settle in 100 sweeps "
                           "(step %d of %d)", step, steps);
            for (size_t k = 0; k < nn; k++) q[k] = c[k] ? tq : 0.0;
            STC_CALL_GOTO(srf_halfspace_contact(hs, h0, q, c, tol, maxit, p, &its), st, done);
            out->iterations += its;
            int grew = 0;
            for (size_t k = 0; k < nn; k++)
                if (p[k] > 0.0 && !c[k]) c[k] = 1, grew = 1;
            if (!grew) break;
        }
    }
    for (size_t k = 0; k < nn; k++) {
        out->P += p[k] * dA;
        if (c[k]) out->A += dA;
        if (p[k] < 0.0) out->tension -= p[k] * dA;
    }
    extents(c, n, h, &out->a_lead, &out->a_trail, &out->a_side);
    out->h = h;
    STC_CHECK_GOTO(out->a_trail < span * aH - h && out->a_lead < span * aH - h &&
                   out->a_side < span * aH - h, st, done, STC_ERANGE,
                   "sphere slide: the contact reached the grid's edge (span = %g): "
                   "widen the span", span);
done:
    free(h0), free(p), free(q), free(c);
    srf_halfspace_destroy(&hs);
    return st;
}
