/* Single-asperity models behind one interface (include/stiction/model.h).
 *
 * Every model is a normalised response (P/Pc, A/Ac, Q/Pc versus w = δ/ωc and
 * t/R) behind a small vtable; asp_model_eval scales it to the summit's own
 * radius.  ωc, Pc, Ac per unit radius come from stc_critical_eval
 * (docs/design.md §6.1): ωc ∝ R, Pc ∝ R², Ac ∝ R².
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include "stiction/formulas.h"
#include "stiction/model.h"
#include "stc_check.h"

typedef unsigned (*norm_fn)(const asp_model *m, double w, double tR, double *p, double *a,
                            double *q);
/* P/Pc alone: the hot call of the pressure solve (no A, no friction law) */
typedef double (*load_fn)(const asp_model *m, double w, double tR);

/* One t/R column of a tabulated model: log-log Steffen interpolants. */
typedef struct data_col {
    double *lw, *lp, *la, *lq; /* [n_w] logs of w, P/Pc, A/Ac, Q/Pc (lq NULL: no friction) */
    gsl_interp *ip, *ia, *iq;
} data_col;

struct asp_model {
    char name[128];
    const char *layer_name;
    norm_fn norm;
    load_fn load;
    stc_material ref;  /* reference layer */
    double t;          /* coating thickness, mm */
    double wc1, Pc1, Ac1, E_star; /* ωc/R, Pc/R², Ac/R², E* */
    asp_model_range range;
    const double *breaks;
    int nbreaks;
    double *knots;     /* a tabulated model's w values: its breaks (owned) */
    /* tabulated models */
    int n_w, n_tR;
    double *tR;        /* [n_tR] */
    data_col *cols;    /* [n_tR] */
};

/* ------------------------------------------------------------ helpers */

static stc_status model_alloc(const stc_material *ref, double t_mm, asp_model **out)
{
    STC_CHECK(out, STC_EINVAL, "asp_model: out must not be NULL");
    *out = NULL;
    STC_CHECK(isfinite(t_mm) && t_mm >= 0, STC_EINVAL,
              "t-mm = %g: coating thickness must be >= 0 mm", t_mm);
    stc_critical c;
    STC_CALL(stc_critical_eval(ref, 1.0, &c)); /* per unit radius */
    asp_model *m = calloc(1, sizeof *m);
    STC_CHECK(m, STC_ENOMEM, "asp_model: out of memory");
    m->ref = *ref;
    m->t = t_mm;
    m->wc1 = c.omega_c;
    m->Pc1 = c.P_c;
    m->Ac1 = c.A_c;
    m->E_star = ref->E / (1.0 - ref->nu * ref->nu);
    m->layer_name = "reference";
    *out = m;
    return STC_OK;
}

static stc_status layer_material(const stc_params *p, asp_layer layer, stc_material *mat,
                                 const char **name)
{
    STC_CHECK(p, STC_EINVAL, "asp_model: params must not be NULL");
    STC_CALL(stc_params_validate(p));
    STC_CHECK(layer == ASP_LAYER_SUBSTRATE || layer == ASP_LAYER_COATING, STC_EINVAL,
              "layer = %d: must be substrate (0) or coating (1)", (int)layer);
    stc_material su, co;
    stc_params_materials(p, &su, &co);
    *mat = layer == ASP_LAYER_SUBSTRATE ? su : co;
    *name = layer == ASP_LAYER_SUBSTRATE ? "substrate" : "coating";
    return STC_OK;
}

/* A model of one layer of p's materials, named NAME (a closed form's constructor). */
static stc_status model_alloc_layer(const stc_params *p, double t_mm, asp_layer layer,
                                    const char *name, asp_model **out)
{
    stc_material mat;
    const char *lname;
    STC_CALL(layer_material(p, layer, &mat, &lname));
    STC_CALL(model_alloc(&mat, t_mm, out));
    snprintf((*out)->name, sizeof (*out)->name, "%s", name);
    (*out)->layer_name = lname;
    return STC_OK;
}

/* ------------------------------------------------------------ hertz */

/* Hertz in normalised form: P/Pc = w^{3/2}, A/Ac = w (docs/design.md §6.1: Pc, Ac are
 * the Hertz load and area at ωc). */
static unsigned hertz_norm(const asp_model *m, double w, double tR, double *p, double *a,
                           double *q)
{
    (void)m;
    (void)tR;
    *p = w * sqrt(w);
    *a = w;
    *q = NAN;
    return ASP_NO_FRICTION;
}

static double hertz_load(const asp_model *m, double w, double tR)
{
    (void)m;
    (void)tR;
    return w * sqrt(w);
}

stc_status asp_model_create_hertz(const stc_params *p, double t_mm, asp_layer layer,
                                  asp_model **out)
{
    STC_CALL(model_alloc_layer(p, t_mm, layer, "hertz", out));
    asp_model *m = *out;
    m->norm = hertz_norm;
    m->load = hertz_load;
    /* elastic: exact for any δ in small-strain theory, but only physical up
     * to yield inception w = 1 */
    m->range = (asp_model_range){0.0, 1.0, 0.0, INFINITY, 0, 0};
    return STC_OK;
}

/* ------------------------------------------------------------ wsp */

/* Kogut & Etsion (2002), J. Appl. Mech. 69:657–662, FE fits for a
 * frictionless elastic–plastic sphere on a rigid flat, w = ω/ωc:
 *   0 <= w <= 1:   Hertz          P/Pc = w^1.5,          A/Ac = w
 *   1 <  w <= 6:   P/Pc = 1.03 w^1.425,  A/Ac = 0.93 w^1.136
 *   6 <  w <= 110: P/Pc = 1.40 w^1.263,  A/Ac = 0.94 w^1.146
 *   w > 110:       fully plastic (KE 2002; Abbott–Firestone area), A = 2 Ac w,
 *                  mean pressure H = 2.8 Y (Tabor), so P/Pc = 2 w · 2.8 Y Ac/Pc.
 * KE normalise with K H = (0.454 + 0.41 ν) 2.8 Y; we use Cv Y (docs/design.md §6.5,
 * Green 2005): (1.271 + 1.148 ν) versus (1.234 + 1.256 ν), 0.1 % apart at
 * ν = 0.32.  The fits are not continuous: P jumps +3 % at w = 1, +2 % at 6,
 * +7 % at 110; A jumps −7 % at 1, +3 % at 6, +7 % at 110.  GW quadrature
 * breaks there (asp_model_breaks). */
#define KE_W1 1.0
#define KE_W2 6.0
#define KE_W3 110.0
#define TABOR_H_OVER_Y 2.8 /* Tabor (1951): hardness of a fully plastic contact */

#define WSP_W_LO 0.5  /* preloads of Wu, Shi & Polycarpou (2012), docs/design.md §6.4 */
#define WSP_W_HI 72.0

static const double ke_breaks[] = {KE_W1, KE_W2, KE_W3};

/* P/Pc of the KE fits (the table above). */
static double ke_load(const asp_model *m, double w, double tR)
{
    (void)tR;
    if (w <= KE_W1) return w * sqrt(w);
    if (w <= KE_W2) return 1.03 * pow(w, 1.425);
    if (w <= KE_W3) return 1.40 * pow(w, 1.263);
    return 2.0 * w * TABOR_H_OVER_Y * m->ref.Y * m->Ac1 / m->Pc1;
}

/* A/Ac of the KE fits. */
static double ke_area(double w)
{
    if (w <= KE_W1) return w;
    if (w <= KE_W2) return 0.93 * pow(w, 1.136);
    if (w <= KE_W3) return 0.94 * pow(w, 1.146);
    return 2.0 * w;
}

static unsigned wsp_norm(const asp_model *m, double w, double tR, double *p, double *a,
                         double *q)
{
    unsigned fit = 0, flags = 0;
    *p = ke_load(m, w, tR);
    *a = ke_area(w);
    /* Wu, Shi & Polycarpou (2012): μs = 0.3 coth(0.57 (ω/ωc)^0.41) */
    *q = stc_wsp_mu(w, &fit) * *p;
    if (fit) flags |= w < 1.0 ? ASP_OUT_W_LOW : ASP_OUT_W_HIGH;
    if (w > KE_W3) flags |= ASP_OUT_W_HIGH;
    return flags;
}

stc_status asp_model_create_wsp(const stc_params *p, double t_mm, asp_layer layer,
                                asp_model **out)
{
    STC_CALL(model_alloc_layer(p, t_mm, layer, "wsp", out));
    asp_model *m = *out;
    m->norm = wsp_norm;
    m->load = ke_load;
    /* in range where every output is a fit inside its data: the WSP μs fit's
     * preloads 0.5 <= ω/ωc <= 72 (docs/design.md §6.4; KE's P, A alone extend
     * to 110) */
    m->range = (asp_model_range){WSP_W_LO, WSP_W_HI, 0.0, INFINITY, 0, 1};
    m->breaks = ke_breaks;
    m->nbreaks = 3;
    return STC_OK;
}

/* ------------------------------------------------------------ data */

static void col_free(data_col *c)
{
    free(c->lw);
    free(c->lp);
    free(c->la);
    free(c->lq);
    if (c->ip) gsl_interp_free(c->ip);
    if (c->ia) gsl_interp_free(c->ia);
    if (c->iq) gsl_interp_free(c->iq);
}

static stc_status col_logs(double *dst, const double *src, int n, const char *what, int j)
{
    for (int i = 0; i < n; i++) {
        STC_CHECK(isfinite(src[i]) && src[i] > 0, STC_EINVAL,
                  "%s[%d][%d] = %g: tabulated values must be finite and > 0", what, j, i,
                  src[i]);
        dst[i] = log(src[i]);
    }
    return STC_OK;
}

static stc_status col_init(data_col *c, const asp_model_data *d, int j)
{
    int n = d->n_w;
    size_t sz = (size_t)n * sizeof(double);
    c->lw = malloc(sz);
    c->lp = malloc(sz);
    c->la = malloc(sz);
    c->lq = d->Q_Pc ? malloc(sz) : NULL;
    STC_CHECK(c->lw && c->lp && c->la && (c->lq || !d->Q_Pc), STC_ENOMEM,
              "asp_model: out of memory");
    STC_CALL(col_logs(c->lw, d->w, n, "w", 0));
    for (int i = 1; i < n; i++) /* GSL's interpolation needs increasing ln w */
        STC_CHECK(c->lw[i] > c->lw[i - 1], STC_EINVAL,
                  "w[%d] = %.17g after %.17g: too close to tell apart in ln w", i, d->w[i],
                  d->w[i - 1]);
    STC_CALL(col_logs(c->lp, d->P_Pc + (size_t)j * n, n, "P_Pc", j));
    STC_CALL(col_logs(c->la, d->A_Ac + (size_t)j * n, n, "A_Ac", j));
    if (d->Q_Pc) STC_CALL(col_logs(c->lq, d->Q_Pc + (size_t)j * n, n, "Q_Pc", j));
    c->ip = gsl_interp_alloc(gsl_interp_steffen, (size_t)n);
    c->ia = gsl_interp_alloc(gsl_interp_steffen, (size_t)n);
    c->iq = d->Q_Pc ? gsl_interp_alloc(gsl_interp_steffen, (size_t)n) : NULL;
    STC_CHECK(c->ip && c->ia && (c->iq || !d->Q_Pc), STC_ENOMEM, "asp_model: out of memory");
    gsl_interp_init(c->ip, c->lw, c->lp, (size_t)n);
    gsl_interp_init(c->ia, c->lw, c->la, (size_t)n);
    if (c->iq) gsl_interp_init(c->iq, c->lw, c->lq, (size_t)n);
    return STC_OK;
}

/* log-log value at lx: Steffen inside the grid, the end interval's power law
 * outside (exact continuation of Hertz-like data).  Below the grid the
 * exponent is held >= 0: no response grows as the interference falls, and an
 * error band that narrows along the first interval (a table's Qmax band) would
 * otherwise diverge as w -> 0.  accel NULL: read-only, so concurrent calls are
 * safe. */
static double col_eval(const data_col *c, const gsl_interp *ip, const double *ly, int n,
                       double lx)
{
    const double *lw = c->lw;
    if (lx < lw[0]) return ly[0] + fmax((ly[1] - ly[0]) / (lw[1] - lw[0]), 0.0) * (lx - lw[0]);
    if (lx > lw[n - 1])
        return ly[n - 1] + (ly[n - 1] - ly[n - 2]) / (lw[n - 1] - lw[n - 2]) * (lx - lw[n - 1]);
    return gsl_interp_eval(ip, lw, ly, lx, NULL);
}

static void col_values(const asp_model *m, int j, double lx, double *p, double *a, double *q)
{
    const data_col *c = &m->cols[j];
    *p = exp(col_eval(c, c->ip, c->lp, m->n_w, lx));
    *a = exp(col_eval(c, c->ia, c->la, m->n_w, lx));
    *q = c->iq ? exp(col_eval(c, c->iq, c->lq, m->n_w, lx)) : NAN;
}

/* Outside a range end, beyond rounding: a summit's t/R = t/R computed from
 * t and R may differ from the axis value it equals in the last bits. */
static int below(double x, double lo) { return x < lo * (1.0 - 1e-12); }
static int above(double x, double hi) { return x > hi * (1.0 + 1e-12); }

static unsigned data_norm(const asp_model *m, double w, double tR, double *p, double *a,
                          double *q)
{
    unsigned flags = m->cols[0].iq ? 0u : (unsigned)ASP_NO_FRICTION;
    double lx = log(w);
    if (w < m->range.w_lo) flags |= ASP_OUT_W_LOW;
    if (w > m->range.w_hi) flags |= ASP_OUT_W_HIGH;
    int nt = m->n_tR;
    if (!m->range.coating_aware || nt == 1) {
        if (m->range.coating_aware && (below(tR, m->tR[0]) || above(tR, m->tR[0])))
            flags |= ASP_OUT_T_OVER_R;
        col_values(m, 0, lx, p, a, q);
        return flags;
    }
    /* linear in t/R between columns, clamped outside */
    int j = 0;
    if (tR <= m->tR[0] || tR >= m->tR[nt - 1]) {
        if (below(tR, m->tR[0]) || above(tR, m->tR[nt - 1])) flags |= ASP_OUT_T_OVER_R;
        col_values(m, tR <= m->tR[0] ? 0 : nt - 1, lx, p, a, q);
        return flags;
    }
    while (j < nt - 2 && tR > m->tR[j + 1]) j++;
    double s = (tR - m->tR[j]) / (m->tR[j + 1] - m->tR[j]);
    double p0, a0, q0, p1, a1, q1;
    col_values(m, j, lx, &p0, &a0, &q0);
    col_values(m, j + 1, lx, &p1, &a1, &q1);
    *p = p0 + s * (p1 - p0);
    *a = a0 + s * (a1 - a0);
    *q = q0 + s * (q1 - q0);
    return flags;
}

static stc_status data_check(const asp_model_data *d)
{
    STC_CHECK(d, STC_EINVAL, "asp_model_data: must not be NULL");
    STC_CHECK(d->n_w >= 3, STC_EINVAL, "n_w = %d: need >= 3 interference values", d->n_w);
    STC_CHECK(d->n_tR >= 1, STC_EINVAL, "n_tR = %d: need >= 1 t/R value", d->n_tR);
    STC_CHECK(d->w && d->tR && d->P_Pc && d->A_Ac, STC_EINVAL,
              "asp_model_data: w, tR, P_Pc, A_Ac must not be NULL");
    STC_CHECK(d->coating_aware || d->n_tR == 1, STC_EINVAL,
              "n_tR = %d: a model that ignores the coating takes one t/R column", d->n_tR);
    for (int i = 1; i < d->n_w; i++)
        STC_CHECK(d->w[i] > d->w[i - 1], STC_EINVAL,
                  "w[%d] = %g after %g: interference values must increase strictly", i,
                  d->w[i], d->w[i - 1]);
    for (int j = 0; j < d->n_tR; j++) {
        STC_CHECK(isfinite(d->tR[j]) && d->tR[j] >= 0, STC_EINVAL,
                  "tR[%d] = %g: must be >= 0", j, d->tR[j]);
        STC_CHECK(j == 0 || d->tR[j] > d->tR[j - 1], STC_EINVAL,
                  "tR[%d] = %g after %g: t/R values must increase strictly", j, d->tR[j],
                  d->tR[j - 1]);
    }
    return STC_OK;
}

stc_status asp_model_create_data(const asp_model_data *d, asp_model **out)
{
    stc_status st = STC_OK;
    STC_CALL(data_check(d));
    STC_CALL(model_alloc(&d->ref, d->t_mm, out));
    asp_model *m = *out;
    snprintf(m->name, sizeof m->name, "%s", d->name ? d->name : "data");
    m->norm = data_norm;
    m->n_w = d->n_w;
    m->n_tR = d->n_tR;
    m->tR = malloc((size_t)d->n_tR * sizeof *m->tR);
    m->cols = calloc((size_t)d->n_tR, sizeof *m->cols);
    STC_CHECK_GOTO(m->tR && m->cols, st, fail, STC_ENOMEM, "asp_model: out of memory");
    memcpy(m->tR, d->tR, (size_t)d->n_tR * sizeof *m->tR);
    for (int j = 0; j < d->n_tR; j++) STC_CALL_GOTO(col_init(&m->cols[j], d, j), st, fail);
    m->range = (asp_model_range){d->w[0], d->w[d->n_w - 1],
                                 d->coating_aware ? d->tR[0] : 0.0,
                                 d->coating_aware ? d->tR[d->n_tR - 1] : INFINITY,
                                 d->coating_aware, d->Q_Pc != NULL};
    /* the interpolant is a cubic between the knots (its second derivative
     * jumps there) and another formula past either end: a quadrature that
     * splits at every knot integrates smooth pieces only */
    m->knots = malloc((size_t)d->n_w * sizeof *m->knots);
    STC_CHECK_GOTO(m->knots, st, fail, STC_ENOMEM, "asp_model: out of memory");
    memcpy(m->knots, d->w, (size_t)d->n_w * sizeof *m->knots);
    m->breaks = m->knots;
    m->nbreaks = d->n_w;
    return STC_OK;
fail:
    asp_model_destroy(out);
    return st;
}

void asp_sample_params_default(asp_sample_params *sp)
{
    sp->w_lo = 0.01;
    sp->w_hi = 200.0; /* past KE's fully plastic 110 and the thesis's 60 */
    sp->n_w = 121;
    sp->tR_lo = 0.002;
    sp->tR_hi = 0.05;
    sp->n_tR = 7;
}

static stc_status sample_grid(const asp_model *base, const asp_sample_params *sp, double *w,
                              double *tR, int nt)
{
    double hi = sp->w_hi;
    STC_CALL(stc_check_range("w-lo", sp->w_lo, 0.0, 0, hi, 0));
    for (int i = 0; i < sp->n_w; i++)
        w[i] = sp->w_lo * pow(hi / sp->w_lo, (double)i / (sp->n_w - 1));
    if (!base->range.coating_aware) {
        tR[0] = 0.0;
        return STC_OK;
    }
    STC_CALL(stc_check_range("tR-lo", sp->tR_lo, 0.0, 1, sp->tR_hi, nt == 1));
    for (int j = 0; j < nt; j++)
        tR[j] = nt == 1 ? sp->tR_lo : sp->tR_lo + (sp->tR_hi - sp->tR_lo) * j / (nt - 1);
    return STC_OK;
}

stc_status asp_model_create_sampled(const asp_model *base, const asp_sample_params *sp,
                                    asp_model **out)
{
    asp_sample_params def;
    stc_status st = STC_OK;
    STC_CHECK(base && out, STC_EINVAL, "asp_model_create_sampled: base and out required");
    if (!sp) {
        asp_sample_params_default(&def);
        sp = &def;
    }
    STC_CHECK(sp->n_w >= 3 && sp->n_w <= 100000, STC_EINVAL,
              "n-w = %d: must be in [3, 100000]", sp->n_w);
    int nt = base->range.coating_aware ? sp->n_tR : 1;
    STC_CHECK(nt >= 1 && nt <= 1000, STC_EINVAL, "n-tR = %d: must be in [1, 1000]", nt);
    size_t nn = (size_t)nt * sp->n_w;
    double *w = malloc(sp->n_w * sizeof *w), *tR = malloc(nt * sizeof *tR);
    double *P = malloc(nn * sizeof *P), *A = malloc(nn * sizeof *A), *Q = malloc(nn * sizeof *Q);
    STC_CHECK_GOTO(w && tR && P && A && Q, st, done, STC_ENOMEM, "asp_model: out of memory");
    STC_CALL_GOTO(sample_grid(base, sp, w, tR, nt), st, done);
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < sp->n_w; i++) {
            size_t k = (size_t)j * sp->n_w + i;
            base->norm(base, w[i], tR[j], &P[k], &A[k], &Q[k]);
        }
    char name[128];
    snprintf(name, sizeof name, "sampled:%.100s", base->name);
    asp_model_data d = {name, base->ref, base->t, sp->n_w, nt, w, tR, P, A,
                        base->range.has_friction ? Q : NULL, base->range.coating_aware};
    STC_CALL_GOTO(asp_model_create_data(&d, out), st, done);
    /* covered: the grid where the base itself is in range */
    asp_model *m = *out;
    m->layer_name = base->layer_name;
    m->range.w_lo = fmax(m->range.w_lo, base->range.w_lo);
    m->range.w_hi = fmin(m->range.w_hi, base->range.w_hi);
    m->range.tR_lo = fmax(m->range.tR_lo, base->range.tR_lo);
    m->range.tR_hi = fmin(m->range.tR_hi, base->range.tR_hi);
done:
    free(w);
    free(tR);
    free(P);
    free(A);
    free(Q);
    return st;
}

void asp_model_destroy(asp_model **pm)
{
    if (!pm || !*pm) return;
    asp_model *m = *pm;
    if (m->cols)
        for (int j = 0; j < m->n_tR; j++) col_free(&m->cols[j]);
    free(m->cols);
    free(m->tR);
    free(m->knots);
    free(m);
    *pm = NULL;
}

/* ------------------------------------------------------------ evaluation */

unsigned asp_model_eval_norm(const asp_model *m, double w, double t_over_R, double *P_Pc,
                             double *A_Ac, double *Q_Pc)
{
    if (!(w > 0)) {
        *P_Pc = *A_Ac = 0.0;
        *Q_Pc = m->range.has_friction ? 0.0 : NAN;
        return m->range.has_friction ? 0u : (unsigned)ASP_NO_FRICTION;
    }
    unsigned flags = m->norm(m, w, t_over_R, P_Pc, A_Ac, Q_Pc);
    /* the range is the model's promise: flag everything outside it alike */
    if (w < m->range.w_lo) flags |= ASP_OUT_W_LOW;
    if (w > m->range.w_hi) flags |= ASP_OUT_W_HIGH;
    if (below(t_over_R, m->range.tR_lo) || above(t_over_R, m->range.tR_hi))
        flags |= ASP_OUT_T_OVER_R;
    return flags;
}

double asp_model_load_norm(const asp_model *m, double w, double t_over_R)
{
    double p, a, q;
    if (!(w > 0)) return 0.0;
    if (m->load) return m->load(m, w, t_over_R);
    m->norm(m, w, t_over_R, &p, &a, &q);
    return p;
}

double asp_model_load(const asp_model *m, double R, double delta)
{
    return asp_model_load_norm(m, delta / (m->wc1 * R), m->t / R) * m->Pc1 * R * R;
}

void asp_model_eval(const asp_model *m, double R, double delta, asp_response *out)
{
    double p, a, q, R2 = R * R;
    out->w = delta / (m->wc1 * R);
    out->flags = asp_model_eval_norm(m, out->w, m->t / R, &p, &a, &q);
    out->P = p * m->Pc1 * R2;
    out->A = a * m->Ac1 * R2;
    out->Qmax = q * m->Pc1 * R2;
}

const char *asp_model_name(const asp_model *m) { return m->name; }
const char *asp_model_layer_name(const asp_model *m) { return m->layer_name; }
void asp_model_get_range(const asp_model *m, asp_model_range *out) { *out = m->range; }
double asp_model_t(const asp_model *m) { return m->t; }
const stc_material *asp_model_ref(const asp_model *m) { return &m->ref; }
double asp_model_omega_c(const asp_model *m, double R) { return m->wc1 * R; }
double asp_model_P_c(const asp_model *m, double R) { return m->Pc1 * R * R; }
double asp_model_A_c(const asp_model *m, double R) { return m->Ac1 * R * R; }
double asp_model_E_star(const asp_model *m) { return m->E_star; }

int asp_model_breaks(const asp_model *m, const double **w)
{
    *w = m->breaks;
    return m->nbreaks;
}
