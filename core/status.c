/* Status codes and the thread-local error message. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "stiction/status.h"

#define STC_ERRMSG_MAX 1024

static _Thread_local char errmsg[STC_ERRMSG_MAX];

const char *stc_strerror(stc_status s)
{
    static const char *const names[STC_NSTATUS] = {
        [STC_OK] = "success",
        [STC_EINVAL] = "invalid argument",
        [STC_ENOMEM] = "out of memory",
        [STC_EIO] = "input/output error",
        [STC_EFORMAT] = "malformed input",
        [STC_ENOCONV] = "no convergence",
        [STC_ESOLVER] = "linear solver failure",
        [STC_ERANGE] = "out of range",
        [STC_EUNSUPPORTED] = "unsupported",
    };
    if ((int)s < 0 || s >= STC_NSTATUS) return "unknown status";
    return names[s];
}

const char *stc_errmsg(void) { return errmsg; }

void stc_error_clear(void) { errmsg[0] = '\0'; }

stc_status stc_error(stc_status s, const char *file, int line,
                     const char *fmt, ...)
{
    /* file/line are kept for debugging builds; the user sees the message. */
    (void)file;
    (void)line;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(errmsg, sizeof errmsg, fmt, ap);
    va_end(ap);
    return s;
}
