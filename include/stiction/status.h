/* stiction — status codes and error reporting shared by every module.
 *
 * Every library function that can fail returns an stc_status.  On failure it
 * also records a human-readable message (what was wrong, the value, what was
 * expected) retrievable with stc_errmsg() from the same thread.  Library code
 * never prints and never exits.
 */
#ifndef STICTION_STATUS_H
#define STICTION_STATUS_H

#include "stiction/export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum stc_status {
    STC_OK = 0,
    STC_EINVAL,       /* invalid argument or parameter value */
    STC_ENOMEM,       /* allocation failed */
    STC_EIO,          /* file could not be read or written */
    STC_EFORMAT,      /* malformed input file */
    STC_ENOCONV,      /* an iteration did not converge (reason in message) */
    STC_ESOLVER,      /* linear solver failure (e.g. matrix not positive definite) */
    STC_ERANGE,       /* result outside representable or fitted range */
    STC_EUNSUPPORTED, /* feature not available for these inputs */
    STC_NSTATUS
} stc_status;

/* Short name of a status code.  Returns a static string; thread-safe. */
STC_API const char *stc_strerror(stc_status s);

/* Message recorded by the last failing call in this thread ("" if none).
 * Returns a pointer to thread-local storage, valid until the next failure. */
STC_API const char *stc_errmsg(void);

/* Record a failure: formats the message into thread-local storage and
 * returns `s` so callers can write `return stc_error(...)`. */
STC_API stc_status stc_error(stc_status s, const char *file, int line,
                             const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Clear the thread's message. */
STC_API void stc_error_clear(void);

#ifdef __cplusplus
}
#endif
#endif
