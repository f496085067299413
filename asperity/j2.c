/* Isotropic linear elasticity + von Mises (J2) perfect plasticity, small
 * strain: the closed-form radial return and its consistent (algorithmic)
 * tangent.  Simo & Hughes, "Computational Inelasticity" (1998), box 3.1
 * (return map) and eq. 3.3.13 (consistent tangent), with the hardening
 * modulus H = 0 (perfect plasticity, SPEC §2).
 *
 * Voigt order [xx, yy, zz, xy, yz, zx], engineering shear strains
 * γ = 2ε.  Stress shear slots hold tensor components.  Hence:
 *   - the tensor norm of a deviatoric stress s is
 *     |s|² = s_xx² + s_yy² + s_zz² + 2 (s_xy² + s_yz² + s_zx²);
 *   - the plastic strain increment Δγ n is stored with its shear slots
 *     doubled (engineering);
 *   - in the tangent, the rank-one term -2μθ n⊗n uses tensor n for both
 *     indices (n : ε = Σ n_a ε_a over normal slots + Σ n_a γ_a over shear),
 *     and the deviatoric identity has 1/2 on the shear diagonal.
 * The same kernel serves the axisymmetric case with slots [rr, zz, θθ, rz,
 * 0, 0]: an isotropic law does not care which normal slot is the hoop one.
 *
 * Pure: no allocation, no globals; thread-safe.
 */
#include <math.h>
#include <string.h>

#include "fe.h"

enum { NV = 6 };

void asp_j2_init(asp_j2 *m, const stc_material *mat)
{
    m->E = mat->E;
    m->nu = mat->nu;
    m->Y = mat->Y;
    m->mu = mat->E / (2.0 * (1.0 + mat->nu));
    m->lambda = mat->E * mat->nu / ((1.0 + mat->nu) * (1.0 - 2.0 * mat->nu));
    m->kappa = mat->E / (3.0 * (1.0 - 2.0 * mat->nu));
}

/* Tensor norm of a deviatoric stress held in Voigt slots (shear counted
 * twice because σ_xy = σ_yx). */
static double dev_norm(const double s[NV])
{
    return sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

double asp_von_mises(const double sig[NV])
{
    double p = (sig[0] + sig[1] + sig[2]) / 3.0;
    double s[NV] = {sig[0] - p, sig[1] - p, sig[2] - p, sig[3], sig[4], sig[5]};
    return sqrt(1.5) * dev_norm(s);
}

/* D = κ 1⊗1 + 2μθ (I_dev - β n⊗n): θ = 1, β = 0 is the elastic tangent. */
static void tangent(const asp_j2 *m, double theta, double beta,
                    const double n[NV], double *D)
{
    double g = 2.0 * m->mu * theta;
    for (int a = 0; a < NV; a++)
        for (int b = 0; b < NV; b++) {
            double idev = 0.0;
            if (a < 3 && b < 3)
                idev = (a == b ? 1.0 : 0.0) - 1.0 / 3.0;
            else if (a == b)
                idev = 0.5; /* engineering shear: σ_xy = μ γ_xy */
            double vol = (a < 3 && b < 3) ? m->kappa : 0.0;
            D[a * NV + b] = vol + g * (idev - beta * n[a] * n[b]);
        }
}

int asp_j2_update(const asp_j2 *m, const double eps[NV], const asp_qp_state *old,
                  asp_qp_state *upd, double sig[NV], double *D)
{
    /* Elastic trial strain and stress */
    double ee[NV];
    for (int a = 0; a < NV; a++)
        ee[a] = eps[a] - old->eps_p[a];
    double tr = ee[0] + ee[1] + ee[2];
    double p = m->kappa * tr;
    double s[NV];
    for (int a = 0; a < 3; a++)
        s[a] = 2.0 * m->mu * (ee[a] - tr / 3.0);
    for (int a = 3; a < NV; a++)
        s[a] = m->mu * ee[a]; /* 2μ ε_xy = μ γ_xy */

    double snorm = dev_norm(s);
    double radius = sqrt(2.0 / 3.0) * m->Y; /* yield surface |s| = √(2/3) Y */
    if (upd != old)
        *upd = *old;
    if (snorm <= radius) {
        for (int a = 0; a < NV; a++)
            sig[a] = s[a] + (a < 3 ? p : 0.0);
        if (D) {
            double zero[NV] = {0};
            tangent(m, 1.0, 0.0, zero, D);
        }
        return 0;
    }

    /* Perfect plasticity: Δγ = (|s_tr| - √(2/3) Y) / 2μ, s = √(2/3) Y n */
    double n[NV], dgam = (snorm - radius) / (2.0 * m->mu);
    for (int a = 0; a < NV; a++) {
        n[a] = s[a] / snorm;
        sig[a] = radius * n[a] + (a < 3 ? p : 0.0);
        upd->eps_p[a] += (a < 3 ? 1.0 : 2.0) * dgam * n[a];
    }
    upd->epbar += sqrt(2.0 / 3.0) * dgam;
    /* Simo & Hughes eq. 3.3.13 with H = 0: θ = θ̄ = √(2/3) Y / |s_tr| */
    if (D)
        tangent(m, radius / snorm, 1.0, n, D);
    return 1;
}
