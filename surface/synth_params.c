/* The synthesis parameters' defaults, names and resolved band edges.  A
 * file of its own because both the synthesis (synth.c) and a map's
 * metadata (map.c: the parameters a synthesized map records) use them,
 * while the synthesis creates maps: with them in synth.c the two files
 * called each other. */
#include <math.h>
#include <string.h>

#include "srf_impl.h"

/* default λs in pixels: 16 points per shortest wavelength (well sampled) */
#define SRF_DEFAULT_CUTOFF_PIXELS 16.0

void srf_synth_params_default(srf_synth_params *p)
{
    memset(p, 0, sizeof *p);
    p->nx = p->ny = 256;
    p->lx = p->ly = 1.0;
    p->rms = 1e-3;
    p->spectrum = SRF_SPECTRUM_EXPONENTIAL;
    p->beta_x = p->beta_y = 0.05;
    p->hurst = 0.8;
    p->amplitude = SRF_AMP_EXACT;
    p->skewness = 0.0;
    p->kurtosis = 3.0;
}

const char *srf_spectrum_name(srf_spectrum s)
{
    switch (s) {
    case SRF_SPECTRUM_EXPONENTIAL: return "exponential";
    case SRF_SPECTRUM_SELF_AFFINE: return "self-affine";
    case SRF_SPECTRUM_USER: return "user";
    }
    return "unknown";
}

/* Resolved self-affine band edges (the 0 = automatic defaults applied). */
void srf_band(const srf_synth_params *p, double *lL, double *lr, double *ls)
{
    double dx = p->lx / p->nx, dy = p->ly / p->ny;
    *lL = p->lambda_long > 0 ? p->lambda_long : p->lx;
    *lr = p->lambda_rolloff > 0 ? p->lambda_rolloff : *lL;
    *ls = p->lambda_cutoff > 0 ? p->lambda_cutoff : SRF_DEFAULT_CUTOFF_PIXELS * fmin(dx, dy);
}
