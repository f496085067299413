/* Nodal shear-limited stick law for the tangential step: a contact point
 * sticks until its frictional shear stress reaches τc, then slips at τc
 * (Wu, Shi & Polycarpou 2012; the thesis's "frictional shear stress limit"
 * σs/√3 with a nearly infinite Coulomb coefficient, §3.2.3.3).
 *
 * Regularisation: a tangential penalty spring per unit area, t = k_t (g - s),
 * with the slip s as internal variable — the friction analogue of J2 radial
 * return (Simo & Hughes, Computational Inelasticity, 1998, §1.2 and the
 * frictional return of Wriggers, Computational Contact Mechanics, 2006,
 * §5.2): elastic predictor t_tr = k_t (g - s_old), and if |t_tr| > τc the
 * return t = τc t_tr/|t_tr|, s_new = g - t/k_t.  Its consistent tangent is
 * symmetric (associated slip rule), so the stiffness stays SPD and CHOLMOD's
 * LLᵀ of the fixed pattern still applies; it only touches the node's own
 * 2x2 diagonal block, which is always in the pattern.  Why not exact
 * stick constraints: docs/design.md §4.1.
 */
#include <math.h>

#include "stc_check.h"
#include "tangential.h"

stc_status asp_fric_law_init(asp_fric_law *law, double tau_c, double E, double nu, double h,
                             double kappa)
{
    STC_CHECK(tau_c > 0.0 && isfinite(tau_c), STC_EINVAL,
              "tau-c = %g MPa: critical shear stress must be > 0", tau_c);
    STC_CHECK(E > 0.0 && isfinite(E), STC_EINVAL, "E = %g MPa: must be > 0", E);
    STC_CHECK(nu > -1.0 && nu < 0.5, STC_EINVAL, "nu = %g: must be in (-1, 0.5)", nu);
    STC_CHECK(h > 0.0 && isfinite(h), STC_EINVAL,
              "h = %g mm: contact element size must be > 0", h);
    STC_CHECK(kappa > 0.0 && isfinite(kappa), STC_EINVAL,
              "kappa = %g: penalty factor must be > 0 (default %g)", kappa,
              ASP_FRIC_KAPPA_DEFAULT);
    law->tau_c = tau_c;
    /* κ G / h: κ times the stiffness per unit area of a surface layer one
     * element thick, so the penalty dominates the body's local compliance */
    law->kt = kappa * E / (2.0 * (1.0 + nu)) / h;
    return STC_OK;
}

/* The stick (slip = 0) or slip branch of the return map at the trial
 * traction tr, |tr| = nt > 0 for slip. */
static int branch(const asp_fric_law *law, int slip, double area, const double g[2],
                  const double s_old[2], const double tr[2], double nt, double s_new[2],
                  double f[2], double K[4])
{
    double kt = law->kt, tc = law->tau_c;
    if (!slip) { /* stick: elastic predictor accepted */
        s_new[0] = s_old[0], s_new[1] = s_old[1];
        f[0] = area * tr[0], f[1] = area * tr[1];
        if (K) K[0] = K[3] = area * kt, K[1] = K[2] = 0.0;
        return ASP_FRIC_STICK;
    }
    /* slip: return onto |t| = τc along the trial direction */
    double n[2] = {tr[0] / nt, tr[1] / nt};
    double t[2] = {tc * n[0], tc * n[1]};
    s_new[0] = g[0] - t[0] / kt, s_new[1] = g[1] - t[1] / kt;
    f[0] = area * t[0], f[1] = area * t[1];
    if (K) {
        /* d(τc t_tr/|t_tr|)/dg = k_t τc/|t_tr| (I - n nᵀ): only rotation resists */
        double c = area * kt * tc / nt;
        K[0] = c * (1.0 - n[0] * n[0]);
        K[1] = K[2] = -c * n[0] * n[1];
        K[3] = c * (1.0 - n[1] * n[1]);
    }
    return ASP_FRIC_SLIP;
}

int asp_fric_update(const asp_fric_law *law, double area, const double g[2],
                    const double s_old[2], double s_new[2], double f[2], double K[4],
                    double *ratio)
{
    return asp_fric_update_as(law, 0, area, g, s_old, s_new, f, K, ratio);
}

int asp_fric_update_as(const asp_fric_law *law, int state, double area, const double g[2],
                       const double s_old[2], double s_new[2], double f[2], double K[4],
                       double *ratio)
{
    double kt = law->kt, tc = law->tau_c;
    double tr[2] = {kt * (g[0] - s_old[0]), kt * (g[1] - s_old[1])};
    double nt = hypot(tr[0], tr[1]);
    if (ratio) *ratio = nt / tc;
    int slip = state == ASP_FRIC_SLIP ? nt > 0.0 : state == ASP_FRIC_STICK ? 0 : !(nt <= tc);
    return branch(law, slip, area, g, s_old, tr, nt, s_new, f, K);
}
