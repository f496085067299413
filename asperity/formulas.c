/* Closed-form contact relations of docs/design.md §6.1–§6.4: Hertz, yield
 * inception of a homogeneous sphere (slip and stick) and the
 * Wu–Shi–Polycarpou friction fit; the published fits for a hard-coated
 * sphere are in coated.c.
 *
 * Every function here is pure: no allocation, no globals, thread-safe.
 * Each fit reports in a flag word whether its inputs lie inside the range it
 * was fitted over; stc_fit_flag_text() says which range in words. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stiction/formulas.h"
#include "stc_check.h"

/* Ranges the fits were made for (sources in stc_fit_flag_text). */
#define BRIZMER_NU_MIN 0.2     /* Brizmer et al. 2006 as summarised in thesis §3.1.1.1 */
#define BRIZMER_NU_MAX 0.5
#define WSP_W_MIN 0.5          /* preloads of Wu, Shi & Polycarpou 2012 (docs/design.md §6.4) */
#define WSP_W_MAX 72.0

/* ---- flag words ------------------------------------------------------- */

const char *stc_fit_flag_text(stc_fit_family fam, unsigned bit)
{
    switch (fam) {
    case STC_FITS_GENERIC:
        break;
    case STC_FITS_STICK_HOMOG:
        if (bit == STC_FIT_NU)
            return "nu outside [0.2, 0.5], the ductile range of the Brizmer et al. (2006) "
                   "stick fits (values <= 0 are not reported)";
        break;
    case STC_FITS_SLIP:
        if (bit == STC_FIT_E_RATIO)
            return "Eco/Esu > 4.5: the slip fits were made for 1 <= Eco/Esu <= 4.5 "
                   "(Goltsberg et al. 2011; Chen et al. 2016)";
        if (bit == STC_FIT_T_OVER_R)
            return "t/R <= (t/R)_p: omega_c1, omega_c2 hold for t/R > (t/R)_p; below it the "
                   "substrate yields first (Chen et al. 2016)";
        if (bit == STC_FIT_ORDER)
            return "omega_c1 > omega_c2: the substrate yields before the coating";
        break;
    case STC_FITS_STICK:
        if (bit == STC_FIT_E_RATIO)
            return "Eco/Esu > 10: beyond 2 <= Eco/Esu <= 10, the range over which the thesis "
                   "applies the Ronen et al. (2017) fits";
        if (bit == STC_FIT_T_OVER_R)
            return "t/R outside ((t/R)_p_st, 0.05]: the Ronen et al. (2017) stick fits hold "
                   "for t/R > (t/R)_p_st; the thesis uses them up to t/R = 0.05";
        if (bit == STC_FIT_NU)
            return "nu_co != nu_su or nu outside [0.2, 0.5]: the Ronen et al. (2017) fits "
                   "take one Poisson ratio (we use the coating's)";
        if (bit == STC_FIT_ORDER)
            return "delta_c1 > delta_c2: the substrate yields first (\"weakening effect\", "
                   "thesis Fig. 4.7)";
        break;
    case STC_FITS_EP:
        if (bit == STC_FIT_DELTA)
            return "delta outside (delta_c1, delta_c2): L/Lc2 and A/Ac2 were fitted for "
                   "delta_c1 < delta < delta_c2 (Ronen et al. 2017)";
        if (bit == STC_FIT_ORDER)
            return "delta_c1 > delta_c2: the elastic-plastic range is empty";
        break;
    case STC_FITS_WSP:
        if (bit == STC_FIT_DELTA)
            return "omega/omega_c outside [0.5, 72], the preloads Wu, Shi & Polycarpou (2012) "
                   "report (docs/design.md §6.4); mu_s is undefined for omega <= 0";
        if (bit == STC_FIT_E_RATIO)
            return "coated input: the WSP fit is for a homogeneous sphere; the value is the "
                   "uncoated substrate's";
        break;
    }
    /* generic wording for bits a family does not define specially */
    switch (bit) {
    case STC_FIT_E_RATIO: return "Eco/Esu outside the fit's range";
    case STC_FIT_T_OVER_R: return "t/R outside the fit's range";
    case STC_FIT_NU: return "Poisson ratio outside the fit's range";
    case STC_FIT_E_OVER_Y: return "E/Y outside the fit's range";
    case STC_FIT_DELTA: return "interference outside the fit's range";
    case STC_FIT_ORDER: return "delta_c1 > delta_c2: the substrate yields first (\"weakening\")";
    default: return "unknown flag";
    }
}

const char *stc_fit_describe_family(stc_fit_family fam, unsigned flags, char *buf, int n)
{
    int used = 0;
    if (n <= 0) return buf;
    buf[0] = '\0';
    for (unsigned bit = 1; bit <= STC_FIT_ORDER && used < n; bit <<= 1) {
        if (!(flags & bit)) continue;
        int w = snprintf(buf + used, (size_t)(n - used), "%s%s", used ? "; " : "",
                         stc_fit_flag_text(fam, bit));
        if (w < 0) break;
        used += w;
    }
    return buf;
}

const char *stc_fit_describe(unsigned flags, char *buf, int n)
{
    /* no family: every bit gets its generic text */
    return stc_fit_describe_family(STC_FITS_GENERIC, flags, buf, n);
}

/* ---- input checks ----------------------------------------------------- */

static stc_status check_material(const stc_material *m)
{
    STC_CHECK(m, STC_EINVAL, "material: NULL pointer");
    STC_CALL(stc_check_range("E", m->E, 0.0, 0, INFINITY, 0));
    STC_CALL(stc_check_range("Y", m->Y, 0.0, 0, m->E, 0));
    STC_CALL(stc_check_range("nu", m->nu, -1.0, 0, 0.5, 0));
    return STC_OK;
}

/* ---- Hertz ------------------------------------------------------------ */

/* Hertz (1882) for an elastic sphere on a rigid flat, e.g. Johnson,
 * Contact Mechanics (1985) §4.2: P = (4/3) E* R^½ δ^{3/2}, a = (Rδ)^½,
 * p0 = 3P/(2πa²) = 2E* a/(πR) (the second form is finite at δ = 0). */
stc_status stc_hertz_eval(const stc_material *m, double R, double delta, stc_hertz *out)
{
    STC_CALL(check_material(m));
    STC_CALL(stc_check_range("R", R, 0.0, 0, INFINITY, 0));
    STC_CALL(stc_check_range("delta", delta, 0.0, 1, INFINITY, 0));
    const double Es = m->E / (1.0 - m->nu * m->nu);
    out->E_star = Es;
    out->a = sqrt(R * delta);
    out->P = 4.0 / 3.0 * Es * sqrt(R) * delta * sqrt(delta);
    out->p0 = 2.0 * Es * out->a / (M_PI * R);
    out->A = M_PI * out->a * out->a;
    return STC_OK;
}

/* ---- homogeneous yield inception -------------------------------------- */

/* Brizmer, Kligerman & Etsion (2006), stick: δc/ωc and Lc/Pc (thesis eqs.
 * 3.1, 3.2).  Both fits turn negative for small ν (below about 0.07 and
 * 0.12): there they mean nothing and we return NAN. */
static double positive_or_nan(double v) { return v > 0.0 ? v : NAN; }

double stc_brizmer_delta_ratio(double nu)
{
    return positive_or_nan(6.82 * nu - 7.83 * (nu * nu + 0.0586));
}

double stc_brizmer_load_ratio(double nu)
{
    return positive_or_nan(8.88 * nu - 10.13 * (nu * nu + 0.089));
}

stc_status stc_critical_eval(const stc_material *m, double R, stc_critical *out)
{
    STC_CALL(check_material(m));
    STC_CALL(stc_check_range("R", R, 0.0, 0, INFINITY, 0));
    const double nu = m->nu, q = 1.0 - nu * nu, YE = m->Y / m->E;
    /* Kogut & Etsion (2002) fit of the maximum dimensionless contact
     * pressure at yield inception (slip). */
    out->Cv = 1.234 + 1.256 * nu;
    /* Chang, Etsion & Bogy (1987) with the Kogut–Etsion Cv (thesis eq. 3.3) */
    const double s = out->Cv * M_PI * q / 2.0 * YE;
    out->omega_c = s * s * R;
    /* thesis eq. 3.4: Pc = (π³Y/6) Cv³ [R(1 − ν²)(Y/E)]² */
    const double r = R * q * YE;
    out->P_c = pow(M_PI, 3) * m->Y / 6.0 * pow(out->Cv, 3) * r * r;
    out->A_c = M_PI * out->omega_c * R;
    /* every model divides by these scales: they must be numbers */
    STC_CHECK(isfinite(out->P_c) && out->P_c > 0.0 && isfinite(out->A_c) && out->A_c > 0.0 &&
              out->omega_c > 0.0, STC_ERANGE,
              "R = %g mm, E = %g MPa, Y = %g MPa: the critical scales omega_c = %g mm, "
              "P_c = %g N, A_c = %g mm2 are not representable (valid: inputs that give finite, "
              "positive scales)", R, m->E, m->Y, out->omega_c, out->P_c, out->A_c);
    out->delta_c_stick_over_omega_c = stc_brizmer_delta_ratio(nu);
    out->L_c_stick_over_P_c = stc_brizmer_load_ratio(nu);
    out->delta_c_stick = out->delta_c_stick_over_omega_c * out->omega_c;
    out->L_c_stick = out->L_c_stick_over_P_c * out->P_c;
    out->A_c_stick = M_PI * out->delta_c_stick * R; /* thesis §3.1.1.1 */
    out->flags = (nu < BRIZMER_NU_MIN || nu > BRIZMER_NU_MAX) ? STC_FIT_NU : STC_FIT_OK;
    return STC_OK;
}

/* ---- Wu, Shi & Polycarpou (2012), thesis eq. 4.1 ---------------------- */

double stc_wsp_mu(double w, unsigned *flags)
{
    unsigned f = STC_FIT_OK;
    double mu = NAN;
    if (w > 0.0 && isfinite(w)) mu = 0.3 / tanh(0.57 * pow(w, 0.41)); /* coth = 1/tanh */
    if (!(w >= WSP_W_MIN && w <= WSP_W_MAX)) f |= STC_FIT_DELTA;
    if (flags) *flags = f;
    return mu;
}
