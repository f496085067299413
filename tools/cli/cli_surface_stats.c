/* stiction surface stats: height, spectral and summit statistics of a map,
 * printed next to random-process theory (Nayak 1971, McCool 1986). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "stiction/surface.h"

typedef struct {
    char *in; /* owned */
    int rule, json;
    cli_surface_import imp;
} stats_opts;

static const cli_opt opts[] = {
    CLI_HEADING("Surface"),
    {"in", "FILE", "surface file (HDF5 from `surface synth`; or a leading FILE argument)"},
    {"rule", "8|4", "summit rule: 8 or 4 neighbours, periodic edges (default 8)"},
    CLI_SURFACE_IMPORT_OPTS,
    CLI_HEADING("Common options"),
    {"json", NULL, "print JSON"},
    CLI_CONFIG_HELP,
    {NULL, NULL, NULL},
};

static stc_status set_opt(void *ctx, const char *key, const char *v)
{
    stats_opts *o = ctx;
    if (strcmp(key, "in") == 0) return cli_set_string(key, v, &o->in);
    else if (strcmp(key, "json") == 0) return cli_parse_flag(key, v, &o->json);
    else if (strcmp(key, "rule") == 0) {
        if (strcmp(v, "8") == 0) o->rule = SRF_RULE_8;
        else if (strcmp(v, "4") == 0) o->rule = SRF_RULE_4;
        else return stc_error(STC_EINVAL, __FILE__, __LINE__, "rule = '%s': must be 8 or 4", v);
    } else return cli_surface_import_opt(&o->imp, key, v);
    return STC_OK;
}

static void print_json(const stats_opts *o, const srf_map *m, const srf_stats *s)
{
    cli_json j;
    cj_init(&j, stdout);
    cj_obj(&j, NULL);
    cj_str(&j, "file", o->in);
    cj_int(&j, "nx", m->nx);
    cj_int(&j, "ny", m->ny);
    cj_num(&j, "lx_mm", m->lx);
    cj_num(&j, "ly_mm", m->ly);
    cj_int(&j, "rule", s->rule);
    cj_num(&j, "sigma_mm", s->sigma);
    cj_num(&j, "skewness", s->skewness);
    cj_num(&j, "kurtosis", s->kurtosis);
    cj_num(&j, "m0", s->m0);
    cj_num(&j, "m2", s->m2);
    cj_num(&j, "m4", s->m4);
    cj_num(&j, "m2_x", s->m20);
    cj_num(&j, "m2_y", s->m02);
    cj_num(&j, "m4_x", s->m40);
    cj_num(&j, "m4_y", s->m04);
    cj_num(&j, "alpha", s->alpha);
    cj_int(&j, "summits", s->summits);
    cj_num(&j, "summit_area_mm2", s->area_mm2);
    cj_num(&j, "summit_density_per_mm2", s->summit_density_per_mm2);
    cj_num(&j, "summit_density_nayak_per_mm2", s->summit_density_nayak_per_mm2);
    cj_num(&j, "mean_summit_radius_mm", s->mean_summit_radius_mm);
    cj_num(&j, "mean_summit_radius_mccool_mm", s->mean_summit_radius_mccool_mm);
    cj_num(&j, "sigma_s_mm", s->sigma_s_mm);
    cj_num(&j, "sigma_s_mccool_mm", s->sigma_s_mccool_mm);
    cj_num(&j, "summit_mean_offset_mm", s->summit_mean_offset_mm);
    cj_num(&j, "summit_mean_offset_mccool_mm", s->summit_mean_offset_mccool_mm);
    cj_bool(&j, "periodic", m->periodic);
    cj_str(&j, "moments_method", s->moments_fd ? "finite differences (non-periodic map)" : "FFT");
    cj_str(&j, "moments", "profile moments averaged over directions: m2 = (m2_x + m2_y)/2, "
                          "m4 = 3(m4_x + 2 m22 + m4_y)/8");
    cj_str(&j, "curvature", "mean curvature -(z_xx + z_yy)/2, radius = 1/mean curvature");
    cj_end_obj(&j);
    cj_done(&j);
}

/* One table row; a value that does not exist (σs of a single summit, the
 * radius when no summit was found) reads "n/a", never "nan". */
static void row(const char *name, double measured, double theory, const char *unit)
{
    char mv[24], tv[24], dv[24];
    double diff = theory != 0 ? 100 * (measured / theory - 1) : NAN;
    printf("  %-28s %14s %14s %10s  %s\n", name, cli_num(mv, sizeof mv, "%.6g", measured, "n/a"),
           cli_num(tv, sizeof tv, "%.6g", theory, "-"),
           cli_num(dv, sizeof dv, "%+.2f %%", diff, ""), unit);
}

static void print_table(const stats_opts *o, const srf_map *m, const srf_stats *s)
{
    printf("%s: %d x %d points, %g x %g mm, summits by the %d-neighbour rule\n", o->in, m->nx,
           m->ny, m->lx, m->ly, s->rule);
    printf("  sigma %.6g mm, skewness %.4f, kurtosis %.4f\n", s->sigma, s->skewness, s->kurtosis);
    printf("  m0 %.6g mm^2, m2 %.6g, m4 %.6g mm^-2 (x: %.6g, %.6g; y: %.6g, %.6g), alpha %.4g\n"
           "  (%s)\n", s->m0, s->m2, s->m4, s->m20, s->m40, s->m02, s->m04, s->alpha,
           s->moments_fd ? "non-periodic map: finite-difference moments, edge points not searched"
                         : "periodic map: FFT moments, periodic summit search");
    printf("  %-28s %14s %14s %10s\n", "", "measured", "theory", "diff");
    row("summits", s->summits, s->summit_density_nayak_per_mm2 * s->area_mm2, "(Nayak 1971)");
    row("summit density", s->summit_density_per_mm2, s->summit_density_nayak_per_mm2,
        "1/mm^2 (Nayak 1971)");
    row("mean summit radius", s->mean_summit_radius_mm, s->mean_summit_radius_mccool_mm,
        "mm (McCool 1986)");
    row("summit height sigma_s", s->sigma_s_mm, s->sigma_s_mccool_mm, "mm (McCool 1986)");
    row("mean summit height offset", s->summit_mean_offset_mm, s->summit_mean_offset_mccool_mm,
        "mm (McCool 1986)");
}

int cli_surface_stats(const cli_cmd *cmd, int argc, char **argv)
{
    stats_opts o = {NULL, SRF_RULE_8, 0, {0, 0, NULL, 1, 0}};
    const char *pos = NULL;
    int done;
    cli_peel_positional(&argc, &argv, &pos);
    int rc = cli_parse(cmd->name, "FILE [--rule 8|4] [--json]", argc, argv, opts, NULL, set_opt,
                       &o, &done);
    srf_map *m = NULL;
    srf_summits *su = NULL;
    srf_stats st;
    stc_status s = STC_OK;
    if (rc != CLI_EXIT_OK || done) goto out;
    if (pos && o.in)
        s = stc_error(STC_EINVAL, __FILE__, __LINE__,
                      "in = '%s' conflicts with the FILE argument '%s': give the input once",
                      o.in, pos);
    else if (pos)
        s = cli_set_string("in", pos, &o.in);
    else if (!o.in)
        s = stc_error(STC_EINVAL, __FILE__, __LINE__,
                      "in: missing (an input file is required: FILE or --in FILE)");
    if (s == STC_OK) s = cli_surface_import_check(&o.imp);
    if (s == STC_OK) s = cli_surface_load("in", o.in, &o.imp, &m);
    if (s == STC_OK) s = srf_summits_find(m, o.rule, &su);
    if (s == STC_OK) s = srf_stats_compute(m, su, &st);
    if (s == STC_OK) {
        if (o.json) print_json(&o, m, &st);
        else print_table(&o, m, &st);
    }
    rc = s == STC_OK ? CLI_EXIT_OK : cli_fail(cmd->name, s);
out:
    srf_summits_destroy(&su);
    srf_map_destroy(&m);
    free(o.in);
    cli_surface_import_free(&o.imp);
    return rc;
}
