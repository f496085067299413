/* stiction table build|info|query|merge: FE friction tables
 * (include/stiction/table.h).  A thin layer: the sweep, the file, the
 * interpolation and its error bars are the library's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "stiction/table.h"
#include "stiction/table_mpi.h"

/* ---- shared ------------------------------------------------------------------ */

static stc_status bad(const char *key, const char *value, const char *what)
{
    return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '%s': must be %s", key, value, what);
}

static stc_status set_num(const char *key, const char *value, double lo, double hi,
                          double *out)
{
    stc_status s = stc_parse_double(key, value, out);
    if (s) return s;
    return stc_check_range(key, *out, lo, 1, hi, 1);
}

/* A number in the open interval (lo, hi) (hi infinite: > lo). */
static stc_status set_open(const char *key, const char *value, double lo, double hi,
                           double *out)
{
    stc_status s = stc_parse_double(key, value, out);
    if (s) return s;
    return stc_check_range(key, *out, lo, 0, hi, 0);
}

/* Every positional argument before the first option (input files). */
static int peel_files(int *argc, char ***argv, const char **files, int cap)
{
    int n = 0;
    while (*argc > 0 && strncmp((*argv)[0], "--", 2) != 0 && n < cap) {
        files[n++] = (*argv)[0];
        (*argc)--, (*argv)++;
    }
    return n;
}

static const char *flags_text(unsigned fl, char *buf, size_t n)
{
    buf[0] = '\0';
    static const struct { unsigned bit; const char *name; } names[] = {
        {TBL_OUT_W_LOW, "delta below the table"}, {TBL_OUT_W_HIGH, "delta above the table"},
        {TBL_OUT_T_OVER_R, "t/R outside (clamped)"}, {TBL_OUT_E_RATIO, "E-ratio outside (clamped)"},
        {TBL_GAP, "a neighbouring point is missing"}};
    for (size_t k = 0; k < sizeof names / sizeof *names; k++)
        if (fl & names[k].bit) {
            size_t l = strlen(buf);
            snprintf(buf + l, n - l, "%s%s", l ? "; " : "", names[k].name);
        }
    return buf;
}

/* ---- build ---------------------------------------------------------------------- */

typedef struct {
    tbl_family fam;
    tbl_numerics num;
    tbl_build_opts bo;
    double *ax[3];
    int n[3];
    char *ax_s[3]; /* the axes as given, for messages */
    char *out;
    int quiet, init, json;
} build_args;

static const cli_opt build_opts[] = {
    CLI_HEADING("Family: materials, contact and friction (one table per family)"),
    {"E-over-Y", "X", "E/Y of both layers (family; default 1000)"},
    {"E-over-Y-su", "X", "E/Y of the substrate (family)"},
    {"E-over-Y-co", "X", "E/Y of the coating (family; held along the E-ratio axis)"},
    {"nu", "X", "Poisson ratio of both layers (family; default 0.32)"},
    {"nu-su", "X", "Poisson ratio of the substrate (family)"},
    {"nu-co", "X", "Poisson ratio of the coating (family)"},
    {"contact", "stick|slip", "contact of the normal step (family; default stick)"},
    {"tau-c-over-Y-co", "X", "tau_c / Y of the coating (family; default 1/sqrt(3))"},
    {"criterion", "shear|stiffness", "sliding criterion (family; default shear)"},
    {"alpha", "A", "stiffness criterion ratio (family; default 0.1)"},
    CLI_HEADING("Axes"),
    {"deltas", "LIST", "delta/omega_c_su values (axis 1), e.g. 0.5,1,2,4,8,15,30,60"},
    {"t-over-R", "LIST", "coating thickness over the sphere's radius R (axis 2): the table is "
                         "normalised, so one table serves every summit radius"},
    {"E-ratio", "LIST", "Eco/Esu values (axis 3)"},
    CLI_HEADING("Accuracy"),
    {"mesh-level", "N", "3D mesh level of every point, 0..3 (default 0; each level costs 5-10x "
                        "the one below)"},
    {"placements", "K", "node placements averaged per point, 1..8 (default 2): a point's mu_s "
                        "comes with the members' spread as its error estimate (thesis grid at "
                        "K = 2: 1.5-14 %, median 3.6 %), at K times the CPU time (20-250 CPU s a point "
                        "at K = 2)"},
    {"placements-max", "K", "refine: a point whose members' standard error exceeds --refine-err "
                            "of its mu_s gets twice the placements, halfway between, and again, "
                            "up to K members; 0 = none (default), else 2 x placements..8.  "
                            "Onto a table built with less refinement (or none): computes again "
                            "only the points this refines, the rest kept"},
    {"refine-err", "X", "the relative standard error that refines a point, (0, 0.5] (default "
                        "0.04)"},
    CLI_HEADING("Common options"),
    {"out", "FILE", "the table file (resumes from FILE.journal and FILE if they exist)"},
    {"jobs", "N", "points computed at once, one thread each (default: one per core); "
                  "fewer points than N: a point's placements share the N threads; "
                  "under mpirun -n N > 1: points rank 0 computes besides handing them out "
                  "(default 1; the other ranks compute one at a time)"},
    {"shard", "I/N", "compute only points with index % N == I (job arrays; join with "
                     "merge); combines with mpirun"},
    {"retry-failed", NULL, "compute the table's failed points again (after a solver change)"},
    {"only-failed", NULL, "compute the table's failed points again and no pending one"},
    {"curves-only", NULL, "compute the normal grid's pending curves and no point (completes "
                          "the normal grid of a table that has none yet)"},
    {"init", NULL, "compute nothing: write FILE with the points it has (none for a new "
                   "table) for `surface predict --fill` or a later build"},
    {"quiet", NULL, "no progress lines"},
    {"json", NULL, "print the summary as JSON"},
    CLI_CONFIG_HELP,
    CLI_HEADING("Expert numerics"),
    {"elements-per-contact", "N", "3D elements across the contact: 0 = the mesh level's "
                                  "(default); a small value (3..6) gives a quick coarse table"},
    {"foot-rows", "F", "junction reading of every point: 0 = the three axis lines (default, "
                       "as stiction asperity), F in (0, 0.9] = every node row within F a0 of "
                       "the axis (docs/design.md §4.2, §4.5)"},
    {"normal-level", "N", "axisymmetric mesh level of the normal grid (the preload's P and A "
                          "from axisymmetric load curves), 0..3, or -1 for none: P and A from "
                          "the 3D points (default 1)"},
    {NULL, NULL, NULL},
};

static stc_status set_axis(build_args *a, int k, const char *key, const char *value)
{
    free(a->ax[k]);
    a->ax[k] = NULL;
    free(a->ax_s[k]);
    a->ax_s[k] = strdup(value);
    return cli_parse_list(key, value, &a->ax[k], &a->n[k]);
}

static stc_status build_set(void *ctx, const char *key, const char *value)
{
    build_args *a = ctx;
    tbl_family *f = &a->fam;
    double v;
    stc_status s = STC_OK;
    if (!strcmp(key, "deltas")) return set_axis(a, 0, key, value);
    if (!strcmp(key, "t-over-R")) return set_axis(a, 1, key, value);
    if (!strcmp(key, "E-ratio")) return set_axis(a, 2, key, value);
    if (!strcmp(key, "E-over-Y")) {
        if (!(s = set_num(key, value, 10, 1e5, &v))) f->E_over_Y_su = f->E_over_Y_co = v;
    } else if (!strcmp(key, "E-over-Y-su")) {
        s = set_num(key, value, 10, 1e5, &f->E_over_Y_su);
    } else if (!strcmp(key, "E-over-Y-co")) {
        s = set_num(key, value, 10, 1e5, &f->E_over_Y_co);
    } else if (!strcmp(key, "nu")) {
        if (!(s = set_num(key, value, 0, 0.4999, &v))) f->nu_su = f->nu_co = v;
    } else if (!strcmp(key, "nu-su")) {
        s = set_num(key, value, 0, 0.4999, &f->nu_su);
    } else if (!strcmp(key, "nu-co")) {
        s = set_num(key, value, 0, 0.4999, &f->nu_co);
    } else if (!strcmp(key, "contact")) {
        if (!strcmp(value, "stick")) f->contact = ASP_CONTACT_STICK;
        else if (!strcmp(value, "slip")) f->contact = ASP_CONTACT_SLIP;
        else s = bad(key, value, "stick or slip");
    } else if (!strcmp(key, "tau-c-over-Y-co")) {
        s = set_num(key, value, 1e-3, 1, &f->tau_c_over_Y_co);
    } else if (!strcmp(key, "criterion")) {
        if (!strcmp(value, "shear")) f->criterion = ASP_SHEAR_CRIT_SHEAR;
        else if (!strcmp(value, "stiffness")) f->criterion = ASP_SHEAR_CRIT_STIFFNESS;
        else s = bad(key, value, "shear or stiffness");
    } else if (!strcmp(key, "alpha")) {
        s = set_num(key, value, 1e-3, 0.999, &f->alpha);
    } else if (!strcmp(key, "mesh-level")) {
        s = cli_parse_int(key, value, 0, 3, &a->num.mesh_level);
    } else if (!strcmp(key, "placements")) {
        s = cli_parse_int(key, value, 1, ASP_PLACEMENTS_MAX, &a->num.placements);
    } else if (!strcmp(key, "placements-max")) {
        s = cli_parse_int(key, value, 0, ASP_PLACEMENTS_MAX, &a->num.placements_max);
    } else if (!strcmp(key, "refine-err")) {
        s = stc_parse_double(key, value, &a->num.refine_err);
    } else if (!strcmp(key, "foot-rows")) {
        s = stc_parse_double(key, value, &a->num.foot_rows);
    } else if (!strcmp(key, "normal-level")) {
        s = cli_parse_int(key, value, -1, 3, &a->num.normal_level);
    } else if (!strcmp(key, "elements-per-contact")) {
        s = stc_parse_double(key, value, &a->num.elements_per_contact);
    } else if (!strcmp(key, "out")) {
        s = cli_set_string(key, value, &a->out);
    } else if (!strcmp(key, "jobs")) {
        s = cli_parse_int(key, value, 1, 1024, &a->bo.jobs);
    } else if (!strcmp(key, "shard")) {
        int i, n, used = 0;
        if (sscanf(value, "%d/%d%n", &i, &n, &used) != 2 || value[used] || n < 1 || i < 0 ||
            i >= n)
            s = bad(key, value, "I/N with 0 <= I < N (e.g. 0/4)");
        else a->bo.shard = i, a->bo.shards = n;
    } else if (!strcmp(key, "quiet")) {
        s = cli_parse_flag(key, value, &a->quiet);
    } else if (!strcmp(key, "json")) {
        s = cli_parse_flag(key, value, &a->json);
    } else if (!strcmp(key, "retry-failed")) {
        s = cli_parse_flag(key, value, &a->bo.retry_failed);
    } else if (!strcmp(key, "only-failed")) {
        s = cli_parse_flag(key, value, &a->bo.only_failed);
    } else if (!strcmp(key, "curves-only")) {
        s = cli_parse_flag(key, value, &a->bo.curves_only);
    } else if (!strcmp(key, "init")) {
        s = cli_parse_flag(key, value, &a->init);
    } else {
        s = STC_EUNSUPPORTED;
    }
    return s;
}

/* table build --json: what the text lines say, as one object. */
static void build_json(const tbl_table *t, const char *out, const tbl_build_summary *sum,
                       int ranks)
{
    int nd, nf, np;
    tbl_count(t, &nd, &nf, &np);
    cli_json j;
    cj_init(&j, stdout);
    cj_obj(&j, NULL);
    cj_str(&j, "file", out);
    cj_int(&j, "points", tbl_points(t));
    cj_int(&j, "done", nd);
    cj_int(&j, "failed", nf);
    cj_int(&j, "pending", np);
    cj_obj(&j, "this_run");
    cj_int(&j, "ranks", ranks);
    cj_int(&j, "share", sum->share);
    cj_int(&j, "computed", sum->computed);
    cj_int(&j, "resumed", sum->resumed);
    cj_int(&j, "reopened", sum->reopened);
    cj_int(&j, "copied", sum->copied);
    cj_int(&j, "members_taken", sum->members_taken);
    cj_num(&j, "wall_s", sum->wall_s);
    cj_num(&j, "cpu_s_per_point", sum->computed ? sum->cpu_s / sum->computed : 0.0);
    cj_int(&j, "curves_computed", sum->curves_computed);
    cj_end_obj(&j);
    if (tbl_curves(t) > 0) {
        int cd, cf, cp;
        tbl_curve_count(t, &cd, &cf, &cp);
        cj_obj(&j, "normal_grid");
        cj_int(&j, "curves", tbl_curves(t));
        cj_int(&j, "done", cd);
        cj_int(&j, "failed", cf);
        cj_int(&j, "pending", cp);
        cj_end_obj(&j);
    }
    tbl_fit_info fi;
    if (tbl_get_fit_info(t, &fi) == STC_OK) {
        cj_obj(&j, "mu_s_surrogate");
        cj_int(&j, "points", fi.n);
        cj_num(&j, "loo_rms", fi.loo_rms);
        cj_num(&j, "loo_max", fi.loo_max);
        cj_num(&j, "loo_within_2sd", fi.loo_cover2);
        cj_end_obj(&j);
    }
    cj_end_obj(&j);
    cj_done(&j);
}

/* table build: the summary as text lines. */
static void build_text(const tbl_table *t, const char *out, const tbl_build_summary *sum,
                       int ranks)
{
    int nd, nf, np;
    tbl_count(t, &nd, &nf, &np);
    const double *v;
    int n0 = tbl_axis(t, 0, &v), n1 = tbl_axis(t, 1, &v), n2 = tbl_axis(t, 2, &v);
    printf("wrote %s: %d points (%d x %d x %d), %d done, %d failed, %d pending\n", out,
           tbl_points(t), n0, n1, n2, nd, nf, np);
    char on[48] = "";
    if (ranks > 1) snprintf(on, sizeof on, " (on %d MPI ranks)", ranks);
    printf("this run%s: %d of %d points of its share computed, %d taken from an earlier run; "
           "%.1f s wall, %.1f CPU s per point\n", on, sum->computed, sum->share, sum->resumed,
           sum->wall_s, sum->computed ? sum->cpu_s / sum->computed : 0.0);
    if (sum->members_taken > 0)
        printf("placement members taken from an earlier run (the journal, or the file a "
               "refinement goes on from): %d\n", sum->members_taken);
    if (sum->copied > 0)
        printf("one material: %d points (Eco/Esu = 1, t/R beyond the first) filled from the "
               "first t/R's run at their delta\n", sum->copied);
    if (sum->reopened > 0) {
        tbl_numerics nu;
        tbl_get_numerics(t, &nu);
        printf("refinement: %d done points of the file re-opened for up to %d placements "
               "(the others kept; a shard computes those of its share)\n", sum->reopened,
               nu.placements_max);
    }
    if (tbl_curves(t) > 0) {
        int cd, cf, cp;
        tbl_curve_count(t, &cd, &cf, &cp);
        printf("normal grid: %d curves, %d done, %d failed, %d pending; this run computed %d\n",
               tbl_curves(t), cd, cf, cp, sum->curves_computed);
    }
    tbl_fit_info fi;
    if (tbl_get_fit_info(t, &fi) == STC_OK)
        printf("mu_s surrogate: %d points, leave-one-out error %.2f %% rms, %.2f %% largest, "
               "%.0f %% within 2 sd\n", fi.n, 100 * fi.loo_rms, 100 * fi.loo_max,
               100 * fi.loo_cover2);
}

static int table_build(const cli_cmd *cmd, int argc, char **argv)
{
    build_args a;
    memset(&a, 0, sizeof a);
    tbl_family_default(&a.fam);
    tbl_numerics_default(&a.num);
    tbl_build_opts_default(&a.bo);
    int done, rc;
    const char *usage = "--config FAMILY.ini --out FILE [options]\n\n"
                        "Sweep the FE asperity solver over the axes and store the table\n"
                        "(resumable: run it again after a crash).\n"
                        "Under `mpirun -n N stiction table build ...` the N processes share "
                        "the points: rank 0\nhands them out one at a time, computes some "
                        "itself and alone writes FILE.journal and\nFILE; the others print "
                        "nothing and return rank 0's outcome.";
    rc = cli_parse(cmd->name, usage, argc, argv, build_opts, NULL, build_set, &a, &done);
    tbl_table *t = NULL;
    if (rc || done) goto out;
    static const char *const axk[3] = {"deltas", "t-over-R", "E-ratio"};
    for (int k = 0; k < 3; k++)
        if (!a.ax[k]) {
            fprintf(stderr, "stiction %s: %s: missing (the table's axis %d)\n", cmd->name,
                    axk[k], k + 1);
            rc = CLI_EXIT_USAGE;
            goto out;
        }
    if (!a.out) {
        fprintf(stderr, "stiction %s: out: missing (the table file to write)\n", cmd->name);
        rc = CLI_EXIT_USAGE;
        goto out;
    }
    stc_status s = tbl_create(&a.fam, &a.num, a.ax[0], a.n[0], a.ax[1], a.n[1], a.ax[2],
                              a.n[2], &t);
    /* an axis the library refused: named as the option that gave it */
    static const char *const axn[3] = {"delta/omega_c = ", "t/R = ", "E-ratio = "};
    for (int k = 0; s && k < 3; k++)
        if (!strncmp(stc_errmsg(), axn[k], strlen(axn[k])) && a.ax_s[k])
            s = cli_name_error(s, axk[k], a.ax_s[k]);
    if (s) {
        rc = cli_fail(cmd->name, s);
        goto out;
    }
    char prov[512];
    cli_command_line(prov, sizeof prov, cmd->name, argc, argv);
    tbl_set_provenance(t, prov, 0.0);
    /* Under mpirun only rank 0 speaks: it has every point and every failure
     * (a failing rank tells rank 0, rank 0 tells every rank).  The others
     * exit 0 and leave the exit status to rank 0 too: mpirun ends the whole
     * job at the first non-zero exit, which could cut rank 0 off before it
     * reports. */
    int rank, ranks;
    tbl_build_rank(&rank, &ranks);
    cli_table_progress pc = {isatty(2), a.quiet, t};
    a.bo.progress = cli_table_progress_line;
    a.bo.ctx = &pc;
    a.bo.report_members = 1;
    tbl_build_summary sum;
    unsigned char *none = a.init ? calloc((size_t)tbl_points(t), 1) : NULL;
    if (a.init && !none) s = stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    a.bo.only = none; /* --init: the build computes nothing, resumes and writes */
    if (s == STC_OK) s = tbl_build(t, a.out, &a.bo, &sum);
    free(none);
    if (rank > 0) goto out;
    if (pc.tty && !a.quiet && sum.computed + sum.curves_computed > 0) fputc('\n', stderr);
    if (s) {
        rc = cli_fail(cmd->name, s);
        goto out;
    }
    int nf;
    tbl_count(t, NULL, &nf, NULL);
    if (a.json) build_json(t, a.out, &sum, ranks);
    else build_text(t, a.out, &sum, ranks);
    if (nf > 0)
        fprintf(stderr, "stiction %s: %d points failed (no numbers stored for them; "
                "`stiction table info %s` lists the reasons)\n", cmd->name, nf, a.out);
out:
    tbl_destroy(&t);
    for (int k = 0; k < 3; k++) free(a.ax[k]), free(a.ax_s[k]);
    free(a.out);
    return rc;
}

/* ---- info ------------------------------------------------------------------------- */

typedef struct {
    int json, points, curves;
    double *w;
    int nw;
    double tR, E;
    double t_mm, R; /* --t-mm with --R: t/R = t_mm / R */
    char *out;
    int plan_k;      /* info: what a refinement up to plan_k members ... */
    double plan_x;   /* ... at this error would compute again (0: ASP_REFINE_ERR) */
} query_args;

/* table info --placements-max K [--refine-err X]: tbl_refine_plan's answer */
typedef struct {
    int k, points;
    double x, cpu_s;
    int unkept;
} refine_plan;

static const cli_opt info_opts[] = {
    {"json", NULL, "print JSON"},
    {"points", NULL, "print every point's stored values instead, as CSV (one row a point; "
                     "source: the point whose run it holds)"},
    {"curves", NULL, "print the normal grid's values instead, as CSV (one row a delta of a "
                     "curve)"},
    {"placements-max", "K", "also say what a build with refinement up to K members (table "
                            "build --placements-max) onto this table would compute again"},
    {"refine-err", "X", "that refinement's threshold (default 0.04)"},
    {NULL, NULL, NULL},
};

static stc_status query_set(void *ctx, const char *key, const char *value)
{
    query_args *q = ctx;
    if (!strcmp(key, "json")) return cli_parse_flag(key, value, &q->json);
    if (!strcmp(key, "points")) return cli_parse_flag(key, value, &q->points);
    if (!strcmp(key, "curves")) return cli_parse_flag(key, value, &q->curves);
    if (!strcmp(key, "delta")) {
        free(q->w);
        q->w = NULL;
        return cli_parse_list(key, value, &q->w, &q->nw);
    }
    /* the ranges of stiction asperity: a query outside the table is flagged */
    if (!strcmp(key, "t-over-R")) return set_open(key, value, 0.0, 1.0, &q->tR);
    if (!strcmp(key, "t-mm")) return set_num(key, value, 1e-12, 1e6, &q->t_mm);
    if (!strcmp(key, "R")) return set_num(key, value, 1e-9, 1e6, &q->R);
    if (!strcmp(key, "E-ratio")) return set_open(key, value, 0.0, HUGE_VAL, &q->E);
    if (!strcmp(key, "out")) return cli_set_string(key, value, &q->out);
    if (!strcmp(key, "placements-max"))
        return cli_parse_int(key, value, 2, ASP_PLACEMENTS_MAX, &q->plan_k);
    if (!strcmp(key, "refine-err")) return set_num(key, value, 1e-9, 0.5, &q->plan_x);
    return STC_EUNSUPPORTED;
}

static int open_table(const char *cmd, const char *path, tbl_table **t)
{
    if (!path) {
        fprintf(stderr, "stiction %s: FILE: missing (a table from `stiction table build`)\n",
                cmd);
        return CLI_EXIT_USAGE;
    }
    stc_status s = cli_name_error(tbl_read(path, t), "FILE", path);
    return s ? cli_fail(cmd, s) : CLI_EXIT_OK;
}

static void print_axis(const char *name, const double *v, int n)
{
    printf("  %-18s %3d:", name, n);
    for (int i = 0; i < n; i++) printf(" %g", v[i]);
    printf("\n");
}

/* CPU s of the points (curves: the normal grid's curves) computed: done or
 * failed, not copies of another's run (tbl_point.copied, tbl_curve.copied);
 * *n of them, *copied the copies. */
static double run_cost(const tbl_table *t, int curves, int *n, int *copied)
{
    double cpu = 0.0;
    *n = *copied = 0;
    for (int i = 0; i < (curves ? tbl_curves(t) : tbl_points(t)); i++) {
        const tbl_point *p = curves ? NULL : tbl_point_get(t, i);
        const tbl_curve *cv = curves ? tbl_curve_get(t, i) : NULL;
        if ((p ? p->state : cv->state) == TBL_PENDING) continue;
        if (p ? p->copied : cv->copied) (*copied)++;
        else cpu += p ? p->cpu_s : cv->cpu_s, (*n)++;
    }
    return cpu;
}

/* How many done points have k members, k = 1 .. ASP_PLACEMENTS_MAX (the
 * refinement's spread); returns the number of different counts. */
static int member_counts(const tbl_table *t, int count[ASP_PLACEMENTS_MAX + 1])
{
    int kinds = 0;
    for (int k = 0; k <= ASP_PLACEMENTS_MAX; k++) count[k] = 0;
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i);
        if (p->state != TBL_DONE || p->members < 1 || p->members > ASP_PLACEMENTS_MAX) continue;
        kinds += count[p->members]++ == 0;
    }
    return kinds;
}

/* The stored error estimates of the done points run as themselves (a
 * copy repeats its source's), relative to their mu_s: how many, their
 * median, how many reach ERR_NOISY (a one-member point's err_single of
 * 10 % counts, to rounding), and the largest (imax its point, -1 with
 * none).  Returns -1, *e unset, when out of memory. */
#define ERR_NOISY 0.10
typedef struct err_summary {
    int n, noisy, imax;
    double median, max;
} err_summary;

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int err_summarise(const tbl_table *t, err_summary *e)
{
    *e = (err_summary){.imax = -1, .median = NAN, .max = NAN};
    double *r = malloc((size_t)(tbl_points(t) + 1) * sizeof *r);
    if (!r) return -1;
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i);
        if (p->state != TBL_DONE || p->copied || !(p->mu_s > 0.0) || !isfinite(p->mu_s_err))
            continue;
        double x = p->mu_s_err / p->mu_s;
        e->noisy += x >= ERR_NOISY * (1.0 - 1e-9);
        if (e->imax < 0 || x > e->max) e->max = x, e->imax = i;
        r[e->n++] = x;
    }
    if (e->n > 0) {
        qsort(r, (size_t)e->n, sizeof *r, cmp_dbl);
        e->median = e->n % 2 ? r[e->n / 2] : 0.5 * (r[e->n / 2 - 1] + r[e->n / 2]);
    }
    free(r);
    return 0;
}

/* How much the done points' μs (run as themselves) depends on where
 * inception is declared (tbl_point.mu_s_ux_slope): of the n that say, how
 * many reach SLOPE_HIGH, from which δ/ωc, the largest (imax its point). */
#define SLOPE_HIGH 0.1
typedef struct slope_summary {
    int n, high, imax;
    double w_min, max;
} slope_summary;

static void slope_summarise(const tbl_table *t, slope_summary *r)
{
    *r = (slope_summary){.imax = -1, .w_min = NAN, .max = NAN};
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i);
        if (p->state != TBL_DONE || p->copied || !isfinite(p->mu_s_ux_slope)) continue;
        r->n++;
        if (r->imax < 0 || p->mu_s_ux_slope > r->max) r->max = p->mu_s_ux_slope, r->imax = i;
        if (p->mu_s_ux_slope < SLOPE_HIGH) continue;
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        if (r->high++ == 0 || w < r->w_min) r->w_min = w;
    }
}

/* The next command of a table's history (tbl_history: one a line) into
 * line[n]; returns where the one after it starts, NULL at the end. */
static const char *history_line(const char *h, char *line, size_t n)
{
    if (!*h) return NULL;
    size_t l = strcspn(h, "\n");
    snprintf(line, n, "%.*s", (int)l, h);
    return h + l + (h[l] == '\n');
}

static void info_json(const tbl_table *t, const char *path, const refine_plan *rp)
{
    cli_json j;
    cj_init(&j, stdout);
    cj_obj(&j, NULL);
    cj_str(&j, "file", path);
    tbl_family f;
    tbl_get_family(t, &f);
    cj_obj(&j, "family");
    cj_num(&j, "E_over_Y_su", f.E_over_Y_su);
    cj_num(&j, "E_over_Y_co", f.E_over_Y_co);
    cj_num(&j, "nu_su", f.nu_su);
    cj_num(&j, "nu_co", f.nu_co);
    cj_str(&j, "contact", f.contact == ASP_CONTACT_STICK ? "stick" : "slip");
    cj_num(&j, "tau_c_over_Y_co", f.tau_c_over_Y_co);
    cj_str(&j, "criterion", f.criterion == ASP_SHEAR_CRIT_SHEAR ? "shear" : "stiffness");
    cj_end_obj(&j);
    tbl_numerics nu;
    tbl_get_numerics(t, &nu);
    cj_obj(&j, "numerics");
    cj_int(&j, "mesh_level", nu.mesh_level);
    cj_num(&j, "elements_per_contact", nu.elements_per_contact);
    cj_int(&j, "placements", nu.placements);
    cj_int(&j, "placements_max", nu.placements_max);
    cj_num(&j, "refine_err", nu.refine_err);
    cj_num(&j, "err_floor", nu.err_floor);
    cj_num(&j, "err_single", nu.err_single);
    cj_num(&j, "foot_rows", nu.foot_rows);
    cj_int(&j, "normal_level", nu.normal_level);
    cj_end_obj(&j);
    int count[ASP_PLACEMENTS_MAX + 1];
    member_counts(t, count);
    cj_obj(&j, "done_points_by_placements"); /* "k": points with k members */
    for (int k = 1; k <= ASP_PLACEMENTS_MAX; k++) {
        char key[8];
        snprintf(key, sizeof key, "%d", k);
        if (count[k]) cj_int(&j, key, count[k]);
    }
    cj_end_obj(&j);
    static const char *const an[3] = {"delta_over_omega_c", "t_over_R", "E_ratio"};
    cj_obj(&j, "axes");
    for (int k = 0; k < 3; k++) {
        const double *v;
        int n = tbl_axis(t, k, &v);
        cj_arr(&j, an[k]);
        for (int i = 0; i < n; i++) cj_num(&j, NULL, v[i]);
        cj_end_arr(&j);
    }
    cj_end_obj(&j);
    int nd, nf, np;
    tbl_count(t, &nd, &nf, &np);
    cj_int(&j, "points", tbl_points(t));
    cj_int(&j, "done", nd);
    cj_int(&j, "failed", nf);
    cj_int(&j, "pending", np);
    double wall;
    int nrun, ncopied;
    double cpu = run_cost(t, 0, &nrun, &ncopied);
    cj_int(&j, "copied", ncopied);
    cj_str(&j, "command", tbl_provenance(t, &wall));
    cj_arr(&j, "history"); /* the commands that built it before, oldest first */
    char line[512];
    for (const char *h = tbl_history(t); (h = history_line(h, line, sizeof line));)
        cj_str(&j, NULL, line);
    cj_end_arr(&j);
    cj_num(&j, "build_wall_s", wall);
    cj_num(&j, "cpu_s_per_point", nrun ? cpu / nrun : NAN);
    err_summary es;
    if (err_summarise(t, &es) != 0) {
        cj_num(&j, "mu_s_err_rel", NAN); /* null: not summarised (out of memory) */
    } else {
        cj_obj(&j, "mu_s_err_rel"); /* the done points' error estimates over their mu_s */
        cj_int(&j, "points", es.n);
        cj_num(&j, "median", es.median);
        cj_num(&j, "noisy_from", ERR_NOISY);
        cj_int(&j, "noisy", es.noisy);
        cj_num(&j, "largest", es.max);
        if (es.imax >= 0) {
            double w, tR, E;
            tbl_coords(t, es.imax, &w, &tR, &E);
            cj_obj(&j, "largest_at");
            cj_num(&j, "delta_over_omega_c", w);
            cj_num(&j, "t_over_R", tR);
            cj_num(&j, "E_ratio", E);
            cj_int(&j, "members", tbl_point_get(t, es.imax)->members);
            cj_end_obj(&j);
        }
        cj_end_obj(&j);
    }
    slope_summary ss;
    slope_summarise(t, &ss);
    cj_obj(&j, "mu_s_ux_slope"); /* how much mu_s depends on where inception is declared */
    cj_int(&j, "points", ss.n);  /* that say (0: a file before format 7) */
    cj_num(&j, "high_from", SLOPE_HIGH);
    cj_int(&j, "high", ss.high);
    cj_num(&j, "high_delta_min", ss.w_min);
    cj_num(&j, "largest", ss.max);
    cj_end_obj(&j);
    tbl_fit_info fi;
    if (tbl_get_fit_info(t, &fi) == STC_OK) {
        cj_num(&j, "loo_rms_rel", fi.loo_rms);
        cj_num(&j, "loo_max_rel", fi.loo_max);
        cj_num(&j, "loo_cover2", fi.loo_cover2);
        cj_num(&j, "noise_scale", fi.noise_scale);
        cj_num(&j, "ell_ln_w", fi.ell[0]);
        cj_num(&j, "ell_ln_t_over_a", fi.ell[1]);
        cj_num(&j, "ell_ln_E_ratio", fi.ell[2]);
        cj_num(&j, "gamma", fi.gamma);
        cj_num(&j, "ell_base_ln_w", fi.ell_base);
        cj_int(&j, "fit_reused", fi.reused);
    }
    int cd, cf, cp;
    tbl_curve_count(t, &cd, &cf, &cp);
    cj_obj(&j, "normal_grid");
    tbl_numerics num;
    tbl_get_numerics(t, &num);
    cj_int(&j, "level", num.normal_level);
    cj_int(&j, "curves", tbl_curves(t));
    cj_int(&j, "done", cd);
    cj_int(&j, "failed", cf);
    cj_int(&j, "pending", cp);
    int crun, ccopied;
    double ccpu = run_cost(t, 1, &crun, &ccopied);
    cj_int(&j, "copied", ccopied);
    cj_num(&j, "cpu_s_per_curve", crun ? ccpu / crun : NAN);
    cj_end_obj(&j);
    cj_arr(&j, "failed_points");
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i);
        if (p->state != TBL_FAILED) continue;
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        cj_obj(&j, NULL);
        cj_num(&j, "delta_over_omega_c", w);
        cj_num(&j, "t_over_R", tR);
        cj_num(&j, "E_ratio", E);
        cj_str(&j, "reason", p->reason);
        cj_end_obj(&j);
    }
    cj_end_arr(&j);
    if (rp) {
        cj_obj(&j, "refine_plan");
        cj_int(&j, "placements_max", rp->k);
        cj_num(&j, "refine_err", rp->x);
        cj_int(&j, "points", rp->points);
        cj_num(&j, "their_cpu_s", rp->cpu_s);
        cj_int(&j, "keeping_no_members", rp->unkept); /* their first members run again */
        cj_end_obj(&j);
    }
    cj_end_obj(&j);
    cj_done(&j);
}

/* Coordinates of normal curve c. */
static void curve_coords(const tbl_table *t, int c, double *tR, double *E)
{
    const double *ax1, *ax2;
    int n1 = tbl_normal_axis(t, 1, &ax1);
    tbl_normal_axis(t, 2, &ax2);
    *tR = ax1[c % n1];
    *E = ax2[c / n1];
}

static void info_normal_text(const tbl_table *t)
{
    tbl_numerics n;
    tbl_get_numerics(t, &n);
    if (tbl_curves(t) == 0) {
        printf("  normal grid: none (preload P and A from the 3D points)\n");
        return;
    }
    int nk[3], cd, cf, cp;
    for (int k = 0; k < 3; k++) nk[k] = tbl_normal_axis(t, k, NULL);
    tbl_curve_count(t, &cd, &cf, &cp);
    int nrun, ncopied;
    double cpu = run_cost(t, 1, &nrun, &ncopied);
    char copies[64] = "";
    if (ncopied > 0) snprintf(copies, sizeof copies, " (%d copied: one material)", ncopied);
    printf("  normal grid (preload P and A): axisymmetric level %d, %d delta x %d t/R x %d "
           "Eco/Esu; curves %d, done %d%s, failed %d, pending %d; %.1f CPU s per curve "
           "computed\n", n.normal_level, nk[0], nk[1], nk[2], tbl_curves(t), cd, copies, cf, cp,
           nrun ? cpu / nrun : 0.0);
    for (int c = 0; c < tbl_curves(t); c++) {
        const tbl_curve *cv = tbl_curve_get(t, c);
        if (cv->state != TBL_FAILED) continue;
        double tR, E;
        curve_coords(t, c, &tR, &E);
        printf("  FAILED normal curve t/R %g, E-ratio %g: %s\n", tR, E, cv->reason);
    }
}

static void info_text(const tbl_table *t, const char *path, const refine_plan *rp)
{
    tbl_family f;
    tbl_numerics n;
    tbl_get_family(t, &f);
    tbl_get_numerics(t, &n);
    char fam[256];
    tbl_family_describe(&f, fam, sizeof fam);
    printf("%s: friction table\n  family: %s\n", path, fam);
    printf("  numerics: 3D mesh level %d", n.mesh_level);
    if (n.elements_per_contact > 0) printf(" (%g elements across the contact)",
                                           n.elements_per_contact);
    printf(", %d node placements per point", n.placements);
    if (n.placements_max > 0)
        printf(" (refined up to %d where their standard error exceeds %g %%)", n.placements_max,
               100 * n.refine_err);
    if (n.foot_rows > 0.0) printf(", junction read on the node rows within %g a0", n.foot_rows);
    printf("\n");
    int count[ASP_PLACEMENTS_MAX + 1];
    if (n.placements_max > 0 && member_counts(t, count) > 0) {
        printf("  node placements of the done points:");
        for (int k = 1, first = 1; k <= ASP_PLACEMENTS_MAX; k++)
            if (count[k]) printf("%s %d (%d point%s)", first ? "" : ",", k, count[k],
                                 count[k] > 1 ? "s" : ""), first = 0;
        printf("\n");
    }
    static const char *const an[3] = {"delta/omega_c_su", "t/R", "Eco/Esu"};
    for (int k = 0; k < 3; k++) {
        const double *v;
        int m = tbl_axis(t, k, &v);
        print_axis(an[k], v, m);
    }
    int nd, nf, np;
    tbl_count(t, &nd, &nf, &np);
    double wall;
    int nrun, ncopied;
    double cpu = run_cost(t, 0, &nrun, &ncopied);
    const char *cmd = tbl_provenance(t, &wall);
    printf("  points: %d, done %d, failed %d, pending %d\n", tbl_points(t), nd, nf, np);
    if (ncopied > 0)
        printf("  one material: %d points (Eco/Esu = 1, t/R beyond the first) hold the first "
               "t/R's run at their delta\n", ncopied);
    printf("  built by: %s\n", cmd);
    const char *h = tbl_history(t);
    if (*h) printf("  before that, oldest first:\n");
    char line[512];
    while ((h = history_line(h, line, sizeof line))) printf("    %s\n", line);
    printf("  build wall time %.1f s, %.1f CPU s per point computed\n", wall,
           nrun ? cpu / nrun : 0.0);
    err_summary es;
    if (err_summarise(t, &es) != 0) {
        printf("  mu_s error estimates: not summarised (out of memory)\n");
    } else if (es.n > 0) {
        double w, tR, E;
        tbl_coords(t, es.imax, &w, &tR, &E);
        int m = tbl_point_get(t, es.imax)->members;
        printf("  mu_s error estimates (one standard error) of the %d point%s computed: median "
               "%.1f %%, %d at %.0f %% or more, largest %.1f %% (delta %g, t/R %g, Eco/Esu %g; %d "
               "member%s)\n", es.n, es.n == 1 ? "" : "s", 100 * es.median, es.noisy,
               100 * ERR_NOISY, 100 * es.max, w, tR, E, m, m == 1 ? "" : "s");
    }
    slope_summary ss;
    slope_summarise(t, &ss);
    if (ss.n > 0) {
        double w, tR, E;
        tbl_coords(t, ss.imax, &w, &tR, &E);
        printf("  mu_s against where inception is declared (d ln mu_s / d ln ux there, "
               "docs/design.md §4.4): %g or more at %d of %d point%s", SLOPE_HIGH, ss.high,
               ss.n, ss.n == 1 ? "" : "s");
        if (ss.high > 0) printf(" (from delta %g on)", ss.w_min);
        printf(", largest %.2f (delta %g, t/R %g, Eco/Esu %g)\n", ss.max, w, tR, E);
    }
    info_normal_text(t);
    tbl_fit_info fi;
    if (tbl_get_fit_info(t, &fi) == STC_OK)
        printf("  mu_s surrogate (%d points): leave-one-out error %.2f %% rms, %.2f %% largest, "
               "%.0f %% within 2 sd; error estimates scaled by %.2f\n", fi.n, 100 * fi.loo_rms,
               100 * fi.loo_max, 100 * fi.loo_cover2, fi.noise_scale);
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i);
        if (p->state != TBL_FAILED) continue;
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        printf("  FAILED delta %g, t/R %g, E-ratio %g: %s\n", w, tR, E, p->reason);
    }
    if (rp)
        printf("  refinement up to %d placements where the members' standard error exceeds "
               "%g of mu_s: %d of the %d done points refined (their members took %.0f CPU "
               "s; the members added, at least as much again)\n", rp->k, rp->x, rp->points, nd,
               rp->cpu_s);
    if (rp && rp->unkept > 0)
        printf("  %d of them keep no members (a file written before format 6): they compute "
               "their first members again\n", rp->unkept);
}

/* --points: the stored values of every point, CSV. */
static void info_points(const tbl_table *t)
{
    static const char *const state[] = {"pending", "done", "failed"};
    printf("index,delta_over_omega_c,t_over_R,E_ratio,state,P_over_P_c,A_over_A_c,"
           "P_slide_over_P_c,Q_max_over_P_c,mu_s,mu_s_err,mu_s_preload,mu_s_min,mu_s_max,"
           "ux_slide_over_omega_c,mu_s_ux_slope,members,newton_iterations,factorizations,"
           "wall_s,cpu_s,source,reason\n");
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i);
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        printf("%d,%.10g,%.10g,%.10g,%s", i, w, tR, E,
               p->state >= 0 && p->state <= 2 ? state[p->state] : "?");
        char sl[32]; /* not kept (a file before format 7): an empty field */
        if (p->state == TBL_DONE)
            printf(",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%s,%d,%d,%d,"
                   "%.4g,%.4g,", p->P_Pc, p->A_Ac, p->P_slide_Pc, p->Q_max_Pc, p->mu_s,
                   p->mu_s_err, p->mu_s_preload, p->mu_s_min, p->mu_s_max, p->ux_slide_wc,
                   cli_num(sl, sizeof sl, "%.6g", p->mu_s_ux_slope, ""), p->members,
                   p->newton_iterations, p->factorizations, p->wall_s, p->cpu_s);
        else printf(",,,,,,,,,,,,,,,%.4g,%.4g,", p->wall_s, p->cpu_s);
        printf("%d,", p->copied ? tbl_point_source(t, i) : i);
        /* the reason is free text: quoted, its quotes doubled */
        putchar('"');
        for (const char *c = p->reason; *c; c++) {
            if (*c == '"') putchar('"');
            putchar(*c);
        }
        printf("\"\n");
    }
}

/* --curves: the normal grid's values, CSV. */
static void info_curves(const tbl_table *t)
{
    static const char *const state[] = {"pending", "done", "failed"};
    const double *w;
    int nw = tbl_normal_axis(t, 0, &w);
    printf("curve,delta_over_omega_c,t_over_R,E_ratio,state,P_over_P_c,A_over_A_c\n");
    for (int c = 0; c < tbl_curves(t); c++) {
        const tbl_curve *cv = tbl_curve_get(t, c);
        double tR, E;
        curve_coords(t, c, &tR, &E);
        for (int k = 0; k < nw; k++) {
            double P, A;
            tbl_curve_values(t, c, k, &P, &A);
            printf("%d,%.10g,%.10g,%.10g,%s", c, w[k], tR, E,
                   cv->state >= 0 && cv->state <= 2 ? state[cv->state] : "?");
            if (cv->state == TBL_DONE) printf(",%.10g,%.10g\n", P, A);
            else printf(",,\n");
        }
    }
}

static int table_info(const cli_cmd *cmd, int argc, char **argv)
{
    const char *path = NULL;
    cli_peel_positional(&argc, &argv, &path);
    query_args q = {0};
    int done;
    int rc = cli_parse(cmd->name, "FILE [--json | --points | --curves]\n\nSummarise a table: "
                       "family, grid, coverage, failed points, build time, fit errors;\n"
                       "or list its points' stored values (--points) or its normal grid's "
                       "(--curves).",
                       argc, argv, info_opts, NULL, query_set, &q, &done);
    tbl_table *t = NULL;
    if (!rc && !done && q.json + q.points + q.curves > 1) {
        fprintf(stderr, "stiction %s: %s conflicts with %s: --points and --curves print CSV\n",
                cmd->name, q.json ? "--json" : "--points", q.curves ? "--curves" : "--points");
        rc = CLI_EXIT_USAGE;
    }
    if (!rc && !done && q.plan_k > 0 && q.points + q.curves > 0) {
        fprintf(stderr, "stiction %s: --placements-max conflicts with %s: the plan is part of "
                "the summary (text or --json)\n", cmd->name, q.points ? "--points" : "--curves");
        rc = CLI_EXIT_USAGE;
    }
    if (!rc && !done && q.plan_x > 0.0 && q.plan_k == 0) {
        fprintf(stderr, "stiction %s: --refine-err needs --placements-max\n", cmd->name);
        rc = CLI_EXIT_USAGE;
    }
    refine_plan rp = {q.plan_k, 0, q.plan_x > 0.0 ? q.plan_x : ASP_REFINE_ERR, 0.0, 0};
    if (!rc && !done && !(rc = open_table(cmd->name, path, &t)) && rp.k > 0) {
        stc_status s = tbl_refine_plan(t, rp.k, rp.x, &rp.points, &rp.cpu_s, &rp.unkept);
        if (s) rc = cli_fail(cmd->name, s);
    }
    if (!rc && !done && t) {
        if (q.points) info_points(t);
        else if (q.curves) info_curves(t);
        else if (q.json) info_json(t, path, rp.k > 0 ? &rp : NULL);
        else info_text(t, path, rp.k > 0 ? &rp : NULL);
    }
    tbl_destroy(&t);
    free(q.w);
    free(q.out);
    return rc;
}

/* ---- query ---------------------------------------------------------------------------- */

static const cli_opt query_opts[] = {
    CLI_HEADING("Point"),
    {"delta", "LIST", "delta/omega_c_su values"},
    {"t-over-R", "X", "coating thickness over the sphere's (summit's) radius R"},
    {"t-mm", "MM", "coating thickness in mm, instead of --t-over-R: t/R = t-mm / R with --R"},
    {"R", "MM", "with --t-mm: the sphere's (summit's) radius R, mm"},
    {"E-ratio", "X", "Eco/Esu"},
    CLI_HEADING("Common options"),
    {"json", NULL, "print a JSON array, one object per delta"},
    CLI_CONFIG_HELP,
    {NULL, NULL, NULL},
};

/* The coating as t/R: --t-over-R, or --t-mm over --R (the pair, not both
 * forms); STC_OK with q->tR set, or STC_EINVAL naming the keys. */
static stc_status query_t_over_R(query_args *q)
{
    if (q->t_mm > 0 && q->tR > 0)
        return cli_conflict("t-mm", "t-over-R", "give the coating thickness one way");
    if (q->t_mm > 0 && !(q->R > 0))
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "t-mm = %g given without R: t/R = "
                         "t-mm / R needs the sphere's radius (--R MM)", q->t_mm);
    if (q->R > 0 && !(q->t_mm > 0))
        return stc_error(STC_EINVAL, __FILE__, __LINE__, "R = %g given without t-mm: R is the "
                         "radius --t-mm MM refers to (a table is normalised by R)", q->R);
    if (q->t_mm > 0) {
        stc_status s = stc_check_range("t-mm / R", q->t_mm / q->R, 0.0, 0, 1.0, 0);
        if (s) return s;
        q->tR = q->t_mm / q->R;
    }
    return STC_OK;
}

static int table_query(const cli_cmd *cmd, int argc, char **argv)
{
    const char *path = NULL;
    cli_peel_positional(&argc, &argv, &path);
    query_args q = {0};
    int done;
    int rc = cli_parse(cmd->name, "FILE --delta LIST (--t-over-R X | --t-mm MM --R MM) "
                       "--E-ratio X [--json]\n\nInterpolated response with one-standard-error "
                       "bars; values outside the table are flagged\n(JSON: in_range, flags) and "
                       "warned about on stderr.",
                       argc, argv, query_opts, NULL, query_set, &q, &done);
    tbl_table *t = NULL;
    tbl_value *v = NULL;
    if (rc || done) goto out;
    stc_status st = query_t_over_R(&q);
    if (st) {
        rc = cli_fail(cmd->name, st);
        goto out;
    }
    const char *miss = !q.w ? "delta" : !(q.tR > 0) ? "t-over-R (or --t-mm with --R)"
                     : !(q.E > 0) ? "E-ratio" : NULL;
    if (miss) {
        fprintf(stderr, "stiction %s: %s: missing\n", cmd->name, miss);
        rc = CLI_EXIT_USAGE;
        goto out;
    }
    for (int i = 0; i < q.nw; i++)
        if (!(q.w[i] > 0)) {
            fprintf(stderr, "stiction %s: delta = %g: must be > 0\n", cmd->name, q.w[i]);
            rc = CLI_EXIT_USAGE;
            goto out;
        }
    if ((rc = open_table(cmd->name, path, &t))) goto out;
    v = calloc((size_t)q.nw, sizeof *v);
    unsigned any = 0;
    for (int i = 0; v && i < q.nw; i++) {
        stc_status s = tbl_query(t, q.w[i], q.tR, q.E, &v[i]);
        if (s) {
            rc = cli_fail(cmd->name, s);
            goto out;
        }
        any |= v[i].flags;
    }
    if (!v) {
        rc = cli_fail(cmd->name, STC_ENOMEM);
        goto out;
    }
    char fl[256];
    if (q.json) {
        cli_json j;
        cj_init(&j, stdout);
        cj_arr(&j, NULL);
        for (int i = 0; i < q.nw; i++) {
            cj_obj(&j, NULL);
            cj_num(&j, "delta_over_omega_c", q.w[i]);
            cj_num(&j, "t_over_R", q.tR);
            cj_num(&j, "E_ratio", q.E);
            cj_num(&j, "P_over_P_c", v[i].P_Pc);
            cj_num(&j, "P_over_P_c_err", v[i].P_Pc_err);
            cj_num(&j, "A_over_A_c", v[i].A_Ac);
            cj_num(&j, "A_over_A_c_err", v[i].A_Ac_err);
            cj_num(&j, "P_slide_over_P_c", v[i].P_slide_Pc);
            cj_num(&j, "mu_s", v[i].mu_s);
            cj_num(&j, "mu_s_err", v[i].mu_s_err);
            cj_num(&j, "Q_max_over_P_c", v[i].Q_max_Pc);
            cj_num(&j, "Q_max_over_P_c_err", v[i].Q_max_Pc_err);
            cj_str(&j, "P_A_from", v[i].from_normal ? "normal grid" : "3D points");
            cj_num(&j, "mu_s_ux_slope", v[i].mu_s_ux_slope);
            cj_bool(&j, "in_range", v[i].flags == 0);
            cj_str(&j, "flags", flags_text(v[i].flags, fl, sizeof fl));
            cj_end_obj(&j);
        }
        cj_end_arr(&j);
        cj_done(&j);
    } else {
        printf("t/R = %g, Eco/Esu = %g (one standard error after +-)\n", q.tR, q.E);
        int slope = 0;
        for (int i = 0; i < q.nw; i++) slope |= isfinite(v[i].mu_s_ux_slope);
        printf("%10s %22s %22s %11s %20s %22s", "delta/wc", "P/Pc", "A/Ac", "Pslide/Pc", "mu_s",
               "Qmax/Pc");
        printf(slope ? " %8s  %s\n" : "%.0s  %s\n", "dmu/dux", "flags");
        for (int i = 0; i < q.nw; i++) {
            printf("%10g %12.5g +- %-7.2g %12.5g +- %-7.2g %11.5g %9.4f +- %-7.4f %12.5g +- "
                   "%-7.2g", q.w[i], v[i].P_Pc, v[i].P_Pc_err, v[i].A_Ac, v[i].A_Ac_err,
                   v[i].P_slide_Pc, v[i].mu_s, v[i].mu_s_err, v[i].Q_max_Pc, v[i].Q_max_Pc_err);
            if (slope) printf(" %8.3f", v[i].mu_s_ux_slope);
            printf("  %s\n", flags_text(v[i].flags, fl, sizeof fl));
        }
        if (slope)
            printf("(dmu/dux: d ln mu_s / d ln ux where inception is declared, of the grid "
                   "points around it: per cent of mu_s per per cent of that ux; "
                   "docs/design.md §4.4)\n");
    }
    if (any)
        fprintf(stderr, "stiction %s: warning: %s: outside the table's range (not an answer of "
                "the table; see the flags)\n", cmd->name, flags_text(any, fl, sizeof fl));
out:
    free(v);
    tbl_destroy(&t);
    free(q.w);
    free(q.out);
    return rc;
}

/* ---- merge --------------------------------------------------------------------------------- */

static const cli_opt merge_opts[] = {
    {"out", "FILE", "the merged table"},
    {"json", NULL, "print the summary as JSON"},
    {NULL, NULL, NULL},
};

enum { MERGE_MAX = 4096 };

static int table_merge(const cli_cmd *cmd, int argc, char **argv)
{
    const char **files = malloc(MERGE_MAX * sizeof *files);
    tbl_table **parts = calloc(MERGE_MAX, sizeof *parts);
    tbl_table *m = NULL;
    query_args q = {0};
    int n = files ? peel_files(&argc, &argv, files, MERGE_MAX) : 0, done, rc;
    rc = cli_parse(cmd->name, "A.h5 B.h5 ... --out FILE\n\nJoin the shards "
                   "(or partial runs) of one build into one table.",
                   argc, argv, merge_opts, NULL, query_set, &q, &done);
    if (rc || done) goto out;
    if (!files || !parts) {
        rc = cli_fail(cmd->name, STC_ENOMEM);
        goto out;
    }
    if (n < 1 || !q.out) {
        fprintf(stderr, "stiction %s: %s: missing\n", cmd->name, n < 1 ? "input tables" : "out");
        rc = CLI_EXIT_USAGE;
        goto out;
    }
    for (int i = 0; i < n; i++)
        if ((rc = open_table(cmd->name, files[i], &parts[i]))) goto out;
    stc_status s = tbl_merge(parts, n, &m);
    if (!s) {
        int nd;
        tbl_count(m, &nd, NULL, NULL);
        if (nd >= 3) s = tbl_fit(m);
    }
    if (!s) s = tbl_write(m, q.out);
    if (s) {
        rc = cli_fail(cmd->name, s);
        goto out;
    }
    int nd, nf, np;
    tbl_count(m, &nd, &nf, &np);
    if (q.json) {
        cli_json j;
        cj_init(&j, stdout);
        cj_obj(&j, NULL);
        cj_str(&j, "file", q.out);
        cj_int(&j, "tables", n);
        cj_int(&j, "points", tbl_points(m));
        cj_int(&j, "done", nd);
        cj_int(&j, "failed", nf);
        cj_int(&j, "pending", np);
        cj_end_obj(&j);
        cj_done(&j);
    } else {
        printf("wrote %s: %d points from %d tables, %d done, %d failed, %d pending\n", q.out,
               tbl_points(m), n, nd, nf, np);
    }
    if (np > 0)
        fprintf(stderr, "stiction %s: warning: %d points pending (a shard missing?)\n",
                cmd->name, np);
out:
    for (int i = 0; parts && i < n; i++) tbl_destroy(&parts[i]);
    tbl_destroy(&m);
    free(parts);
    free(files);
    free(q.w);
    free(q.out);
    return rc;
}

/* ---- dispatch ------------------------------------------------------------------------------- */

static const cli_cmd table_cmds[] = {
    {"table build", "sweep the FE solver over a family's axes into an HDF5 table (resumable)",
     table_build},
    {"table info", "family, grid, coverage, failed points, build time, fit errors",
     table_info},
    {"table query", "interpolated P, A, mu_s with error bars at (delta, t/R, E-ratio)",
     table_query},
    {"table merge", "join shards of one build", table_merge},
    {NULL, NULL, NULL},
};

int cli_table(const cli_cmd *cmd, int argc, char **argv)
{
    (void)cmd;
    return cli_dispatch("table", table_cmds, argc, argv);
}
