/* Gaussian-process smoothing surrogate for noisy table values (not installed).
 *
 * Each table point i carries an input x_i (1 to 3 coordinates), a value y_i
 * and that value's own error estimate sy_i.  The model (Rasmussen & Williams
 * 2006, ch. 2, with the explicit mean of §2.7):
 *
 *   y_i = m + f(x_i) + e_i,
 *   f ~ GP(0, sf^2 exp(-1/2 sum_d ((x_d - x'_d) / ell_d)^2)),
 *   e_i ~ N(0, (c sy_i)^2),
 *
 * (or, with tbl_gp_fit_kernel, length scales that vary along one input and a
 * main term scaled by one input over a base term),
 *
 * with m a constant estimated by generalised least squares (universal
 * kriging: the predictive variance includes m's uncertainty; Santner,
 * Williams & Notz 2003, ch. 3).  ell_d, sf and c maximise the restricted
 * marginal likelihood (R&W eq. 2.45, m integrated out under a flat prior;
 * the REML criterion of Harville 1974), c being confined to [1, 10]: the
 * given sy may be understated, never trusted as too large.  Bounds:
 * ell_d in [0.25 x smallest spacing, 20 x range] of dim d, sf in
 * [1e-3, 1e2] x max(sd(y), rms(sy)).
 *
 * For the caller:
 * - Inputs are used in their own units: a length scale is fitted per input
 *   dimension, so no scaling is needed (a log axis, e.g. of a quantity
 *   spanning decades, is best passed as its log).  A dimension whose inputs
 *   are all equal is ignored (ell = inf) and predictions do not depend on it.
 * - sy is each value's own error estimate (e.g. the standard error of a
 *   mean, or a solver's error bound), in y's units.  Its relative sizes
 *   weight the points; a common understatement up to tenfold is absorbed by
 *   c (sy = true sd / 4 gives c = 4.05 in the test).  Overstated sy are not
 *   corrected (c >= 1): the fit then oversmooths.  noise_scale at 10 says
 *   sy is understated more than tenfold.
 * - With 2 or 3 distinct values in a dimension its length scale is weakly
 *   determined and the sd between those values can be overconfident; check
 *   loo_cover2 (about 0.95 for a calibrated fit) and ell_at_bound.
 * - The fit is O(n^3) per likelihood evaluation and uses a few hundred
 *   evaluations; beyond 256 points it searches on a 256-point subset first,
 *   then refines on all points (measured on 2 cores, 3D scattered / grid:
 *   n = 100 in 13 ms, n = 500 in 0.18 / 0.15 s, n = 1000 in 0.9 / 0.7 s).
 *   Memory: n^2 doubles kept, another n^2 while fitting.
 *
 * Thread safety: tbl_gp_fit and tbl_gp_destroy are not thread-safe on the
 * same handle; tbl_gp_predict, tbl_gp_loo and tbl_gp_get_info only read the
 * handle and may run concurrently on it.  tbl_gp_fit switches GSL's error
 * handler off while it runs (statuses are checked), like surface/gw.c.
 */
#ifndef STICTION_TABLE_FIT_H
#define STICTION_TABLE_FIT_H

#include "stiction/status.h"

typedef struct tbl_gp tbl_gp;

#define TBL_GP_MAXPAR 9 /* searched hyperparameters at most (3 inputs, both kernel options) */

typedef struct tbl_gp_info {
    int n, dim;          /* points, input dimensions (1..3) */
    double ell[3];       /* fitted length scales per input dim (input units); inf for a dim
                            whose inputs are all equal */
    double sf;           /* fitted signal standard deviation (0 when every dim is constant); with
                            scale_dim, the main term's per unit of x[scale_dim]^2 */
    double noise_scale;  /* fitted factor c >= 1 multiplying every given noise sd */
    int mod_dim;         /* input dim modulating the length scales (tbl_gp_fit_kernel),
                            -1: none (stationary) */
    double gamma;        /* fitted modulation: ell_d(x) = ell[d] exp(gamma (x[mod_dim] -
                            mod_centre)); 0 without */
    double mod_centre;   /* the middle of the modulating input's range (0 without) */
    int gamma_at_bound;  /* -1 / +1 when gamma ended at its lower / upper bound, else 0 */
    int scale_dim;       /* input dim scaling the main term (tbl_gp_fit_kernel), -1: none */
    double base_ell[3];  /* with scale_dim: the base term's length scales (inf for a dim
                            not in it) */
    double base_sd;      /* with scale_dim: the base term's sd, rho sf (0 without) */
    double mean;         /* GLS estimate of the constant mean */
    double log_ml;       /* restricted log marginal likelihood (R&W eq. 2.45) at the optimum */
    double loo_rms;      /* rms of leave-one-out residuals y_i - mu_{-i} */
    double loo_max;      /* largest |y_i - mu_{-i}| */
    double loo_cover2;   /* fraction of points with |y_i - mu_{-i}| <= 2 sd_{-i} */
    int evaluations;     /* likelihood evaluations of the optimiser (0 when no input varies:
                            c then has a closed form) */
    /* diagnostics */
    double ell_lo[3], ell_hi[3]; /* bounds of ell per dim (input units; inf for ignored dims):
                                    0.25 x smallest spacing, 20 x range */
    int ell_at_bound[3]; /* -1 / +1 when ell[d] ended within 1e-3 (relative, in log ell) of its
                            lower / upper bound, else 0 */
    int converged;       /* 1 if every Nelder-Mead run met its simplex-size tolerance, 0 if one
                            stopped at its evaluation limit (the best point found is used) */
    int subset_n;        /* points of the first search stage (farthest-point subset) when
                            n > 256, before refining on all points; 0: all points throughout */
    double jitter;       /* variance added to every diagonal element of the covariance for a
                            stable Cholesky factorisation at the optimum (0: none needed) */
    int npar;            /* searched hyperparameters (0 when no input varies) */
    double par[TBL_GP_MAXPAR]; /* their values at the optimum in the search's coordinates: log
                            ell per varying input, log(c / sf), gamma x half the modulating
                            input's range, log ell per base input, log rho (in that order,
                            those the kernel has); tbl_gp_fit_at rebuilds the fit from them */
} tbl_gp_info;

/* Fit.  x: [n][dim] row-major inputs, y: [n] values, sy: [n] noise standard
 * deviations > 0 (each point's own error estimate, in y's units); all
 * borrowed and copied.  Returns new in *out (release with tbl_gp_destroy);
 * *out is NULL on failure.  Deterministic: the same input gives
 * bit-identical results.
 * Errors: STC_EINVAL for n < 2, dim outside 1..3, non-finite x or y, sy not
 * finite and > 0 (message names the argument, value and valid range);
 * STC_ENOMEM; STC_ESOLVER if the covariance at the optimum cannot be
 * factorised even with jitter (not met in practice: the noise keeps it
 * positive definite).  An optimiser run that stops at its evaluation limit
 * is not an error: info.converged = 0. */
stc_status tbl_gp_fit(int n, int dim, const double *x, const double *y, const double *sy,
                      tbl_gp **out);

/* Kernel options of tbl_gp_fit_kernel; {-1, -1, 0} (or NULL) is tbl_gp_fit's
 * stationary squared exponential.
 *
 * mod_dim: length scales that vary along that input,
 * ell_d(x) = ell_d exp(gamma (x[mod_dim] - centre)), centre the middle of
 * its range, the same factor for every dim, in the non-stationary squared
 * exponential of Gibbs (1997) (Paciorek & Schervish 2004):
 *
 *   main(x, x') = prod_d (2 l_d l'_d / (l_d^2 + l'_d^2))^(1/2)
 *                 exp(-sum_d (x_d - x'_d)^2 / (l_d^2 + l'_d^2)),  l_d = ell_d(x),
 *
 * gamma fitted with the other hyperparameters (one more), confined to
 * |gamma| x half that range <= 1.5 (ell at most 4.5-fold either way from the
 * centre); gamma = 0 is the stationary kernel.  For a function that is
 * rougher in one part of the input space than in another.
 *
 * scale_dim: the main term multiplied by that input's values at both ends,
 * plus a stationary base term over the inputs of base_dims (bit d for
 * input d):
 *
 *   k(x, x') = sf^2 (rho^2 exp(-1/2 sum_{d in base} ((x_d - x'_d) / bell_d)^2)
 *                    + x[scale] x'[scale] main(x, x')),
 *
 * so that where x[scale] = 0 the function is the base term's alone, a
 * function of the base inputs only, and the main term is an effect that
 * grows from there in proportion to x[scale] (times the main term's own
 * variation).  bell_d and rho (in [1e-3, 1e3]) are fitted: one more
 * parameter per base input and one.
 *
 * Either option evaluates the kernel per pair (no per-dim factor tables)
 * and adds parameters, so the fit takes longer: measured on 2 cores, 3D
 * grids, both options against none: n = 72 in 0.10 / 0.01 s, n = 300 in
 * 2.5 / 0.19 s, n = 1024 in 12 / 3.2 s (815 / 267 evaluations).  A constant
 * mod_dim or scale_dim is ignored (info.mod_dim / scale_dim = -1).
 * Errors: as tbl_gp_fit; STC_EINVAL for mod_dim or scale_dim outside
 * -1..dim-1 or base_dims naming a dim >= dim. */
typedef struct tbl_gp_kernel {
    int mod_dim;        /* input modulating the length scales, -1: none */
    int scale_dim;      /* input scaling the main term, -1: none */
    unsigned base_dims; /* with scale_dim: the base term's inputs, bit d = input d */
} tbl_gp_kernel;

stc_status tbl_gp_fit_kernel(int n, int dim, const double *x, const double *y, const double *sy,
                             const tbl_gp_kernel *kernel, tbl_gp **out);

/* The fit at given hyperparameters, without the search: par[npar] from
 * info.par of a fit of the same x, y, sy and kernel gives that fit bit for
 * bit (but info.evaluations = 0, info.converged = 1, info.subset_n = 0), in
 * the time of two factorisations and one triangular inverse instead of
 * hundreds of likelihood evaluations (measured on 2 cores, 3D grids, both
 * kernel options: n = 300 in 9 ms against 3.2 s, n = 1024 in 0.17 s against
 * 8.9 s).  For a stored fit whose data are known unchanged.
 * Errors: as tbl_gp_fit_kernel; STC_EINVAL when npar is not the number of
 * hyperparameters these data and kernel have, or a value is not finite or
 * lies outside its bound (hyperparameters of other data). */
stc_status tbl_gp_fit_at(int n, int dim, const double *x, const double *y, const double *sy,
                         const tbl_gp_kernel *kernel, int npar, const double *par,
                         tbl_gp **out);

/* Posterior mean and standard deviation of the latent (noise-free)
 * function m + f at x[dim] (borrowed); sd includes the uncertainty of the
 * estimated mean (R&W eq. 2.42).  mean, sd: nullable; O(n) without sd,
 * O(n^2) with it.  Pure.  For n > 1024 the sd needs a scratch vector of n
 * doubles from malloc; if that fails *sd = NaN (the mean is still
 * returned).  An sd below about sf x 1e-8 is not resolved (cancellation)
 * and may read 0. */
void tbl_gp_predict(const tbl_gp *g, const double *x, double *mean, double *sd);

/* Leave-one-out mean and sd of y_i (i.e. including point i's noise c sy_i)
 * with the hyperparameters held fixed and the GLS mean re-estimated without
 * point i: the closed form of R&W eq. 5.12 extended to the estimated mean
 * (Dubrule 1983).  mean, sd: caller-owned arrays [n]. */
void tbl_gp_loo(const tbl_gp *g, double *mean, double *sd);

/* Copies the fit summary into *info (caller-owned). */
void tbl_gp_get_info(const tbl_gp *g, tbl_gp_info *info);

/* Frees the handle; sets *g = NULL.  NULL or *g == NULL is a no-op. */
void tbl_gp_destroy(tbl_gp **g);

#endif
