/* Surface statistics next to the random-process predictions for the same
 * spectral moments (Nayak 1971, J. Lubr. Technol. 93:398; McCool 1986,
 * Wear 107:37). */
#include <math.h>
#include <string.h>

#include "srf_impl.h"
#include "stc_check.h"

#define SRF_PI 3.14159265358979323846
/* McCool 1986: σs² = (1 - 0.8968/α) m0 (fit to Nayak's summit-height variance) */
#define MCCOOL_SIGMA_S_COEFF 0.8968
/* McCool 1986: mean summit radius R = 0.375 sqrt(π/m4) = 1/((8/3) sqrt(m4/π)),
 * the large-α mean summit curvature of Nayak 1971 */
#define MCCOOL_RADIUS_COEFF 0.375
/* McCool 1986: mean summit height above the mean plane 4 sqrt(m0/(π α)) */
#define MCCOOL_OFFSET_COEFF 4.0

static void height_moments(const srf_map *m, srf_stats *o)
{
    size_t n = (size_t)m->nx * m->ny;
    double sum = 0, s2 = 0, s3 = 0, s4 = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
    for (size_t k = 0; k < n; k++) sum += m->z[k];
    double mean = sum / (double)n;
#pragma omp parallel for schedule(static) reduction(+ : s2, s3, s4)
    for (size_t k = 0; k < n; k++) {
        double d = m->z[k] - mean, d2 = d * d;
        s2 += d2;
        s3 += d2 * d;
        s4 += d2 * d2;
    }
    double var = s2 / (double)n;
    o->mean = mean;
    o->sigma = sqrt(var);
    o->skewness = var > 0 ? s3 / (double)n / (var * o->sigma) : NAN;
    o->kurtosis = var > 0 ? s4 / (double)n / (var * var) : NAN;
}

static void summit_stats(const srf_summits *s, srf_stats *o)
{
    double sz = 0, sk = 0, szz = 0;
    o->rule = s->rule;
    o->summits = s->n;
    o->area_mm2 = s->area;
    o->summit_density_per_mm2 = s->n / s->area;
    for (int k = 0; k < s->n; k++) {
        sz += s->z[k];
        sk += s->kappa[k];
    }
    double mz = s->n ? sz / s->n : NAN;
    for (int k = 0; k < s->n; k++) szz += (s->z[k] - mz) * (s->z[k] - mz);
    o->mean_summit_curvature_per_mm = s->n ? sk / s->n : NAN;
    o->mean_summit_radius_mm = 1.0 / o->mean_summit_curvature_per_mm;
    o->sigma_s_mm = s->n > 1 ? sqrt(szz / s->n) : NAN;
    o->summit_mean_offset_mm = mz; /* s->z is measured from the mean plane */
}

static void theory(srf_stats *o)
{
    o->alpha = o->m2 > 0 ? o->m0 * o->m4 / (o->m2 * o->m2) : NAN;
    /* Nayak 1971: density of all summits of an isotropic Gaussian surface */
    o->summit_density_nayak_per_mm2 = o->m2 > 0 ? o->m4 / (6 * SRF_PI * sqrt(3.0) * o->m2) : NAN;
    o->mean_summit_radius_mccool_mm = o->m4 > 0 ? MCCOOL_RADIUS_COEFF * sqrt(SRF_PI / o->m4) : NAN;
    double f = 1 - MCCOOL_SIGMA_S_COEFF / o->alpha;
    o->sigma_s_mccool_mm = f > 0 ? sqrt(f * o->m0) : NAN;
    o->summit_mean_offset_mccool_mm =
        o->alpha > 0 ? MCCOOL_OFFSET_COEFF * sqrt(o->m0 / (SRF_PI * o->alpha)) : NAN;
}

stc_status srf_stats_compute(const srf_map *m, const srf_summits *s, srf_stats *out)
{
    STC_CHECK(m && m->z && s && out, STC_EINVAL, "stats_compute: NULL argument");
    memset(out, 0, sizeof *out);
    srf_moments mo;
    height_moments(m, out);
    STC_CALL(srf_map_moments(m, &mo));
    out->m0 = mo.m0;
    out->m2 = mo.m2;
    out->m4 = mo.m4;
    out->m20 = mo.m20;
    out->m02 = mo.m02;
    out->m40 = mo.m40;
    out->m04 = mo.m04;
    out->moments_fd = !m->periodic;
    /* heights so large, or pixels so small or large, that the moments
     * overflow or underflow (a file in the wrong unit): statistics of
     * infinities or of zero slopes are not results */
    int finite = isfinite(out->sigma) && isfinite(mo.m0) && isfinite(mo.m2) &&
                 isfinite(mo.m4) && (out->sigma == 0 || isfinite(out->kurtosis)) &&
                 isfinite(m->lx * m->ly) && (out->sigma == 0 || (mo.m2 > 0 && mo.m4 > 0));
    double zmax = 0; /* for the message only */
    for (size_t k = 0; !finite && k < (size_t)m->nx * m->ny; k++) zmax = fmax(zmax, fabs(m->z[k]));
    STC_CHECK(finite, STC_ERANGE,
              "heights up to %g mm on pixels of %g x %g mm: their moments are not "
              "representable (sigma = %g mm, m2 = %g, m4 = %g mm^-2; valid: heights and pixel "
              "sizes in mm that give finite moments, and m2, m4 > 0)", zmax, m->lx / m->nx,
              m->ly / m->ny, out->sigma, mo.m2, mo.m4);
    summit_stats(s, out);
    theory(out);
    return STC_OK;
}
