/* Closed-form fits for a hard-coated sphere (docs/design.md §6.3): the
 * critical thickness ratios and the yield-inception load and area of the
 * coated sphere under slip (Goltsberg, Etsion & Davidi 2011; Chen,
 * Goltsberg & Etsion 2016) and stick (Ronen, Goltsberg & Etsion 2017).
 * Apart from formulas.c because stc_coated_eval takes the model's
 * parameters (params.c), whose validation uses formulas.c's critical
 * scales: together the two files called each other.
 *
 * Every function here is pure: no allocation, no globals, thread-safe. */
#include <math.h>
#include <string.h>

#include "stiction/formulas.h"
#include "stc_check.h"

/* Ranges the fits were made for (sources in stc_fit_flag_text). */
#define SLIP_E_RATIO_MAX 4.5   /* Goltsberg et al. 2011; Chen et al. 2016 */
#define STICK_E_RATIO_MAX 10.0 /* thesis §3.2.2 applies Ronen's fits up to 10 */
#define STICK_TR_MAX 0.05      /* thesis §3.2.2: 0.002 <= t/R <= 0.05 */

/* Pc_co/Pc_su, corrected form (docs/design.md §6.3).  The thesis (eq. 3.6) prints
 * [(1 − ν_co²)/(1 − ν_su²)] unsquared and (Eco/Esu)²; but Pc ∝ Cv³ Y³
 * (1 − ν²)² / E² (eq. 3.4), so the ratio carries the square of the ν term
 * and (Esu/Eco)².  Only this form turns eq. 3.5 into the same-ν form eq.
 * 3.7 (checked in tests/test_formulas.c). */
double stc_pc_ratio(const stc_material *su, const stc_material *co)
{
    const double cv = (1.234 + 1.256 * co->nu) / (1.234 + 1.256 * su->nu);
    const double qn = (1.0 - co->nu * co->nu) / (1.0 - su->nu * su->nu);
    const double y = co->Y / su->Y, e = su->E / co->E;
    return cv * cv * cv * qn * qn * y * y * y * e * e;
}

/* Goltsberg, Etsion & Davidi (2011), thesis eq. 3.5 (slip). */
double stc_tR_p(const stc_material *su, const stc_material *co)
{
    return 2.824 * pow(su->E / su->Y, -1.014) * pow(stc_pc_ratio(su, co), 0.536);
}

/* Chen, Goltsberg & Etsion (2016), thesis eq. 3.7: the same-ν form. */
double stc_tR_p_same_nu(const stc_material *su, const stc_material *co)
{
    return 2.824 * pow(co->E / su->E, 0.536) * pow(co->E / co->Y, -1.608) *
           pow(su->E / su->Y, 0.595);
}

/* Ronen, Goltsberg & Etsion (2017), thesis eq. 3.10 (stick).  One ν: we
 * pass the coating's.  NAN for ν <= 0, where ν^0.724 is undefined. */
double stc_tR_p_st(const stc_material *su, const stc_material *co, double nu)
{
    if (!(nu > 0.0)) return NAN;
    return 3.95 * pow(nu, 0.724) * pow(co->E / su->E, 0.39) * pow(co->Y / co->E, 1.41) *
           pow(su->Y / su->E, -0.45);
}

static void coated_slip(const stc_material *su, const stc_material *co, double tR,
                        stc_coated *c)
{
    const double er = co->E / su->E, ecy = co->E / co->Y, esy = su->E / su->Y;
    c->Pc_co_over_Pc_su = stc_pc_ratio(su, co);
    c->tR_p = stc_tR_p(su, co);
    /* Chen, Goltsberg & Etsion (2016), thesis eqs. 3.8, 3.9 */
    c->omega_c1_over_omega_c_co =
        1.0 + 3.78 * pow(tR, -1.29) * pow(er - 1.0, 0.811) * pow(ecy, -1.3);
    c->omega_c2_over_omega_c_co =
        0.25 * pow(tR, 1.34) * pow(er, -0.14) * ecy * ecy * pow(esy, -0.66);
    c->omega_c1_mm = c->omega_c1_over_omega_c_co * c->co.omega_c;
    c->omega_c2_mm = c->omega_c2_over_omega_c_co * c->co.omega_c;
    c->flags_slip = STC_FIT_OK;
    if (er > SLIP_E_RATIO_MAX) c->flags_slip |= STC_FIT_E_RATIO;
    if (tR <= c->tR_p) c->flags_slip |= STC_FIT_T_OVER_R;
    if (c->omega_c1_mm > c->omega_c2_mm) c->flags_slip |= STC_FIT_ORDER;
}

static void coated_stick(const stc_material *su, const stc_material *co, double tR,
                         stc_coated *c)
{
    const double em1 = co->E / su->E - 1.0, yec = co->Y / co->E, yes = su->Y / su->E;
    const double nu = co->nu, w = c->co.omega_c / c->su.omega_c;
    c->tR_p_st = stc_tR_p_st(su, co, nu);
    /* Ronen, Goltsberg & Etsion (2017), thesis eqs. 3.11–3.14; the first
     * factor of δc1 is Brizmer's stick δc/ωc of the coating (eq. 3.1). */
    c->delta_c1_over_omega_c_co = c->co.delta_c_stick_over_omega_c *
        (1.0 + 0.007 * pow(em1, 0.646) * pow(yec, 0.244) * pow(tR, -1.21));
    c->delta_c2_over_omega_c_co =
        pow(tR, 1.17) * pow(em1, -0.09) * pow(yec, -1.93) * pow(yes, 0.89);
    c->L_c2_over_P_c_co = pow(tR, 1.8) * pow(em1, -0.27) * pow(yec, -2.3) * pow(yes, 0.78);
    c->A_c2_st_over_A_c_co = pow(tR, 1.6) * pow(em1, -0.2) * pow(yec, -2.0) * pow(yes, 0.7);
    c->delta_c1_over_omega_c_su = c->delta_c1_over_omega_c_co * w;
    c->delta_c2_over_omega_c_su = c->delta_c2_over_omega_c_co * w;
    c->delta_c1_mm = c->delta_c1_over_omega_c_co * c->co.omega_c;
    c->delta_c2_mm = c->delta_c2_over_omega_c_co * c->co.omega_c;
    c->L_c2_N = c->L_c2_over_P_c_co * c->co.P_c;
    c->A_c2_st_mm2 = c->A_c2_st_over_A_c_co * c->co.A_c;
    c->flags_stick = STC_FIT_OK;
    if (em1 + 1.0 > STICK_E_RATIO_MAX) c->flags_stick |= STC_FIT_E_RATIO;
    if (!(tR > c->tR_p_st) || tR > STICK_TR_MAX) c->flags_stick |= STC_FIT_T_OVER_R;
    if (co->nu != su->nu || (c->co.flags & STC_FIT_NU)) c->flags_stick |= STC_FIT_NU;
    if (c->delta_c1_mm > c->delta_c2_mm) c->flags_stick |= STC_FIT_ORDER;
}

stc_status stc_coated_eval(const stc_params *p, stc_coated *out)
{
    stc_material su, co;
    STC_CHECK(p && out, STC_EINVAL, "stc_coated_eval: NULL pointer");
    STC_CALL(stc_params_validate(p));
    STC_CHECK(p->t_over_R > 0.0, STC_EUNSUPPORTED,
              "t-over-R = %g: the coated-sphere fits need a coating (t/R > 0)", p->t_over_R);
    STC_CHECK(p->E_ratio > 1.0, STC_EUNSUPPORTED,
              "E-ratio = %g: the coated-sphere fits are for a hard coating (Eco/Esu > 1)",
              p->E_ratio);
    memset(out, 0, sizeof *out);
    stc_params_materials(p, &su, &co);
    STC_CALL(stc_critical_eval(&su, p->R, &out->su));
    STC_CALL(stc_critical_eval(&co, p->R, &out->co));
    out->t_over_R = p->t_over_R;
    out->E_ratio = p->E_ratio;
    coated_slip(&su, &co, p->t_over_R, out);
    coated_stick(&su, &co, p->t_over_R, out);
    return STC_OK;
}

/* Ronen et al. (2017), thesis eqs. 3.15, 3.16: for δc1 < δ < δc2,
 * L/Lc2 = (δ/δc2)^1.25 and A_st/Ac2_st = δ/δc2. */
stc_status stc_coated_ep(const stc_coated *c, double delta_mm, double *L_N, double *A_mm2,
                         unsigned *flags)
{
    STC_CHECK(c && L_N && A_mm2, STC_EINVAL, "stc_coated_ep: NULL pointer");
    STC_CALL(stc_check_range("delta", delta_mm, 0.0, 1, INFINITY, 0));
    const double r = delta_mm / c->delta_c2_mm;
    *L_N = c->L_c2_N * pow(r, 1.25);
    *A_mm2 = c->A_c2_st_mm2 * r;
    if (flags) {
        *flags = STC_FIT_OK;
        if (!(delta_mm > c->delta_c1_mm && delta_mm < c->delta_c2_mm)) *flags |= STC_FIT_DELTA;
        if (c->delta_c1_mm > c->delta_c2_mm) *flags |= STC_FIT_ORDER;
    }
    return STC_OK;
}
