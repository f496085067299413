/* Height maps: allocation, plane detrend, import of measured data (text grid
 * or HDF5 dataset), and the HDF5 file format of the project. */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hdf5.h>

#include "srf_impl.h"
#include "stc_h5.h"
#include "stc_check.h"

#define SRF_FORMAT_NAME "stiction-surface-1"
#define SRF_DATASET "/height"
#define SRF_MAX_POINTS ((size_t)1 << 31) /* 2³¹ heights = 16 GiB: beyond any use here */

stc_status srf_map_create(int nx, int ny, double lx, double ly, srf_map **out)
{
    *out = NULL;
    STC_CHECK(nx >= 3 && ny >= 3, STC_EINVAL, "map size %d x %d: both must be >= 3", nx, ny);
    STC_CHECK((size_t)nx * (size_t)ny <= SRF_MAX_POINTS, STC_EINVAL,
              "map size %d x %d: at most %zu points", nx, ny, SRF_MAX_POINTS);
    STC_CHECK(isfinite(lx) && lx > 0, STC_EINVAL, "map length lx = %g mm: must be > 0", lx);
    STC_CHECK(isfinite(ly) && ly > 0, STC_EINVAL, "map length ly = %g mm: must be > 0", ly);
    srf_map *m = calloc(1, sizeof *m);
    STC_CHECK(m, STC_ENOMEM, "map: out of memory");
    size_t n = (size_t)nx * ny;
    /* fftw_malloc: SIMD-aligned, so synthesis can transform into it directly */
    m->z = fftw_malloc(n * sizeof *m->z);
    if (!m->z) {
        free(m);
        return STC_FAIL(STC_ENOMEM, "map: out of memory for %d x %d heights", nx, ny);
    }
    memset(m->z, 0, n * sizeof *m->z);
    m->nx = nx;
    m->ny = ny;
    m->lx = lx;
    m->ly = ly;
    m->zscale = 1.0;
    m->periodic = 1;
    srf_synth_params_default(&m->synth);
    *out = m;
    return STC_OK;
}

void srf_map_destroy(srf_map **pm)
{
    if (!pm || !*pm) return;
    fftw_free((*pm)->z);
    free(*pm);
    *pm = NULL;
}

/* Least-squares plane on a full regular grid: with centred coordinates the
 * normal equations decouple (Σ(x-x̄)(y-ȳ) = 0), so a, b, c are closed-form. */
void srf_map_detrend(srf_map *m)
{
    int nx = m->nx, ny = m->ny;
    double dx = m->lx / nx, dy = m->ly / ny;
    double xc = 0.5 * (nx - 1) * dx, yc = 0.5 * (ny - 1) * dy;
    double sz = 0, sxz = 0, syz = 0, sxx = 0, syy = 0;
    for (int i = 0; i < nx; i++) sxx += (i * dx - xc) * (i * dx - xc);
    for (int j = 0; j < ny; j++) syy += (j * dy - yc) * (j * dy - yc);
#pragma omp parallel for schedule(static) reduction(+ : sz, sxz, syz)
    for (int j = 0; j < ny; j++) {
        const double *r = m->z + (size_t)j * nx;
        double rs = 0, rx = 0;
        for (int i = 0; i < nx; i++) {
            rs += r[i];
            rx += (i * dx - xc) * r[i];
        }
        sz += rs;
        sxz += rx;
        syz += (j * dy - yc) * rs;
    }
    double a = sxz / (sxx * ny), b = syz / (syy * nx), c = sz / ((double)nx * ny) - a * xc - b * yc;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) m->z[(size_t)j * nx + i] -= a * i * dx + b * j * dy + c;
    m->tilt_x += a;
    m->tilt_y += b;
    m->offset += c;
}

static stc_status check_pixel(double dx, double dy, double zscale)
{
    STC_CHECK(isfinite(dx) && dx > 0, STC_EINVAL, "pixel-size dx = %g mm: must be > 0", dx);
    STC_CHECK(isfinite(dy) && dy > 0, STC_EINVAL, "pixel-size dy = %g mm: must be > 0", dy);
    STC_CHECK(isfinite(zscale) && zscale > 0, STC_EINVAL, "z-scale = %g: must be > 0", zscale);
    return STC_OK;
}

/* A missing or unreadable file, or a directory, deserves the system's
 * reason, not HDF5's "not an HDF5 file" (a directory opens for reading: the
 * text reader then met a "read error after line 0"). */
static stc_status check_readable(const char *path)
{
    struct stat sb;
    STC_CHECK(stat(path, &sb) == 0, STC_EIO, "%s: cannot open: %s", path, strerror(errno));
    STC_CHECK(!S_ISDIR(sb.st_mode), STC_EIO, "%s: is a directory", path);
    FILE *f = fopen(path, "rb");
    STC_CHECK(f, STC_EIO, "%s: cannot open: %s", path, strerror(errno));
    fclose(f);
    return STC_OK;
}

/* Finish an import: scale, detrend, record the source.  Refuses heights whose
 * statistics overflow once scaled.  (A plane imports fine -- to round-off
 * zero after detrending; `stiction surface` refuses to analyse it.) */
static stc_status import_finish(srf_map *m, const char *source, double zscale)
{
    size_t n = (size_t)m->nx * m->ny;
    double zmax = 0, ss = 0;
    for (size_t k = 0; k < n; k++) {
        m->z[k] *= zscale;
        zmax = fmax(zmax, fabs(m->z[k]));
    }
    m->origin = SRF_ORIGIN_IMPORT;
    m->periodic = 0; /* measured data do not wrap around */
    m->zscale = zscale;
    snprintf(m->source, sizeof m->source, "%s", source);
    srf_map_detrend(m);
    for (size_t k = 0; k < n; k++) ss += m->z[k] * m->z[k];
    double rms = sqrt(ss / (double)n);
    STC_CHECK(isfinite(zmax) && isfinite(rms), STC_EFORMAT,
              "heights × z-scale %g reach %g mm: their statistics overflow (valid: finite "
              "heights in mm, use --z-scale for other units)", zscale, zmax);
    return STC_OK;
}

/* ------------------------------------------------------------ text import */

typedef struct {
    double *v;
    size_t n, cap;
} dvec;

static int dvec_push(dvec *d, double x)
{
    if (d->n == d->cap) {
        size_t cap = d->cap ? 2 * d->cap : 4096;
        double *v = realloc(d->v, cap * sizeof *v);
        if (!v) return -1;
        d->v = v;
        d->cap = cap;
    }
    d->v[d->n++] = x;
    return 0;
}

static int is_sep(char c) { return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r' || c == '\n'; }

/* Parse one line into d; returns the number of values or -1 (message set). */
static long parse_line(char *line, const char *path, long lineno, dvec *d, stc_status *st)
{
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    long count = 0;
    char *p = line;
    for (;;) {
        while (*p && is_sep(*p)) p++;
        if (!*p) break;
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        char *tok_end = end;
        while (*tok_end && !is_sep(*tok_end)) tok_end++;
        if (end == p || end != tok_end || !isfinite(v) || errno == ERANGE) {
            char tok[41]; /* echoed with non-printable bytes as '?' (binary files) */
            size_t len = (size_t)(tok_end - p) < sizeof tok - 1 ? (size_t)(tok_end - p) : sizeof tok - 1;
            for (size_t k = 0; k < len; k++) tok[k] = isprint((unsigned char)p[k]) ? p[k] : '?';
            tok[len] = '\0';
            *st = STC_FAIL(STC_EFORMAT, "%s: line %ld, column %ld (character %ld): '%s' is not "
                           "a finite number", path, lineno, count + 1, (long)(p - line) + 1, tok);
            return -1;
        }
        if (dvec_push(d, v)) {
            *st = STC_FAIL(STC_ENOMEM, "%s: out of memory at line %ld", path, lineno);
            return -1;
        }
        count++;
        p = tok_end;
    }
    return count;
}

stc_status srf_map_import_text(const char *path, double dx, double dy, double zscale,
                               srf_map **out)
{
    *out = NULL;
    STC_CALL(check_pixel(dx, dy, zscale));
    STC_CALL(check_readable(path));
    FILE *f = fopen(path, "r");
    STC_CHECK(f, STC_EIO, "%s: cannot open: %s", path, strerror(errno));
    dvec d = {0};
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0, nx = 0, ny = 0, first = 0;
    stc_status st = STC_OK;
    ssize_t len;
    while ((len = getline(&line, &cap, f)) != -1) {
        lineno++;
        /* a NUL would end the line for the parser and hide what follows */
        STC_CHECK_GOTO(memchr(line, '\0', (size_t)len) == NULL, st, done, STC_EFORMAT,
                       "%s: line %ld holds a NUL byte: not a text grid", path, lineno);
        long c = parse_line(line, path, lineno, &d, &st);
        if (c < 0) goto done;
        if (c == 0) continue;
        if (nx == 0) {
            nx = c;
            first = lineno;
        }
        STC_CHECK_GOTO(c == nx, st, done, STC_EFORMAT,
                       "%s: line %ld has %ld values, expected %ld (the row length of line %ld)",
                       path, lineno, c, nx, first);
        ny++;
    }
    STC_CHECK_GOTO(!ferror(f), st, done, STC_EIO, "%s: read error after line %ld", path, lineno);
    STC_CHECK_GOTO(nx >= 3 && ny >= 3, st, done, STC_EFORMAT,
                   "%s: %ld rows of %ld values: a height grid needs at least 3 x 3", path, ny, nx);
    STC_CHECK_GOTO(nx <= 65536 && ny <= 65536, st, done, STC_EFORMAT,
                   "%s: %ld x %ld grid: at most 65536 per side", path, nx, ny);
    STC_CALL_GOTO(srf_map_create((int)nx, (int)ny, nx * dx, ny * dy, out), st, done);
    memcpy((*out)->z, d.v, (size_t)nx * ny * sizeof *d.v);
    STC_CALL_GOTO(import_finish(*out, path, zscale), st, done);
done:
    if (st != STC_OK) srf_map_destroy(out);
    free(line);
    free(d.v);
    fclose(f);
    return st;
}

/* ------------------------------------------------------------ HDF5 import */

/* Every height of a map read from `path` (dataset `name`) must be finite;
 * the message gives the first bad row and column. */
static stc_status check_finite(const srf_map *m, const char *path, const char *pre,
                               const char *name)
{
    size_t nx = (size_t)m->nx, n = nx * (size_t)m->ny;
    for (size_t k = 0; k < n; k++)
        STC_CHECK(isfinite(m->z[k]), STC_EFORMAT,
                  "%s: %s%s' row %zu, column %zu: height is not finite", path, pre, name,
                  k / nx + 1, k % nx + 1);
    return STC_OK;
}

stc_status srf_map_import_h5(const char *path, const char *dataset, double dx, double dy,
                             double zscale, srf_map **out)
{
    *out = NULL;
    STC_CALL(check_pixel(dx, dy, zscale));
    STC_CHECK(dataset && *dataset, STC_EINVAL, "dataset: a dataset name is required");
    stc_status st = STC_OK;
    hid_t f = -1, d = -1, sp = -1;
    STC_CALL(check_readable(path));
    H5E_BEGIN_TRY { f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(f >= 0, STC_EFORMAT, "%s: not an HDF5 file", path);
    H5E_BEGIN_TRY { d = H5Dopen2(f, dataset, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK_GOTO(d >= 0, st, done, STC_EFORMAT, "%s: no dataset '%s'", path, dataset);
    sp = H5Dget_space(d);
    hsize_t dims[2];
    int rank = H5Sget_simple_extent_ndims(sp);
    STC_CHECK_GOTO(rank == 2, st, done, STC_EFORMAT,
                   "%s: dataset '%s' has rank %d, expected a 2-D [ny][nx] grid", path, dataset,
                   rank);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    hid_t t = H5Dget_type(d);
    H5T_class_t cls = H5Tget_class(t);
    H5Tclose(t);
    STC_CHECK_GOTO(cls == H5T_FLOAT || cls == H5T_INTEGER, st, done, STC_EFORMAT,
                   "%s: dataset '%s' is not numeric", path, dataset);
    STC_CHECK_GOTO(dims[0] >= 3 && dims[1] >= 3 && dims[0] <= 65536 && dims[1] <= 65536, st, done,
                   STC_EFORMAT, "%s: dataset '%s' is %llu x %llu: each side must be in [3, 65536]",
                   path, dataset, (unsigned long long)dims[1], (unsigned long long)dims[0]);
    int nx = (int)dims[1], ny = (int)dims[0];
    STC_CALL_GOTO(srf_map_create(nx, ny, nx * dx, ny * dy, out), st, done);
    herr_t r;
    H5E_BEGIN_TRY { r = H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, (*out)->z); } H5E_END_TRY;
    STC_CHECK_GOTO(r >= 0, st, done, STC_EFORMAT, "%s: cannot read dataset '%s' as numbers", path,
                   dataset);
    STC_CALL_GOTO(check_finite(*out, path, "dataset '", dataset), st, done);
    char src[256];
    snprintf(src, sizeof src, "%s:%s", path, dataset);
    STC_CALL_GOTO(import_finish(*out, src, zscale), st, done);
done:
    if (st != STC_OK) srf_map_destroy(out);
    if (sp >= 0) H5Sclose(sp);
    if (d >= 0) H5Dclose(d);
    H5Fclose(f);
    return st;
}

/* ------------------------------------------------------------ write / read */

stc_status srf_tmpname(const char *path, char *buf, size_t n)
{
    /* open(O_EXCL, 0666) rather than mkstemp: the file gets the usual
     * 0666 & ~umask from the kernel, with no umask() round trip (process-wide
     * state another thread could see changed) */
    static unsigned counter;
    for (int tries = 0; tries < 100; tries++) {
        unsigned k = __atomic_fetch_add(&counter, 1u, __ATOMIC_RELAXED);
        int len = snprintf(buf, n, "%s.tmp-%ld-%u", path, (long)getpid(), k);
        STC_CHECK(len > 0 && (size_t)len < n, STC_EINVAL, "%s: path too long", path);
        int fd = open(buf, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            close(fd);
            return STC_OK;
        }
        STC_CHECK(errno == EEXIST, STC_EIO, "%s: cannot create a file there: %s", path,
                  strerror(errno));
    }
    return STC_FAIL(STC_EIO, "%s: cannot create a temporary file beside it (100 names taken)",
                    path);
}

static const char *origin_name(srf_origin o)
{
    return o == SRF_ORIGIN_SYNTH ? "synth" : o == SRF_ORIGIN_IMPORT ? "import" : "none";
}

static int write_synth_attrs(hid_t d, const srf_map *m)
{
    const srf_synth_params *p = &m->synth;
    double lL, lr, ls;
    srf_band(p, &lL, &lr, &ls);
    int e = stc_h5_put_u(d, "seed", m->seed) | stc_h5_put_s(d, "rng", "gsl mt19937") |
            stc_h5_put_s(d, "spectrum", srf_spectrum_name(p->spectrum)) | stc_h5_put_d(d, "rms_mm", p->rms) |
            stc_h5_put_s(d, "amplitude", p->amplitude == SRF_AMP_EXACT ? "exact" : "rayleigh") |
            stc_h5_put_i(d, "non_gaussian", p->non_gaussian) |
            stc_h5_put_d(d, "skewness_target", p->skewness) | stc_h5_put_d(d, "kurtosis_target", p->kurtosis) |
            stc_h5_put_d(d, "skewness_reached", m->skewness_reached) |
            stc_h5_put_d(d, "kurtosis_reached", m->kurtosis_reached);
    if (p->non_gaussian)
        e |= stc_h5_put_s(d, "johnson_family", m->johnson) | stc_h5_put_d(d, "johnson_gamma", m->johnson_gamma) |
             stc_h5_put_d(d, "johnson_delta", m->johnson_delta);
    if (p->spectrum == SRF_SPECTRUM_EXPONENTIAL)
        e |= stc_h5_put_d(d, "corr_length_x_mm", p->beta_x) | stc_h5_put_d(d, "corr_length_y_mm", p->beta_y) |
             stc_h5_put_s(d, "acf", "sigma^2 exp(-ln10 sqrt((tx/bx)^2 + (ty/by)^2))");
    if (p->spectrum == SRF_SPECTRUM_SELF_AFFINE)
        e |= stc_h5_put_d(d, "hurst", p->hurst) | stc_h5_put_d(d, "long_wavelength_mm", lL) |
             stc_h5_put_d(d, "rolloff_wavelength_mm", lr) | stc_h5_put_d(d, "cutoff_wavelength_mm", ls);
    return e;
}

static int write_attrs(hid_t d, const srf_map *m)
{
    int e = stc_h5_put_s(d, "format", SRF_FORMAT_NAME) | stc_h5_put_s(d, "units", "mm") |
            stc_h5_put_s(d, "layout", "[ny][nx] row-major, x = i*dx, y = j*dy, periodic") |
            stc_h5_put_i(d, "nx", m->nx) | stc_h5_put_i(d, "ny", m->ny) | stc_h5_put_d(d, "lx_mm", m->lx) |
            stc_h5_put_d(d, "ly_mm", m->ly) | stc_h5_put_d(d, "dx_mm", m->lx / m->nx) |
            stc_h5_put_d(d, "dy_mm", m->ly / m->ny) | stc_h5_put_s(d, "origin", origin_name(m->origin)) |
            stc_h5_put_i(d, "periodic", m->periodic);
    if (m->origin == SRF_ORIGIN_SYNTH) e |= write_synth_attrs(d, m);
    if (m->origin == SRF_ORIGIN_IMPORT)
        e |= stc_h5_put_s(d, "source", m->source) | stc_h5_put_d(d, "z_scale", m->zscale) |
             stc_h5_put_d(d, "detrend_tilt_x", m->tilt_x) | stc_h5_put_d(d, "detrend_tilt_y", m->tilt_y) |
             stc_h5_put_d(d, "detrend_offset_mm", m->offset);
    return e;
}

stc_status srf_map_write_h5(const srf_map *m, const char *path)
{
    STC_CHECK(m && m->z && path, STC_EINVAL, "map_write_h5: NULL argument");
    char tmp[4096];
    STC_CALL(srf_tmpname(path, tmp, sizeof tmp));
    stc_status st = STC_OK;
    hid_t f = -1, sp = -1, d = -1;
    hsize_t dims[2] = {(hsize_t)m->ny, (hsize_t)m->nx};
    H5E_BEGIN_TRY { f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK_GOTO(f >= 0, st, fail, STC_EIO, "%s: cannot create HDF5 file", tmp);
    sp = H5Screate_simple(2, dims, NULL);
    H5E_BEGIN_TRY {
        d = H5Dcreate2(f, SRF_DATASET, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    } H5E_END_TRY;
    STC_CHECK_GOTO(d >= 0, st, fail, STC_EIO, "%s: cannot create dataset", tmp);
    herr_t w;
    H5E_BEGIN_TRY { w = H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m->z); } H5E_END_TRY;
    STC_CHECK_GOTO(w >= 0, st, fail, STC_EIO, "%s: cannot write heights (disk full?)", tmp);
    int e;
    H5E_BEGIN_TRY { e = write_attrs(d, m); } H5E_END_TRY;
    STC_CHECK_GOTO(e == 0, st, fail, STC_EIO, "%s: cannot write attributes", tmp);
    H5Dclose(d);
    d = -1;
    H5Sclose(sp);
    sp = -1;
    herr_t c;
    H5E_BEGIN_TRY { c = H5Fclose(f); } H5E_END_TRY;
    f = -1;
    STC_CHECK_GOTO(c >= 0, st, fail, STC_EIO, "%s: cannot close (disk full?)", tmp);
    STC_CHECK_GOTO(rename(tmp, path) == 0, st, fail, STC_EIO, "%s: cannot rename from %s: %s",
                   path, tmp, strerror(errno));
    return STC_OK;
fail:
    H5E_BEGIN_TRY {
        if (d >= 0) H5Dclose(d);
        if (sp >= 0) H5Sclose(sp);
        if (f >= 0) H5Fclose(f);
    } H5E_END_TRY;
    remove(tmp);
    return st;
}

static srf_spectrum spectrum_from_name(const char *s)
{
    return strcmp(s, "self-affine") == 0 ? SRF_SPECTRUM_SELF_AFFINE
           : strcmp(s, "user") == 0      ? SRF_SPECTRUM_USER
                                         : SRF_SPECTRUM_EXPONENTIAL;
}

/* Optional metadata: absent attributes keep their defaults. */
static void read_meta(hid_t d, srf_map *m)
{
    char buf[256];
    srf_synth_params *p = &m->synth;
    p->nx = m->nx;
    p->ny = m->ny;
    p->lx = m->lx;
    p->ly = m->ly;
    if (stc_h5_get_s(d, "origin", buf, sizeof buf) == 0)
        m->origin = strcmp(buf, "synth") == 0    ? SRF_ORIGIN_SYNTH
                    : strcmp(buf, "import") == 0 ? SRF_ORIGIN_IMPORT
                                                 : SRF_ORIGIN_NONE;
    stc_h5_get_u(d, "seed", &m->seed);
    stc_h5_get_i(d, "periodic", &m->periodic);
    if (stc_h5_get_s(d, "spectrum", buf, sizeof buf) == 0) p->spectrum = spectrum_from_name(buf);
    if (stc_h5_get_s(d, "amplitude", buf, sizeof buf) == 0)
        p->amplitude = strcmp(buf, "rayleigh") == 0 ? SRF_AMP_RAYLEIGH : SRF_AMP_EXACT;
    stc_h5_get_d(d, "rms_mm", &p->rms);
    stc_h5_get_d(d, "corr_length_x_mm", &p->beta_x);
    stc_h5_get_d(d, "corr_length_y_mm", &p->beta_y);
    stc_h5_get_d(d, "hurst", &p->hurst);
    stc_h5_get_d(d, "long_wavelength_mm", &p->lambda_long);
    stc_h5_get_d(d, "rolloff_wavelength_mm", &p->lambda_rolloff);
    stc_h5_get_d(d, "cutoff_wavelength_mm", &p->lambda_cutoff);
    stc_h5_get_i(d, "non_gaussian", &p->non_gaussian);
    stc_h5_get_d(d, "skewness_target", &p->skewness);
    stc_h5_get_d(d, "kurtosis_target", &p->kurtosis);
    stc_h5_get_d(d, "skewness_reached", &m->skewness_reached);
    stc_h5_get_d(d, "kurtosis_reached", &m->kurtosis_reached);
    stc_h5_get_s(d, "johnson_family", m->johnson, sizeof m->johnson);
    stc_h5_get_d(d, "johnson_gamma", &m->johnson_gamma);
    stc_h5_get_d(d, "johnson_delta", &m->johnson_delta);
    stc_h5_get_s(d, "source", m->source, sizeof m->source);
    stc_h5_get_d(d, "z_scale", &m->zscale);
    stc_h5_get_d(d, "detrend_tilt_x", &m->tilt_x);
    stc_h5_get_d(d, "detrend_tilt_y", &m->tilt_y);
    stc_h5_get_d(d, "detrend_offset_mm", &m->offset);
}

stc_status srf_map_read(const char *path, srf_map **out)
{
    *out = NULL;
    stc_status st = STC_OK;
    hid_t f = -1, d = -1, sp = -1;
    STC_CALL(check_readable(path));
    H5E_BEGIN_TRY { f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(f >= 0, STC_EFORMAT,
              "%s: not an HDF5 file (import a text grid with --pixel-size DX)", path);
    H5E_BEGIN_TRY { d = H5Dopen2(f, SRF_DATASET, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK_GOTO(d >= 0, st, done, STC_EFORMAT,
                   "%s: no dataset '%s': not a stiction surface file (import a measured "
                   "dataset with --dataset NAME --pixel-size DX)", path, SRF_DATASET);
    sp = H5Dget_space(d);
    hsize_t dims[2];
    STC_CHECK_GOTO(H5Sget_simple_extent_ndims(sp) == 2, st, done, STC_EFORMAT,
                   "%s: dataset '%s' is not 2-D", path, SRF_DATASET);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    double lx, ly;
    STC_CHECK_GOTO(stc_h5_get_d(d, "lx_mm", &lx) == 0 && stc_h5_get_d(d, "ly_mm", &ly) == 0, st, done,
                   STC_EFORMAT, "%s: attributes lx_mm, ly_mm missing: not a stiction surface "
                   "file", path);
    STC_CHECK_GOTO(dims[0] >= 3 && dims[1] >= 3 && dims[0] <= 65536 && dims[1] <= 65536, st, done,
                   STC_EFORMAT, "%s: grid %llu x %llu: each side must be in [3, 65536]", path,
                   (unsigned long long)dims[1], (unsigned long long)dims[0]);
    STC_CALL_GOTO(srf_map_create((int)dims[1], (int)dims[0], lx, ly, out), st, done);
    herr_t r;
    H5E_BEGIN_TRY { r = H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, (*out)->z); } H5E_END_TRY;
    STC_CHECK_GOTO(r >= 0, st, done, STC_EFORMAT, "%s: cannot read '%s' as numbers", path,
                   SRF_DATASET);
    STC_CALL_GOTO(check_finite(*out, path, "'", SRF_DATASET), st, done);
    H5E_BEGIN_TRY { read_meta(d, *out); } H5E_END_TRY;
done:
    if (st != STC_OK) srf_map_destroy(out);
    if (sp >= 0) H5Sclose(sp);
    if (d >= 0) H5Dclose(d);
    H5Fclose(f);
    return st;
}
