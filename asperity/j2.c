/* Isotropic linear elasticity + von Mises (J2) perfect plasticity, small
 * strain: two closed-form return maps and their consistent (algorithmic)
 * tangents, with the hardening modulus H = 0 (perfect plasticity, SPEC §2).
 *
 * Radial return (backward Euler): Simo & Hughes, "Computational
 * Inelasticity" (1998), box 3.1 and eq. 3.3.13.  First-order accurate in
 * the strain increment when the stress turns on the yield surface during
 * the increment, which is what happens under a growing contact: the load
 * at 60 ωc (slip, axisymmetric level 1) rose by 0.9 % from 4 to 16 load
 * steps per node entry, and the 3D level-0 load sat 2-3 % below the
 * axisymmetric one at its 2 steps per entry.
 *
 * Midpoint rule (the default): the generalized midpoint rule with α = 1/2,
 * second-order accurate (Ortiz & Popov, Int. J. Numer. Meth. Eng. 21
 * (1985) 1561; Simo & Hughes §3.6).  The plastic flow of the increment is
 * along the normal at the average of the start and end stresses, and the
 * end stress lies on the yield surface.  For von Mises this has a closed
 * form (derived for this code): with s_t the trial and s_0 the start
 * deviator, s_1 = s_t - x n̂ and n̂ ∥ s_0 + s_1 give n̂ = (s_0 + s_t) /
 * |s_0 + s_t|, and |s_1| = k = √(2/3) Y is a quadratic in x = 2μΔλ.  s_0 is where the
 * straight elastic path from the converged stress leaves the yield
 * surface (the converged stress itself when it is on the surface and the
 * increment loads it; a point further along after an elastic unloading,
 * so a reversal within one increment stays smooth).  Measured: the load
 * at 60 ωc moved by 0.13 % from 4 to 16 steps per node entry.  The
 * tangent is not symmetric (n̂ ⊗ ∂x/∂ε is not its transpose); the solver
 * factorizes an SPD approximation of it (asp_j2_update_pc's Dp) and keeps
 * Newton quadratic with the remainder (solver.c: skew_correct, gmres).
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
    m->midpoint = 1;
}

/* Tensor inner product of two deviators held in Voigt slots (shear
 * counted twice because σ_xy = σ_yx), and the norm. */
static double tdot(const double a[NV], const double b[NV])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] +
           2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

static double dev_norm(const double s[NV]) { return sqrt(tdot(s, s)); }

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

/* Midpoint return for the trial deviator str (outside the yield surface)
 * from old->s; p the pressure.  Returns 0, leaving the radial return to
 * the caller, in the degenerate cases: no real root, or an end stress
 * more than 60° from n̂ (a rotation by more than ~120° in one increment;
 * reached at the start of the shear ramp at 48 ωc, where the tangent's
 * 1 / (s_1·n̂) had turned Newton's step into NaN).  Tangent, with
 * M = ∂m/∂s_t, m = s_0 + s_t, P = I - n̂n̂, r = x/|m|, the elastic
 * fraction β (∂β from |s_0| = k) and s_1·ds_1 = 0 for ∂x:
 * ds_1 = [I - r P M - n̂ ⊗ w / (s_1·n̂)] ds_t, w = s_1 - r Mᵀ P s_1,
 * M = (1 + β) I - β Δs ⊗ s_0 / (s_0·Δs); checked against central
 * differences in test_j2. */
static int midpoint(const asp_j2 *m, const double str[NV], const asp_qp_state *old,
                    asp_qp_state *upd, double sig[NV], double p, double *D, double *Dp)
{
    double k = sqrt(2.0 / 3.0) * m->Y, s0[NV], ds[NV], mm[NV], nh[NV], beta = 0.0;
    memcpy(s0, old->s, sizeof s0);
    double n0 = sqrt(tdot(s0, s0));
    for (int a = 0; a < NV; a++) ds[a] = str[a] - s0[a];
    { /* elastic part: where the straight path s0 + β Δs leaves the yield surface */
        double A = tdot(ds, ds), B = tdot(s0, ds), C = n0 * n0 - k * k;
        if (A > 0.0) beta = fmax((-B + sqrt(fmax(B * B - A * C, 0.0))) / A, 0.0);
        for (int a = 0; a < NV; a++) s0[a] += beta * ds[a];
    }
    for (int a = 0; a < NV; a++) mm[a] = s0[a] + str[a];
    double mn = sqrt(tdot(mm, mm));
    if (mn <= 0.0) return 0;
    for (int a = 0; a < NV; a++) nh[a] = mm[a] / mn;
    double c = tdot(str, nh), q = tdot(str, str), disc = c * c - q + k * k;
    if (disc < 0.0) return 0;
    double x = c - sqrt(disc); /* 2μ Δλ */
    if (x < 0.0 || x >= mn) return 0;
    double s1[NV];
    for (int a = 0; a < NV; a++) s1[a] = str[a] - x * nh[a];
    /* the end stress more than 60° from the flow direction: a rotation the
     * midpoint does not follow (its tangent grows as 1 / (s_1·n̂)) */
    double sn = tdot(s1, nh);
    if (sn < 0.5 * k) return 0;
    for (int a = 0; a < NV; a++) {
        sig[a] = s1[a] + (a < 3 ? p : 0.0);
        upd->eps_p[a] += (a < 3 ? 1.0 : 2.0) * x / (2.0 * m->mu) * nh[a];
        upd->s[a] = s1[a];
    }
    upd->epbar += sqrt(2.0 / 3.0) * x / (2.0 * m->mu);
    if (D) {
        double r = x / mn, sd = tdot(s0, ds);
        double ps[NV], pd[NV], w[NV], nds = tdot(nh, ds);
        for (int a = 0; a < NV; a++) ps[a] = s1[a] - nh[a] * sn, pd[a] = ds[a] - nh[a] * nds;
        double g = beta > 0.0 && sd > 1e-12 * k * sqrt(tdot(ds, ds)) ? beta / sd : 0.0;
        double dps = tdot(ds, ps);
        for (int a = 0; a < NV; a++) w[a] = s1[a] - r * ((1.0 + beta) * ps[a] - g * s0[a] * dps);
        tangent(m, 1.0 - r * (1.0 + beta), 0.0, nh, D);
        /* SPD part for the factorization: the exact tangent of a
         * proportional increment, (1 - r(1 + β)) (I_dev - n̂n̂) deviatoric
         * (there β = k/|s_t| from the virgin state: the radial return's
         * θ), floored to stay positive definite */
        if (Dp) tangent(m, fmax(1.0 - r * (1.0 + beta), 0.01), 1.0, nh, Dp);
        for (int a = 0; a < NV; a++)
            for (int b = 0; b < NV; b++)
                D[a * NV + b] += 2.0 * m->mu * (r * (1.0 + beta) * nh[a] * nh[b] +
                                                r * g * pd[a] * s0[b] - nh[a] * w[b] / sn);
    }
    return 1;
}

int asp_j2_update(const asp_j2 *m, const double eps[NV], const asp_qp_state *old,
                  asp_qp_state *upd, double sig[NV], double *D)
{
    return asp_j2_update_pc(m, eps, old, upd, sig, D, NULL);
}

int asp_j2_update_pc(const asp_j2 *m, const double eps[NV], const asp_qp_state *old,
                     asp_qp_state *upd, double sig[NV], double *D, double *Dp)
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
            sig[a] = s[a] + (a < 3 ? p : 0.0), upd->s[a] = s[a];
        if (D) {
            double zero[NV] = {0};
            tangent(m, 1.0, 0.0, zero, D);
            if (Dp) memcpy(Dp, D, NV * NV * sizeof *D);
        }
        return 0;
    }

    if (m->midpoint && midpoint(m, s, old, upd, sig, p, D, D ? Dp : NULL)) return 1;
    /* Perfect plasticity: Δγ = (|s_tr| - √(2/3) Y) / 2μ, s = √(2/3) Y n */
    double n[NV], dgam = (snorm - radius) / (2.0 * m->mu);
    for (int a = 0; a < NV; a++) {
        n[a] = s[a] / snorm;
        sig[a] = radius * n[a] + (a < 3 ? p : 0.0);
        upd->s[a] = radius * n[a];
        upd->eps_p[a] += (a < 3 ? 1.0 : 2.0) * dgam * n[a];
    }
    upd->epbar += sqrt(2.0 / 3.0) * dgam;
    /* Simo & Hughes eq. 3.3.13 with H = 0: θ = θ̄ = √(2/3) Y / |s_tr| */
    if (D) {
        tangent(m, radius / snorm, 1.0, n, D);
        if (Dp) memcpy(Dp, D, NV * NV * sizeof *D);
    }
    return 1;
}
