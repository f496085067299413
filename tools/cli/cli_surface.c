/* stiction surface synth|stats|predict — the nested dispatcher, and helpers
 * the surface subcommands share. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "stiction/surface.h"

static const cli_cmd surface_cmds[] = {
    {"surface synth", "synthesize (or import) a periodic rough surface, write HDF5 + PNG",
     cli_surface_synth},
    {"surface stats", "surface and summit statistics next to Nayak/McCool theory",
     cli_surface_stats},
    {"surface predict", "Greenwood-Williamson friction summation: mu_s, A/An vs load",
     cli_surface_predict},
    {NULL, NULL, NULL},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: stiction surface SUBCOMMAND [options]   (... SUBCOMMAND --help)\n\n"
               "Subcommands:\n");
    for (const cli_cmd *c = surface_cmds; c->name; c++)
        fprintf(f, "  %-10s %s\n", c->name + strlen("surface "), c->summary);
}

int cli_surface(const cli_cmd *cmd, int argc, char **argv)
{
    (void)cmd;
    if (argc < 1) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    for (const cli_cmd *c = surface_cmds; c->name; c++)
        if (strcmp(argv[0], c->name + strlen("surface ")) == 0)
            return c->run(c, argc - 1, argv + 1);
    fprintf(stderr, "stiction surface: unknown subcommand '%s'\n\n", argv[0]);
    usage(stderr);
    return CLI_EXIT_USAGE;
}

stc_status cli_parse_pair(const char *key, const char *value, double *a, double *b)
{
    double *v;
    int n;
    stc_status s = cli_parse_list(key, value, &v, &n);
    if (s != STC_OK) return s;
    if (n < 1 || n > 2 || strchr(value, ':')) {
        free(v);
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "%s = '%s': expected one value or two separated by a comma", key, value);
    }
    *a = v[0];
    *b = n == 2 ? v[1] : v[0];
    free(v);
    return STC_OK;
}

void cli_peel_positional(int *argc, char ***argv, const char **path)
{
    if (*argc > 0 && strncmp((*argv)[0], "--", 2) != 0) {
        *path = (*argv)[0];
        (*argc)--;
        (*argv)++;
    }
}

stc_status cli_surface_load(const char *path, const cli_surface_import *imp, srf_map **out)
{
    if (imp->dx <= 0) return srf_map_read(path, out);
    if (imp->dataset && *imp->dataset)
        return srf_map_import_h5(path, imp->dataset, imp->dx, imp->dy, imp->zscale, out);
    return srf_map_import_text(path, imp->dx, imp->dy, imp->zscale, out);
}

stc_status cli_surface_import_opt(cli_surface_import *imp, const char *key, const char *value)
{
    if (strcmp(key, "pixel-size") == 0) {
        stc_status s = cli_parse_pair(key, value, &imp->dx, &imp->dy);
        if (s != STC_OK) return s;
        if (!(imp->dx > 0 && imp->dy > 0))
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "pixel-size = '%s': must be > 0 (mm)", value);
        return STC_OK;
    }
    if (strcmp(key, "dataset") == 0) {
        imp->dataset = value;
        return STC_OK;
    }
    if (strcmp(key, "z-scale") == 0) {
        stc_status s = stc_parse_double(key, value, &imp->zscale);
        if (s == STC_OK && !(imp->zscale > 0))
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "z-scale = %g: must be > 0 (1e-3 for heights in um)", imp->zscale);
        return s;
    }
    return STC_EUNSUPPORTED;
}
