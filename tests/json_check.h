/* A small strict JSON checker for the CLI tests (RFC 8259 grammar, no
 * semantics).  Header-only: include after <cmocka.h> in one test program. */
#ifndef STICTION_TESTS_JSON_CHECK_H
#define STICTION_TESTS_JSON_CHECK_H

#include <math.h>
#include <stdlib.h>
#include <string.h>


static const char *ws(const char *s)
{
    while (*s == ' ' || *s == '\n' || *s == '\t' || *s == '\r') s++;
    return s;
}

static const char *jvalue(const char *s);

static const char *jstring(const char *s)
{
    if (*s++ != '"') return NULL;
    for (; *s && *s != '"'; s++) {
        if ((unsigned char)*s < 0x20) return NULL;
        if (*s == '\\' && !*++s) return NULL;
    }
    return *s == '"' ? s + 1 : NULL;
}

static const char *jnumber(const char *s)
{
    char *end;
    if (!(*s == '-' || (*s >= '0' && *s <= '9'))) return NULL;
    double v = strtod(s, &end);
    return (end == s || !isfinite(v)) ? NULL : end;
}

static const char *jseq(const char *s, char close, int keyed)
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

static const char *jvalue(const char *s)
{
    s = ws(s);
    if (*s == '{') return jseq(s, '}', 1);
    if (*s == '[') return jseq(s, ']', 0);
    if (*s == '"') return jstring(s);
    if (!strncmp(s, "true", 4) || !strncmp(s, "null", 4)) return s + 4;
    if (!strncmp(s, "false", 5)) return s + 5;
    return jnumber(s);
}

static void assert_json(const char *text)
{
    const char *end = jvalue(text);
    if (!end || *ws(end) != '\0') fail_msg("not one JSON value: %.300s", end ? end : text);
}

#endif
