/* stiction surface synth|stats|predict|sweep — the nested dispatcher, and helpers
 * the surface subcommands share. */
#include <math.h>
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
    {"surface sweep", "coating designs (thickness x Eco/Esu) on a friction table: mu_s, A/An",
     cli_surface_sweep},
    {NULL, NULL, NULL},
};

int cli_surface(const cli_cmd *cmd, int argc, char **argv)
{
    (void)cmd;
    return cli_dispatch("surface", surface_cmds, argc, argv);
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

stc_status cli_parse_flag(const char *key, const char *value, int *flag)
{
    if (!strcmp(value, "1") || !strcmp(value, "true") || !strcmp(value, "yes")) *flag = 1;
    else if (!strcmp(value, "0") || !strcmp(value, "false") || !strcmp(value, "no")) *flag = 0;
    else
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "%s = '%s': must be 1/true/yes or 0/false/no", key, value);
    return STC_OK;
}

stc_status cli_parse_long(const char *key, const char *value, long lo, long hi, long *out)
{
    long l;
    if (stc_parse_long(key, value, &l) != STC_OK || l < lo || l > hi) {
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '%s': must be a whole number "
                         "in [%ld, %ld]", key, value, lo, hi);
    }
    *out = l;
    return STC_OK;
}

stc_status cli_parse_int(const char *key, const char *value, long lo, long hi, int *out)
{
    long l;
    stc_status s = cli_parse_long(key, value, lo, hi, &l);
    if (s == STC_OK) *out = (int)l;
    return s;
}

stc_status cli_parse_choice(const char *key, const char *v, const char *a, const char *b,
                            int *second)
{
    if (strcmp(v, a) == 0) *second = 0;
    else if (strcmp(v, b) == 0) *second = 1;
    else return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '%s': must be %s or %s", key, v,
                          a, b);
    return STC_OK;
}

stc_status cli_parse_values(const char *key, const char *value, int positive, double **out,
                            int *n)
{
    free(*out);
    *out = NULL;
    stc_status s = cli_parse_list(key, value, out, n); /* finite numbers */
    for (int i = 0; s == STC_OK && positive && i < *n; i++)
        if (!((*out)[i] > 0.0))
            s = stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = %g (value %d of '%s'): must be "
                          "> 0", key, (*out)[i], i + 1, value);
    return s;
}

stc_status cli_set_string(const char *key, const char *value, char **out)
{
    if (!value || !*value)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '': must be a file or dataset name",
                         key);
    char *c = strdup(value);
    if (!c) return stc_error(STC_ENOMEM, __FILE__, __LINE__, "%s: out of memory", key);
    free(*out);
    *out = c;
    return STC_OK;
}

unsigned long long cli_opt_bit(const cli_opt *opts, const char *key)
{
    for (int k = 0; k < 64 && opts[k].name; k++)
        if (strcmp(opts[k].name, key) == 0) return 1ULL << k;
    return 0;
}

stc_status cli_conflict(const char *a, const char *b, const char *why)
{
    return stc_error(STC_EINVAL, __FILE__, __LINE__, "--%s conflicts with --%s: %s", a, b, why);
}

void cli_peel_positional(int *argc, char ***argv, const char **path)
{
    if (*argc > 0 && strncmp((*argv)[0], "--", 2) != 0) {
        *path = (*argv)[0];
        (*argc)--;
        (*argv)++;
    }
}

/* What a surface input must be, for the error message. */
static const char *expected_input(const cli_surface_import *imp)
{
    if (imp->dx <= 0)
        return "expected a stiction surface HDF5 file from `surface synth`; import measured "
               "heights with --pixel-size DX (a text grid, or an HDF5 file with --dataset NAME)";
    if (imp->dataset)
        return "expected an HDF5 file holding a 2-D numeric dataset of finite heights, "
               "[ny][nx] with 3 <= nx, ny <= 65536";
    return "expected a text grid: one row of finite numbers per line, every row the same "
           "length, 3 <= columns, rows <= 65536";
}

/* A map whose RMS (about its mean) is below this share of its height scale
 * is flat up to round-off (1e-16 relative): its summits, slopes and
 * curvatures are noise.  Real profilometer data (16-bit heights) sit at 1e-5
 * or more. */
#define CLI_FLAT_REL 1e-10

/* Refuse a flat map (a plane once detrended): stats and predict would print
 * random-process theory for round-off.  The scale includes the plane removed
 * on import. */
static stc_status check_rough(const srf_map *m)
{
    size_t n = (size_t)m->nx * m->ny;
    double sum = 0, ss = 0, zmax = 0;
    for (size_t k = 0; k < n; k++) sum += m->z[k];
    for (size_t k = 0; k < n; k++) {
        double d = m->z[k] - sum / (double)n;
        ss += d * d;
        zmax = fmax(zmax, fabs(m->z[k]));
    }
    double rms = sqrt(ss / (double)n);
    double scale = zmax + fabs(m->offset) + fabs(m->tilt_x) * m->lx + fabs(m->tilt_y) * m->ly;
    if (rms > CLI_FLAT_REL * scale) return STC_OK;
    return stc_error(STC_EFORMAT, __FILE__, __LINE__,
                     "the heights are flat (a plane): RMS %g mm about the plane, height scale "
                     "%g mm (valid: a rough map, RMS > %g x scale)", rms, scale, CLI_FLAT_REL);
}

stc_status cli_surface_load(const char *key, const char *path, const cli_surface_import *imp,
                            srf_map **out)
{
    stc_status s;
    if (imp->dx <= 0) s = srf_map_read(path, out);
    else if (imp->dataset)
        s = srf_map_import_h5(path, imp->dataset, imp->dx, imp->dy, imp->zscale, out);
    else s = srf_map_import_text(path, imp->dx, imp->dy, imp->zscale, out);
    if (s == STC_OK && (s = check_rough(*out)) != STC_OK) srf_map_destroy(out);
    if (s == STC_OK || s == STC_ENOMEM) return s;
    /* the library names the file first ("path: ..."): name the option instead */
    char msg[1024];
    const char *m = stc_errmsg();
    size_t n = strlen(path);
    if (strncmp(m, path, n) == 0 && strncmp(m + n, ": ", 2) == 0) m += n + 2;
    snprintf(msg, sizeof msg, "%s", m);
    return stc_error(s, __FILE__, __LINE__, "%s = '%s': %s (%s)", key, path, msg,
                     expected_input(imp));
}

stc_status cli_surface_import_check(const cli_surface_import *imp)
{
    if (imp->dx > 0) return STC_OK;
    if (imp->dataset)
        return cli_conflict("dataset", "pixel-size", "a dataset is only read when importing a "
                            "measured map, which needs --pixel-size DX[,DY] (mm)");
    if (imp->zscale_set)
        return cli_conflict("z-scale", "pixel-size", "--z-scale only scales imported heights; "
                            "give --pixel-size DX[,DY] (mm) to import");
    return STC_OK;
}

void cli_surface_import_free(cli_surface_import *imp)
{
    free(imp->dataset);
    imp->dataset = NULL;
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
    if (strcmp(key, "dataset") == 0) return cli_set_string(key, value, &imp->dataset);
    if (strcmp(key, "z-scale") == 0) {
        stc_status s = stc_parse_double(key, value, &imp->zscale);
        if (s == STC_OK && !(imp->zscale > 0))
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "z-scale = %g: must be > 0 (1e-3 for heights in um)", imp->zscale);
        imp->zscale_set = 1;
        return s;
    }
    return STC_EUNSUPPORTED;
}
