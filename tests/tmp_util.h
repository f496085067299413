/* Where a test program puts its scratch files: $TMPDIR when set (make check
 * gives each test program a directory of its own there, removed when the
 * run ends), else /tmp.  Header-only. */
#ifndef STICTION_TESTS_TMP_UTIL_H
#define STICTION_TESTS_TMP_UTIL_H

#include <stdlib.h>

static inline const char *test_tmpdir(void)
{
    const char *t = getenv("TMPDIR");
    return t && *t ? t : "/tmp";
}

#endif
