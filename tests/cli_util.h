/* Helpers of the CLI tests: find the CLI binary, and a small strict JSON
 * checker (RFC 8259 grammar, no semantics).  Header-only: include after
 * <cmocka.h> in one test program. */
#ifndef STICTION_TESTS_CLI_UTIL_H
#define STICTION_TESTS_CLI_UTIL_H

#include <limits.h>
#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Path of the CLI: $STICTION_CLI, else ../bin/stiction beside this test
 * program (works for any O=).  Returns 0, or -1 if /proc/self/exe fails. */
static inline int cli_locate(char *cli, size_t n)
{
    const char *env = getenv("STICTION_CLI");
    if (env && *env) {
        snprintf(cli, n, "%s", env);
        return 0;
    }
    char self[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0) return -1;
    self[len] = '\0';
    char *slash = strrchr(self, '/');
    if (!slash) return -1;
    *slash = '\0';
    snprintf(cli, n, "%.*s/../bin/stiction", PATH_MAX - 32, self);
    return 0;
}

/* dir/name in one of 8 rotating static buffers, so that several fit in one
 * call's arguments. */
static inline const char *cli_path(const char *dir, const char *name)
{
    static char ring[8][PATH_MAX];
    static int k;
    char *p = ring[k++ % 8];
    snprintf(p, PATH_MAX, "%s/%s", dir, name);
    return p;
}

/* Run the shell command `cmd`; `which` = 1 captures its stdout, 2 its
 * stderr, into out (NUL-terminated).  Returns the exit status (128 +
 * signal if killed). */
static inline int cli_capture(const char *cmd, int which, char *out, size_t n)
{
    char full[PATH_MAX + 4096];
    snprintf(full, sizeof full, "%s %s", cmd, which == 1 ? "2>/dev/null" : "2>&1 >/dev/null");
    FILE *p = popen(full, "r");
    assert_non_null(p);
    size_t got = fread(out, 1, n - 1, p);
    out[got] = '\0';
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

/* The number after the n-th (0: first) "key": in a JSON text; NaN for
 * null.  Fails the test when the key is missing. */
static inline double cli_jnum_at(const char *text, const char *key, int n)
{
    char pat[96];
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = text;
    for (int k = 0; p && k <= n; k++)
        if ((p = strstr(p, pat))) p += strlen(pat);
    if (!p) fail_msg("key '%s' (occurrence %d) missing", key, n);
    if (!strncmp(p, "null", 4)) return NAN;
    return strtod(p, NULL);
}

static inline double cli_jnum(const char *text, const char *key)
{
    return cli_jnum_at(text, key, 0);
}

static inline const char *ws(const char *s)
{
    while (*s == ' ' || *s == '\n' || *s == '\t' || *s == '\r') s++;
    return s;
}

static inline const char *jvalue(const char *s);

static inline const char *jstring(const char *s)
{
    if (*s++ != '"') return NULL;
    for (; *s && *s != '"'; s++) {
        if ((unsigned char)*s < 0x20) return NULL;
        if (*s == '\\' && !*++s) return NULL;
    }
    return *s == '"' ? s + 1 : NULL;
}

static inline const char *jnumber(const char *s)
{
    char *end;
    if (!(*s == '-' || (*s >= '0' && *s <= '9'))) return NULL;
    double v = strtod(s, &end);
    return (end == s || !isfinite(v)) ? NULL : end;
}

static inline const char *jseq(const char *s, char close, int keyed)
{
    s = ws(s + 1);
    if (*s == close) return s + 1;
    for (;;) {
        if (keyed) {
            if (!(s = jstring(ws(s)))) return NULL;
            s = ws(s);
            if (*s++ != ':') return NULL;
        }
        if (!(s = jvalue(s))) return NULL;
        s = ws(s);
        if (*s == close) return s + 1;
        if (*s++ != ',') return NULL;
    }
}

static inline const char *jvalue(const char *s)
{
    s = ws(s);
    if (*s == '{') return jseq(s, '}', 1);
    if (*s == '[') return jseq(s, ']', 0);
    if (*s == '"') return jstring(s);
    if (!strncmp(s, "true", 4) || !strncmp(s, "null", 4)) return s + 4;
    if (!strncmp(s, "false", 5)) return s + 5;
    return jnumber(s);
}

static inline void assert_json(const char *text)
{
    const char *end = jvalue(text);
    if (!end || *ws(end) != '\0') fail_msg("not one JSON value: %.300s", end ? end : text);
}

#endif
