/* Friction tables (include/stiction/table.h) at library level, without FE
 * runs: a table filled with the closed-form Hertz response, written and read
 * back, gives the same Greenwood–Williamson sums as the Hertz model itself;
 * every field survives the file; the interpolation is exact on a power law
 * and flags what lies outside or next to a missing point; the μs surrogate
 * smooths noise with honest error bars; foreign files, other families and
 * bad axes are refused with named messages; merging shards restores the
 * full table. */
#include <dirent.h>
#include <math.h>
#include <omp.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <cmocka.h>

#include <hdf5.h>

#include "stc_h5.h"
#include "stiction/asperity.h"
#include "stiction/formulas.h"
#include "stiction/gw.h"
#include "stiction/model.h"
#include "stiction/surface.h"
#include "stiction/table.h"
#include "table_impl.h" /* the refinement rule of a build onto a table */
#include "rand_util.h"
#include "tmp_util.h"

/* The grid of every table here: w = δ/ωc log-spaced over five decades. */
#define NW 40
#define W_LO 0.01
#define W_HI 1000.0
static const double TR[] = {0.005, 0.05};
static const double ER[] = {1.0, 2.0};
#define NTR 2
#define NE 2

/* The GW population: a fine-ground surface whose summits carry a coating
 * of T_MM, so t/R = T_MM / R_SUMMIT = 0.0143 lies inside the t/R axis. */
#define ETA 2000.0     /* summits per mm² */
#define R_SUMMIT 0.07  /* mm */
#define T_MM 1e-3      /* mm */

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

static void w_axis(double *w)
{
    for (int i = 0; i < NW; i++)
        w[i] = W_LO * pow(W_HI / W_LO, (double)i / (NW - 1));
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void check_ok(stc_status st, const char *what)
{
    if (st != STC_OK) fail_msg("%s: %s: %s", what, stc_strerror(st), stc_errmsg());
}

/* Materials of the default family (E/Y 1000 both layers, ν 0.32). */
static void family_params(double E_ratio, stc_params *p)
{
    stc_params_default(p);
    p->E_over_Y = 1000.0;
    p->nu = 0.32;
    p->E_ratio = E_ratio;
}

static asp_model *hertz_model(void)
{
    stc_params p;
    asp_model *m = NULL;
    family_params(1.5, &p);
    check_ok(asp_model_create_hertz(&p, T_MM, ASP_LAYER_SUBSTRATE, &m), "hertz model");
    return m;
}

/* A table of the default family on the grid above whose every point holds
 * the Hertz response and μs = μs_WSP(w) (1 + u), u uniform in ±noise, with
 * mu_s_err = err × μs.  Returns new. */
static tbl_table *hertz_table(double noise, double err, uint64_t seed)
{
    tbl_family f;
    tbl_numerics num;
    tbl_table *t = NULL;
    double w[NW];
    tbl_family_default(&f);
    tbl_numerics_default(&num);
    w_axis(w);
    check_ok(tbl_create(&f, &num, w, NW, TR, NTR, ER, NE, &t), "tbl_create");
    asp_model *hz = hertz_model();
    for (int i = 0; i < tbl_points(t); i++) {
        double wi, tR, E, P, A, Q;
        tbl_coords(t, i, &wi, &tR, &E);
        asp_model_eval_norm(hz, wi, tR, &P, &A, &Q);
        tbl_point p;
        memset(&p, 0, sizeof p);
        p.state = TBL_DONE;
        p.P_Pc = p.P_slide_Pc = P;
        p.A_Ac = A;
        p.mu_s = stc_wsp_mu(wi, NULL) * (1.0 + noise * (2.0 * unif(&seed) - 1.0));
        p.mu_s_err = err * p.mu_s;
        p.mu_s_preload = p.mu_s_min = p.mu_s_max = p.mu_s;
        p.Q_max_Pc = p.mu_s * P;
        p.members = 1;
        check_ok(tbl_point_set(t, i, &p), "tbl_point_set");
    }
    asp_model_destroy(&hz);
    return t;
}

/* ---- scratch directory ------------------------------------------------- */

/* The group's scratch directory (made by the group setup, removed by its
 * teardown, which runs even when a test fails); each test writing files
 * works in a subdirectory of its own. */
static int scratch_setup(void **state)
{
    char *dir = malloc(4096);
    if (!dir) return -1;
    snprintf(dir, 4096, "%s/stiction-table-XXXXXX", test_tmpdir());
    if (!mkdtemp(dir)) {
        free(dir);
        return -1;
    }
    *state = dir;
    return 0;
}

static int remove_tree(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    char path[512];
    int e = 0;
    for (struct dirent *en; (en = readdir(d));) {
        if (!strcmp(en->d_name, ".") || !strcmp(en->d_name, "..")) continue;
        snprintf(path, sizeof path, "%s/%s", dir, en->d_name);
        struct stat sb;
        if (lstat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) e |= remove_tree(path);
        else e |= unlink(path);
    }
    closedir(d);
    return e | rmdir(dir);
}

static int scratch_teardown(void **state)
{
    int e = *state ? remove_tree(*state) : 0;
    free(*state);
    *state = NULL;
    return e;
}

static void scratch_sub(void **state, const char *name, char *dir, size_t n)
{
    snprintf(dir, n, "%s/%s", (const char *)*state, name);
    assert_int_equal(mkdir(dir, 0700), 0);
}

/* A new scratch directory `name` and the path of `file` in it. */
static void scratch_file(void **state, const char *name, const char *file, char *path,
                         size_t n)
{
    char dir[128];
    scratch_sub(state, name, dir, sizeof dir);
    snprintf(path, n, "%s/%s", dir, file);
}

/* Names in dir ending in `suffix` (NULL: every entry). */
static int scratch_count(const char *dir, const char *suffix)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int k = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t ln = strlen(e->d_name), ls = suffix ? strlen(suffix) : 0;
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        if (!suffix || (ln >= ls && !strcmp(e->d_name + ln - ls, suffix))) k++;
    }
    closedir(d);
    return k;
}

/* ---- comparing points --------------------------------------------------- */

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* The first field in which a and b differ (numbers bitwise), or NULL. */
static const char *point_diff(const tbl_point *a, const tbl_point *b)
{
#define SAME_D(m) if (!same_bits(a->m, b->m)) return #m
#define SAME_I(m) if (a->m != b->m) return #m
    SAME_I(state);
    SAME_D(P_Pc);
    SAME_D(A_Ac);
    SAME_D(P_slide_Pc);
    SAME_D(Q_max_Pc);
    SAME_D(mu_s);
    SAME_D(mu_s_err);
    SAME_D(mu_s_preload);
    SAME_D(mu_s_min);
    SAME_D(mu_s_max);
    SAME_D(ux_slide_wc);
    SAME_D(mu_s_ux_slope);
    SAME_I(members);
    SAME_I(newton_iterations);
    SAME_I(factorizations);
    SAME_D(wall_s);
    SAME_D(cpu_s);
    SAME_I(copied);
    if (strcmp(a->reason, b->reason)) return "reason";
    /* the members kept, but their CPU times (a timing, as wall_s and cpu_s
     * above, which the callers set equal where they may differ) */
    SAME_I(ens.k);
    if (a->ens.k == 0) return NULL;
    SAME_I(ens.edge_refine);
    SAME_D(ens.period);
    SAME_D(ens.delta);
    SAME_D(ens.delta_mesh);
    SAME_D(ens.edge_a0);
    for (int j = 0; j < a->ens.k; j++) {
        SAME_D(ens.m[j].elements_per_contact);
        SAME_D(ens.m[j].P);
        SAME_D(ens.m[j].A);
        SAME_D(ens.m[j].P_slide);
        SAME_D(ens.m[j].Q_max);
        SAME_D(ens.m[j].ux_slide);
        SAME_D(ens.m[j].mu_s);
        SAME_D(ens.m[j].mu_s_preload);
        SAME_D(ens.m[j].mu_s_err);
        SAME_D(ens.m[j].mu_s_ux_slope);
        SAME_I(ens.m[j].newton_iterations);
        SAME_I(ens.m[j].factorizations);
    }
    return NULL;
#undef SAME_D
#undef SAME_I
}

/* ---- 1. Hertz through the file ------------------------------------------ */

/* A table holding Hertz, written and read back, is an asperity model whose
 * GW sums equal the closed-form Hertz model's (elastic GW 1966): the
 * Steffen cubic in ln P vs ln w is exact on the power law P/Pc = w^3/2, and
 * the columns agree, so only quadrature and rounding remain. */
static void test_hertz_through_file(void **state)
{
    char path[192];
    scratch_file(state, "hertz", "hertz.h5", path, sizeof path);
    tbl_table *t = hertz_table(0.0, 0.02, 1), *r = NULL;
    check_ok(tbl_write(t, path), "tbl_write");
    check_ok(tbl_read(path, &r), "tbl_read");

    stc_params p;
    family_params(1.5, &p); /* between the E_ratio nodes */
    asp_model *hz = hertz_model(), *tm = NULL;
    check_ok(tbl_model_create(r, &p, T_MM, TBL_MODEL_PRELOAD, &tm), "tbl_model_create");
    asp_model_range rg;
    asp_model_get_range(tm, &rg);
    assert_true(rel(rg.w_lo, W_LO) < 1e-12 && rel(rg.w_hi, W_HI) < 1e-12 && rg.coating_aware);

    /* σs = 3 ωc: the load's 99.9 % quantile stays at δ/ωc of order 10 */
    double wc = asp_model_omega_c(hz, R_SUMMIT), sigma_s = 3.0 * wc;
    srf_gw *gh = NULL, *gt = NULL;
    check_ok(srf_gw_create_gaussian(hz, ETA, R_SUMMIT, sigma_s, NULL, &gh), "gw hertz");
    check_ok(srf_gw_create_gaussian(tm, ETA, R_SUMMIT, sigma_s, NULL, &gt), "gw table");
    const double H[] = {-1.0, 0.0, 0.5, 1.0, 2.0, 3.0};
    double worst = 0.0;
    for (int i = 0; i < 6; i++) {
        srf_gw_point a, b;
        check_ok(srf_gw_at_separation(gh, H[i], &a), "gw at separation (hertz)");
        check_ok(srf_gw_at_separation(gt, H[i], &b), "gw at separation (table)");
        double eP = rel(b.pressure_MPa, a.pressure_MPa), eA = rel(b.area_fraction,
                                                                  a.area_fraction);
        worst = fmax(worst, fmax(eP, eA));
        printf("  h = %4.1f: P/An %.6e MPa (hertz %.6e), A/An %.6e (hertz %.6e), "
               "delta_max %.2f wc, load outside %.1e\n", H[i], b.pressure_MPa,
               a.pressure_MPa, b.area_fraction, a.area_fraction,
               b.delta_max_over_omega_c, b.load_fraction_outside);
        assert_true(b.delta_max_over_omega_c > W_LO && b.delta_max_over_omega_c < W_HI);
        assert_true(b.load_fraction_outside < 1e-3);
        assert_true(b.tR_min >= TR[0] && b.tR_max <= TR[NTR - 1]);
    }
    printf("Hertz table through the file (%d points, sigma_s = %.3g mm = 3 wc): GW sums "
           "vs closed-form Hertz, worst rel difference %.2e\n", tbl_points(r), sigma_s,
           worst);
    assert_true(worst < 1e-3);

    srf_gw_destroy(&gh);
    srf_gw_destroy(&gt);
    asp_model_destroy(&tm);
    asp_model_destroy(&hz);
    tbl_destroy(&r);
    tbl_destroy(&t);
    assert_null(t);
}

/* ---- 2. round trip -------------------------------------------------------- */

static void distinct_point(tbl_table *t, int i)
{
    tbl_point p = *tbl_point_get(t, i);
    /* numbers that use the whole mantissa, so a float or text step shows */
    p.ux_slide_wc = 1.0 / (i + 3.0);
    p.mu_s_ux_slope = 1.0 / (i + 29.0);
    p.mu_s_min = p.mu_s * (1.0 - 1.0 / (i + 7.0));
    p.mu_s_max = p.mu_s * (1.0 + 1.0 / (i + 11.0));
    p.mu_s_preload = p.mu_s * M_PI / 3.0;
    p.members = 1 + i % 4;
    p.newton_iterations = 10 * i + 7;
    p.factorizations = 3 * i + 1;
    p.wall_s = 0.1 * i + 1.0 / 3.0;
    p.cpu_s = 0.2 * i + 1.0 / 7.0;
    snprintf(p.reason, sizeof p.reason, "shear: tau reached tau_c over the contact (point %d)",
             i);
    memset(&p.ens, 0, sizeof p.ens);
    if (p.state == TBL_DONE && i % 3 == 0) { /* members kept at every third point */
        p.ens.k = p.members;
        p.ens.edge_refine = i % 3;
        p.ens.period = 1.0 + 1.0 / (i + 13.0);
        p.ens.delta = 1e-3 / (i + 17.0);
        p.ens.delta_mesh = p.ens.delta * M_E;
        p.ens.edge_a0 = 0.1 / (i + 19.0);
        for (int j = 0; j < p.ens.k; j++) {
            tbl_member *m = &p.ens.m[j];
            double x = 1.0 / (i + j + 23.0);
            m->elements_per_contact = 6.0 + x, m->P = 10.0 + x, m->A = 0.01 + x;
            m->P_slide = 9.0 + x, m->Q_max = 3.0 + x, m->ux_slide = 1e-3 * x;
            m->mu_s = 0.3 + x, m->mu_s_preload = 0.29 + x, m->mu_s_err = 0.03 * x;
            m->cpu_s = 7.0 + x;
            m->mu_s_ux_slope = 0.1 + x;
            m->newton_iterations = 11 * j + i, m->factorizations = 3 * j + i;
        }
    }
    check_ok(tbl_point_set(t, i, &p), "tbl_point_set");
}

static void check_family_equal(const tbl_table *a, const tbl_table *b)
{
    tbl_family fa, fb;
    tbl_numerics na, nb;
    tbl_get_family(a, &fa);
    tbl_get_family(b, &fb);
    tbl_get_numerics(a, &na);
    tbl_get_numerics(b, &nb);
    assert_true(same_bits(fa.E_over_Y_su, fb.E_over_Y_su));
    assert_true(same_bits(fa.E_over_Y_co, fb.E_over_Y_co));
    assert_true(same_bits(fa.nu_su, fb.nu_su) && same_bits(fa.nu_co, fb.nu_co));
    assert_int_equal(fa.contact, fb.contact);
    assert_true(same_bits(fa.tau_c_over_Y_co, fb.tau_c_over_Y_co));
    assert_int_equal(fa.criterion, fb.criterion);
    assert_true(same_bits(fa.alpha, fb.alpha));
    assert_int_equal(na.mesh_level, nb.mesh_level);
    assert_true(same_bits(na.elements_per_contact, nb.elements_per_contact));
    assert_int_equal(na.placements, nb.placements);
    assert_int_equal(na.placements_max, nb.placements_max);
    assert_true(same_bits(na.refine_err, nb.refine_err));
    assert_true(same_bits(na.err_floor, nb.err_floor));
    assert_true(same_bits(na.err_single, nb.err_single));
    assert_true(same_bits(na.foot_rows, nb.foot_rows));
    for (int k = 0; k < 3; k++) {
        const double *xa, *xb;
        int n = tbl_axis(a, k, &xa);
        assert_int_equal(tbl_axis(b, k, &xb), n);
        assert_memory_equal(xa, xb, (size_t)n * sizeof *xa);
    }
    assert_true(tbl_same_build(a, b));
}

/* The commands that built a table before its own: a build onto a file with
 * another command (a fill onto a build, a build onto a fill) keeps the
 * file's, oldest first and not twice in a row; when they would not fit, the
 * oldest give way to a first line "..."; the file holds them. */
static void build_as(const char *path, const char *command, const unsigned char *none)
{
    tbl_table *r = NULL;
    tbl_build_opts o;
    tbl_build_opts_default(&o);
    o.only = none; /* nothing to compute: the file is written again */
    o.jobs = 1;
    check_ok(tbl_read(path, &r), "tbl_read");
    tbl_set_provenance(r, command, 0.0);
    check_ok(tbl_build(r, path, &o, NULL), "tbl_build");
    tbl_destroy(&r);
}

static void test_history(void **state)
{
    char dir[128], path[192];
    scratch_sub(state, "history", dir, sizeof dir);
    snprintf(path, sizeof path, "%s/history.h5", dir);
    tbl_table *t = hertz_table(0.01, 0.02, 7), *r = NULL;
    unsigned char *none = calloc((size_t)tbl_points(t), 1);
    assert_non_null(none);
    tbl_set_provenance(t, "first", 1.0);
    check_ok(tbl_write(t, path), "tbl_write");
    build_as(path, "second", none);
    build_as(path, "second", none); /* resumed: the same command */
    build_as(path, "third", none);
    check_ok(tbl_read(path, &r), "tbl_read");
    assert_string_equal(tbl_provenance(r, NULL), "third");
    assert_string_equal(tbl_history(r), "first\nsecond");
    tbl_destroy(&r);
    /* eight commands of 299 bytes: the file's 2048 bytes hold six */
    char c[8][300];
    for (int k = 0; k < 8; k++) {
        memset(c[k], 'a' + k, sizeof c[k] - 1);
        c[k][sizeof c[k] - 1] = '\0';
        build_as(path, c[k], none);
    }
    check_ok(tbl_read(path, &r), "tbl_read");
    const char *h = tbl_history(r);
    int lines = 1;
    for (const char *q = h; *q; q++) lines += *q == '\n';
    printf("  history after 11 builds: %zu bytes, %d lines (the first '...')\n", strlen(h),
           lines);
    assert_int_equal(lines, 7); /* "..." and six commands: c[1] to c[6] */
    assert_memory_equal(h, "...\nb", 5);
    const char *last = strrchr(h, '\n') + 1; /* the newest line: the command before c[7] */
    assert_string_equal(last, c[6]);
    for (const char *l = h + 4; l < last; l += 300) /* whole lines, in order */
        assert_true(l[299] == '\n' && l[0] == last[0] - (char)((last - l) / 300));
    assert_string_equal(tbl_provenance(r, NULL), c[7]);
    tbl_destroy(&r);
    /* a command with a line break (a quoted argument) is one line of it,
     * and that line is not repeated when the next command reads the same */
    build_as(path, "stiction table build --note 'two\nlines'", none);
    build_as(path, "stiction table build --note 'two lines'", none);
    build_as(path, "last", none);
    check_ok(tbl_read(path, &r), "tbl_read");
    h = tbl_history(r);
    const char *one = "stiction table build --note 'two lines'", *at = strstr(h, one);
    assert_non_null(at);
    assert_string_equal(at, one); /* the last line, once */
    assert_memory_equal(at - 300, c[7], 299); /* after c[7]: the break made no line */
    tbl_destroy(&r);
    tbl_destroy(&t);
    free(none);
}

/* Everything a file holds comes back bitwise.  A point that is not done
 * has no numbers: the file stores its doubles as NaN (its state, reason,
 * counts and timings are kept), so that a reader cannot take them for an
 * answer. */
static void test_round_trip(void **state)
{
    char dir[128], path[192];
    scratch_sub(state, "round-trip", dir, sizeof dir);
    snprintf(path, sizeof path, "%s/round-trip.h5", dir);

    /* a family and numerics other than the defaults, so a field read from
     * the wrong attribute or left at its default shows */
    tbl_table *h = hertz_table(0.01, 0.02, 7), *t = NULL, *r = NULL;
    tbl_family f;
    tbl_numerics num;
    tbl_family_default(&f);
    f.E_over_Y_su = 500.0;
    f.E_over_Y_co = 300.0;
    f.nu_su = 0.3;
    f.nu_co = 0.25;
    f.contact = ASP_CONTACT_SLIP;
    f.tau_c_over_Y_co = 0.5;
    f.criterion = ASP_SHEAR_CRIT_STIFFNESS;
    f.alpha = 0.2;
    tbl_numerics_default(&num);
    num.mesh_level = 1;
    num.elements_per_contact = 4.0;
    num.placements = 3;
    num.placements_max = 6;
    num.refine_err = 0.07;
    num.err_floor = 0.02;
    num.err_single = 0.05;
    num.foot_rows = 0.6; /* not the default */
    double w[NW];
    w_axis(w);
    check_ok(tbl_create(&f, &num, w, NW, TR, NTR, ER, NE, &t), "tbl_create");
    for (int i = 0; i < tbl_points(t); i++) {
        check_ok(tbl_point_set(t, i, tbl_point_get(h, i)), "tbl_point_set");
        distinct_point(t, i);
    }
    const int i_failed = 45, i_pending = 101;
    tbl_point p = *tbl_point_get(t, i_failed);
    p.state = TBL_FAILED;
    p.P_Pc = p.mu_s = 42.0; /* stale numbers of a failed run: not an answer */
    p.members = 0;
    p.ens.k = 0; /* no members kept */
    snprintf(p.reason, sizeof p.reason, "Newton diverged at load step 3 of the normal step "
             "(residual 1.2e+03 after 50 iterations)");
    check_ok(tbl_point_set(t, i_failed, &p), "tbl_point_set failed");
    p = *tbl_point_get(t, i_pending);
    p.state = TBL_PENDING;
    p.ens.k = 0;
    p.reason[0] = '\0';
    check_ok(tbl_point_set(t, i_pending, &p), "tbl_point_set pending");
    /* a command too long for the file is cut at a character's start and
     * marked: here a two-byte μ over bytes 507-508 goes whole */
    char longc[600];
    memset(longc, 'a', sizeof longc);
    memcpy(longc + 507, "\xce\xbc", 2);
    longc[sizeof longc - 1] = '\0';
    tbl_set_provenance(t, longc, 0.0);
    const char *pc = tbl_provenance(t, NULL);
    assert_int_equal(strlen(pc), 510);
    assert_string_equal(pc + 507, "...");
    assert_memory_equal(pc, longc, 507);
    tbl_set_provenance(t, "stiction table build --E-over-Y-su 500 --placements 3 "
                          "--output round-trip.h5", 1234.5678);

    check_ok(tbl_write(t, path), "tbl_write");
    assert_int_equal(scratch_count(dir, ".tmp"), 0);
    assert_int_equal(scratch_count(dir, NULL), 1);
    check_ok(tbl_read(path, &r), "tbl_read");

    check_family_equal(t, r);
    double wa, wb;
    assert_string_equal(tbl_provenance(r, &wb), tbl_provenance(t, &wa));
    assert_true(same_bits(wa, wb));
    int done, failed, pending;
    tbl_count(r, &done, &failed, &pending);
    assert_int_equal(done, tbl_points(t) - 2);
    assert_true(failed == 1 && pending == 1);

    int same = 0, kept = 0;
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *a = tbl_point_get(t, i), *b = tbl_point_get(r, i);
        if (i == i_failed || i == i_pending) continue;
        const char *d = point_diff(a, b);
        if (d) fail_msg("point %d: field %s differs after write + read", i, d);
        for (int j = 0; j < a->ens.k; j++)
            if (!same_bits(a->ens.m[j].cpu_s, b->ens.m[j].cpu_s))
                fail_msg("point %d: member %d's cpu_s differs after write + read", i, j);
        kept += a->ens.k > 0;
        same++;
    }
    /* the two points that are not done: everything but the numbers */
    int nan_fields = 0;
    for (int k = 0; k < 2; k++) {
        int i = k ? i_pending : i_failed;
        const tbl_point *a = tbl_point_get(t, i), *b = tbl_point_get(r, i);
        assert_int_equal(b->state, a->state);
        assert_string_equal(b->reason, a->reason);
        assert_int_equal(b->members, a->members);
        assert_int_equal(b->newton_iterations, a->newton_iterations);
        assert_int_equal(b->factorizations, a->factorizations);
        assert_true(same_bits(b->wall_s, a->wall_s) && same_bits(b->cpu_s, a->cpu_s));
        const double v[] = {b->P_Pc, b->A_Ac, b->P_slide_Pc, b->Q_max_Pc, b->mu_s,
                            b->mu_s_err, b->mu_s_preload, b->mu_s_min, b->mu_s_max,
                            b->ux_slide_wc};
        for (int j = 0; j < 10; j++) {
            assert_true(isnan(v[j]));
            nan_fields++;
        }
    }
    printf("round trip: %d done points equal in all 17 fields (bitwise), family, numerics, "
           "3 axes and provenance equal, no .tmp left; the failed point keeps state, reason "
           "'%.40s...', counts and timings, its %d numbers (and the pending point's) read "
           "back as NaN\n", same, tbl_point_get(r, i_failed)->reason, nan_fields / 2);
    printf("round trip: %d of them keep their placement members, equal field by field\n", kept);
    assert_true(kept > 10);

    /* the fit is recomputed on reading: the same as fitting the original */
    tbl_fit_info fa, fb;
    check_ok(tbl_fit(t), "tbl_fit");
    check_ok(tbl_get_fit_info(t, &fa), "fit info");
    check_ok(tbl_get_fit_info(r, &fb), "fit info (read)");
    assert_int_equal(fb.n, done);
    assert_true(same_bits(fa.loo_rms, fb.loo_rms) && same_bits(fa.noise_scale,
                                                                fb.noise_scale));

    /* writing over an existing table replaces it, again without leftovers */
    check_ok(tbl_write(r, path), "tbl_write over");
    assert_int_equal(scratch_count(dir, NULL), 1);

    tbl_destroy(&r);
    tbl_destroy(&t);
    tbl_destroy(&h);
}

/* ---- 3. interpolation ----------------------------------------------------- */

static void query_ok(const tbl_table *t, double w, double tR, double E, tbl_value *v)
{
    check_ok(tbl_query(t, w, tR, E, v), "tbl_query");
}

/* Hertz is a straight line in ln P vs ln w: the Steffen cubic and the
 * ln–ln chord both lie on it, so P/Pc = w^3/2 and A/Ac = w come back to
 * rounding and the error bar |cubic − line| is zero. */
static void test_interpolation(void **state)
{
    (void)state;
    tbl_table *t = hertz_table(0.0, 0.02, 1);
    check_ok(tbl_fit(t), "tbl_fit");
    const double *w;
    int nw = tbl_axis(t, 0, &w);
    const double tq[] = {0.005, 0.0081, 0.0158, 0.05}, eq[] = {1.0, 1.23, 1.5, 2.0};
    const double frac[] = {0.1, 0.5, 0.77};
    double worst = 0.0, worst_err = 0.0;
    int n = 0;
    for (int i = 0; i + 1 < nw; i++)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 4; b++)
                for (int c = 0; c < 4; c++) {
                    double x = exp((1 - frac[a]) * log(w[i]) + frac[a] * log(w[i + 1]));
                    tbl_value v;
                    query_ok(t, x, tq[b], eq[c], &v);
                    assert_int_equal(v.flags, 0);
                    worst = fmax(worst, fmax(rel(v.P_Pc, pow(x, 1.5)), rel(v.A_Ac, x)));
                    worst = fmax(worst, rel(v.P_slide_Pc, pow(x, 1.5)));
                    worst_err = fmax(worst_err, fmax(v.P_Pc_err / v.P_Pc, v.A_Ac_err / v.A_Ac));
                    assert_true(rel(v.Q_max_Pc, v.mu_s * v.P_slide_Pc) < 1e-14);
                    n++;
                }
    printf("interpolation on Hertz: %d queries between nodes, P/Pc vs w^1.5 and A/Ac vs w "
           "worst rel error %.2e, worst relative error bar %.2e\n", n, worst, worst_err);
    assert_true(worst < 1e-6);
    assert_true(worst_err < 1e-9);

    /* outside: flagged; w continues the end interval's power law (exact
     * here), t/R and Eco/Esu clamp to the edge column (all equal here) */
    static const struct { double w, tR, E; unsigned flag; const char *what; } out[] = {
        {0.003, 0.02, 1.5, TBL_OUT_W_LOW, "w below the first node"},
        {3000.0, 0.02, 1.5, TBL_OUT_W_HIGH, "w above the last node"},
        {1.0, 0.08, 1.5, TBL_OUT_T_OVER_R, "t/R above the last"},
        {1.0, 0.002, 1.5, TBL_OUT_T_OVER_R, "t/R below the first"},
        {1.0, 0.02, 3.0, TBL_OUT_E_RATIO, "E_ratio above the last"},
        {1.0, 0.02, 0.5, TBL_OUT_E_RATIO, "E_ratio below the first"},
    };
    for (int k = 0; k < 6; k++) {
        tbl_value v;
        query_ok(t, out[k].w, out[k].tR, out[k].E, &v);
        printf("  %-24s flags 0x%02x, P/Pc %.6e (w^1.5 %.6e)\n", out[k].what, v.flags,
               v.P_Pc, pow(out[k].w, 1.5));
        assert_int_equal(v.flags, out[k].flag);
        assert_true(rel(v.P_Pc, pow(out[k].w, 1.5)) < 1e-6);
    }
    /* exactly on the corner nodes: inside */
    tbl_value v;
    query_ok(t, W_LO, TR[0], ER[0], &v);
    assert_int_equal(v.flags, 0);
    query_ok(t, W_HI, TR[NTR - 1], ER[NE - 1], &v);
    assert_int_equal(v.flags, 0);

    /* a missing interior point: its neighbours' queries say so, the others
     * do not, and the cubic through the remaining points still is exact */
    const int iw = 20;
    tbl_point p = *tbl_point_get(t, iw); /* column (E 1, t/R 0.005) */
    p.state = TBL_PENDING;
    check_ok(tbl_point_set(t, iw, &p), "tbl_point_set pending");
    check_ok(tbl_fit(t), "tbl_fit after a point was reset");
    double below = sqrt(w[iw - 1] * w[iw]), above = sqrt(w[iw] * w[iw + 1]);
    double far = sqrt(w[iw + 5] * w[iw + 6]);
    tbl_value vb, va, vf, vo;
    query_ok(t, below, TR[0], ER[0], &vb);
    query_ok(t, above, TR[0], ER[0], &va);
    query_ok(t, far, TR[0], ER[0], &vf);
    query_ok(t, below, TR[1], ER[1], &vo); /* another column */
    printf("pending point at w = %.4g: flags below 0x%02x, above 0x%02x, 5 nodes away 0x%02x, "
           "other column 0x%02x; P/Pc rel error next to it %.1e\n", w[iw], vb.flags,
           va.flags, vf.flags, vo.flags, rel(vb.P_Pc, pow(below, 1.5)));
    assert_true(vb.flags & TBL_GAP);
    assert_true(va.flags & TBL_GAP);
    assert_int_equal(vf.flags, 0);
    assert_int_equal(vo.flags, 0);
    assert_true(rel(vb.P_Pc, pow(below, 1.5)) < 1e-6);
    /* between t/R columns the missing point's column is used too */
    query_ok(t, below, sqrt(TR[0] * TR[1]), ER[0], &v);
    assert_true(v.flags & TBL_GAP);

    /* missing end points: the column's power law is then continued from
     * the next interval inside the axis, which the flags must say too */
    const int base = (1 * NTR + 1) * NW; /* column (E 2, t/R 0.05) */
    for (int k = 0; k < 2; k++) {
        p = *tbl_point_get(t, base + k * (NW - 1));
        p.state = TBL_PENDING;
        check_ok(tbl_point_set(t, base + k * (NW - 1), &p), "tbl_point_set pending end");
    }
    check_ok(tbl_fit(t), "tbl_fit after the end points were reset");
    tbl_value vlo, vhi, vout;
    query_ok(t, sqrt(w[0] * w[1]), TR[1], ER[1], &vlo);
    query_ok(t, sqrt(w[nw - 2] * w[nw - 1]), TR[1], ER[1], &vhi);
    query_ok(t, 0.5 * w[0], TR[1], ER[1], &vout);
    printf("pending end points: flags in the first interval 0x%02x, in the last 0x%02x, "
           "below the axis 0x%02x\n", vlo.flags, vhi.flags, vout.flags);
    assert_int_equal(vlo.flags, TBL_GAP);
    assert_int_equal(vhi.flags, TBL_GAP);
    assert_int_equal(vout.flags, TBL_GAP | TBL_OUT_W_LOW);

    tbl_destroy(&t);
}

/* ---- 4. μs smoothing ----------------------------------------------------- */

/* μs = μs_WSP(w) (1 + u), u uniform in ±3 %, each point claiming 3 %: the
 * surrogate models ln μs − ln μs_WSP, here pure noise, so its posterior mean
 * lies closer to the noise-free curve than the data and its error bar
 * covers the truth. */
static void test_mu_smoothing(void **state)
{
    (void)state;
    const double noise = 0.03;
    tbl_table *t = hertz_table(noise, noise, 20240611);
    double t0 = now();
    check_ok(tbl_fit(t), "tbl_fit");
    double fit_s = now() - t0;
    tbl_fit_info fi;
    check_ok(tbl_get_fit_info(t, &fi), "tbl_get_fit_info");

    double ss_data = 0.0, ss_fit = 0.0;
    for (int i = 0; i < tbl_points(t); i++) {
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        double truth = stc_wsp_mu(w, NULL);
        tbl_value v;
        query_ok(t, w, tR, E, &v);
        ss_data += pow(tbl_point_get(t, i)->mu_s / truth - 1.0, 2);
        ss_fit += pow(v.mu_s / truth - 1.0, 2);
    }
    int n = tbl_points(t);
    double rms_data = sqrt(ss_data / n), rms_fit = sqrt(ss_fit / n);

    const double *w;
    int nw = tbl_axis(t, 0, &w), mids = 0, within = 0;
    const double tq[] = {TR[0], sqrt(TR[0] * TR[1]), TR[1]}, eq[] = {1.0, M_SQRT2, 2.0};
    double worst_z = 0.0, ss_mid = 0.0;
    for (int i = 0; i + 1 < nw; i++)
        for (int b = 0; b < 3; b++)
            for (int c = 0; c < 3; c++) {
                double x = sqrt(w[i] * w[i + 1]), truth = stc_wsp_mu(x, NULL);
                tbl_value v;
                query_ok(t, x, tq[b], eq[c], &v);
                assert_true(isfinite(v.mu_s_err) && v.mu_s_err > 0.0);
                double z = fabs(v.mu_s - truth) / v.mu_s_err;
                worst_z = fmax(worst_z, z);
                within += z <= 2.0;
                ss_mid += pow(v.mu_s / truth - 1.0, 2);
                mids++;
            }
    double cover = (double)within / mids;
    printf("mu_s smoothing (%d points, +-%.0f %% uniform noise, mu_s_err %.0f %%, fit %.3f s): "
           "rms rel error at the nodes, data %.4f, surrogate %.4f; at %d midpoints %.4f, "
           "truth within 2 sd at %.1f %% (worst %.2f sd)\n", n, 100 * noise, 100 * noise,
           fit_s, rms_data, rms_fit, mids, sqrt(ss_mid / mids), 100 * cover, worst_z);
    printf("  fit: n %d, ell (ln w, ln t/R, ln E) = (%.3g, %.3g, %.3g), noise scale %.3f, "
           "LOO rms %.4f, max %.4f, cover2 %.3f\n", fi.n, fi.ell[0], fi.ell[1], fi.ell[2],
           fi.noise_scale, fi.loo_rms, fi.loo_max, fi.loo_cover2);
    assert_int_equal(fi.n, n);
    assert_true(rms_fit < rms_data);
    assert_true(cover >= 0.9);
    assert_true(isfinite(fi.loo_rms) && fi.loo_rms > 0.0);
    assert_true(isfinite(fi.loo_max) && fi.loo_max >= fi.loo_rms);
    tbl_destroy(&t);
}

/* The surrogate's hyperparameters go into the file with a hash of the data
 * they fit: reading the file takes them instead of searching again, and
 * the surrogate is the writer's bit for bit; a changed point, a stored set
 * that does not fit the data, or a file without the hash (older files) is
 * searched again, giving the fresh fit. */
static int same_query(const tbl_table *a, const tbl_table *b)
{
    const double q[][3] = {{0.37, 0.007, 1.3}, {5.1, 0.02, 1.9}, {240.0, 0.04, 1.0}};
    for (int k = 0; k < 3; k++) {
        tbl_value va, vb;
        query_ok(a, q[k][0], q[k][1], q[k][2], &va);
        query_ok(b, q[k][0], q[k][1], q[k][2], &vb);
        if (!same_bits(va.mu_s, vb.mu_s) || !same_bits(va.mu_s_err, vb.mu_s_err)) return 0;
    }
    return 1;
}

static int same_fit_info(const tbl_fit_info *a, const tbl_fit_info *b)
{
    return a->n == b->n && !memcmp(a->ell, b->ell, sizeof a->ell) &&
           same_bits(a->gamma, b->gamma) && same_bits(a->ell_base, b->ell_base) &&
           same_bits(a->noise_scale, b->noise_scale) && same_bits(a->loo_rms, b->loo_rms) &&
           same_bits(a->loo_max, b->loo_max) && same_bits(a->loo_cover2, b->loo_cover2);
}

/* Replace (or with v = NULL delete) attribute name of path's /fit. */
static void edit_fit_attr(const char *path, const char *name, const double *v, int n)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(f >= 0);
    hid_t g = H5Gopen2(f, "fit", H5P_DEFAULT);
    assert_true(g >= 0);
    assert_true(H5Adelete(g, name) >= 0);
    if (v) {
        hsize_t d = (hsize_t)n;
        hid_t sp = H5Screate_simple(1, &d, NULL);
        hid_t a = H5Acreate2(g, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
        assert_true(a >= 0 && H5Awrite(a, H5T_NATIVE_DOUBLE, v) >= 0);
        H5Aclose(a);
        H5Sclose(sp);
    }
    H5Gclose(g);
    H5Fclose(f);
}

static void test_fit_reused(void **state)
{
    char path[192];
    scratch_file(state, "fit-reused", "fit.h5", path, sizeof path);
    tbl_table *t = hertz_table(0.03, 0.03, 777), *r = NULL;
    double t0 = now();
    check_ok(tbl_fit(t), "tbl_fit");
    double dt_fit = now() - t0;
    tbl_fit_info ft, fr;
    check_ok(tbl_get_fit_info(t, &ft), "fit info");
    assert_int_equal(ft.reused, 0);
    check_ok(tbl_write(t, path), "tbl_write");

    t0 = now();
    check_ok(tbl_read(path, &r), "tbl_read");
    double dt_read = now() - t0;
    check_ok(tbl_get_fit_info(r, &fr), "fit info (read)");
    printf("fit reused: %d points, fit %.0f ms, the file read with its stored fit in %.0f ms; "
           "reused %d, info and queries %s\n", ft.n, 1e3 * dt_fit, 1e3 * dt_read, fr.reused,
           same_fit_info(&ft, &fr) && same_query(t, r) ? "bit-identical" : "DIFFER");
    assert_int_equal(fr.reused, 1);
    assert_true(same_fit_info(&ft, &fr) && same_query(t, r));
    check_ok(tbl_fit(r), "tbl_fit (unchanged)"); /* data unchanged: reused again */
    check_ok(tbl_get_fit_info(r, &fr), "fit info (refit)");
    assert_int_equal(fr.reused, 1);

    /* one point changed: searched again, as a table built with it would be */
    int i = tbl_points(r) / 3;
    tbl_point p = *tbl_point_get(r, i);
    p.mu_s *= 1.02;
    check_ok(tbl_point_set(r, i, &p), "tbl_point_set");
    check_ok(tbl_point_set(t, i, &p), "tbl_point_set");
    check_ok(tbl_fit(r), "tbl_fit (changed)");
    check_ok(tbl_get_fit_info(r, &fr), "fit info (changed)");
    assert_int_equal(fr.reused, 0);
    tbl_destroy(&r);

    /* stored hyperparameters of other data (hash intact): searched again */
    check_ok(tbl_fit(t), "tbl_fit (changed)");
    check_ok(tbl_get_fit_info(t, &ft), "fit info");
    check_ok(tbl_write(t, path), "tbl_write (changed)");
    const double junk[2] = {1e3, 0.0};
    edit_fit_attr(path, "hyperparameters", junk, 2);
    check_ok(tbl_read(path, &r), "tbl_read (junk hyperparameters)");
    check_ok(tbl_get_fit_info(r, &fr), "fit info");
    assert_int_equal(fr.reused, 0);
    assert_true(same_fit_info(&ft, &fr) && same_query(t, r));
    tbl_destroy(&r);
    /* no hash (a file from before the hash was stored): searched again */
    check_ok(tbl_write(t, path), "tbl_write");
    edit_fit_attr(path, "data_hash", NULL, 0);
    check_ok(tbl_read(path, &r), "tbl_read (no hash)");
    check_ok(tbl_get_fit_info(r, &fr), "fit info");
    assert_int_equal(fr.reused, 0);
    assert_true(same_fit_info(&ft, &fr) && same_query(t, r));
    printf("fit reused: a changed point, junk hyperparameters and a missing hash each "
           "searched again, the fresh fit to the bit\n");
    tbl_destroy(&r);
    tbl_destroy(&t);
}

/* ---- 5. refusals ----------------------------------------------------------- */

static void expect_fail(stc_status got, stc_status want, const char *what, const char *part1,
                        const char *part2)
{
    const char *msg = stc_errmsg();
    printf("  %-34s %s: %s\n", what, stc_strerror(got), msg);
    if (want == STC_OK) assert_int_not_equal(got, STC_OK);
    else assert_int_equal(got, want);
    if (part1 && !strstr(msg, part1)) fail_msg("%s: message lacks '%s'", what, part1);
    if (part2 && !strstr(msg, part2)) fail_msg("%s: message lacks '%s'", what, part2);
}

static void test_refusals(void **state)
{
    char dir[128], path[192];
    scratch_sub(state, "refusals", dir, sizeof dir);
    tbl_table *r = NULL;

    /* an HDF5 file of another kind: a surface map, and an empty file */
    srf_map *m = NULL;
    check_ok(srf_map_create(8, 8, 1.0, 1.0, &m), "srf_map_create");
    snprintf(path, sizeof path, "%s/map.h5", dir);
    check_ok(srf_map_write_h5(m, path), "srf_map_write_h5");
    srf_map_destroy(&m);
    expect_fail(tbl_read(path, &r), STC_EFORMAT, "surface map", "not a friction table", NULL);
    assert_null(r);
    snprintf(path, sizeof path, "%s/empty.h5", dir);
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(f >= 0);
    H5Fclose(f);
    expect_fail(tbl_read(path, &r), STC_EFORMAT, "empty HDF5 file", "not a friction table",
                NULL);

    /* a table of a format version this reader does not know */
    tbl_table *t = hertz_table(0.0, 0.02, 1);
    snprintf(path, sizeof path, "%s/future.h5", dir);
    check_ok(tbl_write(t, path), "tbl_write");
    f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(f >= 0);
    /* provenance: the writer's BLAS and the kernels it ran, as
     * asp_blas_kernels_get reports them */
    char blas[256], want[256];
    asp_blas_kernels k;
    asp_blas_kernels_get(&k);
    snprintf(want, sizeof want, "%s; kernels %s", k.config, k.in_use);
    assert_int_equal(stc_h5_get_s(f, "blas", blas, sizeof blas), 0);
    assert_string_equal(blas, want);
    assert_non_null(strstr(blas, "OpenBLAS"));
    hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    int ver = 99;
    assert_true(a >= 0 && H5Awrite(a, H5T_NATIVE_INT, &ver) >= 0);
    H5Aclose(a);
    H5Fclose(f);
    expect_fail(tbl_read(path, &r), STC_EFORMAT, "format version 99", "version 99", NULL);

    /* a text file, a truncated table, a directory, nothing */
    snprintf(path, sizeof path, "%s/table.csv", dir);
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("delta_over_omega_c,P_over_P_c\n1,1\n", fp);
    fclose(fp);
    expect_fail(tbl_read(path, &r), STC_EFORMAT, "text file", "not an HDF5 file", NULL);
    snprintf(path, sizeof path, "%s/truncated.h5", dir);
    check_ok(tbl_write(t, path), "tbl_write");
    struct stat sb;
    assert_int_equal(stat(path, &sb), 0);
    assert_int_equal(truncate(path, sb.st_size / 2), 0);
    expect_fail(tbl_read(path, &r), STC_OK, "table cut in half", NULL, NULL);
    assert_null(r);
    expect_fail(tbl_read(dir, &r), STC_OK, "directory", "directory", NULL);
    snprintf(path, sizeof path, "%s/missing.h5", dir);
    expect_fail(tbl_read(path, &r), STC_OK, "missing file", "cannot open", NULL);
    assert_null(r);

    /* materials of another family, Eco/Esu outside the axis */
    stc_params p;
    asp_model *tm = NULL;
    check_ok(tbl_fit(t), "tbl_fit");
    family_params(1.5, &p);
    p.nu = 0.3;
    expect_fail(tbl_model_create(t, &p, T_MM, TBL_MODEL_PRELOAD, &tm), STC_EINVAL,
                "nu 0.3 against nu 0.32", "materials:", "table:");
    assert_true(strstr(stc_errmsg(), "nu 0.3,") && strstr(stc_errmsg(), "nu 0.32,"));
    assert_null(tm);
    family_params(3.0, &p);
    expect_fail(tbl_model_create(t, &p, T_MM, TBL_MODEL_PRELOAD, &tm), STC_ERANGE,
                "E_ratio 3 on the axis [1, 2]", "E-ratio = 3", "[1, 2]");
    assert_null(tm);

    /* axes that do not increase */
    tbl_family fam;
    tbl_numerics num;
    tbl_family_default(&fam);
    tbl_numerics_default(&num);
    double w[NW], down[] = {0.05, 0.005}, flat[] = {1.0, 1.0};
    w_axis(w);
    tbl_table *bad = NULL;
    expect_fail(tbl_create(&fam, &num, w, NW, down, 2, ER, NE, &bad), STC_EINVAL,
                "decreasing t/R", "t/R", "increase");
    assert_null(bad);
    double wd[NW];
    for (int i = 0; i < NW; i++) wd[i] = w[NW - 1 - i];
    expect_fail(tbl_create(&fam, &num, wd, NW, TR, NTR, ER, NE, &bad), STC_EINVAL,
                "decreasing w", "delta/omega_c", "increase");
    expect_fail(tbl_create(&fam, &num, w, NW, TR, NTR, flat, 2, &bad), STC_EINVAL,
                "repeated E_ratio", "E-ratio", "increase");
    assert_null(bad);

    /* merging tables of other axes */
    tbl_table *other = NULL, *merged = NULL;
    double w2[NW];
    for (int i = 0; i < NW; i++) w2[i] = 2.0 * w[i];
    check_ok(tbl_create(&fam, &num, w2, NW, TR, NTR, ER, NE, &other), "tbl_create");
    tbl_table *parts[2] = {t, other};
    expect_fail(tbl_merge(parts, 2, &merged), STC_EINVAL, "merge of other w axes", "another "
                "build", NULL);
    assert_null(merged);

    tbl_destroy(&other);
    tbl_destroy(&t);
}

/* ---- 6. merge ----------------------------------------------------------------- */

/* Two shards (points split by index parity, the rest pending) merge into
 * the full table, point by point and bitwise. */
static void test_merge(void **state)
{
    (void)state;
    tbl_table *full = hertz_table(0.03, 0.03, 5);
    for (int i = 0; i < tbl_points(full); i++) distinct_point(full, i);
    tbl_point p = *tbl_point_get(full, 33);
    p.state = TBL_FAILED; /* a failed point travels with its shard too */
    snprintf(p.reason, sizeof p.reason, "max iterations in the shear ramp");
    check_ok(tbl_point_set(full, 33, &p), "tbl_point_set failed");
    tbl_set_provenance(full, "stiction table build --shards 2", 10.0);

    tbl_family f;
    tbl_numerics num;
    const double *w, *tR, *E;
    tbl_get_family(full, &f);
    tbl_get_numerics(full, &num);
    int nw = tbl_axis(full, 0, &w), nt = tbl_axis(full, 1, &tR), ne = tbl_axis(full, 2, &E);
    tbl_table *part[2] = {NULL, NULL}, *m = NULL;
    for (int s = 0; s < 2; s++) {
        check_ok(tbl_create(&f, &num, w, nw, tR, nt, E, ne, &part[s]), "tbl_create shard");
        for (int i = s; i < tbl_points(full); i += 2)
            check_ok(tbl_point_set(part[s], i, tbl_point_get(full, i)), "tbl_point_set");
        tbl_set_provenance(part[s], "stiction table build --shards 2", 7.0 + 5.0 * s);
        int done, failed, pending;
        tbl_count(part[s], &done, &failed, &pending);
        assert_int_equal(pending, tbl_points(full) / 2);
        assert_true(tbl_same_build(part[s], full));
    }
    /* the build's identity holds the error term its points use: with two
     * placements err_floor, not err_single (and the reverse with one) */
    tbl_table *o = NULL;
    tbl_numerics on = num;
    on.err_single = 0.5 * num.err_single;
    check_ok(tbl_create(&f, &on, w, nw, tR, nt, E, ne, &o), "tbl_create other");
    assert_int_equal(num.placements, 2);
    assert_true(tbl_same_build(o, full));
    tbl_destroy(&o);
    on = num, on.err_floor = 0.5 * num.err_floor;
    check_ok(tbl_create(&f, &on, w, nw, tR, nt, E, ne, &o), "tbl_create other");
    assert_false(tbl_same_build(o, full));
    tbl_destroy(&o);
    tbl_table *o1 = NULL;
    on = num, on.placements = 1;
    check_ok(tbl_create(&f, &on, w, nw, tR, nt, E, ne, &o), "tbl_create one member");
    on.err_floor = 0.5 * num.err_floor;
    check_ok(tbl_create(&f, &on, w, nw, tR, nt, E, ne, &o1), "tbl_create one member");
    assert_true(tbl_same_build(o, o1));
    tbl_destroy(&o1);
    on.err_single = 0.5 * num.err_single;
    check_ok(tbl_create(&f, &on, w, nw, tR, nt, E, ne, &o1), "tbl_create one member");
    assert_false(tbl_same_build(o, o1));
    tbl_destroy(&o1);
    tbl_destroy(&o);
    on = num, on.foot_rows = 0.6; /* another junction reading: other points */
    check_ok(tbl_create(&f, &on, w, nw, tR, nt, E, ne, &o), "tbl_create rows");
    assert_false(tbl_same_build(o, full));
    tbl_destroy(&o);

    check_ok(tbl_merge(part, 2, &m), "tbl_merge");
    int done, failed, pending;
    tbl_count(m, &done, &failed, &pending);
    for (int i = 0; i < tbl_points(full); i++) {
        const char *d = point_diff(tbl_point_get(full, i), tbl_point_get(m, i));
        if (d) fail_msg("merged point %d: field %s differs from the full table", i, d);
    }
    double wall;
    tbl_provenance(m, &wall);
    printf("merge of 2 parity shards (%d + %d points): %d done, %d failed, %d pending, all %d "
           "points equal to the full table; build wall time %.0f s (the longer shard)\n",
           tbl_points(full) - tbl_points(full) / 2, tbl_points(full) / 2, done, failed,
           pending, tbl_points(full), wall);
    assert_true(done == tbl_points(full) - 1 && failed == 1 && pending == 0);
    assert_true(wall == 12.0);
    check_family_equal(full, m);
    tbl_destroy(&m);

    /* a refinement sharded over two copies of one table: a done point with
     * more members replaces the other copy's, whichever part has it */
    tbl_point r = *tbl_point_get(full, 0);
    assert_int_equal(r.state, TBL_DONE);
    check_ok(tbl_point_set(part[1], 0, &r), "tbl_point_set copy");
    r.members *= 2, r.mu_s *= 1.01;
    check_ok(tbl_point_set(part[1], 0, &r), "tbl_point_set refined");
    check_ok(tbl_merge(part, 2, &m), "tbl_merge refined");
    assert_true(tbl_point_get(m, 0)->members == r.members && tbl_point_get(m, 0)->mu_s == r.mu_s);
    tbl_destroy(&m);
    tbl_table *rev[2] = {part[1], part[0]};
    check_ok(tbl_merge(rev, 2, &m), "tbl_merge refined first");
    assert_true(tbl_point_get(m, 0)->members == r.members && tbl_point_get(m, 0)->mu_s == r.mu_s);

    tbl_destroy(&m);
    tbl_destroy(&part[0]);
    tbl_destroy(&part[1]);
    tbl_destroy(&full);
}

/* ---- 7. a partly built table ----------------------------------------- */

/* tbl_mark_needed marks the nodes a query range reads; a table holding only
 * those points gives a model over that part (its range), refuses an E-ratio
 * whose column is empty, and a homogeneous table answers for every t/R. */
static void test_partial(void **state)
{
    (void)state;
    tbl_table *full = hertz_table(0.0, 0.02, 3), *part = NULL;
    tbl_family f;
    tbl_numerics num;
    double w[NW];
    tbl_family_default(&f);
    tbl_numerics_default(&num);
    w_axis(w);
    check_ok(tbl_create(&f, &num, w, NW, TR, NTR, ER, NE, &part), "tbl_create");
    unsigned char need[NW * NTR * NE];
    memset(need, 0, sizeof need);
    /* δ up to node 10 exactly (nodes 0-10, one more: 11), t/R between the two
     * nodes (both), E-ratio on node 2 (that column only): 12 x 2 x 1 */
    assert_int_equal(tbl_mark_needed(part, W_LO, w[10], 0.01, 0.02, 2.0, need), 24);
    assert_int_equal(tbl_mark_needed(part, W_LO, w[10], 0.01, 0.02, 2.0, need), 0);
    /* past node 10: node 11 brackets it, 12 is the one more */
    assert_int_equal(tbl_mark_needed(part, W_LO, 1.01 * w[10], 0.01, 0.02, 2.0, need), 2);
    int marked = 0;
    for (int i = 0; i < NW * NTR * NE; i++) {
        double wi, tR, E;
        tbl_coords(part, i, &wi, &tR, &E);
        int want = E == 2.0 && wi <= w[12] * (1 + 1e-12);
        assert_int_equal(need[i] != 0, want);
        marked += need[i];
        if (need[i]) check_ok(tbl_point_set(part, i, tbl_point_get(full, i)), "tbl_point_set");
    }
    assert_int_equal(marked, 26);
    assert_int_equal(tbl_mark_needed(part, 0.0, 1.0, 0.01, 0.02, 2.0, need), -1);
    check_ok(tbl_fit(part), "tbl_fit");

    stc_params p;
    family_params(2.0, &p);
    asp_model *tm = NULL, *hz = hertz_model();
    check_ok(tbl_model_create(part, &p, T_MM, TBL_MODEL_PRELOAD, &tm), "model of the part");
    asp_model_range rg;
    asp_model_get_range(tm, &rg);
    printf("part: %d of %d points, model range delta/omega_c %g .. %g (nodes 0 and 12: %g, %g)\n",
           marked, tbl_points(part), rg.w_lo, rg.w_hi, w[0], w[12]);
    assert_true(rel(rg.w_lo, w[0]) < 1e-12 && rel(rg.w_hi, w[12]) < 1e-12);
    double P, A, Q, Ph, Ah, Qh;
    asp_model_eval_norm(tm, 0.3, 0.0143, &P, &A, &Q);
    asp_model_eval_norm(hz, 0.3, 0.0143, &Ph, &Ah, &Qh);
    assert_true(rel(P, Ph) < 1e-9 && rel(A, Ah) < 1e-9);
    asp_model_destroy(&tm);
    family_params(1.5, &p); /* needs the empty E-ratio 1 column too */
    expect_fail(tbl_model_create(part, &p, T_MM, TBL_MODEL_PRELOAD, &tm), STC_ERANGE,
                "model where a column is empty", "E-ratio = 1.5", "no t/R column");

    /* one material: t/R has no effect, so no t/R flag and no t/R range */
    assert_false(tbl_is_homogeneous(full));
    tbl_table *homo = NULL;
    const double one[] = {1.0}, tr1[] = {0.01};
    check_ok(tbl_create(&f, &num, w, NW, tr1, 1, one, 1, &homo), "tbl_create homogeneous");
    for (int i = 0; i < NW; i++) {
        tbl_point q = *tbl_point_get(full, i); /* E-ratio 1, t/R 0.005: Hertz */
        check_ok(tbl_point_set(homo, i, &q), "tbl_point_set");
    }
    check_ok(tbl_fit(homo), "tbl_fit homogeneous");
    assert_true(tbl_is_homogeneous(homo));
    tbl_value v;
    check_ok(tbl_query(homo, 3.0, 0.3, 1.0, &v), "query homogeneous");
    assert_int_equal(v.flags, 0);
    family_params(1.0, &p);
    check_ok(tbl_model_create(homo, &p, T_MM, TBL_MODEL_PRELOAD, &tm), "model homogeneous");
    asp_model_get_range(tm, &rg);
    assert_false(rg.coating_aware);
    asp_model_destroy(&tm);
    asp_model_destroy(&hz);
    tbl_destroy(&homo);
    tbl_destroy(&part);
    tbl_destroy(&full);
}

/* ---- 7b. interpolation across t/R ---------------------------------------- */

/* Point i done with these P, P at inception and A, and mu_s 0.4 +- 0.01. */
static void set_point(tbl_table *t, int i, double P, double P_slide, double A)
{
    tbl_point p;
    memset(&p, 0, sizeof p);
    p.state = TBL_DONE;
    p.P_Pc = P;
    p.P_slide_Pc = P_slide;
    p.A_Ac = A;
    p.mu_s = p.mu_s_preload = p.mu_s_min = p.mu_s_max = 0.4;
    p.mu_s_err = 0.01;
    p.Q_max_Pc = 0.4 * P_slide;
    p.members = 1;
    check_ok(tbl_point_set(t, i, &p), "tbl_point_set");
}

/* A response curved in ln t/R (P = w^1.5 exp(0.2 ln²(t/R / 0.02)), on five
 * t/R columns doubling from 0.005): the monotone cubic across the columns
 * halves the straight line's error at the midpoints (1.21 % against 2.43 %;
 * Steffen's slope limiter keeps it from doing better on a parabola), and its
 * error bar is of the size of its error. */
static void test_interp_t_over_R(void **state)
{
    (void)state;
    tbl_family f;
    tbl_numerics num;
    tbl_family_default(&f);
    tbl_numerics_default(&num);
    const double w[] = {0.5, 1, 2, 4, 8, 16, 32}, tr[] = {0.005, 0.01, 0.02, 0.04, 0.08};
    const double er[] = {1.0};
    tbl_table *t = NULL;
    check_ok(tbl_create(&f, &num, w, 7, tr, 5, er, 1, &t), "tbl_create");
    for (int i = 0; i < tbl_points(t); i++) {
        double wi, tR, E;
        tbl_coords(t, i, &wi, &tR, &E);
        double l = log(tR / 0.02), P = pow(wi, 1.5) * exp(0.2 * l * l);
        set_point(t, i, P, P, wi);
    }
    check_ok(tbl_fit(t), "tbl_fit");
    double worst = 0.0, worst_lin = 0.0, worst_ratio = 0.0;
    for (int j = 1; j < 4; j++) { /* inner intervals: the cubic has both neighbours */
        double tq = sqrt(tr[j] * tr[j + 1]), l = log(tq / 0.02);
        double lin = 0.5 * (0.2 * pow(log(tr[j] / 0.02), 2) + 0.2 * pow(log(tr[j + 1] / 0.02), 2));
        tbl_value v;
        check_ok(tbl_query(t, 3.0, tq, 1.0, &v), "tbl_query");
        double truth = pow(3.0, 1.5) * exp(0.2 * l * l);
        double e = fabs(v.P_Pc / truth - 1), el = fabs(pow(3.0, 1.5) * exp(lin) / truth - 1);
        worst = fmax(worst, e);
        worst_lin = fmax(worst_lin, el);
        worst_ratio = fmax(worst_ratio, e / (v.P_Pc_err / v.P_Pc));
    }
    printf("curved in ln t/R: worst P error at the midpoints %.3f %% (straight line %.3f %%), "
           "error / error bar <= %.2f\n", 100 * worst, 100 * worst_lin, worst_ratio);
    assert_true(worst < 0.6 * worst_lin);
    assert_true(worst_ratio < 1.5);
    tbl_destroy(&t);
}

/* ---- 7c. a population at an end of the t/R axis ------------------------- */

/* Summits whose t/R is the axis's first or last value, computed from t and
 * R, are inside the table (the resampled model keeps the nodes exactly, and
 * the range check allows for the last bit). */
static void test_t_over_R_at_axis_ends(void **state)
{
    (void)state;
    tbl_table *t = hertz_table(0.0, 0.02, 5);
    check_ok(tbl_fit(t), "tbl_fit");
    stc_params p;
    family_params(2.0, &p);
    const double R[] = {T_MM / TR[0], T_MM / TR[NTR - 1]}; /* t/R = 0.005 and 0.05 */
    for (int k = 0; k < 2; k++) {
        asp_model *tm = NULL;
        srf_gw *g = NULL;
        check_ok(tbl_model_create(t, &p, T_MM, TBL_MODEL_PRELOAD, &tm), "model");
        double wc = asp_model_omega_c(tm, R[k]);
        check_ok(srf_gw_create_gaussian(tm, ETA, R[k], 3.0 * wc, NULL, &g), "gw");
        srf_gw_point q;
        check_ok(srf_gw_at_separation(g, 1.0, &q), "gw at separation");
        printf("t/R = %.17g: load outside the table %.3g\n", T_MM / R[k],
               q.load_fraction_outside);
        assert_true(q.load_fraction_outside < 0.01);
        srf_gw_destroy(&g);
        asp_model_destroy(&tm);
    }
    tbl_destroy(&t);
}

/* The bundled thesis table summed over Gaussian summit populations (R 0.1
 * mm, t 0.0005 mm: t/R 0.005) as surface predict --table sums them.  The
 * tabulated model is a cubic in ln w between its knots and a power law past
 * either end; before the quadrature split at the knots it stopped with
 * "roundoff error" on in-range pieces (Eco/Esu 1 at sigma_s 2e-6 mm, 2 and 4
 * at 5.3e-6), and the error band's Qmax, which narrows along the first
 * interval, diverged below the table ("apparent singularity", Eco/Esu 4 at
 * 2e-6). */
static void test_bundled_table_quadrature(void **state)
{
    (void)state;
    tbl_table *t = NULL;
    check_ok(tbl_read(STC_DATA_DIR "/tables/thesis.h5", &t), "tbl_read");
    tbl_numerics nm;
    tbl_get_numerics(t, &nm);
    assert_true(nm.foot_rows == 0.0); /* a format-2 file: the axis-line reading */
    const struct { double E_ratio, sigma_s; } c[] = {{4, 2e-6}, {1, 2e-6}, {2, 5.3e-6},
                                                     {4, 5.3e-6}};
    const double pressure[] = {0.02, 0.05, 0.1, 0.2}; /* MPa */
    for (int ic = 0; ic < 4; ic++) {
        stc_params p;
        family_params(c[ic].E_ratio, &p);
        asp_model *tm[3] = {NULL, NULL, NULL};
        srf_gw *g[3] = {NULL, NULL, NULL};
        for (int k = 0; k < 3; k++) {
            check_ok(tbl_model_create(t, &p, 0.0005, TBL_MODEL_PRELOAD + k, &tm[k]), "model");
            check_ok(srf_gw_create_gaussian(tm[k], 1000.0, 0.1, c[ic].sigma_s, NULL, &g[k]),
                     "gw");
        }
        /* the preload's separation at each pressure, then P at inception and
         * the error band at that separation */
        for (int i = 0; i < 4; i++) {
            srf_gw_point q, qs, qe;
            check_ok(srf_gw_at_pressure(g[0], pressure[i], &q), "gw at pressure");
            check_ok(srf_gw_at_separation(g[1], q.h, &qs), "gw at separation, slide");
            check_ok(srf_gw_at_separation(g[2], q.h, &qe), "gw at separation, error band");
            assert_true(q.Q_MPa > 0 && qs.Q_MPa > 0 && qe.Q_MPa > 0);
        }
        for (int k = 0; k < 3; k++) {
            srf_gw_destroy(&g[k]);
            asp_model_destroy(&tm[k]);
        }
    }
    /* the breaks are the knots, from one range end to the other */
    stc_params p;
    family_params(2.0, &p);
    asp_model *m = NULL;
    check_ok(tbl_model_create(t, &p, 0.0005, TBL_MODEL_PRELOAD, &m), "model");
    const double *w;
    asp_model_range rg;
    asp_model_get_range(m, &rg);
    int nb = asp_model_breaks(m, &w);
    assert_true(nb > 2);
    assert_true(w[0] == rg.w_lo && w[nb - 1] == rg.w_hi);
    asp_model_destroy(&m);
    tbl_destroy(&t);
}

/* ---- 8. failed points computed again ---------------------------------- */

/* The family and numerics of the coarse points: slip, 3 elements across
 * the contact, one placement. */
static void coarse_numerics(tbl_family *f, tbl_numerics *num)
{
    tbl_family_default(f);
    f->contact = ASP_CONTACT_SLIP;
    tbl_numerics_default(num);
    num->elements_per_contact = 3.0;
    num->placements = 1;
}

/* A one-point coarse slip table (3 elements per contact, one placement) at
 * delta w omega_c, t/R 0.01, Eco/Esu er, to be written to DIR/name.h5
 * (path). */
static tbl_table *coarse_point_table(void **state, const char *name, double w, double er,
                                     char *path, size_t n)
{
    char dir[128];
    scratch_sub(state, name, dir, sizeof dir);
    snprintf(path, n, "%s/%s.h5", dir, name);
    tbl_family f;
    tbl_numerics num;
    coarse_numerics(&f, &num);
    const double tr[] = {0.01};
    tbl_table *t = NULL;
    check_ok(tbl_create(&f, &num, &w, 1, tr, 1, &er, 1, &t), "tbl_create");
    return t;
}

/* A journal record as table_build.c writes one (its layout mirrored here:
 * magic, index, payload, FNV-1a of all before). */
static void journal_record(FILE *f, uint32_t magic, int32_t index, const void *p, size_t n)
{
    unsigned char *buf = malloc(8 + n);
    assert_non_null(buf);
    memcpy(buf, &magic, 4);
    memcpy(buf + 4, &index, 4);
    memcpy(buf + 8, p, n);
    uint64_t h = 14695981039346656037ULL;
    for (size_t i = 0; i < 8 + n; i++) h = (h ^ buf[i]) * 1099511628211ULL;
    assert_int_equal(fwrite(buf, 1, 8 + n, f), 8 + n);
    assert_int_equal(fwrite(&h, 8, 1, f), 1);
    free(buf);
}

/* A build killed after a point failed, its failed member journaled (a
 * transient failure, or one a solver change fixes), run again with
 * --retry-failed: the member that failed is not taken (it would fail the
 * point again without a run), the one that reached inception is; the point
 * comes out as the build from scratch computes it.  And a retry killed
 * after it finished a point, run again without --retry-failed, keeps that
 * point (the file still says failed). */
static void test_failed_member_not_taken(void **state)
{
    char path[192], jpath[256];
    tbl_table *t = coarse_point_table(state, "failed-member", 0.5, 2.0, path, sizeof path);
    tbl_numerics num;
    tbl_get_numerics(t, &num);
    num.placements = 2;
    tbl_family fam;
    tbl_get_family(t, &fam);
    double w = 0.5, tr = 0.01, er = 2.0;
    tbl_table *ref = NULL;
    check_ok(tbl_create(&fam, &num, &w, 1, &tr, 1, &er, 1, &ref), "tbl_create");
    tbl_destroy(&t);
    check_ok(tbl_create(&fam, &num, &w, 1, &tr, 1, &er, 1, &t), "tbl_create");
    tbl_build_opts o;
    tbl_build_summary sum;
    tbl_build_opts_default(&o);
    o.jobs = 1;
    char rpath[256];
    snprintf(rpath, sizeof rpath, "%s.ref.h5", path);
    check_ok(tbl_build(ref, rpath, &o, &sum), "tbl_build reference");
    const tbl_point *good = tbl_point_get(ref, 0);
    assert_int_equal(good->ens.k, 2);

    /* the file: the point pending; its journal: member 0 as computed,
     * member 1 failed, the point failed */
    check_ok(tbl_write(t, path), "tbl_write");
    asp_placement_result *e = calloc(1, sizeof *e);
    assert_non_null(e);
    tbl_members_unpack(good, e);
    tbl_member_rec r[2];
    tbl_member_rec_fill(&r[0], 0, e, 0);
    tbl_member_rec_fill(&r[1], 0, e, 1);
    r[1].m.status = STC_ENOCONV, r[1].m.res.converged = 0;
    snprintf(r[1].m.message, sizeof r[1].m.message, "made to fail");
    free(e);
    tbl_point fp;
    memset(&fp, 0, sizeof fp);
    fp.state = TBL_FAILED, fp.members = 1;
    snprintf(fp.reason, sizeof fp.reason, "1 of 2 members failed: made to fail");
    snprintf(jpath, sizeof jpath, "%s.journal", path);
    FILE *f = fopen(jpath, "wb");
    assert_non_null(f);
    uint64_t hash = tbl_build_hash(t);
    assert_int_equal(fwrite("STCTBLJ2", 1, 8, f), 8);
    assert_int_equal(fwrite(&hash, 8, 1, f), 1);
    journal_record(f, 0x4d544254u /* "TBTM" */, 0, &r[0], sizeof r[0]);
    journal_record(f, 0x4d544254u, 0, &r[1], sizeof r[1]);
    journal_record(f, 0x50544254u /* "TBTP" */, 0, &fp, sizeof fp);
    assert_int_equal(fclose(f), 0);

    o.retry_failed = 1;
    check_ok(tbl_build(t, path, &o, &sum), "tbl_build --retry-failed");
    const tbl_point *p = tbl_point_get(t, 0);
    printf("failed member in the journal: the retry computed %d point, took %d member; %s, "
           "mu_s %.6f (from scratch %.6f)\n", sum.computed, sum.members_taken,
           p->state == TBL_DONE ? "done" : "not done", p->mu_s, good->mu_s);
    assert_int_equal(sum.computed, 1);
    assert_int_equal(sum.members_taken, 1);
    assert_int_equal(p->state, TBL_DONE);
    p = tbl_point_get(t, 0);
    tbl_point want = *good;
    want.wall_s = p->wall_s, want.cpu_s = p->cpu_s; /* timings */
    for (int j = 0; j < want.ens.k; j++) want.ens.m[j].cpu_s = p->ens.m[j].cpu_s;
    const char *d = point_diff(&want, p);
    if (d) fail_msg("the retried point differs from the build from scratch in %s", d);
    tbl_destroy(&t);

    /* a retry killed after it finished the point, before it wrote the file,
     * run again without --retry-failed: the done point is taken from the
     * journal, not lost (the file says failed) */
    check_ok(tbl_create(&fam, &num, &w, 1, &tr, 1, &er, 1, &t), "tbl_create");
    check_ok(tbl_point_set(t, 0, &fp), "tbl_point_set failed");
    check_ok(tbl_write(t, path), "tbl_write");
    f = fopen(jpath, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite("STCTBLJ2", 1, 8, f), 8);
    assert_int_equal(fwrite(&hash, 8, 1, f), 1);
    tbl_point done = *good;
    journal_record(f, 0x50544254u, 0, &done, sizeof done);
    assert_int_equal(fclose(f), 0);
    o.retry_failed = 0;
    check_ok(tbl_build(t, path, &o, &sum), "tbl_build without --retry-failed");
    printf("a retry's done point in the journal, resumed without the option: %d computed, %d "
           "resumed, %s\n", sum.computed, sum.resumed,
           tbl_point_get(t, 0)->state == TBL_DONE ? "done" : "not done");
    assert_int_equal(sum.computed, 0);
    assert_int_equal(tbl_point_get(t, 0)->state, TBL_DONE);
    d = point_diff(good, tbl_point_get(t, 0));
    if (d) fail_msg("the point taken from the journal differs in %s", d);
    tbl_destroy(&t);
    tbl_destroy(&ref);
}

/* Refinement (tbl_numerics.placements_max): a coarse elastic point with a
 * threshold below any spread doubles its members twice, 1 -> 2 -> 4 (that
 * a refined ensemble equals the one made at once: test_shear); with a
 * threshold above its error it keeps its one member, whose numbers are the
 * refined point's first member's. */
/* Which done points a build that adds refinement computes again: the rule
 * asp_shear_placements_adaptive applies, read from the stored points; and
 * which builds count as the file's build with refinement added. */
static void test_refinable(void **state)
{
    (void)state;
    tbl_family f;
    tbl_numerics n;
    tbl_family_default(&f);
    tbl_numerics_default(&n);
    const double w[3] = {0.5, 2.0, 10.0}, tR[1] = {0.01}, E[1] = {1.0};
    tbl_table *old = NULL, *t = NULL, *less = NULL;
    check_ok(tbl_create(&f, &n, w, 3, tR, 1, E, 1, &old), "tbl_create plain");
    tbl_numerics r = n;
    r.placements_max = 8, r.refine_err = 0.04;
    check_ok(tbl_create(&f, &r, w, 3, tR, 1, E, 1, &t), "tbl_create refined");
    assert_false(tbl_same_points(t, old));
    assert_true(tbl_refines(t, old));
    assert_false(tbl_refines(old, t)); /* none after some: another build */
    tbl_numerics q = r;
    q.refine_err = 0.05; /* refining less than t */
    check_ok(tbl_create(&f, &q, w, 3, tR, 1, E, 1, &less), "tbl_create less");
    assert_true(tbl_refines(t, less));
    assert_false(tbl_refines(less, t));
    q = r, q.placements_max = 4;
    tbl_destroy(&less);
    check_ok(tbl_create(&f, &q, w, 3, tR, 1, E, 1, &less), "tbl_create fewer");
    assert_false(tbl_refines(less, t));
    tbl_destroy(&less);
    q = r, q.foot_rows = 0.6; /* other points */
    check_ok(tbl_create(&f, &q, w, 3, tR, 1, E, 1, &less), "tbl_create rows");
    assert_false(tbl_refines(less, old));
    tbl_destroy(&less);

    /* k members, standard error of the mean s (relative), error with the floor */
    struct { int members; double se; int state, want; } c[] = {
        {2, 0.050, TBL_DONE, 1},   {2, 0.030, TBL_DONE, 0}, {4, 0.041, TBL_DONE, 1},
        {8, 0.090, TBL_DONE, 0},   /* 16 would exceed placements_max */
        {2, 0.090, TBL_FAILED, 0}, {2, 0.090, TBL_PENDING, 0},
    };
    for (size_t k = 0; k < sizeof c / sizeof *c; k++) {
        tbl_point p;
        memset(&p, 0, sizeof p);
        p.state = c[k].state, p.members = c[k].members, p.mu_s = 0.5;
        p.mu_s_err = p.mu_s * hypot(c[k].se, r.err_floor);
        p.mu_s_min = p.mu_s_max = p.mu_s, p.P_Pc = p.A_Ac = 1.0;
        check_ok(tbl_point_set(t, 1, &p), "tbl_point_set");
        printf("  %d members, standard error %.3f, %s: %s\n", c[k].members, c[k].se,
               tbl_state_name(c[k].state), tbl_point_refinable(t, &r, 1) ? "refined" : "kept");
        assert_int_equal(tbl_point_refinable(t, &r, 1), c[k].want);
    }
    /* one member: the error its own run printed, from its δ over ωc (2.6 %
     * up to first yield, 6.1 % at 2 ωc, 10 % from 3 ωc on) */
    for (int i = 0; i < 3; i++) {
        tbl_point p;
        memset(&p, 0, sizeof p);
        p.state = TBL_DONE, p.members = 1, p.mu_s = 0.5, p.mu_s_err = 0.05;
        p.mu_s_min = p.mu_s_max = p.mu_s, p.P_Pc = p.A_Ac = 1.0;
        check_ok(tbl_point_set(t, i, &p), "tbl_point_set one member");
        double e = asp_mu_s_err_single(0.0, 0, w[i]);
        printf("  one member at %g omega_c: its run's error %.3f: %s\n", w[i], e,
               tbl_point_refinable(t, &r, i) ? "refined" : "kept");
        assert_int_equal(tbl_point_refinable(t, &r, i), e > r.refine_err);
        assert_int_equal(tbl_point_refinable(t, &r, i), i > 0);
    }
    tbl_destroy(&t);
    tbl_destroy(&old);
}

static void test_point_refine(void **state)
{
    (void)state;
    tbl_family f;
    tbl_numerics num;
    coarse_numerics(&f, &num);
    num.placements_max = 4;
    num.refine_err = 1e-6;
    tbl_point a, c;
    check_ok(tbl_point_compute(&f, &num, 0.5, 0.01, 1.0, &a), "refined point");
    num.refine_err = 0.5;
    check_ok(tbl_point_compute(&f, &num, 0.5, 0.01, 1.0, &c), "not refined");
    printf("refined 1 -> 4: mu_s %.6f +- %.6f (%d members, %.6f ... %.6f); one member %.6f "
           "+- %.6f\n", a.mu_s, a.mu_s_err, a.members, a.mu_s_min, a.mu_s_max, c.mu_s,
           c.mu_s_err);
    assert_int_equal(a.state, TBL_DONE);
    assert_int_equal(a.members, 4);
    assert_int_equal(c.members, 1);
    assert_true(a.mu_s_min < a.mu_s_max);
    assert_true(a.mu_s_min <= c.mu_s && c.mu_s <= a.mu_s_max);
    /* the error of 4 members: their standard error and the floor */
    assert_true(a.mu_s_err >= num.err_floor * a.mu_s);
    assert_true(a.mu_s_err <= hypot(0.5 * (a.mu_s_max - a.mu_s_min), num.err_floor * a.mu_s));
    num.placements_max = 1; /* less than twice placements */
    assert_int_equal(tbl_point_compute(&f, &num, 0.5, 0.01, 1.0, &c), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "placements-max = 1"));
}

/* A failed point stays failed in a resumed build, and is computed again
 * with only_failed (one coarse point: about a second; retry_failed takes the
 * same path with the pending points besides). */
static void test_retry_failed(void **state)
{
    char path[192];
    tbl_table *t = coarse_point_table(state, "retry", 1.0, 2.0, path, sizeof path);
    tbl_point p;
    memset(&p, 0, sizeof p);
    p.state = TBL_FAILED;
    snprintf(p.reason, sizeof p.reason, "made to fail");
    check_ok(tbl_point_set(t, 0, &p), "tbl_point_set");
    check_ok(tbl_write(t, path), "tbl_write");
    tbl_build_opts o;
    tbl_build_summary sum;
    tbl_build_opts_default(&o);
    o.jobs = 1;
    check_ok(tbl_build(t, path, &o, &sum), "tbl_build");
    assert_int_equal(sum.computed, 0);
    assert_int_equal(tbl_point_get(t, 0)->state, TBL_FAILED);
    o.only_failed = 1;
    check_ok(tbl_build(t, path, &o, &sum), "tbl_build only_failed");
    assert_int_equal(sum.computed, 1);
    assert_int_equal(sum.failed, 0);
    tbl_destroy(&t);
    check_ok(tbl_read(path, &t), "tbl_read");
    const tbl_point *q = tbl_point_get(t, 0);
    printf("retried point: %s, mu_s %.4f +- %.4f\n", q->state == TBL_DONE ? "done" : "not done",
           q->mu_s, q->mu_s_err);
    assert_int_equal(q->state, TBL_DONE);
    assert_true(q->mu_s > 0.2 && q->mu_s < 2.0);
    tbl_destroy(&t);
}

/* ---- 8. the normal grid ----------------------------------------------------- */

/* The normal grid keeps the table's nodes on its axes and divides each
 * interval evenly in ln (4 per factor 2 along δ and t/R, 2 along Eco/Esu).
 * Where its curves around a query are done, P and A come from them (to the
 * cubics' accuracy on a response curved across t/R) and the load at
 * inception keeps the points' ratio to the preload; a pending curve next to
 * the query sends it back to the points; the curves survive the file; and a
 * real curve on the axisymmetric mesh follows Hertz in the elastic range. */
static double nrm_P(double w, double tR, double E)
{
    double l = log(tR / 0.02);
    return pow(w, 1.5) * exp(0.2 * l * l) * pow(E, 0.3);
}

static void fill_curves(tbl_table *t)
{
    const double *w, *tr, *er;
    int nw = tbl_normal_axis(t, 0, &w), nt = tbl_normal_axis(t, 1, &tr);
    tbl_normal_axis(t, 2, &er);
    double P[64], A[64];
    assert_true(nw <= 64);
    for (int c = 0; c < tbl_curves(t); c++) {
        double tR = tr[c % nt], E = er[c / nt];
        for (int k = 0; k < nw; k++) {
            P[k] = nrm_P(w[k], tR, E);
            A[k] = w[k] * (1.0 + 0.1 * log(tR / 0.02));
        }
        tbl_curve cv = {.state = TBL_DONE, .increments = 10 + c, .cpu_s = 1.0};
        check_ok(tbl_curve_set(t, c, &cv, P, A), "tbl_curve_set");
    }
}

static void test_normal_grid(void **state)
{
    char path[192];
    scratch_file(state, "normal", "normal.h5", path, sizeof path);
    tbl_family f;
    tbl_numerics num;
    tbl_family_default(&f);
    tbl_numerics_default(&num);
    const double w[] = {0.5, 1, 2, 4}, tr[] = {0.01, 0.04}, er[] = {1.0, 4.0};
    tbl_table *t = NULL, *r = NULL;
    check_ok(tbl_create(&f, &num, w, 4, tr, 2, er, 2, &t), "tbl_create");
    const double *nw_ax, *nt_ax, *ne_ax;
    int n0 = tbl_normal_axis(t, 0, &nw_ax), n1 = tbl_normal_axis(t, 1, &nt_ax);
    int n2 = tbl_normal_axis(t, 2, &ne_ax);
    printf("normal grid of a 4 x 2 x 2 table: %d x %d x %d, %d curves\n", n0, n1, n2,
           tbl_curves(t));
    assert_int_equal(n0, 13);
    assert_int_equal(n1, 9);
    assert_int_equal(n2, 5);
    assert_int_equal(tbl_curves(t), 45);
    for (int k = 0; k < 4; k++) assert_true(same_bits(nw_ax[4 * k], w[k]));
    assert_true(same_bits(nt_ax[0], tr[0]) && same_bits(nt_ax[8], tr[1]));
    assert_true(same_bits(ne_ax[0], er[0]) && same_bits(ne_ax[4], er[1]));
    assert_true(rel(nt_ax[4], 0.02) < 1e-14 && rel(ne_ax[2], 2.0) < 1e-14);

    /* the points: P twice the curves' at E = 1, t/R = 0.02, P at inception 0.9 P */
    for (int i = 0; i < tbl_points(t); i++) {
        double wi, tR, E;
        tbl_coords(t, i, &wi, &tR, &E);
        set_point(t, i, 2.0 * pow(wi, 1.5), 1.8 * pow(wi, 1.5), wi);
    }
    check_ok(tbl_fit(t), "tbl_fit");
    tbl_value v;
    query_ok(t, 1.3, 0.017, 1.7, &v);
    assert_int_equal(v.from_normal, 0); /* every curve pending: the points */
    assert_true(rel(v.P_Pc, 2.0 * pow(1.3, 1.5)) < 1e-12);

    fill_curves(t);
    double worst = 0.0, worst_A = 0.0;
    const double qw[] = {0.6, 1.3, 3.1}, qt[] = {0.011, 0.017, 0.033}, qe[] = {1.2, 1.7, 3.5};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int c = 0; c < 3; c++) {
                query_ok(t, qw[a], qt[b], qe[c], &v);
                assert_int_equal(v.from_normal, 1);
                worst = fmax(worst, rel(v.P_Pc, nrm_P(qw[a], qt[b], qe[c])));
                worst_A = fmax(worst_A, rel(v.A_Ac, qw[a] * (1 + 0.1 * log(qt[b] / 0.02))));
                assert_true(rel(v.P_slide_Pc, 0.9 * v.P_Pc) < 1e-12);
                assert_true(rel(v.Q_max_Pc, v.mu_s * v.P_slide_Pc) < 1e-12);
            }
    printf("P and A from the normal grid at 27 queries between its nodes: worst rel error "
           "%.2e (P), %.2e (A); P at inception 0.9 P as the points say\n", worst, worst_A);
    assert_true(worst < 2e-3);
    assert_true(worst_A < 2e-3);

    /* a pending curve next to the query: back to the points */
    const tbl_curve pending = {.state = TBL_PENDING};
    int c_near = 2 * n1 + 3; /* Eco/Esu 2, t/R between 0.0168 and 0.02 */
    double P[13], A[13];
    for (int k = 0; k < n0; k++) tbl_curve_values(t, c_near, k, &P[k], &A[k]);
    check_ok(tbl_curve_set(t, c_near, &pending, P, A), "tbl_curve_set pending");
    query_ok(t, 1.3, 0.018, 2.0, &v);
    assert_int_equal(v.from_normal, 0);
    assert_true(rel(v.P_Pc, 2.0 * pow(1.3, 1.5)) < 1e-12);
    int cd, cf, cp;
    tbl_curve_count(t, &cd, &cf, &cp);
    assert_true(cd == 44 && cf == 0 && cp == 1);
    unsigned char *only = calloc((size_t)tbl_points(t), 1);
    assert_non_null(only);
    assert_int_equal(tbl_curves_pending(t, only), 0); /* no point chosen: no curve */
    only[0] = 1;                                        /* t/R 0.01, Eco/Esu 1 */
    assert_int_equal(tbl_curves_pending(t, only), 0);
    for (int i = 0; i < tbl_points(t); i++) only[i] = 1;
    assert_int_equal(tbl_curves_pending(t, only), 1);
    assert_int_equal(tbl_curves_pending(t, NULL), 1);
    free(only);

    /* through the file, every curve bit for bit */
    check_ok(tbl_write(t, path), "tbl_write");
    check_ok(tbl_read(path, &r), "tbl_read");
    assert_true(tbl_same_build(t, r));
    for (int c = 0; c < tbl_curves(t); c++) {
        assert_int_equal(tbl_curve_get(r, c)->state, tbl_curve_get(t, c)->state);
        assert_int_equal(tbl_curve_get(r, c)->increments, tbl_curve_get(t, c)->increments);
        for (int k = 0; k < n0; k++) {
            double a1, a2, b1, b2;
            tbl_curve_values(t, c, k, &a1, &b1);
            tbl_curve_values(r, c, k, &a2, &b2);
            assert_true(same_bits(a1, a2) && same_bits(b1, b2));
        }
    }
    printf("the normal grid through the file: %d curves equal bit for bit\n", tbl_curves(r));
    tbl_destroy(&r);
    tbl_destroy(&t);

    /* a real curve: homogeneous sphere (a "coating" of the substrate's material, t/R 0.01),
     * slip, elastic range (Hertz: P/Pc = w^1.5, A/Ac = w in Kogut & Etsion's normalisation,
     * on the outer radius); the fixed base at depth R stiffens it by a few tenths of a per
     * cent (docs/design.md §2.1) */
    tbl_family slip = f;
    slip.contact = ASP_CONTACT_SLIP;
    const double we[] = {0.2, 0.4};
    double Pe[2], Ae[2];
    tbl_curve cv;
    double t0 = now();
    check_ok(tbl_curve_compute(&slip, 1, 0.01, 1.0, we, 2, Pe, Ae, &cv), "tbl_curve_compute");
    assert_int_equal(cv.state, TBL_DONE);
    double eP = 0.0, eA = 0.0;
    for (int k = 0; k < 2; k++) {
        /* Hertz on the outer radius R' = 1.01 R: P ∝ R'^1/2, A = π R' δ */
        eP = fmax(eP, fabs(Pe[k] / (pow(we[k], 1.5) * sqrt(1.01)) - 1));
        eA = fmax(eA, fabs(Ae[k] / (we[k] * 1.01) - 1));
    }
    printf("an axisymmetric curve (level 1, slip, elastic): P/Pc vs Hertz within %.3f %%, "
           "A/Ac within %.3f %% (%d increments, %.2f s)\n", 100 * eP, 100 * eA, cv.increments,
           now() - t0);
    assert_true(eP < 0.005);
    assert_true(eA < 0.02);

    /* a curve of one delta is a curve too (it samples the elastic node
     * entries and is loaded on past its point): done, and within 0.5 % of
     * the three-point curve there; it had too few increments for the
     * smoothed load before (NaN, failed) */
    const double w3[] = {0.5, 0.7071067812, 1.0};
    double P3[3], A3[3], P1, A1;
    check_ok(tbl_curve_compute(&slip, 1, 0.01, 2.0, w3, 3, P3, A3, &cv), "tbl_curve_compute");
    assert_int_equal(cv.state, TBL_DONE);
    for (int k = 0; k < 3; k += 2) {
        check_ok(tbl_curve_compute(&slip, 1, 0.01, 2.0, &w3[k], 1, &P1, &A1, &cv),
                 "tbl_curve_compute, one delta");
        printf("a curve of one delta at %g omega_c: %s, P/Pc %.6f (three points: %.6f, "
               "%+.3f %%), A/Ac %+.3f %%\n", w3[k], tbl_state_name(cv.state), P1, P3[k],
               100 * (P1 / P3[k] - 1), 100 * (A1 / A3[k] - 1));
        assert_int_equal(cv.state, TBL_DONE);
        assert_true(fabs(P1 / P3[k] - 1) < 0.005 && fabs(A1 / A3[k] - 1) < 0.005);
    }
}

/* ---- 9. the caller's settings ------------------------------------------- */

int openblas_get_num_threads(void); /* OpenBLAS extension */

typedef struct {
    int calls, lo, hi; /* progress reports; the least and most max-active-levels seen */
} levels_seen;

static int note_levels(void *ctx, const tbl_progress *p)
{
    (void)p;
    levels_seen *l = ctx;
    int v = omp_get_max_active_levels();
    if (l->calls++ == 0 || v < l->lo) l->lo = v;
    if (l->calls == 1 || v > l->hi) l->hi = v;
    return 0;
}

/* One material: at Eco/Esu = 1 in a family with the same E/Y and ν in both
 * layers the coating is the substrate and t/R means nothing, so every t/R
 * column of that Eco/Esu holds the first column's runs.  A build asked for a
 * point there computes its source once (one coarse FE run) and fills the
 * other columns from it, at no cost; the copies survive the file, the
 * surrogate fits each answer once, a merge fills copies whose source another
 * part holds and follows a refined source, and a refinement plan counts the
 * sources only.  Other Eco/Esu, and families with different layers, are
 * their own sources. */
static void test_one_material(void **state)
{
    char path[192];
    scratch_file(state, "one-material", "one.h5", path, sizeof path);
    tbl_family f;
    tbl_numerics num;
    coarse_numerics(&f, &num);
    const double w[2] = {0.5, 1.0}, tR[3] = {0.01, 0.02, 0.04}, E[2] = {1.0, 2.0};
    tbl_table *t = NULL, *other = NULL;
    check_ok(tbl_create(&f, &num, w, 2, tR, 3, E, 2, &t), "tbl_create");
    tbl_family g = f;
    g.E_over_Y_co = 500.0; /* a harder coating: two materials at any Eco/Esu */
    check_ok(tbl_create(&g, &num, w, 2, tR, 3, E, 2, &other), "tbl_create two materials");
    for (int i = 0; i < tbl_points(t); i++) {
        int iw = i % 2, it = (i / 2) % 3, iE = i / 6;
        assert_int_equal(tbl_point_source(t, i), iE == 0 && it > 0 ? iw : i);
        assert_int_equal(tbl_point_source(other, i), i);
    }
    tbl_destroy(&other);
    /* and its run is the uncoated sphere's, whose mesh has no interface */
    stc_params p1;
    tbl_point_params(&f, 0.02, 1.0, &p1);
    assert_true(p1.t_over_R == 0.0);
    tbl_point_params(&f, 0.02, 2.0, &p1);
    assert_true(p1.t_over_R == 0.02);
    tbl_point_params(&g, 0.02, 1.0, &p1);
    assert_true(p1.t_over_R == 0.02);

    /* δ 1 at the first t/R done by hand, and every Eco/Esu 2 point; δ 0.5
     * at the first t/R (point 0) pending */
    for (int i = 1; i < tbl_points(t); i++) {
        if (tbl_point_source(t, i) != i) continue;
        tbl_point p;
        memset(&p, 0, sizeof p);
        p.state = TBL_DONE, p.members = 1;
        p.P_Pc = p.A_Ac = p.P_slide_Pc = 1.0 + i;
        p.mu_s = 0.5 + 0.01 * i, p.mu_s_err = 0.05 * p.mu_s, p.Q_max_Pc = p.mu_s * p.P_slide_Pc;
        p.mu_s_min = p.mu_s_max = p.mu_s;
        p.wall_s = p.cpu_s = 1.0 + i;
        check_ok(tbl_point_set(t, i, &p), "tbl_point_set");
    }
    tbl_point bad = *tbl_point_get(t, 1);
    bad.copied = 1; /* point 1 is its own source */
    assert_int_equal(tbl_point_set(t, 1, &bad), STC_EINVAL);
    stc_error_clear();
    /* the normal grid's curves alike: those that are their own source done
     * by hand (no curve to compute), the others left to the build */
    const double *nw_ax, *nt_ax;
    int nw = tbl_normal_axis(t, 0, &nw_ax), nt = tbl_normal_axis(t, 1, &nt_ax), ncopy = 0;
    double P[16], A[16];
    assert_true(nw <= 16);
    for (int c = 0; c < tbl_curves(t); c++) {
        int src = tbl_curve_source(t, c), iE = c / nt;
        assert_int_equal(src, iE == 0 ? 0 : c); /* Eco/Esu 1: the first t/R's */
        if (src != c) {
            ncopy++;
            continue;
        }
        for (int k = 0; k < nw; k++)
            P[k] = nrm_P(nw_ax[k], nt_ax[c % nt], 1.0 + iE), A[k] = nw_ax[k] * (1.0 + c);
        tbl_curve cv = {.state = TBL_DONE, .increments = 5, .cpu_s = 1.0 + c, .wall_s = 1.0};
        check_ok(tbl_curve_set(t, c, &cv, P, A), "tbl_curve_set");
    }
    assert_int_equal(tbl_curves_pending(t, NULL), 0); /* the copies are not to compute */

    /* a query at t/R 0.02-0.04, Eco/Esu 1 reads points 2-5, which are copies
     * of points 0 and 1: of those only point 0 is to be computed */
    unsigned char need[12] = {0};
    assert_int_equal(tbl_mark_needed(t, 0.5, 1.0, 0.02, 0.04, 1.0, need), 1);
    assert_true(need[0] && need[1] && need[4] && need[5]);

    tbl_build_opts o;
    tbl_build_summary sum;
    tbl_build_opts_default(&o);
    o.jobs = 1;
    unsigned char only[12] = {0};
    only[4] = 1; /* δ 0.5, t/R 0.04, Eco/Esu 1: its source is point 0 */
    o.only = only;
    check_ok(tbl_build(t, path, &o, &sum), "tbl_build");
    printf("one material: a build asked for point 4 computed %d (its source), filled %d copies\n",
           sum.computed, sum.copied);
    assert_int_equal(sum.computed, 1);
    assert_int_equal(sum.copied, 4);
    assert_int_equal(sum.curves_computed, 0);
    tbl_destroy(&t);
    check_ok(tbl_read(path, &t), "tbl_read");
    int done, pending;
    tbl_count(t, &done, NULL, &pending);
    assert_int_equal(done, 12);
    for (int i = 0; i < tbl_points(t); i++) {
        const tbl_point *p = tbl_point_get(t, i), *q = tbl_point_get(t, tbl_point_source(t, i));
        if (p == q) {
            assert_int_equal(p->copied, 0);
            assert_true(p->cpu_s > 0.0);
            continue;
        }
        assert_int_equal(p->copied, 1);
        assert_true(same_bits(p->mu_s, q->mu_s) && same_bits(p->mu_s_err, q->mu_s_err) &&
                    same_bits(p->P_Pc, q->P_Pc) && p->members == q->members);
        assert_true(p->cpu_s == 0.0 && p->wall_s == 0.0 && p->newton_iterations == 0);
    }
    tbl_fit_info fi;
    check_ok(tbl_get_fit_info(t, &fi), "tbl_get_fit_info");
    assert_int_equal(fi.n, 8); /* 2 answers at Eco/Esu 1, 6 at 2 */
    int cd;
    tbl_curve_count(t, &cd, NULL, NULL);
    assert_int_equal(cd, tbl_curves(t));
    for (int c = 0; c < tbl_curves(t); c++) {
        int src = tbl_curve_source(t, c);
        const tbl_curve *cv = tbl_curve_get(t, c);
        assert_int_equal(cv->copied, src != c);
        if (src == c) continue;
        assert_true(cv->cpu_s == 0.0 && cv->increments == 0);
        for (int k = 0; k < nw; k++) {
            double a[2], b[2];
            tbl_curve_values(t, c, k, &a[0], &a[1]);
            tbl_curve_values(t, src, k, &b[0], &b[1]);
            assert_true(same_bits(a[0], b[0]) && same_bits(a[1], b[1]));
        }
    }
    printf("one material: %d of %d normal curves filled from their source\n", ncopy,
           tbl_curves(t));

    /* merge: the copies of a part without them are filled from the source
     * another part holds; a source refined in a part carries its copies */
    tbl_table *parts[3] = {NULL, NULL, NULL}, *m = NULL;
    tbl_get_family(t, &f);
    tbl_get_numerics(t, &num);
    for (int k = 0; k < 3; k++)
        check_ok(tbl_create(&f, &num, w, 2, tR, 3, E, 2, &parts[k]), "tbl_create part");
    for (int i = 0; i < tbl_points(t); i++)
        if (tbl_point_source(t, i) == i)
            check_ok(tbl_point_set(parts[i % 2], i, tbl_point_get(t, i)), "tbl_point_set part");
    tbl_point r = *tbl_point_get(t, 1);
    r.members = 2, r.mu_s *= 1.1, r.cpu_s *= 2.0;
    check_ok(tbl_point_set(parts[2], 1, &r), "tbl_point_set refined");
    check_ok(tbl_merge(parts, 2, &m), "tbl_merge");
    for (int i = 0; i < tbl_points(t); i++)
        if (point_diff(tbl_point_get(t, i), tbl_point_get(m, i)))
            fail_msg("merged point %d: %s differs", i,
                     point_diff(tbl_point_get(t, i), tbl_point_get(m, i)));
    tbl_destroy(&m);
    check_ok(tbl_merge(parts, 3, &m), "tbl_merge with a refined source");
    for (int i = 3; i < 6; i += 2) { /* δ 1, t/R 0.02 and 0.04 */
        assert_int_equal(tbl_point_get(m, i)->members, 2);
        assert_true(same_bits(tbl_point_get(m, i)->mu_s, r.mu_s));
        assert_true(tbl_point_get(m, i)->copied && tbl_point_get(m, i)->cpu_s == 0.0);
    }
    tbl_destroy(&m);
    for (int k = 0; k < 3; k++) tbl_destroy(&parts[k]);

    /* a refinement computes the sources again and fills the copies: its
     * plan counts the sources (one member's error at δ 1 is above 4 %) */
    int k = -1, unkept = -1;
    double cpu = 0.0;
    check_ok(tbl_refine_plan(t, 2, 1e-3, &k, &cpu, &unkept), "tbl_refine_plan");
    printf("one material: a refinement to 2 members computes %d of the 12 points again (%d of "
           "them without kept members)\n", k, unkept);
    assert_int_equal(k, 8);
    /* the point the build computed keeps its member, those set by hand none */
    assert_int_equal(unkept, 7);
    tbl_destroy(&t);
}

/* A build leaves the caller's OpenMP settings alone: the progress callback
 * (run on the build's thread, after the normal curves and the point) sees
 * the caller's max-active-levels, and OpenBLAS's thread count is the
 * caller's again afterwards.  The build used to set max-active-levels 0
 * (one item at a time) or 1 around its items, so the callback saw 0 here. */
static void test_caller_settings(void **state)
{
    char path[192];
    tbl_table *t = coarse_point_table(state, "settings", 0.5, 1.0, path, sizeof path);
    levels_seen seen = {0, -1, -1};
    tbl_build_opts o;
    tbl_build_opts_default(&o);
    o.jobs = 1;
    o.progress = note_levels, o.ctx = &seen;
    int levels = omp_get_max_active_levels(), blas = openblas_get_num_threads();
    omp_set_max_active_levels(3);
    tbl_build_summary sum;
    check_ok(tbl_build(t, path, &o, &sum), "tbl_build");
    printf("max-active-levels: caller 3, in the %d progress callbacks %d..%d, after %d; "
           "OpenBLAS threads before %d, after %d\n", seen.calls, seen.lo, seen.hi,
           omp_get_max_active_levels(), blas, openblas_get_num_threads());
    assert_int_equal(sum.computed, 1);
    assert_true(seen.calls >= 1);
    assert_int_equal(seen.lo, 3);
    assert_int_equal(seen.hi, 3);
    assert_int_equal(omp_get_max_active_levels(), 3);
    assert_int_equal(openblas_get_num_threads(), blas);
    omp_set_max_active_levels(levels);
    tbl_destroy(&t);
}

/* Fewer points than jobs: a point's members share the threads, with the
 * numbers of the build that runs them one after another (bitwise; only the
 * timings differ, and the CPU time counts every member's thread); the
 * caller's max-active-levels and OpenBLAS's count are kept. */
static void test_point_threads(void **state)
{
    char dir[128], pa[192], pb[192];
    scratch_sub(state, "point-threads", dir, sizeof dir);
    snprintf(pa, sizeof pa, "%s/one-thread.h5", dir);
    snprintf(pb, sizeof pb, "%s/two-threads.h5", dir);
    tbl_family f;
    tbl_numerics num;
    coarse_numerics(&f, &num);
    num.placements = 2;
    const double w = 0.5, tr = 0.01, er = 2.0;
    tbl_table *a = NULL, *b = NULL;
    check_ok(tbl_create(&f, &num, &w, 1, &tr, 1, &er, 1, &a), "tbl_create");
    check_ok(tbl_create(&f, &num, &w, 1, &tr, 1, &er, 1, &b), "tbl_create");
    tbl_build_opts o;
    tbl_build_opts_default(&o);
    o.jobs = 1;
    check_ok(tbl_build(a, pa, &o, NULL), "tbl_build, one job");
    int levels = omp_get_max_active_levels(), blas = openblas_get_num_threads();
    o.jobs = 2;
    check_ok(tbl_build(b, pb, &o, NULL), "tbl_build, two jobs");
    tbl_point p = *tbl_point_get(a, 0), q = *tbl_point_get(b, 0);
    printf("one point, 2 members: mu_s %.6f on one thread (%.2f CPU s, %.2f s wall), %.6f on "
           "two (%.2f CPU s, %.2f s wall)\n", p.mu_s, p.cpu_s, p.wall_s, q.mu_s, q.cpu_s,
           q.wall_s);
    assert_int_equal(p.state, TBL_DONE);
    assert_int_equal(p.members, 2);
    assert_true(q.cpu_s > 0.0 && q.wall_s > 0.0);
    p.cpu_s = q.cpu_s, p.wall_s = q.wall_s;
    if (point_diff(&p, &q)) fail_msg("two threads: %s differs", point_diff(&p, &q));
    assert_int_equal(omp_get_max_active_levels(), levels);
    assert_int_equal(openblas_get_num_threads(), blas);
    tbl_destroy(&a);
    tbl_destroy(&b);
}

/* ---- how much μs depends on where inception is declared ----------------- */

/* d ln mu_s / d ln ux at inception (tbl_point.mu_s_ux_slope): a query reads
 * it off the done points around it with multilinear weights in the
 * logarithms, exact for a slope linear in ln w, ln t/R, ln Eco/Esu; a point
 * that does not say makes the query's NaN.  On the surface
 * (TBL_MODEL_SLOPE) sum s Qmax / sum Qmax: a slope the same everywhere is
 * the surface's, to rounding; one that varies lies between its values.  A
 * file of format 6 has no slopes: read back, points and members say NaN
 * (not 0), everything else is as written, and there is no slope model. */
static double slope_fn(double w, double tR, double E)
{
    return 0.3 + 0.05 * log(w) + 0.02 * log(tR) + 0.1 * log(E);
}

static void test_ux_slope(void **state)
{
    char dir[128], path[192];
    scratch_sub(state, "ux-slope", dir, sizeof dir);
    snprintf(path, sizeof path, "%s/slope.h5", dir);
    tbl_table *t = hertz_table(0.0, 0.02, 3), *r = NULL;
    for (int i = 0; i < tbl_points(t); i++) {
        tbl_point p = *tbl_point_get(t, i);
        double w, tR, E;
        tbl_coords(t, i, &w, &tR, &E);
        p.mu_s_ux_slope = slope_fn(w, tR, E);
        if (i == 5) { /* two members, each its own slope */
            p.members = p.ens.k = 2;
            p.ens.period = 1.2, p.ens.delta = 1e-3, p.ens.delta_mesh = 1e-3;
            for (int j = 0; j < 2; j++) {
                tbl_member *m = &p.ens.m[j];
                m->elements_per_contact = 6.0 + 0.6 * j, m->P = 10.0, m->A = 0.01;
                m->P_slide = 9.0, m->Q_max = 3.0, m->ux_slide = 1e-3, m->mu_s = p.mu_s;
                m->mu_s_preload = p.mu_s, m->mu_s_err = 0.01, m->cpu_s = 1.0;
                m->mu_s_ux_slope = p.mu_s_ux_slope + (j ? 0.01 : -0.01);
            }
        }
        check_ok(tbl_point_set(t, i, &p), "tbl_point_set");
    }
    check_ok(tbl_fit(t), "tbl_fit");
    const double *wa;
    tbl_axis(t, 0, &wa);
    double wq = sqrt(wa[10] * wa[11]), tq = 0.01, Eq = 1.5;
    tbl_value v;
    check_ok(tbl_query(t, wq, tq, Eq, &v), "tbl_query");
    printf("slope at an inner query %.12f, the function %.12f\n", v.mu_s_ux_slope,
           slope_fn(wq, tq, Eq));
    assert_true(fabs(v.mu_s_ux_slope - slope_fn(wq, tq, Eq)) < 1e-12);
    check_ok(tbl_query(t, wa[10], TR[1], ER[0], &v), "tbl_query");
    assert_true(v.mu_s_ux_slope == slope_fn(wa[10], TR[1], ER[0])); /* on a node: its own */

    check_ok(tbl_write(t, path), "tbl_write");
    check_ok(tbl_read(path, &r), "tbl_read");
    for (int i = 0; i < tbl_points(t); i++) {
        const char *d = point_diff(tbl_point_get(t, i), tbl_point_get(r, i));
        if (d) fail_msg("point %d: %s differs after the round trip", i, d);
    }
    tbl_destroy(&r);

    /* the same file as format 6 wrote it */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_true(H5Ldelete(f, "points/mu_s_ux_slope", H5P_DEFAULT) >= 0);
    assert_true(H5Ldelete(f, "members/mu_s_ux_slope", H5P_DEFAULT) >= 0);
    hid_t a = H5Aopen(f, "format_version", H5P_DEFAULT);
    int ver = 6;
    assert_true(a >= 0 && H5Awrite(a, H5T_NATIVE_INT, &ver) >= 0);
    H5Aclose(a);
    H5Fclose(f);
    check_ok(tbl_read(path, &r), "tbl_read format 6");
    for (int i = 0; i < tbl_points(t); i++) {
        tbl_point want = *tbl_point_get(t, i);
        const tbl_point *got = tbl_point_get(r, i);
        assert_true(isnan(got->mu_s_ux_slope));
        for (int j = 0; j < got->ens.k; j++) assert_true(isnan(got->ens.m[j].mu_s_ux_slope));
        want.mu_s_ux_slope = got->mu_s_ux_slope;
        for (int j = 0; j < want.ens.k; j++) want.ens.m[j].mu_s_ux_slope = NAN;
        const char *d = point_diff(&want, got);
        if (d) fail_msg("point %d: %s differs in the format-6 file", i, d);
    }
    assert_int_equal(tbl_point_get(r, 5)->ens.k, 2);
    check_ok(tbl_query(r, wq, tq, Eq, &v), "tbl_query format 6");
    assert_true(isnan(v.mu_s_ux_slope));
    stc_params p;
    family_params(1.5, &p);
    asp_model *ms = NULL;
    expect_fail(tbl_model_create(r, &p, T_MM, TBL_MODEL_SLOPE, &ms), STC_ERANGE,
                "slope model of a format-6 file", "before format 7", NULL);
    assert_null(ms);
    tbl_destroy(&r);

    /* the surface: the slope summed as the share of each summit's Qmax */
    asp_model *hz = hertz_model();
    double sigma_s = 3.0 * asp_model_omega_c(hz, R_SUMMIT), lo = INFINITY, hi = -INFINITY;
    asp_model_destroy(&hz);
    for (int pass = 1; pass >= 0; pass--) {
        for (int i = 0; pass == 0 && i < tbl_points(t); i++) { /* 0: one slope, 0.2 */
            tbl_point q = *tbl_point_get(t, i);
            q.mu_s_ux_slope = 0.2;
            check_ok(tbl_point_set(t, i, &q), "tbl_point_set");
        }
        check_ok(tbl_fit(t), "tbl_fit");
        asp_model *mq = NULL;
        ms = NULL;
        srf_gw *gq = NULL, *gs = NULL;
        check_ok(tbl_model_create(t, &p, T_MM, TBL_MODEL_PRELOAD, &mq), "model");
        check_ok(tbl_model_create(t, &p, T_MM, TBL_MODEL_SLOPE, &ms), "slope model");
        check_ok(srf_gw_create_gaussian(mq, ETA, R_SUMMIT, sigma_s, NULL, &gq), "gw");
        check_ok(srf_gw_create_gaussian(ms, ETA, R_SUMMIT, sigma_s, NULL, &gs), "gw slope");
        for (int i = 0; i < tbl_points(t); i++) {
            double w, tR, E;
            tbl_coords(t, i, &w, &tR, &E);
            lo = fmin(lo, slope_fn(w, tR, E)), hi = fmax(hi, slope_fn(w, tR, E));
        }
        for (double h = 0.0; h <= 2.0; h += 1.0) {
            srf_gw_point a, b;
            check_ok(srf_gw_at_separation(gq, h, &a), "gw at separation");
            check_ok(srf_gw_at_separation(gs, h, &b), "gw slope at separation");
            double s = b.Q_MPa / a.Q_MPa;
            printf("  %s slope, h = %.0f: surface d ln mu_s / d ln ux %.12f\n",
                   pass ? "varying" : "uniform", h, s);
            if (pass == 0) assert_true(fabs(s - 0.2) < 1e-12);
            else assert_true(s > lo && s < hi && fabs(s - 0.2) > 1e-3);
        }
        srf_gw_destroy(&gq), srf_gw_destroy(&gs);
        asp_model_destroy(&mq), asp_model_destroy(&ms);
    }

    tbl_destroy(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hertz_through_file), cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_history),
        cmocka_unit_test(test_interpolation),      cmocka_unit_test(test_mu_smoothing),
        cmocka_unit_test(test_refusals),           cmocka_unit_test(test_merge),
        cmocka_unit_test(test_partial),    cmocka_unit_test(test_interp_t_over_R),
        cmocka_unit_test(test_t_over_R_at_axis_ends),
        cmocka_unit_test(test_bundled_table_quadrature), cmocka_unit_test(test_retry_failed),
        cmocka_unit_test(test_point_refine), cmocka_unit_test(test_refinable),
        cmocka_unit_test(test_normal_grid), cmocka_unit_test(test_one_material),
        cmocka_unit_test(test_caller_settings),    cmocka_unit_test(test_point_threads),
        cmocka_unit_test(test_fit_reused),         cmocka_unit_test(test_ux_slope),
        cmocka_unit_test(test_failed_member_not_taken),
    };
    return cmocka_run_group_tests(tests, scratch_setup, scratch_teardown);
}
