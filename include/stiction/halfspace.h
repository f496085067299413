/* stiction — elastic half-space contact by the boundary-element method.
 *
 * A square n × n grid of cells of side h (mm) on the surface z = 0 of a
 * homogeneous elastic half-space (E in MPa, ν); z points into the solid.
 * Every cell carries a uniform pressure p (MPa, compressive > 0) and a uniform
 * tangential traction qx (MPa, acting on the solid along +x).  The normal
 * surface displacement w (mm, into the solid) at the cell centres is
 *
 *     w = Kp * p + Kq * qx,
 *
 * with Kp the Boussinesq influence of a uniformly loaded rectangle (Love 1929;
 * Johnson, Contact Mechanics, 1985, §3.6) and Kq the Cerruti one: at z = 0 a
 * point force Qx at the origin moves the surface by w = (1 − 2ν) Qx x /
 * (4π G ρ²), i.e. INTO the solid ahead of the force (by Betti's theorem from the
 * Boussinesq radial displacement, which points toward a normal load; Johnson
 * eqs 3.19a and 2.19), integrated over the cell in closed form.  The
 * convolutions are done by FFT on a zero-padded 2n × 2n grid, so the grid is
 * not periodic.
 *
 * This is the reference for the elastic junction growth of the asperity's
 * tangential step (a rigid flat on an elastic sphere, full slip at τc, no
 * separation; docs/design.md §5.6) and the seed of the roadmap's
 * deterministic rough-surface contact.  Library code never prints.
 */
#ifndef STICTION_HALFSPACE_H
#define STICTION_HALFSPACE_H

#include "stiction/export.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct srf_halfspace srf_halfspace;

/* n in [8, 4096], h > 0, E > 0, ν in (−1, 0.5]. */
STC_API stc_status srf_halfspace_create(srf_halfspace **out, int n, double h, double E, double nu);
STC_API void srf_halfspace_destroy(srf_halfspace **hs);

/* w[n*n] (row i = x index) from p and qx (either may be NULL = zero). */
STC_API stc_status srf_halfspace_disp(srf_halfspace *hs, const double *p, const double *qx,
                                      double *w);

/* Contact with a rigid body at fixed approach: find p with gap
 * g = h0 + Kq * qx + Kp * p >= 0, p >= 0, p g = 0, except on cells with
 * bond[k] != 0, which stay in contact (g = 0) with p of either sign (no
 * separation).  h0[k] is the initial gap (negative = overlap).  p holds the
 * start on entry (any values; negative ones off the bond are set to 0) and the
 * answer on return.  Polonsky–Keer conjugate gradients (Wear 231 (1999) 206)
 * with the load step dropped (the approach is given).  Converged when the RMS
 * gap over the contact is below tol · max|h0| with no overlap left; otherwise
 * STC_ENOCONV after maxit iterations. */
STC_API stc_status srf_halfspace_contact(srf_halfspace *hs, const double *h0, const double *qx,
                                         const unsigned char *bond, double tol, int maxit,
                                         double *p, int *iterations);

/* Sphere (radius R) pressed by a rigid flat to δ without friction, then the
 * flat slides along +x: the tangential traction on the solid rises as
 * s τc over the current contact (s = 1/steps … 1, full slip), and every cell
 * that has touched stays in contact.  Grid: n cells across 2 span a_H
 * (a_H = sqrt(R δ)), centred on the axis. */
typedef struct srf_slide_result {
    double P0, A0;                /* preload: load N, contact area mm² */
    double P, A;                  /* at full slip */
    double a_lead, a_trail, a_side; /* contact extents along +x, −x, +y at full slip, mm
                                       (outer cell edges) */
    double tension;               /* total tensile (negative) load on bonded cells, N */
    double h;                     /* cell size, mm */
    int iterations;               /* CG iterations in all */
} srf_slide_result;

/* R, δ, E > 0; ν in (−1, 0.5]; τc >= 0; n in [16, 4096]; span in [1.05, 4];
 * steps in [1, 1000]. */
STC_API stc_status srf_halfspace_sphere_slide(double R, double delta, double E, double nu,
                                              double tau_c, int n, double span, int steps,
                                              srf_slide_result *out);

#ifdef __cplusplus
}
#endif
#endif
