/* Internal error-propagation macros (not installed).
 * STC_CHECK(cond, code, fmt, ...): fail with `code` and a message unless cond.
 * STC_CALL(expr): evaluate a call returning stc_status, propagate failure.
 * Both `return`; use STC_CHECK_GOTO / STC_CALL_GOTO where cleanup is needed. */
#ifndef STICTION_STC_CHECK_H
#define STICTION_STC_CHECK_H

#include "stiction/status.h"

#define STC_FAIL(code, ...) stc_error((code), __FILE__, __LINE__, __VA_ARGS__)

#define STC_CHECK(cond, code, ...)                                        \
    do {                                                                  \
        if (!(cond)) return STC_FAIL((code), __VA_ARGS__);                \
    } while (0)

#define STC_CALL(expr)                                                    \
    do {                                                                  \
        stc_status stc_call_s_ = (expr);                                  \
        if (stc_call_s_ != STC_OK) return stc_call_s_;                    \
    } while (0)

/* Variants that store the status in `st` and jump to `label`. */
#define STC_CHECK_GOTO(cond, st, label, code, ...)                        \
    do {                                                                  \
        if (!(cond)) { (st) = STC_FAIL((code), __VA_ARGS__); goto label; } \
    } while (0)

#define STC_CALL_GOTO(expr, st, label)                                    \
    do {                                                                  \
        (st) = (expr);                                                    \
        if ((st) != STC_OK) goto label;                                   \
    } while (0)

#endif
