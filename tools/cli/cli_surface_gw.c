/* What `surface predict` and `surface sweep` share: the summit population
 * (read once, summed with any number of asperity models), the three models
 * of an FE friction table at one coating (preload, P at inception, μs's
 * error band) and their sums at one load, and --fill (the table's missing
 * points that the loads touch, computed into the table file). */
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

stc_status cli_gw_pop_opt(cli_gw_pop *pop, const char *key, const char *v)
{
    int c = 0;
    stc_status s = STC_OK;
    double *x = !strcmp(key, "summit-density") ? &pop->eta
              : !strcmp(key, "summit-radius")  ? &pop->R
              : !strcmp(key, "sigma-s")        ? &pop->sigma_s
                                               : NULL;
    if (x) {
        s = stc_parse_double(key, v, x);
        return s == STC_OK ? stc_check_range(key, *x, 0.0, 0, INFINITY, 0) : s;
    }
    if (!strcmp(key, "rule")) {
        s = cli_parse_choice(key, v, "8", "4", &c);
        pop->rule = c ? SRF_RULE_4 : SRF_RULE_8;
        pop->rule_given = 1;
    } else if (!strcmp(key, "mode"))
        s = cli_parse_choice(key, v, "statistical", "deterministic", &pop->deterministic);
    else if (!strcmp(key, "density")) {
        s = cli_parse_choice(key, v, "gaussian", "kde", &pop->kde);
        pop->density_given = 1;
    } else return STC_EUNSUPPORTED;
    return s;
}

stc_status cli_gw_pop_check(const cli_gw_pop *pop, const char *surface,
                            const cli_surface_import *imp)
{
    int stats = (pop->eta > 0) + (pop->R > 0) + (pop->sigma_s > 0);
    if (!surface && stats != 3)
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "need --surface FILE, or all of --summit-density, --summit-radius, "
                         "--sigma-s (got %d of 3)", stats);
    if (surface && stats)
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "surface = '%s': give either --surface or the summit statistics, "
                         "not both", surface);
    if (!surface && pop->deterministic)
        return cli_conflict("mode deterministic", "summit-density", "the deterministic sums "
                            "need the summits of a map (--surface FILE)");
    /* the options of a map, in the order of the help */
    const char *map_key = pop->rule_given ? "rule" : imp->dx > 0 ? "pixel-size"
                        : imp->dataset    ? "dataset" : imp->zscale_set ? "z-scale"
                        : pop->density_given ? "density" : NULL;
    if (!surface && map_key)
        return cli_conflict(map_key, "summit-density", "only used with a map (--surface FILE); "
                            "the summit statistics given directly define a Gaussian "
                            "population");
    if (pop->deterministic && pop->density_given)
        return cli_conflict("density", "mode deterministic", "the deterministic sums run over "
                            "the map's own summits; a height density (gaussian|kde) is only "
                            "used by --mode statistical");
    return cli_surface_import_check(imp);
}

stc_status cli_gw_pop_load(cli_gw_pop *pop, const char *surface, const cli_surface_import *imp,
                           const stc_params *p)
{
    if (!surface) return STC_OK; /* a Gaussian population from its three statistics */
    srf_map *map = NULL;
    srf_summits *sm = NULL;
    srf_stats st;
    stc_status s = cli_surface_load("surface", surface, imp, &map);
    if (s == STC_OK) s = srf_summits_find(map, pop->rule, &sm);
    if (s == STC_OK) s = srf_stats_compute(map, sm, &st);
    srf_map_destroy(&map);
    if (s == STC_OK && (pop->deterministic || pop->kde)) {
        s = asp_model_create_hertz(p, 0.0, ASP_LAYER_SUBSTRATE, &pop->proto_model);
        if (s == STC_OK)
            s = srf_gw_create_from_summits(pop->proto_model, pop->deterministic
                                                                 ? SRF_GW_DETERMINISTIC
                                                                 : SRF_GW_KDE,
                                           sm, NULL, &pop->proto);
    } else if (s == STC_OK) { /* Gaussian heights of the map's statistics */
        pop->eta = st.summit_density_per_mm2;
        pop->R = st.mean_summit_radius_mm;
        pop->sigma_s = st.sigma_s_mm;
    }
    srf_summits_destroy(&sm);
    return s;
}

stc_status cli_gw_pop_sum(const cli_gw_pop *pop, const asp_model *m, srf_gw **out)
{
    if (pop->proto) return srf_gw_create_like(pop->proto, m, out);
    return srf_gw_create_gaussian(m, pop->eta, pop->R, pop->sigma_s, NULL, out);
}

void cli_gw_pop_free(cli_gw_pop *pop)
{
    srf_gw_destroy(&pop->proto);
    asp_model_destroy(&pop->proto_model);
}

stc_status cli_table_design_create(const tbl_table *t, const stc_params *p, double t_mm,
                                   const cli_gw_pop *pop, cli_table_design *d)
{
    static const tbl_model_kind kind[3] = {TBL_MODEL_PRELOAD, TBL_MODEL_SLIDE, TBL_MODEL_ERR};
    memset(d, 0, sizeof *d);
    stc_status s = STC_OK;
    for (int k = 0; k < 3 && s == STC_OK; k++) {
        s = tbl_model_create(t, p, t_mm, kind[k], &d->m[k]);
        if (s == STC_OK) s = cli_gw_pop_sum(pop, d->m[k], &d->g[k]);
    }
    /* the slope where the table keeps it (format 7 on; STC_ERANGE: it does not) */
    if (s == STC_OK) {
        s = tbl_model_create(t, p, t_mm, TBL_MODEL_SLOPE, &d->m[3]);
        if (s == STC_ERANGE) stc_error_clear(), s = STC_OK;
    }
    if (s == STC_OK && d->m[3]) s = cli_gw_pop_sum(pop, d->m[3], &d->g[3]);
    if (s != STC_OK) cli_table_design_free(d);
    return s;
}

stc_status cli_table_design_at(const cli_table_design *d, int by_pressure, double x,
                               srf_gw_point *pt, double *mu_s_err, double *mu_s_slide,
                               double *mu_s_slope)
{
    stc_status s = by_pressure ? srf_gw_at_pressure(d->g[0], x, pt)
                               : srf_gw_at_separation(d->g[0], x, pt);
    if (s != STC_OK) return s;
    srf_gw_point a, b; /* the same summits at the same separation */
    if ((s = srf_gw_at_separation(d->g[1], pt->h, &a)) ||
        (s = srf_gw_at_separation(d->g[2], pt->h, &b)))
        return s;
    *mu_s_slide = pt->Q_MPa / a.pressure_MPa;
    *mu_s_err = b.Q_MPa / pt->pressure_MPa; /* errors taken fully correlated */
    *mu_s_slope = NAN;
    if (d->g[3]) { /* sum s Qmax / sum Qmax */
        if ((s = srf_gw_at_separation(d->g[3], pt->h, &b))) return s;
        *mu_s_slope = b.Q_MPa / pt->Q_MPa;
    }
    return STC_OK;
}

void cli_table_design_free(cli_table_design *d)
{
    for (int k = 0; k < 4; k++) srf_gw_destroy(&d->g[k]), asp_model_destroy(&d->m[k]);
}

/* The contact states come from a guide model: the table's own where it has
 * one at these materials, else the closed-form wsp model (substrate); a
 * round with the table's model after a fill checks that the filled table
 * needs nothing more (at most 3 rounds). */
stc_status cli_table_fill(const char *cmd, const cli_table_fill_job *job, int ndesign,
                          int jobs)
{
    tbl_table *t = NULL;
    unsigned char *need = NULL;
    int computed = 0, marked = 0, failed = 0, curves = 0;
    double wall = 0.0;
    stc_status s = tbl_read(job->table, &t);
    for (int k = 0; k < ndesign && s == STC_OK; k++) s = tbl_check_params(t, &job->p[k]);
    if (s == STC_OK && !(need = calloc((size_t)tbl_points(t), 1)))
        s = stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    for (int round = 0; round < 3 && s == STC_OK; round++) {
        int pending = 0;
        for (int k = 0; k < ndesign && s == STC_OK; k++) {
            asp_model *guide = NULL;
            srf_gw *g = NULL;
            int pk = 0;
            if (tbl_model_create(t, &job->p[k], job->t_mm[k], TBL_MODEL_PRELOAD, &guide) !=
                STC_OK) {
                stc_error_clear();
                s = asp_model_create_wsp(&job->p[k], job->t_mm[k], ASP_LAYER_SUBSTRATE, &guide);
            }
            if (s == STC_OK) s = cli_gw_pop_sum(job->pop, guide, &g);
            if (s == STC_OK)
                s = srf_gw_table_needs(g, t, job->p[k].E_ratio, job->by_pressure, job->loads,
                                       job->nloads, need, &pk);
            srf_gw_destroy(&g);
            asp_model_destroy(&guide);
            pending += pk; /* each design counts the points not yet marked by another */
        }
        if (s != STC_OK || (pending == 0 && tbl_curves_pending(t, need) == 0)) break;
        tbl_build_opts bo;
        tbl_build_summary sum = {0};
        tbl_build_opts_default(&bo);
        bo.only = need;
        bo.jobs = jobs;
        cli_table_progress pc = {isatty(2), 0, t};
        bo.progress = cli_table_progress_line;
        bo.ctx = &pc;
        bo.report_members = 1;
        double w; /* the file's: tbl_build writes it plus this run's */
        tbl_provenance(t, &w);
        tbl_set_provenance(t, job->command, w); /* this build's command */
        fprintf(stderr, "stiction %s: filling %s: %d points and %d normal curves to compute\n",
                cmd, job->table, pending, tbl_curves_pending(t, need));
        s = tbl_build(t, job->table, &bo, &sum);
        if (pc.tty && sum.computed > 0) fputc('\n', stderr);
        computed += sum.computed;
        curves += sum.curves_computed;
        failed += sum.failed;
        wall += sum.wall_s;
    }
    for (int i = 0; need && i < tbl_points(t); i++) marked += need[i] != 0;
    if (s == STC_OK)
        fprintf(stderr, "stiction %s: fill: the loads touch %d of the table's %d points; %d "
                "computed now (%d failed, %.1f s, with %d normal curves), %d were there\n",
                cmd, marked, tbl_points(t), computed, failed, wall, curves, marked - computed);
    free(need);
    tbl_destroy(&t);
    return cli_name_error(s, "table", job->table);
}
