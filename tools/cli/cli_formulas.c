/* stiction formulas: every closed-form relation of docs/design.md §6.1–§6.4
 * for one set of materials and geometry, as a readable report, one JSON
 * object (--json) or a CSV sweep over t/R and Eco/Esu (--csv, used by make
 * reproduce). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "stiction/formulas.h"

static const char usage[] =
    "[--delta LIST] [sphere, coating, materials] [--json | --csv] [--output FILE]\n"
    "\n"
    "Closed-form contact models of one sphere on a rigid flat: yield inception of the\n"
    "homogeneous sphere (slip and stick), the hard-coating fits (slip: Goltsberg 2011,\n"
    "Chen 2016; stick: Ronen 2017), and at each --delta Hertz, the stick\n"
    "elastic-plastic load L and area A and the WSP friction coefficient.  A fit used\n"
    "outside the range it was made for is flagged (report, JSON *_flags) and warned\n"
    "about on stderr.  LIST is a,b,c or start:stop:count.\n"
    "--json: one object; mu_s_wsp and delta_over_omega_c_su are numbers for one\n"
    "--delta and arrays for several (per-delta detail in \"points\").\n"
    "--csv: one row of coated-sphere values per (t/R, Eco/Esu) of the sweep lists\n"
    "(default: the common --t-over-R and --E-ratio).";

static const cli_opt opts[] = {
    CLI_COATED_SPHERE_SECTIONS,
    CLI_HEADING("Loading"),
    {"delta", "LIST", "interference(s) in units of omega_c_su, the substrate's critical "
                      "interference (> 0)"},
    CLI_HEADING("Common options"),
    {"json", NULL, "print one JSON object instead of the report"},
    {"csv", NULL, "print a CSV table of the coated fits over the sweep lists"},
    {"sweep-t-over-R", "LIST", "t/R values of the --csv sweep (each in (0, 1))"},
    {"sweep-E-ratio", "LIST", "Eco/Esu values of the --csv sweep (each > 1)"},
    {"output", "FILE", "write to FILE (atomically: temp file + rename) instead of stdout"},
    CLI_CONFIG_HELP,
    {NULL, NULL, NULL},
};

typedef struct {
    double *delta, *sw_tr, *sw_er; /* owned lists */
    int ndelta, n_tr, n_er;
    int json, csv;
    char *output; /* owned */
} fopts;

/* Parse a list and check every value is in (lo, hi). */
static stc_status set_list(const char *key, const char *value, double lo, double hi,
                           double **list, int *n)
{
    double *v;
    int k;
    char msg[512];
    stc_status s = cli_parse_list(key, value, &v, &k);
    if (s == STC_OK) { /* range messages already state the range */
        for (int i = 0; i < k; i++)
            if ((s = stc_check_range(key, v[i], lo, 0, hi, 0)) != STC_OK) {
                free(v);
                return s;
            }
    }
    if (s != STC_OK) { /* a syntax error: say what a valid value looks like */
        snprintf(msg, sizeof msg, "%s", stc_errmsg());
        if (isinf(hi))
            return stc_error(s, __FILE__, __LINE__, "%s (expected numbers > %g as a,b,c or "
                             "start:stop:count)", msg, lo);
        return stc_error(s, __FILE__, __LINE__, "%s (expected numbers in (%g, %g) as a,b,c or "
                         "start:stop:count)", msg, lo, hi);
    }
    free(*list); /* a command-line value replaces the config file's */
    *list = v;
    *n = k;
    return STC_OK;
}

static stc_status set_opt(void *ctx, const char *key, const char *value)
{
    fopts *o = ctx;
    if (!strcmp(key, "delta")) return set_list(key, value, 0.0, INFINITY, &o->delta, &o->ndelta);
    if (!strcmp(key, "sweep-t-over-R")) return set_list(key, value, 0.0, 1.0, &o->sw_tr, &o->n_tr);
    if (!strcmp(key, "sweep-E-ratio"))
        return set_list(key, value, 1.0, INFINITY, &o->sw_er, &o->n_er);
    if (!strcmp(key, "json")) return cli_parse_flag(key, value, &o->json);
    if (!strcmp(key, "csv")) return cli_parse_flag(key, value, &o->csv);
    if (!strcmp(key, "output")) {
        if (!*value)
            return stc_error(STC_EINVAL, __FILE__, __LINE__, "output = '': must be a file name");
        free(o->output);
        o->output = strdup(value);
        return o->output ? STC_OK : stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    }
    return STC_EUNSUPPORTED;
}

/* ---- the evaluated model ---------------------------------------------- */

typedef struct {
    stc_params p;
    stc_material su, co;
    stc_critical csu, cco;
    int coated;          /* the coated fits apply (t/R > 0, Eco/Esu > 1) */
    char note[256];      /* why they do not, when !coated */
    stc_coated c;
    double tR_p, tR_p_st, tR_p_same_nu; /* NAN unless Eco/Esu > 1 */
} model;

static stc_status model_eval(const stc_params *p, model *m)
{
    memset(m, 0, sizeof *m);
    m->p = *p;
    stc_params_materials(p, &m->su, &m->co);
    stc_status s;
    if ((s = stc_critical_eval(&m->su, p->R, &m->csu)) != STC_OK) return s;
    if ((s = stc_critical_eval(&m->co, p->R, &m->cco)) != STC_OK) return s;
    m->tR_p = m->tR_p_st = m->tR_p_same_nu = NAN;
    if (p->E_ratio > 1.0) { /* optimal thicknesses need no thickness */
        m->tR_p = stc_tR_p(&m->su, &m->co);
        m->tR_p_same_nu = stc_tR_p_same_nu(&m->su, &m->co);
        m->tR_p_st = stc_tR_p_st(&m->su, &m->co, m->co.nu);
    }
    s = stc_coated_eval(p, &m->c);
    m->coated = (s == STC_OK);
    if (s == STC_EUNSUPPORTED) {
        snprintf(m->note, sizeof m->note, "coated-sphere fits not applicable: %s", stc_errmsg());
        s = STC_OK;
    }
    return s;
}

/* Values at one interference δ = w ωc_su. */
typedef struct {
    double w, delta_mm, mu;
    stc_hertz hsu, hco;
    unsigned wsp_flags;
    double L_ep, A_ep;
    unsigned ep_flags;
} point;

static stc_status point_eval(const model *m, double w, point *pt)
{
    stc_status s;
    pt->w = w;
    pt->delta_mm = w * m->csu.omega_c;
    if ((s = stc_hertz_eval(&m->su, m->p.R, pt->delta_mm, &pt->hsu)) != STC_OK) return s;
    if ((s = stc_hertz_eval(&m->co, m->p.R, pt->delta_mm, &pt->hco)) != STC_OK) return s;
    pt->mu = stc_wsp_mu(w, &pt->wsp_flags);
    if (m->p.t_over_R > 0.0 && m->p.E_ratio != 1.0) pt->wsp_flags |= STC_FIT_E_RATIO;
    pt->L_ep = pt->A_ep = NAN;
    pt->ep_flags = 0;
    if (m->coated)
        return stc_coated_ep(&m->c, pt->delta_mm, &pt->L_ep, &pt->A_ep, &pt->ep_flags);
    return STC_OK;
}

/* ---- JSON ------------------------------------------------------------- */

static void cj_flags(cli_json *j, const char *key, stc_fit_family fam, unsigned flags)
{
    cj_arr(j, key);
    for (unsigned bit = 1; bit <= STC_FIT_ORDER; bit <<= 1)
        if (flags & bit) cj_str(j, NULL, stc_fit_flag_text(fam, bit));
    cj_end_arr(j);
}

static void json_critical(cli_json *j, const stc_critical *c, const char *sfx)
{
    char k[64];
#define K(name) (snprintf(k, sizeof k, name, sfx), k)
    cj_num(j, K("Cv%s"), c->Cv);
    cj_num(j, K("omega_c%s_mm"), c->omega_c);
    cj_num(j, K("P_c%s_N"), c->P_c);
    cj_num(j, K("A_c%s_mm2"), c->A_c);
    cj_num(j, K("delta_c_stick_over_omega_c%s"), c->delta_c_stick_over_omega_c);
    cj_num(j, K("L_c_stick_over_P_c%s"), c->L_c_stick_over_P_c);
    cj_num(j, K("delta_c_stick%s_mm"), c->delta_c_stick);
    cj_num(j, K("L_c_stick%s_N"), c->L_c_stick);
    cj_num(j, K("A_c_stick%s_mm2"), c->A_c_stick);
    cj_flags(j, K("stick_homogeneous_flags%s"), STC_FITS_STICK_HOMOG, c->flags);
#undef K
}

static void json_coated(cli_json *j, const model *m)
{
    const stc_coated *c = &m->c;
    const int ok = m->coated;
#define NUM(key, v) (ok ? cj_num(j, key, v) : cj_null(j, key))
    cj_bool(j, "coated_applicable", ok);
    if (ok) cj_null(j, "coated_note");
    else cj_str(j, "coated_note", m->note);
    NUM("Pc_co_over_Pc_su", c->Pc_co_over_Pc_su);
    cj_num(j, "tR_p", m->tR_p); /* null when Eco/Esu <= 1 */
    cj_num(j, "tR_p_same_nu", m->tR_p_same_nu);
    NUM("omega_c1_over_omega_c_co", c->omega_c1_over_omega_c_co);
    NUM("omega_c2_over_omega_c_co", c->omega_c2_over_omega_c_co);
    NUM("omega_c1_mm", c->omega_c1_mm);
    NUM("omega_c2_mm", c->omega_c2_mm);
    cj_flags(j, "slip_flags", STC_FITS_SLIP, ok ? c->flags_slip : 0);
    cj_num(j, "tR_p_st", m->tR_p_st);
    NUM("delta_c1_over_omega_c_su", c->delta_c1_over_omega_c_su);
    NUM("delta_c2_over_omega_c_su", c->delta_c2_over_omega_c_su);
    NUM("delta_c1_over_omega_c_co", c->delta_c1_over_omega_c_co);
    NUM("delta_c2_over_omega_c_co", c->delta_c2_over_omega_c_co);
    NUM("delta_c2_over_delta_c1", c->delta_c2_mm / c->delta_c1_mm);
    NUM("delta_c1_mm", c->delta_c1_mm);
    NUM("delta_c2_mm", c->delta_c2_mm);
    NUM("L_c2_over_P_c_co", c->L_c2_over_P_c_co);
    NUM("L_c2_N", c->L_c2_N);
    NUM("A_c2_st_over_A_c_co", c->A_c2_st_over_A_c_co);
    NUM("A_c2_st_mm2", c->A_c2_st_mm2);
    cj_flags(j, "stick_flags", STC_FITS_STICK, ok ? c->flags_stick : 0);
    if (ok) cj_bool(j, "weakening", (c->flags_stick & STC_FIT_ORDER) != 0);
    else cj_null(j, "weakening");
#undef NUM
}

static void json_point(cli_json *j, const model *m, const point *pt)
{
    cj_obj(j, NULL);
    cj_num(j, "delta_over_omega_c_su", pt->w);
    cj_num(j, "delta_mm", pt->delta_mm);
    cj_num(j, "hertz_P_N", pt->hsu.P);
    cj_num(j, "hertz_a_mm", pt->hsu.a);
    cj_num(j, "hertz_p0_MPa", pt->hsu.p0);
    cj_num(j, "hertz_A_mm2", pt->hsu.A);
    cj_num(j, "hertz_P_over_P_c", pt->hsu.P / m->csu.P_c);
    cj_num(j, "hertz_co_P_N", pt->hco.P);
    cj_num(j, "hertz_co_p0_MPa", pt->hco.p0);
    cj_num(j, "mu_s_wsp", pt->mu);
    cj_flags(j, "wsp_flags", STC_FITS_WSP, pt->wsp_flags);
    cj_num(j, "L_ep_N", pt->L_ep); /* NAN (null) when the coated fits do not apply */
    cj_num(j, "A_ep_mm2", pt->A_ep);
    cj_num(j, "L_ep_over_L_c2", m->coated ? pt->L_ep / m->c.L_c2_N : NAN);
    cj_num(j, "A_ep_over_A_c2_st", m->coated ? pt->A_ep / m->c.A_c2_st_mm2 : NAN);
    cj_flags(j, "ep_flags", STC_FITS_EP, pt->ep_flags);
    cj_end_obj(j);
}

static void json_report(FILE *f, const model *m, const point *pts, int n)
{
    cli_json j;
    cj_init(&j, f);
    cj_obj(&j, NULL);
    cj_str(&j, "units", "mm, N, MPa");
    cj_obj(&j, "params");
    cj_params(&j, &m->p);
    cj_end_obj(&j);
    json_critical(&j, &m->csu, "");
    json_critical(&j, &m->cco, "_co");
    json_coated(&j, m);
    if (n == 1) {
        cj_num(&j, "delta_over_omega_c_su", pts[0].w);
        cj_num(&j, "mu_s_wsp", pts[0].mu);
    } else if (n == 0) {
        cj_null(&j, "delta_over_omega_c_su");
        cj_null(&j, "mu_s_wsp");
    } else {
        cj_arr(&j, "delta_over_omega_c_su");
        for (int i = 0; i < n; i++) cj_num(&j, NULL, pts[i].w);
        cj_end_arr(&j);
        cj_arr(&j, "mu_s_wsp");
        for (int i = 0; i < n; i++) cj_num(&j, NULL, pts[i].mu);
        cj_end_arr(&j);
    }
    cj_arr(&j, "points");
    for (int i = 0; i < n; i++) json_point(&j, m, &pts[i]);
    cj_end_arr(&j);
    cj_end_obj(&j);
    cj_done(&j);
}

/* ---- readable report -------------------------------------------------- */

/* A number, or "n/a" (never "nan"); buf holds 32 characters. */
static const char *num(char *buf, double v) { return cli_num(buf, 32, "%.6g", v, "n/a"); }

static void text_flags(FILE *f, stc_fit_family fam, unsigned flags)
{
    if (!flags) {
        fprintf(f, "    inputs inside the fits' ranges\n");
        return;
    }
    for (unsigned bit = 1; bit <= STC_FIT_ORDER; bit <<= 1)
        if (flags & bit) fprintf(f, "    ! %s\n", stc_fit_flag_text(fam, bit));
}

static void text_critical(FILE *f, const model *m)
{
    char a[32], b[32];
    const stc_critical *s = &m->csu, *c = &m->cco;
#define ROW(label, field) \
    fprintf(f, "  %-38s %12s %12s\n", label, num(a, s->field), num(b, c->field))
    fprintf(f, "Yield inception, homogeneous sphere on a rigid flat\n"
               "  %-38s %12s %12s\n", "", "substrate", "coating");
    ROW("Cv (Kogut & Etsion 2002)", Cv);
    ROW("omega_c, slip [mm]", omega_c);
    ROW("P_c, slip [N]", P_c);
    ROW("A_c, slip [mm2]", A_c);
    ROW("delta_c/omega_c, stick (Brizmer 2006)", delta_c_stick_over_omega_c);
    ROW("L_c/P_c, stick (Brizmer 2006)", L_c_stick_over_P_c);
#undef ROW
    text_flags(f, STC_FITS_STICK_HOMOG, s->flags | c->flags);
}

static void text_coated(FILE *f, const model *m)
{
    char a[32], b[32];
    const stc_coated *c = &m->c;
    fprintf(f, "\nHard coating: (t/R)_p (slip) = %s, (t/R)_p_st (stick) = %s\n",
            num(a, m->tR_p), num(b, m->tR_p_st));
    if (!m->coated) {
        fprintf(f, "  %s\n", m->note);
        return;
    }
    fprintf(f, "Coated sphere, slip (Goltsberg et al. 2011; Chen et al. 2016)\n");
    fprintf(f, "  Pc_co/Pc_su           %10s   (consistent form, docs/design.md §6.3)\n",
            num(a, c->Pc_co_over_Pc_su));
    fprintf(f, "  omega_c1/omega_c_co   %10s   (%s mm)\n", num(a, c->omega_c1_over_omega_c_co),
            num(b, c->omega_c1_mm));
    fprintf(f, "  omega_c2/omega_c_co   %10s   (%s mm)\n", num(a, c->omega_c2_over_omega_c_co),
            num(b, c->omega_c2_mm));
    text_flags(f, STC_FITS_SLIP, c->flags_slip);
    fprintf(f, "Coated sphere, stick (Ronen et al. 2017)\n");
    fprintf(f, "  delta_c1/omega_c_su   %10s   (%s mm, first yield, coating)\n",
            num(a, c->delta_c1_over_omega_c_su), num(b, c->delta_c1_mm));
    fprintf(f, "  delta_c2/omega_c_su   %10s   (%s mm, second yield, substrate)\n",
            num(a, c->delta_c2_over_omega_c_su), num(b, c->delta_c2_mm));
    fprintf(f, "  L_c2/P_c_co           %10s   (%s N)\n", num(a, c->L_c2_over_P_c_co),
            num(b, c->L_c2_N));
    fprintf(f, "  A_c2_st/A_c_co        %10s   (%s mm2)\n", num(a, c->A_c2_st_over_A_c_co),
            num(b, c->A_c2_st_mm2));
    text_flags(f, STC_FITS_STICK, c->flags_stick);
}

static void text_point(FILE *f, const model *m, const point *pt)
{
    char a[32], b[32], c[32], d[32];
    fprintf(f, "\nAt delta = %s omega_c_su = %s mm\n", num(a, pt->w), num(b, pt->delta_mm));
    fprintf(f, "  Hertz, substrate sphere: P = %s N, a = %s mm, p0 = %s MPa, A = %s mm2\n",
            num(a, pt->hsu.P), num(b, pt->hsu.a), num(c, pt->hsu.p0), num(d, pt->hsu.A));
    if (m->coated) {
        fprintf(f, "  Hertz, coating material: P = %s N, p0 = %s MPa\n", num(a, pt->hco.P),
                num(b, pt->hco.p0));
        fprintf(f, "  Stick elastic-plastic (Ronen 2017): L = %s N, A = %s mm2\n",
                num(a, pt->L_ep), num(b, pt->A_ep));
        text_flags(f, STC_FITS_EP, pt->ep_flags);
    }
    fprintf(f, "  WSP mu_s = 0.3 coth(0.57 (delta/omega_c)^0.41) = %s\n", num(a, pt->mu));
    text_flags(f, STC_FITS_WSP, pt->wsp_flags);
}

static void text_report(FILE *f, const model *m, const point *pts, int n)
{
    const stc_params *p = &m->p;
    fprintf(f, "stiction formulas: closed-form contact models (mm, N, MPa)\n"
               "  R = %g mm, t/R = %g (t = %g mm), nu_su = %g, nu_co = %g\n"
               "  Esu = %g, Ysu = %g; Eco = %g (Eco/Esu = %g), Yco = %g\n\n",
            p->R, p->t_over_R, stc_params_t(p), m->su.nu, m->co.nu, m->su.E, m->su.Y,
            m->co.E, p->E_ratio, m->co.Y);
    text_critical(f, m);
    text_coated(f, m);
    for (int i = 0; i < n; i++) text_point(f, m, &pts[i]);
}

/* ---- warnings ----------------------------------------------------------- */

/* Every fit used outside the range it was made for, one line each on
 * stderr (the flags are in the report and the JSON too).  A coating that
 * yields after its substrate (STC_FIT_ORDER of the slip and stick fits) is a
 * finding of the fits, not a range, and is not warned about. */
static void warn_ranges(const char *name, const model *m, const point *pts, int n)
{
    struct {
        const char *what;
        stc_fit_family fam;
        unsigned flags;
    } f[] = {
        {"stick yield inception (Brizmer 2006)", STC_FITS_STICK_HOMOG,
         m->csu.flags | m->cco.flags},
        {"coated slip fits", STC_FITS_SLIP, m->coated ? m->c.flags_slip & ~STC_FIT_ORDER : 0},
        {"coated stick fits", STC_FITS_STICK, m->coated ? m->c.flags_stick & ~STC_FIT_ORDER : 0},
        {"stick elastic-plastic L, A", STC_FITS_EP, 0},
        {"WSP mu_s", STC_FITS_WSP, 0},
    };
    for (int i = 0; i < n; i++) f[3].flags |= pts[i].ep_flags, f[4].flags |= pts[i].wsp_flags;
    for (size_t k = 0; k < sizeof f / sizeof *f; k++)
        for (unsigned bit = 1; bit <= STC_FIT_ORDER; bit <<= 1)
            if (f[k].flags & bit)
                fprintf(stderr, "stiction %s: warning: %s: %s\n", name, f[k].what,
                        stc_fit_flag_text(f[k].fam, bit));
}

/* ---- CSV sweep -------------------------------------------------------- */

/* f == NULL: only check that every row can be evaluated. */
static stc_status csv_report(FILE *f, const stc_params *base, const fopts *o)
{
    const double tr0 = base->t_over_R, er0 = base->E_ratio;
    const double *tr = o->n_tr ? o->sw_tr : &tr0, *er = o->n_er ? o->sw_er : &er0;
    const int ntr = o->n_tr ? o->n_tr : 1, ner = o->n_er ? o->n_er : 1;
    if (f) fprintf(f, "t_over_R,E_ratio,tR_p,tR_p_st,Pc_co_over_Pc_su,omega_c1_over_omega_c_co,"
               "omega_c2_over_omega_c_co,delta_c1_over_omega_c_su,delta_c2_over_omega_c_su,"
               "delta_c2_over_delta_c1,L_c2_over_P_c_co,A_c2_st_over_A_c_co,"
               "flags_slip,flags_stick\n");
    for (int e = 0; e < ner; e++)
        for (int t = 0; t < ntr; t++) {
            stc_params p = *base;
            stc_coated c;
            p.t_over_R = tr[t];
            p.E_ratio = er[e];
            stc_status s = stc_coated_eval(&p, &c);
            if (s != STC_OK) return s;
            if (!f) continue;
            fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,"
                       "%u,%u\n",
                    p.t_over_R, p.E_ratio, c.tR_p, c.tR_p_st, c.Pc_co_over_Pc_su,
                    c.omega_c1_over_omega_c_co, c.omega_c2_over_omega_c_co,
                    c.delta_c1_over_omega_c_su, c.delta_c2_over_omega_c_su,
                    c.delta_c2_mm / c.delta_c1_mm, c.L_c2_over_P_c_co, c.A_c2_st_over_A_c_co,
                    c.flags_slip, c.flags_stick);
        }
    return STC_OK;
}

/* ---- output file: temp + rename, never a partial file ----------------- */

static FILE *out_open(const char *path, char *tmp, size_t n)
{
    if (!path) return stdout;
    snprintf(tmp, n, "%s.tmp.XXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        unlink(tmp);
    }
    return f;
}

/* Close; on success rename into place, otherwise remove the temp file. */
static int out_close(FILE *f, const char *path, const char *tmp, int ok)
{
    if (!path) return fflush(f) == 0 && ok;
    ok = !ferror(f) && ok;
    ok = (fclose(f) == 0) && ok;
    if (ok && rename(tmp, path) == 0) return 1;
    unlink(tmp);
    return 0;
}

static int run(const char *name, const stc_params *p, const fopts *o)
{
    model m;
    point *pts = NULL;
    stc_status s = STC_OK;
    char tmp[4096];
    if (o->csv && (s = csv_report(NULL, p, o)) != STC_OK) return cli_fail(name, s);
    if (!o->csv) {
        if ((s = model_eval(p, &m)) != STC_OK) return cli_fail(name, s);
        pts = calloc((size_t)(o->ndelta ? o->ndelta : 1), sizeof *pts);
        if (!pts) return cli_fail(name, stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory"));
        for (int i = 0; i < o->ndelta && s == STC_OK; i++) s = point_eval(&m, o->delta[i], &pts[i]);
        if (s != STC_OK) {
            free(pts);
            return cli_fail(name, s);
        }
    }
    FILE *f = out_open(o->output, tmp, sizeof tmp);
    if (!f) {
        free(pts);
        fprintf(stderr, "stiction %s: output = '%s': cannot create a file there\n", name, o->output);
        return CLI_EXIT_FAIL;
    }
    if (o->csv) s = csv_report(f, p, o);
    else if (o->json) json_report(f, &m, pts, o->ndelta);
    else text_report(f, &m, pts, o->ndelta);
    if (!o->csv) warn_ranges(name, &m, pts, o->ndelta);
    free(pts);
    if (!out_close(f, o->output, tmp, s == STC_OK)) {
        if (s != STC_OK) return cli_fail(name, s);
        fprintf(stderr, "stiction %s: output = '%s': write failed\n", name,
                o->output ? o->output : "stdout");
        return CLI_EXIT_FAIL;
    }
    return CLI_EXIT_OK;
}

int cli_formulas(const cli_cmd *cmd, int argc, char **argv)
{
    stc_params p;
    fopts o = {0};
    int done, rc;
    stc_params_default(&p);
    rc = cli_parse(cmd->name, usage, argc, argv, opts, &p, set_opt, &o, &done);
    if (rc == CLI_EXIT_OK && !done) {
        if (o.json && o.csv) {
            fprintf(stderr, "stiction %s: json = 1 and csv = 1: choose one output format\n",
                    cmd->name);
            rc = CLI_EXIT_USAGE;
        } else if (!o.csv && (o.n_tr || o.n_er)) {
            fprintf(stderr, "stiction %s: sweep-t-over-R / sweep-E-ratio: only valid with --csv\n",
                    cmd->name);
            rc = CLI_EXIT_USAGE;
        } else if (o.csv && o.ndelta) {
            fprintf(stderr, "stiction %s: delta: not used by --csv (drop one of them)\n",
                    cmd->name);
            rc = CLI_EXIT_USAGE;
        } else {
            rc = run(cmd->name, &p, &o);
        }
    }
    free(o.delta);
    free(o.sw_tr);
    free(o.sw_er);
    free(o.output);
    return rc;
}
