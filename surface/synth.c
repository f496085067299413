/* FFT synthesis of periodic Gaussian (optionally Johnson-translated) height
 * maps with a prescribed power spectrum (docs/design.md §5.1).
 *
 * Method (Hu & Tonder 1992, Int. J. Mach. Tools Manuf. 32:83; Persson et al.
 * 2005, J. Phys.: Condens. Matter 17:R1): each Fourier mode gets amplitude
 * sqrt(C(q)) and a uniformly random phase (or a complex Gaussian value for
 * Rayleigh amplitudes); Hermitian symmetry makes the inverse FFT real; the
 * map is then shifted to zero mean and scaled to the exact target RMS.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <omp.h>

#include "srf_impl.h"
#include "stc_check.h"

#define SRF_PI 3.14159265358979323846
#define SRF_LN10 2.30258509299404568402
/* relative tolerance when a grid wavevector falls on a band edge */
#define SRF_BAND_EDGE_RTOL 1e-9

struct srf_synth {
    srf_synth_params p;
    int nx, ny, nxh;    /* nxh = nx/2 + 1 complex columns */
    double *amp;        /* [ny][nxh] sqrt of the (symmetrised) discrete PSD */
    fftw_complex *spec; /* [ny][nxh] work spectrum (c2r destroys it) */
    double *rbuf;       /* [ny][nx] aligned output when the map's is not */
    fftw_plan plan;     /* c2r spec → rbuf */
    srf_moments target; /* discrete target moments, scaled to σ² */
    int nthr;           /* threads used by run (params.threads resolved) */
    gsl_rng **rng;      /* [nthr] one generator per thread, reseeded per row */
};

stc_status srf_synth_params_validate(const srf_synth_params *p)
{
    STC_CHECK(p->nx >= 4 && p->nx <= 65536, STC_EINVAL, "size nx = %d: must be in [4, 65536]", p->nx);
    STC_CHECK(p->ny >= 4 && p->ny <= 65536, STC_EINVAL, "size ny = %d: must be in [4, 65536]", p->ny);
    STC_CHECK(isfinite(p->lx) && p->lx > 0, STC_EINVAL, "length lx = %g mm: must be > 0", p->lx);
    STC_CHECK(isfinite(p->ly) && p->ly > 0, STC_EINVAL, "length ly = %g mm: must be > 0", p->ly);
    STC_CHECK(isfinite(p->rms) && p->rms > 0, STC_EINVAL, "rms = %g mm: must be > 0", p->rms);
    STC_CHECK(p->threads >= 0, STC_EINVAL, "threads = %d: must be >= 0", p->threads);
    STC_CHECK(p->amplitude == SRF_AMP_EXACT || p->amplitude == SRF_AMP_RAYLEIGH, STC_EINVAL,
              "amplitude = %d: must be exact (0) or rayleigh (1)", (int)p->amplitude);
    switch (p->spectrum) {
    case SRF_SPECTRUM_EXPONENTIAL:
        STC_CHECK(isfinite(p->beta_x) && p->beta_x > 0, STC_EINVAL,
                  "corr-length beta_x = %g mm: must be > 0", p->beta_x);
        STC_CHECK(isfinite(p->beta_y) && p->beta_y > 0, STC_EINVAL,
                  "corr-length beta_y = %g mm: must be > 0", p->beta_y);
        break;
    case SRF_SPECTRUM_SELF_AFFINE: {
        double lL, lr, ls, pix = fmax(p->lx / p->nx, p->ly / p->ny);
        STC_CHECK(isfinite(p->hurst) && p->hurst > 0 && p->hurst <= 1, STC_EINVAL,
                  "hurst = %g: must be in (0, 1]", p->hurst);
        STC_CHECK(isfinite(p->lambda_long) && p->lambda_long >= 0, STC_EINVAL,
                  "long-wavelength = %g mm: must be > 0 (or 0 = length)", p->lambda_long);
        STC_CHECK(isfinite(p->lambda_rolloff) && p->lambda_rolloff >= 0, STC_EINVAL,
                  "rolloff-wavelength = %g mm: must be > 0 (or 0 = long-wavelength)",
                  p->lambda_rolloff);
        STC_CHECK(isfinite(p->lambda_cutoff) && p->lambda_cutoff >= 0, STC_EINVAL,
                  "cutoff-wavelength = %g mm: must be > 0 (or 0 = 16 pixels)", p->lambda_cutoff);
        srf_band(p, &lL, &lr, &ls);
        STC_CHECK(lr <= lL, STC_EINVAL,
                  "rolloff-wavelength = %g mm: must be <= long-wavelength = %g mm", lr, lL);
        STC_CHECK(ls < lr, STC_EINVAL,
                  "cutoff-wavelength = %g mm: must be < rolloff-wavelength = %g mm", ls, lr);
        STC_CHECK(ls >= 2 * pix, STC_EINVAL,
                  "cutoff-wavelength = %g mm: must be >= 2 pixels = %g mm (Nyquist)", ls, 2 * pix);
        break;
    }
    case SRF_SPECTRUM_USER:
        STC_CHECK(p->psd != NULL, STC_EINVAL, "spectrum = user: a PSD callback is required");
        break;
    default:
        return STC_FAIL(STC_EINVAL, "spectrum = %d: must be exponential, self-affine or user "
                        "(srf_spectrum)", (int)p->spectrum);
    }
    if (p->non_gaussian) {
        STC_CHECK(isfinite(p->skewness), STC_EINVAL, "skewness = %g: must be finite", p->skewness);
        STC_CHECK(isfinite(p->kurtosis) && p->kurtosis > p->skewness * p->skewness + 1,
                  STC_EINVAL, "kurtosis = %g: must be > skewness² + 1 = %g", p->kurtosis,
                  p->skewness * p->skewness + 1);
    }
    return STC_OK;
}

/* Self-affine PSD (Persson et al. 2005; Jacobs, Junge & Persson 2017, Surf.
 * Topogr. Metrol. Prop. 5:013001): flat for qL <= q < qr, ∝ (q/qr)^-2(1+H)
 * for qr <= q <= qs, zero outside [qL, qs]; q = 2π/λ. */
static double psd_self_affine(const srf_synth_params *p, double qx, double qy)
{
    double lL, lr, ls;
    srf_band(p, &lL, &lr, &ls);
    double q = hypot(qx, qy);
    double qL = 2 * SRF_PI / lL, qr = 2 * SRF_PI / lr, qs = 2 * SRF_PI / ls;
    if (q < qL * (1 - SRF_BAND_EDGE_RTOL) || q > qs * (1 + SRF_BAND_EDGE_RTOL)) return 0.0;
    double c0 = p->rms * p->rms;
    return q <= qr ? c0 : c0 * pow(q / qr, -2.0 * (1.0 + p->hurst));
}

/* 2-D PSD of the exponential ACF R = σ² exp(-sqrt((τx/ℓx)² + (τy/ℓy)²)),
 * ℓ = β* / ln10 (β* = length where R falls to 0.1 σ²; Patir 1978, Wear 47:263).
 * Isotropic Hankel transform: ∫ e^{-r/ℓ} J0(qr) r dr = ℓ²(1+q²ℓ²)^-3/2, so
 * C(q) = σ² ℓ²/(2π) (1+q²ℓ²)^-3/2 (Hu & Tonder 1992, eq. 11); anisotropy by
 * scaling the axes. */
static double psd_exponential(const srf_synth_params *p, double qx, double qy)
{
    double lx = p->beta_x / SRF_LN10, ly = p->beta_y / SRF_LN10;
    double s = 1.0 + qx * qx * lx * lx + qy * qy * ly * ly;
    return p->rms * p->rms * lx * ly / (2 * SRF_PI) / (s * sqrt(s));
}

double srf_psd_eval(const srf_synth_params *p, double qx, double qy)
{
    switch (p->spectrum) {
    case SRF_SPECTRUM_EXPONENTIAL: return psd_exponential(p, qx, qy);
    case SRF_SPECTRUM_SELF_AFFINE: return psd_self_affine(p, qx, qy);
    case SRF_SPECTRUM_USER: return p->psd ? p->psd(qx, qy, p->psd_user) : 0.0;
    }
    return 0.0;
}

/* Discrete amplitudes |Z(k)| = sqrt(C), symmetrised under q → -q so the
 * Hermitian partner of every mode has the same power; DC = 0 (zero mean). */
static stc_status fill_amplitudes(srf_synth *s)
{
    const srf_synth_params *p = &s->p;
    int bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad)
    for (int ky = 0; ky < s->ny; ky++) {
        double qy = srf_qy(ky, s->ny, p->ly);
        for (int kx = 0; kx < s->nxh; kx++) {
            double qx = srf_qx(kx, p->lx);
            /* built-in spectra are even; a user PSD need not be */
            double c = p->spectrum == SRF_SPECTRUM_USER
                           ? 0.5 * (srf_psd_eval(p, qx, qy) + srf_psd_eval(p, -qx, -qy))
                           : srf_psd_eval(p, qx, qy);
            if (!(c >= 0 && isfinite(c))) bad++;
            s->amp[(size_t)ky * s->nxh + kx] = sqrt(c);
        }
    }
    STC_CHECK(bad == 0, STC_EINVAL, "spectrum: the PSD is negative or not finite at %d modes", bad);
    s->amp[0] = 0.0;
    /* The self-conjugate columns hold both k and -k: give partners equal power. */
    int cols[2] = {0, s->nxh - 1}, ncol = (s->nx % 2 == 0) ? 2 : 1;
    for (int c = 0; c < ncol; c++)
        for (int ky = 1; ky < (s->ny + 1) / 2; ky++) {
            double *a = &s->amp[(size_t)ky * s->nxh + cols[c]];
            double *b = &s->amp[(size_t)(s->ny - ky) * s->nxh + cols[c]];
            *a = *b = sqrt(0.5 * (*a * *a + *b * *b));
        }
    return STC_OK;
}

stc_status srf_synth_create(const srf_synth_params *p, srf_synth **out)
{
    stc_status st = STC_OK;
    *out = NULL;
    STC_CALL(srf_synth_params_validate(p));
    srf_synth *s = calloc(1, sizeof *s);
    STC_CHECK(s, STC_ENOMEM, "synth: out of memory");
    s->p = *p;
    s->nx = p->nx;
    s->ny = p->ny;
    s->nxh = p->nx / 2 + 1;
    size_t nc = (size_t)s->ny * s->nxh, nr = (size_t)s->nx * s->ny;
    s->amp = fftw_malloc(nc * sizeof *s->amp);
    s->spec = fftw_malloc(nc * sizeof *s->spec);
    s->rbuf = fftw_malloc(nr * sizeof *s->rbuf);
    s->nthr = srf_threads(p->threads);
    s->rng = calloc((size_t)s->nthr, sizeof *s->rng);
    for (int t = 0; s->rng && t < s->nthr; t++)
        if (!(s->rng[t] = gsl_rng_alloc(gsl_rng_mt19937))) break;
    STC_CHECK_GOTO(s->amp && s->spec && s->rbuf && s->rng && s->rng[s->nthr - 1], st, fail,
                   STC_ENOMEM,
                   "synth: out of memory for a %d x %d map", s->nx, s->ny);
    STC_CALL_GOTO(fill_amplitudes(s), st, fail);
    double *pw = malloc(nc * sizeof *pw);
    STC_CHECK_GOTO(pw, st, fail, STC_ENOMEM, "synth: out of memory");
    for (size_t k = 0; k < nc; k++) pw[k] = s->amp[k] * s->amp[k];
    srf_moments_from_power(pw, s->nx, s->ny, p->lx, p->ly, p->rms * p->rms, &s->target);
    free(pw);
    STC_CHECK_GOTO(s->target.m0 > 0, st, fail, STC_EINVAL,
                   "spectrum %s: no Fourier mode of the %d x %d grid (%g x %g mm) carries power; "
                   "check the wavelengths against the grid",
                   srf_spectrum_name(p->spectrum), s->nx, s->ny, p->lx, p->ly);
    s->plan = srf_plan_c2r(s->nx, s->ny, s->spec, s->rbuf, p->threads);
    STC_CHECK_GOTO(s->plan, st, fail, STC_ENOMEM, "synth: FFTW could not plan a %d x %d c2r",
                   s->nx, s->ny);
    *out = s;
    return STC_OK;
fail:
    srf_synth_destroy(&s);
    return st;
}

void srf_synth_destroy(srf_synth **ps)
{
    if (!ps || !*ps) return;
    srf_synth *s = *ps;
    if (s->plan) srf_plan_destroy(s->plan);
    fftw_free(s->amp);
    fftw_free(s->spec);
    fftw_free(s->rbuf);
    for (int t = 0; s->rng && t < s->nthr; t++)
        if (s->rng[t]) gsl_rng_free(s->rng[t]);
    free(s->rng);
    free(s);
    *ps = NULL;
}

stc_status srf_synth_target_moments(const srf_synth *s, srf_moments *out)
{
    STC_CHECK(s && out, STC_EINVAL, "synth_target_moments: NULL argument");
    *out = s->target;
    return STC_OK;
}

/* Seed of row ky's generator: a SplitMix64 hash of (seed, ky) (Steele et al.
 * 2014), so every row has its own stream and the map depends on the seed only,
 * not on the number of threads. */
static unsigned long row_seed(unsigned long seed, int ky)
{
    uint64_t z = (uint64_t)seed * 0x9E3779B97F4A7C15ull + (uint64_t)ky + 1;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (unsigned long)(z ^ (z >> 31));
}

/* Random modes, row by row in parallel.  Exact: amp·e^{2πiu}, u uniform.
 * Rayleigh: amp·(g1 + i g2)/√2 with g standard normal, so E|Z|² = amp². */
static void build_modes(srf_synth *s, unsigned long seed)
{
    int exact = s->p.amplitude == SRF_AMP_EXACT;
#pragma omp parallel num_threads(s->nthr)
    {
        gsl_rng *r = s->rng[omp_get_thread_num()];
#pragma omp for schedule(static)
        for (int ky = 0; ky < s->ny; ky++) {
            gsl_rng_set(r, row_seed(seed, ky));
            for (int kx = 0; kx < s->nxh; kx++) {
                size_t k = (size_t)ky * s->nxh + kx;
                double a = s->amp[k];
                if (exact) {
                    double ph = 2 * SRF_PI * gsl_rng_uniform(r);
                    s->spec[k][0] = a * cos(ph);
                    s->spec[k][1] = a * sin(ph);
                } else {
                    s->spec[k][0] = a * gsl_ran_gaussian_ziggurat(r, 1.0) * M_SQRT1_2;
                    s->spec[k][1] = a * gsl_ran_gaussian_ziggurat(r, 1.0) * M_SQRT1_2;
                }
            }
        }
    }
}

/* Enforce Hermitian symmetry in the self-conjugate columns (kx = 0 and the
 * Nyquist column of even nx): Z(-ky) = conj Z(ky); the self-conjugate modes
 * (ky = 0 and the Nyquist row) are made real with their exact amplitude (a
 * random sign) or, for Rayleigh, a real Gaussian of variance amp². */
static void hermitian(srf_synth *s)
{
    int cols[2] = {0, s->nxh - 1}, ncol = (s->nx % 2 == 0) ? 2 : 1;
    for (int c = 0; c < ncol; c++) {
        int kx = cols[c];
        for (int ky = 0; ky < s->ny; ky++) {
            fftw_complex *z = &s->spec[(size_t)ky * s->nxh + kx];
            int partner = ky == 0 ? 0 : s->ny - ky;
            if (partner == ky) { /* self-conjugate: real */
                double a = s->amp[(size_t)ky * s->nxh + kx];
                (*z)[0] = s->p.amplitude == SRF_AMP_EXACT ? ((*z)[0] >= 0 ? a : -a)
                                                          : (*z)[0] * M_SQRT2;
                (*z)[1] = 0.0;
            } else if (ky > partner) {
                fftw_complex *w = &s->spec[(size_t)partner * s->nxh + kx];
                (*z)[0] = (*w)[0];
                (*z)[1] = -(*w)[1];
            }
        }
    }
}

/* Shift to zero mean and scale to RMS σ exactly (two passes for accuracy). */
static void normalise(double *z, size_t n, double rms)
{
    double sum = 0, ss = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
    for (size_t k = 0; k < n; k++) sum += z[k];
    double mean = sum / (double)n;
#pragma omp parallel for schedule(static) reduction(+ : ss)
    for (size_t k = 0; k < n; k++) ss += (z[k] - mean) * (z[k] - mean);
    double f = ss > 0 ? rms / sqrt(ss / (double)n) : 0.0;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < n; k++) z[k] = (z[k] - mean) * f;
}

/* Johnson translation of the standardised Gaussian map, then re-normalise. */
static stc_status translate(srf_synth *s, srf_map *m)
{
    srf_johnson j;
    size_t n = (size_t)m->nx * m->ny;
    STC_CALL(srf_johnson_fit(s->p.skewness, s->p.kurtosis, &j));
    double inv = 1.0 / s->p.rms;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < n; k++) m->z[k] = srf_johnson_apply(&j, m->z[k] * inv);
    normalise(m->z, n, s->p.rms);
    snprintf(m->johnson, sizeof m->johnson, "%s",
             j.family == 'U' ? "SU" : j.family == 'B' ? "SB" : "N");
    m->johnson_gamma = j.gamma;
    m->johnson_delta = j.delta;
    return STC_OK;
}

/* Skewness and kurtosis of a zero-mean map with RMS σ. */
static void shape_moments(const double *z, size_t n, double sigma, double *sk, double *ku)
{
    double s3 = 0, s4 = 0;
#pragma omp parallel for schedule(static) reduction(+ : s3, s4)
    for (size_t k = 0; k < n; k++) {
        double u = z[k] / sigma, u2 = u * u;
        s3 += u2 * u;
        s4 += u2 * u2;
    }
    *sk = s3 / (double)n;
    *ku = s4 / (double)n;
}

stc_status srf_synth_run(srf_synth *s, unsigned long seed, srf_map *m)
{
    STC_CHECK(s && m && m->z, STC_EINVAL, "synth_run: NULL argument");
    STC_CHECK(m->nx == s->nx && m->ny == s->ny, STC_EINVAL,
              "synth_run: map is %d x %d, synthesizer %d x %d", m->nx, m->ny, s->nx, s->ny);
    size_t n = (size_t)s->nx * s->ny;
    build_modes(s, seed);
    hermitian(s);
    /* Write straight into the map when its alignment matches the plan's. */
    double *dst = fftw_alignment_of(m->z) == fftw_alignment_of(s->rbuf) ? m->z : s->rbuf;
    fftw_execute_dft_c2r(s->plan, s->spec, dst);
    if (dst != m->z) memcpy(m->z, dst, n * sizeof *dst);
    normalise(m->z, n, s->p.rms);
    m->lx = s->p.lx;
    m->ly = s->p.ly;
    m->origin = SRF_ORIGIN_SYNTH;
    m->synth = s->p;
    m->seed = seed;
    m->johnson[0] = '\0';
    m->johnson_gamma = m->johnson_delta = 0;
    if (s->p.non_gaussian) STC_CALL(translate(s, m));
    shape_moments(m->z, n, s->p.rms, &m->skewness_reached, &m->kurtosis_reached);
    return STC_OK;
}

stc_status srf_synthesize(const srf_synth_params *p, unsigned long seed, srf_map **out)
{
    srf_synth *s = NULL;
    srf_map *m = NULL;
    stc_status st;
    *out = NULL;
    STC_CALL(srf_synth_create(p, &s));
    STC_CALL_GOTO(srf_map_create(p->nx, p->ny, p->lx, p->ly, &m), st, done);
    STC_CALL_GOTO(srf_synth_run(s, seed, m), st, done);
    *out = m;
    m = NULL;
done:
    srf_map_destroy(&m);
    srf_synth_destroy(&s);
    return st;
}
