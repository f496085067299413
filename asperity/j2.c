/* Isotropic linear elasticity + von Mises (J2) perfect plasticity, small
 * strain: two closed-form return maps and their consistent (algorithmic)
 * tangents, with the hardening modulus H = 0 (perfect plasticity,
 * docs/design.md §2.1).
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
 * Newton quadratic with the remainder (linsolve.c: skew_correct, gmres).
 *
 * Exact integration: the closed-form solution of the elastic-perfectly
 * plastic von Mises law under a strain rate that is constant over the
 * increment (Krieg & Krieg, J. Pressure Vessel Technol. 99 (1977) 510).
 * The elastic part is the same straight path to the yield surface as
 * above; from there the unit deviator x = s / k turns on the sphere
 * towards ê = Δs / |Δs| along a great circle, tan(θ/2) decaying as
 * exp(-D / k) with D the remaining trial increment.  Exact for any
 * straight strain path, with no degenerate case and a smooth tangent
 * (derivation in exact()'s comment).  But a load increment's strain path
 * is curved, and there the midpoint rule is the more accurate one: 4-25x
 * smaller stress errors on turning paths (test_j2), and the 3D slip curve
 * to 60 ωc at 2 steps per node entry sits 0.5 % lower (docs/design.md
 * §3.4).  So the midpoint rule stays the default; this is the reference for
 * straight paths and an option (--return-map exact).
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
#include "stiction/asperity.h"

enum { NV = 6 };

void asp_j2_init(asp_j2 *m, const stc_material *mat)
{
    m->E = mat->E;
    m->nu = mat->nu;
    m->Y = mat->Y;
    m->mu = mat->E / (2.0 * (1.0 + mat->nu));
    m->lambda = mat->E * mat->nu / ((1.0 + mat->nu) * (1.0 - 2.0 * mat->nu));
    m->kappa = mat->E / (3.0 * (1.0 - 2.0 * mat->nu));
    m->map = ASP_RETURN_MIDPOINT;
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

/* Where the straight elastic path s_0 + β Δs, Δs = s_t - s_0, leaves the
 * yield surface |s| = k: the larger root β of the quadratic, at least 0
 * (s_0 on the surface and the increment loading it).  On return s holds
 * s_0 + β Δs and ds holds Δs; returns β. */
static double elastic_exit(double k, const double s0[NV], const double str[NV], double s[NV],
                           double ds[NV])
{
    double beta = 0.0;
    for (int a = 0; a < NV; a++) ds[a] = str[a] - s0[a];
    double n0 = sqrt(tdot(s0, s0)), A = tdot(ds, ds), B = tdot(s0, ds), C = n0 * n0 - k * k;
    if (A > 0.0) beta = fmax((-B + sqrt(fmax(B * B - A * C, 0.0))) / A, 0.0);
    for (int a = 0; a < NV; a++) s[a] = s0[a] + beta * ds[a];
    return beta;
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
    double k = sqrt(2.0 / 3.0) * m->Y, s0[NV], ds[NV], mm[NV], nh[NV];
    double beta = elastic_exit(k, old->s, str, s0, ds); /* s0: where the path leaves */
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

/* Exact return for the trial deviator str from old->s (Krieg & Krieg
 * 1977).  s_a = s_0 + β Δs is where the straight elastic path leaves the
 * surface, d = (1 - β) Δs the rest, D = |d|, ê = d / D, x_0 = s_a / |s_a|,
 * c = x_0·ê = cos θ_0 (≥ 0: the path leaves the surface there), u =
 * tan²(θ_0/2) = (1 - c) / (1 + c), E = exp(-D / k).  The flow
 * dx/dτ = (d - (x·d) x) / k keeps x in the plane of x_0 and ê with
 * tan(θ/2) = tan(θ_0/2) E^τ, so (derived for this code)
 *   s_1 = k (α ê + ρ x_0),  α = (1 - E)(1 + u E) / (1 + u E²),
 *                           ρ = E (1 + u) / (1 + u E²),
 * and the plastic work per k, ∫ x·d dτ = k ln(sin θ_0 / sin θ_1) = D +
 * k ln((1 + u E²) / (1 + u)), gives ε̄_p.  Tangent: s_1 = F(s_a, d) with
 * ds_a = dβ Δs + β dΔs, dd = -dβ Δs + (1 - β) dΔs.  Since F follows the
 * flow, F_sa f = F_d Δs for f = Δs - (s_a·Δs / k²) s_a, so the dβ terms
 * leave (s_a·Δs / k²) F_sa s_a dβ, which is zero because F depends on s_a
 * only through its direction: ds_1 = (β F_sa + (1 - β) F_d) dΔs, with no
 * 1 / (s_a·Δs) where the path grazes the surface.  Returns 0 (radial
 * return by the caller) only for a vanishing increment or start. */
static int exact(const asp_j2 *m, const double str[NV], const asp_qp_state *old,
                 asp_qp_state *upd, double sig[NV], double p, double *D, double *Dp)
{
    double k = sqrt(2.0 / 3.0) * m->Y, sa[NV], ds[NV];
    double beta = elastic_exit(k, old->s, str, sa, ds), A = tdot(ds, ds);
    /* (β > 1 only by rounding, and then dn < 0: the radial return) */
    double na = dev_norm(sa), dn = (1.0 - beta) * sqrt(A);
    if (!(na > 0.0) || !(dn > 1e-14 * k)) return 0;
    double x0[NV], e[NV];
    for (int a = 0; a < NV; a++) x0[a] = sa[a] / na, e[a] = ds[a] / sqrt(A);
    double c = tdot(x0, e);
    if (c < -0.5) return 0; /* not reached: c ≥ 0 up to rounding */
    double u = (1.0 - c) / (1.0 + c), E = exp(-dn / k), om = -expm1(-dn / k);
    double v = u * E * E, q = 1.0 + v;
    double al = om * (1.0 + u * E) / q, rho = E * (1.0 + u) / q;
    double s1[NV];
    for (int a = 0; a < NV; a++) s1[a] = k * (al * e[a] + rho * x0[a]);
    for (int a = 0; a < NV; a++) {
        double de = (str[a] - s1[a]) / (2.0 * m->mu);
        sig[a] = s1[a] + (a < 3 ? p : 0.0);
        upd->eps_p[a] += (a < 3 ? 1.0 : 2.0) * de;
        upd->s[a] = s1[a];
    }
    /* |Δε_p| integrated along the path (tensor norm) */
    double dgam = (dn + k * log(q / (1.0 + u))) / (2.0 * m->mu);
    upd->epbar += sqrt(2.0 / 3.0) * fmax(dgam, 0.0);
    if (!D) return 1;
    /* scalar derivatives in u and E, then in c (du/dc = -(1 + u)² / 2)
     * and D (dE/dD = -E / k) */
    double q2 = q * q, duc = -0.5 * (1.0 + u) * (1.0 + u);
    double al_u = om * om * E / q2, rho_u = E * (1.0 - E * E) / q2;
    double al_E = ((u - 1.0 - 2.0 * u * E) * q - om * (1.0 + u * E) * 2.0 * u * E) / q2;
    double rho_E = (1.0 + u) * (1.0 - v) / q2;
    double al_c = al_u * duc, rho_c = rho_u * duc;
    double al_D = -al_E * E / k, rho_D = -rho_E * E / k;
    /* J = ∂s_1/∂s_t = β F_sa + (1 - β) F_d, with (a ⊗ b) acting as a (b·v):
     *   F_sa = (k / |s_a|) [g ⊗ (ê - c x_0) + ρ (I - x_0 ⊗ x_0)],
     *   F_d  = k [g ⊗ (x_0 - c ê) / D + h ⊗ ê + (α / D) (I - ê ⊗ ê)],
     * g = α_c ê + ρ_c x_0, h = α_D ê + ρ_D x_0 */
    double fa = beta * k / na, fd = (1.0 - beta) * k, J[NV * NV];
    for (int a = 0; a < NV; a++) {
        double g = al_c * e[a] + rho_c * x0[a], h = al_D * e[a] + rho_D * x0[a];
        for (int b = 0; b < NV; b++) {
            double w = b < 3 ? 1.0 : 2.0; /* the tensor dot's shear weight */
            double ja = g * (e[b] - c * x0[b]) * w + rho * ((a == b) - x0[a] * x0[b] * w);
            double jd = g * (x0[b] - c * e[b]) * w / dn + h * e[b] * w +
                        al / dn * ((a == b) - e[a] * e[b] * w);
            J[a * NV + b] = fa * ja + fd * jd;
        }
    }
    /* D = κ 1⊗1 + J ∂s_t/∂ε, ∂s_t/∂ε = 2μ I_dev (μ on the engineering shears) */
    double S[NV * NV] = {0};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) S[a * NV + b] = 2.0 * m->mu * ((a == b) - 1.0 / 3.0);
    for (int a = 3; a < NV; a++) S[a * NV + a] = m->mu;
    for (int a = 0; a < NV; a++)
        for (int b = 0; b < NV; b++) {
            double v2 = (a < 3 && b < 3) ? m->kappa : 0.0;
            for (int l = 0; l < NV; l++) v2 += J[a * NV + l] * S[l * NV + b];
            D[a * NV + b] = v2;
        }
    /* SPD part for the factorization: the radial return's tangent at the
     * same trial, exact for a proportional increment from the surface to
     * first order in D / k */
    if (Dp) {
        double n1[NV];
        for (int a = 0; a < NV; a++) n1[a] = s1[a] / k;
        tangent(m, fmax(k / dev_norm(str), 0.01), 1.0, n1, Dp);
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

    if (m->map == ASP_RETURN_MIDPOINT && midpoint(m, s, old, upd, sig, p, D, D ? Dp : NULL))
        return 1;
    if (m->map == ASP_RETURN_EXACT && exact(m, s, old, upd, sig, p, D, D ? Dp : NULL)) return 1;
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
