/* Distributed table builds (asperity/table_mpi.c): `mpirun -n N stiction
 * table build` gives the serial build's table, every number bit for bit;
 * --shard combines with it; resuming works as in the serial path, a
 * refinement in place takes the file's members on every rank; only rank
 * 0 writes; a plain run never initialises MPI; a failure on any rank ends
 * every rank with the message, none hangs.
 *
 * The table is a coarse, cheap one (6 points of 3-8 CPU s each, elastic to
 * first yield; its normal grid on axisymmetric level 0).  The
 * serial reference is built with --jobs 1, as two shards side by side: two
 * points computed at once in one process have differed between runs in
 * their last digits (μs by 3e-13 relative), while a point computed alone is
 * reproducible; the farm computes one point at a time per process, so its
 * table must equal the one-thread serial one exactly.
 *
 * Runs mpirun from PATH (Open MPI, tools/deps.sh); allows running as root
 * (CI) and oversubscribing the cores. */
#include <errno.h>
#include <limits.h>
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

#include "cli_util.h"
#include <mpi.h>

#include "stiction/table.h"
#include "stiction/table_mpi.h"
#include "tmp_util.h"

#define AXES "--deltas 0.5,0.7,1 --t-over-R 0.01 --E-ratio 1,2"
#define FAMILY "--contact slip --elements-per-contact 3 --placements 1 --normal-level 0 --quiet"
#define MPIRUN "LSAN_OPTIONS=\"$STICTION_TEST_MPI_LSAN\" timeout 300 mpirun --oversubscribe"
enum { POINTS = 6, OUT_MAX = 1 << 16 };

static char cli[PATH_MAX], dir[PATH_MAX];
static char out[OUT_MAX]; /* the last command's stdout and stderr */

/* dir/name (one of 8 rotating buffers, so that several fit in a call). */
static const char *in_dir(const char *name)
{
    static char ring[8][PATH_MAX + 64];
    static int k;
    char *p = ring[k++ % 8];
    snprintf(p, sizeof ring[0], "%s/%s", dir, name);
    return p;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Run a shell command built from fmt, stdout and stderr into `out`; its
 * exit status (124: timed out). */
static int run(const char *fmt, ...)
{
    char cmd[4 * PATH_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    strncat(cmd, " 2>&1", sizeof cmd - strlen(cmd) - 1);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t got = fread(out, 1, sizeof out - 1, p);
    out[got] = '\0';
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

static void expect_in_output(const char *what)
{
    if (!strstr(out, what)) fail_msg("expected '%s' in:\n%s", what, out);
}

static void copy_file(const char *from, const char *to)
{
    FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
    assert_non_null(a);
    assert_non_null(b);
    char buf[1 << 14];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, a)) > 0) assert_int_equal(fwrite(buf, 1, n, b), n);
    fclose(a);
    assert_int_equal(fclose(b), 0);
}

static tbl_table *read_table(const char *path)
{
    tbl_table *t = NULL;
    if (tbl_read(path, &t) != STC_OK) fail_msg("%s: %s", path, stc_errmsg());
    return t;
}

/* Done point i of two tables: every number equal bit for bit (wall and CPU
 * times aside), its kept members' too. */
static void compare_point(const tbl_point *pa, const tbl_point *pb, int i)
{
    static const size_t dbl[] = {
        offsetof(tbl_point, P_Pc),       offsetof(tbl_point, A_Ac),
        offsetof(tbl_point, P_slide_Pc), offsetof(tbl_point, Q_max_Pc),
        offsetof(tbl_point, mu_s),       offsetof(tbl_point, mu_s_err),
        offsetof(tbl_point, mu_s_preload), offsetof(tbl_point, mu_s_min),
        offsetof(tbl_point, mu_s_max),   offsetof(tbl_point, ux_slide_wc),
        offsetof(tbl_point, mu_s_ux_slope)};
    static const size_t ints[] = {offsetof(tbl_point, members),
                                  offsetof(tbl_point, newton_iterations),
                                  offsetof(tbl_point, factorizations)};
    assert_int_equal(pa->state, TBL_DONE);
    assert_int_equal(pb->state, TBL_DONE);
    for (size_t k = 0; k < sizeof dbl / sizeof *dbl; k++)
        if (memcmp((const char *)pa + dbl[k], (const char *)pb + dbl[k], sizeof(double)))
            fail_msg("point %d: the double at offset %zu differs: %.17g vs %.17g", i, dbl[k],
                     *(const double *)((const char *)pa + dbl[k]),
                     *(const double *)((const char *)pb + dbl[k]));
    for (size_t k = 0; k < sizeof ints / sizeof *ints; k++)
        assert_int_equal(*(const int *)((const char *)pa + ints[k]),
                         *(const int *)((const char *)pb + ints[k]));
    assert_string_equal(pa->reason, pb->reason);
    assert_int_equal(pa->ens.k, pb->ens.k);
    for (int j = 0; j < pa->ens.k; j++)
        if (memcmp(&pa->ens.m[j].mu_s, &pb->ens.m[j].mu_s, sizeof(double)) ||
            memcmp(&pa->ens.m[j].Q_max, &pb->ens.m[j].Q_max, sizeof(double)))
            fail_msg("point %d: member %d differs: mu_s %.17g vs %.17g", i, j,
                     pa->ens.m[j].mu_s, pb->ens.m[j].mu_s);
}

/* Every number of every point of shard/shards equal bit for bit (wall and
 * CPU times aside), the other points of b pending; the same axes, family
 * and numerics.  Returns the points compared. */
static int compare_tables(const tbl_table *a, const tbl_table *b, int shard, int shards)
{
    assert_true(tbl_same_build(a, b));
    for (int k = 0; k < 3; k++) {
        const double *va, *vb;
        int n = tbl_axis(a, k, &va);
        assert_int_equal(tbl_axis(b, k, &vb), n);
        assert_memory_equal(va, vb, (size_t)n * sizeof *va);
    }
    int compared = 0;
    for (int i = 0; i < tbl_points(a); i++) {
        const tbl_point *pa = tbl_point_get(a, i), *pb = tbl_point_get(b, i);
        if (i % shards != shard) {
            assert_int_equal(pb->state, TBL_PENDING);
            continue;
        }
        compare_point(pa, pb, i);
        compared++;
    }
    /* the normal curves of the shard (handed out like the points), bit for bit */
    const double *w;
    int nw = tbl_normal_axis(a, 0, &w);
    assert_int_equal(tbl_curves(a), tbl_curves(b));
    for (int c = 0; c < tbl_curves(a); c++) {
        if (c % shards != shard) {
            assert_int_equal(tbl_curve_get(b, c)->state, TBL_PENDING);
            continue;
        }
        assert_int_equal(tbl_curve_get(a, c)->state, TBL_DONE);
        assert_int_equal(tbl_curve_get(b, c)->state, TBL_DONE);
        for (int k = 0; k < nw; k++) {
            double v[4];
            tbl_curve_values(a, c, k, &v[0], &v[1]);
            tbl_curve_values(b, c, k, &v[2], &v[3]);
            if (memcmp(&v[0], &v[2], 2 * sizeof *v))
                fail_msg("normal curve %d at delta node %d differs: P %.17g vs %.17g, A %.17g "
                         "vs %.17g", c, k, v[0], v[2], v[1], v[3]);
        }
    }
    return compared;
}

/* ---- tests ------------------------------------------------------------------- */

/* The serial reference: two plain runs side by side, one shard and one
 * point at a time each, joined.  Their MPI_Init would fail (an MPI
 * component that does not exist): so they do not initialise MPI. */
static void test_plain_build(void **state)
{
    (void)state;
    int rc = run("export OMPI_MCA_pml=no-such-component; "
                 "'%s' table build " AXES " " FAMILY " --jobs 1 --shard 0/2 --out '%s' & a=$!; "
                 "'%s' table build " AXES " " FAMILY " --jobs 1 --shard 1/2 --out '%s'; b=$?; "
                 "wait $a && [ $b = 0 ] && '%s' table merge '%s' '%s' --out '%s'",
                 cli, in_dir("serial0.h5"), cli, in_dir("serial1.h5"), cli, in_dir("serial0.h5"),
                 in_dir("serial1.h5"), in_dir("serial.h5"));
    if (rc != 0) fail_msg("plain builds: exit %d:\n%s", rc, out);
    expect_in_output("this run: 3 of 3 points of its share computed");
    assert_null(strstr(out, "MPI"));
    tbl_table *t = read_table(in_dir("serial.h5"));
    int done;
    tbl_count(t, &done, NULL, NULL);
    assert_int_equal(done, POINTS);
    tbl_destroy(&t);
    printf("plain builds (their MPI_Init made to fail): 2 shards of 3 points done, merged\n");
}

/* tbl_build in this (plain) process: resumes every point, leaves MPI alone. */
static void test_in_process(void **state)
{
    (void)state;
    copy_file(in_dir("serial.h5"), in_dir("resume.h5"));
    tbl_table *ref = read_table(in_dir("serial.h5")), *t = NULL;
    tbl_family f;
    tbl_numerics num;
    tbl_get_family(ref, &f);
    tbl_get_numerics(ref, &num);
    const double *ax[3];
    int n[3];
    for (int k = 0; k < 3; k++) n[k] = tbl_axis(ref, k, &ax[k]);
    assert_int_equal(tbl_create(&f, &num, ax[0], n[0], ax[1], n[1], ax[2], n[2], &t), STC_OK);
    tbl_build_summary sum;
    if (tbl_build(t, in_dir("resume.h5"), NULL, &sum) != STC_OK) fail_msg("%s", stc_errmsg());
    assert_int_equal(sum.computed, 0);
    assert_int_equal(sum.resumed, POINTS);
    assert_int_equal(compare_tables(ref, t, 0, 1), POINTS);
    int init = 1, fin = 1, rank = -1, size = -1;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    assert_int_equal(init, 0);
    assert_int_equal(fin, 0);
    tbl_build_rank(&rank, &size);
    assert_int_equal(rank, 0);
    assert_int_equal(size, 1);
    tbl_destroy(&t);
    tbl_destroy(&ref);
    printf("tbl_build in a plain process: 6 points resumed, MPI not initialised, rank 0 of 1\n");
}

/* The farm on a shard (rank 2 told another output file: it must write
 * nothing), then the rest of the table on 2 ranks, resuming the shard. */
static void test_mpi_matches_serial(void **state)
{
    (void)state;
    char mpi[PATH_MAX + 64];
    snprintf(mpi, sizeof mpi, "%s", in_dir("mpi.h5"));
    int rc = run(MPIRUN " -n 2 '%s' table build " AXES " " FAMILY " --shard 0/2 --out '%s' : "
                 "-n 1 '%s' table build " AXES " " FAMILY " --shard 0/2 --out '%s'",
                 cli, mpi, cli, in_dir("rank2.h5"));
    if (rc != 0) fail_msg("mpirun -n 3 --shard 0/2: exit %d:\n%s", rc, out);
    expect_in_output("this run (on 3 MPI ranks): 3 of 3 points of its share computed");
    assert_false(exists(in_dir("rank2.h5")));
    assert_false(exists(in_dir("rank2.h5.journal")));
    assert_false(exists(in_dir("mpi.h5.journal")));
    tbl_table *ref = read_table(in_dir("serial.h5")), *t = read_table(mpi);
    assert_int_equal(compare_tables(ref, t, 0, 2), 3);
    tbl_destroy(&t);
    printf("mpirun -n 3 --shard 0/2: its 3 points equal the serial build's bit for bit, the "
           "others pending; rank 2 wrote no file\n");

    rc = run(MPIRUN " -n 2 '%s' table build " AXES " " FAMILY " --out '%s'", cli, mpi);
    if (rc != 0) fail_msg("mpirun -n 2: exit %d:\n%s", rc, out);
    expect_in_output("this run (on 2 MPI ranks): 3 of 6 points of its share computed, "
                     "3 taken from an earlier run");
    assert_false(exists(in_dir("mpi.h5.journal")));
    t = read_table(mpi);
    assert_int_equal(compare_tables(ref, t, 0, 1), POINTS);
    tbl_destroy(&t);
    tbl_destroy(&ref);
    printf("mpirun -n 2 resuming it: 3 points taken, 3 computed; all 6 equal the serial "
           "build's bit for bit\n");
}

/* A refinement in place under the farm (one placement to two, shard 0/2:
 * its three points): every rank's point goes on from the member the file
 * keeps (handed out with the point; the new member sent back to rank 0's
 * journal), and the refined points equal the serial refinement's bit for
 * bit. */
#define REFINE "--placements-max 2 --refine-err 0.001 --shard 0/2"
static void test_mpi_refines_from_members(void **state)
{
    (void)state;
    copy_file(in_dir("mpi.h5"), in_dir("refine-serial.h5"));
    copy_file(in_dir("mpi.h5"), in_dir("refine-mpi.h5"));
    int rc = run("'%s' table build " AXES " " FAMILY " " REFINE " --jobs 1 --out '%s'", cli,
                 in_dir("refine-serial.h5"));
    if (rc != 0) fail_msg("serial refinement: exit %d:\n%s", rc, out);
    expect_in_output("placement members taken from an earlier run (the journal, or the file a "
                     "refinement goes on from): 3");
    rc = run(MPIRUN " -n 2 '%s' table build " AXES " " FAMILY " " REFINE " --out '%s'", cli,
             in_dir("refine-mpi.h5"));
    if (rc != 0) fail_msg("mpirun -n 2 refinement: exit %d:\n%s", rc, out);
    expect_in_output("placement members taken from an earlier run (the journal, or the file a "
                     "refinement goes on from): 3");
    assert_false(exists(in_dir("refine-mpi.h5.journal")));
    tbl_table *a = read_table(in_dir("refine-serial.h5")), *b = read_table(in_dir("refine-mpi.h5"));
    int refined = 0;
    for (int i = 0; i < tbl_points(a); i += 2) {
        assert_int_equal(tbl_point_get(b, i)->members, 2);
        compare_point(tbl_point_get(a, i), tbl_point_get(b, i), i);
        refined++;
    }
    assert_int_equal(refined, 3);
    tbl_destroy(&a);
    tbl_destroy(&b);
    printf("mpirun -n 2 refining shard 0/2 in place: 3 members taken from the file on both "
           "ranks, the 3 refined points equal the serial refinement's bit for bit\n");
}

/* Failures end every rank (timeout 300 would report a hang as 124) with
 * the message, on rank 0's stderr. */
static void test_mpi_failures(void **state)
{
    (void)state;
    /* rank 0 refuses before the farm: a table of another build at the path */
    struct stat before, after;
    assert_int_equal(stat(in_dir("serial.h5"), &before), 0);
    int rc = run(MPIRUN " -n 2 '%s' table build --deltas 0.5,1 --t-over-R 0.01 --E-ratio 1 "
                 FAMILY " --out '%s'", cli, in_dir("serial.h5"));
    assert_int_not_equal(rc, 0);
    assert_int_not_equal(rc, 124);
    expect_in_output("a table of another build is there");
    assert_int_equal(stat(in_dir("serial.h5"), &after), 0);
    assert_true(before.st_mtime == after.st_mtime && before.st_size == after.st_size);
    printf("rank 0 refusing a table of another build: every rank ends (exit %d), file kept\n",
           rc);

    /* a rank started with other axes (rank 0 has every point already, so
     * it computes none while it waits for the hello) */
    copy_file(in_dir("serial.h5"), in_dir("other.h5"));
    rc = run(MPIRUN " -n 1 '%s' table build " AXES " " FAMILY " --out '%s' : -n 1 '%s' table "
             "build --deltas 0.5,1 --t-over-R 0.01 --E-ratio 1,2 " FAMILY " --out '%s'", cli,
             in_dir("other.h5"), cli, in_dir("other.h5"));
    assert_int_not_equal(rc, 0);
    assert_int_not_equal(rc, 124);
    expect_in_output("rank 1: another build");
    printf("a rank with other axes: refused by rank 0 with its rank named (exit %d)\n", rc);

    /* points that cannot be computed (beyond the small-strain limit):
     * rank 0's thread takes the first, good point, the other ranks
     * (usually) the bad ones; the build ends after the good one.  Without
     * a normal grid: rank 0 would refuse its curves (loaded to the same
     * delta) before the farm, which the first case covers */
    rc = run(MPIRUN " -n 3 '%s' table build --deltas 0.5,3e5,4e5 --t-over-R 0.01 --E-ratio 1 "
             FAMILY " --normal-level -1 --out '%s'", cli, in_dir("bad.h5"));
    assert_int_not_equal(rc, 0);
    assert_int_not_equal(rc, 124);
    expect_in_output("beyond the small-strain limit");
    const char *who = strstr(out, ": rank ");
    assert_non_null(who);
    assert_false(exists(in_dir("bad.h5")));
    printf("points failing on the ranks that got them: the build fails with the message of "
           "%.6s (exit %d)\n", who + 2, rc);
}

/* mpirun -n 1 is the serial path. */
static void test_mpirun_one(void **state)
{
    (void)state;
    copy_file(in_dir("serial.h5"), in_dir("one.h5"));
    int rc = run(MPIRUN " -n 1 '%s' table build " AXES " " FAMILY " --out '%s'", cli,
                 in_dir("one.h5"));
    if (rc != 0) fail_msg("mpirun -n 1: exit %d:\n%s", rc, out);
    expect_in_output("this run: 0 of 6 points of its share computed, 6 taken");
    printf("mpirun -n 1: the serial path\n");
}

/* ---- set-up ---------------------------------------------------------------------- */

static int remove_dir(const char *path)
{
    char cmd[PATH_MAX + 32];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", path);
    return system(cmd) == 0 ? 0 : -1;
}

static int setup(void **state)
{
    (void)state;
    if (cli_locate(cli, sizeof cli) != 0) return -1;
    if (access(cli, X_OK) != 0) {
        fprintf(stderr, "test_table_mpi: no executable CLI at '%s'\n", cli);
        return -1;
    }
    snprintf(dir, sizeof dir, "%s/stiction-mpi-XXXXXX", test_tmpdir());
    if (!mkdtemp(dir)) {
        fprintf(stderr, "test_table_mpi: mkdtemp: %s\n", strerror(errno));
        return -1;
    }
    /* CI runs as root; Open MPI refuses that unless told */
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    /* SANITIZE=1: Open MPI's own allocations outlive MPI_Finalize, which
     * LeakSanitizer would report for every rank.  Under mpirun (MPIRUN)
     * the leaks that Open MPI's code allocated are suppressed; that needs
     * whole stacks (its libraries have no frame pointers).  The check stays
     * on for everything else */
    FILE *supp = fopen(in_dir("lsan.supp"), "w");
    if (!supp) return -1;
    fputs("leak:libmpi.so\nleak:libopen-pal.so\nleak:libopen-rte.so\nleak:libpmix.so\n"
          "leak:libhwloc.so\nleak:libevent\n", supp);
    if (fclose(supp) != 0) return -1;
    char lsan[PATH_MAX + 128];
    snprintf(lsan, sizeof lsan, "suppressions=%s:print_suppressions=0:fast_unwind_on_malloc=0",
             in_dir("lsan.supp"));
    setenv("STICTION_TEST_MPI_LSAN", lsan, 1);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    return dir[0] ? remove_dir(dir) : 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plain_build),
        cmocka_unit_test(test_in_process),
        cmocka_unit_test(test_mpi_matches_serial),
        cmocka_unit_test(test_mpi_refines_from_members),
        cmocka_unit_test(test_mpi_failures),
        cmocka_unit_test(test_mpirun_one),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
