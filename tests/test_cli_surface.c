/* `stiction surface synth|stats|predict` as a user meets them: every
 * invalid input exits non-zero with a message naming the key, the value and
 * the valid range, and leaves no output file (nor temporary) behind; a small
 * synth → stats → predict round trip prints JSON whose numbers agree with
 * each other.
 *
 * The binary is $STICTION_CLI if set, else ../bin/stiction relative to this
 * test program (the Makefile's layout for any O=).  Fixtures (text grids,
 * HDF5 files, INI files) are written into a scratch directory; every output
 * a run may produce is named "out*" there, so "nothing left behind" is "no
 * out* entry in the directory". */
#include <dirent.h>
#include <limits.h>
#include <math.h>
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
#include <hdf5.h>
#include "tmp_util.h"

static char cli[PATH_MAX];
static char dir[256]; /* scratch directory */
static char buf[1 << 17];

/* ------------------------------------------------------------ helpers */

/* dir/name (cli_util.h's rotating buffers). */
static const char *P(const char *name) { return cli_path(dir, name); }

static void write_file(const char *name, const char *text)
{
    FILE *f = fopen(P(name), "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Run "cli ARGS" in the scratch directory; `which` = 1 captures stdout, 2
 * stderr.  Returns the exit status (128 + signal if killed). */
static int run(const char *args, int which, char *out, size_t n)
{
    char cmd[PATH_MAX + 2048];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s", dir, cli, args);
    return cli_capture(cmd, which, out, n);
}

/* No entry named out* (outputs and their temporaries) in the scratch dir. */
static void assert_no_outputs(const char *args)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    struct dirent *e;
    while ((e = readdir(d)))
        if (strncmp(e->d_name, "out", 3) == 0) {
            closedir(d);
            fail_msg("'%s' left '%s' behind", args, e->d_name);
        }
    closedir(d);
}

static void rm_outputs(void)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'/out*", dir);
    assert_int_equal(system(cmd), 0);
}

/* Expected failures are queued and run a batch at a time, concurrently:
 * each run is mostly process start-up (shared libraries), so this keeps the
 * program fast on a loaded machine.  A batch's runs only read fixtures (or go
 * one at a time, run_batch); the "nothing left behind" check follows each
 * batch. */
#define BATCH 6
typedef struct {
    char args[640];
    const char *needle[3];
} fail_case;
static fail_case queue[BATCH];
static int nqueue;

/* Read a run's stderr to the end and close it; its wait status in *st. */
static void reap(FILE *p, char *err, size_t n, int *st)
{
    size_t got = fread(err, 1, n - 1, p);
    err[got] = '\0';
    *st = pclose(p);
}

static void run_batch(void)
{
    FILE *p[BATCH];
    static char err[BATCH][8192];
    int n = nqueue, bad = -1, why = 0; /* first failing case; why: -1 exit status, -2
                                        * sanitizer report, i >= 0 needle i missing */
    nqueue = 0; /* the queue is free again even when a case below fails */
    /* runs that name the same output directory go one at a time: a run
     * creates it before it reads its inputs and removes it when it fails,
     * under another run's writability check */
    int serial = 0, st[BATCH];
    for (int k = 0; k < n; k++) serial |= strstr(queue[k].args, "--out out-dir ") != NULL;
    for (int k = 0; k < n; k++) {
        char cmd[2 * PATH_MAX + sizeof queue[0].args];
        snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s 2>&1 >/dev/null", dir, cli, queue[k].args);
        p[k] = popen(cmd, "r");
        assert_non_null(p[k]);
        if (serial) reap(p[k], err[k], sizeof err[k], &st[k]);
    }
    /* every run of the batch is reaped and printed; then the first failure */
    for (int k = 0; k < n; k++) {
        if (!serial) reap(p[k], err[k], sizeof err[k], &st[k]);
        int rc = WIFEXITED(st[k]) ? WEXITSTATUS(st[k]) : 128 + WTERMSIG(st[k]), w = 0;
        const fail_case *c = &queue[k];
        printf("  %-64.64s -> %d: %s", c->args, rc, err[k]);
        if (rc != 1 && rc != 2) w = -1;
        else if (strstr(err[k], "Sanitizer") || strstr(err[k], "runtime error"))
            w = -2; /* SANITIZE=1 builds */
        for (int i = 0; i < 3 && !w; i++)
            if (c->needle[i] && !strstr(err[k], c->needle[i])) w = i + 1;
        if (w && bad < 0) bad = k, why = w;
    }
    if (bad >= 0) {
        const fail_case *c = &queue[bad];
        if (why == -1) fail_msg("'%s' exited other than 1 or 2", c->args);
        if (why == -2) fail_msg("'%s': sanitizer report", c->args);
        fail_msg("'%s': message '%s' lacks '%s'", c->args, err[bad], c->needle[why - 1]);
    }
    assert_no_outputs(n ? queue[n - 1].args : "");
}

/* Expect a failure (exit 1 or 2, not a crash) whose stderr holds every
 * non-NULL needle (string literals), and no output left behind. */
static void expect_fail(const char *args, const char *n1, const char *n2, const char *n3)
{
    fail_case *c = &queue[nqueue++];
    snprintf(c->args, sizeof c->args, "%s", args);
    c->needle[0] = n1;
    c->needle[1] = n2;
    c->needle[2] = n3;
    if (nqueue == BATCH) run_batch();
}

/* Run what is queued (call before anything that reads or writes files). */
static void expect_done(void) { run_batch(); }


/* Lines of a file, and entries (not . or ..) of a directory. */
static int file_lines(const char *path)
{
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    int lines = 0, c;
    while ((c = fgetc(f)) != EOF) lines += c == '\n';
    fclose(f);
    return lines;
}

static int dir_entries(const char *path)
{
    DIR *d = opendir(path);
    assert_non_null(d);
    struct dirent *e;
    int entries = 0;
    while ((e = readdir(d)))
        if (e->d_name[0] != '.') entries++;
    closedir(d);
    return entries;
}

/* Number of the k-th occurrence (0-based) of "key": in text (NaN for null). */
static double jnum_k(const char *text, const char *key, int k)
{
    char pat[96];
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = text;
    for (int i = 0; i <= k; i++) {
        p = strstr(p, pat);
        if (!p) fail_msg("key '%s' (occurrence %d) missing", key, k);
        p += strlen(pat);
    }
    if (!strncmp(p, "null", 4)) return NAN;
    char *end;
    double v = strtod(p, &end);
    if (end == p) fail_msg("key '%s' is not a number", key);
    return v;
}
static double jnum(const char *text, const char *key) { return jnum_k(text, key, 0); }

static int count_str(const char *text, const char *needle)
{
    int n = 0;
    for (const char *p = text; (p = strstr(p, needle)); p += strlen(needle)) n++;
    return n;
}

/* ------------------------------------------------------------ fixtures */

static herr_t h5_dataset(hid_t f, const char *name, int rank, const hsize_t *dims, hid_t type,
                         const void *data)
{
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t d = H5Dcreate2(f, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t r = H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(d);
    H5Sclose(sp);
    return r;
}

/* HDF5 files a user might hand us by mistake. */
static void make_h5_fixtures(void)
{
    double z[16 * 16], zn[4 * 4] = {0};
    for (int k = 0; k < 16 * 16; k++) z[k] = sin(0.7 * k) + 0.3 * cos(1.3 * k * k);
    zn[5] = NAN;
    hsize_t d2[2] = {16, 16}, d1[1] = {256}, d3[3] = {4, 8, 8}, d4[2] = {4, 4};
    /* a measurement file: dataset /scan/z, no /height */
    hid_t f = H5Fcreate(P("meas.h5"), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t g = H5Gcreate2(f, "scan", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Gclose(g);
    assert_true(h5_dataset(f, "/scan/z", 2, d2, H5T_NATIVE_DOUBLE, z) >= 0);
    assert_true(h5_dataset(f, "/profile", 1, d1, H5T_NATIVE_DOUBLE, z) >= 0);
    assert_true(h5_dataset(f, "/stack", 3, d3, H5T_NATIVE_DOUBLE, z) >= 0);
    assert_true(h5_dataset(f, "/holes", 2, d4, H5T_NATIVE_DOUBLE, zn) >= 0);
    hid_t st = H5Tcopy(H5T_C_S1);
    H5Tset_size(st, 4);
    char text[16 * 16 * 4];
    memset(text, 'a', sizeof text);
    assert_true(h5_dataset(f, "/names", 2, d2, st, text) >= 0);
    H5Tclose(st);
    H5Fclose(f);
    /* a stiction-looking file whose /height is 1-D, and one with NaN heights */
    f = H5Fcreate(P("rank1.h5"), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(h5_dataset(f, "/height", 1, d1, H5T_NATIVE_DOUBLE, z) >= 0);
    H5Fclose(f);
    f = H5Fcreate(P("nanh.h5"), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(h5_dataset(f, "/height", 2, d4, H5T_NATIVE_DOUBLE, zn) >= 0);
    hid_t sp = H5Screate(H5S_SCALAR);
    double one = 1.0;
    hid_t ds = H5Dopen2(f, "/height", H5P_DEFAULT);
    const char *attrs[] = {"lx_mm", "ly_mm"};
    for (int k = 0; k < 2; k++) {
        hid_t a = H5Acreate2(ds, attrs[k], H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
        H5Awrite(a, H5T_NATIVE_DOUBLE, &one);
        H5Aclose(a);
    }
    H5Dclose(ds);
    H5Sclose(sp);
    H5Fclose(f);
    /* array attributes where the format has scalars: lx_mm with 4 values (an
     * unusable file), and a 3-element string "origin" next to good lengths
     * (optional metadata: ignored).  Either used to overrun the one value
     * the reader reads into. */
    const double four[4] = {1, 2, 3, 4};
    hsize_t d8[2] = {8, 8}, na = 4, ns = 3;
    for (int k = 0; k < 2; k++) {
        f = H5Fcreate(P(k ? "arrmeta.h5" : "arrlx.h5"), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
        assert_true(h5_dataset(f, "/height", 2, d8, H5T_NATIVE_DOUBLE, z) >= 0);
        ds = H5Dopen2(f, "/height", H5P_DEFAULT);
        hid_t s1 = H5Screate(H5S_SCALAR), s4 = H5Screate_simple(1, &na, NULL);
        hid_t a = H5Acreate2(ds, "lx_mm", H5T_NATIVE_DOUBLE, k ? s1 : s4, H5P_DEFAULT, H5P_DEFAULT);
        H5Awrite(a, H5T_NATIVE_DOUBLE, k ? &one : four);
        H5Aclose(a);
        a = H5Acreate2(ds, "ly_mm", H5T_NATIVE_DOUBLE, s1, H5P_DEFAULT, H5P_DEFAULT);
        H5Awrite(a, H5T_NATIVE_DOUBLE, &one);
        H5Aclose(a);
        if (k) {
            hid_t s3 = H5Screate_simple(1, &ns, NULL), t = H5Tcopy(H5T_C_S1);
            H5Tset_size(t, 8);
            a = H5Acreate2(ds, "origin", t, s3, H5P_DEFAULT, H5P_DEFAULT);
            H5Awrite(a, t, "synth\0\0\0import\0\0none\0\0\0\0");
            H5Aclose(a);
            H5Tclose(t);
            H5Sclose(s3);
        }
        H5Sclose(s1);
        H5Sclose(s4);
        H5Dclose(ds);
        H5Fclose(f);
    }
}

/* Text grids, good and bad. */
static void make_text_fixtures(void)
{
    write_file("ragged.txt", "1 2 3\n4 5 6\n7 8\n");
    write_file("word.txt", "1 2 3\n4 x5 6\n7 8 9\n");
    write_file("empty.txt", "");
    write_file("comments.txt", "# a header\n\n   \n# nothing else\n");
    write_file("small.txt", "1 2\n3 4\n");
    write_file("nan.txt", "1 2 3\n4 nan 6\n7 8 9\n");
    write_file("overflow.txt", "1 2 3\n4 1e999 6\n7 8 9\n");
    write_file("plane.txt", "1 2 3 4\n2 3 4 5\n3 4 5 6\n4 5 6 7\n");
    write_file("huge.txt", "1e300 -1e300 1e300\n-1e300 1e300 -1e300\n1e300 5e299 -1e300\n");
    write_file("notgrid.h5", "this is not an HDF5 file\n");
    assert_int_equal(mkdir(P("adir"), 0700), 0); /* a directory where a file belongs */
    /* a measured-looking grid: 32 x 32 bumps on a tilt of 0.01 (x) and -0.02 (y)
     * per pixel of 0.01 mm, heights in µm */
    FILE *f = fopen(P("grid.txt"), "w");
    assert_non_null(f);
    fprintf(f, "# profilometer export, heights in um\n");
    for (int j = 0; j < 32; j++) {
        for (int i = 0; i < 32; i++)
            fprintf(f, "%s%.6f", i ? "\t" : "",
                    10.0 * i * 0.01 - 20.0 * j * 0.01 +
                        0.5 * sin(0.9 * i + 0.4 * j) * cos(0.5 * i - 1.1 * j) +
                        0.2 * sin(2.1 * i * j));
        fprintf(f, "\r\n"); /* Windows line ends are common in exports */
    }
    fclose(f);
}

#define MAP_ARGS                                                                           \
    "--size 128 --spectrum self-affine --hurst 0.8 --rms 1e-3 --cutoff-wavelength 0.04 --seed 3"

static int setup(void **state)
{
    (void)state;
    if (cli_locate(cli, sizeof cli) != 0) return -1;
    char *real = realpath(cli, NULL);
    if (!real || access(real, X_OK) != 0) {
        fprintf(stderr, "test_cli_surface: no executable CLI at '%s' (build it, or set "
                        "STICTION_CLI)\n", cli);
        free(real);
        return -1;
    }
    snprintf(cli, sizeof cli, "%s", real);
    free(real);
    snprintf(dir, sizeof dir, "%s/stiction-test-cli-surface-%ld", test_tmpdir(), (long)getpid());
    if (mkdir(dir, 0700) != 0) return -1;
    /* one thread per run: the runs are tiny, and the 2 cores are shared */
    setenv("OMP_NUM_THREADS", "1", 1);
    setenv("OPENBLAS_NUM_THREADS", "1", 1);
    make_text_fixtures();
    make_h5_fixtures();
    /* the good map every stats/predict test reads: 128² self-affine, fixed
     * seed, roughness down to 5 pixels (~110 summits) */
    if (run("surface synth " MAP_ARGS " --no-png --out map.h5", 2, buf, sizeof buf) != 0) {
        fprintf(stderr, "test_cli_surface: fixture synthesis failed: %s\n", buf);
        return -1;
    }
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* ------------------------------------------------------------ synth */

#define SY "surface synth --out out.h5 "

static void test_synth_bad_numbers(void **state)
{
    (void)state;
    expect_fail(SY "--size 1", "size = '1'", "[4, 65536]", NULL);         /* out of range */
    expect_fail(SY "--size 0", "size = '0'", "[4, 65536]", NULL);         /* zero */
    expect_fail(SY "--size -8", "size = '-8'", "[4, 65536]", NULL);       /* negative */
    expect_fail(SY "--size 4.5", "size = '4.5'", "integers in [4, 65536]", NULL);
    expect_fail(SY "--size 70000", "size = '70000'", "[4, 65536]", NULL);
    expect_fail(SY "--size 64,2", "size = '64,2'", "[4, 65536]", NULL);
    expect_fail(SY "--size 8,8,8", "size = '8,8,8'", "one value or two", NULL);
    expect_fail(SY "--size nan", "size = 'nan'", "finite number", NULL); /* NaN */
    expect_fail(SY "--size abc", "size = 'abc'", "not a number", NULL);  /* non-number */
    expect_fail(SY "--rms 0", "rms = 0", "must be > 0", NULL);
    expect_fail(SY "--rms -1e-3", "rms = -0.001", "must be > 0", NULL);
    expect_fail(SY "--rms inf", "rms = 'inf'", "finite number", NULL);   /* inf */
    expect_fail(SY "--rms 1um", "rms = '1um'", "not a number", NULL);
    expect_fail(SY "--length 0", "length = '0'", "must be > 0", NULL);
    expect_fail(SY "--length 1,-1", "length = '1,-1'", "must be > 0", NULL);
    expect_fail(SY "--corr-length -inf", "corr-length = '-inf'", "finite number", NULL);
    expect_fail(SY "--corr-length 0.01,0", "corr-length = '0.01,0'", "must be > 0", NULL);
    expect_fail(SY "--spectrum self-affine --hurst 1.5", "hurst = 1.5", "(0, 1]", NULL);
    expect_fail(SY "--spectrum self-affine --hurst 0", "hurst = 0", "(0, 1]", NULL);
    expect_fail(SY "--spectrum self-affine --hurst nan", "hurst = 'nan'", "finite", NULL);
    expect_fail(SY "--spectrum fractal", "spectrum = 'fractal'", "exponential or self-affine",
                NULL);
    expect_fail(SY "--spectrum self-affine --cutoff-wavelength 0", "cutoff-wavelength = 0",
                "must be > 0", NULL);
    /* cross-key ranges of the self-affine band: λs < λr <= λL, λs >= 2 pixels */
    expect_fail(SY "--spectrum self-affine --rolloff-wavelength 2", "rolloff-wavelength = 2",
                "<= long-wavelength = 1", NULL);
    expect_fail(SY "--spectrum self-affine --size 64 --cutoff-wavelength 0.01",
                "cutoff-wavelength = 0.01", ">= 2 pixels = 0.03125", NULL);
    expect_fail(SY "--spectrum self-affine --long-wavelength 0.1 --cutoff-wavelength 0.2",
                "cutoff-wavelength = 0.2", "< rolloff-wavelength = 0.1", NULL);
    expect_fail(SY "--skewness 2 --kurtosis 4", "kurtosis = 4", "> skewness² + 1 = 5", NULL);
    expect_fail(SY "--kurtosis inf", "kurtosis = 'inf'", "finite", NULL);
    expect_fail(SY "--amplitude random", "amplitude = 'random'", "exact or rayleigh", NULL);
    expect_fail(SY "--seed -1", "seed = '-1'", "[0, 4294967295]", NULL);
    expect_fail(SY "--seed 1e3", "seed = '1e3'", "whole number", NULL);
    expect_fail(SY "--threads 2000", "threads = '2000'", "[0, 1024]", NULL);
    expect_done();
}

static void test_synth_bad_usage(void **state)
{
    (void)state;
    expect_fail(SY "--colour blue", "unknown option '--colour'", NULL, NULL);
    expect_fail(SY "--rms", "--rms: missing value", NULL, NULL);
    expect_fail("surface synth --size 32", "out: missing", "--out FILE.h5", NULL);
    expect_fail("surface synth --out ''", "out = ''", "file", NULL);
    expect_fail(SY "--json=maybe", "json = 'maybe'", "1/true/yes or 0/false/no", NULL);
    /* options that would be silently ignored are refused, naming both */
    expect_fail(SY "--hurst 0.5", "--hurst conflicts with --spectrum exponential", NULL, NULL);
    expect_fail(SY "--spectrum self-affine --corr-length 0.1",
                "--corr-length conflicts with --spectrum self-affine", NULL, NULL);
    expect_fail(SY "--import grid.txt --pixel-size 0.01 --rms 1e-3",
                "--rms conflicts with --import", NULL, NULL);
    expect_fail(SY "--pixel-size 0.01", "--pixel-size conflicts with --import", NULL, NULL);
    expect_fail(SY "--png out.png --no-png", "--png conflicts with --no-png", NULL, NULL);
    expect_fail(SY "--png out.h5", "png = 'out.h5'", "must differ from out", NULL);
    expect_fail(SY "--import grid.txt", "import = 'grid.txt'", "--pixel-size", NULL);
    expect_fail(SY "--import grid.txt --dataset /z", "--dataset conflicts with --pixel-size",
                NULL, NULL);
    /* a directory where a file belongs: named as one, before any work */
    expect_fail(SY "--import adir --pixel-size 0.01", "import = 'adir': is a directory", NULL,
                NULL);
    expect_fail("surface synth --size 16 --out adir", "out = 'adir': is a directory", NULL, NULL);
    expect_fail(SY "--size 16 --png adir", "png = 'adir': is a directory", NULL, NULL);
    /* an output path that cannot be written: nothing partial anywhere */
    expect_fail("surface synth --size 32 --out out-missing-dir/x.h5",
                "out-missing-dir/x.png", "cannot create", NULL);
    expect_fail("surface synth --size 32 --out out.h5 --png out-missing-dir/x.png",
                "out-missing-dir/x.png", "cannot create", NULL);
    expect_done();
}

static void test_synth_config(void **state)
{
    (void)state;
    write_file("bad1.ini", "size = 32\ncolour = blue\n");
    expect_fail(SY "--config bad1.ini", "unknown option 'colour'", NULL, NULL);
    write_file("bad2.ini", "size = 32\nthis is not ini\n");
    expect_fail(SY "--config bad2.ini", "config = 'bad2.ini'", "syntax error on line 2",
                "key = value");
    write_file("bad3.ini", "[surface]\nhurst = 2\nspectrum = self-affine\n");
    expect_fail(SY "--config bad3.ini", "hurst = 2", "(0, 1]", NULL);
    write_file("bad4.ini", "rms = nan\n");
    expect_fail(SY "--config bad4.ini", "rms = 'nan'", "finite number", NULL);
    expect_fail(SY "--config nosuch.ini", "config = 'nosuch.ini'", "cannot open", NULL);
    expect_done();
    /* String options from an INI file outlive the parser (they were once
     * dangling pointers into inih's line buffer: the map went to a garbage
     * file name). */
    write_file("good.ini", "size = 16\nout = out-from-ini.h5\npng = out-from-ini.png\n");
    assert_int_equal(run("surface synth --config good.ini --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    assert_non_null(strstr(buf, "\"out\": \"out-from-ini.h5\""));
    struct stat st;
    assert_int_equal(stat(P("out-from-ini.h5"), &st), 0);
    assert_int_equal(stat(P("out-from-ini.png"), &st), 0);
    rm_outputs();
}

/* ------------------------------------------------------------ stats */

static void test_stats_bad_files(void **state)
{
    (void)state;
    expect_fail("surface stats", "in: missing", NULL, NULL);
    expect_fail("surface stats nosuch.h5", "in = 'nosuch.h5'", "cannot open",
                "stiction surface HDF5 file");
    expect_fail("surface stats notgrid.h5", "in = 'notgrid.h5'", "not an HDF5 file", NULL);
    expect_fail("surface stats grid.txt", "in = 'grid.txt'", "not an HDF5 file", "--pixel-size");
    expect_fail("surface stats meas.h5", "in = 'meas.h5'", "no dataset '/height'", "--dataset");
    expect_fail("surface stats rank1.h5", "in = 'rank1.h5'", "not 2-D", NULL);
    expect_fail("surface stats nanh.h5", "in = 'nanh.h5'", "row 2, column 2", "not finite");
    expect_fail("surface stats arrlx.h5", "in = 'arrlx.h5'", "lx_mm, ly_mm missing", NULL);
    expect_fail("surface stats map.h5 --in map.h5", "in = 'map.h5'", "FILE argument", NULL);
    /* a directory is neither missing nor "not an HDF5 file" */
    expect_fail("surface stats adir", "in = 'adir': is a directory", "stiction surface HDF5 file",
                NULL);
    expect_fail("surface stats --in adir/", "in = 'adir/': is a directory", NULL, NULL);
    expect_fail("surface stats adir --pixel-size 0.01", "in = 'adir': is a directory",
                "text grid", NULL);
    expect_fail("surface stats adir --pixel-size 0.01 --dataset /z",
                "in = 'adir': is a directory", "2-D numeric dataset", NULL);
    /* HDF5 import of a measured dataset */
    expect_fail("surface stats meas.h5 --pixel-size 0.01 --dataset /nope", "in = 'meas.h5'",
                "no dataset '/nope'", "2-D numeric dataset");
    expect_fail("surface stats meas.h5 --pixel-size 0.01 --dataset /profile", "in = 'meas.h5'",
                "rank 1", "2-D");
    expect_fail("surface stats meas.h5 --pixel-size 0.01 --dataset /stack", "rank 3", NULL, NULL);
    expect_fail("surface stats meas.h5 --pixel-size 0.01 --dataset /names", "'/names'",
                "not numeric", NULL);
    expect_fail("surface stats meas.h5 --pixel-size 0.01 --dataset /holes", "'/holes'",
                "row 2, column 2", "not finite");
    expect_fail("surface stats notgrid.h5 --pixel-size 0.01 --dataset /z", "in = 'notgrid.h5'",
                "not an HDF5 file", NULL);
    expect_fail("surface stats meas.h5 --dataset /scan/z",
                "--dataset conflicts with --pixel-size", NULL, NULL);
    expect_fail("surface stats map.h5 --z-scale 1e-3", "--z-scale conflicts with --pixel-size",
                NULL, NULL);
    expect_done();
}

static void test_stats_bad_text(void **state)
{
    (void)state;
    expect_fail("surface stats ragged.txt --pixel-size 0.01", "in = 'ragged.txt'",
                "line 3 has 2 values, expected 3", "every row the same length");
    expect_fail("surface stats word.txt --pixel-size 0.01", "line 2, column 2", "'x5'",
                "not a finite number");
    expect_fail("surface stats nan.txt --pixel-size 0.01", "'nan'", "not a finite number", NULL);
    expect_fail("surface stats overflow.txt --pixel-size 0.01", "'1e999'", "not a finite number",
                NULL);
    expect_fail("surface stats empty.txt --pixel-size 0.01", "in = 'empty.txt'", "0 rows",
                "at least 3 x 3");
    expect_fail("surface stats comments.txt --pixel-size 0.01", "0 rows", "at least 3 x 3", NULL);
    expect_fail("surface stats small.txt --pixel-size 0.01", "2 rows of 2 values",
                "at least 3 x 3", NULL);
    expect_fail("surface stats plane.txt --pixel-size 0.01", "in = 'plane.txt'",
                "heights are flat (a plane)", "a rough map");
    expect_fail("surface stats huge.txt --pixel-size 0.01", "in = 'huge.txt'", "overflow", NULL);
    /* binary read as text: the echo is printable, and no crash */
    expect_fail("surface stats map.h5 --pixel-size 0.01", "in = 'map.h5'", "'?HDF",
                "not a finite number");
    expect_fail("surface stats grid.txt --pixel-size 0", "pixel-size = '0'", "must be > 0", NULL);
    expect_fail("surface stats grid.txt --pixel-size 0.01,-1", "pixel-size = '0.01,-1'",
                "must be > 0", NULL);
    expect_fail("surface stats grid.txt --pixel-size nan", "pixel-size = 'nan'", "finite", NULL);
    expect_fail("surface stats grid.txt --pixel-size 0.01 --z-scale 0", "z-scale = 0",
                "must be > 0", NULL);
    expect_fail("surface stats map.h5 --rule 6", "rule = '6'", "8 or 4", NULL);
    expect_fail("surface stats map.h5 --neighbours 8", "unknown option '--neighbours'", NULL, NULL);
    write_file("bad5.ini", "rule = 8\n[surface\njson = 1\n");
    expect_fail("surface stats map.h5 --config bad5.ini", "config = 'bad5.ini'",
                "syntax error on line 2", NULL);
    expect_done();
}

/* ------------------------------------------------------------ predict */

#define ST "--summit-density 100 --summit-radius 0.05 --sigma-s 1e-3 "
#define PR "surface predict --out out-dir --csv out.csv --png out.png "

static void test_predict_bad_values(void **state)
{
    (void)state;
    expect_fail(PR ST "--pressures 0", "pressures = 0", "must be > 0", NULL);
    expect_fail(PR ST "--pressures 1,-2", "pressures = -2", "must be > 0", NULL);
    expect_fail(PR ST "--pressures nan", "pressures = 'nan'", "finite number", NULL);
    expect_fail(PR ST "--pressures 1,inf", "pressures = 'inf'", "finite number", NULL);
    expect_fail(PR ST "--pressures 1,,2", "pressures: missing value", NULL, NULL);
    expect_fail(PR ST "--pressures 1MPa", "pressures = '1MPa'", "not a number", NULL);
    expect_fail(PR ST "--pressures 1:10:0", "pressures = '1:10:0'", "[1, 100000]", NULL);
    expect_fail(PR ST "--separations 1:x:3", "separations = 'x'", "not a number", NULL);
    expect_fail(PR "--summit-density 0 --summit-radius 0.05 --sigma-s 1e-3 --pressures 1",
                "summit-density = 0", "must be > 0", NULL);
    expect_fail(PR "--summit-density 100 --summit-radius -0.05 --sigma-s 1e-3 --pressures 1",
                "summit-radius = -0.05", "must be > 0", NULL);
    expect_fail(PR "--summit-density 100 --summit-radius 0.05 --sigma-s inf --pressures 1",
                "sigma-s = 'inf'", "finite number", NULL);
    expect_fail(PR ST "--t-mm -1e-3 --pressures 1", "t-mm = -0.001", "must be >= 0", NULL);
    /* every summit has its own radius: the coating is a thickness, not a t/R
     * (which was taken against the common R = 10 mm: t = 0.2 mm) */
    expect_fail(PR ST "--t-over-R 0.02 --pressures 1", "t-over-R = 0.02",
                "every summit has its own radius", "--t-mm MM");
    expect_fail(PR ST "--t-over-R 0.02 --t-mm 1e-3 --pressures 1", "t-over-R = 0.02",
                "--t-mm MM", NULL);
    /* a coated run with one yield strength: the other is not left to E-over-Y */
    expect_fail(PR ST "--t-mm 1.5e-3 --Y-su 1500 --pressures 1", "Y-su = 1500 given without Y-co",
                NULL, NULL);
    expect_fail(PR ST "--E-ratio 2 --Y-co 7000 --pressures 1", "Y-co = 7000 given without Y-su",
                NULL, NULL);
    write_file("tr.ini", "t-over-R = 0.02\n");
    expect_fail(PR ST "--config tr.ini --pressures 1", "t-over-R = 0.02",
                "every summit has its own radius", "--t-mm MM");
    expect_fail(PR ST "--model table --pressures 1", "model = 'table'", "hertz or wsp", NULL);
    expect_fail(PR ST "--mode exact --pressures 1", "mode = 'exact'",
                "statistical or deterministic", NULL);
    expect_fail(PR "--surface map.h5 --density normal --pressures 1", "density = 'normal'",
                "gaussian or kde", NULL);
    expect_fail(PR ST "--layer film --pressures 1", "layer = 'film'", "substrate or coating",
                NULL);
    expect_fail(PR ST "--E-su 0 --pressures 1", "E-su = 0", "must be > 0", NULL);
    expect_fail(PR ST "--nu 0.5 --pressures 1", "nu = 0.5", "(-1, 0.5)", NULL);
    expect_fail(PR ST "--pressures 1 --timing=often", "timing = 'often'", "0/false/no", NULL);
    expect_done();
}

static void test_predict_bad_usage(void **state)
{
    (void)state;
    expect_fail(PR "--pressures 1", "need --surface FILE", "got 0 of 3", NULL);
    expect_fail(PR "--summit-density 100 --sigma-s 1e-3 --pressures 1", "got 2 of 3", NULL, NULL);
    expect_fail(PR ST, "exactly one of --pressures", "--separations", NULL);
    expect_fail(PR ST "--pressures 1 --separations 1", "exactly one of --pressures", NULL, NULL);
    expect_fail(PR "--surface map.h5 " ST "--pressures 1", "surface = 'map.h5'", "not both", NULL);
    expect_fail(PR "--surface map.h5 --mode deterministic --density kde --pressures 1",
                "--density conflicts with --mode deterministic", NULL, NULL);
    expect_fail(PR "--surface map.h5 --mode deterministic --density gaussian --pressures 1",
                "--density conflicts with --mode deterministic", NULL, NULL);
    expect_fail(PR ST "--mode deterministic --pressures 1",
                "--mode deterministic conflicts with --summit-density", NULL, NULL);
    expect_fail(PR ST "--density kde --pressures 1", "--density conflicts with --summit-density",
                NULL, NULL);
    expect_fail(PR ST "--rule 4 --pressures 1", "--rule conflicts with --summit-density", NULL,
                NULL);
    expect_fail(PR ST "--pixel-size 0.01 --pressures 1",
                "--pixel-size conflicts with --summit-density", NULL, NULL);
    expect_fail(PR "--surface map.h5 --dataset /height --pressures 1",
                "--dataset conflicts with --pixel-size", NULL, NULL);
    expect_fail(PR "--surface nosuch.h5 --pressures 1", "surface = 'nosuch.h5'", "cannot open",
                NULL);
    expect_fail(PR "--surface notgrid.h5 --pressures 1", "surface = 'notgrid.h5'",
                "not an HDF5 file", NULL);
    expect_fail(PR "--surface meas.h5 --pressures 1", "surface = 'meas.h5'", "no dataset", NULL);
    expect_fail(PR "--surface adir --pressures 1", "surface = 'adir': is a directory", NULL, NULL);
    expect_fail(PR "--surface adir --pixel-size 0.01 --pressures 1",
                "surface = 'adir': is a directory", NULL, NULL);
    expect_fail(PR "--surface ragged.txt --pixel-size 0.01 --pressures 1",
                "surface = 'ragged.txt'", "line 3 has 2 values", NULL);
    write_file("bad6.ini", "pressures = 1,2\nsurface = map.h5\nmode = deterministic\n"
                           "density = kde\n");
    expect_fail(PR "--config bad6.ini", "--density conflicts with --mode deterministic", NULL,
                NULL);
    write_file("bad7.ini", "pressures = 1,2\nsummit_density = 100\nsummit_radius = 0.05\n"
                           "sigma_s = 1e-3\nload = 5\n");
    expect_fail(PR "--config bad7.ini", "unknown option 'load'", NULL, NULL);
    expect_done();
}

/* Loads the summits cannot carry, and outputs that cannot be written: the
 * run fails as a whole, no file of the set is left (the JSON and CSV would
 * be complete before the PNG fails). */
static void test_predict_no_partial_output(void **state)
{
    (void)state;
    expect_fail(PR ST "--pressures 1,10,1e6", "pressure = 1e+06 MPa", "more than the summits "
                "carry", "valid: 0 < pressure <= ");
    expect_fail(PR "--surface map.h5 --mode deterministic --pressures 1,1e7",
                "pressure = 1e+07 MPa", "valid: 0 < pressure <= ", NULL);
    expect_fail(PR "--surface map.h5 --pressures 1e7", "pressure = 1e+07 MPa", "valid", NULL);
    expect_fail("surface predict " ST "--pressures 1 --out out-d1 --png out-no/x.png",
                "png = 'out-no/x.png'", "cannot write", NULL);
    expect_fail("surface predict " ST "--pressures 1 --out out-d2 --csv out-no/x.csv",
                "csv = 'out-no/x.csv'", "cannot write", NULL);
    expect_fail("surface predict " ST "--pressures 1 --out out-no/dir", "out = 'out-no/dir'",
                "cannot create", NULL);
    /* --out DIR is made before the summation, and removed when the run fails */
    expect_fail("surface predict " ST "--pressures 1e6 --out out-d3", "pressure = 1e+06 MPa",
                NULL, NULL);
    expect_done();
    write_file("out-file", "x");
    int rc = run("surface predict " ST "--pressures 1 --out out-file", 2, buf, sizeof buf);
    assert_int_not_equal(rc, 0);
    assert_non_null(strstr(buf, "out = 'out-file': must be a directory"));
    rm_outputs();
}

/* ------------------------------------------------------------ happy paths */

static double stats_rel(double a, double b) { return fabs(a / b - 1); }

/* synth → stats: the map keeps its parameters; the statistics agree with
 * each other (density = count / area, σ = target RMS exactly). */
static void test_roundtrip_synth_stats(void **state)
{
    (void)state;
    assert_int_equal(run("surface synth " MAP_ARGS " --out out.h5 --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    assert_true(jnum(buf, "nx") == 128 && jnum(buf, "seed") == 3);
    double m0 = jnum(buf, "target_m0"), m2 = jnum(buf, "target_m2"), m4 = jnum(buf, "target_m4");
    struct stat st;
    assert_int_equal(stat(P("out.h5"), &st), 0);
    assert_int_equal(stat(P("out.png"), &st), 0); /* PNG beside the HDF5 by default */
    assert_true(st.st_size > 1000);
    assert_int_equal(run("surface stats out.h5 --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    double n = jnum(buf, "summits"), area = jnum(buf, "summit_area_mm2");
    printf("  128^2 self-affine: %g summits (Nayak %g), R %g mm (McCool %g), sigma_s %g mm\n", n,
           jnum(buf, "summit_density_nayak_per_mm2") * area, jnum(buf, "mean_summit_radius_mm"),
           jnum(buf, "mean_summit_radius_mccool_mm"), jnum(buf, "sigma_s_mm"));
    assert_true(n > 0);
    assert_true(stats_rel(jnum(buf, "summit_density_per_mm2"), n / area) < 1e-12);
    assert_true(stats_rel(jnum(buf, "sigma_mm"), 1e-3) < 1e-10);   /* exact after synthesis */
    /* exact amplitudes: the measured moments are the target's (to 1e-10) */
    assert_true(stats_rel(jnum(buf, "m0"), m0) < 1e-10);
    assert_true(stats_rel(jnum(buf, "m2"), m2) < 1e-10);
    assert_true(stats_rel(jnum(buf, "m4"), m4) < 1e-10);
    assert_true(stats_rel(jnum(buf, "alpha"), m0 * m4 / (m2 * m2)) < 1e-9);
    assert_true(jnum(buf, "sigma_s_mm") > 0);
    assert_true(jnum(buf, "mean_summit_radius_mm") > 0);
    assert_true(jnum(buf, "rule") == 8);
    assert_null(strstr(buf, "null"));
    /* the 4-neighbour rule accepts a superset of the 8-neighbour summits */
    assert_int_equal(run("surface stats out.h5 --rule 4 --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    assert_true(jnum(buf, "summits") >= n && jnum(buf, "rule") == 4);
    rm_outputs();
}

/* Import a measured text grid (µm, tilted): the plane is removed and
 * reported, and the result is a valid stiction file. */
static void test_roundtrip_import(void **state)
{
    (void)state;
    assert_int_equal(run("surface synth --import grid.txt --pixel-size 0.01 --z-scale 1e-3 "
                         "--out out-imp.h5 --no-png --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    assert_non_null(strstr(buf, "\"origin\": \"import\""));
    assert_true(jnum(buf, "nx") == 32 && jnum(buf, "ny") == 32);
    assert_true(stats_rel(jnum(buf, "lx_mm"), 0.32) < 1e-12);
    /* the grid's tilt: 10 µm per mm in x, -20 µm per mm in y (= 0.01, -0.02),
     * up to what the bumps contribute to the least-squares plane */
    printf("  detrend tilt %g, %g (grid: 0.01, -0.02)\n", jnum(buf, "detrend_tilt_x"),
           jnum(buf, "detrend_tilt_y"));
    assert_true(fabs(jnum(buf, "detrend_tilt_x") - 0.01) < 1e-3);
    assert_true(fabs(jnum(buf, "detrend_tilt_y") + 0.02) < 1e-3);
    assert_int_equal(run("surface stats out-imp.h5 --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    assert_non_null(strstr(buf, "\"periodic\": false"));
    assert_true(jnum(buf, "summits") > 0);
    /* the same grid straight into stats: same heights, same statistics */
    double sig = jnum(buf, "sigma_mm"), n = jnum(buf, "summits");
    assert_int_equal(run("surface stats grid.txt --pixel-size 0.01 --z-scale 1e-3 --json", 1, buf,
                         sizeof buf), 0);
    assert_true(stats_rel(jnum(buf, "sigma_mm"), sig) < 1e-12 && jnum(buf, "summits") == n);
    /* a stiction file with an array where a scalar attribute belongs: ignored */
    assert_int_equal(run("surface stats arrmeta.h5 --json", 1, buf, sizeof buf), 0);
    assert_json(buf);
    assert_true(jnum(buf, "nx") == 8 && jnum(buf, "lx_mm") == 1);
    /* and an HDF5 dataset of a measurement file */
    assert_int_equal(run("surface stats meas.h5 --pixel-size 0.01 --dataset /scan/z --json", 1,
                         buf, sizeof buf), 0);
    assert_json(buf);
    assert_true(jnum(buf, "nx") == 16 && jnum(buf, "summits") > 0);
    rm_outputs();
}

/* Check a predict JSON array of n points at the given pressures. */
static void check_points(const char *json, const double *p, int n)
{
    assert_json(json);
    assert_int_equal(count_str(json, "\"mu_s\": "), n);
    double prev_a = 0;
    for (int k = 0; k < n; k++) {
        double pk = jnum_k(json, "nominal_pressure_MPa", k), a = jnum_k(json, "A_over_An", k);
        double mu = jnum_k(json, "mu_s", k);
        /* the solve hits the asked pressure (|log P/target| < 1e-12, or |Δh| < 1e-11) */
        assert_true(stats_rel(pk, p[k]) < 1e-6);
        /* wsp: μs = ΣQmax/ΣP; the WSP fit ranges over 0.3 .. ~0.6 in its domain */
        assert_true(isfinite(mu) && mu >= 0.2 && mu <= 1.0);
        assert_true(a > prev_a && a < 1);
        assert_true(stats_rel(jnum_k(json, "Q_over_An_Estar", k),
                              mu * jnum_k(json, "P_over_An_Estar", k)) < 1e-9);
        assert_true(jnum_k(json, "contacts_per_mm2", k) > 0);
        prev_a = a;
    }
}

/* map → predict, statistical and deterministic, pressure-controlled. */
static void test_roundtrip_predict(void **state)
{
    (void)state;
    static char det[1 << 16];
    /* loads where the summits in contact sit mostly inside the WSP fit's
     * 0.5 <= δ/ωc <= 72 (at 1 MPa the few touching tips are below it, and
     * the fit, extrapolated, gives μs > 1) */
    const double p[3] = {10, 30, 100};
    /* 0.5 µm roughness on a 1.5 µm hard coating, as in the bundled example */
    const char *mat = "--E-su 200000 --E-ratio 2 --nu 0.3 --Y-su 1500 --Y-co 7000 --t-mm 1.5e-3";
    char args[1024];
    snprintf(args, sizeof args, "surface predict --surface map.h5 %s --pressures 10,30,100 --json",
             mat);
    assert_int_equal(run(args, 1, buf, sizeof buf), 0);
    check_points(buf, p, 3);
    snprintf(args, sizeof args, "surface predict --surface map.h5 %s --pressures 10,30,100 "
             "--mode deterministic --json --out out-dir", mat);
    assert_int_equal(run(args, 1, det, sizeof det), 0);
    check_points(det, p, 3);
    for (int k = 0; k < 3; k++) {
        double as = jnum_k(buf, "A_over_An", k), ad = jnum_k(det, "A_over_An", k);
        printf("  P/An %5g MPa: A/An statistical %.4g, deterministic %.4g; mu_s %.4f / %.4f\n",
               p[k], as, ad, jnum_k(buf, "mu_s", k), jnum_k(det, "mu_s", k));
        /* a sanity bound only: ~10-20 summits touch on a 128² map, so the
         * deterministic sum carries the sampling error of that handful (the
         * full-size agreement is `make validate`, 30-surface.sh) */
        assert_true(ad / as > 0.5 && ad / as < 2);
        /* deterministic on a 1 mm² map: contacts per mm² = the count */
        assert_true(jnum_k(det, "contacts_per_mm2", k) == jnum_k(det, "contacts", k));
        assert_true(jnum_k(det, "load_fraction_outside_model_range", k) < 0.5);
    }
    /* the bundled example configuration runs as it is */
    assert_int_equal(run("surface predict --config '" STC_DATA_DIR "/../examples/tin-on-steel-"
                         "predict.ini' --surface map.h5 --pressures 10 --json", 1, det, sizeof det),
                     0);
    check_points(det, p, 1);
    /* --out DIR: the three files, complete, and no temporaries */
    struct stat st;
    assert_int_equal(stat(P("out-dir/gw.json"), &st), 0);
    assert_int_equal(stat(P("out-dir/gw.png"), &st), 0);
    assert_true(st.st_size > 1000);
    assert_int_equal(file_lines(P("out-dir/gw.csv")), 3 + 1 + 3); /* 3 comment lines, header,
                                                                      3 points */
    assert_int_equal(dir_entries(P("out-dir")), 3);
    /* separation-controlled, statistics given directly: monotone in d */
    assert_int_equal(run("surface predict " ST "--separations 3,2,1,0 --json", 1, buf,
                         sizeof buf), 0);
    assert_json(buf);
    for (int k = 1; k < 4; k++)
        assert_true(jnum_k(buf, "nominal_pressure_MPa", k) >
                    jnum_k(buf, "nominal_pressure_MPa", k - 1));
    /* a mu_s that does not exist (no friction law; nothing touching) reads
     * n/a in the table and an empty CSV field, never nan */
    assert_int_equal(run("surface predict " ST "--pressures 1 --model hertz --csv out.csv", 1,
                         buf, sizeof buf), 0);
    printf("%s", buf);
    assert_non_null(strstr(buf, "n/a"));
    assert_null(strstr(buf, "nan"));
    FILE *f = fopen(P("out.csv"), "r");
    assert_non_null(f);
    size_t got = fread(det, 1, sizeof det - 1, f);
    det[got] = '\0';
    fclose(f);
    assert_non_null(strstr(det, ",,"));
    assert_null(strstr(det, "nan"));
    /* its PNG too: A/An alone (gnuplot refuses a plot whose mu_s column is all empty) */
    assert_int_equal(run("surface predict " ST "--pressures 1,10 --model hertz --png out.png", 1,
                         buf, sizeof buf), 0);
    assert_int_equal(stat(P("out.png"), &st), 0);
    assert_true(st.st_size > 1000);
    assert_int_equal(run("surface predict " ST "--separations 7000", 1, buf, sizeof buf), 0);
    assert_non_null(strstr(buf, "n/a"));
    assert_null(strstr(buf, "nan"));
    rm_outputs();
}

/* surface sweep: every design reads what `surface predict --table` gives
 * for it alone (the same numbers: the summits read once, each coating the
 * table's model summed over them), the coating's yield strength from the
 * table's family; --out writes its two files and nothing else; bad input is
 * refused naming the key and leaves nothing behind. */
#define SW_POP "--summit-density 1000 --summit-radius 0.1 --sigma-s 2e-6 "
#define SW_TABLE "--table '" STC_DATA_DIR "/tables/thesis.h5' "
static void test_sweep(void **state)
{
    (void)state;
    assert_int_equal(run("surface sweep " SW_POP SW_TABLE "--t-mm 1e-3,2.5e-3 --E-ratio 2,4 "
                         "--pressures 0.02,0.2 --json --out out-sweep", 1, buf, sizeof buf), 0);
    assert_json(buf);
    static char one[1 << 15];
    const double T[2] = {1e-3, 2.5e-3}, E[2] = {2, 4};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            char args[1024];
            int k = 2 * a + b;
            snprintf(args, sizeof args, "surface predict " SW_POP SW_TABLE "--t-mm %g "
                     "--E-ratio %g --pressures 0.02,0.2 --json", T[a], E[b]);
            assert_int_equal(run(args, 1, one, sizeof one), 0);
            assert_true(jnum_k(buf, "t_mm", k) == T[a] && jnum_k(buf, "E_ratio", k) == E[b]);
            assert_true(fabs(jnum_k(buf, "Y_co_MPa", k) / (200.0 * E[b]) - 1) < 1e-12);
            for (int i = 0; i < 2; i++) {
                static const char *const key[] = {"mu_s", "mu_s_err", "mu_s_P_at_inception",
                                                  "A_over_An", "load_fraction_outside_model_range"};
                for (int m = 0; m < 5; m++) {
                    double x = jnum_k(buf, key[m], 2 * k + i), y = jnum_k(one, key[m], i);
                    if (fabs(x - y) > 1e-12 * fabs(y))
                        fail_msg("sweep t %g E %g point %d: %s %.17g, predict %.17g", T[a], E[b],
                                 i, key[m], x, y);
                }
            }
        }
    /* the thesis family's trend (SPEC §6): a stiffer coating, a higher surface mu_s */
    for (int a = 0; a < 2; a++)
        for (int i = 0; i < 2; i++)
            assert_true(jnum_k(buf, "mu_s", 2 * (2 * a + 1) + i) >
                        jnum_k(buf, "mu_s", 2 * (2 * a) + i));
    assert_int_equal(file_lines(P("out-sweep/sweep.csv")), 1 + 4 * 2); /* header, 4 designs x
                                                                           2 pressures */
    static char js[1 << 15];
    FILE *f = fopen(P("out-sweep/sweep.json"), "r");
    assert_non_null(f);
    size_t n = fread(js, 1, sizeof js - 1, f);
    fclose(f);
    js[n] = '\0';
    assert_string_equal(js, buf); /* the file is what --json printed */
    assert_int_equal(dir_entries(P("out-sweep")), 3);
    unsigned char h[8];
    f = fopen(P("out-sweep/sweep.png"), "rb");
    assert_non_null(f);
    assert_int_equal(fread(h, 1, 8, f), 8);
    fclose(f);
    assert_memory_equal(h, "\x89PNG\r\n\x1a\n", 8);
    /* the text form: one row per design in each of the two blocks */
    assert_int_equal(run("surface sweep " SW_POP SW_TABLE "--t-mm 1e-3 --E-ratio 2,4 "
                         "--pressures 0.02", 1, buf, sizeof buf), 0);
    assert_non_null(strstr(buf, "mu_s +- the table's one standard error"));
    assert_non_null(strstr(buf, "A/An"));
    rm_outputs();
    /* a rename that fails (sweep.json a directory) leaves none of the files */
    assert_int_equal(mkdir(P("out-rn"), 0755), 0);
    assert_int_equal(mkdir(P("out-rn/sweep.json"), 0755), 0);
    write_file("out-rn/sweep.json/x", "");
    assert_int_equal(run("surface sweep " SW_POP SW_TABLE "--t-mm 1e-3 --pressures 0.02 "
                         "--out out-rn", 2, buf, sizeof buf), 1);
    assert_non_null(strstr(buf, "cannot rename"));
    assert_int_equal(dir_entries(P("out-rn")), 1);
    rm_outputs();

#define SW "surface sweep " SW_POP SW_TABLE "--pressures 0.02 --out out-bad "
    expect_fail(SW "--t-mm 0,1e-3", "t-mm = 0", "value 1", "> 0");
    expect_fail(SW "--t-mm 1e-3 --E-ratio 2,-4", "E-ratio = -4", "value 2", "> 0");
    expect_fail(SW "--t-mm 1e-3 --Y-co 800", "Y-co = 800", "table's family", NULL);
    expect_fail(SW "--t-mm 1e-3 --t-over-R 0.01", "t-over-R = 0.01", "--t-mm", NULL);
    expect_fail(SW "--E-ratio 2", "t-mm: required", NULL, NULL);
    expect_fail("surface sweep " SW_POP "--t-mm 1e-3 --pressures 0.02 --out out-bad",
                "table: required", NULL, NULL);
    expect_fail("surface sweep " SW_POP SW_TABLE "--t-mm 1e-3 --out out-bad",
                "pressures: required", NULL, NULL);
    expect_fail(SW "--t-mm 1e-3 --E-over-Y 500", "table", "family", NULL);
    expect_fail(SW "--t-mm 1e-3 --pressures 1e9", "pressure", NULL, NULL);
    expect_fail(SW "--t-mm 1e-3 --mode deterministic", "mode deterministic", "summits of a map",
                NULL);
    expect_fail(SW "--t-mm 1e-3 --jobs 2", "--jobs 2 needs --fill", NULL, NULL);
    expect_done();
#undef SW
}

/* A KDE of the map's heights summed with an FE table: at 0.1 MPa the
 * pressure solve tries separations high in the KDE's tail, where the load
 * is 1e-10 of the target and the quadrature stops at roundoff with a bound
 * of 1.3e-6 of that piece; the solve takes it at its own tolerance of the
 * target (it failed with "roundoff error" before). */
static void test_kde_table_low_load(void **state)
{
    (void)state;
    assert_int_equal(run("surface predict --surface map.h5 --density kde --table '" STC_DATA_DIR
                         "/tables/tin-on-steel.h5' --E-su 200000 --Y-su 1500 --Y-co 7000 "
                         "--E-ratio 2 --nu 0.3 --t-mm 1.5e-3 --pressures 0.1,1,10 --json", 1,
                         buf, sizeof buf), 0);
    assert_json(buf);
    for (int k = 0; k < 3; k++) {
        double mu = jnum_k(buf, "mu_s", k), h = jnum_k(buf, "separation_over_sigma_s", k);
        assert_true(mu > 0.5 && mu < 5.0);
        if (k) assert_true(h < jnum_k(buf, "separation_over_sigma_s", k - 1));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_synth_bad_numbers),
        cmocka_unit_test(test_synth_bad_usage),
        cmocka_unit_test(test_synth_config),
        cmocka_unit_test(test_stats_bad_files),
        cmocka_unit_test(test_stats_bad_text),
        cmocka_unit_test(test_predict_bad_values),
        cmocka_unit_test(test_predict_bad_usage),
        cmocka_unit_test(test_predict_no_partial_output),
        cmocka_unit_test(test_roundtrip_synth_stats),
        cmocka_unit_test(test_roundtrip_import),
        cmocka_unit_test(test_roundtrip_predict),
        cmocka_unit_test(test_sweep),
        cmocka_unit_test(test_kde_table_low_load),
    };
    return cmocka_run_group_tests_name("cli_surface", tests, setup, teardown);
}
