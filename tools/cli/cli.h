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
 * setter receives "1").  The table is also the layout of --help: options
 * print in table order, under CLI_HEADING entries; the common keys
 * (stc_params) a command documents are listed in its table too (their
 * setter returns STC_EUNSUPPORTED, so they reach stc_params_set). */
typedef struct cli_opt {
    const char *name; /* without leading "--"; "" for a layout entry */
    const char *arg;  /* metavariable shown in help, or NULL for a flag */
    const char *help;
} cli_opt;

/* Layout entries of an option table: a heading, and the place of the
 * --config FILE and --help lines (printed last when a table has none). */
#define CLI_HEADING(title) {"", NULL, (title)}
/* Off a terminal, long runs print a progress line at most this often (s). */
#define CLI_PROGRESS_EVERY_S 60.0
#define CLI_CONFIG_HELP {"", "", NULL}

/* The common keys as the help documents them: the sphere and its coating
 * (asperity, formulas), then the materials of the two layers. */
#define CLI_SPHERE_OPTS                                                                       \
    {"R", "MM", "radius R of the substrate sphere, mm (default 10)"},                          \
        {"t-over-R", "X", "coating thickness over R (the --R above), 0 = uncoated (default 0)"}, \
        {"t-mm", "MM", "coating thickness in mm, instead of --t-over-R: t/R = t-mm / R with "    \
                       "this run's --R"}
#define CLI_SUBSTRATE_OPTS                                                                    \
    {"E-su", "MPA", "Young's modulus of the substrate (default 200000)"},                      \
        {"E-over-Y", "X", "E/Y of both layers (default 1000)"},                                \
        {"Y-su", "MPA", "yield strength of the substrate (overrides E-over-Y)"},               \
        {"nu", "X", "Poisson's ratio (default 0.32)"}
#define CLI_COATING_MATERIAL_OPTS                                                             \
    {"E-ratio", "X", "Eco/Esu, the coating's Young's modulus over the substrate's (default 1)"}, \
        {"Y-co", "MPA", "yield strength of the coating (overrides E-over-Y); with a coating "    \
                        "(t > 0, E-ratio != 1 or --nu-co) give both --Y-su and --Y-co or "     \
                        "neither"},                                                            \
        {"nu-co", "X", "Poisson's ratio of the coating (default: --nu)"}

/* The sections of a coated sphere's physics (asperity, formulas). */
#define CLI_COATED_SPHERE_SECTIONS                                                            \
    CLI_HEADING("Sphere and coating (units mm, N, MPa)"), CLI_SPHERE_OPTS,                     \
        CLI_HEADING("Materials"), CLI_SUBSTRATE_OPTS, CLI_COATING_MATERIAL_OPTS

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

/* The closest of a set of names to a mistyped one: cli_near_init, then
 * cli_near_add for each known name; cli_near_best gives the closest, or NULL
 * when none is close.  Distance: Damerau-Levenshtein (optimal string
 * alignment: insert, delete, substitute, swap two neighbours), letter case
 * ignored; close = at most a third of the typed length, at least 1 and at
 * most 2, and less than the typed length. */
typedef struct cli_near {
    const char *typed; /* borrowed */
    const char *best;  /* borrowed from the caller's names; NULL: none yet */
    int dist;
} cli_near;
void cli_near_init(cli_near *n, const char *typed);
void cli_near_add(cli_near *n, const char *name);
const char *cli_near_best(const cli_near *n);

/* Print "stiction <cmd>: <stc_errmsg()>" (or the status name) to stderr. */
int cli_fail(const char *cmdname, stc_status s);
/* The failure s names the parameter: its message becomes "key = 'value': ...",
 * without the value repeated where the message began with "value: ".  Returns
 * s; STC_OK and a message already naming key pass unchanged. */
stc_status cli_name_error(stc_status s, const char *key, const char *value);
/* Monotonic wall clock, s (progress lines, timings). */
double cli_now_s(void);
/* "stiction <cmd> argv..." into buf[n] (truncated): a table's provenance. */
void cli_command_line(char *buf, size_t n, const char *cmd, int argc, char **argv);

/* A share of the load from summits outside the table's or model's range
 * above this is warned about (and marked in sweeps): those values are partly
 * extrapolated. */
#define CLI_OUTSIDE_WARN_PERCENT 5
#define CLI_OUTSIDE_WARN (CLI_OUTSIDE_WARN_PERCENT / 100.0)
/* The threshold as help text: "5 %". */
#define CLI_OUTSIDE_WARN_TEXT CLI_XSTR(CLI_OUTSIDE_WARN_PERCENT) " %"
#define CLI_XSTR(x) CLI_STR(x)
#define CLI_STR(x) #x
/* A fraction as a percentage rounded up to 0.1, for "up to X %" (a share
 * just over a threshold never prints as the threshold itself). */
double cli_percent_up(double fraction);

/* An output file written under a temporary name and renamed on success, so
 * a failed run leaves no partial file: cli_out_open(&o, dir, name) opens
 * dir/name.tmp (NULL on failure); cli_out_close(&o) closes it and renames it
 * to dir/name, or removes it; 0 on success, -1 otherwise. */
typedef struct cli_out {
    FILE *f;
    char path[4096], tmp[4200];
} cli_out;
FILE *cli_out_open(cli_out *o, const char *dir, const char *name);
int cli_out_close(cli_out *o);
/* Rename each tmp[k] (k < n; NULL: none) to path[k], in order, all or
 * none: when a rename fails, the files placed before it are removed, and so
 * are the temporaries not placed.  Returns -1 when every one is placed, else
 * the k that failed, errno its reason. */
int cli_place_all(int n, const char *const *tmp, const char *const *path);
/* gnuplot, its script written to p->g, drawing into `file`, which must exist
 * (gnuplot, unable to open its output, would write the image to stdout).
 * Its messages reach stderr; SIGPIPE is ignored until cli_plot_close, so a
 * gnuplot that dies early cannot end the caller before its temporaries are
 * removed.  cli_plot_open returns -1 when gnuplot cannot run (nothing to
 * close); cli_plot_close returns 0 when the file holds an image, else -1,
 * with gnuplot's exit status in *status. */
typedef struct cli_plot {
    FILE *g;
    void (*sigpipe)(int);
} cli_plot;
int cli_plot_open(cli_plot *p);
int cli_plot_close(cli_plot *p, const char *file, int *status);
/* Make sure the output directory `dir` exists (created if missing; then
 * *made = 1 if made is not NULL, so a failed run can remove it) and can be
 * written, before any work is done: returns CLI_EXIT_OK, or prints
 * "stiction <cmd>: out = 'dir': ..." and returns CLI_EXIT_USAGE. */
int cli_out_dir(const char *cmd, const char *dir, int *made);

/* Nested subcommands ("surface synth", "table build", ...): cmds are named
 * "group sub", NULL-terminated; runs the one argv[0] names, or prints the
 * group's usage (--help: stdout, exit 0; missing or unknown: stderr, exit 2). */
int cli_dispatch(const char *group, const cli_cmd *cmds, int argc, char **argv);

/* v printed with `fmt` (one double conversion) into buf[n], or `none` when v
 * is not finite: text and CSV output never show nan or inf ("n/a" in a
 * table, "" in a CSV field).  Returns buf. */
const char *cli_num(char *buf, size_t n, const char *fmt, double v, const char *none);

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
int cli_asperity(const cli_cmd *cmd, int argc, char **argv);
int cli_halfspace(const cli_cmd *cmd, int argc, char **argv);
int cli_table(const cli_cmd *cmd, int argc, char **argv); /* build|info|query|merge */

/* --- asperity --shear (cli_asperity_shear.c) --- */
#include "stiction/asperity.h"
typedef struct cli_shear_args {
    int on;                /* run the tangential step */
    int alpha_set;         /* --alpha given */
    double load;           /* --load X = P/Pc_su (> 0: load control), else 0 */
    int placements;        /* --placements K: node-placement ensemble of K meshes (0/1: one) */
    int placements_max;    /* --placements-max K: refine the ensemble up to K members (0: no) */
    double refine_err;     /* --refine-err X: while its standard error exceeds X mu_s */
    double progress_every; /* --progress-every S: off a terminal, a ramp progress line at
                              most every S seconds (0: none) */
    asp_shear_options so;  /* --criterion, --alpha, --tau-c, --junction */
} cli_shear_args;
void cli_shear_args_default(cli_shear_args *sa);
/* --shear, --criterion, --alpha, --tau-c, --load, --junction, --ramp-return-map,
 * --ramp-refine, --foot-rows, --placements, --placements-max, --refine-err,
 * --progress-every; STC_EUNSUPPORTED for
 * others. */
stc_status cli_shear_opt(cli_shear_args *sa, const char *key, const char *value);
/* Normal step to delta[0] (× omega_c_su unless in_mm) or to --load, then the
 * ramp; prints, writes DIR/shear.csv and fields_Q0/Q080/Qmax; exit code. */
int cli_asperity_shear(const char *cmd, const stc_params *p, asp_options *o,
                       const cli_shear_args *sa, const double *delta, int ndelta, int in_mm,
                       int json, const char *out);
/* --- surface subcommands (cli_surface*.c) --- */
struct srf_map;
int cli_surface(const cli_cmd *cmd, int argc, char **argv); /* synth|stats|predict|sweep */
int cli_surface_synth(const cli_cmd *cmd, int argc, char **argv);
int cli_surface_stats(const cli_cmd *cmd, int argc, char **argv);
int cli_surface_predict(const cli_cmd *cmd, int argc, char **argv);
int cli_surface_sweep(const cli_cmd *cmd, int argc, char **argv);
/* "a" or "a,b" → (a, a) or (a, b). */
stc_status cli_parse_pair(const char *key, const char *value, double *a, double *b);
/* A flag's value: 1/true/yes or 0/false/no ("--json" alone passes "1"). */
stc_status cli_parse_flag(const char *key, const char *value, int *flag);
/* A whole number in [lo, hi] into *out (set only when valid); for int, [lo, hi]
 * within int's range. */
stc_status cli_parse_long(const char *key, const char *value, long lo, long hi, long *out);
stc_status cli_parse_int(const char *key, const char *value, long lo, long hi, int *out);
/* "a" or "b" → *second = 0 or 1, else an error naming key and both. */
stc_status cli_parse_choice(const char *key, const char *v, const char *a, const char *b,
                            int *second);
/* A list (cli_parse_list) into *out (owned; freed first), every value > 0
 * if `positive` (an error names the first that is not and its place). */
stc_status cli_parse_values(const char *key, const char *value, int positive, double **out,
                            int *n);
/* "midpoint", "radial" or "exact" → *rm (--return-map, --ramp-return-map). */
stc_status cli_parse_return_map(const char *key, const char *value, asp_return_map *rm);
/* Replace *out (owned, freed first) by a copy of a non-empty `value`: option
 * values from an INI file live only while the file is parsed, so any string
 * a subcommand keeps must be copied. */
stc_status cli_set_string(const char *key, const char *value, char **out);
/* Bit of option `key` in the table `opts` (0 if absent): subcommands record
 * which options were given, to refuse conflicting or unused combinations. */
unsigned long long cli_opt_bit(const cli_opt *opts, const char *key);
/* Fail (STC_EINVAL) naming both options: "--a conflicts with --b: why". */
stc_status cli_conflict(const char *a, const char *b, const char *why);
/* Take a leading positional argument (not starting with "--") as *path. */
void cli_peel_positional(int *argc, char ***argv, const char **path);
/* Import options for measured maps: --pixel-size DX[,DY] (mm; > 0 means
 * "import": a text grid, or the HDF5 --dataset NAME), --z-scale S. */
typedef struct cli_surface_import {
    double dx, dy;  /* mm; 0 = read a stiction surface file */
    char *dataset;  /* HDF5 dataset of a measured map, or NULL for text (owned) */
    double zscale;  /* raw heights × zscale = mm; default 1 */
    int zscale_set; /* --z-scale given */
} cli_surface_import;
/* Handle the import keys; STC_EUNSUPPORTED for others. */
stc_status cli_surface_import_opt(cli_surface_import *imp, const char *key, const char *value);
/* --dataset / --z-scale without --pixel-size: an error naming both. */
stc_status cli_surface_import_check(const cli_surface_import *imp);
void cli_surface_import_free(cli_surface_import *imp);
/* Load `path`, the value of option `key` ("in", "surface", "import"):
 * a stiction HDF5 file, or with imp->dx > 0 a measured map.  A failure's
 * message starts "key = 'path': " and says what the file must be. */
stc_status cli_surface_load(const char *key, const char *path, const cli_surface_import *imp,
                            struct srf_map **out);
#define CLI_SURFACE_IMPORT_OPTS                                                              \
    {"pixel-size", "DX[,DY]", "import a measured map with this pixel size (mm)"},             \
        {"dataset", "NAME", "with --pixel-size: HDF5 dataset holding the heights ([ny][nx])"}, \
        {"z-scale", "S", "with --pixel-size: multiply raw heights by S to get mm (default 1)"}

/* --- the progress line of a table build (cli_progress.c) --- */
#include "stiction/table.h"
typedef struct cli_table_progress {
    int tty, quiet;
    const tbl_table *t;
} cli_table_progress;
/* tbl_progress_fn: after each point, one line on stderr (rewritten in place
 * on a terminal), with the point's μs, elapsed time and ETA; after each
 * placement member of a point (tbl_build_opts.report_members) the same on a
 * terminal, and elsewhere when the member took 30 s or more. */
int cli_table_progress_line(void *ctx, const tbl_progress *p);

/* --- the sums `surface predict` and `surface sweep` share (cli_surface_gw.c) --- */
#include "stiction/gw.h"
#include "stiction/model.h"
#include "stiction/surface.h"
/* The summit population: a Gaussian one of eta, R, sigma_s (given, or a
 * map's statistics), or a map's summits, sorted once into a prototype that
 * every sum is made like (srf_gw_create_like; deterministic, kde). */
typedef struct cli_gw_pop {
    int rule, deterministic, kde; /* --rule (default SRF_RULE_8), --mode, --density */
    int rule_given, density_given;
    double eta, R, sigma_s;       /* Gaussian heights */
    asp_model *proto_model;       /* the prototype's model (owned) */
    srf_gw *proto;                /* the map's summits (owned), or NULL */
} cli_gw_pop;
/* The options cli_gw_pop_opt takes (with the map's import options), as
 * two sections of a subcommand's help. */
#define CLI_GW_POP_OPTS                                                                       \
    CLI_HEADING("Surface (a map, or its summit statistics; units mm, N, MPa)"),              \
        {"surface", "FILE", "surface HDF5 (from `surface synth`): summits found, stats "       \
                            "measured"},                                                      \
        {"rule", "8|4", "summit rule for --surface (default 8)"}, CLI_SURFACE_IMPORT_OPTS,     \
        {"summit-density", "ETA", "statistical run without a map: summits per mm²"},          \
        {"summit-radius", "MM", "statistical run without a map: summit radius, mm"},           \
        {"sigma-s", "MM", "statistical run without a map: summit-height std, mm (Gaussian)"}
#define CLI_GW_SUM_OPTS                                                                       \
    CLI_HEADING("Summation"),                                                                 \
        {"mode", "statistical|deterministic", "quadrature over a height density, or the sums " \
                                              "over the map's summits (default statistical)"}, \
        {"density", "gaussian|kde", "statistical height density for --surface (default "       \
                                    "gaussian)"}
/* The population's options: rule, mode, density, summit-density,
 * summit-radius, sigma-s; STC_EUNSUPPORTED for others. */
stc_status cli_gw_pop_opt(cli_gw_pop *pop, const char *key, const char *v);
/* One population: a map, or all three statistics (not both), and no map
 * option (or --mode deterministic) without a map; then the import options. */
stc_status cli_gw_pop_check(const cli_gw_pop *pop, const char *surface,
                            const cli_surface_import *imp);
/* Read the map: its summits into the prototype, or its statistics into
 * eta, R, sigma_s (nothing without a map); p: the materials of the
 * prototype's model, any valid set. */
stc_status cli_gw_pop_load(cli_gw_pop *pop, const char *surface, const cli_surface_import *imp,
                           const stc_params *p);
/* The GW sums of model m over the population. */
stc_status cli_gw_pop_sum(const cli_gw_pop *pop, const asp_model *m, srf_gw **out);
void cli_gw_pop_free(cli_gw_pop *pop);
/* One coating on an FE friction table: its models at the preload, at
 * sliding inception, μs's error band and (where the table keeps it, else
 * NULL) μs's slope against where inception is declared, each summed over
 * the population. */
typedef struct cli_table_design {
    asp_model *m[4];
    srf_gw *g[4];
} cli_table_design;
stc_status cli_table_design_create(const tbl_table *t, const stc_params *p, double t_mm,
                                   const cli_gw_pop *pop, cli_table_design *d);
/* The sums at a pressure (MPa; by_pressure) or separation, with μs's error
 * band, μs with P at inception and d ln μs / d ln ux (NaN where the table
 * does not keep it; TBL_MODEL_SLOPE). */
stc_status cli_table_design_at(const cli_table_design *d, int by_pressure, double x,
                               srf_gw_point *pt, double *mu_s_err, double *mu_s_slide,
                               double *mu_s_slope);
void cli_table_design_free(cli_table_design *d);
/* --fill over one or more coatings (t_mm[k] with materials p[k]): the table
 * file's missing points that the loads touch, computed into it; the counts
 * on stderr.  A fill that computes writes `command` as the table's
 * provenance (the build's command line). */
typedef struct cli_table_fill_job {
    const char *table, *command;
    const cli_gw_pop *pop;
    const stc_params *p;
    const double *t_mm;
    const double *loads;
    int nloads, by_pressure;
} cli_table_fill_job;
stc_status cli_table_fill(const char *cmd, const cli_table_fill_job *job, int ndesign, int jobs);

#endif
