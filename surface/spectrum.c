/* FFTW planning (serialised) and spectral moments of maps and spectra. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#include <omp.h>

#include "srf_impl.h"
#include "stc_check.h"

int srf_threads(int requested) { return requested > 0 ? requested : omp_get_max_threads(); }

/* fftw_init_threads must run once before any threaded plan; the planner is
 * not thread-safe, so both run under one lock.  FFTW's planner state is
 * process-wide, and so is the lock: a file-local mutex.  A named OpenMP
 * critical section would do the same, but its lock is a global symbol
 * (.gomp_critical_user_<name>) the shared library would export; an unnamed
 * one shares its lock with every unnamed critical of the process, a
 * caller's too, and would deadlock a call made inside one. */
static pthread_mutex_t planner_lock = PTHREAD_MUTEX_INITIALIZER;
static int fftw_threads_ready;

/* Take the planner and set its thread count for one plan; returns the count
 * it found (0: threads unavailable), which plan_done restores before it
 * lets the planner go, so that a caller's own plans keep their setting. */
static int plan_setup(int threads)
{
    pthread_mutex_lock(&planner_lock);
    if (!fftw_threads_ready) fftw_threads_ready = fftw_init_threads() ? 1 : -1;
    if (fftw_threads_ready < 0) return 0;
    int old = fftw_planner_nthreads();
    fftw_plan_with_nthreads(srf_threads(threads));
    return old;
}

static void plan_done(int old)
{
    if (old > 0) fftw_plan_with_nthreads(old);
    pthread_mutex_unlock(&planner_lock);
}

fftw_plan srf_plan_r2c(int nx, int ny, double *in, fftw_complex *out, int threads)
{
    int old = plan_setup(threads);
    /* ESTIMATE: planning must not overwrite the caller's data, and a
     * MEASURE plan of a 4096² grid costs more than many executions. */
    fftw_plan p = fftw_plan_dft_r2c_2d(ny, nx, in, out, FFTW_ESTIMATE);
    plan_done(old);
    return p;
}

fftw_plan srf_plan_c2r(int nx, int ny, fftw_complex *in, double *out, int threads)
{
    int old = plan_setup(threads);
    fftw_plan p = fftw_plan_dft_c2r_2d(ny, nx, in, out, FFTW_ESTIMATE);
    plan_done(old);
    return p;
}

void srf_plan_destroy(fftw_plan p)
{
    pthread_mutex_lock(&planner_lock);
    fftw_destroy_plan(p);
    pthread_mutex_unlock(&planner_lock);
}

/* Profile moments averaged over directions θ (header convention, Nayak 1971):
 * m2(θ) = m20 c² + 2 m11 cs + m02 s²  → mean (m20 + m02)/2;
 * m4(θ) = m40 c⁴ + 4 m31 c³s + 6 m22 c²s² + 4 m13 cs³ + m04 s⁴
 *       → mean 3(m40 + 2 m22 + m04)/8  (<c⁴> = 3/8, <c²s²> = 1/8). */
static void profile_average(srf_moments *m)
{
    m->m2 = 0.5 * (m->m20 + m->m02);
    m->m4 = 3.0 * (m->m40 + 2.0 * m->m22 + m->m04) / 8.0;
}

void srf_moments_from_power(const double *pw, int nx, int ny, double lx, double ly,
                            double m0, srf_moments *out)
{
    int nxh = nx / 2 + 1;
    double tot = 0, a20 = 0, a02 = 0, a40 = 0, a04 = 0, a22 = 0;
#pragma omp parallel for schedule(static) reduction(+ : tot, a20, a02, a40, a04, a22)
    for (int ky = 0; ky < ny; ky++) {
        double qy = srf_qy(ky, ny, ly), qy2 = qy * qy;
        for (int kx = 0; kx < nxh; kx++) {
            if (kx == 0 && ky == 0) continue; /* the mean is not roughness */
            double qx = srf_qx(kx, lx), qx2 = qx * qx;
            double w = srf_col_weight(kx, nx) * pw[(size_t)ky * nxh + kx];
            tot += w;
            a20 += w * qx2;
            a02 += w * qy2;
            a40 += w * qx2 * qx2;
            a04 += w * qy2 * qy2;
            a22 += w * qx2 * qy2;
        }
    }
    double f = tot > 0 ? m0 / tot : 0.0;
    out->m0 = tot > 0 ? m0 : 0.0;
    out->m20 = a20 * f;
    out->m02 = a02 * f;
    out->m40 = a40 * f;
    out->m04 = a04 * f;
    out->m22 = a22 * f;
    profile_average(out);
}

/* Finite-difference moments over interior points (non-periodic maps):
 * slope central, curvature 3-point, twist the 4-point cross stencil. */
static void fd_moments(const srf_map *m, srf_moments *out)
{
    int nx = m->nx, ny = m->ny;
    double dx = m->lx / nx, dy = m->ly / ny, sum = 0, s0 = 0;
    double a20 = 0, a02 = 0, a40 = 0, a04 = 0, a22 = 0;
    size_t n = (size_t)nx * ny;
    for (size_t k = 0; k < n; k++) sum += m->z[k];
    double mean = sum / (double)n;
#pragma omp parallel for schedule(static) reduction(+ : s0, a20, a02, a40, a04, a22)
    for (int j = 1; j < ny - 1; j++) {
        const double *u = m->z + (size_t)(j - 1) * nx, *c = u + nx, *d = c + nx;
        for (int i = 1; i < nx - 1; i++) {
            double zx = (c[i + 1] - c[i - 1]) / (2 * dx), zy = (d[i] - u[i]) / (2 * dy);
            double zxx = (c[i + 1] - 2 * c[i] + c[i - 1]) / (dx * dx);
            double zyy = (d[i] - 2 * c[i] + u[i]) / (dy * dy);
            double zxy = (d[i + 1] - d[i - 1] - u[i + 1] + u[i - 1]) / (4 * dx * dy);
            s0 += (c[i] - mean) * (c[i] - mean);
            a20 += zx * zx;
            a02 += zy * zy;
            a40 += zxx * zxx;
            a04 += zyy * zyy;
            a22 += zxy * zxy;
        }
    }
    double f = 1.0 / ((double)(nx - 2) * (ny - 2));
    out->m0 = s0 * f;
    out->m20 = a20 * f;
    out->m02 = a02 * f;
    out->m40 = a40 * f;
    out->m04 = a04 * f;
    out->m22 = a22 * f;
    profile_average(out);
}

stc_status srf_map_moments(const srf_map *m, srf_moments *out)
{
    STC_CHECK(m && m->z && out, STC_EINVAL, "map_moments: NULL argument");
    if (!m->periodic) {
        fd_moments(m, out);
        return STC_OK;
    }
    int nx = m->nx, ny = m->ny, nxh = nx / 2 + 1;
    size_t nr = (size_t)nx * ny, nc = (size_t)ny * nxh;
    stc_status st = STC_OK;
    double *in = fftw_malloc(nr * sizeof *in);
    fftw_complex *spec = fftw_malloc(nc * sizeof *spec);
    double *pw = malloc(nc * sizeof *pw);
    fftw_plan plan = NULL;
    STC_CHECK_GOTO(in && spec && pw, st, done, STC_ENOMEM, "map_moments: out of memory");
    plan = srf_plan_r2c(nx, ny, in, spec, 0);
    STC_CHECK_GOTO(plan, st, done, STC_ENOMEM, "map_moments: FFTW could not plan");
    for (size_t k = 0; k < nr; k++) in[k] = m->z[k];
    fftw_execute(plan);
    double tot = 0;
    for (size_t k = 0; k < nc; k++) {
        pw[k] = spec[k][0] * spec[k][0] + spec[k][1] * spec[k][1];
        if (k > 0) tot += srf_col_weight((int)(k % nxh), nx) * pw[k];
    }
    /* Parseval (unnormalised FFTW): Σ z² = Σ_full |Z|² / N. */
    srf_moments_from_power(pw, nx, ny, m->lx, m->ly, tot / ((double)nr * (double)nr), out);
done:
    if (plan) srf_plan_destroy(plan);
    fftw_free(in);
    fftw_free(spec);
    free(pw);
    return st;
}
