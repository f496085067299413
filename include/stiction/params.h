/* stiction — materials and geometry of one coated asperity, and the common
 * options every subcommand accepts.  Units: mm, N, MPa throughout.
 */
#ifndef STICTION_PARAMS_H
#define STICTION_PARAMS_H

#include <stdio.h>
#include "stiction/export.h"
#include "stiction/parse.h" /* the option parsers every subcommand uses */
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One isotropic elastic–perfectly plastic von Mises material. */
typedef struct stc_material {
    double E;  /* Young's modulus, MPa */
    double nu; /* Poisson's ratio, dimensionless, in (-1, 0.5) */
    double Y;  /* yield strength, MPa */
} stc_material;

/* The common options (docs/design.md §2.1): a substrate sphere of radius R
 * carrying a bonded coating of thickness t = (t/R) R.  Coating properties are
 * given relative to the substrate unless set explicitly.  The thickness may
 * be given in mm instead (t_mm): stc_params_resolve then sets t_over_R. */
typedef struct stc_params {
    double R;        /* substrate radius, mm; default 10 */
    double t_over_R; /* coating thickness / R; 0 = uncoated; default 0 */
    double t_mm;     /* coating thickness, mm, when t_mm_set; default 0 */
    int t_mm_set;    /* nonzero when t-mm was given (stc_params_set) */
    int t_over_R_set; /* nonzero when t-over-R was given (stc_params_set) */
    double E_su;     /* substrate Young's modulus, MPa; default 200000 */
    double E_ratio;  /* Eco/Esu; default 1 */
    double E_over_Y; /* E/Y of both layers (used unless Y_su/Y_co set); default 1000 */
    double Y_su;     /* substrate yield strength, MPa; 0 = E_su / E_over_Y */
    double Y_co;     /* coating yield strength, MPa; 0 = E_co / E_over_Y */
    double nu;       /* substrate Poisson ratio (and coating unless nu_co set); default 0.32 */
    double nu_co;    /* coating Poisson ratio (used when nu_co_set); default = nu */
    int nu_co_set;   /* nonzero when nu_co was given explicitly */
} stc_params;

/* Fill `p` with the defaults listed above. */
STC_API void stc_params_default(stc_params *p);

/* Set one common option from text, e.g. key "t-over-R", value "0.025".
 * Keys: R, t-over-R, t-mm, E-su, E-ratio, E-over-Y, Y-su, Y-co, nu, nu-co
 * (a leading "--" is accepted; '_' and '-' are interchangeable).
 * Returns STC_OK, STC_EINVAL with a message naming key, value and the valid
 * range, or STC_EUNSUPPORTED (no message) when the key is not a common one. */
STC_API stc_status stc_params_set(stc_params *p, const char *key, const char *value);

/* Name of the i-th common key (i = 0, 1, ...), NULL past the last: for
 * listings and for suggesting the closest key to a mistyped one. */
STC_API const char *stc_params_key(int i);

/* Check the whole set for consistency (ranges that involve several keys). */
STC_API stc_status stc_params_validate(const stc_params *p);

/* Finish a set given through stc_params_set, once every key is in: a
 * thickness given as t-mm becomes t_over_R = t_mm / R with the final R
 * (refused when t-over-R was given too, or when t/R would reach 1); one
 * yield strength without the other is refused where the set describes two
 * layers (t > 0, E-ratio != 1, nu-co or Y-co given), since the other would
 * come from E-over-Y unasked; then stc_params_validate.  STC_OK or
 * STC_EINVAL naming the keys. */
STC_API stc_status stc_params_resolve(stc_params *p);

/* Resolved layer materials (substrate, coating).  Either pointer may be NULL. */
STC_API void stc_params_materials(const stc_params *p, stc_material *su, stc_material *co);

/* Coating thickness t in mm. */
STC_API double stc_params_t(const stc_params *p);

#ifdef __cplusplus
}
#endif
#endif
