/* The stiction CLI as a user meets it: every invalid-input path must exit
 * non-zero with a message naming the key, the value and the valid range,
 * and leave no output file; valid runs print parseable JSON / CSV.
 *
 * The binary is $STICTION_CLI if set, else ../bin/stiction relative to this
 * test program (the Makefile's layout for any O=). */
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
#include "stiction/asperity.h"
#include "tmp_util.h"

static char cli[PATH_MAX];
static char ini[256]; /* scratch INI file */
static char ini_dir[256]; /* scratch directory, given where a file belongs */

static int find_cli(void **state)
{
    (void)state;
    if (cli_locate(cli, sizeof cli) != 0) return -1;
    if (access(cli, X_OK) != 0) {
        fprintf(stderr, "test_cli: no executable CLI at '%s' (build it, or set STICTION_CLI)\n", cli);
        return -1;
    }
    snprintf(ini, sizeof ini, "%s/stiction-test-cli-%ld.ini", test_tmpdir(), (long)getpid());
    snprintf(ini_dir, sizeof ini_dir, "%s/stiction-test-cli-%ld.d", test_tmpdir(), (long)getpid());
    return mkdir(ini_dir, 0700) == 0 ? 0 : -1;
}

static int cleanup(void **state)
{
    (void)state;
    remove(ini);
    rmdir(ini_dir);
    return 0;
}

/* Run "cli ARGS"; `which` = 1 captures stdout, 2 stderr.  Returns the exit
 * status; the captured text goes to buf (NUL-terminated). */
static int run(const char *args, int which, char *buf, size_t n)
{
    char cmd[PATH_MAX + 1024];
    snprintf(cmd, sizeof cmd, "'%s' %s", cli, args);
    return cli_capture(cmd, which, buf, n);
}

static void write_ini(const char *text)
{
    FILE *f = fopen(ini, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Expect failure with every needle in the message on stderr. */
static void expect_fail(const char *args, const char *n1, const char *n2)
{
    static char err[8192];
    int rc = run(args, 2, err, sizeof err);
    printf("  %-58s -> %d: %s", args, rc, err);
    if (rc == 0) fail_msg("'%s' exited 0", args);
    if (!strstr(err, n1) || (n2 && !strstr(err, n2)))
        fail_msg("'%s': message '%s' lacks '%s' / '%s'", args, err, n1, n2 ? n2 : "");
}

/* expect_fail on "base extra". */
static void expect_fail_on(const char *base, const char *extra, const char *n1, const char *n2)
{
    char args[512];
    snprintf(args, sizeof args, "%s %s", base, extra);
    expect_fail(args, n1, n2);
}

/* --placements: a whole number of meshes in [1, 8] (refused while parsing,
 * before any mesh is built) */
static void test_bad_placements(void **state)
{
    (void)state;
    expect_fail("asperity --delta 3 --shear --placements 0", "placements = '0'", "[1, 8]");
    expect_fail("asperity --delta 3 --shear --placements 9", "placements = '9'", "[1, 8]");
    expect_fail("asperity --delta 3 --shear --placements 2.5", "placements = '2.5'", "[1, 8]");
    expect_fail("asperity --delta 3 --shear --edge-refine 3", "edge-refine = '3'", "[0, 2]");
    expect_fail("asperity --delta 3 --edge-refine 2", "edge-refine = 2", "only with --shear");
}

static void test_bad_common_values(void **state)
{
    (void)state;
    expect_fail("formulas --R -1", "R = -1", "must be > 0");               /* negative */
    expect_fail("formulas --E-su 0", "E-su = 0", "must be > 0");           /* zero */
    expect_fail("formulas --E-ratio=0", "E-ratio = 0", "must be > 0");
    expect_fail("formulas --nu nan", "nu = 'nan'", "finite number");       /* NaN */
    expect_fail("formulas --R inf", "R = 'inf'", "finite number");         /* inf */
    expect_fail("formulas --R -inf", "R = '-inf'", "finite number");
    expect_fail("formulas --t-over-R abc", "t-over-R = 'abc'", "not a number");
    expect_fail("formulas --R 10mm", "R = '10mm'", "not a number");
    expect_fail("formulas --nu 0.7", "nu = 0.7", "(-1, 0.5)");
    expect_fail("formulas --nu-co -1", "nu-co = -1", "(-1, 0.5)");
    expect_fail("formulas --t-over-R 1", "t-over-R = 1", "[0, 1)");
    expect_fail("formulas --t-over-R -0.01", "t-over-R = -0.01", "[0, 1)");
    expect_fail("formulas --E-over-Y 1", "E-over-Y = 1", "must be > 1");
    expect_fail("formulas --Y-co 0", "Y-co = 0", "must be > 0");
    expect_fail("formulas --Y-su 300000", "Y-su = 300000", "below E-su");  /* cross-key */
}

static void test_bad_syntax(void **state)
{
    (void)state;
    expect_fail("formulas --radius 3", "unknown option '--radius'", NULL);
    expect_fail("formulas --R", "--R: missing value", NULL);
    expect_fail("formulas --delta", "--delta: missing value", NULL);
    /* a forgotten value is not filled with the next option (found by test_fuzz:
     * `surface synth --png --json` wrote a PNG named --json) */
    expect_fail("formulas --t-over-R --R 3", "--t-over-R: missing value",
                "the next argument, '--R', is an option");
    expect_fail("surface synth --out out.h5 --png --json", "--png: missing value", "'--json'");
    expect_fail("formulas --R ''", "R: missing value", "number");
    expect_fail("formulas 10", "unexpected argument '10'", NULL);
    expect_fail("formulas --json=maybe", "json = 'maybe'", "1/true/yes or 0/false/no");
    expect_fail("formulas --json --csv", "choose one", NULL);
    expect_fail("formulas --sweep-E-ratio 2", "only valid with --csv", NULL);
    expect_fail("nosuchcommand", "unknown command 'nosuchcommand'", NULL);
}

static void test_bad_delta(void **state)
{
    (void)state;
    expect_fail("formulas --delta 0", "delta = 0", "must be > 0");
    expect_fail("formulas --delta -2", "delta = -2", "must be > 0");
    expect_fail("formulas --delta 1,abc", "delta = 'abc'", "expected numbers > 0");
    expect_fail("formulas --delta 1,,2", "delta: missing value", "expected numbers > 0");
    expect_fail("formulas --delta 1,nan", "delta = 'nan'", "expected numbers > 0");
    expect_fail("formulas --delta 1:5", "delta = '1:5'", "start:stop:count");
    expect_fail("formulas --delta 1:5:0", "delta = '1:5:0'", "[1, 100000]");
    expect_fail("formulas --delta 1:5:x", "delta = 'x'", "not an integer");
    expect_fail("formulas --delta -1:5:3", "delta = -1", "must be > 0");
    expect_fail("formulas --csv --sweep-E-ratio 0.5,2", "sweep-E-ratio = 0.5", "must be > 1");
    expect_fail("formulas --csv --sweep-t-over-R 0.01,1.5", "sweep-t-over-R = 1.5", "(0, 1)");
    expect_fail("formulas --csv --delta 3", "delta", "not used by --csv");
}

static void test_bad_config(void **state)
{
    (void)state;
    char args[512];
    snprintf(args, sizeof args, "formulas --config %s", ini);
    write_ini("[material]\ncolour = blue\n");
    expect_fail(args, "unknown option 'colour'", NULL);                  /* unknown key */
    write_ini("R = 3\nthis line is not ini\n");
    expect_fail(args, "syntax error on line 2", "key = value");         /* malformed */
    write_ini("t-over-R = -0.5\n");
    expect_fail(args, "t-over-R = -0.5", "[0, 1)");                     /* bad value */
    write_ini("nu = nan\n");
    expect_fail(args, "nu = 'nan'", "finite number");
    write_ini("delta = 1,abc\n");
    expect_fail(args, "delta = 'abc'", "not a number");                 /* own key */
    expect_fail("formulas --config /nonexistent/x.ini", "config = '/nonexistent/x.ini'",
                "cannot open");                                          /* missing file */
    expect_fail("formulas --config", "--config: missing file name", NULL);
}

/* --config names a file: a directory is refused by name, with the exit
 * status of a file that cannot be opened, by every subcommand that reads
 * one (a directory read as an empty file: formulas ran on the defaults). */
static void test_config_directory(void **state)
{
    (void)state;
    static const char *const cmds[] = {"formulas",      "asperity",      "halfspace",
                                       "surface synth", "surface stats", "surface predict",
                                       "surface sweep",
                                       "table build",   "table info",    "table query",
                                       "table merge"};
    char args[512], needle[384], err[4096];
    int bad = 0;
    snprintf(needle, sizeof needle, "config = '%s': is a directory", ini_dir);
    for (size_t i = 0; i < sizeof cmds / sizeof *cmds; i++) {
        snprintf(args, sizeof args, "%s --config %s", cmds[i], ini_dir);
        int rc = run(args, 2, err, sizeof err);
        int ok = rc == 1 && strstr(err, needle);
        printf("  %-58s -> %d: %s%s", args, rc, err, ok ? "" : "    (expected 1 and the message)\n");
        bad += !ok;
    }
    if (bad) fail_msg("%d subcommands took a directory for --config", bad);
    snprintf(args, sizeof args, "formulas --config=%s/", ini_dir);
    expect_fail(args, "is a directory", NULL);
}

/* A mistyped option, key or (sub)command is answered with the closest
 * known name of that command (edit distance <= 1 up to 5 characters, 2
 * beyond; case ignored); a name near nothing gets no guess. */
static void test_suggestions(void **state)
{
    (void)state;
    char args[512];
    expect_fail("surface predict --presures 1", "unknown option '--presures'",
                "(did you mean --pressures?)");
    expect_fail("surface predict --presures=1", "unknown option '--presures'",
                "(did you mean --pressures?)");
    expect_fail("formulas --dleta 3", "unknown option '--dleta'", "(did you mean --delta?)");
    expect_fail("formulas --t-over-r 0.01", "unknown option '--t-over-r'",
                "(did you mean --t-over-R?)");                              /* case */
    expect_fail("formulas --E_ration 2", "unknown option '--E-ration'",
                "(did you mean --E-ratio?)");
    expect_fail("formulas --confg x.ini", "unknown option '--confg'", "(did you mean --config?)");
    expect_fail("asperity --elements-per-contat 3", "unknown option '--elements-per-contat'",
                "(did you mean --elements-per-contact?)");
    expect_fail("halfspace --cels 64", "unknown option '--cels'", "(did you mean --cells?)");
    expect_fail("surface synth --hurts 0.5", "unknown option '--hurts'", "(did you mean --hurst?)");
    expect_fail("surface stats --rlue 4", "unknown option '--rlue'", "(did you mean --rule?)");
    expect_fail("table info --jsno", "unknown option '--jsno'", "(did you mean --json?)");
    expect_fail("table query --detla 1", "unknown option '--detla'", "(did you mean --delta?)");
    expect_fail("formulas -delta 3", "unexpected argument '-delta'", "did you mean --delta?");
    expect_fail("formulsa", "unknown command 'formulsa'", "(did you mean formulas?)");
    expect_fail("surface predcit", "unknown subcommand 'predcit'", "(did you mean predict?)");
    expect_fail("table bulid", "unknown subcommand 'bulid'", "(did you mean build?)");
    /* keys of a --config file */
    snprintf(args, sizeof args, "formulas --config %s", ini);
    write_ini("dleta = 3\n");
    expect_fail(args, "unknown option 'dleta'", "(did you mean delta?)");
    write_ini("[material]\nnu_c = 0.3\n");
    expect_fail(args, "unknown option 'nu-c'", "(did you mean nu-co?)");
    /* nothing close: no guess */
    static const char *const far[] = {"formulas --colour blue", "formulas --x 1", "nosuchcommand",
                                      "surface nosuch", "formulas --radius 3"};
    static char err[4096];
    for (size_t i = 0; i < sizeof far / sizeof *far; i++) {
        expect_fail(far[i], "unknown", NULL);
        run(far[i], 2, err, sizeof err);
        if (strstr(err, "did you mean")) fail_msg("'%s': a guess for a far name: %s", far[i], err);
    }
}

/* A failing run writes no output file; a good one leaves no temp file. */
static void test_output_file(void **state)
{
    (void)state;
    char out[128], args[512], buf[256];
    struct stat st;
    snprintf(out, sizeof out, "%s/stiction-test-cli-%ld.json", test_tmpdir(), (long)getpid());
    remove(out);
    snprintf(args, sizeof args, "formulas --json --output %s --delta 1,abc", out);
    assert_int_not_equal(run(args, 2, buf, sizeof buf), 0);
    assert_int_not_equal(stat(out, &st), 0);
    snprintf(args, sizeof args, "formulas --csv --output %s --t-over-R 0", out);
    assert_int_not_equal(run(args, 2, buf, sizeof buf), 0);
    assert_non_null(strstr(buf, "t-over-R = 0"));
    assert_int_not_equal(stat(out, &st), 0);
    expect_fail("formulas --json --output /nonexistent/dir/x.json", "output = '/nonexistent/dir/x.json'",
                "cannot create");
    snprintf(args, sizeof args, "formulas --json --output %s --delta 2", out);
    assert_int_equal(run(args, 2, buf, sizeof buf), 0);
    assert_int_equal(stat(out, &st), 0);
    assert_true(st.st_size > 100);
    snprintf(args, sizeof args, "ls %s.tmp.* 2>/dev/null | wc -l", out);
    FILE *p = popen(args, "r");
    assert_non_null(p);
    assert_non_null(fgets(buf, sizeof buf, p));
    pclose(p);
    assert_int_equal(atoi(buf), 0);
    remove(out);
}


/* Value of a top-level-style "key": number (first occurrence). */
static char out[1 << 16];

static void test_json_coated(void **state)
{
    (void)state;
    assert_int_equal(run("formulas --t-over-R 0.025 --E-ratio 2 --delta 10 --json", 1, out, sizeof out), 0);
    assert_json(out);
    printf("  JSON: %zu bytes, valid\n", strlen(out));
    const char *keys[] = {"omega_c_mm", "P_c_N", "A_c_mm2", "delta_c_stick_over_omega_c",
                          "L_c_stick_over_P_c", "tR_p", "tR_p_st", "delta_c1_over_omega_c_su",
                          "delta_c2_over_omega_c_su", "L_c2_over_P_c_co", "A_c2_st_over_A_c_co",
                          "mu_s_wsp", "hertz_P_N", "R_mm", "E_ratio"};
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        assert_true(isfinite(cli_jnum(out, keys[i])));
    assert_true(fabs(cli_jnum(out, "omega_c_mm") - 5.320e-5) < 0.5e-8);
    assert_true(fabs(cli_jnum(out, "delta_c2_over_omega_c_su") - 17.60) < 0.005); /* Table 4.2 */
    assert_true(fabs(cli_jnum(out, "mu_s_wsp") - 0.3 / tanh(0.57 * pow(10, 0.41))) < 1e-9);
    assert_null(strstr(out, "nan"));
    assert_non_null(strstr(out, "\"coated_applicable\": true"));
}

static void test_json_uncoated(void **state)
{
    (void)state;
    assert_int_equal(run("formulas --json --delta 1,3", 1, out, sizeof out), 0);
    assert_json(out);
    assert_true(isnan(cli_jnum(out, "delta_c1_over_omega_c_su"))); /* null, not NaN */
    assert_non_null(strstr(out, "\"coated_note\": \"coated-sphere fits not applicable: t-over-R = 0"));
    assert_non_null(strstr(out, "\"mu_s_wsp\": [")); /* an array for a list */
    assert_null(strstr(out, "nan"));
    /* the readable report says n/a, never nan (ν = 0.05: Brizmer's fits < 0) */
    assert_int_equal(run("formulas --nu 0.05 --delta 1", 1, out, sizeof out), 0);
    assert_null(strstr(out, "nan"));
    assert_non_null(strstr(out, "n/a"));
    assert_non_null(strstr(out, "not applicable"));
}

/* A 3D load curve is meshed for all its contacts by default (graded core,
 * asp_options.grade_3d): the text names the range, and its 1 ωc point is
 * resolved where the uniform core sized to 3 ωc is not.  Reference: raw P
 * of `--delta 1,3 --contact slip --mesh 3` (axisymmetric level 3) 0.3651055
 * / 1.8042887 N.  Measured at 1 ωc: graded -0.21 %, uniform (--grade-3d=no)
 * -1.56 %.  At 3 ωc (printed, not checked) graded +0.94 %, uniform +0.08 %:
 * past yield a raw P carries the node-entry sawtooth (the uniform core at
 * 4 / 8 elements across reads -2.2 / -0.3 % there), so one point does not
 * rank the meshes (docs/design.md §2.4, §3.2).  ~4 s for both. */
static void test_curve_3d_graded(void **state)
{
    (void)state;
    const double ref = 0.3651055, ref3 = 1.8042887;
    const char *base = "asperity --model 3d --delta 1,3 --contact slip";
    char args[512];
    snprintf(args, sizeof args, "%s", base);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    assert_non_null(strstr(out, "4 elements across every a in ["));
    snprintf(args, sizeof args, "%s --json", base);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    double eg = cli_jnum(out, "P_N") / ref - 1;
    double eg3 = cli_jnum(strstr(out, "}"), "P_N") / ref3 - 1;
    snprintf(args, sizeof args, "%s --grade-3d=no --json", base);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    double eu = cli_jnum(out, "P_N") / ref - 1;
    double eu3 = cli_jnum(strstr(out, "}"), "P_N") / ref3 - 1;
    printf("  3D curve 1, 3 wc: P vs axisymmetric level 3: graded %+.2f / %+.2f %%, uniform "
           "%+.2f / %+.2f %%\n", 100 * eg, 100 * eg3, 100 * eu, 100 * eu3);
    assert_true(fabs(eg) < 0.005);
    assert_true(fabs(eu) > 0.01);
    snprintf(args, sizeof args, "%s --grade-3d=no", base);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    assert_null(strstr(out, "elements across every a in"));
}

/* Command line overrides the INI file, which overrides the defaults. */
static void test_config_override(void **state)
{
    (void)state;
    char args[512];
    write_ini("; coated case\n[asperity]\nt_over_R = 0.05\nE-ratio = 4\ndelta = 2\n");
    snprintf(args, sizeof args, "formulas --config %s --E-ratio 2 --json", ini);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    assert_json(out);
    assert_true(cli_jnum(out, "t_over_R") == 0.05 && cli_jnum(out, "E_ratio") == 2.0);
    assert_true(cli_jnum(out, "delta_over_omega_c_su") == 2.0);
    assert_true(fabs(cli_jnum(out, "delta_c2_over_omega_c_su") - 39.61) < 0.005);
}

/* The coating thickness in mm: --t-mm MM is t/R = MM / R of the run's R,
 * the same number as --t-over-R gives (bit for bit where MM / R rounds to
 * it); refused with --t-over-R, and where t/R would reach 1. */
static void test_thickness_mm(void **state)
{
    (void)state;
    static char ref[1 << 16];
    char args[512];
    const char *cases[][2] = {{"--t-over-R 0.025", "--t-mm 0.25"},
                              {"--R 5 --t-over-R 0.025", "--R 5 --t-mm 0.125"}};
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "formulas --E-ratio 2 --delta 10 --json %s", cases[k][0]);
        assert_int_equal(run(args, 1, ref, sizeof ref), 0);
        snprintf(args, sizeof args, "formulas --E-ratio 2 --delta 10 --json %s", cases[k][1]);
        int rc = run(args, 1, out, sizeof out);
        if (rc != 0) {
            run(args, 2, out, sizeof out);
            fail_msg("'%s' exited %d: %s", args, rc, out);
        }
        printf("  %s: t/R %.17g, t %.17g mm, delta_c2 %.6g\n", cases[k][1],
               cli_jnum(out, "t_over_R"), cli_jnum(out, "t_mm"),
               cli_jnum(out, "delta_c2_over_omega_c_su"));
        assert_true(cli_jnum(out, "t_over_R") == 0.025);
        assert_true(cli_jnum(out, "t_over_R") == cli_jnum(ref, "t_over_R"));
        assert_true(cli_jnum(out, "mu_s_wsp") == cli_jnum(ref, "mu_s_wsp"));
        assert_true(cli_jnum(out, "delta_c2_over_omega_c_su") ==
                    cli_jnum(ref, "delta_c2_over_omega_c_su"));
    }
    /* the FE asperity (coarsest mesh, elastic, 0.1 s): the same load */
    assert_int_equal(run("asperity --mesh 0 --delta 1 --E-ratio 2 --t-over-R 0.025 --json", 1, ref,
                         sizeof ref), 0);
    assert_int_equal(run("asperity --mesh 0 --delta 1 --E-ratio 2 --t-mm 0.25 --json", 1, out,
                         sizeof out), 0);
    printf("  asperity --t-mm 0.25: P %.10g N (--t-over-R 0.025: %.10g N)\n", cli_jnum(out, "P_N"),
           cli_jnum(ref, "P_N"));
    assert_true(cli_jnum(out, "P_N") == cli_jnum(ref, "P_N"));
    /* from a --config file too */
    write_ini("t-mm = 0.25\nE-ratio = 2\n");
    snprintf(args, sizeof args, "formulas --config %s --delta 10 --json", ini);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    assert_true(cli_jnum(out, "t_over_R") == 0.025);
    /* both forms of the thickness: refused naming both, wherever each came from */
    expect_fail("formulas --t-mm 0.25 --t-over-R 0.025", "t-mm = 0.25", "t-over-R = 0.025");
    expect_fail("asperity --delta 1 --t-over-R 0.025 --t-mm 0.25", "t-mm = 0.25",
                "t-over-R = 0.025");
    write_ini("t-over-R = 0.025\n");
    snprintf(args, sizeof args, "formulas --config %s --t-mm 0.25", ini);
    expect_fail(args, "t-mm = 0.25", "t-over-R = 0.025");
    expect_fail("formulas --t-mm 10", "t-mm = 10", "t/R = 1");
    expect_fail("formulas --R 2 --t-mm 3", "t-mm = 3", "R = 2 mm");
    expect_fail("formulas --t-mm -0.1", "t-mm = -0.1", "must be >= 0");
    expect_fail("formulas --t-mm 1um", "t-mm = '1um'", "not a number");
    /* and the help says what it is */
    const char *help[] = {"formulas --help", "asperity --help"};
    for (int k = 0; k < 2; k++) {
        assert_int_equal(run(help[k], 1, out, sizeof out), 0);
        if (!strstr(out, "--t-mm MM") || !strstr(out, "t-mm / R"))
            fail_msg("'%s' does not document --t-mm MM as t/R = t-mm / R", help[k]);
    }
}

/* Coating and radius keys a command would ignore are refused by name:
 * surface predict takes each summit's radius from the map or
 * --summit-radius, not the common --R; the half-space reference is a
 * homogeneous sphere, so a coating given as --t-mm, --E-ratio, Y-co or
 * nu-co (before: silently ignored, or named as t-over-R) is refused. */
static void test_ignored_keys(void **state)
{
    (void)state;
    expect_fail("surface predict --summit-density 100 --summit-radius 0.05 --sigma-s 0.001 "
                "--pressures 1 --R 5", "R = 5", "--summit-radius");
    const char *h = "halfspace --R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --delta 0.5 --cells 32";
    char args[512];
    expect_fail_on(h, "--t-mm 0.1 --Y-co 325", "t-mm = 0.1", "homogeneous");
    expect_fail_on(h, "--E-ratio 2 --Y-co 650", "E-ratio = 2", "homogeneous");
    expect_fail_on(h, "--Y-co 300", "Y-co = 300", "homogeneous");
    expect_fail_on(h, "--nu-co 0.3 --Y-co 325", "nu-co = 0.3", "homogeneous");
    /* the coating's own values equal to the substrate's describe no coating */
    snprintf(args, sizeof args, "%s --Y-co 325 --nu-co 0.33 --json", h);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    /* the help says which R a thickness refers to */
    assert_int_equal(run("surface predict --help", 1, out, sizeof out), 0);
    assert_non_null(strstr(out, "t-mm / R with its own radius R"));
    assert_non_null(strstr(out, "--R MM"));
}

/* A closed-form fit used outside the range it was made for is flagged in
 * the report and the JSON (before: only there) and warned about on stderr,
 * one line per fit; inputs inside every range give no warning. */
static void test_formulas_range_warnings(void **state)
{
    (void)state;
    static char err[8192];
    assert_int_equal(run("formulas --delta 100 --json", 2, err, sizeof err), 0);
    printf("  formulas --delta 100: %s", err);
    assert_non_null(strstr(err, "warning: WSP mu_s: omega/omega_c outside [0.5, 72]"));
    assert_int_equal(run("formulas --t-over-R 0.001 --E-ratio 12 --delta 10", 2, err, sizeof err),
                     0);
    assert_non_null(strstr(err, "warning: coated slip fits: Eco/Esu > 4.5"));
    assert_non_null(strstr(err, "warning: coated stick fits: Eco/Esu > 10"));
    assert_non_null(strstr(err, "warning: WSP mu_s: coated input"));
    assert_int_equal(run("formulas --delta 3", 2, err, sizeof err), 0);
    assert_string_equal(err, "");
}

/* --help puts first what a user chooses: the physics (sphere, coating,
 * materials, loading, contact and friction), then one accuracy choice with
 * what it costs and buys, then the common options, and the numerics knobs
 * last under "Expert numerics" (no switch called experimental).  The
 * top-level help says asperity also shears to sliding. */
static void test_help_layout(void **state)
{
    (void)state;
    static char help[1 << 15];
    assert_int_equal(run("asperity --help", 1, help, sizeof help), 0);
    const char *order[] = {"Sphere and coating", "--t-mm MM", "Materials:", "Loading:",
                           "--shear", "Contact and friction:", "--criterion", "Accuracy:",
                           "--mesh LEVEL", "--placements K", "Common options:", "--json",
                           "Expert numerics", "--elements-per-contact", "--foot-rows",
                           "--ramp-refine", "--threads"};
    const char *at = help;
    for (size_t i = 0; i < sizeof order / sizeof *order; i++) {
        const char *next = strstr(at, order[i]);
        if (!next) fail_msg("asperity --help: '%s' missing or out of order", order[i]);
        at = next;
    }
    assert_null(strstr(help, "xperimental"));
    const char *expert[] = {"--surface-layers", "--shell-coarsen", "--edge-refine", "--grade-3d",
                            "--newton-reuse", "--krylov", "--krylov-max", "--steps-per-node",
                            "--return-map", "--ramp-return-map", "--junction"};
    const char *sect = strstr(help, "Expert numerics");
    for (size_t i = 0; i < sizeof expert / sizeof *expert; i++)
        if (!strstr(sect, expert[i])) fail_msg("'%s' is not under Expert numerics", expert[i]);
    /* every command: physics or input first, the common options after it */
    const char *cmds[] = {"formulas", "halfspace", "surface synth", "surface stats",
                          "surface predict", "table build", "table info", "table query",
                          "table merge"};
    char args[64];
    for (size_t i = 0; i < sizeof cmds / sizeof *cmds; i++) {
        snprintf(args, sizeof args, "%s --help", cmds[i]);
        assert_int_equal(run(args, 1, help, sizeof help), 0);
        const char *common = strstr(help, "--config FILE");
        if (!common || !strstr(help, "--help ")) fail_msg("'%s' lacks --config/--help", args);
        const char *x = strstr(help, "Expert numerics");
        if (x && x < common) fail_msg("'%s': Expert numerics before the common options", args);
    }
    assert_int_equal(run("--help", 1, help, sizeof help), 0);
    const char *a = strstr(help, "asperity ");
    assert_non_null(a);
    if (!strstr(a, "--shear") || strstr(a, "--shear") > strchr(a, '\n'))
        fail_msg("stiction --help does not say asperity shears (--shear): %.200s", a);
}

/* Yield strengths: a run with a coating (t > 0, E-ratio != 1 or nu-co)
 * that gives one of Y-su, Y-co would take the other from the default
 * E-over-Y (Y-su 1500 left the coating at E_co/1000 = 200 MPa): both or
 * neither.  Y-co alone describes a coating too.  A homogeneous sphere
 * takes Y-su alone. */
static void test_yield_pair(void **state)
{
    (void)state;
    char args[512];
    expect_fail("formulas --Y-su 1500 --t-over-R 0.01", "Y-su = 1500 given without Y-co",
                "give the coating's yield strength too");
    expect_fail("formulas --Y-su 1500 --t-mm 0.1", "Y-su = 1500 given without Y-co",
                "(t = 0.1 mm)");
    expect_fail("formulas --Y-su 1500 --E-ratio 2", "Y-su = 1500 given without Y-co",
                "(E-ratio = 2)");
    expect_fail("formulas --Y-su 1500 --nu-co 0.25", "Y-su = 1500 given without Y-co", NULL);
    expect_fail("formulas --Y-co 7000 --t-over-R 0.01 --E-ratio 2", "Y-co = 7000 given without "
                "Y-su", "give the substrate's yield strength too");
    expect_fail("formulas --Y-co 7000", "Y-co = 7000 given without Y-su", NULL);
    expect_fail("asperity --mesh 0 --delta 1 --t-over-R 0.025 --E-ratio 2 --Y-su 1500",
                "Y-su = 1500 given without Y-co", NULL);
    expect_fail("halfspace --delta 0.5 --E-ratio 2 --Y-su 325", "Y-su = 325 given without Y-co",
                NULL);
    write_ini("t-over-R = 0.01\nE-ratio = 2\nY-su = 1500\n");
    snprintf(args, sizeof args, "formulas --config %s", ini);
    expect_fail(args, "Y-su = 1500 given without Y-co", NULL);
    /* both, from the file and the command line; neither; or no coating */
    snprintf(args, sizeof args, "formulas --config %s --Y-co 7000 --json", ini);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    assert_true(cli_jnum(out, "Y_su_MPa") == 1500 && cli_jnum(out, "Y_co_MPa") == 7000);
    assert_int_equal(run("formulas --t-over-R 0.01 --E-ratio 2 --E-over-Y 500 --json", 1, out,
                         sizeof out), 0);
    assert_true(cli_jnum(out, "Y_su_MPa") == 400 && cli_jnum(out, "Y_co_MPa") == 800);
    assert_int_equal(run("formulas --Y-su 325 --json", 1, out, sizeof out), 0);
    assert_true(cli_jnum(out, "Y_su_MPa") == 325);
}

static void test_csv(void **state)
{
    (void)state;
    assert_int_equal(run("formulas --csv --sweep-t-over-R 0.005,0.025,0.05 --sweep-E-ratio 2,4", 1, out,
                         sizeof out), 0);
    int lines = 0;
    for (const char *c = out; *c; c++) lines += (*c == '\n');
    assert_int_equal(lines, 1 + 6);
    assert_non_null(strstr(out, "\n0.005,4,"));
    assert_null(strstr(out, "nan"));
}

/* stiction halfspace: bad values name the option and its range; the JSON
 * reports the reference (the WSP sphere at 0.5 wc on a coarse grid). */
static void test_halfspace(void **state)
{
    (void)state;
    const char *w = "halfspace --R 10.5 --E-su 74000 --nu 0.33 --Y-su 325";
    char args[512];
    expect_fail_on(w, "--delta 0.5 --cells 8", "cells = '8'", "[16, 4096]");
    expect_fail_on(w, "--delta 0.5 --cells 64.5", "cells = '64.5'", "whole number");
    expect_fail_on(w, "--delta 0.5 --span 9", "span = 9", "[1.05, 4]");
    expect_fail_on(w, "--delta -1", "delta = -1", "> 0");
    expect_fail_on(w, "--delta 0.5 --delta-mm 0.001", "one of --delta and --delta-mm", NULL);
    /* (with a coating, Y-su alone is refused first, by the common options) */
    expect_fail_on(w, "--Y-co 325 --delta 0.5 --t-over-R 0.01", "t-over-R = 0.01", "homogeneous");
    expect_fail_on(w, "--delta 0.5 --t-over-R 0.01", "Y-su = 325 given without Y-co", NULL);
    snprintf(args, sizeof args, "%s --delta 0.5 --cells 64 --json", w);
    assert_int_equal(run(args, 1, out, sizeof out), 0);
    assert_json(out);
    assert_true(fabs(cli_jnum(out, "P0_N") / cli_jnum(out, "P_hertz_N") - 1) < 1e-3);
    assert_true(cli_jnum(out, "area_growth") > 0.02 && cli_jnum(out, "area_growth") < 0.08);
    assert_true(cli_jnum(out, "a_trail_over_a0") > cli_jnum(out, "a_lead_over_a0"));
    assert_true(fabs(cli_jnum(out, "tau_c_MPa") - 325 / sqrt(3.0)) < 1e-6);
    assert_true(cli_jnum(out, "mu_s") > cli_jnum(out, "mu_s_no_growth"));
}

/* The BLAS kernels (asp_blas_kernels_get): the library reports the ones in
 * use, and the CLI, started without OPENBLAS_CORETYPE, runs the fastest this
 * CPU supports where OpenBLAS fell back to its generic ones; with the
 * variable set it keeps it.  The CLI's part needs an x86-64 OpenBLAS that
 * picks its kernels at run time (DYNAMIC_ARCH, as Debian builds it). */
static void test_blas_kernels(void **state)
{
    (void)state;
    asp_blas_kernels k;
    asp_blas_kernels_get(&k);
    printf("# BLAS: %s; kernels %s, suggested '%s'\n", k.config, k.in_use, k.suggested);
    assert_non_null(strstr(k.config, "OpenBLAS"));
    assert_true(k.in_use[0] != '\0');
    assert_int_equal(run("--version", 1, out, sizeof out), 0);
    assert_non_null(strstr(out, "BLAS: OpenBLAS"));
#if defined(__x86_64__) && defined(__GNUC__)
    if (!strstr(k.config, "DYNAMIC_ARCH")) skip();
    char cmd[PATH_MAX + 64];
    snprintf(cmd, sizeof cmd, "env OPENBLAS_CORETYPE=Prescott '%s' --version", cli);
    assert_int_equal(cli_capture(cmd, 1, out, sizeof out), 0);
    assert_non_null(strstr(out, "; kernels Prescott (OPENBLAS_CORETYPE)"));
    /* started without it: never the generic kernels on a CPU with AVX2 */
    snprintf(cmd, sizeof cmd, "env -u OPENBLAS_CORETYPE '%s' --version", cli);
    assert_int_equal(cli_capture(cmd, 1, out, sizeof out), 0);
    const char *kern = strstr(out, "; kernels ");
    assert_non_null(kern);
    printf("# started without OPENBLAS_CORETYPE: %s", kern + 2);
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2")) assert_null(strstr(kern, "kernels Prescott"));
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_common_values),
        cmocka_unit_test(test_bad_placements), cmocka_unit_test(test_bad_syntax),
        cmocka_unit_test(test_bad_delta),         cmocka_unit_test(test_bad_config),
        cmocka_unit_test(test_config_directory),  cmocka_unit_test(test_suggestions),
        cmocka_unit_test(test_thickness_mm),      cmocka_unit_test(test_yield_pair),
        cmocka_unit_test(test_output_file),       cmocka_unit_test(test_json_coated),
        cmocka_unit_test(test_json_uncoated),     cmocka_unit_test(test_config_override),
        cmocka_unit_test(test_csv),               cmocka_unit_test(test_halfspace),
        cmocka_unit_test(test_curve_3d_graded),  cmocka_unit_test(test_ignored_keys),
        cmocka_unit_test(test_formulas_range_warnings), cmocka_unit_test(test_help_layout),
        cmocka_unit_test(test_blas_kernels),
    };
    return cmocka_run_group_tests_name("cli", tests, find_cli, cleanup);
}
