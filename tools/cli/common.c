/* Option parsing shared by every subcommand: INI config, then argv. */
#include <ctype.h>
#include <errno.h>
#include <signal.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

typedef struct {
    const cli_opt *opts;
    stc_params *params;
    cli_set_fn set;
    void *ctx;
} dispatch_ctx;

static const cli_opt *find_opt(const cli_opt *opts, const char *key)
{
    for (; opts && opts->name; opts++)
        if (*opts->name && strcmp(opts->name, key) == 0) return opts;
    return NULL;
}

/* ---- the closest name to a mistyped one ------------------------------- */

/* Longest name compared (keys are read into 64-byte buffers). */
#define NEAR_MAX 64

static int near_distance(const char *a, const char *b)
{
    size_t m = strlen(a), n = strlen(b);
    if (m >= NEAR_MAX || n >= NEAR_MAX) return INT_MAX;
    int d[NEAR_MAX + 1][NEAR_MAX + 1];
    for (size_t i = 0; i <= m; i++) d[i][0] = (int)i;
    for (size_t j = 0; j <= n; j++) d[0][j] = (int)j;
    for (size_t i = 1; i <= m; i++)
        for (size_t j = 1; j <= n; j++) {
            int ai = tolower((unsigned char)a[i - 1]), bj = tolower((unsigned char)b[j - 1]);
            int v = d[i - 1][j - 1] + (ai != bj);
            if (d[i - 1][j] + 1 < v) v = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < v) v = d[i][j - 1] + 1;
            /* two neighbours swapped ("formulsa") cost one edit */
            if (i > 1 && j > 1 && ai == tolower((unsigned char)b[j - 2]) &&
                tolower((unsigned char)a[i - 2]) == bj && d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[m][n];
}

void cli_near_init(cli_near *n, const char *typed)
{
    n->typed = typed;
    n->best = NULL;
    n->dist = INT_MAX;
}

void cli_near_add(cli_near *n, const char *name)
{
    int d = near_distance(n->typed, name);
    if (d < n->dist) n->dist = d, n->best = name;
}

const char *cli_near_best(const cli_near *n)
{
    int len = (int)strlen(n->typed), limit = len / 3;
    limit = limit < 1 ? 1 : limit > 2 ? 2 : limit;
    return n->best && n->dist <= limit && n->dist < len ? n->best : NULL;
}

/* The known option closest to `key`: the subcommand's, the common ones
 * (with params) and, on the command line, config and help.  NULL if none
 * is close. */
static const char *near_option(const char *key, const cli_opt *opts, int common, int cmdline)
{
    cli_near n;
    cli_near_init(&n, key);
    for (; opts && opts->name; opts++) cli_near_add(&n, opts->name);
    for (int i = 0; common && stc_params_key(i); i++) cli_near_add(&n, stc_params_key(i));
    if (cmdline) cli_near_add(&n, "config"), cli_near_add(&n, "help");
    return cli_near_best(&n);
}

/* " (did you mean <pre><near>?)", or `otherwise` when near is NULL. */
static const char *near_hint(char *buf, size_t n, const char *pre, const char *near,
                             const char *otherwise)
{
    if (near) snprintf(buf, n, " (did you mean %s%s?)", pre, near);
    else snprintf(buf, n, "%s", otherwise);
    return buf;
}

/* Route one key to the subcommand or to the common parameters: an option
 * the subcommand lists is its own, also where a common key has its name
 * (surface predict refuses t-over-R with its own reason). */
static stc_status dispatch(void *u, const char *section, const char *key,
                           const char *value)
{
    dispatch_ctx *d = u;
    (void)section;
    if (d->set && find_opt(d->opts, key)) {
        stc_status s = d->set(d->ctx, key, value);
        if (s != STC_EUNSUPPORTED) return s;
    }
    if (d->params) {
        stc_status s = stc_params_set(d->params, key, value);
        if (s != STC_EUNSUPPORTED) return s;
    }
    char hint[96];
    const char *near = near_option(key, d->opts, d->params != NULL, 0);
    return stc_error(STC_EINVAL, __FILE__, __LINE__, "unknown option '%s'%s", key,
                     near_hint(hint, sizeof hint, "", near, " (see --help for the valid keys)"));
}

/* The normalised option name of argument a ("--t_over_R=3" -> "t-over-R")
 * into key[n]; returns the value after '=', or NULL when there is none. */
static const char *arg_key(const char *a, char *key, size_t n)
{
    const char *eq = strchr(a, '=');
    size_t len = eq ? (size_t)(eq - a) : strlen(a);
    if (len >= n) len = n - 1;
    memcpy(key, a, len);
    key[len] = '\0';
    stc_key_normalise(key, key, (int)n);
    return eq ? eq + 1 : NULL;
}

static int is_common_key(const char *key)
{
    stc_params scratch;
    stc_params_default(&scratch);
    /* a value-free probe: parse with a valid dummy and see if recognised */
    return stc_params_set(&scratch, key, "0.25") != STC_EUNSUPPORTED;
}

/* --help: an option's name in a column of HELP_LEFT characters, its text
 * wrapped at HELP_WIDTH columns; a name too wide for the column gets a line
 * of its own. */
enum { HELP_LEFT = 25, HELP_WIDTH = 92 };

/* A line may break at the space p[i], except before a unit ("3 %"). */
static int help_break(const char *p, int i) { return p[i] == ' ' && p[i + 1] != '%'; }

static void help_line(const char *left, const char *text)
{
    int col = printf("  %s", left);
    if (col >= HELP_LEFT) printf("\n"), col = 0;
    const int room = HELP_WIDTH - HELP_LEFT;
    for (const char *p = text; *p;) {
        int len = (int)strlen(p), cut = len;
        if (len > room) { /* at the last space that fits, or after one long word */
            for (cut = room; cut > 0 && !help_break(p, cut); cut--) {}
            if (cut == 0)
                for (cut = room; p[cut] && !help_break(p, cut); cut++) {}
        }
        printf("%*s%.*s\n", HELP_LEFT - col, "", cut, p);
        col = 0;
        for (p += cut; *p == ' '; p++) {}
    }
}

static void help_config(void)
{
    help_line("--config FILE", "INI file with the same keys as the options (the command line "
                               "overrides it)");
    help_line("--help", "this text");
}

static void print_help(const char *cmdname, const char *usage, const cli_opt *opts)
{
    printf("usage: stiction %s %s\n", cmdname, usage);
    int placed = 0, headed = 0;
    for (const cli_opt *o = opts; o && o->name; o++) {
        if (!*o->name && !o->arg) { /* a heading */
            printf("\n%s:\n", o->help);
            headed = 1;
            continue;
        }
        if (!headed) printf("\nOptions:\n"), headed = 1;
        if (!*o->name) {
            help_config();
            placed = 1;
            continue;
        }
        char left[64];
        snprintf(left, sizeof left, "--%s%s%s", o->name, o->arg ? " " : "",
                 o->arg ? o->arg : "");
        help_line(left, o->help);
    }
    if (!placed) {
        if (!headed) printf("\nOptions:\n");
        help_config();
    }
}

FILE *cli_out_open(cli_out *o, const char *dir, const char *name)
{
    snprintf(o->path, sizeof o->path, "%s/%s", dir, name);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp", o->path);
    return o->f = fopen(o->tmp, "w");
}

int cli_out_dir(const char *cmd, const char *dir, int *made)
{
    struct stat st;
    char why[160] = "";
    int new_dir = mkdir(dir, 0777) == 0;
    if (made) *made = new_dir;
    if (!new_dir && errno != EEXIST)
        snprintf(why, sizeof why, "cannot create the directory (%s)", strerror(errno));
    else if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        snprintf(why, sizeof why, "must be a directory");
    else if (access(dir, W_OK | X_OK) != 0)
        snprintf(why, sizeof why, "the directory is not writable");
    if (!*why) return CLI_EXIT_OK;
    fprintf(stderr, "stiction %s: out = '%s': %s (valid: a writable directory, created if "
            "missing)\n", cmd, dir, why);
    return CLI_EXIT_USAGE;
}

int cli_out_close(cli_out *o)
{
    int bad = ferror(o->f);
    if (fclose(o->f) != 0 || bad || rename(o->tmp, o->path) != 0) return remove(o->tmp), -1;
    return 0;
}

double cli_percent_up(double fraction)
{
    /* 1e-9 keeps a share that is a whole tenth (5.0 %) from rounding up
     * through its binary representation */
    return ceil(1000.0 * fraction - 1e-9) / 10.0;
}

int cli_place_all(int n, const char *const *tmp, const char *const *path)
{
    int k = 0;
    while (k < n && (!tmp[k] || rename(tmp[k], path[k]) == 0)) k++;
    if (k == n) return -1;
    int err = errno;
    for (int i = 0; i < n; i++)
        if (tmp[i]) remove(i < k ? path[i] : tmp[i]);
    errno = err;
    return k;
}

int cli_plot_open(cli_plot *p)
{
    p->sigpipe = signal(SIGPIPE, SIG_IGN);
    p->g = popen("gnuplot >/dev/null", "w");
    if (!p->g) signal(SIGPIPE, p->sigpipe);
    return p->g ? 0 : -1;
}

int cli_plot_close(cli_plot *p, const char *file, int *status)
{
    *status = pclose(p->g);
    p->g = NULL;
    signal(SIGPIPE, p->sigpipe);
    struct stat sb;
    return *status == 0 && stat(file, &sb) == 0 && sb.st_size > 0 ? 0 : -1;
}

void cli_command_line(char *buf, size_t n, const char *cmd, int argc, char **argv)
{
    snprintf(buf, n, "stiction %s", cmd);
    for (int i = 0; i < argc; i++) {
        size_t l = strlen(buf);
        snprintf(buf + l, n - l, " %s", argv[i]);
    }
}

double cli_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int cli_fail(const char *cmdname, stc_status s)
{
    const char *m = stc_errmsg();
    fprintf(stderr, "stiction %s: %s\n", cmdname, (m && *m) ? m : stc_strerror(s));
    return (s == STC_EINVAL || s == STC_EFORMAT) ? CLI_EXIT_USAGE : CLI_EXIT_FAIL;
}

stc_status cli_name_error(stc_status s, const char *key, const char *value)
{
    char head[64], msg[1024];
    snprintf(head, sizeof head, "%s = '", key);
    const char *m = stc_errmsg();
    if (s == STC_OK || !m || strncmp(m, head, strlen(head)) == 0) return s;
    size_t n = strlen(value);
    if (strncmp(m, value, n) == 0 && strncmp(m + n, ": ", 2) == 0) m += n + 2;
    snprintf(msg, sizeof msg, "%s", m);
    return stc_error(s, __FILE__, __LINE__, "%s = '%s': %s", key, value, msg);
}

int cli_parse(const char *cmdname, const char *usage, int argc, char **argv,
              const cli_opt *opts, stc_params *params, cli_set_fn set, void *ctx,
              int *done)
{
    dispatch_ctx d = {opts, params, set, ctx};
    char key[64];
    stc_status s;
    *done = 0;

    /* Pass 1: --help and --config */
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            print_help(cmdname, usage, opts);
            *done = 1;
            return CLI_EXIT_OK;
        }
        const char *path = NULL;
        if (strcmp(a, "--config") == 0) {
            if (i + 1 >= argc) {
                fprintf(stderr, "stiction %s: --config: missing file name\n", cmdname);
                return CLI_EXIT_USAGE;
            }
            path = argv[i + 1];
        } else if (strncmp(a, "--config=", 9) == 0) {
            path = a + 9;
        }
        if (path && (s = stc_ini_load(path, dispatch, &d)) != STC_OK)
            return cli_fail(cmdname, s);
    }

    /* Pass 2: command line, overriding the file */
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        char hint[96];
        if (strncmp(a, "--", 2) != 0 || a[2] == '\0') {
            /* "-delta 3": an option with its dashes mistyped? */
            arg_key(a, key, sizeof key);
            const char *near = near_option(key, opts, params != NULL, 1);
            fprintf(stderr, "stiction %s: unexpected argument '%s' (options start with --%s%s%s)\n",
                    cmdname, a, near ? ": did you mean --" : "", near ? near : "", near ? "?" : "");
            return CLI_EXIT_USAGE;
        }
        const char *value = arg_key(a, key, sizeof key);
        if (strcmp(key, "config") == 0) {
            if (!value) i++;
            continue;
        }
        const cli_opt *o = find_opt(opts, key);
        if (!o && !(params && is_common_key(key))) {
            fprintf(stderr, "stiction %s: unknown option '--%s'%s\n", cmdname, key,
                    near_hint(hint, sizeof hint, "--", near_option(key, opts, params != NULL, 1),
                              " (see --help)"));
            return CLI_EXIT_USAGE;
        }
        int is_flag = o && !o->arg;
        if (!value) {
            if (is_flag) value = "1";
            else {
                if (i + 1 >= argc) {
                    fprintf(stderr, "stiction %s: --%s: missing value\n", cmdname, key);
                    return CLI_EXIT_USAGE;
                }
                /* "--png --json": the value was forgotten, not a file named --json */
                char next[64];
                const char *nx = argv[i + 1];
                arg_key(nx, next, sizeof next);
                if (strncmp(nx, "--", 2) == 0 &&
                    (find_opt(opts, next) || (params && is_common_key(next)) ||
                     !strcmp(next, "config") || !strcmp(next, "help"))) {
                    fprintf(stderr, "stiction %s: --%s: missing value (the next argument, '%s', "
                            "is an option)\n", cmdname, key, nx);
                    return CLI_EXIT_USAGE;
                }
                value = argv[++i];
            }
        }
        if ((s = dispatch(&d, "", key, value)) != STC_OK) return cli_fail(cmdname, s);
    }
    if (params && (s = stc_params_resolve(params)) != STC_OK) return cli_fail(cmdname, s);
    return CLI_EXIT_OK;
}

const char *cli_num(char *buf, size_t n, const char *fmt, double v, const char *none)
{
    if (isfinite(v)) snprintf(buf, n, fmt, v);
    else snprintf(buf, n, "%s", none);
    return buf;
}

stc_status cli_parse_list(const char *key, const char *value, double **out, int *n)
{
    *out = NULL;
    *n = 0;
    if (strchr(value, ':')) {
        double a, b;
        long cnt;
        char buf[3][64];
        const char *p = value;
        for (int k = 0; k < 3; k++) {
            const char *c = strchr(p, ':');
            size_t len = c ? (size_t)(c - p) : strlen(p);
            if (len >= sizeof buf[k] || (k < 2 && !c) || (k == 2 && c))
                return stc_error(STC_EINVAL, __FILE__, __LINE__,
                                 "%s = '%s': a range is start:stop:count", key, value);
            memcpy(buf[k], p, len);
            buf[k][len] = '\0';
            p = c ? c + 1 : p + len;
        }
        stc_status s;
        if ((s = stc_parse_double(key, buf[0], &a)) || (s = stc_parse_double(key, buf[1], &b)) ||
            (s = stc_parse_long(key, buf[2], &cnt)))
            return s;
        if (cnt < 1 || cnt > 100000)
            return stc_error(STC_EINVAL, __FILE__, __LINE__,
                             "%s = '%s': count %ld must be in [1, 100000]", key, value, cnt);
        double *v = malloc((size_t)cnt * sizeof *v);
        if (!v) return stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
        for (long k = 0; k < cnt; k++) v[k] = cnt == 1 ? a : a + (b - a) * (double)k / (double)(cnt - 1);
        *out = v;
        *n = (int)cnt;
        return STC_OK;
    }
    int cap = 1;
    for (const char *c = value; *c; c++) cap += (*c == ',');
    double *v = malloc((size_t)cap * sizeof *v);
    if (!v) return stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    const char *p = value;
    for (int k = 0; k < cap; k++) {
        const char *c = strchr(p, ',');
        size_t len = c ? (size_t)(c - p) : strlen(p);
        char buf[64];
        if (len >= sizeof buf) len = sizeof buf - 1;
        memcpy(buf, p, len);
        buf[len] = '\0';
        stc_status s = stc_parse_double(key, buf, &v[k]);
        if (s) {
            free(v);
            return s;
        }
        p = c ? c + 1 : p + len;
    }
    *out = v;
    *n = cap;
    return STC_OK;
}

static void group_usage(FILE *f, const char *group, const cli_cmd *cmds)
{
    fprintf(f, "usage: stiction %s SUBCOMMAND [options]   (... SUBCOMMAND --help)\n\n"
               "Subcommands:\n", group);
    size_t skip = strlen(group) + 1; /* cmds are named "group sub" */
    for (const cli_cmd *c = cmds; c->name; c++)
        fprintf(f, "  %-10s %s\n", c->name + skip, c->summary);
}

int cli_dispatch(const char *group, const cli_cmd *cmds, int argc, char **argv)
{
    if (argc < 1) {
        group_usage(stderr, group, cmds);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
        group_usage(stdout, group, cmds);
        return CLI_EXIT_OK;
    }
    size_t skip = strlen(group) + 1;
    cli_near near;
    cli_near_init(&near, argv[0]);
    for (const cli_cmd *c = cmds; c->name; c++) {
        if (strcmp(argv[0], c->name + skip) == 0) return c->run(c, argc - 1, argv + 1);
        cli_near_add(&near, c->name + skip);
    }
    char hint[96];
    fprintf(stderr, "stiction %s: unknown subcommand '%s'%s\n\n", group, argv[0],
            near_hint(hint, sizeof hint, "", cli_near_best(&near), ""));
    group_usage(stderr, group, cmds);
    return CLI_EXIT_USAGE;
}
