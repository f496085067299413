/* Tangential step of the asperity solver: coarse versions of the checks
 * whose full-size forms are in tools/validate-shear.py.
 *
 * One shared run (group setup): the homogeneous Wu-Shi-Polycarpou sphere
 * (E 74 GPa, ν 0.33, Y 325 MPa, R' 10.5 mm), slip normal step to
 * ω = 0.5 ωc — still elastic, so Cattaneo-Mindlin applies — then the ramp
 * with the shear criterion, 3D mesh level 0.  Checked on it: the initial
 * tangential stiffness against Mindlin, the full-slip plateau against
 * τc × contact area, μs against the WSP fit, and Q from the friction forces
 * against Q from the base reactions at every point.  Then option errors
 * and the CLI (errors, JSON keys, output files). */
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
#include "data_util.h"
#include "stiction/asperity.h"
#include "stiction/formulas.h"
#include "stiction/halfspace.h"
#include "tmp_util.h"

enum { MAXPT = 256 };

typedef struct shared {
    stc_params p;
    stc_material m;
    stc_critical c;
    asp_point pt;               /* end of the normal step */
    asp_shear_result res;
    asp_shear_point pts[MAXPT]; /* the ramp */
    int n;
    stc_status st;
} shared;

static shared R, RN, RE; /* the default junction rule (footprint), ASP_JUNCTION_NODES, elastic */

static void wsp_params(stc_params *p)
{
    stc_params_default(p);
    p->R = 10.5, p->E_su = 74000.0, p->nu = 0.33, p->Y_su = p->Y_co = 325.0;
}

/* Hertz δ for load P on a rigid flat (Johnson 1985 §4.2). */
static double hertz_delta(double P, double E, double nu, double R)
{
    double Es = E / (1.0 - nu * nu);
    return pow(3.0 * P / (4.0 * Es * sqrt(R)), 2.0 / 3.0);
}

static int keep(void *ctx, const asp_shear_point *pt)
{
    shared *r = ctx;
    if (r->n < MAXPT) r->pts[r->n++] = *pt;
    return 0;
}

/* elastic = 1: the same δ and τc (Y/√3 of the WSP sphere), but the sphere
 * stays elastic (Y just below E), for the half-space reference.  so: the
 * ramp's options (its τc is set here for the elastic case). */
static int run_case_so(shared *r, asp_shear_options *so, int elastic)
{
    asp_options o;
    asp_solver *s = NULL;
    wsp_params(&r->p);
    stc_params_materials(&r->p, &r->m, NULL);
    if (stc_critical_eval(&r->m, r->p.R, &r->c) != STC_OK) return -1;
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D, o.mesh_level = 0;
    o.threads = 1; /* make check runs two test programs at a time */
    double delta = 0.5 * r->c.omega_c;
    if (elastic) {
        so->tau_c = r->m.Y / sqrt(3.0);
        r->p.Y_su = r->p.Y_co = 0.95 * r->p.E_su;
    }
    if (asp_solver_create(&r->p, &o, delta, &s) != STC_OK) return -1;
    if (asp_solver_load(s, delta, &r->pt) != STC_OK) return asp_solver_destroy(&s), -1;
    r->st = asp_solver_shear(s, so, keep, r, &r->res);
    printf("# WSP 0.5 wc, level 0, junction %s: %d ramp points, %d Newton iterations, "
           "%d factorizations, %.1f s (%s)\n",
           so->junction == ASP_JUNCTION_NODES ? "nodes" : "footprint", r->n,
           r->res.newton_iterations, r->res.factorizations, r->res.wall_s, r->res.reason);
    asp_solver_destroy(&s);
    return 0;
}

static int run_case_map(shared *r, asp_junction junction, int elastic, asp_return_map map)
{
    asp_shear_options so;
    asp_shear_options_default(&so);
    so.junction = junction;
    so.return_map = map;
    so.foot_rows = 0.0; /* the three axis lines: the shared runs' numbers below */
    return run_case_so(r, &so, elastic);
}

static int run_case_mat(shared *r, asp_junction junction, int elastic)
{
    return run_case_map(r, junction, elastic, ASP_RETURN_RADIAL);
}

static int run_case(shared *r, asp_junction junction) { return run_case_mat(r, junction, 0); }

static int run_shared(void **state)
{
    (void)state;
    return run_case(&R, ASP_JUNCTION_FOOTPRINT);
}

static void test_ramp_converged(void **state)
{
    (void)state;
    assert_int_equal(R.st, STC_OK);
    assert_true(R.res.converged);
    assert_true(R.n >= 4 && R.n < MAXPT);
    assert_true(R.pts[0].ux == 0.0 && fabs(R.pts[0].Q) < 1e-9 * R.res.Q_max);
    assert_true(R.res.tau_c == R.m.Y / sqrt(3.0)); /* default: Y/√3 of the sphere */
    assert_true(R.res.ux_slide > 0.0 && R.res.Q_max > 0.0);
}

/* Cattaneo-Mindlin: initial tangential stiffness of an elastic sphere on a
 * rigid flat, K_T0 = 8 G a / (2 - ν) (Mindlin 1949; Johnson 1985 §7.2),
 * with a from the FE normal step.  The first increment (5 % of the
 * elastic slide distance) is fully stuck.  Measured: -3.2 % at level 0
 * (-0.7 % for a/R = 0.0013 with E/Y = 1000): the penalty springs in series
 * (≈ 8h/(πκ(2-ν)a) = 0.3 %), the compliance of the finite sphere above the
 * fixed base (≈ 8a/((2-ν)πR) = 1.1 % here, a/R = 0.0072) and the coarse
 * mesh (5.5 elements across a).  Tolerance 5 %. */
static void test_mindlin_stiffness(void **state)
{
    (void)state;
    double G = R.m.E / (2.0 * (1.0 + R.m.nu));
    double K0 = 8.0 * G * R.res.a0 / (2.0 - R.m.nu);
    double K1 = R.pts[1].Q / R.pts[1].ux;
    printf("# K_T1 / K_T0(Mindlin) - 1 = %+.2f %% (slip fraction %.3g)\n", 100 * (K1 / K0 - 1),
           R.pts[1].slip_frac);
    assert_true(R.pts[1].slip_frac == 0.0);
    assert_true(fabs(K1 / K0 - 1.0) < 0.05);
}

/* Full slip: every contact node at τc, so Q = τc × contact area; the areas
 * are the tributary areas over the contact's footprint, the disc of the
 * normal step (Σ = π a0² to 3e-4) grown under shear (junction rule
 * footprint, shear.c).  Measured: last point Q / (τc A) - 1 = -0.04 % (the
 * areas are updated after the increment), Q_max / (τc π a0²) - 1 = +2.85 %
 * (contact growth; +0.8 % with the nodes rule, test_junction_bracket).
 * The 3 % bound on the growth guards the reading, it is not the physics: the
 * half-space reference puts the elastic growth alone at +4.9 % here
 * (test_elastic_growth_bem), which the footprint reads as +2.6 %. */
static void test_full_slip_plateau(void **state)
{
    (void)state;
    const asp_shear_point *l = &R.pts[R.n - 1];
    double tc = R.res.tau_c;
    printf("# full slip: Q/(tau_c A) - 1 = %+.3f %%, Q_max/(tau_c pi a0^2) - 1 = %+.2f %%\n",
           100 * (l->Q / (tc * l->A) - 1), 100 * (R.res.Q_max / (tc * M_PI * R.res.a0 * R.res.a0) - 1));
    assert_true(l->slip_frac >= 0.999);
    assert_true(fabs(l->Q / (tc * l->A) - 1.0) < 5e-3);
    assert_true(fabs(R.res.Q_max / (tc * M_PI * R.res.a0 * R.res.a0) - 1.0) < 0.03);
    /* the plateau is flat: the last increment changed Q by < 1 % */
    assert_true(fabs(l->Q - R.pts[R.n - 2].Q) < 0.01 * R.res.Q_max);
    /* and the flat plateau shows in the stiffness left after inception
     * (measured 0.013; the thin hard coating of docs/design.md §4.4 leaves ~0.2) */
    printf("# KT/KT_1 after inception %.4f\n", R.res.KT_after);
    assert_true(fabs(R.res.KT_after) < 0.05);
}

/* μs = Q_max / P against the WSP fit (within 5 %).
 * Measured at level 0: +3.87 % (+1.33 % with the nodes rule). */
static void test_wsp_mu(void **state)
{
    (void)state;
    double fit = stc_wsp_mu(0.5, NULL);
    printf("# mu_s = %.4f, WSP fit %.4f: %+.2f %%; mu_s(preload) %.4f\n", R.res.mu_s, fit,
           100 * (R.res.mu_s / fit - 1), R.res.mu_s_preload);
    assert_true(fabs(R.res.mu_s / fit - 1.0) < 0.05);
    assert_true(fabs(R.res.mu_s - R.res.Q_max / R.res.P_slide) < 1e-12);
    assert_true(fabs(R.res.mu_s_preload - R.res.Q_max / R.pt.P) < 1e-12);
    assert_true(fabs(R.res.P0 / R.pt.P - 1.0) < 1e-12);
}

/* The shared run is the default single run of the held case wsp-0.5
 * (tools/references.py): against its converged reference, the four-placement
 * ensemble one full mesh refinement finer (data/fe/references.csv, mesh level
 * 1), it must lie within two standard errors, its printed one and the
 * reference's in quadrature (docs/design.md §4.6). */
static void test_converged_reference(void **state)
{
    (void)state;
    enum { MAX = 64 };
    static const char *const cols[] = {"delta_over_omega_c", "t_over_R", "mesh_level", "mu_s",
                                       "mu_s_err"};
    double d[MAX], t[MAX], lv[MAX], mu[MAX], se[MAX], *out[] = {d, t, lv, mu, se};
    int n = data_read_columns("fe/references.csv", 5, cols, out, MAX), k = -1;
    assert_true(n > 0);
    for (int i = 0; i < n; i++)
        if (d[i] == 0.5 && t[i] == 0.0 && lv[i] == 1.0) k = i;
    assert_true(k >= 0);
    double err = R.res.mu_s / mu[k] - 1, band = 2.0 * hypot(R.res.mu_s_err, se[k]);
    printf("# converged reference %.5f +- %.5f: single run %.5f +- %.5f, %+.2f %% (band %.2f %%)\n",
           mu[k], se[k], R.res.mu_s, R.res.mu_s_err, 100 * err, 100 * band / mu[k]);
    assert_true(fabs(R.res.mu_s - mu[k]) <= band);
}

/* The two junction rules (asp_junction) bracket the contact growth: the
 * footprint reads it high on a coarse mesh, F_z/p_m of the nodes that touch
 * reads it low (docs/design.md §4.2), so the nodes rule gives the
 * smaller plateau; both start from the same preload (identical normal
 * step) and reach full slip.  Measured at 0.5 ωc, level 0: Q_max / (τc π
 * a0²) - 1 = +2.85 % (footprint), +0.8 % (nodes). */
static void test_junction_bracket(void **state)
{
    (void)state;
    assert_int_equal(run_case(&RN, ASP_JUNCTION_NODES), 0);
    assert_int_equal(RN.st, STC_OK);
    assert_true(RN.res.converged);
    double tc = R.res.tau_c, A0 = M_PI * R.res.a0 * R.res.a0;
    printf("# junction: Q_max/(tau_c pi a0^2) - 1 = %+.2f %% (footprint), %+.2f %% (nodes)\n",
           100 * (R.res.Q_max / (tc * A0) - 1), 100 * (RN.res.Q_max / (tc * A0) - 1));
    assert_true(RN.res.P0 == R.res.P0 && RN.res.a0 == R.res.a0);
    assert_true(RN.res.Q_max < R.res.Q_max);
    assert_true(RN.res.Q_max > tc * A0 * (1.0 - 1e-3)); /* the contact does not shrink */
    assert_true(RN.pts[RN.n - 1].slip_frac >= 0.999);
}

/* Q from the friction forces = -2 Σ base reactions_x (global equilibrium in
 * x of the half model) at every ramp point. */
static void test_equilibrium(void **state)
{
    (void)state;
    double worst = 0.0;
    for (int i = 1; i < R.n; i++)
        worst = fmax(worst, fabs(R.pts[i].Q - R.pts[i].Q_base) / R.res.Q_max);
    printf("# max |Q - Q_base| / Q_max = %.2e\n", worst);
    assert_true(worst < 1e-6);
}

/* ---- errors ------------------------------------------------------------- */

static void test_errors(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_shear_options so;
    asp_shear_result r;
    asp_solver *s = NULL;
    wsp_params(&p);
    asp_options_default(&o);
    o.mesh_level = 0, o.threads = 1;
    /* axisymmetric: refused, naming the geometry */
    assert_int_equal(asp_solver_create(&p, &o, 1e-3, &s), STC_OK);
    assert_int_equal(asp_solver_shear(s, NULL, NULL, NULL, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "3D"));
    assert_int_equal(r.converged, 0);
    asp_solver_destroy(&s);
    /* 3D, bad options name the parameter; not loaded yet */
    o.geom = ASP_GEOM_3D;
    assert_int_equal(asp_solver_create(&p, &o, 1e-3, &s), STC_OK);
    asp_shear_options_default(&so);
    so.alpha = 1.5;
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "alpha = 1.5"));
    asp_shear_options_default(&so);
    so.tau_c = -2.0;
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "tau-c = -2"));
    asp_shear_options_default(&so);
    so.ramp_refine = 0.5;
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "ramp refine = 0.5"));
    asp_shear_options_default(&so);
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "before the ramp"));
    asp_solver_destroy(&s);
    /* the graded 3D core (a load curve's mesh, here to ~20 ωc) is refused
     * for the ramp */
    o.grade_3d = 1;
    assert_int_equal(asp_solver_create(&p, &o, 2e-2, &s), STC_OK);
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "grade-3d"));
    asp_solver_destroy(&s);
}

/* ---- load control ---------------------------------------------------------- */

/* The WSP sphere, its critical values and level-0 options on one thread. */
static void wsp_setup(stc_params *p, stc_material *m, stc_critical *c, asp_options *o)
{
    wsp_params(p);
    stc_params_materials(p, m, NULL);
    assert_int_equal(stc_critical_eval(m, p->R, c), STC_OK);
    asp_options_default(o);
    o->mesh_level = 0, o->threads = 1;
}

/* asp_solver_load_to_P on the (cheap) axisymmetric model: an elastic Hertz
 * target and one well past yield (P = 20 Pc, slip), each reached within the
 * tolerance; the plastic P(δ) lies below Hertz, so δ exceeds the Hertz δ. */
static void test_load_control(void **state)
{
    (void)state;
    stc_params p;
    stc_material m;
    stc_critical c;
    asp_options o;
    asp_point pt;
    wsp_setup(&p, &m, &c, &o);
    const double X[2] = {0.5, 20.0};
    for (int i = 0; i < 2; i++) {
        asp_solver *s = NULL;
        double P = X[i] * c.P_c, dh = hertz_delta(P, m.E, m.nu, p.R);
        assert_int_equal(asp_solver_create(&p, &o, fmin(2.0 * dh, 0.01 * p.R), &s), STC_OK);
        stc_status st = asp_solver_load_to_P(s, P, 1e-3, &pt);
        if (st) fail_msg("load control to %g Pc: %s", X[i], stc_errmsg());
        printf("# load control P = %g Pc: P/target - 1 = %+.2e, delta/delta_Hertz = %.4f, "
               "%d increments\n", X[i], pt.P / P - 1, pt.delta / dh, pt.increments);
        assert_true(fabs(pt.P / P - 1.0) <= 1e-3);
        assert_true(i == 0 ? fabs(pt.delta / dh - 1.0) < 0.02 : pt.delta > dh);
        /* forward only: a second target below the current load is refused */
        assert_int_equal(asp_solver_load_to_P(s, 0.5 * P, 1e-3, &pt), STC_EINVAL);
        asp_solver_destroy(&s);
    }
}

/* The ensemble under load control: member 0 is the single load-controlled
 * run (asp_shear_preload to P, then the ramp), the other member runs at its
 * interference on a mesh sized as its own, shifted by half a period.  A
 * coarse mesh (4 elements per contact): the mechanics, not the accuracy. */
static void test_placements_load(void **state)
{
    (void)state;
    stc_params p;
    stc_material m;
    stc_critical c;
    asp_options o;
    asp_shear_options so;
    wsp_setup(&p, &m, &c, &o);
    o.geom = ASP_GEOM_3D, o.elements_per_contact = 4.0;
    assert_int_equal(asp_options_for_shear(&o), STC_OK);
    asp_shear_options_default(&so);
    double P = 0.3 * c.P_c;
    asp_placement_result *e = malloc(sizeof *e);
    assert_non_null(e);
    assert_int_equal(asp_shear_placements_preload(&p, &o, &so, 0.1, P, 2, e), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "give one of them"));
    stc_status st = asp_shear_placements_preload(&p, &o, &so, 0.0, P, 2, e);
    if (st) fail_msg("placements under load control: %s", stc_errmsg());
    asp_solver *s = NULL;
    asp_point pt;
    asp_shear_result r;
    assert_int_equal(asp_shear_preload(&p, &o, 0.0, P, &s, &pt), STC_OK);
    assert_int_equal(asp_solver_shear(s, &so, NULL, NULL, &r), STC_OK);
    asp_solver_destroy(&s);
    printf("# placements at P = 0.3 Pc: delta %.6g mm, P0/P - 1 = %+.1e, P1/P - 1 = %+.1e, "
           "mu_s %.5f / %.5f (single run %.5f), mean %.5f\n", e->m[0].pt.delta,
           e->m[0].pt.P / P - 1, e->m[1].pt.P / P - 1, e->m[0].res.mu_s, e->m[1].res.mu_s,
           r.mu_s, e->mu_s);
    assert_true(fabs(e->m[0].pt.delta / pt.delta - 1) < 1e-10);
    assert_true(fabs(e->m[0].res.mu_s / r.mu_s - 1) < 1e-10);
    assert_true(fabs(e->m[0].pt.P / P - 1) <= 1e-3);
    assert_true(e->m[1].pt.delta == e->m[0].pt.delta);
    assert_true(fabs(e->m[1].pt.P / P - 1) < 0.02);
    assert_true(fabs(e->m[1].elements_per_contact - 4.0 - 0.5 * e->period) < 1e-12);
    assert_true(e->m[1].pt.a != e->m[0].pt.a); /* another mesh */
    /* the meshes are sized to the contact (asp_shear_preload: 1.1 times the
     * axisymmetric δ(P)): a_max / a0 = 1.1 sqrt(1.1) for Hertz, where
     * twice the Hertz guess gave 1.1 sqrt(2) */
    printf("# period (a_max / a0) %.4f\n", e->period);
    assert_true(e->period > 1.1 && e->period < 1.25);
    free(e);
}

/* ---- CLI ------------------------------------------------------------------- */

static char cli[PATH_MAX];

static int cli_run(const char *args, char *buf, size_t n, int want_stderr)
{
    char cmd[PATH_MAX + 2048];
    snprintf(cmd, sizeof cmd, "'%s' asperity %s", cli, args);
    return cli_capture(cmd, want_stderr ? 2 : 1, buf, n);
}

static void test_cli_errors(void **state)
{
    (void)state;
    char buf[4096], dir[256];
    assert_int_equal(cli_locate(cli, sizeof cli), 0);
    snprintf(dir, sizeof dir, "%s/stiction-test-shear-%ld", test_tmpdir(), (long)getpid());
    struct {
        const char *args, *msg;
    } bad[] = {
        {"--delta 0.5 --shear --model axisym", "model = 'axisym'"},
        {"--delta 0.5 --criterion sideways", "criterion = 'sideways'"},
        {"--delta 0.5 --tau-c -3", "tau-c = '-3'"},
        {"--delta 0.5 --junction rings", "junction = 'rings'"},
        {"--delta 0.5 --ramp-return-map euler", "ramp-return-map = 'euler'"},
        {"--delta 0.5 --return-map euler", "return-map = 'euler'"},
        {"--delta 0.5 --grade-3d=perhaps", "grade-3d = 'perhaps'"},
        {"--delta 0.5 --ramp-refine 0.5", "ramp-refine = '0.5'"},
        {"--delta 0.5 --foot-rows 0.95", "foot-rows = '0.95'"},
        {"--delta 0.5 --shear --alpha 2", "alpha = '2'"},
        {"--delta 0.5,1 --shear", "one interference"},
        {"--delta 0.5 --load 2", "--load conflicts"},
        {"--load -1", "load = '-1'"},
        {"--delta 0.5 --placements 9", "placements = '9'"},
        {"--delta 0.5 --placements 2.5", "placements = '2.5'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char args[512];
        snprintf(args, sizeof args, "%s --out %s", bad[i].args, dir);
        int rc = cli_run(args, buf, sizeof buf, 1);
        if (rc == 0 || !strstr(buf, bad[i].msg))
            fail_msg("'%s': exit %d, stderr '%s' (expected '%s')", args, rc, buf, bad[i].msg);
        struct stat sb;
        assert_true(stat(dir, &sb) != 0); /* no output at all */
    }
}

/* A short valid run: the stiffness criterion with α = 0.9 stops after a few
 * increments; every documented JSON key is there and the files exist. */
static void test_cli_json(void **state)
{
    (void)state;
    static char buf[1 << 16];
    char dir[256], args[1024], path[512];
    assert_int_equal(cli_locate(cli, sizeof cli), 0);
    snprintf(dir, sizeof dir, "%s/stiction-test-shear-out-%ld", test_tmpdir(), (long)getpid());
    snprintf(args, sizeof args,
             "--R 10.5 --E-su 74000 --nu 0.33 --Y-su 325 --Y-co 325 --delta 0.5 --mesh 0 "
             "--threads 1 --criterion stiffness --alpha 0.9 --json --out %s", dir);
    int rc = cli_run(args, buf, sizeof buf, 0);
    if (rc != 0) fail_msg("exit %d: %s", rc, buf);
    assert_json(buf);
    const char *keys[] = {"\"Q_max_N\"", "\"Q_max_over_P_c\"", "\"mu_s\"", "\"mu_s_preload\"",
                          "\"ux_at_slide_mm\"", "\"ux_at_slide_over_omega_c\"",
                          "\"P_at_slide_N\"", "\"P_preload_N\"", "\"criterion\": \"stiffness\"",
                          "\"tau_c_MPa\"", "\"junction\": \"footprint\"",
                          "\"stick_radius_mm\"", "\"shear_increments\"",
                          "\"KT_over_KT1_after_slide\"", "\"mu_s_err\"",
                          "\"Q_still_rising\"", "\"mu_s_ux_slope\"", "\"elements_per_contact\"",
                          "\"factorizations\"", "\"converged\": true", "\"reason\"",
                          "\"delta_mm\"", "\"P_N\""};
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (!strstr(buf, keys[i])) fail_msg("JSON lacks %s: %.2000s", keys[i], buf);
    /* the time split: each part positive, together within the run's wall time */
    const char *tk[] = {"\"time_assembly_s\": ", "\"time_factorize_s\": ", "\"time_pcg_s\": ",
                        "\"wall_s\": ", "\"shear_wall_s\": "};
    double tv[5];
    for (int i = 0; i < 5; i++) {
        const char *at = strstr(buf, tk[i]);
        if (!at) fail_msg("JSON lacks %s", tk[i]);
        tv[i] = strtod(at + strlen(tk[i]), NULL);
    }
    assert_true(tv[0] > 0.0 && tv[1] > 0.0 && tv[2] >= 0.0);
    assert_true(tv[0] + tv[1] + tv[2] <= tv[3] + tv[4]);
    const char *files[] = {"shear.csv", "fields_Q0.h5", "fields_Q0.xmf", "fields_Q080.h5",
                           "fields_Qmax.h5", "fields_Qmax.xmf"};
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        if (access(path, R_OK) != 0) fail_msg("missing %s", path);
    }
    snprintf(path, sizeof path, "%s/shear.csv", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[512];
    assert_non_null(fgets(line, sizeof line, f));
    assert_string_equal(line, "ux_mm,ux_over_omega_c,Q_N,Q_over_P_c,P_N,A_mm2,stick_area_mm2,"
                              "slip_fraction,n_contact,a_lead_mm,a_trail_mm,a_side_mm,"
                              "limit_fraction\n");
    assert_non_null(fgets(line, sizeof line, f));
    assert_true(!strncmp(line, "0,0,", 4)); /* first row: ux = 0 */
    /* every row: the fraction at the shear limit counts the slipping area and
     * the stuck area on saturated material, so it is never below the
     * slipping fraction */
    int rows = 0;
    do {
        double v[13];
        char *c = line;
        for (int k = 0; k < 13; k++) {
            v[k] = strtod(c, &c);
            if (k < 12 && *c++ != ',') fail_msg("shear.csv row %d: %s", rows, line);
        }
        if (!(v[7] >= 0.0 && v[7] <= 1.0 && v[12] >= v[7] - 1e-12 && v[12] <= 1.0))
            fail_msg("shear.csv row %d: slip_fraction %g, limit_fraction %g", rows, v[7], v[12]);
        rows++;
    } while (fgets(line, sizeof line, f));
    assert_true(rows >= 3);
    fclose(f);
    char rm[300];
    snprintf(rm, sizeof rm, "rm -rf '%s'", dir);
    assert_int_equal(system(rm), 0);
}

/* Junction growth of the ELASTIC sphere against the half-space boundary
 * elements (surface/halfspace.c; docs/design.md §5.6, §4.2): a rigid flat
 * sheared in full slip at τc with no separation grows the contact on the
 * trailing side only (the Cerruti coupling lifts the surface behind the
 * traction toward the flat), by +4.9 % in area and +7.5 % along -x at 0.5 ωc
 * of the WSP sphere (512 cells).  The FE footprint reads the growth low
 * (two half-ellipses cannot hold the fuller trailing lobe, and the trailing
 * edge lags): measured -2.3 … -1.9 % in area at 6, 6.6, 7.3 and 12 elements
 * per contact, so 3 % is the bound here; the trailing extent must grow by
 * more than half the reference and the leading one by less than a fifth of
 * the trailing one. */
static void test_elastic_growth_bem(void **state)
{
    (void)state;
    assert_int_equal(run_case_mat(&RE, ASP_JUNCTION_FOOTPRINT, 1), 0);
    assert_int_equal(RE.st, STC_OK);
    assert_true(RE.res.converged);
    const asp_shear_point *l = &RE.pts[RE.n - 1];
    double tc = RE.res.tau_c, a0 = RE.res.a0, delta = 0.5 * RE.c.omega_c;
    double fe = RE.res.Q_max / (tc * M_PI * a0 * a0) - 1.0;
    srf_slide_result b;
    assert_int_equal(srf_halfspace_sphere_slide(RE.p.R, delta, RE.m.E, RE.m.nu, tc, 128, 1.3, 2,
                                                &b),
                     STC_OK);
    double bem = b.A / b.A0 - 1.0, a0b = sqrt(b.A0 / M_PI);
    printf("# elastic growth: FE %+.2f %% (lead %+.1f, trail %+.1f, side %+.1f %%), "
           "half-space %+.2f %% (lead %+.1f, trail %+.1f, side %+.1f %%, cell %.1f %%)\n",
           100 * fe, 100 * (l->a_lead / a0 - 1), 100 * (l->a_trail / a0 - 1),
           100 * (l->a_side / a0 - 1), 100 * bem, 100 * (b.a_lead / a0b - 1),
           100 * (b.a_trail / a0b - 1), 100 * (b.a_side / a0b - 1), 100 * b.h / a0b);
    assert_true(fabs(fe - bem) < 0.03);
    assert_true(l->a_trail / a0 - 1 > 0.5 * (b.a_trail / a0b - 1));
    assert_true(l->a_lead - a0 < 0.2 * (l->a_trail - a0));
}

/* The rows reading of the junction footprint (asp_shear_options.foot_rows,
 * --foot-rows; docs/design.md §4.2): the edge advance is read on every row
 * of surface nodes within F a0 of the axis that crosses the edge, not on
 * the three axis lines only.  On the elastic sphere of the test above it
 * reads more of the half-space's growth than the axis lines: measured
 * +5.58 % at F = 0.6 against +2.56 % (axis lines) and +4.89 % (half space,
 * 512 cells); docs/design.md: +0.7 … +1.4 points over the reference at 6 to
 * 12 elements per contact.  Checked: at least 1.5 points more growth than
 * the axis lines, and within 2 points of the half-space. */
static void test_foot_rows(void **state)
{
    (void)state;
    static shared X;
    if (RE.n == 0) assert_int_equal(run_case_mat(&RE, ASP_JUNCTION_FOOTPRINT, 1), 0);
    asp_shear_options so;
    asp_shear_options_default(&so);
    so.foot_rows = 0.6;
    assert_int_equal(run_case_so(&X, &so, 1), 0);
    assert_int_equal(X.st, STC_OK);
    assert_true(X.res.converged);
    double tc = X.res.tau_c, a0 = X.res.a0, delta = 0.5 * X.c.omega_c;
    assert_true(a0 == RE.res.a0 && tc == RE.res.tau_c); /* the same preload */
    double rows = X.res.Q_max / (tc * M_PI * a0 * a0) - 1.0;
    double axis = RE.res.Q_max / (tc * M_PI * a0 * a0) - 1.0;
    srf_slide_result b;
    assert_int_equal(srf_halfspace_sphere_slide(X.p.R, delta, X.m.E, X.m.nu, tc, 128, 1.3, 2, &b),
                     STC_OK);
    double bem = b.A / b.A0 - 1.0;
    printf("# elastic growth read on rows (F = 0.6): %+.2f %%, on the axis lines %+.2f %%, "
           "half-space %+.2f %%\n", 100 * rows, 100 * axis, 100 * bem);
    assert_true(rows - axis > 0.015);
    assert_true(fabs(rows - bem) < 0.02);
}

/* The ramp's increment targets divided by K (asp_shear_options.ramp_refine,
 * --ramp-refine; docs/design.md §4.3): the shared run again at K = 2 takes
 * more than 1.5 times its increments and its μs moves by less than 0.2 %
 * (measured: 20 against 9 increments, +0.065 %): the ramp is
 * increment-converged here. */
static void test_ramp_refine(void **state)
{
    (void)state;
    static shared X;
    asp_shear_options so;
    asp_shear_options_default(&so);
    so.ramp_refine = 2.0;
    so.foot_rows = 0.0; /* as the shared run */
    assert_int_equal(run_case_so(&X, &so, 0), 0);
    assert_int_equal(X.st, STC_OK);
    double d = X.res.mu_s / R.res.mu_s - 1;
    printf("# ramp refined 2x: %d increments (against %d), mu_s %.6f, %+.2e\n",
           X.res.increments, R.res.increments, X.res.mu_s, d);
    assert_true(X.res.increments > 1.5 * R.res.increments);
    assert_true(fabs(d) < 2e-3);
}

/* The ramp's return map (asp_shear_options.return_map): at 0.5 ωc the
 * plastic zone under the contact is small, so the midpoint rule and the
 * exact integration give the radial return's μs.  Measured: +2.1e-4 for
 * both (at 3 ωc, where a node enters the junction late in the ramp, the
 * exact map's μs is 1.4 % above the radial's, the node-entry scatter of
 * docs/design.md §4.5; the return maps: docs/design.md §3.4). */
static void test_ramp_return_maps(void **state)
{
    (void)state;
    static shared X;
    for (int k = 0; k < 2; k++) {
        asp_return_map map = k ? ASP_RETURN_EXACT : ASP_RETURN_MIDPOINT;
        memset(&X, 0, sizeof X);
        assert_int_equal(run_case_map(&X, ASP_JUNCTION_FOOTPRINT, 0, map), 0);
        assert_int_equal(X.st, STC_OK);
        double d = X.res.mu_s / R.res.mu_s - 1;
        printf("# ramp return map %s: mu_s %.6f, %+.1e from the radial return's\n",
               k ? "exact" : "midpoint", X.res.mu_s, d);
        assert_true(fabs(d) < 1e-3);
    }
}

/* Node-placement ensemble (asp_shear_placements): member 0 is the shared run
 * itself (same mesh, same answer to rounding), member 1 sits half a node
 * spacing further at the contact edge (elements per contact + T/2, T =
 * a_max / a0), the mean is the members' mean; bad k and the axisymmetric
 * model are refused by name.  Measured: 0.76992 / 0.76619 (N = 6 / 6.546). */
static void test_placements(void **state)
{
    (void)state;
    asp_options o;
    asp_shear_options so;
    asp_placement_result *e = malloc(sizeof *e);
    assert_non_null(e);
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D, o.mesh_level = 0, o.threads = 2;
    asp_shear_options_default(&so);
    so.foot_rows = 0.0; /* as the shared run */
    double delta = 0.5 * R.c.omega_c;
    assert_int_equal(asp_shear_placements(&R.p, &o, &so, delta, 9, e), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "placements = 9"));
    o.geom = ASP_GEOM_AXISYM;
    assert_int_equal(asp_shear_placements(&R.p, &o, &so, delta, 2, e), STC_EINVAL);
    o.geom = ASP_GEOM_3D;
    assert_int_equal(asp_shear_placements(&R.p, &o, &so, delta, 2, e), STC_OK);
    printf("# placements: period %.4f, mu_s %.5f / %.5f (N = %.4g / %.4g), mean %.5f, %.1f s\n",
           e->period, e->m[0].res.mu_s, e->m[1].res.mu_s, e->m[0].elements_per_contact,
           e->m[1].elements_per_contact, e->mu_s, e->wall_s);
    assert_int_equal(e->k, 2);
    assert_int_equal(e->n_ok, 2);
    assert_true(e->m[0].elements_per_contact == 6.0);
    /* the same run, to rounding: the members factorize on one thread
     * each, R on the threads it is given (one here: equal to the bit, as
     * make check measures), and on two OpenBLAS may sum in another order:
     * measured 2-3e-16 while every Krylov solve went to 1e-6; since the
     * solves stop at the inexact-Newton forcing term (up to 1e-2,
     * newton.c), the rounding steers the iterates and the answers agree to
     * the Newton tolerance's scale instead: measured 1.3e-12 (rtol 1e-8;
     * another mesh moves μs by ~1e-2) */
    printf("# member 0 vs the single run: mu_s %+.1e, P %+.1e relative\n",
           e->m[0].res.mu_s / R.res.mu_s - 1, e->m[0].pt.P / R.pt.P - 1);
    assert_true(fabs(e->m[0].res.mu_s / R.res.mu_s - 1) < 1e-10);
    assert_true(fabs(e->m[0].pt.P / R.pt.P - 1) < 1e-10);
    assert_true(fabs(e->period - 1.1 * sqrt(R.p.R * delta) / e->m[0].pt.a) < 1e-9);
    assert_true(fabs(e->m[1].elements_per_contact - 6.0 - 0.5 * e->period) < 1e-12);
    assert_true(e->m[1].pt.a != e->m[0].pt.a); /* another mesh */
    assert_true(fabs(e->mu_s - 0.5 * (e->m[0].res.mu_s + e->m[1].res.mu_s)) < 1e-15);
    assert_true(e->mu_s_min <= e->mu_s && e->mu_s <= e->mu_s_max);
    assert_true(fabs(e->m[1].res.mu_s / e->m[0].res.mu_s - 1) < 0.03);
    /* the error estimate: the two members' standard error of the mean,
     * |μ0 − μ1| / 2, and the mesh floor in quadrature; one member alone
     * carries the single-mesh scatter, as the single run does */
    double se = 0.5 * fabs(e->m[0].res.mu_s - e->m[1].res.mu_s);
    double want = hypot(se, ASP_MU_S_ERR_FLOOR * e->mu_s);
    printf("# mu_s error: %.5f (standard error %.5f, floor %.5f)\n", e->mu_s_err, se,
           ASP_MU_S_ERR_FLOOR * e->mu_s);
    assert_true(fabs(e->mu_s_err / want - 1) < 1e-12);
    /* the single run at 0.5 ωc carries the elastic regime's scatter; the
     * axis lines' error rises continuously and monotonically to the plastic
     * one at 3 ωc; the rows' is the smaller of theirs and the axis lines' */
    assert_true(fabs(R.res.mu_s_err / (ASP_MU_S_ERR_ELASTIC * R.res.mu_s) - 1) < 1e-15);
    for (int band = 0; band <= 2; band++) {
        /* one band level is no better than the default mesh (docs/design.md
         * §2.7); two have their own, smaller plastic value */
        double hi = band == 2 ? ASP_MU_S_ERR_BAND : ASP_MU_S_ERR_SINGLE;
        assert_true(asp_mu_s_err_single(0.0, band, 1.0) == ASP_MU_S_ERR_ELASTIC);
        assert_true(asp_mu_s_err_single(0.0, band, 3.0) == hi);
        assert_true(asp_mu_s_err_single(0.0, band, 60.0) == hi);
        assert_true(fabs(asp_mu_s_err_single(0.0, band, 1.0 + 1e-9) - ASP_MU_S_ERR_ELASTIC) < 1e-9);
        assert_true(fabs(asp_mu_s_err_single(0.0, band, 3.0 - 1e-9) - hi) < 1e-9);
        for (double x = 1.0, prev = 0.0; x <= 3.0; x += 0.125) {
            double v = asp_mu_s_err_single(0.0, band, x);
            assert_true(v > prev);
            assert_true(band < 2 || v <= asp_mu_s_err_single(0.0, 0, x));
            prev = v;
        }
        assert_true(asp_mu_s_err_single(0.6, band, 0.5) == ASP_MU_S_ERR_ELASTIC);
        assert_true(asp_mu_s_err_single(0.6, band, 10.0) == ASP_MU_S_ERR_ROWS);
    }
    assert_true(ASP_MU_S_ERR_ELASTIC < ASP_MU_S_ERR_BAND && ASP_MU_S_ERR_BAND < ASP_MU_S_ERR_SINGLE);
    e->k = e->n_ok = 1;
    assert_true(asp_placement_mu_s_err(e, 0.05, 0.01) == 0.05 * e->mu_s);
    e->k = 2; /* a member that failed: no estimate */
    assert_true(isnan(asp_placement_mu_s_err(e, 0.05, 0.01)));
    free(e);
}

/* The options of a coarse ensemble on two threads at 0.5 ωc of the shared
 * run's sphere (the identities checked with it do not depend on the mesh);
 * returns that δ, mm. */
static double coarse_ensemble(asp_options *o, asp_shear_options *so)
{
    asp_options_default(o);
    o->geom = ASP_GEOM_3D, o->mesh_level = 0, o->elements_per_contact = 3.0, o->threads = 2;
    asp_shear_options_default(so);
    so->foot_rows = 0.0;
    return 0.5 * R.c.omega_c;
}

/* An ensemble refined (asp_shear_placements_refine): one member, then the
 * member half a period on, equals the two-member ensemble made at once,
 * member by member and in its means, to the bit (each member runs alone on
 * one thread); a refinement past ASP_PLACEMENTS_MAX or of an ensemble with
 * a failed member is refused by name. */
static void test_placements_refine(void **state)
{
    (void)state;
    asp_options o;
    asp_shear_options so;
    asp_placement_result *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    assert_non_null(a);
    assert_non_null(b);
    double delta = coarse_ensemble(&o, &so);
    assert_int_equal(asp_shear_placements(&R.p, &o, &so, delta, 1, a), STC_OK);
    assert_int_equal(asp_shear_placements_refine(&R.p, &o, &so, a), STC_OK);
    assert_int_equal(asp_shear_placements(&R.p, &o, &so, delta, 2, b), STC_OK);
    printf("# refined 1 -> 2: mu_s %.6f +- %.6f (members %.6f, %.6f), at once %.6f +- %.6f\n",
           a->mu_s, a->mu_s_err, a->m[0].res.mu_s, a->m[1].res.mu_s, b->mu_s, b->mu_s_err);
    assert_int_equal(a->k, 2);
    assert_int_equal(a->n_ok, 2);
    for (int j = 0; j < 2; j++) {
        assert_true(a->m[j].elements_per_contact == b->m[j].elements_per_contact);
        assert_true(a->m[j].res.mu_s == b->m[j].res.mu_s);
        assert_true(a->m[j].pt.P == b->m[j].pt.P);
    }
    assert_true(a->mu_s == b->mu_s && a->mu_s_err == b->mu_s_err);
    assert_true(a->mu_s_min == b->mu_s_min && a->mu_s_max == b->mu_s_max);
    assert_true(a->P_slide == b->P_slide && a->Q_max == b->Q_max);
    a->k = 8;
    assert_int_equal(asp_shear_placements_refine(&R.p, &o, &so, a), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "8 members"));
    a->k = 2, a->n_ok = 1;
    assert_int_equal(asp_shear_placements_refine(&R.p, &o, &so, a), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "1 of 2 members"));
    free(a);
    free(b);
}

/* An in-memory asp_placement_store: the members by slot, and how many
 * were put. */
typedef struct {
    int have[ASP_PLACEMENTS_MAX], puts, slots_put[ASP_PLACEMENTS_MAX];
    asp_placement_member m[ASP_PLACEMENTS_MAX];
    asp_placement_result geom; /* the header fields only */
} mem_store;

static void mem_put(void *ctx, const asp_placement_result *e, int j)
{
    mem_store *s = ctx;
#pragma omp critical(mem_store)
    {
        int slot = asp_placement_slot(j, e->k);
        s->have[slot] = 1;
        s->m[slot] = e->m[j];
        s->slots_put[s->puts++] = slot;
        s->geom.period = e->period, s->geom.edge_refine = e->edge_refine;
        s->geom.delta = e->delta, s->geom.delta_mesh = e->delta_mesh;
        s->geom.edge_a0 = e->edge_a0;
    }
}

static int mem_get(void *ctx, int slot, asp_placement_result *g, asp_placement_member *m)
{
    mem_store *s = ctx;
    int got = 0;
#pragma omp critical(mem_store)
    if (s->have[slot]) {
        *m = s->m[slot];
        g->period = s->geom.period, g->edge_refine = s->geom.edge_refine;
        g->delta = s->geom.delta, g->delta_mesh = s->geom.delta_mesh;
        g->edge_a0 = s->geom.edge_a0;
        got = 1;
    }
    return got;
}

static void assert_same_ensemble(const asp_placement_result *a, const asp_placement_result *b)
{
    assert_int_equal(a->k, b->k);
    assert_int_equal(a->n_ok, b->n_ok);
    for (int j = 0; j < a->k; j++) {
        assert_true(a->m[j].elements_per_contact == b->m[j].elements_per_contact);
        assert_true(a->m[j].res.mu_s == b->m[j].res.mu_s);
        assert_true(a->m[j].pt.P == b->m[j].pt.P && a->m[j].pt.A == b->m[j].pt.A);
    }
    assert_true(a->mu_s == b->mu_s && a->mu_s_err == b->mu_s_err);
    assert_true(a->P_slide == b->P_slide && a->Q_max == b->Q_max);
    assert_true(a->period == b->period && a->delta == b->delta);
}

/* Members kept in a store (asp_shear_placements_stored): an adaptive
 * ensemble refined from one member to two puts both (slots 0 and
 * ASP_PLACEMENTS_MAX / 2); run again with both stored it runs none, with
 * only the refined one stored it runs member 0 alone, and both times the
 * result is the first run's to the bit, with the stored members' CPU time
 * counted. */
static void test_placements_stored(void **state)
{
    (void)state;
    asp_options o;
    asp_shear_options so;
    asp_placement_result *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    mem_store *st = calloc(1, sizeof *st);
    assert_non_null(a);
    assert_non_null(b);
    assert_non_null(st);
    double delta = coarse_ensemble(&o, &so);
    asp_placement_store store = {mem_put, mem_get, st};
    assert_int_equal(asp_shear_placements_stored(&R.p, &o, &so, delta, 0.0, 1, 2, 0.001, &store,
                                                 a), STC_OK);
    printf("# stored: %d members put (slots %d, %d), mu_s %.6f, CPU %.2f s (members %.2f + "
           "%.2f)\n", st->puts, st->slots_put[0], st->slots_put[1], a->mu_s, a->cpu_s,
           a->m[0].cpu_s, a->m[1].cpu_s);
    assert_int_equal(a->k, 2);
    assert_int_equal(st->puts, 2);
    assert_true(st->have[0] && st->have[ASP_PLACEMENTS_MAX / 2]);
    assert_true(a->m[0].cpu_s > 0.0 && a->m[1].cpu_s > 0.0);
    /* everything stored: nothing runs */
    st->puts = 0;
    assert_int_equal(asp_shear_placements_stored(&R.p, &o, &so, delta, 0.0, 1, 2, 0.001, &store,
                                                 b), STC_OK);
    assert_int_equal(st->puts, 0);
    assert_same_ensemble(a, b);
    printf("# all taken: CPU %.2f s counted\n", b->cpu_s);
    assert_true(b->cpu_s >= a->m[0].cpu_s + a->m[1].cpu_s);
    /* the refined member stored alone: member 0 runs, its normal step too */
    st->have[0] = 0, st->puts = 0;
    assert_int_equal(asp_shear_placements_stored(&R.p, &o, &so, delta, 0.0, 1, 2, 0.001, &store,
                                                 b), STC_OK);
    assert_int_equal(st->puts, 1);
    assert_int_equal(st->slots_put[0], 0);
    assert_same_ensemble(a, b);
    free(a);
    free(b);
    free(st);
}

/* A thin coating much stronger in shear than its substrate (t/R 0.001,
 * Eco/Esu 4, stick, δ = 10 ωc_su; docs/design.md §4.9, §4.2, §4.3): Newton
 * stalls in the ramp.  The held nodes (asp_shear_options.hold_stalled)
 * here never reach a state the stick law keeps, so each such try falls
 * back to the cut-back, as with hold_stalled = 0 (the same ramp to the bit,
 * measured: 0.9383, 2 cut-backs, 33 increments both ways); the cut-backs
 * must share the junction reading's step: before they did, every cut try
 * started 0.81 of the reaction out of equilibrium and the ramp failed at
 * ux = 5.85 ωc.  The μs itself is mesh- and path-sensitive in this regime
 * (0.67-1.07 over N = 3.5 ... 6; Q still rising at inception), so only a
 * wide band is checked.  Run on 5 elements across the contact, where the
 * ramp stalls once: 0.8515, 1 cut-back, 24 increments, measured alike on
 * one and two threads and on the Prescott, Haswell and SkylakeX BLAS
 * kernels (the default 6 stalls twice in twice the time, 4 not at all:
 * were the stall to go, the check that it happens fails and says so). */
static void test_thin_strong_coating(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_shear_options so;
    asp_shear_result res;
    asp_point pt;
    stc_material su;
    stc_critical c;
    asp_solver *s = NULL;
    stc_params_default(&p);
    p.t_over_R = 0.001, p.E_ratio = 4.0;
    stc_params_materials(&p, &su, NULL);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D, o.contact = ASP_CONTACT_STICK;
    o.elements_per_contact = 5.0;
    asp_shear_options_default(&so);
    /* the axis lines (the default): their reading jumps with a node entering,
     * which is what made the cut-backs fail (the rows read 0.8403 in 19
     * increments with none) */
    so.foot_rows = 0.0;
    double delta = 10.0 * c.omega_c;
    assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, delta, &pt), STC_OK);
    stc_status st = asp_solver_shear(s, &so, NULL, NULL, &res);
    printf("# thin strong coating: mu_s %.4f, %d cut-backs, %d nodes held, "
           "%d re-solves, %d increments, %.1f s (%s)\n", res.mu_s, res.cutbacks,
           res.held_nodes, res.hold_passes, res.increments, res.wall_s, res.reason);
    asp_solver_destroy(&s);
    assert_int_equal(st, STC_OK);
    assert_true(res.converged);
    assert_true(res.cutbacks + res.held_nodes >= 1); /* it stalls */
    assert_true(res.mu_s > 0.5 && res.mu_s < 1.5);
}

int main(void)
{
    const struct CMUnitTest ramp[] = {
        cmocka_unit_test(test_ramp_converged),
        cmocka_unit_test(test_mindlin_stiffness),
        cmocka_unit_test(test_full_slip_plateau),
        cmocka_unit_test(test_wsp_mu),
        cmocka_unit_test(test_converged_reference),
        cmocka_unit_test(test_equilibrium),
        cmocka_unit_test(test_junction_bracket),
        cmocka_unit_test(test_elastic_growth_bem),
        cmocka_unit_test(test_foot_rows),
        cmocka_unit_test(test_ramp_refine),
        cmocka_unit_test(test_placements),
        cmocka_unit_test(test_placements_refine),
        cmocka_unit_test(test_placements_stored),
        cmocka_unit_test(test_ramp_return_maps),
    };
    const struct CMUnitTest other[] = {
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_load_control),
        cmocka_unit_test(test_placements_load),
        cmocka_unit_test(test_cli_errors),
        cmocka_unit_test(test_cli_json),
        cmocka_unit_test(test_thin_strong_coating),
    };
    int f = cmocka_run_group_tests_name("shear ramp (WSP 0.5 wc, level 0)", ramp, run_shared, NULL);
    return f + cmocka_run_group_tests_name("shear errors and CLI", other, NULL, NULL);
}
