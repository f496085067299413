/* Internal helpers of the surface module (not installed). */
#ifndef STICTION_SRF_IMPL_H
#define STICTION_SRF_IMPL_H

#include <fftw3.h>

#include "stiction/surface.h"

/* FFTW's planner and its thread set-up are global state: every planner call
 * in the library goes through these, serialised by one lock (spectrum.c;
 * FFTW: only fftw_execute* is thread-safe). */
fftw_plan srf_plan_r2c(int nx, int ny, double *in, fftw_complex *out, int threads);
fftw_plan srf_plan_c2r(int nx, int ny, fftw_complex *in, double *out, int threads);
void srf_plan_destroy(fftw_plan p);
int srf_threads(int requested); /* 0 → omp_get_max_threads() */

/* Wavevector (rad/mm) of half-spectrum index (kx, ky) of an nx × ny grid. */
static inline double srf_qx(int kx, double lx) { return 2.0 * 3.14159265358979323846 * kx / lx; }
static inline double srf_qy(int ky, int ny, double ly)
{
    int k = ky <= ny / 2 ? ky : ky - ny;
    return 2.0 * 3.14159265358979323846 * k / ly;
}

/* Weight of half-spectrum column kx in a full-spectrum sum (1 for the
 * self-conjugate columns kx = 0 and kx = nx/2 of even nx, else 2). */
static inline double srf_col_weight(int kx, int nx)
{
    return (kx == 0 || (nx % 2 == 0 && kx == nx / 2)) ? 1.0 : 2.0;
}

/* Accumulate the 2-D moments of a half-spectrum power array pw[ny][nx/2+1]
 * into out (normalised by the total power, then scaled by m0). */
void srf_moments_from_power(const double *pw, int nx, int ny, double lx, double ly,
                            double m0, srf_moments *out);

/* Self-affine band edges λL, λr, λs (mm) with the 0 = automatic defaults resolved. */
void srf_band(const srf_synth_params *p, double *lL, double *lr, double *ls);

/* A summit's height and radius (mm). */
typedef struct srf_zr {
    double z, R;
} srf_zr;

/* Sort v[n] by height, highest first, stably (equal heights keep their
 * order; -0 ranks with +0): heightsort.c.  STC_ENOMEM if out of memory. */
stc_status srf_sort_desc(srf_zr *v, int n);

/* Temporary file name beside `path` ("path.tmp-PID-K", created empty with
 * mode 0666 & ~umask); buf must hold strlen(path) + 32. */
stc_status srf_tmpname(const char *path, char *buf, size_t n);

#endif
