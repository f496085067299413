/* Common asperity parameters: defaults, text parsing with range checks
 * (the parsers themselves are the core's, core/parse.c). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "stiction/formulas.h"
#include "stiction/params.h"
#include "stc_check.h"

void stc_params_default(stc_params *p)
{
    p->R = 10.0;
    p->t_over_R = 0.0;
    p->t_mm = 0.0;
    p->t_mm_set = 0;
    p->t_over_R_set = 0;
    p->E_su = 200000.0;
    p->E_ratio = 1.0;
    p->E_over_Y = 1000.0;
    p->Y_su = 0.0;
    p->Y_co = 0.0;
    p->nu = 0.32;
    p->nu_co = 0.32;
    p->nu_co_set = 0;
}

/* Table of the common keys: name, field, valid range. */
typedef struct {
    const char *key;
    size_t offset;
    double lo, hi;
    int lo_incl, hi_incl;
} param_key;

#define PK(k, f, lo, li, hi, hiincl) {k, offsetof(stc_params, f), lo, hi, li, hiincl}
static const param_key param_keys[] = {
    PK("R", R, 0.0, 0, INFINITY, 0),
    /* t/R < 1: the coating must be thinner than the sphere is large */
    PK("t-over-R", t_over_R, 0.0, 1, 1.0, 0),
    /* the same thickness in mm (t/R < 1 is checked with R, in resolve) */
    PK("t-mm", t_mm, 0.0, 1, INFINITY, 0),
    PK("E-su", E_su, 0.0, 0, INFINITY, 0),
    PK("E-ratio", E_ratio, 0.0, 0, INFINITY, 0),
    /* E/Y > 1: yield strain below 100 % (small-strain model) */
    PK("E-over-Y", E_over_Y, 1.0, 0, INFINITY, 0),
    PK("Y-su", Y_su, 0.0, 0, INFINITY, 0),
    PK("Y-co", Y_co, 0.0, 0, INFINITY, 0),
    /* thermodynamic bounds of an isotropic solid */
    PK("nu", nu, -1.0, 0, 0.5, 0),
    PK("nu-co", nu_co, -1.0, 0, 0.5, 0),
};
#undef PK

const char *stc_params_key(int i)
{
    return i >= 0 && (size_t)i < sizeof param_keys / sizeof *param_keys ? param_keys[i].key : NULL;
}

static void describe_range(const param_key *pk, char *buf, size_t n)
{
    if (isinf(pk->hi))
        snprintf(buf, n, "%s %g", pk->lo_incl ? ">=" : ">", pk->lo);
    else
        snprintf(buf, n, "in %c%g, %g%c", pk->lo_incl ? '[' : '(', pk->lo, pk->hi,
                 pk->hi_incl ? ']' : ')');
}

stc_status stc_params_set(stc_params *p, const char *key, const char *value)
{
    char k[64];
    stc_key_normalise(key, k, sizeof k);
    for (size_t i = 0; i < sizeof param_keys / sizeof *param_keys; i++) {
        const param_key *pk = &param_keys[i];
        if (strcmp(k, pk->key) != 0) continue;
        double v;
        if (stc_parse_double(k, value, &v) != STC_OK) {
            char range[96], msg[160];
            describe_range(pk, range, sizeof range);
            snprintf(msg, sizeof msg, "%s", stc_errmsg());
            return STC_FAIL(STC_EINVAL, "%s (valid: a number %s)", msg, range);
        }
        STC_CALL(stc_check_range(k, v, pk->lo, pk->lo_incl, pk->hi, pk->hi_incl));
        *(double *)((char *)p + pk->offset) = v;
        if (strcmp(k, "nu-co") == 0) p->nu_co_set = 1;
        if (strcmp(k, "t-mm") == 0) p->t_mm_set = 1;
        if (strcmp(k, "t-over-R") == 0) p->t_over_R_set = 1;
        return STC_OK;
    }
    return STC_EUNSUPPORTED;
}

void stc_params_materials(const stc_params *p, stc_material *su, stc_material *co)
{
    double E_co = p->E_su * p->E_ratio;
    if (su) {
        su->E = p->E_su;
        su->nu = p->nu;
        su->Y = p->Y_su > 0 ? p->Y_su : p->E_su / p->E_over_Y;
    }
    if (co) {
        co->E = E_co;
        co->nu = p->nu_co_set ? p->nu_co : p->nu;
        co->Y = p->Y_co > 0 ? p->Y_co : E_co / p->E_over_Y;
    }
}

double stc_params_t(const stc_params *p) { return p->t_over_R * p->R; }

stc_status stc_params_validate(const stc_params *p)
{
    for (size_t i = 0; i < sizeof param_keys / sizeof *param_keys; i++) {
        const param_key *pk = &param_keys[i];
        double v = *(const double *)((const char *)p + pk->offset);
        /* Y-su / Y-co: 0 means "derive from E-over-Y" */
        if ((strcmp(pk->key, "Y-su") == 0 || strcmp(pk->key, "Y-co") == 0) && v == 0.0)
            continue;
        STC_CALL(stc_check_range(pk->key, v, pk->lo, pk->lo_incl, pk->hi, pk->hi_incl));
    }
    stc_material su, co;
    stc_params_materials(p, &su, &co);
    STC_CHECK(isfinite(co.E) && co.E > 0.0, STC_EINVAL,
              "E-ratio = %g with E-su = %g MPa: the coating modulus %g MPa is not representable "
              "(valid: a finite, positive product)", p->E_ratio, p->E_su, co.E);
    STC_CHECK(su.Y < su.E, STC_EINVAL,
              "Y-su = %g MPa: must be below E-su = %g MPa", su.Y, su.E);
    STC_CHECK(co.Y < co.E, STC_EINVAL,
              "Y-co = %g MPa: must be below the coating modulus %g MPa", co.Y, co.E);
    /* Each range alone is open-ended, but together the values must give
     * critical scales (ωc, Pc, Ac) that are numbers: every model divides by
     * them (R = 1e308 mm passes its own check and overflows Pc). */
    const stc_material *layer[2] = {&su, &co};
    for (int i = 0; i < 2; i++) {
        stc_critical c;
        if (stc_critical_eval(layer[i], p->R, &c) != STC_OK) {
            char msg[512];
            snprintf(msg, sizeof msg, "%s", stc_errmsg());
            return STC_FAIL(STC_EINVAL, "%s: %s", i ? "coating (set by R, E-su x E-ratio, "
                            "E-over-Y or Y-co)" : "substrate (set by R, E-su, E-over-Y or Y-su)",
                            msg);
        }
    }
    return STC_OK;
}

/* One yield strength given and the other left to E-over-Y (a default the
 * user may never have chosen) is refused wherever two layers are described:
 * a coating (t > 0), coating properties of its own (E-ratio != 1, nu-co), or
 * Y-co itself.  A homogeneous sphere takes Y-su alone. */
static stc_status check_yield_pair(const stc_params *p)
{
    int su = p->Y_su > 0.0, co = p->Y_co > 0.0;
    if (su == co) return STC_OK;
    if (co)
        return STC_FAIL(STC_EINVAL, "Y-co = %g given without Y-su: the substrate's yield "
                        "strength would be E-su / E-over-Y = %g MPa; give the substrate's yield "
                        "strength too (Y-su, MPa), or neither and E-over-Y for both layers",
                        p->Y_co, p->E_su / p->E_over_Y);
    char why[64];
    if (p->t_over_R > 0.0) snprintf(why, sizeof why, "t = %g mm", stc_params_t(p));
    else if (p->E_ratio != 1.0) snprintf(why, sizeof why, "E-ratio = %g", p->E_ratio);
    else if (p->nu_co_set) snprintf(why, sizeof why, "nu-co = %g", p->nu_co);
    else return STC_OK; /* one layer: Y-su is all there is */
    return STC_FAIL(STC_EINVAL, "Y-su = %g given without Y-co, with a coating (%s): its yield "
                    "strength would be E_co / E-over-Y = %g MPa; give the coating's yield "
                    "strength too (Y-co, MPa), or neither and E-over-Y for both layers", p->Y_su,
                    why, p->E_su * p->E_ratio / p->E_over_Y);
}

stc_status stc_params_resolve(stc_params *p)
{
    if (p->t_mm_set) {
        STC_CHECK(!p->t_over_R_set, STC_EINVAL, "t-mm = %g conflicts with t-over-R = %g: give "
                  "the coating thickness once, in mm (t-mm) or as a share of R (t-over-R)",
                  p->t_mm, p->t_over_R);
        double tR = p->t_mm / p->R;
        STC_CHECK(tR < 1.0, STC_EINVAL, "t-mm = %g with R = %g mm: t/R = %g must be < 1 (a "
                  "coating thinner than the sphere's radius)", p->t_mm, p->R, tR);
        p->t_over_R = tR;
    }
    STC_CALL(check_yield_pair(p));
    return stc_params_validate(p);
}
