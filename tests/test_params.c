/* Common parameters: defaults, parsing, every invalid-input path. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <unistd.h>
#include <cmocka.h>

#include "stiction/params.h"
#include "tmp_util.h"

static void test_defaults(void **state)
{
    (void)state;
    stc_params p;
    stc_material su, co;
    stc_params_default(&p);
    assert_int_equal(stc_params_validate(&p), STC_OK);
    stc_params_materials(&p, &su, &co);
    assert_true(su.E == 200000.0 && su.Y == 200.0 && su.nu == 0.32);
    assert_true(co.E == 200000.0 && co.Y == 200.0 && co.nu == 0.32);
    assert_true(p.R == 10.0 && p.t_over_R == 0.0);
}

static void test_set_and_derive(void **state)
{
    (void)state;
    stc_params p;
    stc_material su, co;
    stc_params_default(&p);
    assert_int_equal(stc_params_set(&p, "--E-ratio", "4"), STC_OK);
    assert_int_equal(stc_params_set(&p, "t_over_R", "0.025"), STC_OK);
    assert_int_equal(stc_params_set(&p, "nu-co", "0.25"), STC_OK);
    assert_int_equal(stc_params_set(&p, "Y-su", "300"), STC_OK);
    stc_params_materials(&p, &su, &co);
    assert_true(co.E == 800000.0 && co.Y == 800.0 && co.nu == 0.25);
    assert_true(su.Y == 300.0);
    assert_true(fabs(stc_params_t(&p) - 0.25) < 1e-15);
}

/* Each invalid value must fail with a message naming key and value. */
static void expect_bad(const char *key, const char *value, const char *needle)
{
    stc_params p;
    stc_params_default(&p);
    stc_error_clear();
    assert_int_equal(stc_params_set(&p, key, value), STC_EINVAL);
    if (strstr(stc_errmsg(), needle) == NULL)
        fail_msg("message '%s' lacks '%s'", stc_errmsg(), needle);
}

static void test_invalid_values(void **state)
{
    (void)state;
    expect_bad("R", "-1", "R = -1: must be > 0");
    expect_bad("R", "0", "R = 0");
    expect_bad("R", "nan", "R = 'nan': must be a finite number");
    expect_bad("R", "inf", "must be a finite number");
    expect_bad("R", "", "missing value");
    expect_bad("R", "10mm", "R = '10mm': not a number");
    expect_bad("t-over-R", "-0.01", "t-over-R = -0.01");
    expect_bad("t-over-R", "1", "must be in [0, 1)");
    expect_bad("E-su", "0", "E-su = 0");
    expect_bad("E-ratio", "-2", "E-ratio = -2");
    expect_bad("E-over-Y", "1", "E-over-Y = 1: must be > 1");
    expect_bad("Y-su", "0", "Y-su = 0");
    expect_bad("Y-co", "-5", "Y-co = -5");
    expect_bad("nu", "0.5", "nu = 0.5: must be in (-1, 0.5)");
    expect_bad("nu-co", "-1", "nu-co = -1");
}

static void test_unknown_key(void **state)
{
    (void)state;
    stc_params p;
    stc_params_default(&p);
    assert_int_equal(stc_params_set(&p, "radius", "3"), STC_EUNSUPPORTED);
}

static void test_validate_cross(void **state)
{
    (void)state;
    stc_params p;
    stc_params_default(&p);
    assert_int_equal(stc_params_set(&p, "Y-su", "300000"), STC_OK);
    assert_int_equal(stc_params_validate(&p), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "Y-su = 300000"));
    /* each value in its own range, but together not representable (found
     * by test_fuzz): Pc overflows, ωc underflows, Eco overflows */
    static const char *const bad[][2] = {{"R", "1e308"}, {"E-over-Y", "1e308"},
                                         {"R", "1e-200"}, {"E-ratio", "1e305"}};
    static const char *const says[] = {"R = 1e+308 mm", "Y = 2e-303 MPa", "P_c = 0 N",
                                       "E-ratio = 1e+305"};
    for (int i = 0; i < 4; i++) {
        stc_params_default(&p);
        assert_int_equal(stc_params_set(&p, "t-over-R", "0.025"), STC_OK);
        assert_int_equal(stc_params_set(&p, bad[i][0], bad[i][1]), STC_OK);
        if (i == 3) assert_int_equal(stc_params_set(&p, "E-su", "1e10"), STC_OK);
        assert_int_equal(stc_params_validate(&p), STC_EINVAL);
        printf("  %s = %s: %s\n", bad[i][0], bad[i][1], stc_errmsg());
        assert_non_null(strstr(stc_errmsg(), says[i]));
        assert_non_null(strstr(stc_errmsg(), "not representable"));
    }
}

/* t-mm: the thickness in mm becomes t/R with the final R, whichever came
 * first; never together with t-over-R; t/R < 1.  And the yield pair. */
static void test_resolve_thickness(void **state)
{
    (void)state;
    stc_params p;
    stc_params_default(&p);
    assert_int_equal(stc_params_set(&p, "t-mm", "0.125"), STC_OK);
    assert_int_equal(stc_params_set(&p, "R", "5"), STC_OK);
    assert_int_equal(stc_params_resolve(&p), STC_OK);
    assert_true(p.t_over_R == 0.025 && p.t_mm_set && !p.t_over_R_set);
    assert_int_equal(stc_params_resolve(&p), STC_OK); /* idempotent */
    assert_true(p.t_over_R == 0.025);
    assert_true(fabs(stc_params_t(&p) - 0.125) < 1e-16);
    assert_int_equal(stc_params_set(&p, "t-over-R", "0.025"), STC_OK);
    stc_error_clear();
    assert_int_equal(stc_params_resolve(&p), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "t-mm = 0.125 conflicts with t-over-R = 0.025"));
    stc_params_default(&p);
    assert_int_equal(stc_params_set(&p, "t-mm", "10"), STC_OK);
    assert_int_equal(stc_params_resolve(&p), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "t-mm = 10 with R = 10 mm: t/R = 1 must be < 1"));
    /* one yield strength of two layers: refused; of one layer: taken */
    stc_params_default(&p);
    assert_int_equal(stc_params_set(&p, "Y-su", "1500"), STC_OK);
    assert_int_equal(stc_params_resolve(&p), STC_OK);
    assert_int_equal(stc_params_set(&p, "t-mm", "0.1"), STC_OK);
    assert_int_equal(stc_params_resolve(&p), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "Y-su = 1500 given without Y-co"));
    assert_int_equal(stc_params_set(&p, "Y-co", "7000"), STC_OK);
    assert_int_equal(stc_params_resolve(&p), STC_OK);
    /* the key table lists it with the others */
    int found = 0, n = 0;
    for (; stc_params_key(n); n++) found += strcmp(stc_params_key(n), "t-mm") == 0;
    assert_true(found == 1 && n == 10 && stc_params_key(-1) == NULL);
}

static stc_status collect(void *user, const char *section, const char *key,
                          const char *value)
{
    (void)section;
    return stc_params_set(user, key, value) == STC_EUNSUPPORTED
               ? stc_error(STC_EINVAL, __FILE__, __LINE__, "unknown key '%s'", key)
               : stc_errmsg()[0] ? STC_EINVAL : STC_OK;
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_ini(void **state)
{
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/stiction-test-XXXXXX.ini", test_tmpdir());
    stc_params p;
    stc_params_default(&p);
    int fd = mkstemps(path, 4);
    assert_true(fd >= 0);
    close(fd);
    write_file(path, "; comment\n[material]\nE_ratio = 2\nt-over-R = 0.05\n");
    stc_error_clear();
    assert_int_equal(stc_ini_load(path, collect, &p), STC_OK);
    assert_true(p.E_ratio == 2.0 && p.t_over_R == 0.05);

    write_file(path, "R = 3\nthis line is not ini\n");
    stc_error_clear();
    assert_int_equal(stc_ini_load(path, collect, &p), STC_EFORMAT);
    assert_non_null(strstr(stc_errmsg(), "line 2"));

    write_file(path, "R = -3\nnu = 0.3\n");
    stc_error_clear();
    assert_int_equal(stc_ini_load(path, collect, &p), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "R = -3"));

    write_file(path, "colour = blue\n");
    stc_error_clear();
    assert_int_equal(stc_ini_load(path, collect, &p), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "colour"));
    remove(path);

    assert_int_equal(stc_ini_load("/nonexistent/x.ini", collect, &p), STC_EIO);
    assert_non_null(strstr(stc_errmsg(), "/nonexistent/x.ini"));
    /* a directory opens for reading and reads as nothing: refused by name */
    assert_int_equal(stc_ini_load("/tmp", collect, &p), STC_EIO);
    assert_non_null(strstr(stc_errmsg(), "config = '/tmp': is a directory"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),       cmocka_unit_test(test_set_and_derive),
        cmocka_unit_test(test_invalid_values), cmocka_unit_test(test_unknown_key),
        cmocka_unit_test(test_validate_cross), cmocka_unit_test(test_ini),
        cmocka_unit_test(test_resolve_thickness),
    };
    return cmocka_run_group_tests_name("params", tests, NULL, NULL);
}
