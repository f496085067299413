/* stiction — strict parsing of option values, the project's range-check
 * messages, and INI files: the helpers every option parser of the library
 * and of a caller (the CLI) shares. */
#ifndef STICTION_PARSE_H
#define STICTION_PARSE_H

#include "stiction/export.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parse a number from text strictly: whole string, finite.  Messages name
 * `key`.  Helpers for every option parser in the project. */
STC_API stc_status stc_parse_double(const char *key, const char *value, double *out);
STC_API stc_status stc_parse_long(const char *key, const char *value, long *out);

/* Range checks producing the project's standard message
 * "<key> = <value>: must be <what>". lo/hi inclusive flags. */
STC_API stc_status stc_check_range(const char *key, double v, double lo, int lo_incl,
                                   double hi, int hi_incl);

/* Normalise an option key in place: strip leading "--", map '_' to '-'. */
STC_API const char *stc_key_normalise(const char *key, char *buf, int bufsize);

/* INI files (parsed by libinih): calls handler(user, section, key, value) for
 * every entry; stops at the first handler failure.  Section names are passed
 * through (may be ""); keys are normalised.  Returns STC_EIO when the file
 * cannot be opened or read or is a directory, STC_EFORMAT with the line
 * number for a syntax error, or the handler's status. */
typedef stc_status (*stc_ini_handler)(void *user, const char *section,
                                      const char *key, const char *value);
STC_API stc_status stc_ini_load(const char *path, stc_ini_handler handler, void *user);

#ifdef __cplusplus
}
#endif
#endif
