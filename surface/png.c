/* Grey-scale PNG of a height map (libpng), written to a temp file and renamed. */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "srf_impl.h"
#include "stc_check.h"

/* zlib level 1..9: 3 keeps a 4096² map under a second with near-best size */
#define SRF_PNG_COMPRESSION 3

/* Rows top to bottom = y from high to low, so the picture has y up. */
static int write_rows(png_structp png, const srf_map *m, unsigned char *row, double lo, double hi)
{
    double f = hi > lo ? 255.0 / (hi - lo) : 0.0;
    for (int r = 0; r < m->ny; r++) {
        const double *z = m->z + (size_t)(m->ny - 1 - r) * m->nx;
        for (int i = 0; i < m->nx; i++) row[i] = (unsigned char)lrint((z[i] - lo) * f);
        png_write_row(png, row);
    }
    return 0;
}

static stc_status write_png_file(FILE *fp, const srf_map *m, unsigned char *row, double lo,
                                 double hi)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        return STC_FAIL(STC_ENOMEM, "png: out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return STC_FAIL(STC_EIO, "png: libpng write error (disk full?)");
    }
    png_init_io(png, fp);
    png_set_compression_level(png, SRF_PNG_COMPRESSION);
    png_set_IHDR(png, info, (png_uint_32)m->nx, (png_uint_32)m->ny, 8, PNG_COLOR_TYPE_GRAY,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    write_rows(png, m, row, lo, hi);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return STC_OK;
}

stc_status srf_map_write_png(const srf_map *m, const char *path)
{
    STC_CHECK(m && m->z && path, STC_EINVAL, "map_write_png: NULL argument");
    size_t n = (size_t)m->nx * m->ny;
    double lo = m->z[0], hi = m->z[0];
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
    for (size_t k = 0; k < n; k++) {
        lo = fmin(lo, m->z[k]);
        hi = fmax(hi, m->z[k]);
    }
    char tmp[4096];
    STC_CALL(srf_tmpname(path, tmp, sizeof tmp));
    unsigned char *row = malloc((size_t)m->nx);
    FILE *fp = fopen(tmp, "wb");
    stc_status st = STC_OK;
    STC_CHECK_GOTO(row, st, fail, STC_ENOMEM, "png: out of memory");
    STC_CHECK_GOTO(fp, st, fail, STC_EIO, "%s: cannot open: %s", tmp, strerror(errno));
    STC_CALL_GOTO(write_png_file(fp, m, row, lo, hi), st, fail);
    int c = fclose(fp);
    fp = NULL;
    STC_CHECK_GOTO(c == 0, st, fail, STC_EIO, "%s: write error: %s", tmp, strerror(errno));
    STC_CHECK_GOTO(rename(tmp, path) == 0, st, fail, STC_EIO, "%s: cannot rename: %s", path,
                   strerror(errno));
    free(row);
    return STC_OK;
fail:
    if (fp) fclose(fp);
    free(row);
    remove(tmp);
    return st;
}
