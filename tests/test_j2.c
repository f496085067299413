/* J2 material kernel: elastic law, return onto the yield surface (midpoint,
 * radial, exact), isochoric flow, consistent tangents vs finite
 * differences, order of accuracy in the increment, exactness of the exact
 * integration along a straight path, uniaxial strain against the closed
 * form. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "fe.h"
#include "stiction/asperity.h"

static asp_j2 steel(void)
{
    asp_j2 m;
    stc_material mat = {200000.0, 0.32, 200.0};
    asp_j2_init(&m, &mat);
    return m;
}

/* Strain directions (Voigt, engineering shear) used throughout. */
static const double DIRS[5][6] = {
    {1, 0, 0, 0, 0, 0},
    {0.3, -0.7, 0.2, 0.5, -0.4, 0.9},
    {-1, 0.5, 0.5, 0, 0, 0},
    {0.1, 0.2, -0.6, -1.1, 0.3, 0.05},
    {0, 0, 0, 1, 0, 0},
};

static void test_elastic_exact(void **state)
{
    (void)state;
    asp_j2 m = steel();
    asp_qp_state old = {{0}, 0, {0}}, upd;
    double eps[6] = {1e-4, -2e-4, 0.5e-4, 3e-4, -1e-4, 0.7e-4}, sig[6], D[36];
    assert_int_equal(asp_j2_update(&m, eps, &old, &upd, sig, D), 0);
    double tr = eps[0] + eps[1] + eps[2];
    for (int a = 0; a < 3; a++)
        assert_true(fabs(sig[a] - (m.lambda * tr + 2 * m.mu * eps[a])) < 1e-12 * m.E);
    for (int a = 3; a < 6; a++)
        assert_true(fabs(sig[a] - m.mu * eps[a]) < 1e-12 * m.E);
    assert_true(upd.epbar == 0.0);
    /* Lamé / bulk consistency */
    assert_true(fabs(m.kappa - (m.lambda + 2.0 * m.mu / 3.0)) < 1e-9 * m.E);
    printf("elastic stress exact; kappa = lambda + 2mu/3\n");
}

static void test_return_on_surface(void **state)
{
    (void)state;
    asp_j2 m = steel();
    asp_qp_state old = {{0}, 0, {0}}, upd;
    double worst = 0.0, worst_tr = 0.0;
    for (int d = 0; d < 5; d++) {
        double eps[6], sig[6];
        for (int a = 0; a < 6; a++) eps[a] = 5e-3 * DIRS[d][a];
        assert_int_equal(asp_j2_update(&m, eps, &old, &upd, sig, NULL), 1);
        double e = fabs(asp_von_mises(sig) - m.Y) / m.Y;
        double trp = fabs(upd.eps_p[0] + upd.eps_p[1] + upd.eps_p[2]);
        worst = fmax(worst, e);
        worst_tr = fmax(worst_tr, trp);
        assert_true(e < 1e-12);
        assert_true(trp < 1e-15 * fmax(1.0, upd.epbar) + 1e-18);
        /* the pressure is elastic: p = kappa tr(eps) */
        double p = (sig[0] + sig[1] + sig[2]) / 3.0;
        double tr = eps[0] + eps[1] + eps[2];
        assert_true(fabs(p - m.kappa * tr) < 1e-10 * m.E);
        assert_true(upd.epbar > 0.0);
    }
    printf("after return |svm - Y|/Y max = %.2e, |tr eps_p| max = %.2e\n", worst, worst_tr);
}

/* Central differences of the stress against D, in state `old` at eps0. */
static double tangent_error(const asp_j2 *m, const asp_qp_state *old,
                            const double eps0[6], int expect_plastic)
{
    double D[36], sig0[6];
    asp_qp_state upd;
    assert_int_equal(asp_j2_update(m, eps0, old, &upd, sig0, D), expect_plastic);
    double dnorm = 0.0;
    for (int k = 0; k < 36; k++) dnorm = fmax(dnorm, fabs(D[k]));
    double worst = 0.0;
    for (int b = 0; b < 6; b++) {
        double h = 1e-8 * fmax(1e-3, fabs(eps0[b])), ep[6], em[6], sp[6], sm[6];
        memcpy(ep, eps0, sizeof ep);
        memcpy(em, eps0, sizeof em);
        ep[b] += h;
        em[b] -= h;
        assert_int_equal(asp_j2_update(m, ep, old, &upd, sp, NULL), expect_plastic);
        assert_int_equal(asp_j2_update(m, em, old, &upd, sm, NULL), expect_plastic);
        for (int a = 0; a < 6; a++) {
            double fd = (sp[a] - sm[a]) / (2 * h);
            worst = fmax(worst, fabs(fd - D[a * 6 + b]) / dnorm);
        }
    }
    return worst;
}

static void test_tangent_fd(void **state)
{
    (void)state;
    static const char *name[3] = {"midpoint", "radial", "exact"};
    for (int mode = 0; mode < 3; mode++) { /* asp_return_map */
        asp_j2 m = steel();
        m.map = mode;
        asp_qp_state virgin = {{0}, 0, {0}};
        /* a pre-strained state, to test with nonzero eps_p */
        asp_qp_state pre;
        double e1[6], s1[6];
        for (int a = 0; a < 6; a++) e1[a] = 4e-3 * DIRS[1][a];
        assert_int_equal(asp_j2_update(&m, e1, &virgin, &pre, s1, NULL), 1);
        double worst_el = 0.0, worst_pl = 0.0;
        for (int d = 0; d < 5; d++) {
            double eps[6];
            for (int a = 0; a < 6; a++) eps[a] = 1e-4 * DIRS[d][a];
            worst_el = fmax(worst_el, tangent_error(&m, &virgin, eps, 0));
            for (int a = 0; a < 6; a++) eps[a] = 6e-3 * DIRS[d][a];
            worst_pl = fmax(worst_pl, tangent_error(&m, &virgin, eps, 1));
            for (int a = 0; a < 6; a++) eps[a] = e1[a] + 3e-3 * DIRS[(d + 2) % 5][a];
            worst_pl = fmax(worst_pl, tangent_error(&m, &pre, eps, 1));
        }
        /* a reversal within one increment: elastic unloading through the
         * yield surface's interior, then reverse yield (midpoint: the
         * elastic fraction beta > 0 from a point on the surface) */
        double eps[6];
        for (int a = 0; a < 6; a++) eps[a] = e1[a] - 9e-3 * DIRS[1][a] + 1e-3 * DIRS[4][a];
        worst_pl = fmax(worst_pl, tangent_error(&m, &pre, eps, 1));
        /* exact: an increment that grazes the surface (the path leaves it
         * almost tangentially), where dβ/dε is singular */
        if (mode == 2) {
            /* the strain direction DIRS[3], deviatoric, with its part along
             * s removed: Δs·s = 2μ Σ s_a ε_a (engineering shears), and a
             * strain along s has ε_a = s_a (normal), 2 s_a (shear) */
            double dir[6], tr = (DIRS[3][0] + DIRS[3][1] + DIRS[3][2]) / 3.0, se = 0.0, ss = 0.0;
            for (int a = 0; a < 6; a++) dir[a] = DIRS[3][a] - (a < 3 ? tr : 0.0);
            for (int a = 0; a < 6; a++)
                se += pre.s[a] * dir[a], ss += pre.s[a] * pre.s[a] * (a < 3 ? 1.0 : 2.0);
            for (int a = 0; a < 6; a++) dir[a] -= se / ss * pre.s[a] * (a < 3 ? 1.0 : 2.0);
            for (int a = 0; a < 6; a++) eps[a] = e1[a] + 2e-3 * dir[a];
            double g = tangent_error(&m, &pre, eps, 1);
            printf("exact: increment tangent to the yield surface, tangent vs FD %.2e\n", g);
            worst_pl = fmax(worst_pl, g);
        }
        printf("%s: tangent vs central FD: elastic %.2e, plastic %.2e (rel. to max|D|)\n",
               name[mode], worst_el, worst_pl);
        assert_true(worst_el < 1e-6);
        assert_true(worst_pl < 1e-6);
    }
}

/* Order of accuracy in the increment: a strain path that first yields, then
 * turns its deviatoric direction by 90° while growing (the stress turns
 * on the yield surface, as under a growing contact), integrated in n and 2n
 * increments against 20000 midpoint increments.  Measured errors (|Δσ|/Y)
 * and ratios printed; second order for the midpoint rule and the exact
 * integration (exact on each chord of the curved path), first for the
 * radial return, and the midpoint more accurate than radial at equal n. */
static double path_error(int map, int n, const double ref[6], double out[6])
{
    asp_j2 m = steel();
    m.map = map;
    asp_qp_state st = {{0}, 0, {0}}, nx;
    double ey = m.Y / (2 * m.mu), d1[6] = {1, -1, 0, 0, 0, 0}, d2[6] = {0, 0, 0, 1, 0, 0};
    double sig[6], e = 0.0;
    for (int k = 1; k <= n; k++) {
        double t = (double)k / n, th = 0.5 * M_PI * t, mag = ey * (3.0 + 3.0 * t), eps[6];
        for (int a = 0; a < 6; a++)
            eps[a] = mag * (cos(th) * d1[a] + sin(th) * d2[a] * 2.0) + 2e-4 * t * (a < 3);
        asp_j2_update(&m, eps, &st, &nx, sig, NULL);
        st = nx;
    }
    if (out) memcpy(out, sig, sizeof sig);
    if (ref)
        for (int a = 0; a < 6; a++) e = fmax(e, fabs(sig[a] - ref[a]) / m.Y);
    return e;
}

static void test_increment_order(void **state)
{
    (void)state;
    double ref[6];
    path_error(ASP_RETURN_MIDPOINT, 20000, NULL, ref);
    double m1 = path_error(ASP_RETURN_MIDPOINT, 8, ref, NULL);
    double m2 = path_error(ASP_RETURN_MIDPOINT, 16, ref, NULL);
    double r1 = path_error(ASP_RETURN_RADIAL, 8, ref, NULL);
    double r2 = path_error(ASP_RETURN_RADIAL, 16, ref, NULL);
    double x1 = path_error(ASP_RETURN_EXACT, 8, ref, NULL);
    double x2 = path_error(ASP_RETURN_EXACT, 16, ref, NULL);
    double rr = path_error(ASP_RETURN_RADIAL, 20000, ref, NULL);
    double xx = path_error(ASP_RETURN_EXACT, 20000, ref, NULL);
    printf("turning path, |dsigma|/Y at 8 / 16 increments: midpoint %.2e / %.2e (ratio %.2f), "
           "radial %.2e / %.2e (ratio %.2f), exact %.2e / %.2e (ratio %.2f); "
           "at 20000: radial %.1e, exact %.1e\n",
           m1, m2, m1 / m2, r1, r2, r1 / r2, x1, x2, x1 / x2, rr, xx);
    assert_true(m1 / m2 > 3.0 && m1 / m2 < 5.5);
    assert_true(r1 / r2 > 1.5 && r1 / r2 < 2.7);
    assert_true(x1 / x2 > 3.0 && x1 / x2 < 5.5);
    assert_true(m1 < 0.5 * r1);
    assert_true(rr < 1e-3); /* all converge to the same path integral */
    assert_true(xx < 1e-7);
}

/* The exact integration is exact along a straight strain path: from a
 * yielded state, one increment that unloads through the elastic interior
 * and reloads 150° away from the start gives the same stress and ε̄_p as
 * 4000 increments along the same line, and as the midpoint and radial
 * returns in the limit of many increments. */
static void test_exact_straight(void **state)
{
    (void)state;
    asp_j2 m = steel();
    m.map = ASP_RETURN_EXACT;
    asp_qp_state virgin = {{0}, 0, {0}}, pre, st, nx;
    double e0[6], e1[6], sig1[6], sign[6], sig[6];
    for (int a = 0; a < 6; a++) e0[a] = 4e-3 * DIRS[1][a];
    asp_j2_update(&m, e0, &virgin, &pre, sig, NULL);
    for (int a = 0; a < 6; a++) e1[a] = e0[a] - 7e-3 * DIRS[1][a] + 4e-3 * DIRS[3][a];
    assert_int_equal(asp_j2_update(&m, e1, &pre, &nx, sig1, NULL), 1);
    double ep1 = nx.epbar - pre.epbar, err[3], dep[3];
    for (int map = 0; map < 3; map++) {
        m.map = map == 0 ? ASP_RETURN_EXACT : map == 1 ? ASP_RETURN_MIDPOINT : ASP_RETURN_RADIAL;
        int n = 4000;
        st = pre;
        for (int k = 1; k <= n; k++) {
            double eps[6], t = (double)k / n;
            for (int a = 0; a < 6; a++) eps[a] = e0[a] + t * (e1[a] - e0[a]);
            asp_j2_update(&m, eps, &st, &nx, sign, NULL);
            st = nx;
        }
        err[map] = 0.0;
        for (int a = 0; a < 6; a++) err[map] = fmax(err[map], fabs(sign[a] - sig1[a]) / m.Y);
        dep[map] = fabs(st.epbar - pre.epbar - ep1) / ep1;
    }
    printf("straight path, one exact increment vs 4000 increments: |dsigma|/Y exact %.1e, "
           "midpoint %.1e, radial %.1e; eps_p-bar rel. %.1e / %.1e / %.1e\n",
           err[0], err[1], err[2], dep[0], dep[1], dep[2]);
    assert_true(err[0] < 1e-11 && dep[0] < 1e-9);
    assert_true(err[1] < 1e-6 && dep[1] < 1e-5);
    assert_true(err[2] < 1e-3 && dep[2] < 1e-2);
}

/* D symmetric (associative flow) and the plastic tangent annihilates n. */
static void test_tangent_structure(void **state)
{
    (void)state;
    asp_j2 m = steel();
    asp_qp_state old = {{0}, 0, {0}}, upd;
    double eps[6], sig[6], D[36];
    for (int a = 0; a < 6; a++) eps[a] = 5e-3 * DIRS[3][a];
    assert_int_equal(asp_j2_update(&m, eps, &old, &upd, sig, D), 1);
    for (int a = 0; a < 6; a++)
        for (int b = 0; b < 6; b++)
            assert_true(fabs(D[a * 6 + b] - D[b * 6 + a]) < 1e-9 * m.E);
    /* strain increment along the flow direction (engineering n) gives no
     * stress change: D n_eng = 0 */
    double p = (sig[0] + sig[1] + sig[2]) / 3.0, neng[6];
    for (int a = 0; a < 6; a++) neng[a] = (a < 3 ? sig[a] - p : 2.0 * sig[a]);
    for (int a = 0; a < 6; a++) {
        double v = 0.0;
        for (int b = 0; b < 6; b++) v += D[a * 6 + b] * neng[b];
        assert_true(fabs(v) < 1e-9 * m.E * m.Y);
    }
    printf("plastic tangent symmetric, D n = 0\n");
}

/* Uniaxial strain eps_xx = e (others 0), incrementally: elastic up to
 * e_y = Y / 2mu, then sxx - syy = Y and p = kappa e (closed form). */
static void test_uniaxial_strain(void **state)
{
    (void)state;
    asp_j2 m = steel();
    asp_qp_state st = {{0}, 0, {0}}, nx;
    double ey = m.Y / (2 * m.mu), worst = 0.0;
    int nstep = 40;
    for (int k = 1; k <= nstep; k++) {
        double e = 4.0 * ey * k / nstep, eps[6] = {e, 0, 0, 0, 0, 0}, sig[6];
        int pl = asp_j2_update(&m, eps, &st, &nx, sig, NULL);
        double sx, sy;
        if (e <= ey) {
            sx = (m.lambda + 2 * m.mu) * e;
            sy = m.lambda * e;
            assert_int_equal(pl, 0);
        } else {
            sx = m.kappa * e + 2.0 * m.Y / 3.0;
            sy = m.kappa * e - m.Y / 3.0;
            assert_int_equal(pl, 1);
        }
        worst = fmax(worst, fabs(sig[0] - sx) / m.Y);
        worst = fmax(worst, fabs(sig[1] - sy) / m.Y);
        worst = fmax(worst, fabs(sig[2] - sy) / m.Y);
        st = nx;
    }
    /* eps_p_xx = e - e_y (all deviatoric strain beyond yield is plastic) */
    double e = 4.0 * ey;
    assert_true(fabs(st.eps_p[0] - 2.0 / 3.0 * (e - ey)) < 1e-12);
    assert_true(fabs(st.epbar - 2.0 / 3.0 * (e - ey)) < 1e-12);
    printf("uniaxial strain path vs closed form: max error %.2e Y\n", worst);
    assert_true(worst < 1e-10);
}

static void test_von_mises(void **state)
{
    (void)state;
    double uni[6] = {3, 0, 0, 0, 0, 0}, shear[6] = {0, 0, 0, 0, 0, 2};
    double hyd[6] = {5, 5, 5, 0, 0, 0};
    assert_true(fabs(asp_von_mises(uni) - 3.0) < 1e-14);
    assert_true(fabs(asp_von_mises(shear) - 2.0 * sqrt(3.0)) < 1e-14);
    assert_true(fabs(asp_von_mises(hyd)) < 1e-14);
    printf("von Mises: uniaxial, pure shear, hydrostatic\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_elastic_exact),
        cmocka_unit_test(test_return_on_surface),
        cmocka_unit_test(test_tangent_fd),
        cmocka_unit_test(test_increment_order),
        cmocka_unit_test(test_exact_straight),
        cmocka_unit_test(test_tangent_structure),
        cmocka_unit_test(test_uniaxial_strain),
        cmocka_unit_test(test_von_mises),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
