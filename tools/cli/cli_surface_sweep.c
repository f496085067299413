/* stiction surface sweep: the surface μs and A/An of one summit population
 * for every coating of a design grid (thickness × Eco/Esu) on an FE
 * friction table, at the same nominal pressures: which coating gives the
 * friction wanted.  The summits are read once; each coating is the table's
 * model summed over them (as `surface predict --table` does for one). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "stiction/gw.h"
#include "stiction/surface.h"
#include "stiction/table.h"

typedef struct {
    char *surface, *table, *out; /* owned */
    int json, fill, jobs;
    double Y_su; /* --Y-su, MPa; 0: E-su / E-over-Y */
    cli_gw_pop pop; /* the population's options (its summits are read later) */
    double *t_mm, *E_ratio, *pressures; /* owned lists */
    int nt, nE, np;
    cli_surface_import imp;
    int out_made;
} sweep_opts;

static const cli_opt opts[] = {
    CLI_GW_POP_OPTS,
    CLI_HEADING("The designs"),
    {"table", "FILE", "FE friction table (`stiction table build`) of the coating's family"},
    {"t-mm", "LIST", "coating thicknesses in mm (> 0): a,b,c or start:stop:count; each "
                     "summit's t/R = t-mm / R with its own radius"},
    {"E-ratio", "LIST", "Eco/Esu values (> 0; default 1): the table's family holds E/Y of "
                        "the coating, so its yield strength is Eco / (E/Y)_co"},
    {"t-over-R", "X", "refused: every summit has its own radius; give --t-mm"},
    {"R", "MM", "refused: the summits' radii come from the map or --summit-radius"},
    {"Y-co", "MPA", "refused: the coating's yield strength follows from Eco/Esu and the "
                    "table's family"},
    {"E-su", "MPA", "Young's modulus of the substrate (default 200000)"},
    {"E-over-Y", "X", "E/Y of the substrate (default 1000; the coating's is the table's)"},
    {"Y-su", "MPA", "yield strength of the substrate (overrides E-over-Y)"},
    {"nu", "X", "Poisson's ratio (default 0.32)"},
    {"nu-co", "X", "Poisson's ratio of the coating (default: --nu)"},
    {"pressures", "LIST", "nominal pressures P/An, MPa: a,b,c or start:stop:count"},
    {"fill", NULL, "first compute the table's missing points that these designs and loads "
                   "touch (FE runs, added to the table file; resumable)"},
    {"jobs", "N", "with --fill: points computed at once (default: one per core)"},
    CLI_GW_SUM_OPTS,
    CLI_HEADING("Common options"),
    {"out", "DIR", "write DIR/sweep.csv, DIR/sweep.json and DIR/sweep.png (mu_s against the "
                   "thickness, one line per Eco/Esu and pressure)"},
    {"json", NULL, "print JSON: the designs, each with its load points"},
    CLI_CONFIG_HELP,
    {NULL, NULL, NULL},
};

static stc_status set_opt(void *ctx, const char *key, const char *v)
{
    sweep_opts *o = ctx;
    stc_status s = STC_OK;
    if (!strcmp(key, "surface")) s = cli_set_string(key, v, &o->surface);
    else if (!strcmp(key, "table")) s = cli_set_string(key, v, &o->table);
    else if (!strcmp(key, "out")) s = cli_set_string(key, v, &o->out);
    else if (!strcmp(key, "json")) s = cli_parse_flag(key, v, &o->json);
    else if (!strcmp(key, "fill")) s = cli_parse_flag(key, v, &o->fill);
    else if (!strcmp(key, "t-mm")) s = cli_parse_values(key, v, 1, &o->t_mm, &o->nt);
    else if (!strcmp(key, "E-ratio")) s = cli_parse_values(key, v, 1, &o->E_ratio, &o->nE);
    else if (!strcmp(key, "pressures")) s = cli_parse_values(key, v, 1, &o->pressures, &o->np);
    else if (!strcmp(key, "jobs")) s = cli_parse_int(key, v, 1, 1024, &o->jobs);
    else if (!strcmp(key, "Y-su")) {
        s = stc_parse_double(key, v, &o->Y_su);
        if (s == STC_OK) s = stc_check_range(key, o->Y_su, 0.0, 0, INFINITY, 0);
    } else if (!strcmp(key, "t-over-R") || !strcmp(key, "R") || !strcmp(key, "Y-co"))
        s = stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = %s: not an option of a sweep (%s)",
                      key, v, key[0] == 'Y' ? "the coating's yield strength follows from "
                      "Eco/Esu and the table's family" : "give the coating thickness as "
                      "--t-mm, each summit having its own radius");
    else if ((s = cli_gw_pop_opt(&o->pop, key, v)) == STC_EUNSUPPORTED)
        return cli_surface_import_opt(&o->imp, key, v);
    return s;
}

static stc_status check_opts(const sweep_opts *o)
{
    stc_status s = cli_gw_pop_check(&o->pop, o->surface, &o->imp);
    if (s != STC_OK) return s;
    if (!o->table)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "table: required (--table FILE, an FE "
                         "friction table of the coating's family)");
    if (!o->nt)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "t-mm: required (--t-mm LIST, the "
                         "coating thicknesses in mm)");
    if (!o->np)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "pressures: required (--pressures "
                         "LIST, MPa)");
    if (o->jobs && !o->fill)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "--jobs %d needs --fill: it sets "
                         "how many table points --fill computes at once", o->jobs);
    return STC_OK;
}

/* One design's materials: Eco/Esu = E, the coating's Y from the table's
 * family (its E/Y held along the Eco/Esu axis), the substrate's as given. */
static stc_status design_params(const tbl_table *t, const stc_params *base, double Y_su,
                                double E, stc_params *p)
{
    tbl_family f;
    tbl_get_family(t, &f);
    *p = *base;
    p->E_ratio = E;
    p->Y_su = Y_su > 0.0 ? Y_su : base->E_su / base->E_over_Y;
    p->Y_co = E * base->E_su / f.E_over_Y_co;
    stc_status s = stc_params_validate(p);
    return s == STC_OK ? tbl_check_params(t, p) : s;
}

typedef struct {
    double t_mm, E_ratio, Y_co;
    srf_gw_point *pt;       /* [np] */
    double *mu_err, *mu_pi, *mu_slope; /* [np] */
} design;

static void json_out(FILE *f, const sweep_opts *o, const design *d, int nd, const srf_gw_info *gi)
{
    cli_json j;
    cj_init(&j, f);
    cj_obj(&j, NULL);
    cj_obj(&j, "parameters");
    cj_str(&j, "table", o->table);
    cj_str(&j, "surface", o->surface);
    cj_str(&j, "mode", srf_gw_mode_name(gi->mode));
    cj_int(&j, "summits", gi->n_summits);
    cj_num(&j, "summit_density_per_mm2", gi->eta_per_mm2);
    cj_num(&j, "sigma_s_mm", gi->sigma_s_mm);
    cj_num(&j, "summit_radius_mm", gi->R_mm);
    cj_str(&j, "mu_s_definition", "sum Qmax / sum P with P the preload; mu_s_err the table's "
                                  "one-standard-error band; mu_s_P_at_inception with P at "
                                  "sliding inception");
    cj_end_obj(&j);
    cj_arr(&j, "designs");
    for (int k = 0; k < nd; k++) {
        cj_obj(&j, NULL);
        cj_num(&j, "t_mm", d[k].t_mm);
        cj_num(&j, "E_ratio", d[k].E_ratio);
        cj_num(&j, "Y_co_MPa", d[k].Y_co);
        cj_arr(&j, "points");
        for (int i = 0; i < o->np; i++) {
            const srf_gw_point *q = &d[k].pt[i];
            cj_obj(&j, NULL);
            cj_num(&j, "nominal_pressure_MPa", q->pressure_MPa);
            cj_num(&j, "mu_s", q->mu_s);
            cj_num(&j, "mu_s_err", d[k].mu_err[i]);
            cj_num(&j, "mu_s_P_at_inception", d[k].mu_pi[i]);
            cj_num(&j, "mu_s_ux_slope", d[k].mu_slope[i]);
            cj_num(&j, "A_over_An", q->area_fraction);
            cj_num(&j, "contacts_per_mm2", q->contacts_per_mm2);
            cj_num(&j, "separation_over_sigma_s", q->h);
            cj_num(&j, "delta_max_over_omega_c", q->delta_max_over_omega_c);
            cj_num(&j, "t_over_R_min", q->tR_min);
            cj_num(&j, "t_over_R_max", q->tR_max);
            cj_num(&j, "load_fraction_outside_model_range", q->load_fraction_outside);
            cj_bool(&j, "in_range", !(q->load_fraction_outside > 0.0));
            cj_end_obj(&j);
        }
        cj_end_arr(&j);
        cj_end_obj(&j);
    }
    cj_end_arr(&j);
    cj_end_obj(&j);
    cj_done(&j);
}

static void csv_out(FILE *f, const sweep_opts *o, const design *d, int nd)
{
    fprintf(f, "t_mm,E_ratio,Y_co_MPa,nominal_pressure_MPa,mu_s,mu_s_err,mu_s_P_at_inception,"
               "A_over_An,contacts_per_mm2,delta_max_over_omega_c,"
               "load_fraction_outside_model_range\n");
    for (int k = 0; k < nd; k++)
        for (int i = 0; i < o->np; i++) {
            const srf_gw_point *q = &d[k].pt[i];
            fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g,%.4g,%.10g,%.10g,%.10g,%.6g,%.6g\n",
                    d[k].t_mm, d[k].E_ratio, d[k].Y_co, q->pressure_MPa, q->mu_s,
                    d[k].mu_err[i], d[k].mu_pi[i], q->area_fraction, q->contacts_per_mm2,
                    q->delta_max_over_omega_c, q->load_fraction_outside);
        }
}

static void text_out(const sweep_opts *o, const design *d, int nd, const srf_gw_info *gi)
{
    char who[64];
    if (o->surface) snprintf(who, sizeof who, "%d summits (%s heights)", gi->n_summits,
                             srf_gw_mode_name(gi->mode));
    else snprintf(who, sizeof who, "Gaussian summit heights");
    printf("coating designs on %s: %s, eta = %g /mm^2, sigma_s = %g mm, R = %g mm\n", o->table,
           who, gi->eta_per_mm2, gi->sigma_s_mm, gi->R_mm);
    for (int block = 0; block < 2; block++) {
        printf(block ? "  A/An\n" : "  mu_s +- the table's one standard error\n");
        printf("  %9s %8s %9s", "t [um]", "Eco/Esu", "Yco [MPa]");
        for (int i = 0; i < o->np; i++) {
            char h[32];
            snprintf(h, sizeof h, "%g MPa", o->pressures[i]);
            printf(" %16s", h);
        }
        putchar('\n');
        int marked = 0;
        for (int k = 0; k < nd; k++) {
            printf("  %9.4g %8.4g %9.4g", 1000 * d[k].t_mm, d[k].E_ratio, d[k].Y_co);
            for (int i = 0; i < o->np; i++) {
                const srf_gw_point *q = &d[k].pt[i];
                char c[48];
                int out = q->load_fraction_outside > CLI_OUTSIDE_WARN;
                marked |= out;
                if (block) snprintf(c, sizeof c, "%.4e", q->area_fraction);
                else snprintf(c, sizeof c, "%.3f +- %.3f", q->mu_s, d[k].mu_err[i]);
                /* the mark, or a blank that keeps the columns (none at the end) */
                printf(" %15s%s", c, out ? "*" : i + 1 < o->np ? " " : "");
            }
            putchar('\n');
        }
        if (marked && block)
            printf("  (*: more than %.0f %% of the load from summits outside the table's range)"
                   "\n", 100 * CLI_OUTSIDE_WARN);
    }
    printf("  (mu_s = sum Qmax / sum P, P the preload; Yco: the table's family holds the "
           "coating's E/Y)\n");
}

/* The design chart: mu_s with its band against the thickness, one line per
 * Eco/Esu (its colour) and pressure (its dash and marker); against Eco/Esu,
 * one line per pressure, when there is one thickness.  Drawn by gnuplot
 * into the (existing, empty) file tmp. */
static stc_status png_out(const char *tmp, const sweep_opts *o, const design *d, int nE)
{
    int by_E = o->nt == 1 && nE > 1;
    char name[512];
    const char *t = strrchr(o->table, '/');
    snprintf(name, sizeof name, "%s", t ? t + 1 : o->table);
    for (char *q = name; *q; q++) /* a quote would end gnuplot's string */
        if (*q == '\'' || *q == '"' || *q == '\\') *q = '_';
    cli_plot pl;
    if (cli_plot_open(&pl) != 0)
        return stc_error(STC_EIO, __FILE__, __LINE__, "out = '%s': cannot run gnuplot", o->out);
    FILE *g = pl.g;
    fprintf(g, "set terminal pngcairo enhanced size 1000,650 font ',10'\nset encoding utf8\n"
               "set output '%s'\nset grid\nset key outside right\n"
               "set xlabel '%s'\nset ylabel 'static friction coefficient μ_s = ΣQ_{max} / ΣP'\n"
               "set title 'coating designs on %s: surface μ_s ± the table''s one standard error"
               "%s' noenhanced\nset offsets graph 0.05, graph 0.05, 0, 0\nplot ",
            tmp, by_E ? "E_{co} / E_{su}" : "coating thickness t [μm]", name,
            by_E ? "" : "; one line per Eco/Esu and pressure");
    int nl = by_E ? 1 : nE, nx = by_E ? nE : o->nt;
    /* markers: filled circle, square, triangles, diamond, then their open forms;
     * with the five dash types, ten pressures drawn apart */
    static const int pts[10] = {7, 5, 9, 11, 13, 6, 4, 8, 10, 12};
    for (int l = 0; l < nl; l++)
        for (int i = 0; i < o->np; i++) {
            if (by_E) fprintf(g, "%s'-' using 1:2:3 with yerrorlines lw 2 title '%g MPa'",
                              l + i ? ", " : "", o->pressures[i]);
            else fprintf(g, "%s'-' using 1:2:3 with yerrorlines lw 2 lc %d dt %d pt %d title "
                         "'E_{co}/E_{su} %g, %g MPa'", l + i ? ", " : "", l % 8 + 1, i % 5 + 1,
                         pts[i % 10], d[l].E_ratio, o->pressures[i]);
        }
    fputc('\n', g);
    for (int l = 0; l < nl; l++)
        for (int i = 0; i < o->np; i++) {
            for (int x = 0; x < nx; x++) {
                const design *e = by_E ? &d[x] : &d[x * nE + l];
                fprintf(g, "%.10g %.10g %.10g\n", by_E ? e->E_ratio : 1000 * e->t_mm,
                        e->pt[i].mu_s, e->mu_err[i]);
            }
            fputs("e\n", g);
        }
    int rc;
    if (cli_plot_close(&pl, tmp, &rc) != 0)
        return stc_error(STC_EIO, __FILE__, __LINE__, "out = '%s': gnuplot failed (status %d)",
                         o->out, rc);
    return STC_OK;
}

/* DIR/sweep.csv, DIR/sweep.json and DIR/sweep.png, each written beside its
 * name and renamed once all three are complete. */
static stc_status write_files(const sweep_opts *o, const design *d, int nd, int nE,
                              const srf_gw_info *gi)
{
    static const char *const ext[3] = {"csv", "json", "png"};
    char path[3][4096], tmp[3][4200];
    stc_status s = STC_OK;
    int made[3] = {0, 0, 0};
    for (int k = 0; k < 3 && s == STC_OK; k++) {
        snprintf(path[k], sizeof path[k], "%s/sweep.%s", o->out, ext[k]);
        snprintf(tmp[k], sizeof tmp[k], "%s.tmp%ld", path[k], (long)getpid());
        FILE *f = fopen(tmp[k], "w");
        if (!f) {
            s = stc_error(STC_EIO, __FILE__, __LINE__, "out = '%s': cannot write %s (%s)",
                          o->out, tmp[k], strerror(errno));
            break;
        }
        made[k] = 1;
        if (k == 1) json_out(f, o, d, nd, gi);
        else if (k == 0) csv_out(f, o, d, nd);
        int bad = ferror(f);
        bad |= fclose(f) != 0;
        if (bad)
            s = stc_error(STC_EIO, __FILE__, __LINE__, "out = '%s': write failed (disk full?)",
                          o->out);
        else if (k == 2) s = png_out(tmp[k], o, d, nE);
    }
    const char *tp[3], *pp[3];
    for (int k = 0; k < 3; k++) tp[k] = made[k] ? tmp[k] : NULL, pp[k] = path[k];
    if (s != STC_OK) {
        for (int k = 0; k < 3; k++)
            if (tp[k]) remove(tp[k]);
        return s;
    }
    /* no partial output: what was placed before a failed rename goes too */
    int bad = cli_place_all(3, tp, pp);
    if (bad >= 0)
        s = stc_error(STC_EIO, __FILE__, __LINE__, "out = '%s': cannot rename %s (%s)", o->out,
                      tmp[bad], strerror(errno));
    return s;
}

static const char *USAGE =
    "(--surface FILE | --summit-density ETA --summit-radius MM --sigma-s MM)\n"
    "       --table FILE --t-mm LIST [--E-ratio LIST] --pressures LIST [--fill] [materials]\n"
    "       [--mode statistical|deterministic] [--out DIR] [--json]\n\n"
    "Coating design sweep: the surface mu_s (with the table's error band) and A/An at each\n"
    "nominal pressure for every coating thickness x Eco/Esu, one summit population, one FE\n"
    "friction table.  Each design is what `surface predict --table FILE --t-mm T\n"
    "--E-ratio E --Y-co Yco` gives with Yco = E Esu / (E/Y)_co: along Eco/Esu the coating's\n"
    "E/Y is the table's family's, so a stiffer coating is proportionally harder.  A value\n"
    "with more than " CLI_OUTSIDE_WARN_TEXT " of its load from summits outside the table's range is marked *.";

int cli_surface_sweep(const cli_cmd *cmd, int argc, char **argv)
{
    sweep_opts o = {0};
    stc_params p;
    tbl_table *t = NULL;
    design *d = NULL;
    stc_params *dp = NULL;
    double *dt = NULL;
    int done, rc, nd = 0;
    o.pop.rule = SRF_RULE_8;
    o.imp.zscale = 1.0;
    stc_params_default(&p);
    rc = cli_parse(cmd->name, USAGE, argc, argv, opts, &p, set_opt, &o, &done);
    if (rc != CLI_EXIT_OK || done) goto out;
    stc_status s = check_opts(&o);
    if (s == STC_OK && o.out && (rc = cli_out_dir(cmd->name, o.out, &o.out_made)) != CLI_EXIT_OK)
        goto out;
    double one = 1.0;
    const double *E = o.nE ? o.E_ratio : &one;
    int nE = o.nE ? o.nE : 1;
    if (s == STC_OK && (long)o.nt * nE > 100000)
        s = stc_error(STC_EINVAL, __FILE__, __LINE__, "%d t-mm x %d E-ratio = %ld designs: at "
                      "most 100000", o.nt, nE, (long)o.nt * nE);
    nd = s == STC_OK ? o.nt * nE : 0;
    if (s == STC_OK && (!(d = calloc((size_t)nd, sizeof *d)) ||
                        !(dp = calloc((size_t)nd, sizeof *dp)) ||
                        !(dt = calloc((size_t)nd, sizeof *dt))))
        s = stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    if (s == STC_OK) s = cli_name_error(tbl_read(o.table, &t), "table", o.table);
    for (int a = 0; a < o.nt && s == STC_OK; a++)
        for (int b = 0; b < nE && s == STC_OK; b++) {
            int k = a * nE + b;
            s = cli_name_error(design_params(t, &p, o.Y_su, E[b], &dp[k]), "table", o.table);
            dt[k] = d[k].t_mm = o.t_mm[a];
            d[k].E_ratio = E[b];
            d[k].Y_co = dp[k].Y_co;
            if (s == STC_OK && (!(d[k].pt = calloc((size_t)o.np, sizeof *d[k].pt)) ||
                                !(d[k].mu_err = calloc((size_t)o.np, sizeof(double))) ||
                                !(d[k].mu_pi = calloc((size_t)o.np, sizeof(double))) ||
                                !(d[k].mu_slope = calloc((size_t)o.np, sizeof(double)))))
                s = stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
        }
    if (s == STC_OK) s = cli_gw_pop_load(&o.pop, o.surface, &o.imp, &p);
    if (s == STC_OK && o.fill) {
        char prov[1024];
        cli_command_line(prov, sizeof prov, cmd->name, argc, argv);
        cli_table_fill_job job = {o.table, prov, &o.pop, dp, dt, o.pressures, o.np, 1};
        s = cli_table_fill(cmd->name, &job, nd, o.jobs);
        if (s == STC_OK) { /* the filled table */
            tbl_destroy(&t);
            s = cli_name_error(tbl_read(o.table, &t), "table", o.table);
        }
    }
    srf_gw_info gi = {0};
    for (int k = 0; k < nd && s == STC_OK; k++) {
        cli_table_design td;
        s = cli_name_error(cli_table_design_create(t, &dp[k], d[k].t_mm, &o.pop, &td), "table",
                           o.table);
        if (s != STC_OK) break; /* td freed */
        if (k == 0) srf_gw_get_info(td.g[0], &gi);
        for (int i = 0; i < o.np && s == STC_OK; i++)
            s = cli_table_design_at(&td, 1, o.pressures[i], &d[k].pt[i], &d[k].mu_err[i],
                                    &d[k].mu_pi[i], &d[k].mu_slope[i]);
        cli_table_design_free(&td);
    }
    if (s == STC_OK && o.out) s = write_files(&o, d, nd, nE, &gi);
    if (s != STC_OK) {
        rc = cli_fail(cmd->name, s);
        goto out;
    }
    if (o.json) json_out(stdout, &o, d, nd, &gi);
    else text_out(&o, d, nd, &gi);
    double worst = 0.0;
    for (int k = 0; k < nd; k++)
        for (int i = 0; i < o.np; i++) worst = fmax(worst, d[k].pt[i].load_fraction_outside);
    if (worst > CLI_OUTSIDE_WARN)
        fprintf(stderr, "stiction %s: warning: up to %.1f %% of the load comes from summits "
                "outside the table's range (marked *): those values are partly extrapolated\n",
                cmd->name, cli_percent_up(worst));
out:
    if (rc != CLI_EXIT_OK && o.out_made) rmdir(o.out);
    for (int k = 0; d && k < nd; k++) free(d[k].pt), free(d[k].mu_err), free(d[k].mu_pi),
                                    free(d[k].mu_slope);
    free(d);
    free(dp);
    free(dt);
    tbl_destroy(&t);
    cli_gw_pop_free(&o.pop);
    free(o.surface), free(o.table), free(o.out);
    free(o.t_mm), free(o.E_ratio), free(o.pressures);
    cli_surface_import_free(&o.imp);
    return rc;
}
