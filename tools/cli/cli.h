/* The stiction command-line tool: a thin layer over the library.
 * Each subcommand lives in its own cli_*.c and registers in main.c. */
#ifndef STICTION_CLI_H
#define STICTION_CLI_H

#include <stdio.h>
#include "stiction/params.h"
#include "stiction/status.h"

/* Exit codes */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAIL = 1, CLI_EXIT_USAGE = 2 };

/* A subcommand-specific option.  arg == NULL: a flag taking no value (the
 * setter receives "1"). */
typedef struct cli_opt {
    const char *name; /* without leading "--" */
    const char *arg;  /* metavariable shown in help, or NULL for a flag */
    const char *help;
} cli_opt;

/* Setter for subcommand options; return STC_EUNSUPPORTED for unknown keys. */
typedef stc_status (*cli_set_fn)(void *ctx, const char *key, const char *value);

typedef struct cli_cmd {
    const char *name;
    const char *summary;
    int (*run)(const struct cli_cmd *cmd, int argc, char **argv);
} cli_cmd;

/* Parse `argv` (after the subcommand name): a --config FILE (INI) first, then
 * command-line options overriding it.  Common keys go to `params` (if not
 * NULL), the rest to `set(ctx, ...)`.  --help prints usage and returns
 * CLI_EXIT_OK with *done = 1.  On error prints "stiction <cmd>: message" to
 * stderr and returns CLI_EXIT_USAGE.  Returns CLI_EXIT_OK otherwise. */
int cli_parse(const char *cmdname, const char *usage, int argc, char **argv,
              const cli_opt *opts, stc_params *params, cli_set_fn set, void *ctx,
              int *done);

/* Print "stiction <cmd>: <stc_errmsg()>" (or the status name) to stderr. */
int cli_fail(const char *cmdname, stc_status s);

/* Print the common options' help. */
void cli_common_help(FILE *f);

/* Parse a list of numbers: "a,b,c" or a range "start:stop:count" (inclusive,
 * linear).  Returns a new array in *out (caller frees) and its length. */
stc_status cli_parse_list(const char *key, const char *value, double **out, int *n);

/* Minimal streaming JSON writer: commas and nesting handled here.  NaN and
 * infinities are written as null.  key == NULL inside arrays. */
typedef struct cli_json {
    FILE *f;
    int depth;
    int count[32]; /* members written at each depth */
} cli_json;
void cj_init(cli_json *j, FILE *f);
void cj_obj(cli_json *j, const char *key);
void cj_end_obj(cli_json *j);
void cj_arr(cli_json *j, const char *key);
void cj_end_arr(cli_json *j);
void cj_num(cli_json *j, const char *key, double v);
void cj_int(cli_json *j, const char *key, long v);
void cj_str(cli_json *j, const char *key, const char *v);
void cj_bool(cli_json *j, const char *key, int v);
void cj_null(cli_json *j, const char *key);
void cj_params(cli_json *j, const stc_params *p); /* the common parameters */
void cj_done(cli_json *j); /* final newline */

/* Subcommand entry points, registered in main.c */
int cli_formulas(const cli_cmd *cmd, int argc, char **argv);

#endif
