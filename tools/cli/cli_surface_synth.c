/* stiction surface synth: FFT-synthesize a periodic rough surface (or import a
 * measured one), write HDF5 (heights + every parameter) and a PNG. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "stiction/surface.h"

typedef struct {
    srf_synth_params p;
    unsigned long seed;
    char *out, *png, *import; /* owned */
    int no_png, json;
    cli_surface_import imp;
    unsigned long long seen; /* cli_opt_bit() of every option given */
} synth_opts;

static const cli_opt opts[] = {
    CLI_HEADING("Grid (units mm)"),
    {"size", "N[,M]", "grid points in x[,y] (default 256)"},
    {"length", "L[,Ly]", "periodic lengths, mm (default 1)"},
    CLI_HEADING("Heights and spectrum"),
    {"rms", "SIGMA", "RMS height, mm, exact after synthesis (default 0.001)"},
    {"spectrum", "KIND", "exponential | self-affine (default exponential)"},
    {"corr-length", "BX[,BY]", "exponential: ACF falls to 0.1 at BX, BY mm (default 0.05)"},
    {"hurst", "H", "self-affine: Hurst exponent in (0, 1] (default 0.8)"},
    {"long-wavelength", "LL", "self-affine: no power at wavelengths > LL, mm (default length)"},
    {"rolloff-wavelength", "LR", "self-affine: flat spectrum for LR..LL, mm (default LL)"},
    {"cutoff-wavelength", "LS", "self-affine: no power below LS, mm (default 16 pixels)"},
    {"skewness", "SK", "non-Gaussian heights (Johnson translator): target skewness"},
    {"kurtosis", "KU", "non-Gaussian heights: target kurtosis (Gaussian 3)"},
    {"amplitude", "MODE", "exact (random phase, default) | rayleigh (random amplitude)"},
    {"seed", "N", "GSL mt19937 seed, stored in the output (default 1)"},
    CLI_HEADING("A measured map instead"),
    {"import", "FILE", "import a measured map instead of synthesizing (needs --pixel-size)"},
    CLI_SURFACE_IMPORT_OPTS,
    CLI_HEADING("Common options"),
    {"out", "FILE.h5", "output HDF5 file (required)"},
    {"png", "FILE", "PNG of the map (default: FILE.h5 with .png)"},
    {"no-png", NULL, "do not write a PNG"},
    {"json", NULL, "print the summary as JSON"},
    {"threads", "N", "FFTW/OpenMP threads (default: all)"},
    CLI_CONFIG_HELP,
    {NULL, NULL, NULL},
};

static stc_status set_size(synth_opts *o, const char *key, const char *v)
{
    double a, b;
    stc_status s = cli_parse_pair(key, v, &a, &b);
    if (s != STC_OK) return s;
    if (a != (long)a || b != (long)b || a < 4 || b < 4 || a > 65536 || b > 65536)
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "size = '%s': must be integers in [4, 65536]", v);
    o->p.nx = (int)a;
    o->p.ny = (int)b;
    return STC_OK;
}

static stc_status set_positive(const char *key, const char *v, double *out)
{
    stc_status s = stc_parse_double(key, v, out);
    if (s == STC_OK && !(*out > 0))
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = %g: must be > 0 (mm)", key, *out);
    return s;
}

static stc_status set_spectrum(synth_opts *o, const char *v)
{
    if (strcmp(v, "exponential") == 0) o->p.spectrum = SRF_SPECTRUM_EXPONENTIAL;
    else if (strcmp(v, "self-affine") == 0) o->p.spectrum = SRF_SPECTRUM_SELF_AFFINE;
    else
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "spectrum = '%s': must be exponential or self-affine", v);
    return STC_OK;
}

static stc_status set_opt1(synth_opts *o, const char *key, const char *v)
{
    long l;
    stc_status s;
    if (strcmp(key, "size") == 0) return set_size(o, key, v);
    if (strcmp(key, "length") == 0) {
        if ((s = cli_parse_pair(key, v, &o->p.lx, &o->p.ly))) return s;
        if (!(o->p.lx > 0 && o->p.ly > 0))
            return stc_error(STC_EINVAL, __FILE__, __LINE__, "length = '%s': must be > 0 (mm)", v);
        return STC_OK;
    }
    if (strcmp(key, "rms") == 0) return set_positive(key, v, &o->p.rms);
    if (strcmp(key, "spectrum") == 0) return set_spectrum(o, v);
    if (strcmp(key, "corr-length") == 0) {
        if ((s = cli_parse_pair(key, v, &o->p.beta_x, &o->p.beta_y))) return s;
        if (!(o->p.beta_x > 0 && o->p.beta_y > 0))
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "corr-length = '%s': must be > 0 (mm)", v);
        return STC_OK;
    }
    if (strcmp(key, "hurst") == 0) {
        if ((s = stc_parse_double(key, v, &o->p.hurst))) return s;
        return stc_check_range(key, o->p.hurst, 0, 0, 1, 1);
    }
    if (strcmp(key, "long-wavelength") == 0) return set_positive(key, v, &o->p.lambda_long);
    if (strcmp(key, "rolloff-wavelength") == 0) return set_positive(key, v, &o->p.lambda_rolloff);
    if (strcmp(key, "cutoff-wavelength") == 0) return set_positive(key, v, &o->p.lambda_cutoff);
    if (strcmp(key, "skewness") == 0) {
        o->p.non_gaussian = 1;
        return stc_parse_double(key, v, &o->p.skewness);
    }
    if (strcmp(key, "kurtosis") == 0) {
        o->p.non_gaussian = 1;
        return stc_parse_double(key, v, &o->p.kurtosis); /* range: srf_synth_params_validate */
    }
    if (strcmp(key, "amplitude") == 0) {
        if (strcmp(v, "exact") == 0) o->p.amplitude = SRF_AMP_EXACT;
        else if (strcmp(v, "rayleigh") == 0) o->p.amplitude = SRF_AMP_RAYLEIGH;
        else
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "amplitude = '%s': must be exact or rayleigh", v);
        return STC_OK;
    }
    if (strcmp(key, "seed") == 0) {
        if ((s = cli_parse_long(key, v, 0, 4294967295L, &l))) return s;
        o->seed = (unsigned long)l;
        return STC_OK;
    }
    if (strcmp(key, "threads") == 0) {
        return cli_parse_int(key, v, 0, 1024, &o->p.threads);
    }
    if (strcmp(key, "out") == 0) return cli_set_string(key, v, &o->out);
    if (strcmp(key, "png") == 0) return cli_set_string(key, v, &o->png);
    if (strcmp(key, "import") == 0) return cli_set_string(key, v, &o->import);
    if (strcmp(key, "no-png") == 0) return cli_parse_flag(key, v, &o->no_png);
    if (strcmp(key, "json") == 0) return cli_parse_flag(key, v, &o->json);
    return cli_surface_import_opt(&o->imp, key, v);
}

static stc_status set_opt(void *ctx, const char *key, const char *v)
{
    synth_opts *o = ctx;
    stc_status s = set_opt1(o, key, v);
    if (s == STC_OK) o->seen |= cli_opt_bit(opts, key);
    return s;
}

static int given(const synth_opts *o, const char *key) { return (o->seen & cli_opt_bit(opts, key)) != 0; }

/* Options that shape a synthesized map; an imported map takes none of them. */
static const char *const SYNTH_KEYS[] = {"size", "length", "rms", "spectrum", "corr-length",
                                         "hurst", "long-wavelength", "rolloff-wavelength",
                                         "cutoff-wavelength", "skewness", "kurtosis",
                                         "amplitude", "seed", NULL};
static const char *const SELF_AFFINE_KEYS[] = {"hurst", "long-wavelength", "rolloff-wavelength",
                                               "cutoff-wavelength", NULL};
static const char *const IMPORT_KEYS[] = {"pixel-size", "dataset", "z-scale", NULL};

/* Refuse combinations in which an option would be silently ignored. */
static stc_status check_opts(const synth_opts *o)
{
    if (o->import) {
        for (const char *const *k = SYNTH_KEYS; *k; k++)
            if (given(o, *k))
                return cli_conflict(*k, "import", "an imported map is measured, not "
                                    "synthesized: its size and heights come from the file");
        return cli_surface_import_check(&o->imp);
    }
    for (const char *const *k = IMPORT_KEYS; *k; k++)
        if (given(o, *k))
            return cli_conflict(*k, "import", "only used when importing a measured map "
                                "(--import FILE --pixel-size DX[,DY])");
    if (o->p.spectrum == SRF_SPECTRUM_EXPONENTIAL)
        for (const char *const *k = SELF_AFFINE_KEYS; *k; k++)
            if (given(o, *k))
                return cli_conflict(*k, "spectrum exponential", "only the self-affine "
                                    "spectrum has a Hurst exponent and band wavelengths (add "
                                    "--spectrum self-affine)");
    if (o->p.spectrum == SRF_SPECTRUM_SELF_AFFINE && given(o, "corr-length"))
        return cli_conflict("corr-length", "spectrum self-affine", "the correlation length "
                            "shapes only the exponential spectrum");
    if (o->no_png && o->png)
        return cli_conflict("png", "no-png", "ask for a PNG file or for none");
    if (!o->out)
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "out: missing (--out FILE.h5 is required)");
    if (o->png && strcmp(o->png, o->out) == 0)
        return stc_error(STC_EINVAL, __FILE__, __LINE__,
                         "png = '%s': must differ from out = '%s'", o->png, o->out);
    return STC_OK;
}

/* Moments: the synthesizer's discrete target (exact amplitudes reproduce it to
 * round-off; an extra FFT of a 4096² map would cost more than the synthesis). */
static void summary(const synth_opts *o, const srf_map *m, const char *png, const srf_moments *mo)
{
    if (o->json) {
        cli_json j;
        cj_init(&j, stdout);
        cj_obj(&j, NULL);
        cj_str(&j, "out", o->out);
        cj_str(&j, "png", png);
        cj_str(&j, "origin", m->origin == SRF_ORIGIN_SYNTH ? "synth" : "import");
        cj_int(&j, "nx", m->nx);
        cj_int(&j, "ny", m->ny);
        cj_num(&j, "lx_mm", m->lx);
        cj_num(&j, "ly_mm", m->ly);
        if (m->origin == SRF_ORIGIN_SYNTH) {
            cj_str(&j, "spectrum", srf_spectrum_name(m->synth.spectrum));
            cj_int(&j, "seed", (long)m->seed);
            cj_num(&j, "rms_mm", m->synth.rms);
            cj_num(&j, "skewness_reached", m->skewness_reached);
            cj_num(&j, "kurtosis_reached", m->kurtosis_reached);
            if (m->synth.non_gaussian) cj_str(&j, "johnson_family", m->johnson);
            cj_num(&j, "target_m0", mo->m0);
            cj_num(&j, "target_m2", mo->m2);
            cj_num(&j, "target_m4", mo->m4);
        } else {
            cj_str(&j, "source", m->source);
            cj_num(&j, "detrend_tilt_x", m->tilt_x);
            cj_num(&j, "detrend_tilt_y", m->tilt_y);
        }
        cj_end_obj(&j);
        cj_done(&j);
        return;
    }
    printf("wrote %s (%d x %d points, %g x %g mm)%s%s\n", o->out, m->nx, m->ny, m->lx, m->ly,
           png ? " and " : "", png ? png : "");
    if (m->origin == SRF_ORIGIN_SYNTH) {
        printf("  %s spectrum, seed %lu, rms %g mm, skewness %.4f, kurtosis %.4f%s%s\n",
               srf_spectrum_name(m->synth.spectrum), m->seed, m->synth.rms, m->skewness_reached,
               m->kurtosis_reached, m->synth.non_gaussian ? ", Johnson " : "",
               m->synth.non_gaussian ? m->johnson : "");
        printf("  target spectrum moments: m0 %.6g mm^2, m2 %.6g, m4 %.6g mm^-2 "
               "(stiction surface stats measures them)\n", mo->m0, mo->m2, mo->m4);
    } else {
        printf("  imported %s, plane removed: tilt %g, %g\n", m->source, m->tilt_x, m->tilt_y);
    }
}

/* An output that names a directory is refused before any work (the rename
 * onto it failed once the map was made). */
static stc_status check_out_file(const char *key, const char *path, const char *what)
{
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '%s': is a directory (expected "
                         "the name of the %s file to write)", key, path, what);
    return STC_OK;
}

/* FILE.h5 → FILE.png (or FILE.png appended). */
static void png_beside(const char *h5, char *buf, size_t n)
{
    size_t len = strlen(h5);
    if (len > 3 && strcmp(h5 + len - 3, ".h5") == 0) snprintf(buf, n, "%.*s.png", (int)(len - 3), h5);
    else snprintf(buf, n, "%s.png", h5);
}

static stc_status make_map(synth_opts *o, srf_map **m, srf_moments *mo)
{
    memset(mo, 0, sizeof *mo);
    if (o->import) {
        if (o->imp.dx <= 0)
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "import = '%s': --pixel-size DX[,DY] (mm) is required", o->import);
        return cli_surface_load("import", o->import, &o->imp, m);
    }
    srf_synth *s = NULL;
    stc_status st = srf_synth_create(&o->p, &s);
    if (st == STC_OK) st = srf_synth_target_moments(s, mo);
    if (st == STC_OK) st = srf_map_create(o->p.nx, o->p.ny, o->p.lx, o->p.ly, m);
    if (st == STC_OK) st = srf_synth_run(s, o->seed, *m);
    if (st != STC_OK) srf_map_destroy(m);
    srf_synth_destroy(&s);
    return st;
}

static void free_opts(synth_opts *o)
{
    free(o->out);
    free(o->png);
    free(o->import);
    cli_surface_import_free(&o->imp);
}

int cli_surface_synth(const cli_cmd *cmd, int argc, char **argv)
{
    synth_opts o;
    memset(&o, 0, sizeof o);
    srf_synth_params_default(&o.p);
    o.seed = 1;
    o.imp.zscale = 1;
    int done;
    int rc = cli_parse(cmd->name, "--out FILE.h5 [options]", argc, argv, opts, NULL, set_opt, &o,
                       &done);
    if (rc != CLI_EXIT_OK || done) {
        free_opts(&o);
        return rc;
    }
    srf_map *m = NULL;
    srf_moments mo;
    stc_status s = check_opts(&o);
    char pngbuf[4096];
    const char *png = NULL;
    if (s == STC_OK && !o.no_png) {
        if (o.png) png = o.png;
        else png_beside(o.out, pngbuf, sizeof pngbuf), png = pngbuf;
    }
    if (s == STC_OK) s = check_out_file("out", o.out, "HDF5");
    if (s == STC_OK && png) s = check_out_file("png", png, "PNG");
    if (s == STC_OK) s = make_map(&o, &m, &mo);
    if (s == STC_OK && png) {
        s = srf_map_write_png(m, png);
        if (s != STC_OK) png = NULL; /* nothing written */
    }
    /* PNG first: if the HDF5 write fails, remove the PNG so nothing partial stays. */
    if (s == STC_OK && (s = srf_map_write_h5(m, o.out)) != STC_OK && png) remove(png);
    if (s == STC_OK) summary(&o, m, png, &mo);
    srf_map_destroy(&m);
    free_opts(&o);
    return s == STC_OK ? CLI_EXIT_OK : cli_fail(cmd->name, s);
}
