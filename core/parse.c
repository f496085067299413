/* Strict text parsing, range checks and INI files: the helpers every
 * option parser of the library and the CLI shares (include/stiction/parse.h). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <ini.h>

#include "stiction/parse.h"
#include "stc_check.h"

const char *stc_key_normalise(const char *key, char *buf, int bufsize)
{
    int n = 0;
    while (*key == '-') key++;
    for (; *key && n < bufsize - 1; key++)
        buf[n++] = (*key == '_') ? '-' : *key;
    buf[n] = '\0';
    return buf;
}

stc_status stc_parse_double(const char *key, const char *value, double *out)
{
    char *end;
    STC_CHECK(value && *value, STC_EINVAL, "%s: missing value (expected a number)", key);
    errno = 0;
    double v = strtod(value, &end);
    while (*end && isspace((unsigned char)*end)) end++;
    STC_CHECK(end != value && *end == '\0', STC_EINVAL,
              "%s = '%s': not a number", key, value);
    STC_CHECK(isfinite(v) && errno != ERANGE, STC_EINVAL,
              "%s = '%s': must be a finite number", key, value);
    *out = v;
    return STC_OK;
}

stc_status stc_parse_long(const char *key, const char *value, long *out)
{
    char *end;
    STC_CHECK(value && *value, STC_EINVAL, "%s: missing value (expected an integer)", key);
    errno = 0;
    long v = strtol(value, &end, 10);
    while (*end && isspace((unsigned char)*end)) end++;
    STC_CHECK(end != value && *end == '\0' && errno != ERANGE, STC_EINVAL,
              "%s = '%s': not an integer", key, value);
    *out = v;
    return STC_OK;
}

stc_status stc_check_range(const char *key, double v, double lo, int lo_incl,
                           double hi, int hi_incl)
{
    int ok = !isnan(v) && (lo_incl ? v >= lo : v > lo) && (hi_incl ? v <= hi : v < hi);
    if (ok) return STC_OK;
    if (isinf(hi))
        return STC_FAIL(STC_EINVAL, "%s = %g: must be %s %g", key, v,
                        lo_incl ? ">=" : ">", lo);
    return STC_FAIL(STC_EINVAL, "%s = %g: must be in %c%g, %g%c", key, v,
                    lo_incl ? '[' : '(', lo, hi, hi_incl ? ']' : ')');
}

/* ---- INI -------------------------------------------------------------- */

typedef struct {
    stc_ini_handler handler;
    void *user;
    stc_status status;
} ini_ctx;

static int ini_entry(void *u, const char *section, const char *name, const char *value)
{
    ini_ctx *c = u;
    char k[64];
    if (c->status != STC_OK) return 0; /* keep the first failure */
    stc_key_normalise(name, k, sizeof k);
    c->status = c->handler(c->user, section ? section : "", k, value);
    return c->status == STC_OK; /* inih: nonzero = keep going */
}

stc_status stc_ini_load(const char *path, stc_ini_handler handler, void *user)
{
    ini_ctx c = {handler, user, STC_OK};
    struct stat sb;
    /* fopen() opens a directory for reading, and its first read fails:
     * inih took that for an empty file and the run went on with defaults */
    STC_CHECK(stat(path, &sb) == 0, STC_EIO, "config = '%s': cannot open file (%s)", path,
              strerror(errno));
    STC_CHECK(!S_ISDIR(sb.st_mode), STC_EIO, "config = '%s': is a directory (expected an INI "
              "file of 'key = value' lines)", path);
    FILE *f = fopen(path, "r");
    STC_CHECK(f, STC_EIO, "config = '%s': cannot open file (%s)", path, strerror(errno));
    int line = ini_parse_file(f, ini_entry, &c);
    int read_errno = ferror(f) ? (errno ? errno : EIO) : 0;
    fclose(f);
    if (c.status != STC_OK) return c.status; /* handler already set the message */
    STC_CHECK(!read_errno, STC_EIO, "config = '%s': cannot read the file (%s)", path,
              strerror(read_errno));
    STC_CHECK(line == 0, STC_EFORMAT,
              "config = '%s': syntax error on line %d (expected 'key = value')", path, line);
    return STC_OK;
}
