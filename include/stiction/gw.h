/* stiction — Greenwood–Williamson summation of asperity responses over a
 * summit population (Greenwood & Williamson 1966).  Units: mm, N,
 * MPa; every sum is returned per unit nominal area An.
 *
 * Separation d is measured from the MEAN SUMMIT HEIGHT (as in GW 1966) and
 * given as h = d/σs, σs the standard deviation of summit heights.  A summit
 * of height z touches at interference δ = z − d.
 *
 * Three summit-height populations:
 *  - SRF_GW_GAUSSIAN: φ Gaussian with σs, one summit radius R, density η.
 *    Quadrature (adaptive 21-point Gauss–Kronrod, QUADPACK's QAG, on the
 *    pieces between the model's breakpoints; the tail mapped onto (0, 1],
 *    15-point rule) with the summed abserr as the stated error bound.  The
 *    contact count is exact: η ½ erfc(h/√2).
 *  - SRF_GW_KDE: φ is a Gaussian kernel density estimate of the measured
 *    summit heights (Silverman's rule bandwidth, tabulated on a fine grid and
 *    interpolated by Steffen cubics), one radius R (the mean summit radius
 *    1/<κ>), η = n/An.  Same pieces and quadrature; the abserr bound covers
 *    the quadrature of the tabulated density only, not the KDE's sampling
 *    error.
 *  - SRF_GW_DETERMINISTIC: the sums over the actual summits, each with its
 *    own height and radius (hence its own t/R).  Summits with R <= 0 or
 *    R = inf (curvature <= 0) are excluded and counted.  Exact sums (no
 *    quadrature error); OpenMP reduction over the summits in contact.
 *
 * μs = ΣQmax/ΣP — a ratio of sums, never an average of asperity μs.
 *
 * Thread safety: a srf_gw holds its quadrature and root-solver workspaces;
 * calls on one handle must not run concurrently (separate handles may).
 * The sums neither use nor change GSL's process-wide error handler.
 */
#ifndef STICTION_GW_H
#define STICTION_GW_H

#include "stiction/export.h"
#include "stiction/model.h"
#include "stiction/status.h"
#include "stiction/surface.h"
#include "stiction/table.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum srf_gw_mode {
    SRF_GW_GAUSSIAN = 0,
    SRF_GW_KDE = 1,
    SRF_GW_DETERMINISTIC = 2
} srf_gw_mode;
STC_API const char *srf_gw_mode_name(srf_gw_mode m); /* "gaussian", "kde", "deterministic" */

/* Numerical controls. */
typedef struct srf_gw_params {
    double epsrel;            /* quadrature relative tolerance; default 1e-10 */
    int limit;                /* quadrature subintervals; default 1000 */
    double root_tol;          /* |Δh| tolerance of the pressure solve; default 1e-11 */
    int max_iter;             /* pressure solve iterations; default 200 */
    double coverage_quantile; /* statistical modes: delta_max = the δ below which this
                                 fraction of the load is carried; default 0.999 */
    int kde_grid;             /* KDE: density grid points; default 4096 */
} srf_gw_params;
STC_API void srf_gw_params_default(srf_gw_params *p);

typedef struct srf_gw srf_gw;

/* Gaussian summit heights.  model borrowed (must outlive the handle);
 * p may be NULL (defaults).  Returns new in *out. */
STC_API stc_status srf_gw_create_gaussian(const asp_model *model, double eta_per_mm2, double R_mm,
                                          double sigma_s_mm, const srf_gw_params *p, srf_gw **out);

/* Measured summits: heights z[n] (mm, any datum), radii R[n] (mm) on a
 * nominal area (mm²).  Arrays copied.  mode KDE uses the mean radius 1/<κ>
 * over valid summits; DETERMINISTIC each summit's own. */
STC_API stc_status srf_gw_create_summits(const asp_model *model, srf_gw_mode mode, const double *z,
                                         const double *R, int n, double area_mm2,
                                         const srf_gw_params *p, srf_gw **out);

/* Convenience over srf_summits (borrowed). */
STC_API stc_status srf_gw_create_from_summits(const asp_model *model, srf_gw_mode mode,
                                              const srf_summits *s, const srf_gw_params *p,
                                              srf_gw **out);

/* The same summit population as src (its heights, radii, KDE density and
 * parameters, sorted and standardised once) summed with another model:
 * what srf_gw_create_* would give for model, to the bit, without sorting
 * the summits again (a design sweep sums one population with many
 * models).  src is only read. */
STC_API stc_status srf_gw_create_like(const srf_gw *src, const asp_model *model, srf_gw **out);

STC_API void srf_gw_destroy(srf_gw **g);

/* Population summary. */
typedef struct srf_gw_info {
    srf_gw_mode mode;
    double eta_per_mm2;      /* summit density */
    double sigma_s_mm;       /* summit-height standard deviation */
    double mean_height_mm;   /* mean summit height in the input datum (0 for Gaussian) */
    double R_mm;             /* radius used (statistical) or 1/<κ> (deterministic) */
    double area_mm2;         /* nominal area (NaN for Gaussian) */
    int n_summits;           /* summits used (0 for Gaussian) */
    int n_excluded;          /* summits dropped for R <= 0 or R = inf */
    double E_star_MPa;       /* reference layer E* (model) */
    double H_MPa;            /* hardness H = 2.8 Y of the reference layer (Tabor 1951) */
    double plasticity_index; /* ψ = (E* / H) sqrt(σs/R) (Greenwood & Williamson 1966) */
    double bandwidth_mm;     /* KDE bandwidth (NaN otherwise) */
} srf_gw_info;
STC_API void srf_gw_get_info(const srf_gw *g, srf_gw_info *out);

/* One load point.  Sums per unit nominal area. */
typedef struct srf_gw_point {
    double h;                 /* separation d/σs from the mean summit height */
    double pressure_MPa;      /* P/An */
    double area_fraction;     /* A/An */
    double contacts_per_mm2;  /* N/An */
    double Q_MPa;             /* ΣQmax/An */
    double mu_s;              /* ΣQmax/ΣP (NaN when P = 0 or the model has no friction) */
    double err_P_MPa, err_A, err_Q_MPa; /* absolute error bounds (quadrature; 0 deterministic) */
    double delta_max_over_omega_c; /* deterministic: largest δ/ωc in contact; statistical:
                                      the load quantile (srf_gw_params.coverage_quantile) */
    double tR_min, tR_max;    /* t/R of the summits in contact */
    double load_fraction_outside; /* share of P from δ/ωc or t/R outside the model's range */
    int n_contacts;           /* deterministic: summits in contact (0 statistical) */
    int iterations;           /* pressure solve: Brent iterations (0 for a separation) */
} srf_gw_point;

/* Sums at separation h = d/σs. */
STC_API stc_status srf_gw_at_separation(srf_gw *g, double h, srf_gw_point *out);

/* Solve P(h)/An = pressure_MPa (> 0) for h by Brent's method (GSL) and
 * return the sums there.  Fails with STC_ENOCONV (reason in the message) if
 * the iteration does not converge, STC_ERANGE if the pressure cannot be
 * bracketed (e.g. above what the summits can carry). */
STC_API stc_status srf_gw_at_pressure(srf_gw *g, double pressure_MPa, srf_gw_point *out);

/* The points of the FE friction table t that a prediction at these loads
 * reads, if g's model gives the contact state (a guide: the closed-form
 * model before the table has points, the table's own model after): at each
 * load (pressures, MPa, when by_pressure, else separations h) the contacts'
 * δ/ωc (from the table's first node to the largest in contact, or the load
 * quantile when statistical) and t/R range, at Eco/Esu = E_ratio, marked in
 * need[tbl_points(t)] by tbl_mark_needed.  *pending: how many of the newly
 * marked points are pending. */
STC_API stc_status srf_gw_table_needs(srf_gw *g, const tbl_table *t, double E_ratio,
                                      int by_pressure, const double *loads, int n,
                                      unsigned char *need, int *pending);

#ifdef __cplusplus
}
#endif
#endif
