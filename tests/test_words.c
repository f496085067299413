/* The tree speaks of the product only: no tracked text file may refer to a
 * numbered work item or meeting of its development (the word "issue" or
 * "session", optionally plural, then a space or a hyphen or nothing, an
 * optional '#' and a digit;
 * any case), nor to a path of one particular machine (the directory "work"
 * at the root of the file system).  History belongs in commit messages.
 *
 * The files are those `git ls-files` lists in the repository root: the
 * directory above STC_DATA_DIR (the Makefile passes "<root>/data"), or
 * $STICTION_WORDS_ROOT if set (any git work tree: useful to try the check on
 * a scratch repository).  Without git or without a .git entry in the root
 * (an exported source tree) the test is skipped.  Binary files (a NUL byte
 * in the first 8 KB) and files over 1 MB are not read.  Every offending line
 * is printed as file:line: text.
 *
 * The patterns are assembled from pieces so that this file never matches
 * them itself. */
#include <limits.h>
#include <regex.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

#define MAX_FILE_BYTES (1L << 20) /* files above this size are not read */
#define BINARY_PROBE 8192         /* a NUL byte in these first bytes: binary */
#define SHOW_CHARS 200            /* at most this much of an offending line */

/* \b emulated by (^|[^[:alnum:]_]); the words are split so that this source
 * line does not spell the pattern out. */
static const char WORD_RE[] = "(^|[^[:alnum:]_])(iss" "ue|sess" "ion)s?[ -]?#?[0-9]";
static const char PATH_BAD[] = "/wor" "k/";

static regex_t word_re;

static int compile_patterns(void)
{
    return regcomp(&word_re, WORD_RE, REG_EXTENDED | REG_ICASE | REG_NOSUB);
}

/* 1 if the NUL-terminated line is offending. */
static int line_bad(const char *line)
{
    return strstr(line, PATH_BAD) != NULL || regexec(&word_re, line, 0, NULL, 0) == 0;
}

/* ------------------------------------------------------------ the matcher */

/* The pattern itself, on made-up lines (pieces glued at run time). */
static void test_pattern(void **state)
{
    (void)state;
    assert_int_equal(compile_patterns(), 0);
    static const char *const bad[][2] = {
        {"see iss", "ue 4 for the reason"},
        {"Iss", "ue #12: the fix"},
        {"ISS", "UES 3 and 4"},
        {"(sess", "ion 16; the case failed)"},
        {"", "Sess" "ions 2-3"},
        {"tools/x.py (iss", "ue 5)"},
        {"the iss", "ue-3 wording"},
        {"sess", "ion12 notes"},
        {"stored in /wor", "k/main/data"},
    };
    static const char *const good[][2] = {
        {"tissue 4 of the sample", ""},
        {"reissue 3 times", ""},
        {"issues: none", ""},
        {"an issue with the mesh", ""},
        {"session_4 variable", ""},
        {"issue  4 (two spaces)", ""},
        {"homework/ directory", ""},
        {"/workdir/ and /works/", ""},
    };
    char line[256];
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(line, sizeof line, "%s%s", bad[i][0], bad[i][1]);
        if (!line_bad(line)) fail_msg("not flagged: '%s'", line);
    }
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        snprintf(line, sizeof line, "%s%s", good[i][0], good[i][1]);
        if (line_bad(line)) fail_msg("flagged: '%s'", line);
    }
    regfree(&word_re);
}

/* ------------------------------------------------------------ the tree */

/* The repository root into `root`: $STICTION_WORDS_ROOT, else STC_DATA_DIR
 * without its last component, else two levels above this program
 * (<root>/tests-bin/test_words). */
static int find_root(char *root, size_t n)
{
    const char *env = getenv("STICTION_WORDS_ROOT");
    if (env && *env) {
        snprintf(root, n, "%s", env);
        return 0;
    }
#ifdef STC_DATA_DIR
    snprintf(root, n, "%s", STC_DATA_DIR);
#else
    ssize_t len = readlink("/proc/self/exe", root, n - 1);
    if (len <= 0) return -1;
    root[len] = '\0';
    char *s = strrchr(root, '/');
    if (!s) return -1;
    *s = '\0';
#endif
    char *slash = strrchr(root, '/');
    if (!slash) return -1;
    if (slash == root) slash[1] = '\0';
    else *slash = '\0';
    return 0;
}

/* Single-quoted for sh. */
static void sh_quote(const char *s, char *out, size_t n)
{
    size_t k = 0;
    if (k + 1 < n) out[k++] = '\'';
    for (; *s && k + 5 < n; s++) {
        if (*s == '\'') {
            memcpy(out + k, "'\\''", 4);
            k += 4;
        } else {
            out[k++] = *s;
        }
    }
    if (k + 1 < n) out[k++] = '\'';
    out[k] = '\0';
}

/* `git ls-files -z` of root, NUL-separated, malloc'd; *len its size.  NULL
 * (and a reason in `why`) if git fails. */
static char *list_files(const char *root, size_t *len, char *why, size_t nwhy)
{
    char q[2 * PATH_MAX + 8], cmd[2 * PATH_MAX + 64];
    sh_quote(root, q, sizeof q);
    snprintf(cmd, sizeof cmd, "git -C %s ls-files -z 2>&1", q);
    FILE *p = popen(cmd, "r");
    if (!p) {
        snprintf(why, nwhy, "cannot run git");
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n, p)) > 0) {
        n += got;
        if (n == cap) {
            char *b = realloc(buf, cap *= 2);
            if (!b) free(buf);
            buf = b;
        }
    }
    int st = pclose(p);
    if (!buf) {
        snprintf(why, nwhy, "out of memory");
        return NULL;
    }
    if (st == -1 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        /* the output is git's (or sh's) message */
        size_t m = n < 300 ? n : 300;
        for (size_t i = 0; i < m; i++)
            if (buf[i] == '\n' || buf[i] == '\0') buf[i] = ' ';
        snprintf(why, nwhy, "git ls-files failed (status %d): %.*s",
                 WIFEXITED(st) ? WEXITSTATUS(st) : -1, (int)m, buf);
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

/* Read a regular file of at most MAX_FILE_BYTES; NULL if it is not one, is
 * larger, or is binary.  NUL-terminated; *len its size. */
static char *read_text(const char *path, size_t *len)
{
    struct stat sb;
    if (lstat(path, &sb) != 0 || !S_ISREG(sb.st_mode) || sb.st_size > MAX_FILE_BYTES)
        return NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = malloc((size_t)sb.st_size + 1);
    size_t n = buf ? fread(buf, 1, (size_t)sb.st_size, f) : 0;
    fclose(f);
    if (!buf) return NULL;
    buf[n] = '\0';
    if (memchr(buf, '\0', n < BINARY_PROBE ? n : BINARY_PROBE)) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

/* Offending lines of one file, printed; returns their number. */
static int scan_file(const char *root, const char *name)
{
    char path[2 * PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", root, name);
    size_t n = 0;
    char *buf = read_text(path, &n);
    if (!buf) return 0;
    int bad = 0;
    long lineno = 0;
    for (char *line = buf; line < buf + n || (line == buf && n == 0);) {
        char *end = memchr(line, '\n', (size_t)(buf + n - line));
        if (end) *end = '\0';
        lineno++;
        if (line_bad(line)) { /* (a NUL past the probe ends the line early) */
            size_t l = strlen(line);
            if (l && line[l - 1] == '\r') line[--l] = '\0';
            printf("%s:%ld: %.*s%s\n", name, lineno, SHOW_CHARS, line,
                   l > SHOW_CHARS ? " ..." : "");
            bad++;
        }
        if (!end) break;
        line = end + 1;
    }
    free(buf);
    return bad;
}

static void test_tree(void **state)
{
    (void)state;
    char root[PATH_MAX], why[512], gitpath[PATH_MAX + 8];
    if (find_root(root, sizeof root) != 0) {
        printf("# words: cannot find the repository root; skipped\n");
        fflush(stdout);
        skip();
    }
    struct stat sb;
    snprintf(gitpath, sizeof gitpath, "%s/.git", root);
    if (stat(gitpath, &sb) != 0) {
        printf("# words: %s is not a git work tree (no .git); skipped\n", root);
        fflush(stdout);
        skip();
    }
    size_t len = 0;
    char *list = list_files(root, &len, why, sizeof why);
    if (!list) {
        printf("# words: %s: %s; skipped\n", root, why);
        fflush(stdout);
        skip();
    }
    assert_int_equal(compile_patterns(), 0);
    int files = 0, bad_files = 0, bad_lines = 0;
    for (size_t i = 0; i < len;) {
        const char *name = list + i;
        size_t l = strnlen(name, len - i);
        if (l == len - i) break; /* not NUL-terminated: cannot happen with -z */
        i += l + 1;
        files++;
        int b = scan_file(root, name);
        if (b) {
            bad_files++;
            bad_lines += b;
        }
    }
    free(list);
    regfree(&word_re);
    printf("# words: %d tracked files in %s, %d offending lines in %d files\n", files, root,
           bad_lines, bad_files);
    fflush(stdout);
    if (bad_lines)
        fail_msg("%d lines in %d files refer to the development process or to one machine's "
                 "paths (listed above): state the fact without its history",
                 bad_lines, bad_files);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pattern),
        cmocka_unit_test(test_tree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
