/* stiction — closed-form contact relations (docs/design.md §6.1–§6.4).
 *
 * Every function is pure and thread-safe.  Units: mm, N, MPa.  Each fit
 * reports whether its inputs lie inside the range the fit was made for
 * through an stc_fit_range flag word (0 = inside every range).
 */
#ifndef STICTION_FORMULAS_H
#define STICTION_FORMULAS_H

#include "stiction/export.h"
#include "stiction/params.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Out-of-range flags (bitwise OR). */
enum {
    STC_FIT_OK = 0,
    STC_FIT_E_RATIO = 1 << 0,   /* Eco/Esu outside the fit's range */
    STC_FIT_T_OVER_R = 1 << 1,  /* t/R outside the fit's range (e.g. below (t/R)_p_st) */
    STC_FIT_NU = 1 << 2,        /* Poisson ratio outside the fit's range */
    STC_FIT_E_OVER_Y = 1 << 3,  /* E/Y outside the fit's range */
    STC_FIT_DELTA = 1 << 4,     /* interference outside the fit's range */
    STC_FIT_ORDER = 1 << 5      /* delta_c1 > delta_c2: substrate yields first ("weakening") */
};

/* Describe the flags in words ("Eco/Esu outside the fit's range; ...").
 * Writes at most n bytes into buf (NUL-terminated); returns buf. */
STC_API const char *stc_fit_describe(unsigned flags, char *buf, int n);

/* Which family of fits a flag word belongs to: the same bit means a
 * different range for each family (e.g. Eco/Esu <= 4.5 for the slip fits). */
typedef enum stc_fit_family {
    STC_FITS_GENERIC = 0,  /* no range known: generic wording */
    STC_FITS_STICK_HOMOG,  /* stc_critical.flags: Brizmer et al. 2006 stick fits */
    STC_FITS_SLIP,         /* stc_coated.flags_slip: Goltsberg 2011, Chen 2016 */
    STC_FITS_STICK,        /* stc_coated.flags_stick: Ronen et al. 2017 */
    STC_FITS_EP,           /* stc_coated_ep flags: L/Lc2, A/Ac2 */
    STC_FITS_WSP           /* stc_wsp_mu flags */
} stc_fit_family;

/* One sentence naming the range (and its source) that flag `bit` of
 * family `fam` violates.  Returns a static string; thread-safe. */
STC_API const char *stc_fit_flag_text(stc_fit_family fam, unsigned bit);

/* stc_fit_describe with the family's wording: the set bits' sentences
 * joined by "; " into buf (at most n bytes, NUL-terminated); returns buf. */
STC_API const char *stc_fit_describe_family(stc_fit_family fam, unsigned flags, char *buf, int n);

/* --- Hertz: elastic sphere on a rigid flat (docs/design.md §6.1) --- */
typedef struct stc_hertz {
    double E_star; /* E/(1-ν²), MPa */
    double P;      /* load, N */
    double a;      /* contact radius, mm */
    double p0;     /* peak pressure, MPa */
    double A;      /* contact area π a², mm² */
} stc_hertz;
STC_API stc_status stc_hertz_eval(const stc_material *m, double R, double delta, stc_hertz *out);

/* --- Yield inception of a homogeneous sphere (docs/design.md §6.1–§6.2) --- */
typedef struct stc_critical {
    double Cv;              /* 1.234 + 1.256 ν (Kogut & Etsion 2002; thesis §3.1.1.1) */
    double omega_c;         /* critical interference, mm (slip) */
    double P_c;             /* critical load, N (slip) */
    double A_c;             /* π ωc R, mm² */
    double delta_c_stick_over_omega_c; /* Brizmer et al. 2006; NAN where the fit is <= 0 */
    double L_c_stick_over_P_c;         /* Brizmer et al. 2006; NAN where the fit is <= 0 */
    double delta_c_stick;   /* mm */
    double L_c_stick;       /* N */
    double A_c_stick;       /* π δc R, mm² */
    unsigned flags;         /* STC_FITS_STICK_HOMOG: STC_FIT_NU */
} stc_critical;
STC_API stc_status stc_critical_eval(const stc_material *m, double R, stc_critical *out);

/* Brizmer et al. 2006 stick ratios δc/ωc and Lc/Pc alone; NAN where the fit
 * is not positive (ν below about 0.07 and 0.12 respectively). */
STC_API double stc_brizmer_delta_ratio(double nu);
STC_API double stc_brizmer_load_ratio(double nu);

/* --- Coated sphere fits (docs/design.md §6.3) --- */
typedef struct stc_coated {
    /* slip: Goltsberg, Etsion & Davidi 2011; Chen, Goltsberg & Etsion 2016 */
    double Pc_co_over_Pc_su;        /* corrected form, docs/design.md §6.3 */
    double tR_p;                    /* (t/R)_p */
    double omega_c1_over_omega_c_co;
    double omega_c2_over_omega_c_co;
    double omega_c1_mm, omega_c2_mm;
    unsigned flags_slip;
    /* stick: Ronen, Goltsberg & Etsion 2017 */
    double tR_p_st;                 /* (t/R)_p_st */
    double delta_c1_over_omega_c_co, delta_c2_over_omega_c_co;
    double delta_c1_over_omega_c_su, delta_c2_over_omega_c_su;
    double delta_c1_mm, delta_c2_mm;
    double L_c2_over_P_c_co, L_c2_N;
    double A_c2_st_over_A_c_co, A_c2_st_mm2;
    unsigned flags_stick;
    stc_critical su, co;            /* the layers' homogeneous values */
    double t_over_R, E_ratio;       /* the inputs the fits were evaluated at */
} stc_coated;
/* Requires t/R > 0 and Eco/Esu > 1 (the stick fits contain (Eco/Esu - 1)
 * raised to negative powers): otherwise returns STC_EUNSUPPORTED with a
 * message saying why the coated fits do not apply (callers report "not
 * applicable", not an error).  STC_EINVAL for invalid parameters. */
STC_API stc_status stc_coated_eval(const stc_params *p, stc_coated *out);

/* The pieces of stc_coated_eval usable without a coating thickness (e.g. to
 * choose one).  Materials are not checked here; pass validated ones. */
/* Pc_co/Pc_su, corrected */
STC_API double stc_pc_ratio(const stc_material *su, const stc_material *co);
/* Goltsberg 2011, eq. 3.5 */
STC_API double stc_tR_p(const stc_material *su, const stc_material *co);
/* Chen 2016, eq. 3.7 */
STC_API double stc_tR_p_same_nu(const stc_material *su, const stc_material *co);
/* Ronen 2017 */
STC_API double stc_tR_p_st(const stc_material *su, const stc_material *co, double nu);

/* Elastic–plastic stick relations for δc1 < δ < δc2 (Ronen et al. 2017):
 * L/Lc2 = (δ/δc2)^1.25, A/Ac2 = δ/δc2.  flags gets STC_FIT_DELTA when δ is
 * outside (δc1, δc2). */
STC_API stc_status stc_coated_ep(const stc_coated *c, double delta_mm, double *L_N, double *A_mm2,
                                 unsigned *flags);

/* --- Wu, Shi & Polycarpou 2012: μs = 0.3 coth(0.57 (ω/ωc)^0.41) ---
 * Returns NAN (and STC_FIT_DELTA) for ω/ωc <= 0 or not finite; flags
 * (nullable) gets STC_FIT_DELTA outside the preloads 0.5–72 of the paper. */
STC_API double stc_wsp_mu(double omega_over_omega_c, unsigned *flags);

#ifdef __cplusplus
}
#endif
#endif
