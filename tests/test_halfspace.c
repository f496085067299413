/* Elastic half-space boundary elements (surface/halfspace.c): the influence of
 * one cell against the point-load solutions far away and Love's closed form at
 * its centre, Hertz for the frictionless sphere, the side and size of the
 * junction growth under full slip, and invalid input. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "stiction/halfspace.h"
#include "stiction/status.h"

#define PI 3.14159265358979323846
#define E_ 74000.0
#define NU 0.33

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

/* One loaded cell in the middle of a 64 × 64 grid. */
static void one_cell(int tangential, double h, double *w)
{
    int n = 64;
    srf_halfspace *hs;
    double *f = calloc((size_t)n * n, sizeof *f);
    assert_non_null(f);
    assert_int_equal(srf_halfspace_create(&hs, n, h, E_, NU), STC_OK);
    f[(size_t)(n / 2) * n + n / 2] = 1.0;
    assert_int_equal(srf_halfspace_disp(hs, tangential ? NULL : f, tangential ? f : NULL, w),
                     STC_OK);
    srf_halfspace_destroy(&hs);
    assert_null(hs);
    free(f);
}

/* Boussinesq: far away w = (1 − ν²) F / (π E ρ); at the centre of a square of
 * side h, Love's integral gives 4 h ln(1 + √2) (1 − ν²) p / (π E). */
static void test_boussinesq_cell(void **state)
{
    (void)state;
    int n = 64, c = n / 2;
    double h = 0.01, F = h * h, w[64 * 64];
    one_cell(0, h, w);
    double k = (1 - NU * NU) / (PI * E_);
    assert_true(rel(w[c * n + c], 4 * h * log(1 + sqrt(2.0)) * k) < 1e-12);
    for (int d = 20; d <= 30; d += 10) {
        double far = k * F / (d * h);
        assert_true(rel(w[(c + d) * n + c], far) < 2e-4); /* along x */
        assert_true(rel(w[c * n + c - d], far) < 2e-4);   /* along −y */
    }
}

/* Cerruti: a traction along +x moves the surface ahead of it INTO the solid,
 * w = (1 − 2ν) Fx x / (4π G ρ²) (Betti with the Boussinesq radial displacement
 * toward a normal load); odd in x, zero on the line x = 0. */
static void test_cerruti_cell(void **state)
{
    (void)state;
    int n = 64, c = n / 2;
    double h = 0.01, F = h * h, w[64 * 64];
    one_cell(1, h, w);
    double G = E_ / (2 * (1 + NU)), k = (1 - 2 * NU) / (4 * PI * G);
    assert_true(fabs(w[c * n + c]) < 1e-15);
    assert_true(fabs(w[c * n + c + 10]) < 1e-15);
    for (int d = 20; d <= 30; d += 10) {
        double far = k * F / (d * h);
        assert_true(w[(c + d) * n + c] > 0.0);
        assert_true(rel(w[(c + d) * n + c], far) < 2e-4);
        assert_true(rel(w[(c - d) * n + c], -far) < 2e-4);
        /* off axis, at (x, y) = (d, d) h: x/ρ² = 1/(2 d h) */
        assert_true(rel(w[(c + d) * n + c + d], k * F / (2 * d * h)) < 2e-4);
    }
}

/* Frictionless sphere: P within 0.1 % of Hertz, A within one cell ring; with
 * τc = 0 the slide changes nothing. */
static void test_hertz(void **state)
{
    (void)state;
    double R = 10.5, delta = 5.391661175e-4, Es = E_ / (1 - NU * NU);
    double a = sqrt(R * delta), P = 4.0 / 3.0 * Es * a * a * a / R;
    srf_slide_result r;
    assert_int_equal(srf_halfspace_sphere_slide(R, delta, E_, NU, 0.0, 96, 1.3, 2, &r), STC_OK);
    assert_true(rel(r.P0, P) < 1e-3);
    assert_true(fabs(r.A0 - PI * a * a) < 2 * PI * a * r.h);
    assert_true(r.A == r.A0);
    assert_true(rel(r.P, r.P0) < 1e-9);
    assert_true(r.tension == 0.0);
}

/* Full slip at τc = Y/√3 (Y = 325 MPa) at 0.5 ωc of the WSP sphere: the contact
 * grows on the trailing side (−x) only, by 7.5 % of a0 on fine grids
 * (docs/design.md §5.6: 512 cells +7.6 %, area +4.9 %); on 64 cells
 * (4 % of a0 each) within two cells of that; lead and side stay within a cell
 * of a0; the load hardly changes and the trailing side carries tension. */
static void test_junction_growth(void **state)
{
    (void)state;
    double R = 10.5, delta = 5.391661175e-4, tau = 325 / sqrt(3.0);
    srf_slide_result r;
    assert_int_equal(srf_halfspace_sphere_slide(R, delta, E_, NU, tau, 64, 1.3, 2, &r), STC_OK);
    double a0 = sqrt(r.A0 / PI), c = r.h / a0;
    assert_true(fabs(r.a_trail / a0 - 1.075) < 2 * c);
    assert_true(fabs(r.a_lead / a0 - 1.0) < c);
    assert_true(fabs(r.a_side / a0 - 1.0) < c);
    assert_true(r.A / r.A0 - 1 > 0.049 - 4 * c && r.A / r.A0 - 1 < 0.049 + 4 * c);
    assert_true(fabs(r.P / r.P0 - 1) < 0.005);
    assert_true(r.tension > 0.0);
}

static void test_invalid(void **state)
{
    (void)state;
    srf_halfspace *hs = (srf_halfspace *)1;
    srf_slide_result r;
    assert_int_equal(srf_halfspace_create(&hs, 4, 0.01, E_, NU), STC_EINVAL);
    assert_null(hs);
    assert_non_null(strstr(stc_errmsg(), "n = 4"));
    assert_int_equal(srf_halfspace_create(&hs, 32, 0.01, E_, 0.6), STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "nu = 0.6"));
    assert_int_equal(srf_halfspace_sphere_slide(10, -1e-3, E_, NU, 100, 64, 1.3, 2, &r),
                     STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "delta = -0.001"));
    assert_int_equal(srf_halfspace_sphere_slide(10, 1e-3, E_, NU, 100, 64, 0.5, 2, &r),
                     STC_EINVAL);
    assert_non_null(strstr(stc_errmsg(), "span = 0.5"));
    /* a shear strength far above the pressures: the contact grows off the grid */
    assert_int_equal(srf_halfspace_sphere_slide(10, 1e-3, E_, NU, 5e4, 32, 1.05, 1, &r),
                     STC_ERANGE);
    assert_non_null(strstr(stc_errmsg(), "grid's edge"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_boussinesq_cell), cmocka_unit_test(test_cerruti_cell),
        cmocka_unit_test(test_hertz),           cmocka_unit_test(test_junction_growth),
        cmocka_unit_test(test_invalid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
