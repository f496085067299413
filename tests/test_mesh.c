/* Axisymmetric mesh of the coated hemisphere: geometry, layers, grading,
 * quality, invalid input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fe.h"
#include "solver_impl.h" /* asp_mesh_axisym_n */

static double quad_area(const asp_mesh *m, int e, double *rc, double *zc)
{
    double A = 0.0, cr = 0.0, cz = 0.0;
    for (int a = 0; a < 4; a++) {
        const double *p = m->x + 2 * m->conn[4 * e + a], *q = m->x + 2 * m->conn[4 * e + (a + 1) % 4];
        A += 0.5 * (p[0] * q[1] - q[0] * p[1]);
        cr += 0.25 * p[0], cz += 0.25 * p[1];
    }
    *rc = cr, *zc = cz;
    return A;
}

/* Polar angles (from the axis) of the nodes on the outer arc |x| = Rp,
 * ascending; returns their count.  *out: new array. */
static int outer_arc_angles(const asp_mesh *m, double Rp, double **out)
{
    double *th = malloc((size_t)m->nnode * sizeof *th);
    int nb = 0;
    assert_non_null(th);
    for (int i = 0; i < m->nnode; i++)
        if (fabs(hypot(m->x[2 * i], m->x[2 * i + 1]) - Rp) < 1e-9 * Rp)
            th[nb++] = atan2(m->x[2 * i], m->x[2 * i + 1]);
    for (int i = 1; i < nb; i++) /* insertion sort */
        for (int k = i; k > 0 && th[k] < th[k - 1]; k--) {
            double t = th[k];
            th[k] = th[k - 1], th[k - 1] = t;
        }
    *out = th;
    return nb;
}

/* Area = quarter disk (up to the chord error of the arc), every element
 * positively oriented, quality bounded away from zero. */
static void check_mesh(const asp_mesh_spec *s, int *nelem)
{
    asp_mesh *m = NULL;
    double Rp = s->R + s->t, worst, area = 0.0;
    assert_int_equal(asp_mesh_axisym(s, &m), STC_OK);
    assert_int_equal(asp_mesh_quality(m, &worst), STC_OK);
    assert_true(worst > 0.2);
    for (int e = 0; e < m->nelem; e++) {
        double rc, zc, A = quad_area(m, e, &rc, &zc);
        assert_true(A > 0.0);
        area += A;
        (void)rc, (void)zc;
        for (int a = 0; a < 4; a++) { /* every node of an element in its layer */
            const double *p = m->x + 2 * m->conn[4 * e + a];
            double rho = hypot(p[0], p[1]);
            if (m->region[e] == ASP_REGION_COATING) assert_true(rho > s->R * (1 - 1e-12));
            else assert_true(rho < s->R * (1 + 1e-12));
        }
    }
    /* exact area of the polygon inscribed in the outer arc */
    double *th, exact = M_PI * Rp * Rp / 4.0;
    int nb = outer_arc_angles(m, Rp, &th);
    for (int i = 1; i < nb; i++) {
        double d = th[i] - th[i - 1];
        exact -= 0.5 * Rp * Rp * (d - sin(d));
    }
    free(th);
    assert_true(fabs(area - exact) < 1e-9 * exact);
    /* surface spacing at the contact: h = a_max / (6 2^level) */
    double h = s->a_max / (6 << s->level), dmin = 1e9;
    int ntop = 0, naxis_coat = 0;
    for (int i = 0; i < m->nnode; i++) {
        double r = m->x[2 * i], z = m->x[2 * i + 1];
        if (m->flags[i] & ASP_NODE_TOP) {
            ntop++;
            if (r > 0.0) dmin = fmin(dmin, r);
        }
        if ((m->flags[i] & ASP_NODE_AXIS) && z >= s->R - 1e-12 && z < Rp - 1e-12) naxis_coat++;
        if (m->flags[i] & ASP_NODE_BASE) assert_true(z == 0.0);
    }
    assert_true(fabs(dmin - h) < 1e-3 * h);
    assert_true(ntop >= 10);
    if (s->t > 0.0) assert_true(naxis_coat >= 4); /* >= 4 layers through the coating */
    printf("# R' %g t %g a_max %g level %d: %d nodes %d elements, worst scaled Jacobian %.3f\n",
           Rp, s->t, s->a_max, s->level, m->nnode, m->nelem, worst);
    *nelem = m->nelem;
    asp_mesh_destroy(&m);
    assert_null(m);
}

static void test_uncoated_levels(void **state)
{
    (void)state;
    int n[4];
    for (int l = 0; l < 4; l++) {
        asp_mesh_spec s = {10.0, 0.0, 0.1, l, 0.0, 0, 0.0};
        check_mesh(&s, &n[l]);
        if (l) assert_true(n[l] > 2 * n[l - 1]); /* refinement adds elements */
    }
}

static void test_coated(void **state)
{
    (void)state;
    int n;
    asp_mesh_spec thin = {10.0, 0.01, 0.18, 1, 0.0, 0, 0.0};
    asp_mesh_spec thick = {10.0, 0.5, 0.1, 1, 0.0, 0, 0.0};
    asp_mesh_spec mid = {10.0, 0.25, 0.05, 0, 0.0, 0, 0.0};
    check_mesh(&thin, &n);
    check_mesh(&thick, &n);
    check_mesh(&mid, &n);
}

static void test_small_contact(void **state)
{
    (void)state;
    int n;
    for (double a = 0.002; a < 1.0; a *= 4.0) {
        asp_mesh_spec s = {10.0, 0.0, a, 1, 0.0, 0, 0.0};
        check_mesh(&s, &n);
    }
}

static void test_invalid(void **state)
{
    (void)state;
    asp_mesh *m = NULL;
    asp_mesh_spec s = {10.0, 0.0, -1.0, 1, 0.0, 0, 0.0};
    assert_int_equal(asp_mesh_axisym(&s, &m), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "a_max = -1"));
    s.a_max = 0.1, s.level = 9;
    assert_int_equal(asp_mesh_axisym(&s, &m), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "level = 9"));
    s.level = 1, s.t = 5.0;
    assert_int_equal(asp_mesh_axisym(&s, &m), STC_EINVAL);
    assert_null(m);
}

/* n elements across a_max: n = 6 2^level is that level's mesh exactly; an n
 * between two levels gives a valid mesh of intermediate size. */
static void test_elements_per_contact(void **state)
{
    (void)state;
    asp_mesh_spec s = {10.0, 0.0, 0.1, 0, 0.0, 0, 0.0};
    asp_mesh *a = NULL, *b = NULL;
    assert_int_equal(asp_mesh_axisym_graded(&s, 0.02, &a), STC_OK);
    assert_int_equal(asp_mesh_axisym_n(&s, 0.02, 6.0, &b), STC_OK);
    assert_int_equal(a->nnode, b->nnode);
    assert_int_equal(a->nelem, b->nelem);
    assert_memory_equal(a->x, b->x, (size_t)a->nnode * 2 * sizeof *a->x);
    asp_mesh_destroy(&a), asp_mesh_destroy(&b);
    int ne[3];
    const double n[3] = {6.0, 8.0, 12.0};
    for (int k = 0; k < 3; k++) {
        double worst;
        assert_int_equal(asp_mesh_axisym_n(&s, 0.02, n[k], &a), STC_OK);
        assert_int_equal(asp_mesh_quality(a, &worst), STC_OK);
        assert_true(worst > 0.2);
        ne[k] = a->nelem;
        asp_mesh_destroy(&a);
    }
    printf("# elements for n = 6, 8, 12 across a_max: %d %d %d\n", ne[0], ne[1], ne[2]);
    assert_true(ne[0] < ne[1] && ne[1] < ne[2]);
    assert_int_equal(asp_mesh_axisym_n(&s, 0.02, 2.0, &a), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "elements per contact = 2"));
    assert_null(a);
}

/* A mesh for a load curve (a_min < a_max): between 1.25 a_min and 1.25 a_max
 * every surface interval is at most its distance from the axis / n (and not
 * much finer), so each contact radius of the curve has about n elements
 * across (growth by q = 1.3 alone gave intervals of ~0.3 times the
 * distance, docs/design.md §2.3). */
static void test_proportional_surface(void **state)
{
    (void)state;
    const double amin = 0.03, n = 6.0;
    asp_mesh_spec s = {10.0, 0.0, 0.3, 0, 0.0, 0, 0.0};
    asp_mesh *m = NULL;
    assert_int_equal(asp_mesh_axisym_n(&s, amin, n, &m), STC_OK);
    double *th;
    int nb = outer_arc_angles(m, s.R, &th), inzone = 0;
    for (int i = 0; i + 1 < nb; i++) {
        double x = s.R * th[i], h = s.R * (th[i + 1] - th[i]);
        if (x < 1.25 * amin * (1 + 1e-9) || x >= 1.25 * s.a_max) continue;
        inzone++;
        assert_true(h <= x / n * (1 + 1e-9));
        if (x / n < s.a_max / n) assert_true(h >= 0.75 * x / n);
    }
    printf("# %d surface intervals between 1.25 a_min and 1.25 a_max\n", inzone);
    assert_true(inzone >= (int)(n * log(s.a_max / amin)) - 1);
    free(th);
    asp_mesh_destroy(&m);
}

/* an inverted element is reported by the quality check */
static void test_inverted(void **state)
{
    (void)state;
    asp_mesh *m = NULL;
    asp_mesh_spec s = {10.0, 0.0, 0.1, 0, 0.0, 0, 0.0};
    double w;
    assert_int_equal(asp_mesh_axisym(&s, &m), STC_OK);
    int t = m->conn[1];
    m->conn[1] = m->conn[3], m->conn[3] = t;
    assert_int_equal(asp_mesh_quality(m, &w), STC_EFORMAT);
    assert_true(w < 0.0);
    asp_mesh_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uncoated_levels), cmocka_unit_test(test_coated),
        cmocka_unit_test(test_small_contact), cmocka_unit_test(test_invalid),
        cmocka_unit_test(test_inverted),    cmocka_unit_test(test_elements_per_contact),
        cmocka_unit_test(test_proportional_surface),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
