/* stiction — single-asperity response models behind one interface
 * (an asperity model gives P, A, Qmax versus δ for a summit of radius R and
 * coating t).  Units: mm, N, MPa.
 *
 * A model is normalised the way the FE tables are: for a summit of radius R
 * it returns P/Pc, A/Ac, Qmax/Pc as functions of w = δ/ωc and t/R, where ωc,
 * Pc, Ac (docs/design.md §6.1) are those of the model's REFERENCE layer
 * evaluated at the summit's own radius R (ωc ∝ R, Pc ∝ R², Ac ∝ R²).  The
 * coating thickness t (mm) is fixed by the model, so every summit has its own
 * t/R.  asp_model_eval() scales back to N and mm².
 *
 * Models:
 *  - hertz:   elastic (Hertz) P and A only.  It has NO friction law: Qmax is
 *             NaN and ASP_NO_FRICTION is set (the shear limit over the Hertz
 *             area is not a friction law).
 *  - wsp:     P, A from the Kogut & Etsion (2002) elastic–plastic fits,
 *             Qmax = μs_WSP(ω/ωc) P (Wu, Shi & Polycarpou 2012).
 *  - data:    P/Pc, A/Ac, Q/Pc tabulated on a (w, t/R) grid and interpolated
 *             (the path the FE tables take); `sampled` builds one by sampling
 *             any other model.
 * The closed-form models ignore the coating: they use the properties of ONE
 * layer, the substrate by default (ASP_LAYER_SUBSTRATE) or the coating.
 * That is a stand-in until the FE tables exist, stated in every output.
 *
 * Thread safety: create/destroy are not thread-safe on the same handle;
 * asp_model_eval and every query are pure and may run concurrently on one
 * model (e.g. inside an OpenMP loop).
 */
#ifndef STICTION_MODEL_H
#define STICTION_MODEL_H

#include "stiction/export.h"
#include "stiction/params.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct asp_model asp_model;

/* Which layer's properties a closed-form model uses (and normalises by). */
typedef enum asp_layer { ASP_LAYER_SUBSTRATE = 0, ASP_LAYER_COATING = 1 } asp_layer;

/* Flags of one evaluation (bitwise OR). */
enum {
    ASP_IN_RANGE = 0,
    ASP_OUT_W_LOW = 1 << 0,     /* δ/ωc below the model's range (extrapolated) */
    ASP_OUT_W_HIGH = 1 << 1,    /* δ/ωc above the model's range (extrapolated) */
    ASP_OUT_T_OVER_R = 1 << 2,  /* t/R outside the model's range (clamped) */
    ASP_NO_FRICTION = 1 << 3    /* the model has no friction law: Qmax = NaN */
};

/* Response of one summit. */
typedef struct asp_response {
    double P;      /* normal load, N */
    double A;      /* real contact area, mm² */
    double Qmax;   /* static friction force (sliding inception), N; NaN without friction law */
    double w;      /* δ/ωc of the reference layer at this R */
    unsigned flags;
} asp_response;

/* What a model covers, in its normalised variables. */
typedef struct asp_model_range {
    double w_lo, w_hi;   /* δ/ωc range of the underlying fit / table */
    double tR_lo, tR_hi; /* t/R range; [0, inf] for models that ignore the coating */
    int coating_aware;   /* 0: t only changes the reported t/R, not the response */
    int has_friction;    /* 0: Qmax is NaN (hertz) */
} asp_model_range;

/* --- closed-form models --------------------------------------------------
 * p: materials (borrowed, copied; p->R and p->t_over_R are NOT used: R comes
 * per summit and t is t_mm).  t_mm >= 0.  Returns new in *out. */
STC_API stc_status asp_model_create_hertz(const stc_params *p, double t_mm, asp_layer layer,
                                          asp_model **out);
STC_API stc_status asp_model_create_wsp(const stc_params *p, double t_mm, asp_layer layer,
                                        asp_model **out);

/* --- tabulated models (the FE-table path) --------------------------------
 * Data on a grid of n_w values w[] (strictly increasing, > 0) times n_tR
 * values tR[] (strictly increasing, >= 0): arrays P_Pc, A_Ac, Q_Pc of shape
 * [n_tR][n_w], all > 0 (Q_Pc may be NULL: no friction law).  Interpolation:
 * monotone Steffen (1990) cubic in log P versus log w (exact for power laws
 * such as Hertz), linear in t/R between columns; below/above the w range a
 * power law continued from the first/last interval (flagged); t/R outside
 * the grid clamps to the nearest column (flagged).  With coating_aware == 0
 * (requires n_tR == 1) t/R is ignored.  The reference layer (normalisation)
 * is `ref` with Pc, ωc, Ac of docs/design.md §6.1.  All arrays are copied. */
typedef struct asp_model_data {
    const char *name;       /* e.g. "table:coated-TiN.h5" (copied) */
    stc_material ref;       /* reference layer for ωc, Pc, Ac */
    double t_mm;            /* coating thickness, mm */
    int n_w, n_tR;          /* grid sizes: n_w >= 3, n_tR >= 1 */
    const double *w;        /* [n_w] δ/ωc */
    const double *tR;       /* [n_tR] t/R */
    const double *P_Pc;     /* [n_tR][n_w] */
    const double *A_Ac;     /* [n_tR][n_w] */
    const double *Q_Pc;     /* [n_tR][n_w] or NULL */
    int coating_aware;
} asp_model_data;
STC_API stc_status asp_model_create_data(const asp_model_data *d, asp_model **out);

/* Sampling grid for asp_model_create_sampled. */
typedef struct asp_sample_params {
    double w_lo, w_hi; /* δ/ωc range, log-spaced; default 0.01 .. 200.  The sampled
                          model's range is this grid within the base's range. */
    int n_w;           /* default 121 */
    double tR_lo, tR_hi; /* t/R range (coating-aware bases only); default 0.002 .. 0.05 */
    int n_tR;          /* default 7 (1 for bases that ignore the coating) */
} asp_sample_params;
STC_API void asp_sample_params_default(asp_sample_params *sp);

/* Sample `base` (borrowed, may be destroyed afterwards) on the grid sp (NULL
 * = defaults) and return an interpolating data model (new in *out).  A jump
 * of the base (wsp at w = 1, 6, 110) is smeared over two grid intervals
 * each side (Steffen's node slopes use both neighbours).  The table-ready path: the same code reads FE tables. */
STC_API stc_status asp_model_create_sampled(const asp_model *base, const asp_sample_params *sp,
                                            asp_model **out);

STC_API void asp_model_destroy(asp_model **m);

/* --- evaluation ----------------------------------------------------------
 * Response of a summit of radius R (mm, > 0, finite) at interference δ (mm).
 * δ <= 0: zero P, A, Qmax (Qmax NaN for frictionless models), w <= 0. */
STC_API void asp_model_eval(const asp_model *m, double R, double delta, asp_response *out);

/* The normal load P (N) alone, equal to asp_model_eval's P (cheaper: no area,
 * no friction law).  0 for δ <= 0. */
STC_API double asp_model_load(const asp_model *m, double R, double delta);
/* P/Pc alone at w = δ/ωc (0 for w <= 0). */
STC_API double asp_model_load_norm(const asp_model *m, double w, double t_over_R);

/* Normalised response at w = δ/ωc and t/R (P/Pc, A/Ac, Q/Pc); returns flags. */
STC_API unsigned asp_model_eval_norm(const asp_model *m, double w, double t_over_R, double *P_Pc,
                                     double *A_Ac, double *Q_Pc);

/* --- queries -------------------------------------------------------------- */
STC_API const char *asp_model_name(const asp_model *m);       /* "hertz", "wsp", ... */
/* "substrate", "coating" or "reference" */
STC_API const char *asp_model_layer_name(const asp_model *m);
STC_API void asp_model_get_range(const asp_model *m, asp_model_range *out);
STC_API double asp_model_t(const asp_model *m);               /* coating thickness, mm */
STC_API const stc_material *asp_model_ref(const asp_model *m); /* reference layer (borrowed) */
STC_API double asp_model_omega_c(const asp_model *m, double R); /* mm, docs/design.md §6.1 */
STC_API double asp_model_P_c(const asp_model *m, double R);     /* N */
STC_API double asp_model_A_c(const asp_model *m, double R);     /* mm² */
STC_API double asp_model_E_star(const asp_model *m); /* E/(1-ν²) of the reference, MPa */

/* Values of w where the response has a kink or jump (for quadrature
 * breakpoints), ascending; returns their count and a borrowed array. */
STC_API int asp_model_breaks(const asp_model *m, const double **w);

#ifdef __cplusplus
}
#endif
#endif
