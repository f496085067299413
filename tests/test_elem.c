/* B-bar elements (hex8, axisymmetric quad4): stiffness vs finite
 * differences of the internal force, patch tests, rigid-body modes, the
 * axisymmetric hoop strain and 2πr weighting, and absence of volumetric
 * locking under isochoric plastic flow. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_sort_vector.h>

#include "fe.h"

static asp_j2 material(double nu)
{
    asp_j2 m;
    stc_material mat = {200000.0, nu, 200.0};
    asp_j2_init(&m, &mat);
    return m;
}

/* Deterministic pseudo-random numbers in [-1, 1] (no global state). */
static double prand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xffff) / 32767.5 - 1.0;
}

static const double HEXC[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

/* A distorted hex of size h at (x0, y0, z0). */
static void hex_geom(double h, double distort, unsigned seed, double X[24])
{
    unsigned s = seed;
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            X[3 * a + i] = 1.0 + h * HEXC[a][i] + distort * h * prand(&s);
}

/* A distorted axisymmetric quad at r in [r0, r0 + h]. */
static void quad_geom(double r0, double h, double distort, unsigned seed, double X[8])
{
    static const double QC[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    unsigned s = seed;
    for (int a = 0; a < 4; a++) {
        X[2 * a] = r0 + h * QC[a][0] + distort * h * prand(&s);
        X[2 * a + 1] = 2.0 + h * QC[a][1] + distort * h * prand(&s);
    }
}

typedef int (*elem_fn)(const double *, const double *, const asp_j2 *,
                       const asp_qp_state *, asp_qp_state *, double *, double *,
                       double *, double *);

/* max |Ke - FD(fe)| / max |Ke| with central differences; every call must
 * report `nplastic` plastic points (so no FD step crosses the yield surface).
 * Also: the factorization matrix Kp is symmetric, and equals Ke where Ke is
 * symmetric (elastic; and the midpoint return from a virgin state is a
 * proportional increment). */
static double ke_fd_error(elem_fn f, int nd, const double *X, const double *u,
                          const asp_j2 *m, const asp_qp_state *old, int nplastic)
{
    double fe[24], Ke[576], Kp[576], fp[24], fm[24], up[24];
    assert_int_equal(f(X, u, m, old, NULL, fe, Ke, Kp, NULL), nplastic);
    double kpmax = 0.0;
    for (int k = 0; k < nd * nd; k++) kpmax = fmax(kpmax, fabs(Kp[k]));
    for (int i = 0; i < nd; i++)
        for (int j = 0; j < nd; j++) {
            assert_true(fabs(Kp[i * nd + j] - Kp[j * nd + i]) <= 1e-12 * kpmax);
            if (!old) assert_true(fabs(Kp[i * nd + j] - Ke[i * nd + j]) <= 1e-9 * kpmax);
        }
    double umax = 0.0, kmax = 0.0, worst = 0.0;
    for (int j = 0; j < nd; j++) umax = fmax(umax, fabs(u[j]));
    for (int k = 0; k < nd * nd; k++) kmax = fmax(kmax, fabs(Ke[k]));
    double h = 1e-7 * umax;
    for (int j = 0; j < nd; j++) {
        memcpy(up, u, sizeof(double) * (size_t)nd);
        up[j] = u[j] + h;
        assert_int_equal(f(X, up, m, old, NULL, fp, NULL, NULL, NULL), nplastic);
        up[j] = u[j] - h;
        assert_int_equal(f(X, up, m, old, NULL, fm, NULL, NULL, NULL), nplastic);
        for (int i = 0; i < nd; i++)
            worst = fmax(worst, fabs((fp[i] - fm[i]) / (2 * h) - Ke[i * nd + j]) / kmax);
    }
    return worst;
}

static void test_hex8_tangent_fd(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    double X[24], u[24], worst_el = 0, worst_pl = 0;
    hex_geom(0.1, 0.12, 7u, X);
    unsigned s = 99u;
    /* elastic: strains ~ 1e-4 */
    for (int j = 0; j < 24; j++) u[j] = 1e-5 * prand(&s);
    worst_el = ke_fd_error(asp_hex8, 24, X, u, &m, NULL, 0);
    /* plastic: a deviatoric stretch of 1e-2 plus noise, from a virgin and
     * from a pre-strained state */
    for (int a = 0; a < 8; a++) {
        u[3 * a] = 1e-2 * (X[3 * a] - 1.0) + 1e-4 * prand(&s);
        u[3 * a + 1] = -1e-2 * (X[3 * a + 1] - 1.0) + 1e-4 * prand(&s);
        u[3 * a + 2] = 1e-4 * prand(&s);
    }
    worst_pl = fmax(worst_pl, ke_fd_error(asp_hex8, 24, X, u, &m, NULL, 8));
    asp_qp_state pre[8];
    double fe[24];
    assert_int_equal(asp_hex8(X, u, &m, NULL, pre, fe, NULL, NULL, NULL), 8);
    for (int a = 0; a < 8; a++) u[3 * a + 2] += 0.2e-2 * (X[3 * a] - 1.0);
    worst_pl = fmax(worst_pl, ke_fd_error(asp_hex8, 24, X, u, &m, pre, 8));
    /* from the pre-strained state the stress turns: the midpoint return's
     * Ke is not symmetric there, so the check above covers its skew part */
    double fk[24], Ke[576], kmax = 0.0, asym = 0.0;
    assert_int_equal(asp_hex8(X, u, &m, pre, NULL, fk, Ke, NULL, NULL), 8);
    for (int i = 0; i < 24; i++)
        for (int j = 0; j < 24; j++) {
            kmax = fmax(kmax, fabs(Ke[i * 24 + j]));
            asym = fmax(asym, fabs(Ke[i * 24 + j] - Ke[j * 24 + i]));
        }
    printf("hex8 Ke vs FD of fe: elastic %.2e, plastic %.2e; |Ke - Keᵀ| / |Ke| %.2e after the "
           "pre-strain\n", worst_el, worst_pl, asym / kmax);
    assert_true(asym > 1e-4 * kmax);
    assert_true(worst_el < 1e-6);
    assert_true(worst_pl < 1e-6);
}

static void test_quad4_tangent_fd(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    double X[8], u[8], worst_el = 0, worst_pl = 0;
    for (int c = 0; c < 2; c++) {
        /* c = 0: an element touching the axis (r0 = 0); c = 1: off axis */
        quad_geom(c ? 0.5 : 0.0, 0.1, 0.1, 3u + c, X);
        if (c == 0) X[0] = X[6] = 0.0;
        unsigned s = 11u;
        for (int j = 0; j < 8; j++) u[j] = 1e-5 * prand(&s);
        worst_el = fmax(worst_el, ke_fd_error(asp_quad4_axi, 8, X, u, &m, NULL, 0));
        for (int a = 0; a < 4; a++) {
            u[2 * a] = 1e-2 * X[2 * a] + 1e-4 * prand(&s);
            u[2 * a + 1] = -2e-2 * (X[2 * a + 1] - 2.0) + 1e-4 * prand(&s);
        }
        worst_pl = fmax(worst_pl, ke_fd_error(asp_quad4_axi, 8, X, u, &m, NULL, 4));
    }
    printf("quad4 axi Ke vs FD of fe: elastic %.2e, plastic %.2e\n", worst_el, worst_pl);
    assert_true(worst_el < 1e-6);
    assert_true(worst_pl < 1e-6);
}

/* Linear field u = G x (+ c): strain of G is exact, so stress is too. */
static void linear_field(const double G[3][3], const double *x, double *u)
{
    for (int i = 0; i < 3; i++)
        u[i] = 1e-3 * i + G[i][0] * x[0] + G[i][1] * x[1] + G[i][2] * x[2];
}

/* 2x2x2 hexes around a displaced interior node: constant stress from a
 * linear field and zero net internal force at the interior node. */
static void test_hex8_patch(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    const double G[3][3] = {{2e-4, 1e-4, -3e-5}, {0.5e-4, -1e-4, 0.7e-4}, {2e-5, 1e-5, 3e-4}};
    double Xg[3][3][3][3]; /* node grid [i][j][k][xyz] */
    unsigned s = 5u;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                int ijk[3] = {i, j, k};
                for (int d = 0; d < 3; d++) {
                    double x = 0.5 * ijk[d];
                    /* perturb every node that is not on a face normal to d */
                    if (ijk[d] == 1) x += 0.12 * prand(&s);
                    Xg[i][j][k][d] = x;
                }
            }
    double eps_ex[6] = {G[0][0], G[1][1], G[2][2], G[0][1] + G[1][0],
                        G[1][2] + G[2][1], G[2][0] + G[0][2]};
    double sig_ex[6], fint[3] = {0}, serr = 0.0;
    asp_qp_state z = {{0}, 0, {0}}, tmp;
    asp_j2_update(&m, eps_ex, &z, &tmp, sig_ex, NULL);
    double smax = 0.0;
    for (int a = 0; a < 6; a++) smax = fmax(smax, fabs(sig_ex[a]));
    for (int e = 0; e < 8; e++) {
        int e0 = e & 1, e1 = (e >> 1) & 1, e2 = (e >> 2) & 1;
        double X[24], u[24], fe[24], sig[48];
        int corner_of_center = -1;
        for (int a = 0; a < 8; a++) {
            int i = e0 + (int)HEXC[a][0], j = e1 + (int)HEXC[a][1], k = e2 + (int)HEXC[a][2];
            memcpy(X + 3 * a, Xg[i][j][k], sizeof(double) * 3);
            linear_field(G, X + 3 * a, u + 3 * a);
            if (i == 1 && j == 1 && k == 1) corner_of_center = a;
        }
        assert_int_equal(asp_hex8(X, u, &m, NULL, NULL, fe, NULL, NULL, sig), 0);
        for (int q = 0; q < 48; q++) serr = fmax(serr, fabs(sig[q] - sig_ex[q % 6]) / smax);
        for (int d = 0; d < 3; d++) fint[d] += fe[3 * corner_of_center + d];
    }
    double fnorm = fabs(fint[0]) + fabs(fint[1]) + fabs(fint[2]);
    double fscale = smax * 0.25; /* stress × face area of one element */
    printf("hex8 patch: stress error %.2e, interior node force %.2e (rel.)\n",
           serr, fnorm / fscale);
    assert_true(serr < 1e-12);
    assert_true(fnorm / fscale < 1e-12);
}

/* Axisymmetric 2x2 patch with u_r = a r, u_z = c r + d z: constant strain
 * including the hoop strain u_r/r = a, so every Gauss point must carry the
 * exact stress.  With c = 0 the constant stress (σ_rr = σ_θθ, σ_rz = 0) is
 * also in equilibrium, so the interior node must see zero net force; with
 * c ≠ 0 it is not (the z equation has the term σ_rz/r), so only the stress
 * is checked then. */
static void quad4_patch_case(const double a, const double c, const double d,
                             double *serr, double *frel)
{
    asp_j2 m = material(0.3);
    double Xg[3][3][2];
    unsigned s = 17u;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            Xg[i][j][0] = 0.3 + 0.2 * i + (i == 1 ? 0.05 * prand(&s) : 0.0);
            Xg[i][j][1] = 0.2 * j + (j == 1 ? 0.05 * prand(&s) : 0.0);
        }
    double eps_ex[6] = {a, d, a, c, 0, 0}, sig_ex[6], smax = 0.0;
    asp_qp_state z = {{0}, 0, {0}}, tmp;
    asp_j2_update(&m, eps_ex, &z, &tmp, sig_ex, NULL);
    for (int k = 0; k < 6; k++) smax = fmax(smax, fabs(sig_ex[k]));
    static const int QC[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    double fint[2] = {0};
    *serr = 0.0;
    for (int e = 0; e < 4; e++) {
        double X[8], u[8], fe[8], sig[24];
        int center = -1;
        for (int n = 0; n < 4; n++) {
            int i = (e & 1) + QC[n][0], j = (e >> 1) + QC[n][1];
            X[2 * n] = Xg[i][j][0];
            X[2 * n + 1] = Xg[i][j][1];
            u[2 * n] = a * X[2 * n];
            u[2 * n + 1] = c * X[2 * n] + d * X[2 * n + 1] + 1e-3;
            if (i == 1 && j == 1) center = n;
        }
        assert_int_equal(asp_quad4_axi(X, u, &m, NULL, NULL, fe, NULL, NULL, sig), 0);
        for (int q = 0; q < 24; q++)
            *serr = fmax(*serr, fabs(sig[q] - sig_ex[q % 6]) / smax);
        fint[0] += fe[2 * center];
        fint[1] += fe[2 * center + 1];
    }
    double fscale = smax * 2 * M_PI * 0.5 * 0.2;
    *frel = (fabs(fint[0]) + fabs(fint[1])) / fscale;
}

static void test_quad4_patch(void **state)
{
    (void)state;
    double serr1, frel1, serr0, frel0;
    quad4_patch_case(1e-4, 3e-5, -2e-4, &serr1, &frel1);
    quad4_patch_case(1e-4, 0.0, -2e-4, &serr0, &frel0);
    printf("quad4 axi patch: stress error %.2e (with shear) %.2e (without); "
           "interior node force %.2e (rel.)\n", serr1, serr0, frel0);
    assert_true(serr1 < 1e-12);
    assert_true(serr0 < 1e-12);
    assert_true(frel0 < 1e-12);
}

static void test_rigid_modes(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    double X[24], u[24], fe[24], worst = 0.0;
    hex_geom(0.1, 0.15, 23u, X);
    /* 3 translations + 3 infinitesimal rotations u = ω × x */
    for (int mode = 0; mode < 6; mode++) {
        for (int a = 0; a < 8; a++) {
            const double *x = X + 3 * a;
            double w[3] = {0, 0, 0}, *ua = u + 3 * a;
            if (mode < 3) {
                ua[0] = ua[1] = ua[2] = 0.0;
                ua[mode] = 1e-3;
                continue;
            }
            w[mode - 3] = 1e-3;
            ua[0] = w[1] * x[2] - w[2] * x[1];
            ua[1] = w[2] * x[0] - w[0] * x[2];
            ua[2] = w[0] * x[1] - w[1] * x[0];
        }
        assert_int_equal(asp_hex8(X, u, &m, NULL, NULL, fe, NULL, NULL, NULL), 0);
        for (int j = 0; j < 24; j++) worst = fmax(worst, fabs(fe[j]));
    }
    /* scale: force of a 1e-3 strain on a face */
    double fscale = m.E * 1e-3 * 0.01;
    printf("hex8 rigid modes: max |fe| = %.2e of %.2e\n", worst, fscale);
    assert_true(worst < 1e-10 * fscale);

    /* axisymmetric: a uniform u_z is rigid, a uniform u_r is not (hoop) */
    double Xq[8], uq[8], fq[8], wq = 0.0, wr = 0.0;
    quad_geom(0.4, 0.1, 0.1, 29u, Xq);
    for (int a = 0; a < 4; a++) { uq[2 * a] = 0.0; uq[2 * a + 1] = 1e-3; }
    assert_int_equal(asp_quad4_axi(Xq, uq, &m, NULL, NULL, fq, NULL, NULL, NULL), 0);
    for (int j = 0; j < 8; j++) wq = fmax(wq, fabs(fq[j]));
    for (int a = 0; a < 4; a++) { uq[2 * a] = 1e-3; uq[2 * a + 1] = 0.0; }
    asp_quad4_axi(Xq, uq, &m, NULL, NULL, fq, NULL, NULL, NULL);
    for (int j = 0; j < 8; j++) wr = fmax(wr, fabs(fq[j]));
    printf("quad4 axi: uniform u_z max |fe| = %.2e; uniform u_r %.2e (not rigid)\n", wq, wr);
    assert_true(wq < 1e-10 * wr);
    assert_true(wr > 1e-3 * fscale);
}

/* u_r = c r, u_z = 0: ε_rr = ε_θθ = c, σ_rr = σ_θθ = 2(λ+μ)c, σ_zz = 2λc.
 * And u_z = d z alone: the axial force through the top edge equals
 * σ_zz π (r2² - r1²), which checks the 2πr weighting of fe. */
static void test_axi_hoop_and_ring_force(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    const double c = 2e-4, d = -3e-4, r1 = 0.3, r2 = 0.5;
    double X[8] = {r1, 0.0, r2, 0.0, r2, 0.2, r1, 0.2}, u[8], fe[8], sig[24];
    for (int a = 0; a < 4; a++) { u[2 * a] = c * X[2 * a]; u[2 * a + 1] = 0.0; }
    assert_int_equal(asp_quad4_axi(X, u, &m, NULL, NULL, fe, NULL, NULL, sig), 0);
    double err = 0.0, s_rr = 2 * (m.lambda + m.mu) * c, s_zz = 2 * m.lambda * c;
    for (int q = 0; q < 4; q++) {
        err = fmax(err, fabs(sig[6 * q + 0] - s_rr) / s_rr);
        err = fmax(err, fabs(sig[6 * q + 2] - s_rr) / s_rr);
        err = fmax(err, fabs(sig[6 * q + 1] - s_zz) / s_rr);
        err = fmax(err, fabs(sig[6 * q + 3]) / s_rr);
    }
    for (int a = 0; a < 4; a++) { u[2 * a] = 0.0; u[2 * a + 1] = d * X[2 * a + 1]; }
    asp_quad4_axi(X, u, &m, NULL, NULL, fe, NULL, NULL, sig);
    double Fz = fe[5] + fe[7], Fex = sig[1] * M_PI * (r2 * r2 - r1 * r1);
    double ferr = fabs(Fz - Fex) / fabs(Fex);
    printf("axi radial expansion stress error %.2e; ring force %.6g N vs %.6g N (rel %.1e)\n",
           err, Fz, Fex, ferr);
    assert_true(err < 1e-12);
    assert_true(fabs(sig[1] - (m.lambda + 2 * m.mu) * d) < 1e-12 * fabs(sig[1]));
    assert_true(ferr < 1e-12);
}

/* Number of eigenvalues of the (symmetric) Ke above `thr`. */
static int count_stiff(const double *Ke, int nd, double *eig_out)
{
    gsl_matrix *A = gsl_matrix_alloc((size_t)nd, (size_t)nd);
    gsl_vector *ev = gsl_vector_alloc((size_t)nd);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc((size_t)nd);
    for (int i = 0; i < nd; i++)
        for (int j = 0; j < nd; j++)
            gsl_matrix_set(A, (size_t)i, (size_t)j, 0.5 * (Ke[i * nd + j] + Ke[j * nd + i]));
    gsl_eigen_symm(A, ev, w);
    double emax = 0.0;
    for (int i = 0; i < nd; i++) emax = fmax(emax, gsl_vector_get(ev, (size_t)i));
    /* The fully plastic tangent is κ 1⊗1 + 2μθ(I_dev - n⊗n) with θ ~ 1e-3
     * here: eigenvalues split into ~κ (volumetric) and ≤ ~μθ (deviatoric).
     * Count those within a factor 30 of the largest. */
    int n = 0;
    for (int i = 0; i < nd; i++) {
        double e = gsl_vector_get(ev, (size_t)i);
        if (e > emax / 30.0) n++;
    }
    gsl_sort_vector(ev);
    for (int i = 0; i < nd; i++) eig_out[i] = gsl_vector_get(ev, (size_t)i);
    gsl_eigen_symm_free(w);
    gsl_vector_free(ev);
    gsl_matrix_free(A);
    return n;
}

/* Volumetric locking: in a fully plastic, isochoric state the B-bar element
 * carries exactly ONE stiff (volumetric) mode — its mean dilatation.  A
 * plain fully integrated hex8 has 6 here (quad4 axi: 3; measured by
 * zeroing the B-bar correction), which then dominate
 * the response and lock the element (Nagtegaal et al. 1974). */
static void test_no_locking(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    double X[24], u[24], fe[24], Ke[576], eig[24];
    hex_geom(0.1, 0.1, 31u, X);
    for (int a = 0; a < 8; a++) { /* deviatoric strain 1000× yield */
        u[3 * a] = 0.5 * (X[3 * a] - 1.0);
        u[3 * a + 1] = -0.5 * (X[3 * a + 1] - 1.0);
        u[3 * a + 2] = 0.0;
    }
    assert_int_equal(asp_hex8(X, u, &m, NULL, NULL, fe, Ke, NULL, NULL), 8);
    int nh = count_stiff(Ke, 24, eig);
    printf("hex8 plastic: %d stiff mode(s) (largest %.3g, next %.3g)\n", nh,
           eig[23], eig[22]);
    assert_int_equal(nh, 1);

    double Xq[8], uq[8], fq[8], Kq[64], eq[8];
    quad_geom(0.3, 0.1, 0.1, 37u, Xq);
    for (int a = 0; a < 4; a++) {
        uq[2 * a] = 0.5 * Xq[2 * a];
        uq[2 * a + 1] = -1.0 * (Xq[2 * a + 1] - 2.0);
    }
    assert_int_equal(asp_quad4_axi(Xq, uq, &m, NULL, NULL, fq, Kq, NULL, NULL), 4);
    int nq = count_stiff(Kq, 8, eq);
    printf("quad4 axi plastic: %d stiff mode(s) (largest %.3g, next %.3g)\n", nq,
           eq[7], eq[6]);
    assert_int_equal(nq, 1);
}

/* Zero-energy modes of the elastic Ke: exactly the rigid-body ones (hex8:
 * 6; axisymmetric: only the axial translation), all other eigenvalues
 * clearly positive — full integration, so no hourglass modes. */
static void test_spectrum(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    double X[24], u[24] = {0}, fe[24], Ke[576], eig[24];
    hex_geom(0.1, 0.15, 41u, X);
    assert_int_equal(asp_hex8(X, u, &m, NULL, NULL, fe, Ke, NULL, NULL), 0);
    count_stiff(Ke, 24, eig);
    double emax = eig[23];
    int nzero = 0;
    for (int i = 0; i < 24; i++) nzero += fabs(eig[i]) < 1e-10 * emax;
    printf("hex8 elastic: %d zero eigenvalues, smallest nonzero %.3g of max %.3g\n",
           nzero, eig[6], emax);
    assert_int_equal(nzero, 6);
    assert_true(eig[6] > 1e-6 * emax); /* a spurious mode would be ~1e-12 */

    double Xq[8], uq[8] = {0}, fq[8], Kq[64], eq[8];
    quad_geom(0.3, 0.1, 0.1, 43u, Xq);
    assert_int_equal(asp_quad4_axi(Xq, uq, &m, NULL, NULL, fq, Kq, NULL, NULL), 0);
    count_stiff(Kq, 8, eq);
    int nzq = 0;
    for (int i = 0; i < 8; i++) nzq += fabs(eq[i]) < 1e-10 * eq[7];
    printf("quad4 axi elastic: %d zero eigenvalue(s), smallest nonzero %.3g of max %.3g\n",
           nzq, eq[1], eq[7]);
    assert_int_equal(nzq, 1);
    assert_true(eq[1] > 1e-6 * eq[7]);
}

static void test_bad_jacobian(void **state)
{
    (void)state;
    asp_j2 m = material(0.3);
    double X[24], u[24] = {0}, fe[24];
    hex_geom(0.1, 0.0, 1u, X);
    /* swap two top nodes: inverted element */
    for (int i = 0; i < 3; i++) {
        double t = X[3 * 4 + i];
        X[3 * 4 + i] = X[3 * 6 + i];
        X[3 * 6 + i] = t;
    }
    assert_int_equal(asp_hex8(X, u, &m, NULL, NULL, fe, NULL, NULL, NULL), -1);
    double Xq[8] = {0.1, 0, 0.1, 0.1, 0.2, 0.1, 0.2, 0}, uq[8] = {0}, fq[8]; /* clockwise */
    assert_int_equal(asp_quad4_axi(Xq, uq, &m, NULL, NULL, fq, NULL, NULL, NULL), -1);
    printf("inverted hex8 and clockwise quad4 rejected\n");
}

static void test_qp_coords(void **state)
{
    (void)state;
    double X[24], xq[24], Xq[8], xq2[8];
    hex_geom(0.1, 0.0, 1u, X); /* axis-aligned cube [1, 1.1]^3 */
    asp_hex8_qp_coords(X, xq);
    double g = 0.05 / sqrt(3.0);
    for (int q = 0; q < 8; q++)
        for (int i = 0; i < 3; i++)
            assert_true(fabs(xq[3 * q + i] - (1.05 + (HEXC[q][i] ? g : -g))) < 1e-14);
    quad_geom(0.0, 1.0, 0.0, 1u, Xq);
    asp_quad4_qp_coords(Xq, xq2);
    assert_true(fabs(xq2[0] - (0.5 - 0.5 / sqrt(3.0))) < 1e-14);
    assert_true(fabs(xq2[5] - (2.5 + 0.5 / sqrt(3.0))) < 1e-14);
    printf("Gauss point q sits next to node q\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hex8_tangent_fd),
        cmocka_unit_test(test_quad4_tangent_fd),
        cmocka_unit_test(test_hex8_patch),
        cmocka_unit_test(test_quad4_patch),
        cmocka_unit_test(test_rigid_modes),
        cmocka_unit_test(test_axi_hoop_and_ring_force),
        cmocka_unit_test(test_no_locking),
        cmocka_unit_test(test_spectrum),
        cmocka_unit_test(test_bad_jacobian),
        cmocka_unit_test(test_qp_coords),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
