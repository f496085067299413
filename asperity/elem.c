/* B-bar (mean-dilatation) elements: axisymmetric 4-node quadrilateral and
 * 8-node hexahedron with full 2x2 / 2x2x2 Gauss integration.
 *
 * Why B-bar: under fully plastic (isochoric) flow a fully integrated
 * bilinear/trilinear element must keep the volume constant at every Gauss
 * point, which over-constrains it (volumetric locking).  Replacing the
 * volumetric part of B at each Gauss point by its element volume average
 * leaves one volume constraint per element.  Hughes, "The Finite Element
 * Method" (1987/2000), §4.5.2 (B-bar, eqs. 4.5.22–4.5.27); Nagtegaal, Parks
 * & Rice, Comput. Meth. Appl. Mech. Eng. 4 (1974) 153 (the locking).
 *
 * Because B-bar depends only on the geometry (small strain), the strain is
 * ε = B̄ u, the internal force is fe = Σ_q B̄_qᵀ σ_q w_q and its exact
 * derivative is Ke = Σ_q B̄_qᵀ D_q B̄_q w_q with D the consistent tangent.
 *
 * Axisymmetric: the volumetric strain is ∂u_r/∂r + u_r/r + ∂u_z/∂z, the
 * average is weighted by 2πr, and fe, Ke include the 2πr factor so that
 * forces are those of the full 360° ring (N).
 *
 * Node / Gauss-point numbering: nodes in the usual counter-clockwise order
 * (hex8: bottom face ζ = -1 counter-clockwise seen from +ζ, then the top
 * face); Gauss point q sits at (natural coordinates of node q)/√3, i.e.
 * next to node q.
 *
 * `old` may be NULL (virgin material: zero plastic strain); `upd`, `fe`,
 * `Ke` and `sig` may be NULL when not wanted.  Pure: no allocation (fixed
 * stack arrays only), no globals; thread-safe.
 */
#include <math.h>
#include <string.h>

#include "fe.h"

enum { NV = 6, MAXQP = 8, MAXDOF = 24 };

static const double QUAD_XI[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
static const double HEX_XI[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1},
                                    {-1, 1, -1},  {-1, -1, 1}, {1, -1, 1},
                                    {1, 1, 1},    {-1, 1, 1}};

/* 2-point Gauss abscissa 1/√3 (weights 1). */
static double gauss_pt(void) { return 1.0 / sqrt(3.0); }

/* DB = w M B for a 6x6 M and one Gauss point's B [6][ndof]. */
static void times_B(const double *M, const double *Bq, int ndof, double wq, double *DB)
{
    for (int a = 0; a < NV; a++)
        for (int j = 0; j < ndof; j++) {
            double v = 0.0;
            for (int b = 0; b < NV; b++)
                v += M[a * NV + b] * Bq[b * ndof + j];
            DB[a * ndof + j] = v * wq;
        }
}

/* K += Bᵀ DB on the upper triangle (j >= i), or strictly below it. */
static void add_BtX(const double *Bq, const double *DB, int ndof, double *K, int lower)
{
    for (int i = 0; i < ndof; i++)
        for (int a = 0; a < NV; a++) {
            double bai = Bq[a * ndof + i];
            if (bai == 0.0) continue;
            int j0 = lower ? 0 : i, j1 = lower ? i : ndof;
            for (int j = j0; j < j1; j++)
                K[i * ndof + j] += bai * DB[a * ndof + j];
        }
}

/* Material update at every Gauss point and accumulation of fe and Ke.
 * B: [nqp][6][ndof], w: [nqp] (quadrature weight × det J [× 2πr]). */
static int integrate(int nqp, int ndof, const double *B, const double *w,
                     const double *u, const asp_j2 *m,
                     const asp_qp_state *old, asp_qp_state *upd,
                     double *fe, double *Ke, double *Kp, double *sig)
{
    static const asp_qp_state virgin = {{0}, 0.0, {0}};
    double D[NV * NV], Dp[NV * NV], DB[NV * MAXDOF];
    int nplastic = 0;
    if (fe) memset(fe, 0, sizeof(double) * (size_t)ndof);
    if (Ke) memset(Ke, 0, sizeof(double) * (size_t)(ndof * ndof));
    if (!Ke) Kp = NULL;
    if (Kp) memset(Kp, 0, sizeof(double) * (size_t)(ndof * ndof));
    for (int q = 0; q < nqp; q++) {
        const double *Bq = B + (size_t)q * NV * ndof;
        double eps[NV], s[NV];
        for (int a = 0; a < NV; a++) {
            eps[a] = 0.0;
            for (int j = 0; j < ndof; j++)
                eps[a] += Bq[a * ndof + j] * u[j];
        }
        asp_qp_state tmp;
        asp_qp_state *uq = upd ? &upd[q] : &tmp;
        nplastic += asp_j2_update_pc(m, eps, old ? &old[q] : &virgin, uq, s,
                                     Ke ? D : NULL, Kp ? Dp : NULL);
        /* the midpoint return's tangent is not symmetric: its skew part
         * W = (D - Dᵀ)/2 is kept apart and D symmetrized */
        double W[NV * NV] = {0};
        int skew = 0;
        if (Ke)
            for (int a = 0; a < NV; a++)
                for (int b = 0; b < a; b++) {
                    double sy = 0.5 * (D[a * NV + b] + D[b * NV + a]);
                    double sk = 0.5 * (D[a * NV + b] - D[b * NV + a]);
                    D[a * NV + b] = D[b * NV + a] = sy;
                    W[a * NV + b] = sk, W[b * NV + a] = -sk;
                    skew |= sk != 0.0;
                }
        if (sig) memcpy(sig + q * NV, s, sizeof s);
        if (fe)
            for (int j = 0; j < ndof; j++) {
                double f = 0.0;
                for (int a = 0; a < NV; a++)
                    f += Bq[a * ndof + j] * s[a];
                fe[j] += f * w[q];
            }
        if (!Ke) continue;
        /* upper triangle of the symmetric part; Kp collects Bᵀ (Dp - D) B
         * where they differ (midpoint points that turned), and the
         * symmetric part is added to it at the end */
        times_B(D, Bq, ndof, w[q], DB);
        add_BtX(Bq, DB, ndof, Ke, 0);
        if (Kp && memcmp(D, Dp, sizeof D)) {
            for (int k = 0; k < NV * NV; k++) Dp[k] -= D[k];
            times_B(Dp, Bq, ndof, w[q], DB);
            add_BtX(Bq, DB, ndof, Kp, 0);
        }
        if (!skew) continue;
        /* skew part Bᵀ W B, kept below the diagonal until the end */
        times_B(W, Bq, ndof, w[q], DB);
        add_BtX(Bq, DB, ndof, Ke, 1);
    }
    if (Kp)
        for (int i = 0; i < ndof; i++)
            for (int j = i; j < ndof; j++)
                Kp[j * ndof + i] = Kp[i * ndof + j] += Ke[i * ndof + j];
    /* Ke = symmetric (upper) + skew (lower holds its (i > j) entries) */
    if (Ke)
        for (int i = 0; i < ndof; i++)
            for (int j = 0; j < i; j++) {
                double sy = Ke[j * ndof + i], sk = Ke[i * ndof + j];
                Ke[i * ndof + j] = sy + sk;
                Ke[j * ndof + i] = sy - sk;
            }
    return nplastic;
}

/* ---- axisymmetric quad4 ------------------------------------------------ */

/* Shape functions and natural derivatives at (xi, eta). */
static void quad_shape(double xi, double eta, double N[4], double dN[4][2])
{
    for (int a = 0; a < 4; a++) {
        double xa = QUAD_XI[a][0], ea = QUAD_XI[a][1];
        N[a] = 0.25 * (1 + xi * xa) * (1 + eta * ea);
        dN[a][0] = 0.25 * xa * (1 + eta * ea);
        dN[a][1] = 0.25 * ea * (1 + xi * xa);
    }
}

void asp_quad4_qp_coords(const double *X, double *xq)
{
    double g = gauss_pt(), N[4], dN[4][2];
    for (int q = 0; q < ASP_QUAD4_NQP; q++) {
        quad_shape(g * QUAD_XI[q][0], g * QUAD_XI[q][1], N, dN);
        for (int i = 0; i < 2; i++) {
            xq[2 * q + i] = 0.0;
            for (int a = 0; a < 4; a++)
                xq[2 * q + i] += N[a] * X[2 * a + i];
        }
    }
}

int asp_quad4_axi(const double *X, const double *u, const asp_j2 *m,
                  const asp_qp_state *old, asp_qp_state *upd,
                  double *fe, double *Ke, double *Kp, double *sig)
{
    enum { NQ = ASP_QUAD4_NQP, ND = 8 };
    double g = gauss_pt(), B[NQ][NV][ND], w[NQ];
    double bq[NQ][ND];      /* volumetric row ∂N/∂r + N/r, ∂N/∂z per qp */
    double bm[ND] = {0}, V = 0.0;
    memset(B, 0, sizeof B);
    for (int q = 0; q < NQ; q++) {
        double N[4], dN[4][2], J[2][2] = {{0}}, r = 0.0;
        quad_shape(g * QUAD_XI[q][0], g * QUAD_XI[q][1], N, dN);
        for (int a = 0; a < 4; a++) {
            r += N[a] * X[2 * a];
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++)
                    J[i][j] += X[2 * a + i] * dN[a][j]; /* ∂x_i/∂ξ_j */
        }
        double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (!(det > 0.0) || !(r > 0.0)) return -1;
        w[q] = det * 2.0 * M_PI * r;
        for (int a = 0; a < 4; a++) {
            /* ∂N/∂x = J⁻ᵀ ∂N/∂ξ */
            double dr = (J[1][1] * dN[a][0] - J[1][0] * dN[a][1]) / det;
            double dz = (-J[0][1] * dN[a][0] + J[0][0] * dN[a][1]) / det;
            B[q][0][2 * a] = dr;           /* ε_rr */
            B[q][1][2 * a + 1] = dz;       /* ε_zz */
            B[q][2][2 * a] = N[a] / r;     /* ε_θθ = u_r / r */
            B[q][3][2 * a] = dz;           /* γ_rz */
            B[q][3][2 * a + 1] = dr;
            bq[q][2 * a] = dr + N[a] / r;
            bq[q][2 * a + 1] = dz;
        }
        V += w[q];
        for (int j = 0; j < ND; j++) bm[j] += bq[q][j] * w[q];
    }
    for (int j = 0; j < ND; j++) bm[j] /= V;
    /* B̄: replace the qp volumetric part (1/3 b_q on each normal row) by
     * the 2πr-weighted element mean (Hughes eq. 4.5.25, axisymmetric). */
    for (int q = 0; q < NQ; q++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < ND; j++)
                B[q][k][j] += (bm[j] - bq[q][j]) / 3.0;
    return integrate(NQ, ND, &B[0][0][0], w, u, m, old, upd, fe, Ke, Kp, sig);
}

/* ---- hex8 ---------------------------------------------------------------- */

static void hex_shape(const double xi[3], double N[8], double dN[8][3])
{
    for (int a = 0; a < 8; a++) {
        double f[3], d[3];
        for (int i = 0; i < 3; i++) {
            f[i] = 0.5 * (1 + xi[i] * HEX_XI[a][i]);
            d[i] = 0.5 * HEX_XI[a][i];
        }
        N[a] = f[0] * f[1] * f[2];
        dN[a][0] = d[0] * f[1] * f[2];
        dN[a][1] = f[0] * d[1] * f[2];
        dN[a][2] = f[0] * f[1] * d[2];
    }
}

void asp_hex8_qp_coords(const double *X, double *xq)
{
    double g = gauss_pt(), N[8], dN[8][3];
    for (int q = 0; q < ASP_HEX8_NQP; q++) {
        double xi[3] = {g * HEX_XI[q][0], g * HEX_XI[q][1], g * HEX_XI[q][2]};
        hex_shape(xi, N, dN);
        for (int i = 0; i < 3; i++) {
            xq[3 * q + i] = 0.0;
            for (int a = 0; a < 8; a++)
                xq[3 * q + i] += N[a] * X[3 * a + i];
        }
    }
}

/* Physical derivatives dNdx[8][3] at one point; returns det J. */
static double hex_grad(const double *X, const double xi[3], double dNdx[8][3])
{
    double N[8], dN[8][3], J[3][3] = {{0}}, C[3][3];
    hex_shape(xi, N, dN);
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                J[i][j] += X[3 * a + i] * dN[a][j]; /* ∂x_i/∂ξ_j */
    /* cofactors: J⁻¹ = Cᵀ / det */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            C[i][j] = J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1];
        }
    double det = J[0][0] * C[0][0] + J[0][1] * C[0][1] + J[0][2] * C[0][2];
    if (!(det > 0.0)) return det;
    /* ∂N/∂x_k = Σ_j ∂N/∂ξ_j (J⁻¹)_jk = Σ_j ∂N/∂ξ_j C_kj / det */
    for (int a = 0; a < 8; a++)
        for (int k = 0; k < 3; k++)
            dNdx[a][k] = (dN[a][0] * C[k][0] + dN[a][1] * C[k][1] +
                          dN[a][2] * C[k][2]) / det;
    return det;
}

int asp_hex8(const double *X, const double *u, const asp_j2 *m,
             const asp_qp_state *old, asp_qp_state *upd,
             double *fe, double *Ke, double *Kp, double *sig)
{
    enum { NQ = ASP_HEX8_NQP, ND = 24 };
    /* Voigt shear rows: (xy, yz, zx) pair the components (0,1), (1,2), (2,0) */
    static const int SH[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    double g = gauss_pt(), B[NQ][NV][ND], w[NQ], d[NQ][8][3];
    double bm[8][3] = {{0}}, V = 0.0;
    for (int q = 0; q < NQ; q++) {
        double xi[3] = {g * HEX_XI[q][0], g * HEX_XI[q][1], g * HEX_XI[q][2]};
        double det = hex_grad(X, xi, d[q]);
        if (!(det > 0.0)) return -1;
        w[q] = det;
        V += det;
        for (int a = 0; a < 8; a++)
            for (int i = 0; i < 3; i++) bm[a][i] += d[q][a][i] * det;
    }
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) bm[a][i] /= V;
    memset(B, 0, sizeof B);
    for (int q = 0; q < NQ; q++)
        for (int a = 0; a < 8; a++) {
            for (int i = 0; i < 3; i++) { /* Hughes eq. 4.5.25 */
                double v = (bm[a][i] - d[q][a][i]) / 3.0;
                for (int k = 0; k < 3; k++) B[q][k][3 * a + i] = (k == i ? d[q][a][i] : 0.0) + v;
            }
            for (int s = 0; s < 3; s++) {
                int i = SH[s][0], j = SH[s][1];
                B[q][3 + s][3 * a + i] = d[q][a][j];
                B[q][3 + s][3 * a + j] = d[q][a][i];
            }
        }
    return integrate(NQ, ND, &B[0][0][0], w, u, m, old, upd, fe, Ke, Kp, sig);
}
