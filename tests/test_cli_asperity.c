/* `stiction asperity` from a C caller: the runs the CLI makes are library
 * calls (include/stiction/asperity.h: asp_options_for_curve, asp_curve_run,
 * asp_options_for_shear, asp_shear_preload), so a program that sets the same
 * materials and options gets every number the CLI prints, digit for digit:
 * an axisymmetric stick curve (elastic node entries sampled, loaded on past
 * its end), a 3D slip curve (graded core), a 3D elastic point (Hertz, shells
 * not coarsened) and a load-controlled shear run, alone and as member 0 of an
 * ensemble.
 * Coarse meshes and one thread keep each pair of runs to seconds.
 *
 * The binary is $STICTION_CLI if set, else ../bin/stiction relative to this
 * test program. */
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cmocka.h>

#include "cli_util.h"
#include "stiction/asperity.h"
#include "stiction/formulas.h"

static char cli[PATH_MAX];
static char out[1 << 16];

static int find_cli(void **state)
{
    (void)state;
    if (cli_locate(cli, sizeof cli) != 0) return -1;
    if (access(cli, X_OK) != 0) {
        fprintf(stderr, "test_cli_asperity: no executable CLI at '%s' (build it, or set "
                        "STICTION_CLI)\n", cli);
        return -1;
    }
    return 0;
}

/* "cli asperity ARGS --json" into out; fails the test on a non-zero exit. */
static void run_json(const char *args)
{
    char cmd[PATH_MAX + 1024];
    snprintf(cmd, sizeof cmd, "'%s' asperity %s --threads 1 --json", cli, args);
    int rc = cli_capture(cmd, 1, out, sizeof out);
    if (rc != 0) fail_msg("'%s' exited %d", cmd, rc);
    assert_json(out);
}

/* The n-th "key" of the CLI's JSON and the C caller's value print alike
 * (the CLI writes %.10g; null is NaN). */
static void same(const char *key, int n, double mine)
{
    char a[64], b[64];
    double cli_v = cli_jnum_at(out, key, n);
    snprintf(a, sizeof a, "%.10g", cli_v);
    snprintf(b, sizeof b, "%.10g", mine);
    if (strcmp(a, b) != 0 && !(isnan(cli_v) && isnan(mine)))
        fail_msg("%s[%d]: CLI %s, C caller %s", key, n, a, b);
}

/* A curve's points against the CLI's JSON array. */
static void same_curve(const asp_curve_point *pts, int n, const stc_critical *c)
{
    for (int i = 0; i < n; i++) {
        const asp_curve_point *q = &pts[i];
        assert_int_equal(q->status, STC_OK);
        same("delta_mm", i, q->pt.delta);
        same("P_N", i, q->pt.P);
        same("P_smooth_N", i, q->P_smooth);
        same("A_mm2", i, q->pt.A);
        same("increments", i, q->pt.increments);
        same("newton_iterations", i, q->pt.newton_iterations);
        same("delta_c1_over_omega_c_su", i,
             q->yield[1].reached ? q->yield[1].delta / c->omega_c : NAN);
        same("delta_c2_over_omega_c_su", i,
             q->yield[0].reached ? q->yield[0].delta / c->omega_c : NAN);
        printf("  point %d: delta %.4g mm, P %.10g N, P_smooth %.10g N, %d increments\n", i,
               q->pt.delta, q->pt.P, q->P_smooth, q->pt.increments);
    }
}

static void curve(const stc_params *p, asp_options *o, const double *w, int n,
                  asp_curve_point *pts, asp_curve_result *res, stc_critical *c)
{
    stc_material su;
    stc_params_materials(p, &su, NULL);
    assert_int_equal(stc_critical_eval(&su, p->R, c), STC_OK);
    double d[8];
    for (int i = 0; i < n; i++) d[i] = w[i] * c->omega_c;
    asp_options_for_curve(o, n);
    assert_int_equal(asp_curve_run(p, o, d, n, NULL, NULL, pts, res), STC_OK);
    assert_int_equal(res->n, n);
}

/* The README's coated stick curve on the coarse mesh: sample_elastic set,
 * the tail loaded (P_smooth at 30 wc averages both sides). */
static void test_axisym_stick_curve(void **state)
{
    (void)state;
    stc_params p;
    stc_params_default(&p);
    p.t_over_R = 0.025, p.E_ratio = 2.0;
    assert_int_equal(stc_params_resolve(&p), STC_OK);
    asp_options o;
    asp_options_default(&o);
    o.contact = ASP_CONTACT_STICK, o.mesh_level = 0, o.threads = 1;
    const double w[3] = {1, 10, 30};
    asp_curve_point pts[3];
    asp_curve_result res;
    stc_critical c;
    curve(&p, &o, w, 3, pts, &res, &c);
    assert_int_equal(o.sample_elastic, 1);
    assert_int_equal(o.grade_3d, 0);
    assert_int_equal(res.info.dim, 2);
    assert_int_equal(res.tail, STC_OK);
    run_json("--t-over-R 0.025 --E-ratio 2 --contact stick --delta 1,10,30 --mesh 0");
    same_curve(pts, 3, &c);
    same("dofs", 0, res.info.dofs);
}

/* A 3D slip curve: the graded core sized to the smallest contact. */
static void test_3d_curve(void **state)
{
    (void)state;
    stc_params p;
    stc_params_default(&p);
    asp_options o;
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D, o.elements_per_contact = 3.0, o.threads = 1;
    const double w[2] = {1, 3};
    asp_curve_point pts[2];
    asp_curve_result res;
    stc_critical c;
    curve(&p, &o, w, 2, pts, &res, &c);
    assert_int_equal(o.grade_3d, 1);
    assert_int_equal(o.sample_elastic, 0);
    assert_true(res.info.a_min < res.info.a_max); /* graded: every contact resolved */
    run_json("--model 3d --delta 1,3 --elements-per-contact 3");
    same_curve(pts, 2, &c);
    same("dofs", 0, res.info.dofs);
}

/* A homogeneous sphere (both layers alike) and its material. */
static void homogeneous(stc_params *p, double R, double E, double nu, double Y, stc_material *su)
{
    stc_params_default(p);
    p->R = R, p->E_su = E, p->nu = nu, p->Y_su = p->Y_co = Y;
    assert_int_equal(stc_params_resolve(p), STC_OK);
    stc_params_materials(p, su, NULL);
}

/* A 3D point of the normal step alone, elastic (Hertz, a/R = 0.003, the
 * default 3D mesh): the policy leaves its shells uncoarsened, and P is
 * within 0.5 % of Hertz (measured +0.316 %; the converged model +0.174 %,
 * its base fixed at depth R; with the shear runs' coarsening +0.500 %). */
static void test_3d_hertz_point(void **state)
{
    (void)state;
    stc_params p;
    stc_material su;
    homogeneous(&p, 10.09, 74000.0, 0.32, 70000.0, &su);
    double d = 0.003 * 0.003 * p.R;
    stc_hertz h;
    assert_int_equal(stc_hertz_eval(&su, p.R, d, &h), STC_OK);
    asp_options o;
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D, o.threads = 1;
    asp_options_for_curve(&o, 1);
    assert_int_equal(o.shell_coarsen, 0); /* a 3D point: the shells not coarsened */
    assert_int_equal(o.grade_3d, 0);
    asp_options set = o;
    set.shell_coarsen = 2; /* unless the caller set it */
    asp_options_for_curve(&set, 1);
    assert_int_equal(set.shell_coarsen, 2);
    asp_curve_point pt;
    asp_curve_result res;
    assert_int_equal(asp_curve_run(&p, &o, &d, 1, NULL, NULL, &pt, &res), STC_OK);
    assert_int_equal(pt.status, STC_OK);
    printf("  3D Hertz a/R = 0.003: P/P_H - 1 = %+.3f %%, %d DOFs\n", 100 * (pt.pt.P / h.P - 1),
           res.info.dofs);
    assert_true(fabs(pt.pt.P / h.P - 1) < 0.005);
    char args[256];
    snprintf(args, sizeof args,
             "--model 3d --R 10.09 --E-su 74000 --nu 0.32 --Y-su 70000 --delta-mm %.17g", d);
    run_json(args);
    same("P_N", 0, pt.pt.P);
    same("dofs", 0, res.info.dofs);
}

/* Load control then the ramp (the stiffness criterion at alpha 0.9 ends
 * it after a few increments): the mesh sized from the Hertz guess and the
 * load found within 1e-3 as the CLI does. */
static void test_shear_load(void **state)
{
    (void)state;
    stc_params p;
    stc_material su;
    stc_critical c;
    homogeneous(&p, 10.5, 74000.0, 0.33, 325.0, &su);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    asp_options o;
    asp_options_default(&o);
    o.elements_per_contact = 4.0, o.threads = 1;
    assert_int_equal(asp_options_for_shear(&o), STC_OK);
    assert_int_equal(o.geom, ASP_GEOM_3D);
    asp_shear_options so;
    asp_shear_options_default(&so);
    so.criterion = ASP_SHEAR_CRIT_STIFFNESS, so.alpha = 0.9;
    asp_solver *s = NULL;
    asp_point pt;
    assert_int_equal(asp_shear_preload(&p, &o, 0.0, 0.3 * c.P_c, &s, &pt), STC_OK);
    asp_shear_result r;
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_OK);
    asp_solver_destroy(&s);
    printf("  load 0.3 Pc: delta %.6g mm, P %.10g N; mu_s %.10g after %d increments\n",
           pt.delta, pt.P, r.mu_s, r.increments);
    run_json("--R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --Y-co 325 --load 0.3 "
             "--criterion stiffness --alpha 0.9 --elements-per-contact 4");
    same("delta_mm", 0, pt.delta);
    same("P_N", 0, pt.P);
    same("increments", 0, pt.increments);
    same("Q_max_N", 0, r.Q_max);
    same("mu_s", 0, r.mu_s);
    same("mu_s_err", 0, r.mu_s_err);
    assert_non_null(strstr(out, r.q_rising ? "\"Q_still_rising\": true"
                                           : "\"Q_still_rising\": false"));
    same("P_at_slide_N", 0, r.P_slide);
    same("shear_increments", 0, r.increments);
    /* under --placements 2 member 0 is this run and sets the others' delta */
    run_json("--R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --Y-co 325 --load 0.3 "
             "--criterion stiffness --alpha 0.9 --elements-per-contact 4 --placements 2");
    same("load_P_over_P_c", 0, 0.3);
    same("delta_mm", 0, pt.delta);
    same("P_preload_N", 0, pt.P);
    same("mu_s", 1, r.mu_s); /* members[0] */
    /* refined from the one run (--placements-max): its member 0 is the run;
     * a threshold above the run's error keeps it alone */
    run_json("--R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --Y-co 325 --load 0.3 "
             "--criterion stiffness --alpha 0.9 --elements-per-contact 4 --placements-max 2 "
             "--refine-err 0.001");
    same("placements", 0, 2);
    same("mu_s", 1, r.mu_s);
    run_json("--R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --Y-co 325 --load 0.3 "
             "--criterion stiffness --alpha 0.9 --elements-per-contact 4 --placements-max 2 "
             "--refine-err 0.5");
    same("placements", 0, 1);
    same("mu_s", 0, r.mu_s);
}

/* A short shear run with a few ramp points, for the progress tests. */
static const char *const PROGRESS_ARGS =
    "asperity --shear --threads 1 --R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --Y-co 325 "
    "--load 0.3 --criterion stiffness --alpha 0.9 --elements-per-contact 4";

/* A shear run shows its phases and the ramp's progress on a terminal
 * (stderr), and nothing of it when stderr is a file or a pipe.  The
 * terminal is script(1)'s pseudo-terminal; without script, or a pseudo-terminal
 * for it, the test skips. */
static void test_shear_progress(void **state)
{
    (void)state;
    if (access("/usr/bin/script", X_OK) != 0 ||
        system("/usr/bin/script -q -e -c true /dev/null >/dev/null 2>&1") != 0)
        skip(); /* no script(1), or no pseudo-terminal for it */
    const char *args = PROGRESS_ARGS;
    char cmd[PATH_MAX + 1024];
    snprintf(cmd, sizeof cmd, "/usr/bin/script -q -e -c \"'%s' %s\" /dev/null", cli, args);
    assert_int_equal(cli_capture(cmd, 1, out, sizeof out), 0);
    assert_non_null(strstr(out, "normal step (3D mesh, load and solve) ... done"));
    assert_non_null(strstr(out, "shear ramp: point"));
}

/* Off a terminal (a log, a pipe) a shear run prints a ramp line at most every
 * --progress-every seconds: none in a run shorter than the default 60 s, one
 * per ramp point when the interval is shorter than a point. */
static void test_shear_progress_log(void **state)
{
    (void)state;
    const char *args = PROGRESS_ARGS;
    char cmd[PATH_MAX + 1024];
    snprintf(cmd, sizeof cmd, "'%s' %s", cli, args);
    assert_int_equal(cli_capture(cmd, 2, out, sizeof out), 0);
    assert_null(strstr(out, "shear ramp"));
    assert_null(strstr(out, "normal step (3D mesh"));
    snprintf(cmd, sizeof cmd, "'%s' %s --progress-every 1e-6", cli, args);
    assert_int_equal(cli_capture(cmd, 2, out, sizeof out), 0);
    assert_non_null(strstr(out, "stiction asperity: shear ramp: point 1, ux/wc 0,"));
    assert_non_null(strstr(out, "stiction asperity: shear ramp: point 2,"));
    assert_null(strchr(out, '\r')); /* lines, not a line rewritten in place */
}

/* What the policy functions refuse, by name. */
static void test_refusals(void **state)
{
    (void)state;
    asp_options o;
    asp_options_default(&o);
    o.geom = ASP_GEOM_AXISYM;
    assert_int_equal(asp_options_for_shear(&o), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "model = 'axisym'"));
    asp_options_default(&o);
    asp_options_for_curve(&o, 1); /* one point: nothing changes */
    assert_int_equal(o.sample_elastic, 0);
    assert_int_equal(o.grade_3d, 0);
    assert_int_equal(o.shell_coarsen, -1);
    stc_params p;
    stc_params_default(&p);
    asp_solver *s = (asp_solver *)&p; /* set to NULL on failure */
    asp_point pt;
    assert_int_equal(asp_shear_preload(&p, &o, 1e-4, 1.0, &s, &pt), STC_EINVAL);
    assert_null(s);
    assert_non_null(strstr(stc_errmsg(), "give one of them"));
    assert_int_equal(asp_shear_preload(&p, &o, 0.0, 0.0, &s, &pt), STC_EINVAL);
    asp_curve_point q;
    asp_curve_result res;
    double d = 0.2 * p.R; /* beyond the small-strain limit: create fails */
    assert_int_equal(asp_curve_run(&p, &o, &d, 1, NULL, NULL, &q, &res), STC_EINVAL);
    assert_int_equal(res.n, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_shear_progress_log),
        cmocka_unit_test(test_axisym_stick_curve),
        cmocka_unit_test(test_3d_curve),
        cmocka_unit_test(test_3d_hertz_point),
        cmocka_unit_test(test_shear_load),
        cmocka_unit_test(test_shear_progress),
    };
    return cmocka_run_group_tests(tests, find_cli, NULL);
}
