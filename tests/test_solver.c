/* Asperity FE solver, coarse versions of the normal-step checks of
 * `make validate` (the full-size ones: tools/validate.d/20-asperity.sh):
 * Hertz and its mesh convergence, yield inception (slip, stick), coated
 * first yield in the coating, equilibrium, zero penetration, error paths,
 * field output.  Tolerances are those of the coarse meshes used here, each
 * stated with the measured value at the time of writing. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include <hdf5.h>

#include "stiction/asperity.h"
#include "stiction/formulas.h"
#include "data_util.h"
#include "tmp_util.h"

/* The thesis's Hertz check: R = 10.09 mm, E = 74 GPa, ν = 0.32, elastic
 * (Y far above any stress reached). */
static void hertz_params(stc_params *p)
{
    stc_params_default(p);
    p->R = 10.09, p->E_su = 74000.0, p->nu = 0.32, p->Y_su = p->Y_co = 70000.0;
}

static double hertz_run(int level, double delta, asp_point *pt)
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    hertz_params(&p);
    asp_options_default(&o);
    o.mesh_level = level;
    o.threads = 1; /* the test runner shares the machine */
    assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, delta, pt), STC_OK);
    asp_solver_destroy(&s);
    assert_null(s);
    return pt->P;
}

static void test_hertz(void **state)
{
    (void)state;
    stc_material m = {74000.0, 0.32, 70000.0};
    double delta = 0.003 * 0.003 * 10.09; /* a/R = 0.003 */
    asp_point pt;
    stc_hertz h;
    assert_int_equal(stc_hertz_eval(&m, 10.09, delta, &h), STC_OK);
    hertz_run(1, delta, &pt);
    printf("# Hertz a/R = 0.003, level 1: P/P_H - 1 = %+.3f %%, a/a_H - 1 = %+.3f %%\n",
           100 * (pt.P / h.P - 1), 100 * (pt.a / h.a - 1));
    /* measured: +0.42 % (base stiffening + discretization), -0.09 % */
    assert_true(fabs(pt.P / h.P - 1) < 0.006);
    assert_true(fabs(pt.a / h.a - 1) < 0.01);
    assert_true(fabs(pt.P_base / pt.P - 1) < 1e-8); /* equilibrium */
    assert_true(pt.max_penetration <= 1e-3 * delta);
}

/* P converges under refinement: successive differences shrink. */
static void test_hertz_convergence(void **state)
{
    (void)state;
    double delta = 0.001, P[3];
    asp_point pt;
    for (int l = 0; l < 3; l++) P[l] = hertz_run(l, delta, &pt);
    double d1 = fabs(P[1] - P[0]), d2 = fabs(P[2] - P[1]);
    printf("# Hertz a/R = 0.01: P = %.6g %.6g %.6g N (levels 0-2), ratio of differences %.2f\n",
           P[0], P[1], P[2], d1 / d2);
    /* measured 0.14 %; level 0 is pre-asymptotic (the observed order over
     * levels 1-3 is reported by make validate) */
    assert_true(d2 / P[2] < 0.003); /* the level-1 answer is within 0.3 % of level 2 */
    assert_true(d1 / P[2] < 0.003);
}

typedef struct {
    double dy, Py, r, z, Rp, ac;
} yres;

static void yield_run(double t_over_R, double E_ratio, asp_contact_law law, double wmax,
                      int layer, yres *y)
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_material su;
    stc_critical c;
    asp_yield yy;
    stc_params_default(&p);
    p.t_over_R = t_over_R, p.E_ratio = E_ratio;
    stc_params_materials(&p, &su, NULL);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    asp_options_default(&o);
    o.contact = law;
    o.threads = 1;
    assert_int_equal(asp_solver_create(&p, &o, wmax * c.omega_c, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, wmax * c.omega_c, NULL), STC_OK);
    asp_solver_yield(s, layer, &yy);
    assert_true(yy.reached);
    y->dy = yy.delta / c.omega_c, y->Py = yy.P / c.P_c, y->r = yy.r, y->z = yy.z;
    y->Rp = p.R * (1 + t_over_R), y->ac = sqrt(p.R * c.omega_c);
    asp_solver_destroy(&s);
}

static void test_yield_slip(void **state)
{
    (void)state;
    yres y;
    yield_run(0.0, 1.0, ASP_CONTACT_SLIP, 1.2, 0, &y);
    printf("# slip first yield: delta/wc = %.4f, P/Pc = %.4f, r = %.3g mm, depth/a = %.3f\n",
           y.dy, y.Py, y.r, (y.Rp - y.z) / y.ac);
    /* level 1 measured 0.967 / 0.950; converges to 1 (level 3: 0.997) */
    assert_true(fabs(y.dy - 1.0) < 0.05 && fabs(y.Py - 1.0) < 0.07);
    /* on the axis, below the surface (Hertz: 0.48 a; Johnson 1985 fig. 4.6) */
    assert_true(y.r < 0.05 * y.ac);
    assert_true(fabs((y.Rp - y.z) / y.ac - 0.48) < 0.1);
}

static void test_yield_stick(void **state)
{
    (void)state;
    yres y;
    stc_material su = {200000.0, 0.32, 200.0};
    stc_critical c;
    stc_critical_eval(&su, 10.0, &c);
    yield_run(0.0, 1.0, ASP_CONTACT_STICK, 1.2, 0, &y);
    printf("# stick first yield: delta/wc = %.4f (Brizmer %.4f), L/Pc = %.4f (Brizmer %.4f)\n",
           y.dy, c.delta_c_stick_over_omega_c, y.Py, c.L_c_stick_over_P_c);
    /* level 1 measured +2.1 % and +2.9 % */
    assert_true(fabs(y.dy / c.delta_c_stick_over_omega_c - 1) < 0.04);
    assert_true(fabs(y.Py / c.L_c_stick_over_P_c - 1) < 0.05);
    assert_true(y.r < 0.05 * y.ac && y.Rp - y.z > 0.2 * y.ac);
}

/* Table 4.2: t/R = 0.025, Eco/Esu = 2, stick: δc1/ωc_su = 1.03 (thesis),
 * first yield in the coating. */
static void test_coated_first_yield(void **state)
{
    (void)state;
    yres y;
    stc_params p;
    stc_coated cf;
    stc_params_default(&p);
    p.t_over_R = 0.025, p.E_ratio = 2.0;
    assert_int_equal(stc_coated_eval(&p, &cf), STC_OK);
    yield_run(0.025, 2.0, ASP_CONTACT_STICK, 2.0, 1, &y);
    printf("# coated stick t/R 0.025 Eco/Esu 2: delta_c1/wc = %.4f (fit %.4f), depth %.3g mm\n",
           y.dy, cf.delta_c1_over_omega_c_su, y.Rp - y.z);
    assert_true(fabs(y.dy / cf.delta_c1_over_omega_c_su - 1) < 0.1);
    assert_true(y.Rp - y.z < 0.25); /* inside the coating (t = 0.25 mm) */
}

static void test_errors(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_params_default(&p);
    asp_options_default(&o);
    assert_int_equal(asp_solver_create(&p, &o, -1.0, &s), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "delta = -1"));
    assert_null(s);
    o.mesh_level = 9;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "level = 9"));
    o.mesh_level = 0;
    o.rtol = 0.5;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "rtol = 0.5"));
    o.rtol = 1e-8;
    o.geom = ASP_GEOM_AXISYM;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, 2e-4, NULL), STC_EINVAL); /* beyond the meshed δ */
    assert_int_equal(asp_solver_load(s, 1e-4, NULL), STC_OK);
    assert_int_equal(asp_solver_load(s, 0.5e-4, NULL), STC_EINVAL); /* unloading */
    asp_solver_destroy(&s);
    /* a Newton limit too small to converge ends with a reason */
    o.max_newton = 2;
    o.max_cutbacks = 1;
    assert_int_equal(asp_solver_create(&p, &o, 5e-4, &s), STC_OK);
    stc_status st = asp_solver_load(s, 5e-4, NULL);
    if (st != STC_OK) {
        assert_int_equal(st, STC_ENOCONV);
        assert_non_null(strstr(stc_errmsg(), "cut-back limit"));
    }
    asp_solver_destroy(&s);
}

/* The first-yield interference of a sphere: the substrate's ωc uncoated,
 * the smaller of the layers' ωc (each as a whole sphere) coated. */
static void test_omega_yield(void **state)
{
    (void)state;
    stc_params p;
    stc_material su, co;
    stc_critical c, cc;
    double w;
    stc_params_default(&p);
    stc_params_materials(&p, &su, &co);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    assert_int_equal(asp_omega_yield(&p, &w), STC_OK);
    assert_true(w == c.omega_c);
    p.t_over_R = 0.01, p.E_ratio = 2.0, p.Y_su = 200.0, p.Y_co = 300.0; /* coating yields first */
    stc_params_materials(&p, &su, &co);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    assert_int_equal(stc_critical_eval(&co, p.R, &cc), STC_OK);
    assert_true(cc.omega_c < c.omega_c);
    assert_int_equal(asp_omega_yield(&p, &w), STC_OK);
    assert_true(w == cc.omega_c);
    assert_int_equal(asp_omega_yield(NULL, &w), STC_EINVAL);
}

static void test_fields(void **state)
{
    (void)state;
    stc_params p;
    asp_solver *s = NULL;
    char dir[256], path[512];
    snprintf(dir, sizeof dir, "%s/stc_fieldsXXXXXX", test_tmpdir());
    assert_non_null(mkdtemp(dir));
    stc_params_default(&p);
    p.t_over_R = 0.01, p.E_ratio = 2.0;
    assert_int_equal(asp_solver_create(&p, NULL, 3e-4, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, 3e-4, NULL), STC_OK);
    snprintf(path, sizeof path, "%s/f", dir);
    H5E_auto2_t fn0 = NULL, fn1 = NULL;
    void *data0 = NULL, *data1 = NULL;
    H5Eget_auto2(H5E_DEFAULT, &fn0, &data0);
    assert_int_equal(asp_solver_write_fields(s, path), STC_OK);
    /* the caller's HDF5 error reporting is left as it was */
    H5Eget_auto2(H5E_DEFAULT, &fn1, &data1);
    assert_true(fn0 != NULL && fn1 == fn0 && data1 == data0);
    snprintf(path, sizeof path, "%s/f.xmf", dir);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char buf[4096];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    assert_non_null(strstr(buf, "Quadrilateral"));
    assert_non_null(strstr(buf, "f.h5:/von_mises"));
    remove(path);
    snprintf(path, sizeof path, "%s/f.h5", dir);
    assert_int_equal(access(path, R_OK), 0);
    /* the heavy data: load attribute and one von Mises value per element */
    asp_point pt;
    asp_info in;
    asp_solver_load(s, 3e-4, &pt);
    asp_solver_info(s, &in);
    hid_t h = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(h >= 0);
    double P = 0.0;
    hid_t at = H5Aopen(h, "P_N", H5P_DEFAULT);
    assert_true(at >= 0 && H5Aread(at, H5T_NATIVE_DOUBLE, &P) >= 0);
    H5Aclose(at);
    assert_true(fabs(P - pt.P) <= 1e-12 * pt.P && P > 0.0);
    hid_t ds = H5Dopen2(h, "/von_mises", H5P_DEFAULT), sp = H5Dget_space(ds);
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(sp, dims, NULL);
    assert_int_equal((int)dims[0], in.elements);
    H5Sclose(sp), H5Dclose(ds), H5Fclose(h);
    remove(path);
    snprintf(path, sizeof path, "%s/nodir/f", dir);
    assert_int_equal(asp_solver_write_fields(s, path), STC_EIO);
    H5Eget_auto2(H5E_DEFAULT, &fn1, &data1);
    assert_true(fn1 == fn0 && data1 == data0);
    rmdir(dir);
    asp_solver_destroy(&s);
}

/* A one-thread solver of the default homogeneous sphere (slip) on mesh
 * `level`, meshed for delta_max = dmax wc_su, sampling the elastic node
 * entries (asp_options.sample_elastic) if `sample`; *c gets its critical
 * values. */
static asp_solver *curve_solver(int level, double dmax, int sample, stc_critical *c)
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_material su;
    stc_params_default(&p);
    stc_params_materials(&p, &su, NULL);
    stc_critical_eval(&su, p.R, c);
    asp_options_default(&o);
    o.mesh_level = level;
    o.threads = 1;
    o.sample_elastic = sample;
    assert_int_equal(asp_solver_create(&p, &o, dmax * c->omega_c, &s), STC_OK);
    return s;
}

/* P, P_smooth, A, A_smooth (normalised) at d[0..n-1] of one curve. */
static void curve_run(int level, int n, const double *d, double *P, double *Ps, double *A,
                      double *As, int *incr)
{
    stc_critical c;
    asp_point pt;
    asp_solver *s = curve_solver(level, d[n - 1], 0, &c);
    for (int i = 0; i < n; i++) {
        assert_int_equal(asp_solver_load(s, d[i] * c.omega_c, &pt), STC_OK);
        P[i] = pt.P / c.P_c;
        A[i] = pt.A / c.A_c;
        *incr = pt.increments;
    }
    /* as the CLI does for a curve: on past the end, so the last points'
     * windows have both sides */
    assert_int_equal(asp_solver_load_tail(s, NULL), STC_OK);
    for (int i = 0; i < n; i++) {
        assert_true(asp_solver_P_smooth(s, d[i] * c.omega_c, &Ps[i]) >= 5);
        assert_true(asp_solver_A_smooth(s, d[i] * c.omega_c, &As[i]) >= 5);
        Ps[i] /= c.P_c;
        As[i] /= c.A_c;
    }
    asp_solver_destroy(&s);
}

/* Load curve past yield (slip, homogeneous) on meshes 0 and 1: the raw P
 * is a sawtooth (one tooth per surface node entering the contact), the
 * smoothed load asp_solver_P_smooth agrees across the two meshes; the
 * contact area steps with the same entries and asp_solver_A_smooth brings
 * the two meshes together too. */
static void test_smooth_load(void **state)
{
    (void)state;
    enum { N = 5 };
    const double d[N] = {6, 12, 18, 24, 30};
    double P0[N], S0[N], P1[N], S1[N], A0[N], T0[N], A1[N], T1[N], raw = 0.0, sm = 0.0;
    double raw_A = 0.0, sm_A = 0.0;
    int i0, i1;
    curve_run(0, N, d, P0, S0, A0, T0, &i0);
    curve_run(1, N, d, P1, S1, A1, T1, &i1);
    for (int i = 0; i < N; i++) {
        printf("# delta/wc %4.0f: P/Pc %.3f | %.3f (levels 0 | 1), smoothed %.3f | %.3f; A/Ac "
               "%.3f | %.3f, smoothed %.3f | %.3f\n", d[i], P0[i], P1[i], S0[i], S1[i], A0[i],
               A1[i], T0[i], T1[i]);
        raw = fmax(raw, fabs(P0[i] / P1[i] - 1));
        sm = fmax(sm, fabs(S0[i] / S1[i] - 1));
        raw_A = fmax(raw_A, fabs(A0[i] / A1[i] - 1));
        sm_A = fmax(sm_A, fabs(T0[i] / T1[i] - 1));
        /* the smoothed curves stay within the steps' reach */
        assert_true(fabs(S1[i] / P1[i] - 1) < 0.06);
        assert_true(fabs(T1[i] / A1[i] - 1) < 0.06);
    }
    printf("# max level 0/1 difference of A: raw %.2f %%, smoothed %.2f %%\n", 100 * raw_A,
           100 * sm_A);
    /* measured: raw 5.34 %, smoothed 1.07 % */
    assert_true(sm_A < 0.015 && sm_A < 0.5 * raw_A);
    printf("# max level 0/1 difference: raw %.2f %%, smoothed %.2f %% (%d, %d increments)\n",
           100 * raw, 100 * sm, i0, i1);
    /* measured: raw 3.7 %, smoothed 0.14 % with the tail (without it the
     * end point's one-sided window read 0.58 % on the earlier mesh and 1.13 %
     * on the proportionally graded one: its tooth phase) */
    assert_true(sm < 0.01);
}

/* The reference curve 1:60:12 wc (slip) on mesh level 0 as the CLI solves
 * it: elastic node entries sampled (asp_options.sample_elastic) and loaded
 * on past the last point (asp_solver_load_tail).  Reference: P_smooth of
 * `stiction asperity --delta 1:60:12 --contact slip --mesh 3` (42292 DOFs;
 * the level-3 mesh without the proportional surface grading agrees within
 * 0.05 % at every point), stored in data/fe/slip-curve-level3.csv.
 * Measured at level 0: +0.26 +0.29 +0.12 -0.11 +0.03 +0.06 +0.11 +0.13
 * +0.12 +0.15 +0.17 +0.13 %; without the tail the last two points read one
 * side of their window; without the elastic
 * sampling the 1 wc window is fitted across the yield bend from a few
 * increments (+0.8 %, docs/design.md §3.3). */
static void test_smooth_tail(void **state)
{
    (void)state;
    enum { N = 12 };
    static const char *const cols[] = {"delta_over_omega_c", "P_smooth_N"};
    double d3[N], P3[N], *ref[] = {d3, P3}; /* ωc, N */
    assert_int_equal(data_read_columns("fe/slip-curve-level3.csv", 2, cols, ref, N), N);
    for (int i = 0; i < N; i++) assert_true(fabs(d3[i] - (1.0 + i * 59.0 / 11.0)) < 1e-6);
    stc_critical c;
    asp_point pt;
    double one[2], P, worst = 0.0;
    asp_solver *s = curve_solver(0, 60.0, 1, &c);
    for (int i = 0; i < N; i++)
        assert_int_equal(asp_solver_load(s, (1.0 + i * 59.0 / 11.0) * c.omega_c, &pt), STC_OK);
    for (int i = 0; i < 2; i++)
        assert_true(asp_solver_P_smooth(s, (1.0 + (i + 10) * 59.0 / 11.0) * c.omega_c, &one[i]));
    /* loading past the meshed maximum needs the tail call */
    assert_int_equal(asp_solver_load(s, 61.0 * c.omega_c, &pt), STC_EINVAL);
    assert_int_equal(asp_solver_load_tail(s, &pt), STC_OK);
    assert_true(fabs(pt.delta / (90.0 * c.omega_c) - 1) < 1e-9);
    for (int i = 0; i < N; i++) {
        assert_true(asp_solver_P_smooth(s, (1.0 + i * 59.0 / 11.0) * c.omega_c, &P) >= 5);
        printf("# P_smooth at %4.1f wc: %+.2f %% vs level 3", 1.0 + i * 59.0 / 11.0,
               100 * (P / P3[i] - 1));
        if (i >= 10) printf(" (one-sided before the tail %+.2f %%)", 100 * (one[i - 10] / P3[i] - 1));
        printf("\n");
        worst = fmax(worst, fabs(P / P3[i] - 1));
    }
    printf("# worst %.2f %%, %d increments\n", 100 * worst, pt.increments);
    assert_true(worst < 0.005);
    /* a second call has nothing left to do */
    assert_int_equal(asp_solver_load_tail(s, &pt), STC_OK);
    asp_solver_destroy(&s);
    /* the option is checked */
    stc_params p;
    asp_options o;
    stc_params_default(&p);
    asp_options_default(&o);
    o.sample_elastic = 2;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "sample-elastic = 2"));
    assert_null(s);
}

/* elements_per_contact: 6 is mesh level 0 exactly; 8 adds DOFs and stays
 * within 0.5 % of level 1 (Hertz a/R = 0.01).  P is NOT monotone in n:
 * measured P - P(level 2) = +0.25 % (level 0), +0.41 % (n = 8), +0.13 %
 * (level 1); the contact edge sits at 5.5, 7.3 and 10.9 element sizes, and
 * P depends on where it falls between two nodes (the node-entry sawtooth),
 * so there is no "closer than level 0" check.  Bad values are rejected.
 * The 3D mesh takes the same knob (DOFs only: its solves are slow). */
static void test_elements_per_contact(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    asp_point pt;
    asp_info in;
    double P[3], delta = 0.001;
    int dofs[3];
    const double n[3] = {6.0, 0.0, 8.0}; /* 0: from the level */
    hertz_params(&p);
    for (int k = 0; k < 3; k++) {
        asp_options_default(&o);
        o.mesh_level = 0, o.threads = 1, o.elements_per_contact = n[k];
        assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
        assert_int_equal(asp_solver_load(s, delta, &pt), STC_OK);
        asp_solver_info(s, &in);
        P[k] = pt.P, dofs[k] = in.dofs;
        asp_solver_destroy(&s);
    }
    double P1 = hertz_run(1, delta, &pt);
    printf("# Hertz a/R = 0.01: P level 0 %.6g, n = 8 %.6g, level 1 %.6g N (%d, %d DOFs)\n",
           P[1], P[2], P1, dofs[1], dofs[2]);
    assert_true(P[0] == P[1] && dofs[0] == dofs[1]);
    assert_true(dofs[2] > dofs[1]);
    assert_true(fabs(P[2] / P1 - 1) < 0.005);
    asp_options_default(&o);
    o.elements_per_contact = 2.0;
    assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "elements per contact = 2"));
    /* 3D: n = 6 is level 0; n = 8 lies between levels 0 and 1 */
    int d3[3];
    for (int k = 0; k < 3; k++) {
        asp_options_default(&o);
        o.geom = ASP_GEOM_3D, o.threads = 1;
        o.mesh_level = k == 2 ? 1 : 0, o.elements_per_contact = k == 1 ? 8.0 : 0.0;
        if (k == 0) o.elements_per_contact = 6.0;
        assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
        asp_solver_info(s, &in);
        d3[k] = in.dofs;
        asp_solver_destroy(&s);
    }
    asp_options_default(&o);
    o.geom = ASP_GEOM_3D, o.mesh_level = 0;
    assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
    asp_solver_info(s, &in);
    asp_solver_destroy(&s);
    printf("# 3D DOFs: level 0 %d, n = 6 %d, n = 8 %d, level 1 %d\n", in.dofs, d3[0], d3[1], d3[2]);
    assert_int_equal(d3[0], in.dofs);
    assert_true(d3[1] > d3[0] && d3[1] < d3[2]);
    /* the default level is the model's own: 0 in 3D, "fine" one above */
    int dd[2];
    for (int k = 0; k < 2; k++) {
        asp_options_default(&o);
        o.geom = ASP_GEOM_3D, o.threads = 1;
        if (k) o.mesh_level = ASP_MESH_FINE;
        assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
        asp_solver_info(s, &in);
        dd[k] = in.dofs;
        asp_solver_destroy(&s);
    }
    assert_int_equal(dd[0], d3[0]);
    assert_int_equal(dd[1], d3[2]);
}

/* 3D half model against the axisymmetric model, Hertz a/R = 0.01, coarsest
 * 3D mesh (its discretization dominates): measured P -0.05 %, a +0.66 %,
 * 2 s (P +1.35 % with the 3D mesh before the perf3d rework). */
static void test_3d_vs_axisym(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    asp_point p3, p2;
    double delta = 0.01 * 0.01 * 10.09;
    hertz_params(&p);
    asp_options_default(&o);
    o.mesh_level = 0;
    o.geom = ASP_GEOM_3D;
    assert_int_equal(asp_solver_create(&p, &o, delta, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, delta, &p3), STC_OK);
    asp_solver_destroy(&s);
    hertz_run(2, delta, &p2);
    printf("# 3D level 0 vs axisymmetric level 2: P %+.2f %%, a %+.2f %% (%.1f s)\n",
           100 * (p3.P / p2.P - 1), 100 * (p3.a / p2.a - 1), p3.wall_s);
    assert_true(fabs(p3.P / p2.P - 1) < 0.01);
    assert_true(fabs(p3.a / p2.a - 1) < 0.02);
    assert_true(fabs(p3.P_base / p3.P - 1) < 1e-6);
}

/* One 3D Hertz point with options o: its point and mesh; the base
 * reaction must balance the contact load (a hanging node's force lost or
 * put on the wrong master would break it). */
static void hertz_3d(const asp_options *o, double delta, asp_point *pt, asp_info *in)
{
    stc_params p;
    asp_solver *s = NULL;
    hertz_params(&p);
    assert_int_equal(asp_solver_create(&p, o, delta, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, delta, pt), STC_OK);
    asp_solver_info(s, in);
    asp_solver_destroy(&s);
    assert_true(fabs(pt->P_base / pt->P - 1) < 1e-8);
}

/* Hanging nodes of the coarsened 3D shells (mesh3d.c, assemble.c
 * scatter_hang): the default (one 2:1 step from 6 a_max) and two steps
 * against the uncoarsened mesh.  A force of a hanging node lost or put on
 * the wrong master breaks the equilibrium of the base reaction with the
 * contact load.  Measured (Hertz a/R = 0.01, level 0): 23022 / 14976 /
 * 13689 DOFs, P +0.15 % / +0.22 %. */
static void test_hanging_nodes(void **state)
{
    (void)state;
    asp_options o;
    asp_info in;
    asp_point pt[3];
    int dofs[3];
    double delta = 0.01 * 0.01 * 10.09;
    for (int k = 0; k < 3; k++) {
        asp_options_default(&o);
        o.mesh_level = 0, o.geom = ASP_GEOM_3D, o.shell_coarsen = k == 0 ? 0 : k == 1 ? -1 : 2;
        hertz_3d(&o, delta, &pt[k], &in);
        dofs[k] = in.dofs;
    }
    printf("# hanging nodes: %d / %d / %d DOFs (none / default / 2 steps), P %+.3f %% / %+.3f %%\n",
           dofs[0], dofs[1], dofs[2], 100 * (pt[1].P / pt[0].P - 1), 100 * (pt[2].P / pt[0].P - 1));
    assert_true(dofs[1] < 0.7 * dofs[0] && dofs[2] < dofs[1]);
    assert_true(pt[1].P > pt[0].P && pt[1].P / pt[0].P - 1 < 0.003);
    assert_true(pt[2].P > pt[1].P && pt[2].P / pt[0].P - 1 < 0.004);
    assert_true(fabs(pt[1].a / pt[0].a - 1) < 0.002);
}

/* The band refined around the contact edge (refine3d.c): its hanging nodes
 * keep the equilibrium of the base reaction with the contact load, the
 * surface nodes added at the edge come into contact, and the elastic load
 * moves by what the finer contact sampling at the edge adds.  Hertz a/R =
 * 0.01, band at the Hertz radius; measured P against Hertz (converged
 * +0.62 %): n = 6: +0.665 / +1.034 / +1.099 % (0 / 1 / 2 levels), n = 7:
 * +0.751 / +0.947 / +0.989 %, n = 12: +0.735 / +0.812 / +0.819 %: node-to-flat
 * contact on the coarse edge lets the faces between nodes sink in (softer),
 * which cancelled part of the coarse hexahedra's stiffness. */
static void test_edge_band(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_info in[3];
    asp_point pt[3];
    double delta = 0.01 * 0.01 * 10.09;
    hertz_params(&p);
    for (int k = 0; k < 3; k++) {
        asp_options_default(&o);
        o.mesh_level = 0, o.geom = ASP_GEOM_3D, o.shell_coarsen = 0;
        o.edge_refine = k, o.edge_a0 = sqrt(p.R * delta);
        hertz_3d(&o, delta, &pt[k], &in[k]);
        assert_int_equal(in[k].edge_refine, k);
    }
    printf("# edge band 0 / 1 / 2 levels: %d / %d / %d DOFs, %d / %d / %d nodes in contact, "
           "P %+.3f %% / %+.3f %%, a %+.3f %% / %+.3f %%\n", in[0].dofs, in[1].dofs, in[2].dofs,
           pt[0].n_contact, pt[1].n_contact, pt[2].n_contact, 100 * (pt[1].P / pt[0].P - 1),
           100 * (pt[2].P / pt[0].P - 1), 100 * (pt[1].a / pt[0].a - 1),
           100 * (pt[2].a / pt[0].a - 1));
    assert_true(in[0].dofs < in[1].dofs && in[1].dofs < in[2].dofs);
    assert_true(pt[0].n_contact < pt[1].n_contact && pt[1].n_contact < pt[2].n_contact);
    for (int k = 1; k < 3; k++) {
        assert_true(pt[k].P > pt[0].P && pt[k].P / pt[0].P - 1 < 0.006);
        assert_true(fabs(pt[k].a / pt[0].a - 1) < 0.01);
    }
}

/* Coated stick run with the Newton steps solved by a factorization each
 * (krylov off) or by PCG preconditioned with the last factor (on). */
static void krylov_run(asp_krylov mode, asp_contact_law contact, asp_geom geom, asp_point *pt,
                       asp_yield y[2])
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_params_default(&p);
    p.t_over_R = 0.025, p.E_ratio = 2.0;
    asp_options_default(&o);
    o.contact = contact, o.mesh_level = 0, o.threads = 1, o.krylov = mode, o.geom = geom;
    /* 3D: 4 elements across the contact (16k DOFs, a supernodal factor as
     * at 6), 12 s instead of 95 s for the run without Krylov */
    if (geom == ASP_GEOM_3D) o.elements_per_contact = 4.0;
    stc_material su, co;
    stc_critical c;
    stc_params_materials(&p, &su, &co);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    assert_int_equal(asp_solver_create(&p, &o, 4.0 * c.omega_c, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, 4.0 * c.omega_c, pt), STC_OK);
    asp_solver_yield(s, 0, &y[0]), asp_solver_yield(s, 1, &y[1]);
    asp_solver_destroy(&s);
}

/* Newton-Krylov changes the cost, not the answer: the stick positions come
 * from the iterates (path dependent), so an inexact step would show.
 * Measured: the same 42 Newton iterations, answers equal to 5e-10,
 * 42 -> 8 factorizations (379 PCG iterations; PCG forced on: on this
 * axisymmetric mesh auto would factorize, factorizations being cheap).
 * Slip: see the printout (axisymmetric and 3D). */
static void test_krylov(void **state)
{
    (void)state;
    asp_point pd, pk;
    asp_yield yd[2], yk[2];
    krylov_run(ASP_KRYLOV_OFF, ASP_CONTACT_STICK, ASP_GEOM_AXISYM, &pd, yd);
    krylov_run(ASP_KRYLOV_ON, ASP_CONTACT_STICK, ASP_GEOM_AXISYM, &pk, yk);
    printf("# krylov: P %+.2e, a %+.2e, delta_c1 %+.2e relative; Newton %d -> %d, "
           "factorizations %d -> %d, PCG iterations %d\n",
           pk.P / pd.P - 1, pk.a / pd.a - 1, yk[1].delta / yd[1].delta - 1, pd.newton_iterations,
           pk.newton_iterations, pd.factorizations, pk.factorizations, pk.krylov_iterations);
    assert_true(yd[1].reached && yk[1].reached);
    assert_true(fabs(pk.P / pd.P - 1) < 1e-6);
    assert_true(fabs(pk.a / pd.a - 1) < 1e-6);
    assert_true(fabs(yk[1].delta / yd[1].delta - 1) < 1e-6);
    assert_int_equal(yk[0].reached, yd[0].reached);
    assert_int_equal(pk.increments, pd.increments);
    assert_int_equal(pd.krylov_iterations, 0);
    assert_true(pk.krylov_iterations > 0);
    assert_true(pk.factorizations * 2 < pd.factorizations);
    /* slip, where a factorization lasts many Newton steps */
    /* and in 3D, where the preconditioner is the float copy of the
     * supernodal factor (fsolve): were it wrong, PCG would fail and every
     * step would refactorize */
    for (int g = 0; g < 2; g++) {
        asp_geom geom = g ? ASP_GEOM_3D : ASP_GEOM_AXISYM;
        krylov_run(ASP_KRYLOV_OFF, ASP_CONTACT_SLIP, geom, &pd, yd);
        krylov_run(ASP_KRYLOV_ON, ASP_CONTACT_SLIP, geom, &pk, yk);
        printf("# krylov, slip, %s: P %+.2e, a %+.2e relative; Newton %d -> %d, "
               "factorizations %d -> %d, PCG iterations %d\n", g ? "3D" : "axisymmetric",
               pk.P / pd.P - 1, pk.a / pd.a - 1, pd.newton_iterations, pk.newton_iterations,
               pd.factorizations, pk.factorizations, pk.krylov_iterations);
        assert_true(fabs(pk.P / pd.P - 1) < 1e-6);
        assert_true(fabs(pk.a / pd.a - 1) < 1e-6);
        assert_int_equal(pk.increments, pd.increments);
        assert_true(pk.krylov_iterations > 0);
        assert_true(pk.factorizations * 4 < pd.factorizations);
    }
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_params_default(&p);
    asp_options_default(&o);
    o.krylov_max = 0;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "krylov max = 0"));
    assert_null(s);
}

/* P at d ωc (slip, axisymmetric level 0) with a return map and a number
 * of load steps per node entry. */
static double step_run(double d, asp_return_map rm, double spn, int *newton)
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    asp_point pt;
    stc_params_default(&p);
    asp_options_default(&o);
    o.geom = ASP_GEOM_AXISYM, o.mesh_level = 0, o.threads = 1;
    o.return_map = rm, o.steps_per_node = spn;
    stc_material su, co;
    stc_critical c;
    stc_params_materials(&p, &su, &co);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    assert_int_equal(asp_solver_create(&p, &o, d * c.omega_c, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, d * c.omega_c, &pt), STC_OK);
    asp_solver_destroy(&s);
    *newton = pt.newton_iterations;
    return pt.P;
}

/* The load's error from the increment size: the midpoint return is second
 * order, the radial return first (j2.c).  The raw P's increment error
 * depends on where δ falls in the node-entry sawtooth, so it is averaged
 * over δ = 29, 30, 31 ωc (level 0).  Measured, P at 2 against 8 steps per
 * node entry: midpoint +0.003 / +0.233 / +0.450 %, radial -0.250 / -1.242
 * / -1.829 %; at 28 and 32 ωc +0.07 / -0.74 % against -0.60 / -2.16 %.
 * (One δ alone, 30 ωc on the mesh before the proportional surface
 * grading, read +0.10 / -0.69 %.)  At 8 steps the midpoint agrees with
 * the radial return extrapolated to zero step as first order within
 * 0.008 / 0.054 / 0.037 %.  The skew-part corrections keep Newton
 * quadratic: at 8 steps the midpoint takes no more iterations than the
 * radial return with its symmetric tangent.  The exact integration along
 * each increment's straight strain path (Krieg & Krieg) sits between the
 * two: -0.033 / -0.336 / -1.802 % at 2 steps (mean 0.72 %, midpoint 0.23,
 * radial 1.11), because the real path within an increment is curved; at
 * 8 steps it agrees with the extrapolated radial return within 0.09 %. */
static void test_return_map_steps(void **state)
{
    (void)state;
    const double d[3] = {29.0, 30.0, 31.0};
    double em = 0.0, er = 0.0, ex = 0.0;
    int nm8 = 0, nr8 = 0;
    for (int i = 0; i < 3; i++) {
        int n2, n8, k2, k8, x2n, x8n;
        double m2 = step_run(d[i], ASP_RETURN_MIDPOINT, 2.0, &n2);
        double m8 = step_run(d[i], ASP_RETURN_MIDPOINT, 8.0, &n8);
        double r2 = step_run(d[i], ASP_RETURN_RADIAL, 2.0, &k2);
        double r8 = step_run(d[i], ASP_RETURN_RADIAL, 8.0, &k8);
        double x2 = step_run(d[i], ASP_RETURN_EXACT, 2.0, &x2n);
        double x8 = step_run(d[i], ASP_RETURN_EXACT, 8.0, &x8n);
        printf("# %.0f wc: P(2 steps/node) / P(8) - 1: midpoint %+.3f %%, radial %+.3f %%; "
               "Newton iterations midpoint %d / %d, radial %d / %d\n",
               d[i], 100 * (m2 / m8 - 1), 100 * (r2 / r8 - 1), n2, n8, k2, k8);
        printf("#   exact %+.3f %%, Newton iterations %d / %d\n", 100 * (x2 / x8 - 1), x2n, x8n);
        em += fabs(m2 / m8 - 1) / 3, er += fabs(r2 / r8 - 1) / 3, ex += fabs(x2 / x8 - 1) / 3;
        nm8 += n8, nr8 += k8;
        /* both converge to one answer: the radial return extrapolated as
         * first order in the step (Richardson, 2 and 8 steps) */
        double rx = r8 + (r8 - r2) / 3.0;
        printf("#   8 steps / radial extrapolated - 1: midpoint %+.3f %%, exact %+.3f %%\n",
               100 * (m8 / rx - 1), 100 * (x8 / rx - 1));
        assert_true(fabs(m8 / rx - 1) < 0.004);
        assert_true(fabs(x8 / rx - 1) < 0.004);
    }
    printf("# mean |error|: midpoint %.3f %%, radial %.3f %%, exact %.3f %%\n", 100 * em, 100 * er,
           100 * ex);
    /* the midpoint's error is a fraction of the radial return's, and inside
     * the 0.5 % the axisymmetric load curve is held to (docs/design.md §2.3) */
    assert_true(em < 0.5 * er);
    assert_true(em < 0.005);
    assert_true(er > 0.004);
    assert_true(nm8 < 1.25 * nr8);
}

/* Surface boundary layer (asp_options.surface_layers): at ν = 0.25 the
 * stick first yield sits on the stuck surface near the axis (Brizmer et al.
 * 2006: the stick yield point moves to the surface as ν falls), which the
 * Gauss points of a full-size top row see 0.21 h below it.  The automatic
 * layers (3 under stick) must lower δ_y and move the yield point onto the
 * surface; under slip (yield at 0.48 a below the surface) they must not
 * matter.  Level 1, measured: stick δ_y/ωc 0.8125 (0 layers, depth 1.9e-3
 * mm) → 0.8006 (auto, depth 2.4e-4 mm); slip 0.9800 → 0.9808. */
static double layers_run(asp_contact_law law, int layers, double *depth, double *ac)
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_material su;
    stc_critical c;
    asp_yield y;
    stc_params_default(&p);
    p.nu = 0.25;
    stc_params_materials(&p, &su, NULL);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    asp_options_default(&o);
    o.contact = law, o.surface_layers = layers, o.threads = 1;
    assert_int_equal(asp_solver_create(&p, &o, 1.3 * c.omega_c, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, 1.3 * c.omega_c, NULL), STC_OK);
    asp_solver_yield(s, 0, &y);
    assert_true(y.reached);
    *depth = p.R - y.z, *ac = sqrt(p.R * c.omega_c);
    asp_solver_destroy(&s);
    return y.delta / c.omega_c;
}

static void test_surface_layers(void **state)
{
    (void)state;
    double z0, za, zs0, zs3, ac;
    double d0 = layers_run(ASP_CONTACT_STICK, 0, &z0, &ac);
    double da = layers_run(ASP_CONTACT_STICK, -1, &za, &ac);
    double s0 = layers_run(ASP_CONTACT_SLIP, 0, &zs0, &ac);
    double s3 = layers_run(ASP_CONTACT_SLIP, 3, &zs3, &ac);
    printf("# nu = 0.25 stick delta_y/wc: %.4f (0 layers, depth/a_c %.4f), %.4f (auto, %.4f); "
           "slip %.4f -> %.4f (3 layers)\n", d0, z0 / ac, da, za / ac, s0, s3);
    assert_true(da < 0.992 * d0);                  /* measured -1.5 % */
    assert_true(za < 0.02 * ac && z0 > 0.05 * ac); /* onto the surface */
    assert_true(fabs(s3 / s0 - 1) < 0.003);        /* measured +0.08 % */
    /* the option is checked */
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    stc_params_default(&p);
    asp_options_default(&o);
    o.surface_layers = 7;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_EINVAL);
    o.surface_layers = 2, o.geom = ASP_GEOM_3D;
    assert_int_equal(asp_solver_create(&p, &o, 1e-4, &s), STC_EINVAL);
    assert_null(s);
}

/* Contact radius of an elastic–plastic (flat-topped) contact on a coarse
 * mesh: the homogeneous WSP sphere (E = 74 GPa, ν = 0.33, Y = 325 MPa,
 * R = 10.5 mm, slip) at δ = 6 ωc, level 1.  Reference a_ref = 0.28651 mm:
 * the mean of this estimator over six fine runs, levels 3 and 4 and
 * --elements-per-contact 40, 44, 52, 56 (spread 0.32 %; the old Hertz
 * two-node fit: mean 0.28576, spread 0.95 %; docs/design.md §3.7).
 * Level 1 measured: +1.41 % (0.29055 mm, 0.9 s); the old estimator gave
 * +5.0 % (0.30091 mm: a flat-topped pressure read as Hertz puts a outward). */
static void test_contact_radius_plastic(void **state)
{
    (void)state;
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    asp_point pt;
    stc_material su;
    stc_critical c;
    const double a_ref = 0.28651;
    stc_params_default(&p);
    p.R = 10.5, p.t_over_R = 0.0, p.E_su = 74000.0, p.nu = 0.33, p.Y_su = 325.0;
    stc_params_materials(&p, &su, NULL);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    asp_options_default(&o);
    o.mesh_level = 1, o.threads = 1;
    assert_int_equal(asp_solver_create(&p, &o, 6.0 * c.omega_c, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, 6.0 * c.omega_c, &pt), STC_OK);
    asp_solver_destroy(&s);
    printf("# WSP slip 6 wc, level 1: a = %.5f mm, a/a_ref - 1 = %+.2f %% (%.1f s)\n", pt.a,
           100 * (pt.a / a_ref - 1), pt.wall_s);
    assert_true(pt.plastic_points > 0);
    assert_true(fabs(pt.a / a_ref - 1) < 0.03);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hertz),       cmocka_unit_test(test_hertz_convergence),
        cmocka_unit_test(test_yield_slip),  cmocka_unit_test(test_yield_stick),
        cmocka_unit_test(test_coated_first_yield), cmocka_unit_test(test_errors),
        cmocka_unit_test(test_omega_yield), cmocka_unit_test(test_fields),      cmocka_unit_test(test_smooth_load),
        cmocka_unit_test(test_smooth_tail),
        cmocka_unit_test(test_3d_vs_axisym),
        cmocka_unit_test(test_hanging_nodes), cmocka_unit_test(test_elements_per_contact),
        cmocka_unit_test(test_edge_band),
        cmocka_unit_test(test_krylov),
        cmocka_unit_test(test_return_map_steps),
        cmocka_unit_test(test_surface_layers), cmocka_unit_test(test_contact_radius_plastic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
