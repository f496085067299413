/* stiction — rough surfaces: FFT synthesis, import, summits, statistics
 * (docs/design.md §5).  Units: mm throughout (heights, lengths), 1/mm for
 * curvature, rad/mm for wavevectors q = 2π/λ.  Library code never prints.
 *
 * Conventions stated once, used everywhere:
 *  - A map is an nx × ny periodic grid of heights z[j*nx + i] (row-major,
 *    row j = y index), pixel dx = lx/nx, dy = ly/ny; point (i, j) sits at
 *    x = i dx, y = j dy.
 *  - Spectral moments m0, m2, m4 are Nayak's (1971) PROFILE moments averaged
 *    over all profile directions θ:  with the 2-D moments
 *    m_pq = Σ qx^p qy^q |Z(q)|² (Σ over the discrete spectrum, normalised so
 *    m00 = <z²>),
 *        m0 = m00,  m2 = (m20 + m02)/2,  m4 = 3 (m40 + 2 m22 + m04)/8.
 *    For an isotropic surface these equal the moments of any single profile;
 *    the x and y profile moments (m20, m40 / m02, m04) are reported too.
 *    Periodic maps (synthesized): m_pq from the FFT.  Non-periodic maps
 *    (imported measurements, where the wrap-around jump would swamp m2 and
 *    m4): the same quantities from finite differences over interior points,
 *    m20 = <z_x²>, m40 = <z_xx²>, m22 = <z_xy²> (McCool 1987, Wear 115:361),
 *    z_x central, z_xx 3-point, z_xy the 4-point cross stencil.
 *  - Mean curvature of a summit: κ = -(z_xx + z_yy)/2 from 3-point central
 *    differences (the 5-point Laplacian stencil), positive at a maximum;
 *    summit radius R = 1/κ (Nayak 1971 and McCool 1986 use the same mean
 *    curvature, so R compares with their mean-radius predictions).
 *  - Summit: a grid point strictly higher than all its 8 (SRF_RULE_8,
 *    default) or 4 (SRF_RULE_4) neighbours, periodic edges; on a
 *    non-periodic (imported) map the edge rows and columns are not searched
 *    and the summit area is the interior (nx-2)(ny-2) dx dy.
 */
#ifndef STICTION_SURFACE_H
#define STICTION_SURFACE_H

#include "stiction/export.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- spectra */

typedef enum srf_spectrum {
    SRF_SPECTRUM_EXPONENTIAL = 0, /* exponential ACF, correlation lengths βx*, βy* */
    SRF_SPECTRUM_SELF_AFFINE = 1, /* plateau + power law q^-2(1+H), cut-offs */
    SRF_SPECTRUM_USER = 2         /* caller's PSD callback */
} srf_spectrum;

typedef enum srf_amplitude {
    SRF_AMP_EXACT = 0,   /* |Z(q)| = sqrt(C(q)) exactly, random phase (default) */
    SRF_AMP_RAYLEIGH = 1 /* complex Gaussian Z(q): Rayleigh amplitude, random phase */
} srf_amplitude;

/* A 2-D power spectral density C(qx, qy) >= 0 (any overall scale: the map is
 * rescaled to the target RMS).  qx, qy in rad/mm.  Must be thread-safe. */
typedef double (*srf_psd_fn)(double qx, double qy, void *user);

/* Synthesis parameters.  Every field is written as an HDF5 attribute. */
typedef struct srf_synth_params {
    int nx, ny;             /* grid points; default 256 × 256 */
    double lx, ly;          /* periodic lengths, mm; default 1 × 1 */
    double rms;             /* target RMS height σ, mm (exact after synthesis); default 1e-3 */
    srf_spectrum spectrum;  /* default SRF_SPECTRUM_EXPONENTIAL */
    double beta_x, beta_y;  /* exponential: lengths where the ACF falls to 0.1 (βx*, βy*), mm;
                               default 0.05, 0.05 */
    double hurst;           /* self-affine: Hurst exponent H in (0, 1]; default 0.8 */
    double lambda_long;     /* self-affine: no power at wavelengths > λL, mm; 0 = lx (default) */
    double lambda_rolloff;  /* self-affine: plateau for λr <= λ <= λL, mm; 0 = λL (no plateau) */
    double lambda_cutoff;   /* self-affine: no power at wavelengths < λs, mm;
                               0 = 16 pixels (default: the well-sampled limit) */
    srf_psd_fn psd;         /* SRF_SPECTRUM_USER: the PSD (borrowed); default NULL */
    void *psd_user;         /* passed to psd (borrowed); default NULL */
    srf_amplitude amplitude;/* default SRF_AMP_EXACT */
    int non_gaussian;       /* nonzero: Johnson-translate to skewness/kurtosis; default 0 */
    double skewness;        /* target skewness; default 0 */
    double kurtosis;        /* target kurtosis (3 = Gaussian); default 3 */
    int threads;            /* FFTW/OpenMP threads; 0 = omp_get_max_threads() (default) */
} srf_synth_params;

STC_API void srf_synth_params_default(srf_synth_params *p);
STC_API stc_status srf_synth_params_validate(const srf_synth_params *p);
STC_API const char *srf_spectrum_name(srf_spectrum s); /* "exponential", "self-affine", "user" */

/* The continuous PSDs the synthesizer samples (exposed for tests and callers).
 * Exponential ACF R(τ) = σ² exp(-ln10 · sqrt((τx/βx*)² + (τy/βy*)²)) has the
 * 2-D spectrum C(q) = σ² ℓx ℓy / (2π) · (1 + qx²ℓx² + qy²ℓy²)^(-3/2), ℓ = β* / ln10. */
STC_API double srf_psd_eval(const srf_synth_params *p, double qx, double qy);

/* ---------------------------------------------------------------- maps */

/* Where a map came from and how (all written as HDF5 attributes). */
typedef enum srf_origin { SRF_ORIGIN_NONE = 0, SRF_ORIGIN_SYNTH, SRF_ORIGIN_IMPORT } srf_origin;

typedef struct srf_map {
    int nx, ny;          /* grid points */
    double lx, ly;       /* periodic lengths, mm (pixel dx = lx/nx) */
    double *z;           /* [ny][nx] heights, mm, row-major (owned) */
    srf_origin origin;   /* SRF_ORIGIN_SYNTH: `synth` and `seed` are meaningful */
    int periodic;        /* 1 (create, synthesis) or 0 (import): edge handling, moments */
    srf_synth_params synth; /* synthesis parameters (psd pointers cleared when read back) */
    unsigned long seed;  /* GSL RNG seed */
    double skewness_reached, kurtosis_reached; /* after (optional) Johnson translation */
    char johnson[8];     /* "", "SU", "SB" or "N": translator family used */
    double johnson_gamma, johnson_delta; /* translator parameters (z = f((u-γ)/δ)) */
    char source[256];    /* imported file (and dataset), or "" */
    double zscale;       /* import: raw heights were multiplied by this to give mm */
    double tilt_x, tilt_y, offset; /* plane removed on import: z -= a x + b y + c (mm/mm, mm) */
} srf_map;

/* Returns a new zeroed map (takes nothing; caller owns *out). */
STC_API stc_status srf_map_create(int nx, int ny, double lx, double ly, srf_map **out);
STC_API void srf_map_destroy(srf_map **m);

/* Read a map written by srf_map_write_h5 (dataset "/height" + attributes).
 * Returns new in *out.  Here and in the imports below, a path that is
 * missing, unreadable or a directory is STC_EIO ("path: is a directory"). */
STC_API stc_status srf_map_read(const char *path, srf_map **out);

/* Write heights [ny][nx] as dataset "/height" with every parameter as an
 * attribute.  Writes to a temporary file beside `path` and renames it on
 * success, so a failed write leaves no file. */
STC_API stc_status srf_map_write_h5(const srf_map *m, const char *path);

/* Write a grey-scale PNG (black = lowest, white = highest), temp + rename. */
STC_API stc_status srf_map_write_png(const srf_map *m, const char *path);

/* Import measured heights with pixel size dx × dy (mm) and remove the
 * least-squares plane.  Text: whitespace-separated numbers, one grid row per
 * line (rows = y), '#' starts a comment; every row the same length.  HDF5:
 * a 2-D numeric dataset `dataset` ([ny][nx]).  `zscale` multiplies the raw
 * heights (e.g. 1e-3 for µm data); 1 = already mm.  Malformed input →
 * STC_EFORMAT naming line and column.  Returns new in *out. */
STC_API stc_status srf_map_import_text(const char *path, double dx, double dy, double zscale,
                                       srf_map **out);
STC_API stc_status srf_map_import_h5(const char *path, const char *dataset, double dx, double dy,
                                     double zscale, srf_map **out);

/* Remove the least-squares plane z = a x + b y + c; stores a, b, c in the map. */
STC_API void srf_map_detrend(srf_map *m);

/* ---------------------------------------------------------------- synthesis */

/* A synthesizer owns its FFTW plans and spectrum (plan once, execute many).
 * create/destroy are not thread-safe (FFTW planner); run on distinct
 * synthesizers may proceed concurrently. */
typedef struct srf_synth srf_synth;
STC_API stc_status srf_synth_create(const srf_synth_params *p, srf_synth **out); /* copies p */
STC_API void srf_synth_destroy(srf_synth **s);

/* Fill `map` (borrowed; must be p->nx × p->ny) with one realisation for
 * `seed`.  Random numbers: GSL mt19937, one stream per spectrum row seeded
 * with a SplitMix64 hash of (seed, row), so the modes do not depend on the
 * thread count; same seed + params + thread count → bit-identical map
 * (OpenMP reductions may change the last bit across thread counts). */
STC_API stc_status srf_synth_run(srf_synth *s, unsigned long seed, srf_map *map);

/* Convenience: create, run once, destroy.  Returns a new map. */
STC_API stc_status srf_synthesize(const srf_synth_params *p, unsigned long seed, srf_map **out);

/* Spectral moments of the synthesizer's discrete target spectrum, scaled to
 * σ² = rms² (the Gaussian map, exact-amplitude mode, reproduces them). */
typedef struct srf_moments {
    double m0;        /* <z²>, mm² */
    double m2, m4;    /* direction-averaged profile moments (header convention) */
    double m20, m02;  /* x- and y-profile slope variances */
    double m40, m04, m22;
} srf_moments;
STC_API stc_status srf_synth_target_moments(const srf_synth *s, srf_moments *out);

/* Spectral moments of a map: FFT when m->periodic, else finite differences
 * (header convention).  The mean is excluded. */
STC_API stc_status srf_map_moments(const srf_map *m, srf_moments *out);

/* Johnson (1949) translator fitted to skewness/kurtosis by moment matching.
 * family: 'N' (Gaussian), 'U' (SU, unbounded) or 'B' (SB, bounded).
 * Transform of a standard normal u: SU: sinh((u-γ)/δ), SB: 1/(1+exp(-(u-γ)/δ)),
 * followed by standardisation. */
typedef struct srf_johnson {
    char family;
    double gamma, delta;
    double mean, sd; /* of the untranslated variable, for standardisation */
} srf_johnson;
STC_API stc_status srf_johnson_fit(double skewness, double kurtosis, srf_johnson *out);
STC_API double srf_johnson_apply(const srf_johnson *j, double u); /* standardised result */

/* ---------------------------------------------------------------- summits */

enum { SRF_RULE_8 = 8, SRF_RULE_4 = 4 };

typedef struct srf_summits {
    int n;          /* number of summits */
    int rule;       /* SRF_RULE_8 or SRF_RULE_4 */
    double area;    /* area searched, mm²: lx·ly (periodic) or the interior (imported) */
    double *x, *y;  /* [n] positions, mm */
    double *z;      /* [n] heights above the map's mean plane, mm */
    double *kappa;  /* [n] mean curvature -(z_xx+z_yy)/2, 1/mm (> 0 normally) */
    double *R;      /* [n] 1/kappa, mm (inf when kappa <= 0) */
} srf_summits;

/* Find summits of `m` (borrowed).  Returns new in *out, ordered by (y, x). */
STC_API stc_status srf_summits_find(const srf_map *m, int rule, srf_summits **out);
STC_API void srf_summits_destroy(srf_summits **s);

/* ---------------------------------------------------------------- statistics */

typedef struct srf_stats {
    /* heights */
    double mean, sigma, skewness, kurtosis;
    /* spectral moments (header convention) and bandwidth α = m0 m4 / m2² */
    double m0, m2, m4, alpha;
    double m20, m02, m40, m04;
    int moments_fd;                 /* 1: finite-difference moments (non-periodic map) */
    /* measured summits */
    int rule;
    int summits;
    double area_mm2;                /* area searched for summits (srf_summits.area) */
    double summit_density_per_mm2;
    double mean_summit_radius_mm;   /* 1 / (mean of κ over summits) */
    double mean_summit_curvature_per_mm;
    double sigma_s_mm;              /* std of summit heights */
    double summit_mean_offset_mm;   /* mean summit height - mean surface height */
    /* random-process theory for the same m0, m2, m4 */
    double summit_density_nayak_per_mm2;  /* Nayak 1971: m4/(6π√3 m2) */
    double mean_summit_radius_mccool_mm;  /* McCool 1986: 0.375 sqrt(π/m4) */
    double sigma_s_mccool_mm;             /* McCool 1986: sqrt(1 - 0.8968/α) σ */
    double summit_mean_offset_mccool_mm;  /* McCool 1986: 4 σ / sqrt(π α) */
} srf_stats;

/* Statistics of map `m` and its summits `s` (both borrowed). */
STC_API stc_status srf_stats_compute(const srf_map *m, const srf_summits *s, srf_stats *out);

#ifdef __cplusplus
}
#endif
#endif
