/* stiction table build|info|query|merge from the command line: a build
 * killed at random moments resumes without losing a finished point and ends
 * equal to an uninterrupted one; shards joined by merge equal the serial
 * build; bad input is refused by name and leaves no file.  The builds are
 * small and coarse (3 elements across the contact, one placement, slip
 * normal step: about 2 s a point, one at a time), so the test measures the machinery, not
 * the accuracy of the points. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "cli_util.h"
#include "stiction/table.h"
#include "tmp_util.h"

static char cli[PATH_MAX], dir[256];
static const char *P(const char *name) { return cli_path(dir, name); }

#define BUILD_AXES "--deltas 0.5,1 --t-over-R 0.01 --E-ratio 1,2"
#define BUILD_NUM "--contact slip --elements-per-contact 3 --placements 1"

/* argv of the CLI with the arguments args (split at blanks) */
static int cli_argv(char **av, int cap, const char *args)
{
    static char buf[2048];
    snprintf(buf, sizeof buf, "%s", args);
    int n = 0;
    av[n++] = cli;
    for (char *t = strtok(buf, " "); t && n < cap - 1; t = strtok(NULL, " ")) av[n++] = t;
    av[n] = NULL;
    return n;
}

/* Start the CLI with args in the scratch directory, stderr to errfile;
 * returns its pid. */
static pid_t start_cli(const char *args, const char *errfile)
{
    char *av[64];
    cli_argv(av, 64, args);
    fflush(stdout); /* the child must not write the parent's buffered lines again */
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        if (chdir(dir) != 0) _exit(127);
        FILE *e = freopen(errfile, "w", stderr);
        FILE *o = freopen("/dev/null", "w", stdout);
        (void)e, (void)o;
        execv(cli, av);
        _exit(127);
    }
    return pid;
}

/* Start a build of the small table into `out`, extra args appended. */
static pid_t start_build(const char *out, const char *extra, const char *errfile)
{
    char args[1024];
    snprintf(args, sizeof args, "table build " BUILD_AXES " " BUILD_NUM " --out %s %s", out,
             extra ? extra : "");
    return start_cli(args, errfile);
}

static int wait_rc(pid_t pid)
{
    int st;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {}
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

/* Run the CLI in the scratch directory; which = 1 captures stdout, 2 stderr. */
static int run(const char *args, int which, char *out, size_t n)
{
    static char cmd[PATH_MAX + 2048]; /* cli_capture adds its redirection */
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s", dir, cli, args);
    return cli_capture(cmd, which, out, n);
}

static int count_lines(const char *path, const char *needle)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    char line[4096];
    int n = 0;
    while (fgets(line, sizeof line, f)) n += strstr(line, needle) != NULL;
    fclose(f);
    return n;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* The uninterrupted reference build runs while the first test kills builds
 * (one point at a time each); a test that reads ref.h5 waits for it first,
 * and fails if it failed. */
static pid_t ref_pid = -1;
static int ref_rc;

static void wait_ref(void)
{
    if (ref_pid > 0) {
        ref_rc = wait_rc(ref_pid);
        ref_pid = -1;
    }
    if (ref_rc != 0) fail_msg("reference build failed: exit %d (%s)", ref_rc, P("ref.err"));
}

/* The results of two tables are equal point by point, bitwise (times
 * excluded: they are measurements of the run).  Every build here runs one
 * point at a time: a point's numbers then do not depend on what the process
 * computed before it (measured: a shard computing one point alone gives the
 * full build's bits).  Two points computed at once in one process agree only
 * to the solver's tolerances (up to 2.6e-7 relative in mu_s, measured). */
static double same_points(const tbl_table *ta, const tbl_table *tb)
{
    assert_true(tbl_same_build(ta, tb));
    double worst = 0.0;
    for (int i = 0; i < tbl_points(ta); i++) {
        const tbl_point *p = tbl_point_get(ta, i), *q = tbl_point_get(tb, i);
        assert_int_equal(p->state, q->state);
        assert_int_equal(p->state, TBL_DONE);
        const double va[] = {p->P_Pc, p->A_Ac, p->P_slide_Pc, p->Q_max_Pc, p->mu_s,
                             p->mu_s_err, p->mu_s_preload, p->ux_slide_wc};
        const double vb[] = {q->P_Pc, q->A_Ac, q->P_slide_Pc, q->Q_max_Pc, q->mu_s,
                             q->mu_s_err, q->mu_s_preload, q->ux_slide_wc};
        for (size_t k = 0; k < sizeof va / sizeof *va; k++)
            worst = fmax(worst, fabs(va[k] - vb[k]) / fabs(vb[k]));
        assert_int_equal(p->members, q->members);
        assert_int_equal(p->newton_iterations, q->newton_iterations);
        assert_int_equal(p->factorizations, q->factorizations);
        assert_string_equal(p->reason, q->reason);
    }
    return worst;
}

static void assert_same_results(const char *a, const char *b)
{
    tbl_table *ta = NULL, *tb = NULL;
    wait_ref();
    assert_int_equal(tbl_read(a, &ta), STC_OK);
    assert_int_equal(tbl_read(b, &tb), STC_OK);
    double worst = same_points(ta, tb);
    assert_int_equal(tbl_curves(ta), tbl_curves(tb));
    assert_true(tbl_curves(ta) > 0);
    const double *w;
    int nw = tbl_normal_axis(ta, 0, &w);
    for (int c = 0; c < tbl_curves(ta); c++) {
        assert_int_equal(tbl_curve_get(ta, c)->state, TBL_DONE);
        assert_int_equal(tbl_curve_get(tb, c)->state, TBL_DONE);
        for (int k = 0; k < nw; k++) {
            double Pa, Aa, Pb, Ab;
            tbl_curve_values(ta, c, k, &Pa, &Aa);
            tbl_curve_values(tb, c, k, &Pb, &Ab);
            worst = fmax(worst, fmax(fabs(Pa - Pb) / Pb, fabs(Aa - Ab) / Ab));
        }
    }
    printf("  largest relative difference of any stored result (points and normal curves): "
           "%.2g\n", worst);
    assert_true(worst == 0.0);
    tbl_destroy(&ta);
    tbl_destroy(&tb);
}

/* ------------------------------------------------------------ fixtures */

static int setup(void **state)
{
    (void)state;
    if (cli_locate(cli, sizeof cli) != 0) return -1;
    snprintf(dir, sizeof dir, "%s/stiction-test-table-XXXXXX", test_tmpdir());
    if (!mkdtemp(dir)) return -1;
    ref_pid = start_build("ref.h5", "--jobs 1", P("ref.err"));
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    if (ref_pid > 0) { /* a test failed before it waited */
        kill(ref_pid, SIGKILL);
        wait_rc(ref_pid);
    }
    char cmd[PATH_MAX + 32];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* ------------------------------------------------------------ tests */

/* SIGKILL three times, each at a pseudo-random moment (fixed seed) after
 * the run has reported its first normal curve (the first kill) or its first
 * point (the others), then to the end: every curve and point reported before
 * a kill is taken by the next run (no curve is computed twice once it was
 * reported), no half-written table ever sits under the final name, and the
 * result equals the uninterrupted build. */
static void test_killed_build_resumes(void **state)
{
    (void)state;
    unsigned seed = 20261126u;
    int reported_before = 0, curves_reported = 0;
    for (int k = 0; k < 3; k++) {
        seed = seed * 1103515245u + 12345u;
        double wait_s = 1.5 * ((seed >> 8) % 1000) / 1000.0;
        const char *first = k == 0 ? "[normal " : "] delta ";
        char err[32];
        snprintf(err, sizeof err, "kill%d.err", k);
        pid_t pid = start_build("k.h5", "--jobs 1", P(err));
        int st, gone = 0;
        while (!(gone = waitpid(pid, &st, WNOHANG) == pid) && count_lines(P(err), first) < 1) {
            struct timespec poll = {0, 20000000};
            nanosleep(&poll, NULL);
        }
        if (gone) fail_msg("build %d ended before it could be killed", k);
        struct timespec ts = {(time_t)wait_s, (long)((wait_s - floor(wait_s)) * 1e9)};
        nanosleep(&ts, NULL);
        kill(pid, SIGKILL);
        int rc = wait_rc(pid);
        int reported = count_lines(P(err), "] delta ");
        int curves = count_lines(P(err), "[normal ");
        printf("  kill %d at %.2f s after its first %s (exit %d): %d curves, %d points "
               "reported\n", k, wait_s, k == 0 ? "curve" : "point", rc, curves, reported);
        reported_before += reported;
        curves_reported += curves;
        if (exists(P("k.h5"))) { /* only ever a whole table */
            tbl_table *t = NULL;
            assert_int_equal(tbl_read(P("k.h5"), &t), STC_OK);
            tbl_destroy(&t);
        }
    }
    char out[4096];
    int rc = run("table build " BUILD_AXES " " BUILD_NUM " --out k.h5 --jobs 1", 1, out,
                 sizeof out);
    assert_int_equal(rc, 0);
    int taken = -1, share = -1, computed = -1;
    const char *p = strstr(out, "this run: ");
    assert_non_null(p);
    assert_int_equal(sscanf(p, "this run: %d of %d points of its share computed, %d taken",
                            &computed, &share, &taken), 3);
    int curves_total = -1, curves_now = -1;
    const char *q = strstr(out, "normal grid: ");
    assert_non_null(q);
    assert_int_equal(sscanf(q, "normal grid: %d curves, %*d done, %*d failed, %*d pending; "
                            "this run computed %d", &curves_total, &curves_now), 2);
    printf("  final run: %d computed, %d taken from the killed runs (%d reported by them); "
           "normal curves: %d computed, %d reported by the killed runs, of %d\n", computed,
           taken, reported_before, curves_now, curves_reported, curves_total);
    assert_int_equal(curves_now + curves_reported, curves_total);
    assert_int_equal(share, 4);
    assert_int_equal(computed + taken, 4);
    assert_true(taken >= reported_before); /* journal first, report after */
    assert_false(exists(P("k.h5.journal")));
    assert_false(exists(P("k.h5.tmp")));
    assert_same_results(P("ref.h5"), P("k.h5"));
    printf("  resumed table equals the uninterrupted build (every point)\n");
}

/* The file at path holds the bytes of tag (a journal record's magic). */
static int file_has(const char *path, const char *tag)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    static char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf, f), k = strlen(tag);
    fclose(f);
    for (size_t i = 0; i + k <= n; i++)
        if (!memcmp(buf + i, tag, k)) return 1;
    return 0;
}

/* One point of two placement members, no normal grid */
#define MEMBER_BUILD "table build --deltas 0.5 --t-over-R 0.01 --E-ratio 2 " \
                     "--contact slip --elements-per-contact 3 --placements 2 " \
                     "--normal-level -1 --jobs 1 --out "

/* A build killed during a point, after its first placement member was
 * journaled ("TBTM") and before the point was ("TBTP"), keeps that member:
 * the next run computes only the other one, and the point equals the
 * uninterrupted build's. */
/* Run `args` (a build writing file, whose journal is file.journal) and
 * kill it after its first member's record and before the point's (up to
 * three tries); `keep`: file existed before and must still. */
static void kill_after_first_member(const char *args, const char *file, int keep)
{
    char journal[512], err[512];
    snprintf(journal, sizeof journal, "%s.journal", file);
    snprintf(err, sizeof err, "%s.err", file);
    int attempt = 0, caught = 0;
    for (; attempt < 3 && !caught; attempt++) {
        unlink(journal);
        pid_t pid = start_cli(args, err);
        int st, gone = 0;
        while (!(gone = waitpid(pid, &st, WNOHANG) == pid) && !file_has(journal, "TBTM")) {
            struct timespec poll = {0, 5000000};
            nanosleep(&poll, NULL);
        }
        if (gone) fail_msg("the build ended before its first member was journaled");
        kill(pid, SIGKILL);
        wait_rc(pid);
        assert_int_equal(exists(file), keep);
        /* the point itself journaled before the kill landed: try again */
        caught = !file_has(journal, "TBTP");
    }
    printf("  killed after the first member's record (attempt %d)\n", attempt);
    assert_true(caught);
}

static void test_killed_point_keeps_members(void **state)
{
    (void)state;
    pid_t ref = start_cli(MEMBER_BUILD "mref.h5", P("mref.err"));
    kill_after_first_member(MEMBER_BUILD "mk.h5", P("mk.h5"), 0);
    char out[4096];
    assert_int_equal(run(MEMBER_BUILD "mk.h5", 1, out, sizeof out), 0);
    printf("%s", out);
    assert_non_null(strstr(out, "1 of 1 points of its share computed"));
    assert_non_null(strstr(out, "placement members taken from an earlier run (the journal, or "
                              "the file a refinement goes on from): 1"));
    assert_false(exists(P("mk.h5.journal")));
    assert_int_equal(wait_rc(ref), 0);
    tbl_table *ta = NULL, *tb = NULL;
    assert_int_equal(tbl_read(P("mref.h5"), &ta), STC_OK);
    assert_int_equal(tbl_read(P("mk.h5"), &tb), STC_OK);
    assert_int_equal(tbl_point_get(tb, 0)->members, 2);
    double worst = same_points(ta, tb);
    printf("  resumed point against the uninterrupted build: largest relative difference "
           "%.2g; CPU s %.2f against %.2f\n", worst, tbl_point_get(tb, 0)->cpu_s,
           tbl_point_get(ta, 0)->cpu_s);
    assert_true(worst == 0.0);
    assert_true(tbl_point_get(tb, 0)->cpu_s > 0.75 * tbl_point_get(ta, 0)->cpu_s);
    tbl_destroy(&tb);

    /* the same when the point was failed and is retried (--retry-failed) */
    tbl_point p;
    memset(&p, 0, sizeof p);
    p.state = TBL_FAILED;
    snprintf(p.reason, sizeof p.reason, "made to fail");
    assert_int_equal(tbl_point_set(ta, 0, &p), STC_OK);
    assert_int_equal(tbl_write(ta, P("mr.h5")), STC_OK);
    kill_after_first_member(MEMBER_BUILD "mr.h5 --retry-failed", P("mr.h5"), 1);
    assert_int_equal(run(MEMBER_BUILD "mr.h5 --retry-failed", 1, out, sizeof out), 0);
    printf("%s", out);
    assert_non_null(strstr(out, "placement members taken from an earlier run (the journal, or "
                              "the file a refinement goes on from): 1"));
    tbl_destroy(&ta);
    assert_int_equal(tbl_read(P("mref.h5"), &ta), STC_OK);
    assert_int_equal(tbl_read(P("mr.h5"), &tb), STC_OK);
    worst = same_points(ta, tb);
    printf("  retried point resumed against the uninterrupted build: largest relative "
           "difference %.2g\n", worst);
    assert_true(worst == 0.0);
    tbl_destroy(&ta);
    tbl_destroy(&tb);
}

/* Two shards built separately and merged equal the serial build; a shard
 * alone is a partial table. */
static void test_shards_merge(void **state)
{
    (void)state;
    char out[4096];
    pid_t a = start_build("s0.h5", "--shard 0/2 --jobs 1", P("s0.err"));
    pid_t b = start_build("s1.h5", "--shard 1/2 --jobs 1", P("s1.err"));
    assert_int_equal(wait_rc(a), 0);
    assert_int_equal(wait_rc(b), 0);
    assert_int_equal(run("table info s0.h5 --json", 1, out, sizeof out), 0);
    assert_json(out);
    assert_non_null(strstr(out, "\"pending\": 2"));
    assert_int_equal(run("table merge s0.h5 s1.h5 --out m.h5", 2, out, sizeof out), 0);
    assert_same_results(P("ref.h5"), P("m.h5"));
    assert_int_equal(run("table merge s0.h5 s1.h5 --out m2.h5 --json", 1, out, sizeof out), 0);
    assert_json(out);
    assert_non_null(strstr(out, "\"tables\": 2,"));
    assert_non_null(strstr(out, "\"pending\": 0"));
    assert_same_results(P("ref.h5"), P("m2.h5"));
    printf("  shards 0/2 + 1/2 merged equal the serial build\n");
}

/* A refusal (exit code != 0) naming n1 and n2, or with code 0 an answer
 * flagged on stderr (a value outside the table's range). */
static void expect_refusal(const char *args, int code, const char *n1, const char *n2)
{
    char out[8192];
    int rc = run(args, 2, out, sizeof out);
    printf("  %-60.60s -> %d: %s", args, rc, out);
    assert_int_equal(rc, code);
    assert_non_null(strstr(out, n1));
    if (n2) assert_non_null(strstr(out, n2));
}

static void test_bad_input(void **state)
{
    (void)state;
    char out[8192];
    wait_ref();
    /* a file that is not a table */
    assert_int_equal(run("surface synth --size 16 --out map.h5", 1, out, sizeof out), 0);
    expect_refusal("table info map.h5", 2, "not a friction table", NULL);
    expect_refusal("table info nosuch.h5", 1, "FILE = 'nosuch.h5': cannot open", NULL);
    expect_refusal("table info .", 1, "is a directory", NULL);
    /* a build onto a table of another build leaves it as it was */
    struct stat before, after;
    assert_int_equal(stat(P("ref.h5"), &before), 0);
    expect_refusal("table build --deltas 0.5,1 --t-over-R 0.01 --E-ratio 1 --contact slip "
                   "--out ref.h5", 2, "another build", NULL);
    assert_int_equal(stat(P("ref.h5"), &after), 0);
    assert_true(before.st_mtime == after.st_mtime && before.st_size == after.st_size);
    expect_refusal("table build --deltas 1,0.5 --t-over-R 0.01 --E-ratio 1 --out x.h5", 2,
                   "deltas = '1,0.5'", "must increase");
    expect_refusal("table build --deltas 1 --t-over-R 0.01 --out x.h5", 2, "E-ratio: missing",
                   NULL);
    expect_refusal("table build " BUILD_AXES " --shard 2/2 --out x.h5", 2, "shard = '2/2'",
                   NULL);
    /* below the solver's least: refused before any point runs */
    expect_refusal("table build " BUILD_AXES " --elements-per-contact 2 --out x.h5", 2,
                   "elements-per-contact = 2", "[3, 200]");
    assert_false(exists(P("x.h5")));
    assert_false(exists(P("x.h5.journal")));
    /* merge of tables of different builds, or of a missing one: no output */
    assert_int_equal(run("table build --deltas 0.5 --t-over-R 0.01 --E-ratio 1 " BUILD_NUM
                         " --out other.h5", 1, out, sizeof out), 0);
    expect_refusal("table merge ref.h5 other.h5 --out mm.h5", 2, "another build", NULL);
    expect_refusal("table merge ref.h5 nosuch.h5 --out mm.h5", 1,
                   "FILE = 'nosuch.h5': cannot open", NULL);
    assert_false(exists(P("mm.h5")));
    /* a query outside the table: answered, flagged on stderr and in JSON */
    int rc = run("table query ref.h5 --delta 1,5 --t-over-R 0.01 --E-ratio 1.5 --json", 1, out,
                 sizeof out);
    assert_int_equal(rc, 0);
    assert_json(out);
    assert_non_null(strstr(out, "\"in_range\": true"));
    assert_non_null(strstr(out, "delta above the table"));
    expect_refusal("table query ref.h5 --delta 5 --t-over-R 0.01 --E-ratio 1", 0,
                   "warning: delta above the table", NULL);
    /* the materials of another family */
    expect_refusal("surface predict --table ref.h5 --nu 0.3 --summit-density 2000 "
                   "--summit-radius 0.07 --sigma-s 0.0004 --pressures 1", 2,
                   "another family", "nu 0.3, 0.3");
    expect_refusal("surface predict --table ref.h5 --E-ratio 3 --summit-density 2000 "
                   "--summit-radius 0.07 --sigma-s 0.0004 --pressures 1", 1,
                   "E-ratio = 3: outside the table's [1, 2]", NULL);
    expect_refusal("surface predict --table ref.h5 --model wsp --summit-density 2000 "
                   "--summit-radius 0.07 --sigma-s 0.0004 --pressures 1", 2,
                   "--model conflicts with --table", NULL);
    /* a missing table: named once, as the parameter */
    char err[8192];
    assert_int_equal(run("surface predict --table nosuch.h5 --summit-density 2000 "
                         "--summit-radius 0.07 --sigma-s 0.0004 --pressures 1", 2, err,
                         sizeof err), 1);
    assert_non_null(strstr(err, "table = 'nosuch.h5': cannot open"));
    assert_null(strstr(err, "nosuch.h5: cannot open"));
}

/* The coating of a query in mm, as on the other commands: --t-mm MM with
 * the sphere's radius --R MM gives the answer of --t-over-R t/R, and one
 * without the other, or both forms, is refused by name. */
static void test_query_t_mm(void **state)
{
    (void)state;
    static char ref[8192], out[8192];
    wait_ref();
    assert_int_equal(run("table query ref.h5 --delta 1,5 --t-over-R 0.01 --E-ratio 1.5 --json", 1,
                         ref, sizeof ref), 0);
    assert_int_equal(run("table query ref.h5 --delta 1,5 --t-mm 0.05 --R 5 --E-ratio 1.5 --json",
                         1, out, sizeof out), 0);
    assert_string_equal(out, ref);
    printf("  --t-mm 0.05 --R 5 answers as --t-over-R 0.01\n");
    expect_refusal("table query ref.h5 --delta 1 --t-mm 0.05 --E-ratio 1.5", 2,
                   "t-mm = 0.05 given without R", NULL);
    expect_refusal("table query ref.h5 --delta 1 --R 5 --E-ratio 1.5", 2,
                   "R = 5 given without t-mm", NULL);
    expect_refusal("table query ref.h5 --delta 1 --t-mm 0.05 --R 5 --t-over-R 0.01 "
                   "--E-ratio 1.5", 2, "--t-mm conflicts with --t-over-R", NULL);
    expect_refusal("table query ref.h5 --delta 1 --E-ratio 1.5", 2,
                   "t-over-R (or --t-mm with --R): missing", NULL);
    /* the ranges of stiction asperity; inside them, a point off the table is flagged */
    expect_refusal("table query ref.h5 --delta 1 --t-over-R 1 --E-ratio 1.5", 2,
                   "t-over-R = 1: must be in (0, 1)", NULL);
    expect_refusal("table query ref.h5 --delta 1 --t-mm 6 --R 5 --E-ratio 1.5", 2,
                   "must be in (0, 1)", NULL);
    expect_refusal("table query ref.h5 --delta 1 --t-over-R 0.01 --E-ratio 0", 2,
                   "E-ratio = 0: must be > 0", NULL);
    expect_refusal("table query ref.h5 --delta 1 --t-over-R 0.9995 --E-ratio 2000", 0,
                   "t/R outside (clamped); E-ratio outside (clamped)", NULL);
    assert_int_equal(run("table query --help", 1, out, sizeof out), 0);
    assert_non_null(strstr(out, "t/R = t-mm / R"));
}

/* surface predict --fill computes only the table points its loads touch,
 * adds them to the table file, and a second run finds nothing to do. */
static void test_fill(void **state)
{
    (void)state;
    char out[8192], a[8192], b[8192];
    /* (its normal grid on the coarse axisymmetric level 0: a third of level 1's time) */
    assert_int_equal(run("table build --deltas 0.5,1,2,4,8 --t-over-R 0.02 --E-ratio 1,2 "
                         BUILD_NUM " --normal-level 0 --out fill.h5 --init", 1, out,
                         sizeof out), 0);
    assert_non_null(strstr(out, "10 points (5 x 1 x 2), 0 done, 0 failed, 10 pending"));
    /* E-ratio 2 on its node, t/R = 0.0014/0.07 = 0.02; delta/omega_c up to
     * 1.2 here: delta nodes 0.5, 1, 2 and one more */
#define FILL_RUN "surface predict --table fill.h5 --E-ratio 2 --t-mm 0.0014 " \
                 "--summit-density 2000 --summit-radius 0.07 --sigma-s 1e-7 --pressures 0.01"
    assert_int_equal(run(FILL_RUN " --fill --jobs 2", 2, out, sizeof out), 0);
    printf("%s", out);
    assert_non_null(strstr(out, "the loads touch 4 of the table's 10 points; 4 computed now "
                                "(0 failed"));
    assert_int_equal(run("table info fill.h5 --json", 1, out, sizeof out), 0);
    assert_json(out);
    /* the numerics it was built with (BUILD_NUM) */
    assert_non_null(strstr(out, "\"elements_per_contact\": 3"));
    assert_non_null(strstr(out, "\"placements\": 1"));
    assert_non_null(strstr(out, "\"placements_max\": 0"));
    assert_non_null(strstr(out, "\"normal_level\": 0"));
    assert_non_null(strstr(out, "\"done\": 4"));
    /* one member each: every error estimate is err_single, 10 % */
    const char *es = strstr(out, "\"mu_s_err_rel\": {");
    assert_non_null(es);
    assert_non_null(strstr(es, "\"points\": 4,"));
    assert_non_null(strstr(es, "\"noisy\": 4,"));
    assert_true(fabs(cli_jnum(es, "median") - 0.1) < 1e-9);
    assert_non_null(strstr(out, "\"pending\": 6"));
    /* the filled table carries its surrogate's fit: read without a search */
    assert_non_null(strstr(out, "\"fit_reused\": 1"));
    /* --points: a CSV row per point, the done ones with their numbers */
    assert_int_equal(run("table info fill.h5 --points", 1, out, sizeof out), 0);
    int rows = 0, done_rows = 0;
    for (char *l = strtok(out, "\n"); l; l = strtok(NULL, "\n")) {
        rows++;
        if (strstr(l, ",done,")) {
            done_rows++;
            double mu = 0.0;
            char *c = l;
            for (int k = 0; k < 9 && c; k++) c = strchr(c + 1, ','); /* to mu_s */
            assert_non_null(c);
            mu = strtod(c + 1, NULL);
            assert_true(mu > 0.2 && mu < 2.0);
        }
    }
    assert_int_equal(rows, 11);
    assert_int_equal(done_rows, 4);
    expect_refusal("table info fill.h5 --points --json", 2, "--json conflicts with --points",
                   NULL);
    assert_int_equal(run(FILL_RUN " --fill --jobs 1", 2, out, sizeof out), 0);
    assert_non_null(strstr(out, "touch 4 of the table's 10 points; 0 computed now"));
    assert_non_null(strstr(out, "4 were there"));
    assert_int_equal(run(FILL_RUN " --fill", 1, a, sizeof a), 0);
    assert_int_equal(run(FILL_RUN, 1, b, sizeof b), 0);
    assert_string_equal(a, b);
    expect_refusal("surface predict --fill --summit-density 2000 --summit-radius 0.07 "
                   "--sigma-s 1e-7 --pressures 1", 2, "--fill needs --table FILE", NULL);
    expect_refusal(FILL_RUN " --jobs 2", 2, "--jobs 2 needs --fill", NULL);
    /* a design sweep fills for every design: Eco/Esu 1 adds its 4 points,
     * those of 2 are there; then each design reads what predict reads */
#define SWEEP_RUN "surface sweep --table fill.h5 --E-ratio 1,2 --t-mm 0.0014 " \
                  "--summit-density 2000 --summit-radius 0.07 --sigma-s 1e-7 --pressures 0.01"
    assert_int_equal(run("table info fill.h5 --json", 1, out, sizeof out), 0);
    double w1 = cli_jnum(out, "build_wall_s"), ws = -1.0;
    assert_int_equal(run(SWEEP_RUN " --fill --jobs 2", 2, out, sizeof out), 0);
    const char *cn = strstr(out, "the loads touch 8 of the table's 10 points; 4 computed now "
                                 "(0 failed, ");
    assert_non_null(cn);
    assert_int_equal(sscanf(strstr(cn, "(0 failed, ") + 11, "%lf", &ws), 1);
    assert_non_null(strstr(out, "4 were there"));
    /* the file's build time: the earlier builds' and this one's, each once;
     * the command: this fill's */
    assert_int_equal(run("table info fill.h5 --json", 1, out, sizeof out), 0);
    double w2 = cli_jnum(out, "build_wall_s");
    printf("  build wall time %.2f s + this fill's %.1f s -> %.2f s\n", w1, ws, w2);
    assert_true(w1 > 1.0 && fabs(w2 - (w1 + ws)) < 0.2);
    assert_non_null(strstr(out, "\"command\": \"stiction surface sweep --table fill.h5"));
    /* and the commands before it, oldest first: the build and the predict */
    const char *hist = strstr(out, "\"history\": [");
    assert_non_null(hist);
    const char *hb = strstr(hist, "\"stiction table build --deltas 0.5,1,2,4,8 "),
               *hp = strstr(hist, "\"stiction surface predict --table fill.h5 ");
    assert_true(hb && hp && hb < hp && hp < strchr(hist, ']'));
    const char *more = strstr(hp + 1, "\"stiction ");
    assert_true(!more || more > strchr(hp, ']')); /* those two only */
    assert_int_equal(run(SWEEP_RUN " --json", 1, a, sizeof a), 0);
    assert_int_equal(run(FILL_RUN " --json", 1, b, sizeof b), 0);
    assert_json(a);
    double sw = cli_jnum_at(a, "mu_s", 1), pr = cli_jnum(b, "mu_s");
    printf("  sweep Eco/Esu 2: mu_s %.10g, predict %.10g\n", sw, pr);
    assert_true(sw == pr);
#undef SWEEP_RUN
#undef FILL_RUN
}

/* --curves-only completes the normal grid of a table without computing a
 * point; its curves equal those of the full build. */
static void test_curves_only(void **state)
{
    (void)state;
    char out[4096];
    assert_int_equal(run("table build " BUILD_AXES " " BUILD_NUM " --out c.h5 --init", 1, out,
                         sizeof out), 0);
    assert_non_null(strstr(out, "normal grid: 3 curves, 0 done, 0 failed, 3 pending"));
    assert_int_equal(run("table build " BUILD_AXES " " BUILD_NUM " --out c.h5 --curves-only "
                         "--jobs 1", 1, out, sizeof out), 0);
    printf("  %s", strstr(out, "this run"));
    assert_non_null(strstr(out, "this run: 0 of 0 points of its share computed"));
    assert_non_null(strstr(out, "normal grid: 3 curves, 3 done, 0 failed, 0 pending; this run "
                                "computed 3"));
    assert_non_null(strstr(out, "0 done, 0 failed, 4 pending"));
    tbl_table *a = NULL, *b = NULL;
    wait_ref();
    assert_int_equal(tbl_read(P("c.h5"), &a), STC_OK);
    assert_int_equal(tbl_read(P("ref.h5"), &b), STC_OK);
    const double *w;
    int nw = tbl_normal_axis(a, 0, &w);
    for (int c = 0; c < tbl_curves(a); c++)
        for (int k = 0; k < nw; k++) {
            double v[4];
            tbl_curve_values(a, c, k, &v[0], &v[1]);
            tbl_curve_values(b, c, k, &v[2], &v[3]);
            assert_memory_equal(v, v + 2, 2 * sizeof *v);
        }
    printf("  its %d curves equal the full build's bit for bit\n", tbl_curves(a));
    tbl_destroy(&a);
    tbl_destroy(&b);
}

/* A build with refinement (--placements-max, --refine-err): a point whose
 * members disagree gets twice as many; info names the refinement and how
 * many points have how many placements, in text and JSON; a bad value is
 * refused by name. */
static void test_refined_build(void **state)
{
    (void)state;
    char out[8192];
    expect_refusal("table build --deltas 0.5 --t-over-R 0.01 --E-ratio 1 --placements 2 "
                   "--placements-max 3 --out bad.h5", 2, "placements-max = 3", "[4, 8]");
    expect_refusal("table build --deltas 0.5 --t-over-R 0.01 --E-ratio 1 --placements 8 "
                   "--placements-max 4 --out bad.h5", 2, "placements = 8",
                   "leaves no room to refine");
    expect_refusal("table build --deltas 0.5 --t-over-R 0.01 --E-ratio 1 --placements-max 2 "
                   "--refine-err 0.9 --placements 1 --out bad.h5", 2, "refine-err", NULL);
    assert_false(exists(P("bad.h5")));
    assert_int_equal(run("table build --deltas 0.5 --t-over-R 0.01 --E-ratio 1 " BUILD_NUM
                         " --placements-max 2 --refine-err 0.001 --normal-level -1 --quiet "
                         "--out refined.h5 --json", 1, out, sizeof out), 0);
    /* the build's summary as JSON: the one point computed by this run */
    assert_json(out);
    assert_non_null(strstr(out, "\"done\": 1,"));
    assert_non_null(strstr(out, "\"computed\": 1,"));
    assert_null(strstr(out, "wrote "));
    assert_int_equal(run("table info refined.h5", 1, out, sizeof out), 0);
    printf("%s", out);
    assert_non_null(strstr(out, "refined up to 2 where their standard error exceeds 0.1 %"));
    assert_non_null(strstr(out, "node placements of the done points: 2 (1 point)"));
    assert_non_null(strstr(out, "error estimates (one standard error) of the 1 point computed: "
                                "median "));
    assert_non_null(strstr(out, "mu_s against where inception is declared (d ln mu_s / d ln ux "
                                "there, docs/design.md §4.4): 0.1 or more at "));
    assert_non_null(strstr(out, " of 1 point"));
    /* the point keeps its members' d ln mu_s / d ln ux, and their mean */
    tbl_table *rt = NULL;
    assert_int_equal(tbl_read(P("refined.h5"), &rt), STC_OK);
    const tbl_point *rp = tbl_point_get(rt, 0);
    assert_int_equal(rp->ens.k, 2);
    double s0 = rp->ens.m[0].mu_s_ux_slope, s1 = rp->ens.m[1].mu_s_ux_slope;
    printf("  d ln mu_s / d ln ux: members %.4f, %.4f; point %.4f\n", s0, s1,
           rp->mu_s_ux_slope);
    assert_true(isfinite(s0) && isfinite(s1));
    assert_true(rp->mu_s_ux_slope == s0 / 2 + s1 / 2);
    /* and --points lists it (the column after ux at inception) */
    assert_int_equal(run("table info refined.h5 --points", 1, out, sizeof out), 0);
    char want[64];
    snprintf(want, sizeof want, ",%.6g,2,", rp->mu_s_ux_slope); /* slope, members */
    assert_non_null(strstr(out, "ux_slide_over_omega_c,mu_s_ux_slope,members,"));
    assert_non_null(strstr(out, want));
    tbl_destroy(&rt);
    assert_int_equal(run("table info refined.h5 --json", 1, out, sizeof out), 0);
    assert_json(out);
    assert_non_null(strstr(out, "\"mu_s_ux_slope\": {\n    \"points\": 1,"));
    const char *by = strstr(out, "\"done_points_by_placements\": {");
    assert_non_null(by);
    assert_non_null(strstr(by, "\"2\": 1"));
    assert_true(strstr(by, "\"2\": 1") < strchr(by, '}'));
    assert_non_null(strstr(out, "\"placements_max\": 2"));
}

/* Refinement added to a built table: the build onto it computes again only
 * the points whose members disagree (here: one member each, whose own error
 * is 2.6 % at 0.5 omega_c and 6.1 % at 2), each as a build with that
 * refinement from the start computes it, bit for bit; less refinement than
 * the file's is another build. */
static void test_refine_in_place(void **state)
{
    (void)state;
    char out[8192];
#define RIP "table build --t-over-R 0.01 --E-ratio 1 " BUILD_NUM \
            " --normal-level -1 --quiet --jobs 1 "
#define RIP_REFINE "--placements-max 2 --refine-err 0.04 "
    assert_int_equal(run(RIP "--deltas 0.5,2 --out rip.h5", 1, out, sizeof out), 0);
    tbl_table *t0 = NULL;
    assert_int_equal(tbl_read(P("rip.h5"), &t0), STC_OK);
    tbl_point kept = *tbl_point_get(t0, 0);
    assert_int_equal(kept.members, 1);
    tbl_destroy(&t0);
    /* what the refinement would compute again, before it runs */
    assert_int_equal(run("table info rip.h5 --placements-max 2 --refine-err 0.04 --json", 1,
                         out, sizeof out), 0);
    assert_json(out);
    const char *plan = strstr(out, "\"refine_plan\": {");
    assert_non_null(plan);
    assert_non_null(strstr(plan, "\"points\": 1,"));
    assert_non_null(strstr(plan, "\"keeping_no_members\": 0")); /* format 6 on keeps them */
    /* the same refinement sharded over two copies of the file, then merged */
    char cmd[3 * PATH_MAX];
    snprintf(cmd, sizeof cmd, "cp '%s' '%s' && cp '%s' '%s'", P("rip.h5"), P("r0.h5"),
             P("rip.h5"), P("r1.h5"));
    assert_int_equal(system(cmd), 0);
    assert_int_equal(run(RIP RIP_REFINE "--deltas 0.5,2 --shard 0/2 --out r0.h5", 1, out,
                         sizeof out), 0);
    assert_int_equal(run(RIP RIP_REFINE "--deltas 0.5,2 --shard 1/2 --out r1.h5", 1, out,
                         sizeof out), 0);
    assert_int_equal(run("table merge r0.h5 r1.h5 --out rm.h5", 1, out, sizeof out), 0);
    assert_int_equal(run(RIP RIP_REFINE "--deltas 0.5,2 --json --out rip.h5", 1, out,
                         sizeof out), 0);
    assert_json(out);
    assert_non_null(strstr(out, "\"reopened\": 1,"));
    assert_non_null(strstr(out, "\"computed\": 1,"));
    assert_non_null(strstr(out, "\"resumed\": 1,"));
    /* the reopened point's member from the file, not computed again */
    assert_non_null(strstr(out, "\"members_taken\": 1,"));
    /* the refined point against the same point built with the refinement
     * from the start (alone: the same computation as in a full build) */
    assert_int_equal(run(RIP RIP_REFINE "--deltas 2 --quiet=no --out fresh.h5", 2, out,
                         sizeof out), 0);
    assert_non_null(strstr(out, ", 2 placements (")); /* the progress line says how far */
    tbl_table *ta = NULL, *tb = NULL;
    assert_int_equal(tbl_read(P("rip.h5"), &ta), STC_OK);
    assert_int_equal(tbl_read(P("fresh.h5"), &tb), STC_OK);
    const tbl_point *r = tbl_point_get(ta, 1), *f = tbl_point_get(tb, 0);
    assert_int_equal(r->members, 2);
    assert_int_equal(f->members, 2);
    assert_true(r->mu_s == f->mu_s && r->mu_s_err == f->mu_s_err && r->P_Pc == f->P_Pc &&
                r->A_Ac == f->A_Ac && r->P_slide_Pc == f->P_slide_Pc &&
                r->Q_max_Pc == f->Q_max_Pc && r->mu_s_preload == f->mu_s_preload &&
                r->mu_s_min == f->mu_s_min && r->mu_s_max == f->mu_s_max &&
                r->ux_slide_wc == f->ux_slide_wc &&
                r->newton_iterations == f->newton_iterations &&
                r->factorizations == f->factorizations);
    assert_string_equal(r->reason, f->reason);
    /* the other point as the file had it */
    const tbl_point *k = tbl_point_get(ta, 0);
    assert_true(k->members == 1 && k->mu_s == kept.mu_s && k->mu_s_err == kept.mu_s_err &&
                k->cpu_s == kept.cpu_s);
    tbl_numerics nu;
    tbl_get_numerics(ta, &nu);
    assert_true(nu.placements_max == 2 && nu.refine_err == 0.04);
    const double mu = f->mu_s, err = f->mu_s_err; /* f is tb's */
    tbl_destroy(&tb);
    assert_int_equal(tbl_read(P("rm.h5"), &tb), STC_OK); /* the sharded refinement */
    assert_true(same_points(ta, tb) == 0.0);
    tbl_destroy(&ta);
    tbl_destroy(&tb);
    printf("  refined in place: the point at 2 omega_c computed again (%.6f +- %.6f), equal "
           "to the refined build's bit for bit; the one at 0.5 kept; two shards of the "
           "refinement merged: the same table\n", mu, err);
    /* less refinement than the file's, or none: another build */
    expect_refusal(RIP "--placements-max 2 --refine-err 0.5 --deltas 0.5,2 --out rip.h5", 2,
                   "another build", NULL);
    expect_refusal(RIP "--deltas 0.5,2 --out rip.h5", 2, "another build", NULL);
    expect_refusal("table info rip.h5 --placements-max 2 --refine-err 0.5", 2,
                   "refine-err = 0.5", "refines from 0.04 already");
    expect_refusal("table info rip.h5 --placements-max 4 --points", 2,
                   "--placements-max conflicts with --points", NULL);
    expect_refusal("table info rip.h5 --refine-err 0.01", 2,
                   "--refine-err needs --placements-max", NULL);
    assert_int_equal(run("table info rip.h5 --placements-max 2 --refine-err 0.04", 1, out,
                         sizeof out), 0);
    assert_non_null(strstr(out, "0 of the 2 done points refined"));
#undef RIP_REFINE
#undef RIP
}

/* A table with failed points: the prediction runs over the done ones and
 * warns, naming how many failed and where the reasons are. */
static void test_failed_points_warned(void **state)
{
    (void)state;
    tbl_family f;
    tbl_numerics num;
    tbl_family_default(&f);
    tbl_numerics_default(&num);
    const double w[] = {0.5, 1, 2, 4, 8, 16, 32}, tr[] = {0.01, 0.05}, er[] = {1, 2};
    tbl_table *t = NULL;
    assert_int_equal(tbl_create(&f, &num, w, 7, tr, 2, er, 2, &t), STC_OK);
    for (int i = 0; i < tbl_points(t); i++) {
        double wi, tR, E;
        tbl_coords(t, i, &wi, &tR, &E);
        tbl_point p;
        memset(&p, 0, sizeof p);
        if (i == 3) {
            p.state = TBL_FAILED;
            snprintf(p.reason, sizeof p.reason, "made to fail");
        } else {
            p.state = TBL_DONE;
            p.P_Pc = p.P_slide_Pc = pow(wi, 1.5); /* a power law stands for the response */
            p.A_Ac = wi;
            p.mu_s = p.mu_s_preload = p.mu_s_min = p.mu_s_max = 0.5;
            p.mu_s_err = 0.01;
            p.Q_max_Pc = 0.5 * p.P_Pc;
            p.members = 1;
        }
        assert_int_equal(tbl_point_set(t, i, &p), STC_OK);
    }
    assert_int_equal(tbl_write(t, P("failed.h5")), STC_OK);
    tbl_destroy(&t);
    expect_refusal("surface predict --table failed.h5 --E-ratio 2 --t-mm 0.0014 "
                   "--summit-density 2000 --summit-radius 0.07 --sigma-s 1e-6 --pressures 0.1",
                   0, "warning: 1 of the table's points failed", "table info failed.h5");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_killed_build_resumes),
        cmocka_unit_test(test_killed_point_keeps_members),
        cmocka_unit_test(test_shards_merge),
        cmocka_unit_test(test_refine_in_place),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_query_t_mm),
        cmocka_unit_test(test_fill),
        cmocka_unit_test(test_curves_only),
        cmocka_unit_test(test_failed_points_warned),
        cmocka_unit_test(test_refined_build),
    };
    return cmocka_run_group_tests_name("cli_table", tests, setup, teardown);
}
