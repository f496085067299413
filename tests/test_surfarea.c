/* Tributary areas of the outer-surface nodes (asperity/surfarea.c):
 * sums against the exact hemisphere area with second-order convergence
 * under the generators' `level`, the nodal quadrature of a smooth traction
 * concentrated at the contact against its exact spherical integral, the
 * axisymmetric and 3D half models against each other, coated meshes, and
 * invalid input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "tangential.h"

static const double R = 10.0, A_MAX = 0.3;

static asp_mesh *make(int dim, double t, int level)
{
    asp_mesh *m = NULL;
    /* uncoarsened shells: the whole-hemisphere sums below need every
     * surface face on the sphere (hanging nodes sit on flat coarse faces) */
    asp_mesh_spec s = {R, t, A_MAX, level, 0.0, -1, 0.0};
    assert_int_equal(dim == 2 ? asp_mesh_axisym(&s, &m) : asp_mesh_half3d(&s, &m), STC_OK);
    return m;
}

/* Σ A_i and the nodal quadrature Σ A_i f(r_i) of f = exp(-(r/w)²), r the
 * distance from the axis, w = A_MAX / 2 (a traction on the contact), and
 * the moment Σ A_i r_i² (exact: (4π/3) R'^4 over the hemisphere). */
static void sums(const asp_mesh *m, double Rp, double *total, double *gauss, double *mom2,
                 int *nsurf)
{
    double *A = malloc((size_t)m->nnode * sizeof *A), w = 0.5 * A_MAX;
    assert_non_null(A);
    assert_int_equal(asp_surface_node_areas(m, Rp, A), STC_OK);
    *total = *gauss = *mom2 = 0.0;
    *nsurf = 0;
    for (int n = 0; n < m->nnode; n++) {
        const double *x = m->x + (size_t)m->dim * n;
        double r = m->dim == 2 ? x[0] : hypot(x[0], x[1]);
        double rho = m->dim == 2 ? hypot(x[0], x[1]) : sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        assert_true(A[n] >= 0.0);
        if (fabs(rho - Rp) > 1e-9 * Rp) assert_true(A[n] == 0.0);
        if (A[n] > 0.0) (*nsurf)++;
        *total += A[n];
        *gauss += A[n] * exp(-(r / w) * (r / w));
        *mom2 += A[n] * r * r;
    }
    free(A);
}

/* ∫ exp(-(R' sin θ / w)²) 2π R'² sin θ dθ over the hemisphere (composite
 * Simpson, 20000 panels: converged to 1e-12). */
static double gauss_exact(double Rp)
{
    int n = 20000;
    double w = 0.5 * A_MAX, h = M_PI_2 / n, s = 0.0;
    for (int i = 0; i <= n; i++) {
        double th = i * h, r = Rp * sin(th);
        double f = exp(-(r / w) * (r / w)) * 2.0 * M_PI * Rp * Rp * sin(th);
        s += f * (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0);
    }
    return s * h / 3.0;
}

static void convergence(int dim, double t, int levels)
{
    double Rp = R + t, sym = dim == 2 ? 1.0 : 0.5;
    double exact = sym * 2.0 * M_PI * Rp * Rp, gex = sym * gauss_exact(Rp);
    double et[4], eg[4], em[4];
    for (int l = 0; l < levels; l++) {
        asp_mesh *m = make(dim, t, l);
        double tot, g, m2;
        int ns;
        sums(m, Rp, &tot, &g, &m2, &ns);
        et[l] = fabs(tot / exact - 1.0);
        eg[l] = fabs(g / gex - 1.0);
        em[l] = fabs(m2 / (sym * 4.0 * M_PI / 3.0 * pow(Rp, 4)) - 1.0);
        printf("dim %d t = %g level %d: %5d surface nodes, errors: sum %.3e, r² moment %.3e, "
               "contact traction %.3e", dim, t, l, ns, et[l], em[l], eg[l]);
        if (l > 0)
            printf("  (ratios %.2f, %.2f, %.2f)", et[l - 1] / et[l], em[l - 1] / em[l],
                   eg[l - 1] / eg[l]);
        printf("\n");
        asp_mesh_destroy(&m);
    }
    /* second order: the far-field size falls by √2 per level (sum, moment:
     * ratio 2).  The contact traction: in 3D the contact grid is uniform,
     * where nodal quadrature of a smooth bump is far better than second
     * order (the error, < 5e-4 already at level 0, is the tail in the
     * graded zone); axisymmetric: the contact size halves (ratio 4). */
    int L = levels - 1;
    double rt = pow(et[0] / et[L], 1.0 / L), rm = pow(em[0] / em[L], 1.0 / L);
    printf("  mean error ratio per level: sum %.2f, r² moment %.2f (second order: 2)\n", rt, rm);
    assert_true(rt > 1.85 && rm > 1.85);
    for (int l = 1; l < levels; l++) { /* no level out of step (graded sizes are not exact halves) */
        assert_true(et[l - 1] / et[l] > 1.6);
        assert_true(em[l - 1] / em[l] > 1.6);
        if (dim == 2) assert_true(eg[l - 1] / eg[l] > 3.5);
    }
    assert_true(et[levels - 1] < 2e-3 && em[levels - 1] < 4e-3);
    assert_true(eg[levels - 1] < (dim == 2 ? 5e-3 : 5e-4));
}

static void test_axisym(void **state)
{
    (void)state;
    convergence(2, 0.0, 4);
}

static void test_half3d(void **state)
{
    (void)state;
    convergence(3, 0.0, 3);
}

static void test_coated(void **state)
{
    (void)state;
    convergence(2, 0.25, 3);
    convergence(3, 0.25, 2);
}

/* Both models integrate the same traction: the 3D half model carries half
 * of the axisymmetric total. */
static void test_axisym_vs_3d(void **state)
{
    (void)state;
    for (int l = 0; l < 3; l++) {
        asp_mesh *m2 = make(2, 0.0, l), *m3 = make(3, 0.0, l);
        double t2, g2, t3, g3, q2, q3;
        int n2, n3;
        sums(m2, R, &t2, &g2, &q2, &n2);
        sums(m3, R, &t3, &g3, &q3, &n3);
        double d = fabs(2.0 * g3 / g2 - 1.0);
        printf("level %d: traction integral 3D x 2 vs axisymmetric: %.3e relative\n", l, d);
        assert_true(d < (l == 0 ? 2e-2 : l == 1 ? 5e-3 : 1.5e-3));
        asp_mesh_destroy(&m2);
        asp_mesh_destroy(&m3);
    }
}

/* Areas restricted to the contact disc r < rc sum to the exact spherical
 * cap 2π R'² (1 - cos θc), sin θc = rc/R' (half of it in the half model):
 * the consistent load of a uniform traction over the contact.  Errors:
 * dim 2 the chord error only (clipping is exact); dim 3 also the sub-cell
 * quadrature of the faces the circle cuts. */
static void test_disc_cap(void **state)
{
    (void)state;
    const double rcs[3] = {0.05, 0.13, 0.29};
    for (int dim = 2; dim <= 3; dim++)
        for (int l = 0; l < 3; l++) {
            asp_mesh *m = make(dim, 0.0, l);
            double *A = malloc((size_t)m->nnode * sizeof *A), worst = 0.0;
            for (int k = 0; k < 3; k++) {
                double rc = rcs[k], ct = sqrt(1.0 - (rc / R) * (rc / R));
                double cap = (dim == 2 ? 1.0 : 0.5) * 2.0 * M_PI * R * R * (1.0 - ct), sum = 0.0;
                assert_int_equal(asp_surface_node_areas_disc(m, R, rc, A), STC_OK);
                for (int n = 0; n < m->nnode; n++) {
                    assert_true(A[n] >= 0.0);
                    /* a node carries area only if some of its faces reach inside */
                    const double *x = m->x + (size_t)dim * n;
                    double r = dim == 2 ? x[0] : hypot(x[0], x[1]);
                    if (r > rc + 0.2) assert_true(A[n] == 0.0);
                    sum += A[n];
                }
                worst = fmax(worst, fabs(sum / cap - 1.0));
            }
            printf("dim %d level %d: cap areas (rc = 0.05, 0.13, 0.29 mm) worst relative "
                   "error %.2e\n", dim, l, worst);
            assert_true(worst < (dim == 2 ? 1e-5 : 1e-3));
            free(A);
            asp_mesh_destroy(&m);
        }
}

/* Areas over a footprint of two half-ellipses (semi-axes ap along +x, am
 * along -x, ay along y; the sheared contact, shear.c) sum to the spherical
 * area over it, ∫ R'/sqrt(R'² - x² - y²) dx dy over the quarter ellipses of
 * the half model (midpoint rule in elliptic polar coordinates, 400 x 400). */
static double foot_cap(double ap, double am, double ay)
{
    enum { NQ = 400 };
    double sum = 0.0;
    for (int h = 0; h < 2; h++) {
        double ax = h ? am : ap;
        for (int i = 0; i < NQ; i++)
            for (int j = 0; j < NQ; j++) {
                double rho = (i + 0.5) / NQ, phi = 0.5 * M_PI * (j + 0.5) / NQ;
                double x = ax * rho * cos(phi), y = ay * rho * sin(phi);
                sum += R / sqrt(R * R - x * x - y * y) * ax * ay * rho / NQ * (0.5 * M_PI / NQ);
            }
    }
    return sum;
}

static void test_foot_cap(void **state)
{
    (void)state;
    const double F[3][3] = {{0.13, 0.13, 0.13}, {0.2, 0.12, 0.15}, {0.29, 0.21, 0.25}};
    for (int l = 0; l < 2; l++) {
        asp_mesh *m = make(3, 0.0, l);
        double *A = malloc((size_t)m->nnode * sizeof *A), *D = malloc((size_t)m->nnode * sizeof *D);
        assert_non_null(A), assert_non_null(D);
        double worst = 0.0;
        for (int k = 0; k < 3; k++) {
            double sum = 0.0;
            assert_int_equal(asp_surface_node_areas_foot(m, R, F[k][0], F[k][1], F[k][2], A),
                             STC_OK);
            for (int n = 0; n < m->nnode; n++) sum += A[n];
            worst = fmax(worst, fabs(sum / foot_cap(F[k][0], F[k][1], F[k][2]) - 1.0));
        }
        /* the disc is the footprint with equal semi-axes, node by node */
        assert_int_equal(asp_surface_node_areas_disc(m, R, 0.13, D), STC_OK);
        assert_int_equal(asp_surface_node_areas_foot(m, R, 0.13, 0.13, 0.13, A), STC_OK);
        for (int n = 0; n < m->nnode; n++) assert_true(A[n] == D[n]);
        printf("level %d: footprint areas worst relative error %.2e\n", l, worst);
        assert_true(worst < 1e-3);
        free(A), free(D);
        asp_mesh_destroy(&m);
    }
}

/* The edge advance recovers the edge of a gap profile g = C (r - a)^(3/2)
 * translated from a0 to a, exactly, while the first open node is open and as
 * the next one takes over; stays at a0 when the gaps open (the trailing
 * side) or no node is open. */
static void test_edge_advance(void **state)
{
    (void)state;
    double r[7] = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6}, g0[7], g[7], a0 = 0.23;
    for (int i = 0; i < 7; i++) g0[i] = r[i] > a0 ? 2.5 * pow(r[i] - a0, 1.5) : 0.0;
    for (double a = a0; a < 0.45; a += 0.0123) {
        for (int i = 0; i < 7; i++) g[i] = r[i] > a ? 2.5 * pow(r[i] - a, 1.5) : 0.0;
        assert_true(fabs(asp_contact_edge_advance(r, g0, g, 7, a0) - a) < 1e-12);
    }
    for (int i = 0; i < 7; i++) g[i] = 1.2 * g0[i]; /* opening */
    assert_true(asp_contact_edge_advance(r, g0, g, 7, a0) == a0);
    for (int i = 0; i < 7; i++) g[i] = 0.0; /* the whole line in contact */
    assert_true(asp_contact_edge_advance(r, g0, g, 7, a0) == r[6]);
    for (int i = 0; i < 7; i++) g[i] = 1.0; /* nothing in contact */
    assert_true(asp_contact_edge_advance(r, g0, g, 7, a0) == a0);
}

static void test_invalid(void **state)
{
    (void)state;
    asp_mesh *m = make(2, 0.0, 0);
    double *A = malloc((size_t)m->nnode * sizeof *A);
    stc_error_clear();
    assert_int_equal(asp_surface_node_areas(m, -1.0, A), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "R_outer = -1 mm"));
    assert_int_equal(asp_surface_node_areas(m, 9.0, A), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "no element face lies on the sphere"));
    assert_int_equal(asp_surface_node_areas_disc(m, R, 0.0, A), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "rc = 0 mm"));
    free(A);
    asp_mesh_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_axisym),       cmocka_unit_test(test_half3d),
        cmocka_unit_test(test_coated),       cmocka_unit_test(test_axisym_vs_3d),
        cmocka_unit_test(test_disc_cap),     cmocka_unit_test(test_foot_cap),
        cmocka_unit_test(test_edge_advance),     cmocka_unit_test(test_invalid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
