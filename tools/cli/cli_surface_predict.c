/* stiction surface predict: Greenwood–Williamson friction summation of an
 * asperity model over a summit population (Greenwood & Williamson 1966), versus nominal pressure
 * or separation.  Writes CSV + JSON + a gnuplot PNG of μs and A/An. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "stiction/gw.h"
#include "stiction/model.h"
#include "stiction/surface.h"
#include "stiction/table.h"

typedef struct {
    char *surface, *out, *csv, *png, *table; /* owned */
    int json, wsp, sampled, timing, fill, jobs;
    unsigned long long seen; /* cli_opt_bit() of every option given */
    asp_layer layer;
    cli_gw_pop pop; /* the population's options (its summits are read later) */
    double t_mm;
    double *pressures, *separations;
    int np, ns;
    cli_surface_import imp;
    int out_made; /* --out DIR was created by this run (removed again if it fails) */
} predict_opts;

static const cli_opt opts[] = {
    CLI_GW_POP_OPTS,
    CLI_HEADING("Coating and materials"),
    {"t-mm", "MM", "coating thickness in mm, the same on every summit: each summit's t/R = "
                   "t-mm / R with its own radius R (default 0: uncoated)"},
    {"t-over-R", "X", "refused: every summit has its own radius; give the coating thickness as "
                      "--t-mm MM"},
    {"R", "MM", "refused: the summits' radii come from the map or --summit-radius"},
    CLI_SUBSTRATE_OPTS,
    CLI_COATING_MATERIAL_OPTS,
    CLI_HEADING("Loading"),
    {"pressures", "LIST", "nominal pressures P/An, MPa: a,b,c or start:stop:count"},
    {"separations", "LIST", "separations d/sigma_s from the MEAN SUMMIT HEIGHT (GW)"},
    CLI_HEADING("Asperity model"),
    {"table", "FILE", "asperity response from an FE friction table (`stiction table build`): "
                      "the coating counts, each summit with its own t/R; mu_s with an error band"},
    {"fill", NULL, "with --table: first compute the table's missing points that these loads "
                   "touch (FE runs, added to the table file; resumable), then predict"},
    {"jobs", "N", "with --fill: points computed at once (default: one per core)"},
    {"model", "hertz|wsp", "closed-form asperity model (default wsp; hertz has no friction "
                           "law)"},
    {"layer", "substrate|coating", "layer whose properties the closed-form model uses "
                                   "(default substrate)"},
    CLI_GW_SUM_OPTS,
    CLI_HEADING("Common options"),
    {"out", "DIR", "write DIR/gw.csv, DIR/gw.json, DIR/gw.png"},
    {"csv", "FILE", "write the CSV here"},
    {"png", "FILE", "write the PNG (mu_s and A/An vs nominal pressure) here"},
    {"json", NULL, "print a JSON array, one object per load point"},
    {"timing", NULL, "print set-up and per-load-point wall times to stderr"},
    CLI_CONFIG_HELP,
    CLI_HEADING("Expert numerics"),
    {"sampled", NULL, "evaluate the closed-form model through the table path (sampled + "
                      "interpolated)"},
    {NULL, NULL, NULL},
};

static stc_status set_opt1(predict_opts *o, const char *key, const char *v)
{
    int c = 0;
    stc_status s = STC_OK;
    if (strcmp(key, "surface") == 0) s = cli_set_string(key, v, &o->surface);
    else if (strcmp(key, "table") == 0) s = cli_set_string(key, v, &o->table);
    else if (strcmp(key, "out") == 0) s = cli_set_string(key, v, &o->out);
    else if (strcmp(key, "csv") == 0) s = cli_set_string(key, v, &o->csv);
    else if (strcmp(key, "png") == 0) s = cli_set_string(key, v, &o->png);
    else if (strcmp(key, "json") == 0) s = cli_parse_flag(key, v, &o->json);
    else if (strcmp(key, "sampled") == 0) s = cli_parse_flag(key, v, &o->sampled);
    else if (strcmp(key, "timing") == 0) s = cli_parse_flag(key, v, &o->timing);
    else if (strcmp(key, "fill") == 0) s = cli_parse_flag(key, v, &o->fill);
    else if (strcmp(key, "jobs") == 0) s = cli_parse_int(key, v, 1, 1024, &o->jobs);
    else if (strcmp(key, "model") == 0) s = cli_parse_choice(key, v, "hertz", "wsp", &o->wsp);
    else if (strcmp(key, "layer") == 0) {
        s = cli_parse_choice(key, v, "substrate", "coating", &c);
        o->layer = c ? ASP_LAYER_COATING : ASP_LAYER_SUBSTRATE;
    } else if (strcmp(key, "R") == 0)
        /* the common R (10 mm) is not a summit's: it would change nothing */
        s = stc_error(STC_EINVAL, __FILE__, __LINE__, "R = %s: the summits' radii come from "
                      "the map (--surface) or --summit-radius; R is not used here", v);
    else if (strcmp(key, "t-over-R") == 0)
        /* the common t/R would be taken against the common R (10 mm) */
        s = stc_error(STC_EINVAL, __FILE__, __LINE__, "t-over-R = %s: every summit has its own "
                      "radius, so one t/R is no thickness; give the coating thickness with "
                      "--t-mm MM", v);
    else if (strcmp(key, "pressures") == 0) s = cli_parse_values(key, v, 1, &o->pressures, &o->np);
    else if (strcmp(key, "separations") == 0)
        s = cli_parse_values(key, v, 0, &o->separations, &o->ns);
    else if ((s = cli_gw_pop_opt(&o->pop, key, v)) == STC_EUNSUPPORTED)
        return cli_surface_import_opt(&o->imp, key, v);
    return s;
}

static stc_status set_opt(void *ctx, const char *key, const char *v)
{
    predict_opts *o = ctx;
    stc_status s = set_opt1(o, key, v);
    if (s == STC_OK) o->seen |= cli_opt_bit(opts, key);
    return s;
}

static int given(const predict_opts *o, const char *key) { return (o->seen & cli_opt_bit(opts, key)) != 0; }


/* Cross-option checks: exactly one population and one load range. */
static stc_status check_opts(const predict_opts *o)
{
    stc_status s = cli_gw_pop_check(&o->pop, o->surface, &o->imp);
    if (s != STC_OK) return s;
    static const char *const CLOSED_FORM_KEYS[] = {"model", "layer", "sampled", NULL};
    for (const char *const *k = CLOSED_FORM_KEYS; o->table && *k; k++)
        if (given(o, *k))
            return cli_conflict(*k, "table", "the table is the asperity model; --model, --layer "
                                "and --sampled choose a closed-form one");
    if (o->fill && !o->table)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "--fill needs --table FILE: it "
                         "computes the missing points of that table");
    if (given(o, "jobs") && !o->fill)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "--jobs %d needs --fill: it sets "
                         "how many table points --fill computes at once", o->jobs);
    if ((o->np > 0) == (o->ns > 0))
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "give exactly one of --pressures (MPa) or --separations (units of "
                         "sigma_s)");
    return STC_OK;
}

/* ------------------------------------------------------------ set-up */

/* With --table: the table and its three models at --t-mm (design.m[0] is
 * the main model, the preload's). */
typedef struct {
    tbl_table *t;
    cli_table_design d;
} table_aux;

static stc_status make_model(const predict_opts *o, const stc_params *p, asp_model **out)
{
    asp_model *base = NULL;
    stc_status s = o->wsp ? asp_model_create_wsp(p, o->t_mm, o->layer, &base)
                          : asp_model_create_hertz(p, o->t_mm, o->layer, &base);
    if (s != STC_OK || !o->sampled) {
        *out = base;
        return s;
    }
    s = asp_model_create_sampled(base, NULL, out);
    asp_model_destroy(&base);
    return s;
}

/* Per load point with --table: μs's error band and μs with P at inception. */
typedef struct {
    double mu_s_err, mu_s_slide, mu_s_slope;
} table_extra;

static stc_status run_points(const predict_opts *o, srf_gw *g, const table_aux *x,
                             srf_gw_point *pts, table_extra *ex)
{
    int n = o->np ? o->np : o->ns;
    for (int i = 0; i < n; i++) {
        stc_status s;
        if (x->t)
            s = cli_table_design_at(&x->d, o->np > 0, o->np ? o->pressures[i] : o->separations[i],
                                    &pts[i], &ex[i].mu_s_err, &ex[i].mu_s_slide,
                                    &ex[i].mu_s_slope);
        else
            s = o->np ? srf_gw_at_pressure(g, o->pressures[i], &pts[i])
                      : srf_gw_at_separation(g, o->separations[i], &pts[i]);
        if (s != STC_OK) return s;
    }
    return STC_OK;
}

/* ------------------------------------------------------------ output */

typedef struct {
    const predict_opts *o;
    const table_extra *ex; /* [n] with --table, else NULL */
    const asp_model *m;
    srf_gw_info info;
    asp_model_range range;
    const stc_params *p;
} context;

static const char *DATUM =
    "separation d from the mean summit height (Greenwood & Williamson 1966), in units of sigma_s";

static void json_point(cli_json *j, const context *c, const srf_gw_point *q,
                       const table_extra *e)
{
    double Es = c->info.E_star_MPa;
    cj_obj(j, NULL);
    cj_num(j, "separation_over_sigma_s", q->h);
    cj_num(j, "nominal_pressure_MPa", q->pressure_MPa);
    cj_num(j, "P_over_An_Estar", q->pressure_MPa / Es);
    cj_num(j, "A_over_An", q->area_fraction);
    cj_num(j, "contacts_per_mm2", q->contacts_per_mm2);
    cj_num(j, "Q_over_An_Estar", q->Q_MPa / Es);
    cj_num(j, "mu_s", q->mu_s);
    if (e) {
        cj_num(j, "mu_s_err", e->mu_s_err);
        cj_num(j, "mu_s_P_at_inception", e->mu_s_slide);
        cj_num(j, "mu_s_ux_slope", e->mu_s_slope); /* null: the table does not keep it */
    }
    cj_bool(j, "in_range", !(q->load_fraction_outside > 0.0));
    cj_num(j, "delta_max_over_omega_c", q->delta_max_over_omega_c);
    cj_num(j, "t_over_R_min", q->tR_min);
    cj_num(j, "t_over_R_max", q->tR_max);
    cj_num(j, "load_fraction_outside_model_range", q->load_fraction_outside);
    cj_num(j, "err_P_over_An_MPa", q->err_P_MPa);
    cj_num(j, "err_A_over_An", q->err_A);
    cj_num(j, "err_Q_over_An_MPa", q->err_Q_MPa);
    cj_int(j, "contacts", q->n_contacts);
    cj_int(j, "iterations", q->iterations);
    cj_end_obj(j);
}

static void json_points(FILE *f, const context *c, const srf_gw_point *pts, int n, int meta)
{
    cli_json j;
    cj_init(&j, f);
    if (meta) {
        const srf_gw_info *i = &c->info;
        cj_obj(&j, NULL);
        cj_obj(&j, "parameters");
        cj_str(&j, "model", asp_model_name(c->m));
        cj_str(&j, "layer", asp_model_layer_name(c->m));
        cj_str(&j, "mode", srf_gw_mode_name(i->mode));
        if (c->o->table) {
            cj_str(&j, "table", c->o->table);
            cj_str(&j, "mu_s_definition", "sum Qmax / sum P with P the preload at the "
                                          "separation; mu_s_P_at_inception uses the asperities' "
                                          "P at sliding inception");
            cj_str(&j, "mu_s_ux_slope", "d ln mu_s / d ln ux: per cent of mu_s per per cent "
                                        "of the ux at which every asperity's inception is "
                                        "declared (sum s Qmax / sum Qmax)");
        }
        cj_str(&j, "surface", c->o->surface);
        cj_str(&j, "separation_datum", DATUM);
        cj_num(&j, "coating_t_mm", asp_model_t(c->m));
        cj_str(&j, "note", "R_mm, t_over_R, t_mm below are the common options; summit radii come "
                            "from the population and t from coating_t_mm");
        cj_num(&j, "summit_density_per_mm2", i->eta_per_mm2);
        cj_num(&j, "sigma_s_mm", i->sigma_s_mm);
        cj_num(&j, "summit_radius_mm", i->R_mm);
        cj_int(&j, "summits", i->n_summits);
        cj_int(&j, "summits_excluded", i->n_excluded);
        cj_num(&j, "kde_bandwidth_mm", i->bandwidth_mm);
        cj_num(&j, "E_star_MPa", i->E_star_MPa);
        cj_num(&j, "H_MPa", i->H_MPa);
        cj_str(&j, "H_convention", "H = 2.8 Y of the model's layer (Tabor 1951)");
        cj_num(&j, "plasticity_index", i->plasticity_index);
        cj_num(&j, "model_delta_over_omega_c_min", c->range.w_lo);
        cj_num(&j, "model_delta_over_omega_c_max", c->range.w_hi);
        cj_num(&j, "model_t_over_R_min", c->range.tR_lo);
        cj_num(&j, "model_t_over_R_max", c->range.tR_hi);
        cj_params(&j, c->p);
        cj_end_obj(&j);
        cj_arr(&j, "points");
    } else cj_arr(&j, NULL);
    for (int k = 0; k < n; k++) json_point(&j, c, &pts[k], c->ex ? &c->ex[k] : NULL);
    cj_end_arr(&j);
    if (meta) cj_end_obj(&j);
    cj_done(&j);
}

static void csv_points(FILE *f, const context *c, const srf_gw_point *pts, int n)
{
    const srf_gw_info *i = &c->info;
    fprintf(f, "# stiction surface predict: model %s (%s layer), mode %s, t = %g mm\n",
            asp_model_name(c->m), asp_model_layer_name(c->m), srf_gw_mode_name(i->mode),
            asp_model_t(c->m));
    fprintf(f, "# eta = %g /mm^2, sigma_s = %g mm, R = %g mm, E* = %g MPa, H = 2.8 Y = %g MPa, "
               "psi = %g\n# %s\n", i->eta_per_mm2, i->sigma_s_mm, i->R_mm, i->E_star_MPa,
            i->H_MPa, i->plasticity_index, DATUM);
    fprintf(f, "separation_over_sigma_s,nominal_pressure_MPa,P_over_An_Estar,A_over_An,"
               "contacts_per_mm2,Q_over_An_Estar,mu_s,delta_max_over_omega_c,t_over_R_min,"
               "t_over_R_max,load_fraction_outside_model_range,err_P_over_An_MPa%s\n",
            c->ex ? ",mu_s_err,mu_s_P_at_inception,mu_s_ux_slope" : "");
    for (int k = 0; k < n; k++) {
        const srf_gw_point *q = &pts[k];
        /* a value that does not exist (Q and mu_s of the frictionless hertz
         * model, mu_s where nothing touches) is an empty field */
        const double v[12] = {q->h, q->pressure_MPa, q->pressure_MPa / i->E_star_MPa,
                              q->area_fraction, q->contacts_per_mm2, q->Q_MPa / i->E_star_MPa,
                              q->mu_s, q->delta_max_over_omega_c, q->tR_min, q->tR_max,
                              q->load_fraction_outside, q->err_P_MPa};
        static const char *const fmt[12] = {"%.10g", "%.10g", "%.10g", "%.10g", "%.10g",
                                            "%.10g", "%.10g", "%.6g",  "%.6g",  "%.6g",
                                            "%.6g",  "%.3g"};
        for (int m = 0; m < 12; m++) {
            char b[32];
            fprintf(f, "%s%s", cli_num(b, sizeof b, fmt[m], v[m], ""), m < 11 ? "," : "");
        }
        if (c->ex) {
            char b[3][32];
            fprintf(f, ",%s,%s,%s", cli_num(b[0], sizeof b[0], "%.4g", c->ex[k].mu_s_err, ""),
                    cli_num(b[1], sizeof b[1], "%.10g", c->ex[k].mu_s_slide, ""),
                    cli_num(b[2], sizeof b[2], "%.4g", c->ex[k].mu_s_slope, ""));
        }
        fputc('\n', f);
    }
}

static void table_points(const context *c, const srf_gw_point *pts, int n)
{
    const srf_gw_info *i = &c->info;
    printf("GW summation: model %s (%s layer), %s heights, t = %g mm\n", asp_model_name(c->m),
           asp_model_layer_name(c->m), srf_gw_mode_name(i->mode), asp_model_t(c->m));
    printf("  eta = %g /mm^2, sigma_s = %g mm, R = %g mm, plasticity index psi = %.3g "
           "(E*/H sqrt(sigma_s/R), H = 2.8 Y)\n", i->eta_per_mm2, i->sigma_s_mm, i->R_mm,
           i->plasticity_index);
    printf("  %s\n", DATUM);
    printf("  %8s %12s %11s %11s %8s%s %10s %8s\n", "d/sig_s", "P/An [MPa]", "A/An",
           "N [/mm2]", "mu_s", c->ex ? "   +- err  mu_s(Pi)" : "", "dmax/wc", "outside");
    for (int k = 0; k < n; k++) {
        const srf_gw_point *q = &pts[k];
        char mu[32], dm[32], ex[64] = ""; /* mu_s: n/a for hertz, and where nothing touches */
        if (c->ex) {
            char b[2][32];
            snprintf(ex, sizeof ex, " %9s %9s",
                     cli_num(b[0], sizeof b[0], "%.4f", c->ex[k].mu_s_err, "n/a"),
                     cli_num(b[1], sizeof b[1], "%.4f", c->ex[k].mu_s_slide, "n/a"));
        }
        printf("  %8.4f %12.5g %11.4e %11.4g %8s%s %10s %8.3f\n", q->h, q->pressure_MPa,
               q->area_fraction, q->contacts_per_mm2,
               cli_num(mu, sizeof mu, "%.4f", q->mu_s, "n/a"), ex,
               cli_num(dm, sizeof dm, "%.3g", q->delta_max_over_omega_c, "n/a"),
               q->load_fraction_outside);
    }
    if (c->ex)
        printf("  (mu_s = sum Qmax / sum P with P the preload; +- err: the table's one-standard-"
               "error band; mu_s(Pi): P at sliding inception)\n");
    if (c->ex && isfinite(c->ex[0].mu_s_slope)) {
        printf("  (d ln mu_s / d ln ux where inception is declared, load by load:");
        for (int k = 0; k < n; k++) printf(" %.3f", c->ex[k].mu_s_slope);
        printf("; docs/table-format.md)\n");
    }
    printf("  (outside = share of the load from summits outside the model's range "
           "delta/omega_c in [%g, %g])\n", c->range.w_lo, c->range.w_hi);
}

/* Every output goes to a temporary beside its final path; only when all of
 * them are complete are they renamed, so a failure leaves no file behind. */
typedef void (*writer_fn)(FILE *f, const context *c, const srf_gw_point *pts, int n);

typedef struct {
    const char *key;  /* the option that named the file (for messages) */
    const char *path; /* final path, or NULL: not requested */
    char tmp[4096];   /* temporary, valid when made */
    int made;
} out_file;

static int out_error(const out_file *f, const char *what)
{
    fprintf(stderr, "stiction surface predict: %s = '%s': %s\n", f->key, f->path, what);
    return CLI_EXIT_FAIL;
}

static int tmp_name(out_file *f, const char *suffix)
{
    int k = snprintf(f->tmp, sizeof f->tmp, "%s.tmp%ld%s", f->path, (long)getpid(), suffix);
    return k > 0 && k < (int)sizeof f->tmp ? CLI_EXIT_OK : out_error(f, "path too long");
}

static int write_tmp(out_file *f, const char *suffix, writer_fn w, const context *c,
                     const srf_gw_point *pts, int n)
{
    if (tmp_name(f, suffix) != CLI_EXIT_OK) return CLI_EXIT_FAIL;
    FILE *fp = fopen(f->tmp, "w");
    if (!fp) {
        char why[256];
        snprintf(why, sizeof why, "cannot write there (%s)", strerror(errno));
        return out_error(f, why);
    }
    f->made = 1;
    w(fp, c, pts, n);
    int bad = ferror(fp);
    bad |= fclose(fp) != 0;
    return bad ? out_error(f, "write failed (disk full?)") : CLI_EXIT_OK;
}

static void json_file(FILE *f, const context *c, const srf_gw_point *pts, int n)
{
    json_points(f, c, pts, n, 1);
}

static void csv_writer(FILE *f, const context *c, const srf_gw_point *pts, int n)
{
    csv_points(f, c, pts, n);
}

/* The PNG's title, one clause a line: the summits summed, the asperity
 * response and whether the coating enters it, the population's statistics.
 * A closed-form model takes one layer's properties, so it says that the
 * coating has no effect instead of showing t as if it mattered. */
static void png_title(char *buf, size_t n, const context *c)
{
    const predict_opts *o = c->o;
    const srf_gw_info *i = &c->info;
    stc_material su, co;
    stc_params_materials(c->p, &su, &co);
    const char *name = o->surface ? strrchr(o->surface, '/') : NULL;
    name = name ? name + 1 : o->surface;
    int k = o->surface ? snprintf(buf, n, "Greenwood-Williamson sum over the %d summits of %s "
                                          "(%s heights)", i->n_summits, name,
                                  srf_gw_mode_name(i->mode))
                       : snprintf(buf, n, "Greenwood-Williamson sum over a Gaussian summit "
                                          "population");
    size_t m = k > 0 && (size_t)k < n ? (size_t)k : n - 1;
    const char *tname = o->table ? strrchr(o->table, '/') : NULL;
    tname = tname ? tname + 1 : o->table;
    const stc_material *lay = o->layer == ASP_LAYER_COATING ? &co : &su;
    if (!o->table)
        k = snprintf(buf + m, n - m, "\\nasperity: closed-form %s model with the %s's E = %g GPa, "
                     "Y = %g MPa, ν = %g: the coating is not modelled (t = %g μm has no effect)",
                     asp_model_name(c->m), asp_model_layer_name(c->m), lay->E / 1000, lay->Y,
                     lay->nu, 1000 * asp_model_t(c->m));
    else if (co.E == su.E && co.Y == su.Y && co.nu == su.nu)
        k = snprintf(buf + m, n - m, "\\nasperity: FE friction table %s, uncoated (the coating "
                     "layer is the substrate material: E = %g GPa, Y = %g MPa, ν = %g)", tname,
                     su.E / 1000, su.Y, su.nu);
    else
        k = snprintf(buf + m, n - m, "\\nasperity: FE friction table %s; coating t = %g μm on "
                     "every summit (%s):\\nEco/Esu = %g, Yco = %g MPa on a substrate of "
                     "E = %g GPa, Y = %g MPa, ν = %g", tname, 1000 * asp_model_t(c->m),
                     c->range.coating_aware ? "its own t/R" : "at the table's one t/R",
                     co.E / su.E, co.Y, su.E / 1000, su.Y, su.nu);
    m += k > 0 && (size_t)k < n - m ? (size_t)k : n - m - 1;
    snprintf(buf + m, n - m, "\\nsummits: η = %.4g /mm², σ_s = %.3g μm, mean radius R = %.3g μm; "
             "plasticity index ψ = %.3g", i->eta_per_mm2, 1000 * i->sigma_s_mm,
             1000 * i->R_mm, i->plasticity_index);
    for (char *q = buf; *q; q++) /* a file name's quote or backslash would end the string */
        if (*q == '"' || (*q == '\\' && q[1] != 'n')) *q = '\'';
}

/* gnuplot: μs (left axis, with the table's error band) and A/An (right
 * axis, log) versus P/An (log); A/An alone for a model without friction. */
static int write_png(out_file *f, const char *csv, const context *c)
{
    if (tmp_name(f, ".png") != CLI_EXIT_OK) return CLI_EXIT_FAIL;
    /* create the file first: gnuplot, unable to open it, would write the
     * image to its stdout instead */
    FILE *t = fopen(f->tmp, "wb");
    if (!t) {
        char why[256];
        snprintf(why, sizeof why, "cannot write there (%s)", strerror(errno));
        return out_error(f, why);
    }
    fclose(t);
    f->made = 1;
    cli_plot pl;
    if (cli_plot_open(&pl) != 0) return out_error(f, "cannot run gnuplot");
    FILE *g = pl.g;
    char title[2048];
    png_title(title, sizeof title, c);
    int mu = c->range.has_friction;
    fprintf(g, "set terminal pngcairo enhanced size 1000,650 font ',10'\nset encoding utf8\n"
               "set output '%s'\nset datafile separator ','\nset key top center\n"
               "set logscale x\nset grid\nset xlabel 'nominal pressure P/A_n [MPa]'\n"
               "set title \"%s\" noenhanced\n", f->tmp, title);
    if (mu)
        fprintf(g, "set logscale y2\nset ytics nomirror\nset y2tics\nset format y2 '%%g'\n"
                   "set ylabel 'static friction coefficient μ_s = ΣQ_{max} / ΣP'\n"
                   "set y2label 'real contact area fraction A/A_n'\nplot ");
    else /* hertz: Qmax and μs are not defined */
        fprintf(g, "set logscale y\nset ylabel 'real contact area fraction A/A_n'\n"
                   "set label 'μ_s: not defined (the %s model has no friction law)' at graph "
                   "0.02, graph 0.95\nplot ", asp_model_name(c->m));
    if (c->ex) /* column 13: mu_s_err, the table's one-standard-error band */
        fprintf(g, "'%s' every ::1 using 2:($7-$13):($7+$13) with filledcurves fs transparent "
                   "solid 0.25 lc rgb '#c04000' title 'μ_s ± 1 standard error (table)', ", csv);
    if (mu)
        fprintf(g, "'%s' every ::1 using 2:7 with linespoints lw 2 pt 7 lc rgb '#c04000' "
                   "title 'μ_s', ", csv);
    fprintf(g, "'%s' every ::1 using 2:4 %s with linespoints lw 2 pt 5 lc rgb '#0050a0' "
               "title 'A/A_n%s'\n", csv, mu ? "axes x1y2" : "", mu ? " (right axis)" : "");
    int rc;
    if (cli_plot_close(&pl, f->tmp, &rc) != 0) {
        char why[128];
        snprintf(why, sizeof why, "gnuplot failed (status %d)", rc);
        return out_error(f, why);
    }
    return CLI_EXIT_OK;
}

/* All requested files; the PNG plots from the CSV (a scratch one if no CSV
 * was requested). */
static int write_outputs(const predict_opts *o, const context *c, const srf_gw_point *pts, int n)
{
    char csv[4096], json[4096], png[4096];
    out_file fj = {"out", NULL, "", 0}, fc = {"csv", o->csv, "", 0}, fp = {"png", o->png, "", 0};
    out_file fs = {"png", NULL, "", 0}; /* scratch CSV for the PNG */
    out_file *all[] = {&fj, &fc, &fp};
    int rc = CLI_EXIT_OK;
    if (o->out) { /* checked (and made) before the summation */
        snprintf(json, sizeof json, "%s/gw.json", o->out);
        snprintf(csv, sizeof csv, "%s/gw.csv", o->out);
        snprintf(png, sizeof png, "%s/gw.png", o->out);
        fj.path = json;
        if (!fc.path) fc.path = csv, fc.key = "out";
        if (!fp.path) fp.path = png, fp.key = "out";
    }
    if (fj.path) rc = write_tmp(&fj, "", json_file, c, pts, n);
    if (rc == CLI_EXIT_OK && fc.path) rc = write_tmp(&fc, "", csv_writer, c, pts, n);
    if (rc == CLI_EXIT_OK && fp.path) {
        const char *src = fc.tmp;
        if (!fc.path) {
            fs.key = fp.key;
            fs.path = fp.path;
            rc = write_tmp(&fs, ".csv", csv_writer, c, pts, n);
            src = fs.tmp;
        }
        if (rc == CLI_EXIT_OK) rc = write_png(&fp, src, c);
    }
    if (fs.made) remove(fs.tmp);
    const char *tmp[3], *dst[3];
    for (int k = 0; k < 3; k++) tmp[k] = all[k]->made ? all[k]->tmp : NULL, dst[k] = all[k]->path;
    if (rc != CLI_EXIT_OK) {
        for (int k = 0; k < 3; k++)
            if (tmp[k]) remove(tmp[k]);
        return rc;
    }
    /* no partial output: the files placed before a failed rename go too */
    int bad = cli_place_all(3, tmp, dst);
    if (bad >= 0) {
        char why[4400];
        snprintf(why, sizeof why, "cannot rename %s into place (%s)", tmp[bad], strerror(errno));
        rc = out_error(all[bad], why);
    }
    return rc;
}

static void warn_outside(const char *cmd, const context *c, const srf_gw_point *pts, int n)
{
    double worst = 0.0;
    int k = 0;
    for (int i = 0; i < n; i++)
        if (pts[i].load_fraction_outside > worst) worst = pts[i].load_fraction_outside, k = i;
    if (worst > CLI_OUTSIDE_WARN)
        fprintf(stderr, "stiction %s: warning: up to %.1f %% of the load (at P/An = %.4g MPa) "
                "comes from summits outside the model's range (delta/omega_c in [%g, %g], "
                "t/R in [%g, %g]): those points are partly extrapolated\n", cmd,
                cli_percent_up(worst), pts[k].pressure_MPa, c->range.w_lo, c->range.w_hi,
                c->range.tR_lo, c->range.tR_hi);
}

static void report_timing(const srf_gw *g, int n, double setup, double points)
{
    srf_gw_info i;
    srf_gw_get_info(g, &i);
    fprintf(stderr, "timing: set-up %.4f s (map, summits, model); %d load points in %.4f s = "
                    "%.3g s per point; %s, %d summits\n", setup, n, points, points / n,
            srf_gw_mode_name(i.mode), i.n_summits);
}

static const char *USAGE =
    "(--surface FILE | --summit-density ETA --summit-radius MM --sigma-s MM)\n"
    "       (--pressures LIST | --separations LIST) [--table FILE [--fill] | --model hertz|wsp]\n"
    "       [--t-mm MM] [materials] [--mode statistical|deterministic] [--out DIR] [--json]\n\n"
    "Greenwood-Williamson summation: N, P, A, Qmax summed over the summits; mu_s = sum Qmax /\n"
    "sum P (never a mean of asperity mu_s).  Separations are measured from the MEAN SUMMIT\n"
    "HEIGHT in units of sigma_s.  The asperity response: an FE friction table (--table; the\n"
    "coating counts, mu_s comes with an error band), or a closed-form model with ONE layer's\n"
    "properties (the coating then enters only through t/R).  The coating is --t-mm MM thick\n"
    "on every summit, each summit with its own radius and so its own t/R (--t-over-R is\n"
    "refused).  The share of the load from summits outside the model's range is\n"
    "printed (\"outside\"; JSON: in_range) and warned about on stderr above " CLI_OUTSIDE_WARN_TEXT ".";

int cli_surface_predict(const cli_cmd *cmd, int argc, char **argv)
{
    predict_opts o = {0};
    stc_params p;
    table_aux aux = {0};
    table_extra *ex = NULL;
    asp_model *m = NULL;
    srf_gw *g = NULL;
    srf_gw_point *pts = NULL;
    int done, rc;
    o.pop.rule = SRF_RULE_8;
    o.wsp = 1;
    o.imp.zscale = 1.0;
    stc_params_default(&p);
    rc = cli_parse(cmd->name, USAGE, argc, argv, opts, &p, set_opt, &o, &done);
    if (rc != CLI_EXIT_OK || done) goto out;
    double t0 = cli_now_s();
    stc_status s = check_opts(&o);
    /* a bad --out is refused before any work is done */
    if (s == STC_OK && o.out && (rc = cli_out_dir(cmd->name, o.out, &o.out_made)) != CLI_EXIT_OK)
        goto out;
    o.t_mm = p.t_mm; /* 0 unless --t-mm: uncoated */
    cli_gw_pop pop = o.pop; /* its summits, read here, freed below */
    if (s == STC_OK) s = cli_gw_pop_load(&pop, o.surface, &o.imp, &p);
    if (s == STC_OK && o.fill) {
        int nl = o.np ? o.np : o.ns;
        char prov[1024];
        cli_command_line(prov, sizeof prov, cmd->name, argc, argv);
        cli_table_fill_job job = {o.table, prov, &pop, &p, &o.t_mm,
                                  o.np ? o.pressures : o.separations, nl, o.np > 0};
        s = cli_table_fill(cmd->name, &job, 1, o.jobs);
    }
    if (s == STC_OK && o.table) {
        s = tbl_read(o.table, &aux.t);
        if (s == STC_OK) s = cli_table_design_create(aux.t, &p, o.t_mm, &pop, &aux.d);
        s = cli_name_error(s, "table", o.table);
        if (s == STC_OK) m = aux.d.m[0], g = aux.d.g[0]; /* owned by aux */
    } else if (s == STC_OK) {
        s = make_model(&o, &p, &m);
        if (s == STC_OK) s = cli_gw_pop_sum(&pop, m, &g);
    }
    cli_gw_pop_free(&pop);
    int n = o.np ? o.np : o.ns;
    if (s == STC_OK && (!(pts = calloc((size_t)n, sizeof *pts)) ||
                        !(ex = calloc((size_t)n, sizeof *ex))))
        s = stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    double t1 = cli_now_s();
    if (s == STC_OK) s = run_points(&o, g, &aux, pts, ex);
    double t2 = cli_now_s();
    if (s != STC_OK) {
        rc = cli_fail(cmd->name, s);
        goto out;
    }
    if (o.timing) report_timing(g, n, t1 - t0, t2 - t1);
    context c;
    c.o = &o;
    c.ex = o.table ? ex : NULL;
    c.m = m;
    c.p = &p;
    srf_gw_get_info(g, &c.info);
    asp_model_get_range(m, &c.range);
    rc = write_outputs(&o, &c, pts, n);
    if (rc == CLI_EXIT_OK) {
        if (o.json) json_points(stdout, &c, pts, n, 0);
        else table_points(&c, pts, n);
        warn_outside(cmd->name, &c, pts, n);
        int nf = 0;
        if (aux.t) tbl_count(aux.t, NULL, &nf, NULL);
        if (nf > 0)
            fprintf(stderr, "stiction %s: warning: %d of the table's points failed (`stiction table "
                    "info %s` gives the reasons); the interpolation runs over its done points "
                    "around them\n", cmd->name, nf, o.table);
    }
out:
    if (rc != CLI_EXIT_OK && o.out_made) rmdir(o.out); /* empty: outputs go in by rename */
    free(pts);
    free(ex);
    free(o.table);
    if (aux.t) m = NULL, g = NULL; /* the design's */
    cli_table_design_free(&aux.d);
    tbl_destroy(&aux.t);
    free(o.pressures);
    free(o.separations);
    free(o.surface);
    free(o.out);
    free(o.csv);
    free(o.png);
    cli_surface_import_free(&o.imp);
    srf_gw_destroy(&g);
    asp_model_destroy(&m);
    return rc;
}
