/* Tributary areas of the outer-surface nodes: the weights that turn a
 * contact traction t (MPa) into consistent nodal forces f_i = A_i t_i (N)
 * for the tangential stick law (friction.c) — the nodal ("lumped")
 * quadrature of ∫ N_i t dA, second-order accurate for smooth t.
 *
 * The integrals run over the chordal (bilinear) faces the elements
 * actually have, so Σ A_i is the area of the discrete surface:
 *   dim 2: 2π ∫ r N_i ds along each straight edge — exact, L (2 r_a + r_b)/6;
 *   dim 3: ∫ N_i |x_ξ × x_η| dξ dη on each bilinear quad — 3x3 Gauss (the
 *          integrand is smooth; 3x3 is exact to roundoff for planar faces).
 * The _disc variant integrates only over the contact disc r < rc (r = the
 * distance from the axis): the consistent nodal weights of a traction that
 * is uniform over the contact and zero outside (the shear-limited law at
 * full slip), so Σ f_i = τc × the cap area exactly instead of jumping by
 * a ring of nodes at a time (docs/design.md §4.1).
 */
#include <math.h>
#include <string.h>

#include "stc_check.h"
#include "tangential.h"

/* Sub-cells per direction on a face cut by the contact circle: the cut
 * error is ~ (h/ASP_DISC_NSUB)² per cut face (measured in test_surfarea). */
enum { ASP_DISC_NSUB = 32 };

/* Axisymmetric: every quad edge with both nodes on the sphere. */
/* 2π ∫ r N_a ds and 2π ∫ r N_b ds over the part of the edge a -> b with
 * r < rc (r is linear along the chord: clip the parameter range). */
static void edge_disc(const double *xa, const double *xb, double rc, double *wa, double *wb)
{
    double L = hypot(xb[0] - xa[0], xb[1] - xa[1]), ra = xa[0], rb = xb[0];
    double s0 = 0.0, s1 = 1.0; /* parameter range with r(s) = ra + (rb - ra) s < rc */
    if (ra >= rc && rb >= rc) s1 = s0;
    else if (ra >= rc) s0 = (rc - ra) / (rb - ra);
    else if (rb >= rc) s1 = (rc - ra) / (rb - ra);
    /* ∫ (ra + Δ s)(1 - s) ds and ∫ (ra + Δ s) s ds on [s0, s1] */
    double d = rb - ra;
#define P1(s) ((s) - 0.5 * (s) * (s))
#define P2(s) (0.5 * (s) * (s) - (s) * (s) * (s) / 3.0)
#define P3(s) (0.5 * (s) * (s))
#define P4(s) ((s) * (s) * (s) / 3.0)
    *wa = 2.0 * M_PI * L * (ra * (P1(s1) - P1(s0)) + d * (P2(s1) - P2(s0)));
    *wb = 2.0 * M_PI * L * (ra * (P3(s1) - P3(s0)) + d * (P4(s1) - P4(s0)));
#undef P1
#undef P2
#undef P3
#undef P4
}

static int areas_axisym(const asp_mesh *m, double R, double rc, double *area)
{
    int nedge = 0;
    for (int e = 0; e < m->nelem; e++) {
        const int *c = m->conn + 4 * (size_t)e;
        for (int k = 0; k < 4; k++) {
            int a = c[k], b = c[(k + 1) % 4];
            if (!asp_mesh_on_sphere(m, a, R) || !asp_mesh_on_sphere(m, b, R)) continue;
            const double *xa = m->x + 2 * (size_t)a, *xb = m->x + 2 * (size_t)b;
            double wa, wb;
            if (isinf(rc)) { /* 2π ∫ r N ds with r linear along the edge */
                double L = hypot(xb[0] - xa[0], xb[1] - xa[1]);
                wa = 2.0 * M_PI * L * (2.0 * xa[0] + xb[0]) / 6.0;
                wb = 2.0 * M_PI * L * (xa[0] + 2.0 * xb[0]) / 6.0;
            } else {
                edge_disc(xa, xb, rc, &wa, &wb);
            }
            area[a] += wa, area[b] += wb;
            nedge++;
        }
    }
    return nedge;
}

/* Contact footprint in the plane: two half-ellipses with the semi-axes ap
 * (x >= 0), am (x < 0) along x and ay along y (a disc: all three equal).
 * Its gauge ρ (< 1 inside) is convex: the union of the halves is convex
 * (same width ay and vertical tangents where they meet). */
typedef struct foot { double ap, am, ay; } foot;

static double gauge(const foot *f, double x, double y)
{
    return hypot(x / (x >= 0.0 ? f->ap : f->am), y / f->ay);
}

/* ∫ N_a |x_ξ × x_η| dξ dη over the part of the bilinear face X [4][3]
 * inside the footprint, on nsub x nsub sub-cells of 3x3 Gauss points each
 * (nsub = 1 for an uncut face).  w: [4], written. */
static void quad_face(const double *X, const foot *fp, int nsub, double *w)
{
    static const double G[3] = {-0.774596669241483377, 0.0, 0.774596669241483377};
    static const double W[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    static const double XI[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    double hs = 2.0 / nsub;
    w[0] = w[1] = w[2] = w[3] = 0.0;
    for (int cu = 0; cu < nsub; cu++)
        for (int cv = 0; cv < nsub; cv++)
            for (int p = 0; p < 3; p++)
                for (int q = 0; q < 3; q++) {
                    double xi = -1.0 + hs * (cu + 0.5 * (1.0 + G[p]));
                    double eta = -1.0 + hs * (cv + 0.5 * (1.0 + G[q]));
                    double N[4], x[3] = {0, 0, 0}, t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
                    for (int a = 0; a < 4; a++) {
                        N[a] = 0.25 * (1 + XI[a][0] * xi) * (1 + XI[a][1] * eta);
                        double dxi = 0.25 * XI[a][0] * (1 + XI[a][1] * eta);
                        double deta = 0.25 * XI[a][1] * (1 + XI[a][0] * xi);
                        for (int i = 0; i < 3; i++) {
                            x[i] += N[a] * X[3 * a + i];
                            t1[i] += dxi * X[3 * a + i], t2[i] += deta * X[3 * a + i];
                        }
                    }
                    if (gauge(fp, x[0], x[1]) >= 1.0) continue;
                    double n[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2],
                                   t1[0] * t2[1] - t1[1] * t2[0]};
                    double J = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * W[p] * W[q] *
                               0.25 * hs * hs;
                    for (int a = 0; a < 4; a++) w[a] += N[a] * J;
                }
}

/* Is the face cut by the footprint's edge?  The gauge is convex, so its
 * maximum over the face is at a corner; the minimum is bounded below by the
 * smallest corner value minus the face diameter over the smallest axis. */
static int face_cut(const double *X, const foot *fp, int *outside)
{
    double rmin = INFINITY, rmax = 0.0, diam = 0.0;
    for (int a = 0; a < 4; a++) {
        double r = gauge(fp, X[3 * a], X[3 * a + 1]);
        rmin = fmin(rmin, r), rmax = fmax(rmax, r);
        for (int b = 0; b < a; b++)
            diam = fmax(diam, hypot(hypot(X[3 * a] - X[3 * b], X[3 * a + 1] - X[3 * b + 1]),
                                    X[3 * a + 2] - X[3 * b + 2]));
    }
    *outside = rmin - diam / fmin(fmin(fp->ap, fp->am), fp->ay) >= 1.0;
    return !(rmax < 1.0) && !*outside;
}

/* 3D: every hex face whose four corners lie on the sphere. */
static int areas_half3d(const asp_mesh *m, double R, const foot *fp, double *area)
{
    int nface = 0;
    for (int e = 0; e < m->nelem; e++) {
        const int *c = m->conn + 8 * (size_t)e;
        for (int f = 0; f < 6; f++) {
            int id[4], all = 1;
            for (int a = 0; a < 4; a++)
                id[a] = c[asp_hex8_faces[f][a]], all &= asp_mesh_on_sphere(m, id[a], R);
            if (!all) continue;
            double X[12], w[4];
            for (int a = 0; a < 4; a++) memcpy(X + 3 * a, m->x + 3 * (size_t)id[a], 3 * sizeof *X);
            int outside, cut = face_cut(X, fp, &outside);
            if (outside) w[0] = w[1] = w[2] = w[3] = 0.0;
            else quad_face(X, fp, cut ? ASP_DISC_NSUB : 1, w);
            for (int a = 0; a < 4; a++) area[id[a]] += w[a];
            nface++;
        }
    }
    return nface;
}

static stc_status node_areas(const asp_mesh *m, double R_outer, const foot *fp, double *area)
{
    double rc = fmin(fmin(fp->ap, fp->am), fp->ay);
    STC_CHECK(R_outer > 0.0 && isfinite(R_outer), STC_EINVAL,
              "R_outer = %g mm: outer radius must be > 0", R_outer);
    STC_CHECK(rc > 0.0, STC_EINVAL, "rc = %g mm: contact radius must be > 0", rc);
    STC_CHECK(m && (m->dim == 2 || m->dim == 3) && m->nen == (m->dim == 2 ? 4 : 8),
              STC_EINVAL, "surface areas: mesh must be quad4 (dim 2) or hex8 (dim 3)");
    memset(area, 0, (size_t)m->nnode * sizeof *area);
    STC_CHECK(m->dim == 3 || (fp->ap == fp->am && fp->ap == fp->ay), STC_EINVAL,
              "surface areas: an elliptic footprint needs the 3D mesh");
    int n = m->dim == 2 ? areas_axisym(m, R_outer, fp->ap, area)
                        : areas_half3d(m, R_outer, fp, area);
    STC_CHECK(n > 0, STC_EINVAL,
              "surface areas: no element face lies on the sphere R_outer = %g mm", R_outer);
    /* a hanging node (refine3d.c) carries no load of its own: its share goes
     * to its masters by its weights, as its forces do */
    for (int k = 0; k < m->nhang; k++) {
        double *ah = area + m->hang[k];
        for (int a = 0; a < 4 && m->hang_m[4 * k + a] >= 0; a++)
            area[m->hang_m[4 * k + a]] += m->hang_w[4 * k + a] * *ah;
        *ah = 0.0;
    }
    return STC_OK;
}

stc_status asp_surface_node_areas(const asp_mesh *m, double R_outer, double *area)
{
    foot all = {INFINITY, INFINITY, INFINITY};
    return node_areas(m, R_outer, &all, area);
}

stc_status asp_surface_node_areas_disc(const asp_mesh *m, double R_outer, double rc,
                                       double *area)
{
    foot d = {rc, rc, rc};
    return node_areas(m, R_outer, &d, area);
}

stc_status asp_surface_node_areas_foot(const asp_mesh *m, double R_outer, double ap, double am,
                                       double ay, double *area)
{
    foot f = {ap, am, ay};
    return node_areas(m, R_outer, &f, area);
}
