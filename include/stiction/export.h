/* stiction — the mark of the public API.  The library is compiled with
 * -fvisibility=hidden, so libstiction.so exports exactly the functions whose
 * declarations in include/stiction/ carry STC_API (make check compares the
 * two: tools/check-exports.sh); everything else stays internal to the
 * library (the static library keeps it all, for the CLI and the tests). */
#ifndef STICTION_EXPORT_H
#define STICTION_EXPORT_H

#if defined(__GNUC__) && __GNUC__ >= 4
#define STC_API __attribute__((visibility("default")))
#else
#define STC_API
#endif

#endif
