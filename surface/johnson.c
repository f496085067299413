/* Johnson (1949, Biometrika 36:149) translator system, fitted to a target
 * skewness √β1 and kurtosis β2 by moment matching, to make non-Gaussian
 * heights from a Gaussian map (as Hu & Tonder 1992 and Bakolas 2003 do).
 *
 *   SU (unbounded, β2 above the lognormal line): y = sinh((u - γ)/δ)
 *   SB (bounded, between the line and β2 = β1 + 1): y = 1/(1 + e^{-(u-γ)/δ})
 *   N: y = u.
 * SU moments are closed-form (Johnson 1949, eqs. 32-35); SB moments are
 * integrals over the standard normal (composite Simpson on [-U, U]).
 */
#include <math.h>
#include <string.h>

#include "stiction/surface.h"
#include "stc_check.h"

/* |skewness| and |kurtosis - 3| below this: Gaussian, no translation */
#define JS_GAUSS_TOL 1e-9
/* bisection: relative interval width at convergence, iteration cap */
#define JS_RTOL 1e-13
#define JS_MAXIT 200
/* Simpson grid for the SB moments: ±JS_U standard deviations, JS_NQ panels */
#define JS_U 9.0
#define JS_NQ 3000

/* SU central moments for ω = e^{1/δ²}, Ω = γ/δ (Johnson 1949). */
static void su_moments(double w, double O, double *mean, double *m2, double *b1, double *b2)
{
    double sw = sqrt(w), wm1 = w - 1;
    double mu2 = 0.5 * wm1 * (w * cosh(2 * O) + 1);
    double mu3 = -0.25 * sw * wm1 * wm1 * (w * (w + 2) * sinh(3 * O) + 3 * sinh(O));
    double mu4 = 0.125 * wm1 * wm1 *
                 (w * w * (w * w * w * w + 2 * w * w * w + 3 * w * w - 3) * cosh(4 * O) +
                  4 * w * w * (w + 2) * cosh(2 * O) + 3 * (2 * w + 1));
    if (mean) *mean = -sw * sinh(O);
    if (m2) *m2 = mu2;
    if (b1) *b1 = mu3 * mu3 / (mu2 * mu2 * mu2);
    if (b2) *b2 = mu4 / (mu2 * mu2);
}

/* Lognormal line: β1 = (ω-1)(ω+2)², β2 = ω⁴ + 2ω³ + 3ω² - 3 (SU/SB border). */
static double logn_b1(double w) { return (w - 1) * (w + 2) * (w + 2); }
static double logn_b2(double w) { return w * w * w * w + 2 * w * w * w + 3 * w * w - 3; }

/* Bisection for an increasing function f on [lo, hi] with f(lo) <= t <= f(hi). */
typedef double (*js_fn)(double x, const void *ctx);
static double bisect(js_fn f, const void *ctx, double t, double lo, double hi)
{
    for (int it = 0; it < JS_MAXIT && hi - lo > JS_RTOL * fabs(hi); it++) {
        double mid = 0.5 * (lo + hi);
        if (f(mid, ctx) < t) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

static double f_logn_b1(double w, const void *c) { (void)c; return logn_b1(w); }
static double f_logn_b2(double w, const void *c) { (void)c; return logn_b2(w); }

/* ω on the lognormal line where g(ω) reaches t (g increasing from g(1)). */
static double logn_omega(js_fn g, double t)
{
    double hi = 2;
    while (g(hi, NULL) < t && hi < 1e6) hi *= 2;
    return bisect(g, NULL, t, 1, hi);
}

typedef struct { double w, b2; } su_ctx;
static double f_su_b2(double O, const void *c)
{
    double b2;
    su_moments(((const su_ctx *)c)->w, O, NULL, NULL, NULL, &b2);
    return b2;
}

/* For fixed ω, the Ω >= 0 reaching kurtosis b2 (β2 grows with |Ω|). */
static double su_Omega(double w, double b2)
{
    su_ctx c = {w, b2};
    double hi = 1;
    while (f_su_b2(hi, &c) < b2 && hi < 100) hi *= 2;
    return bisect(f_su_b2, &c, b2, 0, hi);
}

static double f_su_b1(double w, const void *c)
{
    double b1, b2 = *(const double *)c;
    su_moments(w, su_Omega(w, b2), NULL, NULL, &b1, NULL);
    return -b1; /* β1 falls as ω rises along the β2 = const line */
}

/* SU: ω ∈ (ω on the lognormal line at β2, ω of the symmetric SU at β2]. */
static stc_status fit_su(double skew, double b2, srf_johnson *j)
{
    double b1 = skew * skew;
    double wlo = logn_omega(f_logn_b2, b2);
    double whi = sqrt(sqrt(2 * b2 - 2) - 1); /* Ω = 0: β2 = (ω⁴ + 2ω² + 3)/2 */
    double w = b1 > 0 ? bisect(f_su_b1, &b2, -b1, wlo, whi) : whi;
    double O = b1 > 0 ? su_Omega(w, b2) : 0;
    j->family = 'U';
    j->delta = 1 / sqrt(log(w));
    j->gamma = (skew > 0 ? -O : O) * j->delta; /* μ3 ∝ -sinh(Ω) */
    su_moments(w, skew > 0 ? -O : O, &j->mean, &j->sd, NULL, NULL);
    j->sd = sqrt(j->sd);
    return STC_OK;
}

/* SB raw moments by Simpson: E[y^k], k = 1..4, y = logistic((u-γ)/δ). */
static void sb_moments(double g, double d, double *mean, double *var, double *b1, double *b2)
{
    double h = 2 * JS_U / JS_NQ, r[5] = {0};
    for (int i = 0; i <= JS_NQ; i++) {
        double u = -JS_U + i * h;
        double wt = (i == 0 || i == JS_NQ) ? 1 : (i % 2 ? 4 : 2);
        double phi = exp(-0.5 * u * u) / sqrt(2 * M_PI);
        double y = 1 / (1 + exp(-(u - g) / d)), p = wt * phi;
        for (int k = 1; k <= 4; k++) r[k] += (p *= y);
    }
    for (int k = 1; k <= 4; k++) r[k] *= h / 3;
    double m = r[1], v = r[2] - m * m;
    double c3 = r[3] - 3 * m * r[2] + 2 * m * m * m;
    double c4 = r[4] - 4 * m * r[3] + 6 * m * m * r[2] - 3 * m * m * m * m;
    if (mean) *mean = m;
    if (var) *var = v;
    if (b1) *b1 = c3 * c3 / (v * v * v);
    if (b2) *b2 = c4 / (v * v);
}

typedef struct { double d, b1; } sb_ctx;
static double f_sb_b1(double g, const void *c)
{
    double b1;
    sb_moments(g, ((const sb_ctx *)c)->d, NULL, NULL, &b1, NULL);
    return b1;
}

/* For fixed δ, the γ >= 0 reaching β1 (β1 grows with γ towards the lognormal
 * line); returns -1 when β1 is beyond this δ's reach. */
static double sb_gamma(double d, double b1)
{
    sb_ctx c = {d, b1};
    if (b1 <= 0) return 0;
    double hi = 1;
    while (f_sb_b1(hi, &c) < b1) {
        if ((hi *= 2) > JS_U) return -1;
    }
    return bisect(f_sb_b1, &c, b1, 0, hi);
}

/* SB: bisection on δ; β2 along the β1 = const line rises with δ towards the
 * lognormal line. */
static stc_status fit_sb(double skew, double b2, srf_johnson *j)
{
    double b1 = skew * skew, lo = 0.05, hi = 0, g = 0, b2t;
    /* upper end: the largest δ that still reaches β1 within the grid */
    for (double d = lo; d < 50; d *= 1.25) {
        if (sb_gamma(d, b1) < 0) break;
        hi = d;
    }
    STC_CHECK(hi > lo, STC_ENOCONV,
              "skewness = %g, kurtosis = %g: Johnson SB fit out of reach (|skewness| too large "
              "for a bounded translator on this quadrature)", skew, b2);
    for (int it = 0; it < JS_MAXIT && hi - lo > JS_RTOL * hi; it++) {
        double mid = 0.5 * (lo + hi);
        g = sb_gamma(mid, b1);
        sb_moments(g, mid, NULL, NULL, NULL, &b2t);
        if (b2t < b2) lo = mid;
        else hi = mid;
    }
    j->family = 'B';
    j->delta = 0.5 * (lo + hi);
    g = sb_gamma(j->delta, b1);
    j->gamma = skew > 0 ? g : -g; /* γ > 0: most mass low, lognormal-like upper tail */
    sb_moments(j->gamma, j->delta, &j->mean, &j->sd, NULL, &b2t);
    j->sd = sqrt(j->sd);
    STC_CHECK(fabs(b2t - b2) < 1e-6 * b2, STC_ENOCONV,
              "skewness = %g, kurtosis = %g: Johnson SB fit reached kurtosis %g only", skew, b2,
              b2t);
    return STC_OK;
}

stc_status srf_johnson_fit(double skew, double kurt, srf_johnson *j)
{
    memset(j, 0, sizeof *j);
    STC_CHECK(isfinite(skew), STC_EINVAL, "skewness = %g: must be finite", skew);
    STC_CHECK(isfinite(kurt) && kurt > skew * skew + 1, STC_EINVAL,
              "kurtosis = %g: must be > skewness² + 1 = %g (no distribution has less)", kurt,
              skew * skew + 1);
    if (fabs(skew) < JS_GAUSS_TOL && fabs(kurt - 3) < JS_GAUSS_TOL) {
        j->family = 'N';
        j->sd = 1;
        return STC_OK;
    }
    double wl = skew != 0 ? logn_omega(f_logn_b1, skew * skew) : 1;
    if (kurt > logn_b2(wl)) return fit_su(skew, kurt, j);
    return fit_sb(skew, kurt, j);
}

double srf_johnson_apply(const srf_johnson *j, double u)
{
    double x = j->family == 'N' ? u : (u - j->gamma) / j->delta;
    double y = j->family == 'U' ? sinh(x) : j->family == 'B' ? 1 / (1 + exp(-x)) : x;
    return (y - j->mean) / j->sd;
}
