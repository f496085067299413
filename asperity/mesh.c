/* Axisymmetric mesh of the coated hemisphere, and mesh quality / cleanup
 * for both the axisymmetric and the 3D half model.
 *
 * Meaning of `level` (asp_mesh_spec), shared with the 3D generator:
 *   n(level) = ASP_MESH_N0 * 2^level elements across the largest contact
 *   radius a_max, i.e. the element size at the contact is h = a_max / n
 *   (level 0: a_max/6, 1: a_max/12, 2: a_max/24, 3: a_max/48).  An n between
 *   levels (asp_mesh_axisym_n, the solver's elements_per_contact) uses the
 *   same formulas with sqrt(2)^level replaced by sqrt(n / 6).  Here the fine
 *   zone is uniform over 1.25 a_max along the surface and 0.8 a_max in depth
 *   (the 3D half model uses a 1.0 a_max core and its own shell growth, see
 *   mesh3d.c)
 *   (the Hertz stress maximum sits at 0.48 a), then sizes grow geometrically
 *   with ratio q(level) = 1 + 0.3 / sqrt(2)^level up to the far-field size
 *   hmax(level) = 0.15 R' / sqrt(2)^level.  The coating always gets at least
 *   4 elements through its thickness (spacing min(h, t/4) starting at the
 *   surface); a coating with t <= 3 a_max keeps size h through its whole
 *   thickness and 0.5 a_max into the substrate (interface stresses).
 *   With a_min < a_max (a load curve whose first yield must be resolved) the
 *   size is a_min/n over 1.25 a_min along the surface and 0.8 a_min in depth,
 *   grows by q to a_max/n and stays there over the a_max zone.
 *   Optional surface layers (asp_options.surface_layers = N): the top row
 *   is split into N + 1 rows halving towards the surface (h/2^N there).
 *
 * Layout (axisymmetric, (r, z), θ measured from the z axis, ρ from the
 * sphere centre): a polar band mesh on circles ρ_k (the outer surface ρ = R'
 * and the coating interface ρ = R are circles of the family, so every
 * element lies in one layer) and rays θ_j.  Going inwards the rays are
 * thinned by conforming 3-to-1 transition cells (4 quads each) wherever the
 * elements would otherwise become much taller than wide, so the fine
 * surface resolution does not propagate inwards as slivers.  The core
 * ρ < ρ_c = 0.4 R' is a quarter disk split into three transfinite patches.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fe.h"
#include "solver_impl.h" /* asp_mesh_axisym_n */
#include "stc_check.h"

enum { ASP_MESH_N0 = 6 };

/* Growing arrays for the generator (private). */
typedef struct mbuild {
    double *x;
    int nnode, capn;
    int *conn, *region;
    int nelem, cape;
} mbuild;

static int mb_node(mbuild *b, double r, double z)
{
    if (b->nnode == b->capn) {
        int cap = b->capn ? 2 * b->capn : 1024;
        double *nx = realloc(b->x, (size_t)cap * 2 * sizeof *nx);
        if (!nx) return -1;
        b->x = nx;
        b->capn = cap;
    }
    b->x[2 * b->nnode] = r;
    b->x[2 * b->nnode + 1] = z;
    return b->nnode++;
}

static int mb_quad(mbuild *b, int n0, int n1, int n2, int n3, int region)
{
    if (b->nelem == b->cape) {
        int cap = b->cape ? 2 * b->cape : 1024;
        int *nc = realloc(b->conn, (size_t)cap * 4 * sizeof *nc);
        if (!nc) return -1;
        b->conn = nc;
        int *nr = realloc(b->region, (size_t)cap * sizeof *nr);
        if (!nr) return -1;
        b->region = nr;
        b->cape = cap;
    }
    int *c = b->conn + 4 * b->nelem;
    c[0] = n0, c[1] = n1, c[2] = n2, c[3] = n3;
    b->region[b->nelem] = region;
    return b->nelem++;
}

/* Interval sizes covering [0, L]: size h0 while the position is below L0,
 * then growing by q up to h1 while below L1, then growing by q up to hmax.
 * prop > 0: between L0 and L1 the size also stays below prop times the
 * position (never shrinking), so a contact edge anywhere in that zone has
 * about 1 / prop elements inside it.
 * Only the part beyond L1 is rescaled so that the sizes sum exactly to L.
 * Returns the count, or -1 on allocation failure.  *out: new array. */
static int graded_sizes(double L, double h0, double L0, double h1, double L1, double q,
                        double hmax, double prop, double **out)
{
    int cap = 64, n = 0, nfix = 0;
    double *s = malloc((size_t)cap * sizeof *s), sum = 0.0, prev = h0;
    if (!s) return -1;
    while (sum < L * (1 - 1e-12)) {
        double c = sum + 0.5 * h0 < L0 ? h0 : sum < L1 ? h1 : hmax;
        double next = fmin(n ? prev * q : h0, c);
        if (prop > 0.0 && sum >= L0 && sum < L1) next = fmin(next, fmax(prev, prop * sum));
        if (sum < L0) next = h0;
        if (n == cap) {
            double *ns = realloc(s, (size_t)(cap *= 2) * sizeof *ns);
            if (!ns) return free(s), -1;
            s = ns;
        }
        s[n++] = next;
        sum += next;
        prev = next;
        if (sum <= L1 * (1 + 1e-12)) nfix = n;
    }
    /* drop the last interval if it overshoots by more than half of it */
    if (n > nfix + 1 && sum - L > 0.5 * s[n - 1]) sum -= s[--n];
    double fixed = 0.0, graded = 0.0;
    for (int i = 0; i < n; i++) (i < nfix ? (fixed += s[i]) : (graded += s[i]));
    if (graded > 0.0 && L - fixed > 0.0) {
        double f = (L - fixed) / graded;
        for (int i = nfix; i < n; i++) s[i] *= f;
    } else {
        for (int i = 0; i < n; i++) s[i] *= L / sum;
    }
    *out = s;
    return n;
}

/* Polar point (ρ, θ) → (r, z); exact zeros on the axis and the base. */
static void polar(double rho, double th, double *r, double *z)
{
    *r = th == 0.0 ? 0.0 : rho * sin(th);
    *z = th == M_PI_2 ? 0.0 : rho * cos(th);
}

/* Depth levels d_0 = 0 < ... < d_K = D with a level exactly at the coating
 * interface t (if 0 < t < D). */
static int depth_levels(const asp_mesh_spec *s, double amin, double h0, double h, double q, double hmax,
                        double D, double **out)
{
    double L0 = 0.8 * amin, L1 = 0.8 * s->a_max, *a = NULL, *b = NULL;
    int na = 0, nb = 0;
    if (s->t > 0.0) {
        /* an interface within reach of the contact stresses (t <= 3 a_max)
         * keeps the contact size h down to 0.5 a_max below it: the
         * substrate's first yield sits just under the interface */
        int near = s->t <= 3.0 * s->a_max;
        double L1c = near ? fmax(L1, s->t) : L1, L1s = near ? fmax(L1 - s->t, 0.5 * s->a_max)
                                                            : L1 - s->t;
        double hc = fmin(h0, s->t / 4.0);
        na = graded_sizes(s->t, hc, L0, fmin(h, fmax(hc, s->t / 4.0)), L1c, q, hmax, 0.0, &a);
        if (na < 0) return -1;
        if (na < 4) { /* at least 4 layers through the coating */
            double *na4 = realloc(a, 4 * sizeof *a);
            if (!na4) return free(a), -1;
            a = na4;
            na = 4;
            for (int i = 0; i < 4; i++) a[i] = s->t / 4.0;
        }
        double last = a[na - 1], t = s->t;
        /* continue from the coating's last size */
        nb = graded_sizes(D - t, fmax(last, fmin(h0, h)), L0 - t, fmax(h, last), L1s, q, hmax,
                          0.0, &b);
    } else {
        nb = graded_sizes(D, h0, L0, h, L1, q, hmax, 0.0, &b);
    }
    if (nb < 0) return free(a), -1;
    double *d = malloc((size_t)(na + nb + 1) * sizeof *d);
    if (!d) return free(a), free(b), -1;
    d[0] = 0.0;
    for (int i = 0; i < na; i++) d[i + 1] = d[i] + a[i];
    if (na) d[na] = s->t;
    for (int i = 0; i < nb; i++) d[na + i + 1] = d[na + i] + b[i];
    d[na + nb] = D;
    free(a);
    free(b);
    *out = d;
    return na + nb;
}

/* Transfinite (Coons) patch: sides as node-id arrays, bottom/top [nu+1]
 * left to right, left/right [nv+1] bottom to top.  Creates interior nodes and
 * nu*nv quads. */
static int tfi_patch(mbuild *b, const int *bot, const int *top, const int *lft,
                     const int *rgt, int nu, int nv, int region)
{
    int *g = malloc((size_t)(nu + 1) * (nv + 1) * sizeof *g);
    if (!g) return -1;
#define G(i, j) g[(j) * (nu + 1) + (i)]
    for (int i = 0; i <= nu; i++) G(i, 0) = bot[i], G(i, nv) = top[i];
    for (int j = 0; j <= nv; j++) G(0, j) = lft[j], G(nu, j) = rgt[j];
    for (int j = 1; j < nv; j++)
        for (int i = 1; i < nu; i++) {
            double u = (double)i / nu, v = (double)j / nv, p[2];
            for (int k = 0; k < 2; k++) {
                const double *X = b->x;
                p[k] = (1 - v) * X[2 * bot[i] + k] + v * X[2 * top[i] + k] +
                       (1 - u) * X[2 * lft[j] + k] + u * X[2 * rgt[j] + k] -
                       (1 - u) * (1 - v) * X[2 * bot[0] + k] - u * (1 - v) * X[2 * bot[nu] + k] -
                       (1 - u) * v * X[2 * top[0] + k] - u * v * X[2 * top[nu] + k];
            }
            if ((G(i, j) = mb_node(b, p[0], p[1])) < 0) return free(g), -1;
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++)
            if (mb_quad(b, G(i, j), G(i + 1, j), G(i + 1, j + 1), G(i, j + 1), region) < 0)
                return free(g), -1;
#undef G
    free(g);
    return 0;
}

/* Nodes evenly spaced on the segment a → b, endpoints given (ids). */
static int segment(mbuild *b, int ia, int ib, int n, int *ids)
{
    double xa = b->x[2 * ia], za = b->x[2 * ia + 1];
    double xb = b->x[2 * ib], zb = b->x[2 * ib + 1];
    ids[0] = ia;
    ids[n] = ib;
    for (int i = 1; i < n; i++) {
        double f = (double)i / n;
        if ((ids[i] = mb_node(b, xa + f * (xb - xa), za + f * (zb - za))) < 0) return -1;
    }
    return 0;
}

/* Core quarter disk ρ < ρc bounded by the arc nodes arc[0..N] (θ = 0 → π/2). */
static int mesh_core(mbuild *b, const int *arc, const double *th, int N, double rc)
{
    int js = 1;
    for (int j = 1; j < N; j++)
        if (fabs(th[j] - M_PI_4) < fabs(th[js] - M_PI_4)) js = j;
    int N1 = js, N2 = N - js;
    /* interior corner C on the ray of the split node, so the three patches
     * stay convex whatever θ* the arc offers; Q_C is then a rectangle */
    double cr = 0.78 * rc * sin(th[js]), cz = 0.78 * rc * cos(th[js]);
    double hc = rc * M_PI_2 / N;
    int k1 = (int)fmax(1.0, round(0.22 * rc / hc));
    int o = mb_node(b, 0, 0), am = mb_node(b, 0, cz), bm = mb_node(b, cr, 0);
    int C = mb_node(b, cr, cz);
    if (o < 0 || am < 0 || bm < 0 || C < 0) return -1;
    int nmax = N + k1 + 2, rc_ = -1;
    int *w = malloc((size_t)nmax * 9 * sizeof *w);
    if (!w) return -1;
    int *axU = w, *axL = w + nmax, *bsI = w + 2 * nmax, *bsO = w + 3 * nmax;
    int *cA = w + 4 * nmax, *cB = w + 5 * nmax, *cT = w + 6 * nmax;
    int *arcA = w + 7 * nmax, *arcBr = w + 8 * nmax;
    for (int j = 0; j <= N1; j++) arcA[j] = arc[j];           /* top → θ* */
    for (int j = 0; j <= N2; j++) arcBr[j] = arc[N - j];      /* π/2 → θ* */
    if (segment(b, am, arc[0], k1, axU) || segment(b, o, am, N2, axL) ||
        segment(b, o, bm, N1, bsI) || segment(b, bm, arc[N], k1, bsO) ||
        segment(b, am, C, N1, cA) || segment(b, bm, C, N2, cB) || segment(b, C, arc[js], k1, cT))
        goto done;
    if (tfi_patch(b, bsI, cA, axL, cB, N1, N2, ASP_REGION_SUBSTRATE) ||
        tfi_patch(b, cA, arcA, axU, cT, N1, k1, ASP_REGION_SUBSTRATE) ||
        tfi_patch(b, bsO, cT, cB, arcBr, k1, N2, ASP_REGION_SUBSTRATE))
        goto done;
    rc_ = 0;
done:
    free(w);
    return rc_;
}

/* One polar layer between ring k (outer: ids `on`, angles `oth`, `no`
 * intervals) and ring k+1 at radius rin, merging triples of thin intervals
 * with the 3-to-1 template.  Writes the inner ring to `in`/`ith`. */
static int polar_layer(mbuild *b, const int *on, const double *oth, int no, double rout,
                       double rin, int region, int *in, double *ith, int *nin)
{
    double H = rout - rin, rmid = 0.5 * (rout + rin);
    int ni = 0, j = 0;
    double r, z;
    polar(rin, oth[0], &r, &z);
    if ((in[0] = mb_node(b, r, z)) < 0) return -1;
    ith[0] = oth[0];
    while (j < no) {
        int merge = j + 3 <= no;
        for (int k = j; merge && k < j + 3; k++)
            merge = rout * (oth[k + 1] - oth[k]) < 0.55 * H;
        if (merge && rout * (oth[j + 3] - oth[j]) > 2.0 * H) merge = 0;
        int step = merge ? 3 : 1;
        polar(rin, oth[j + step], &r, &z);
        if ((in[ni + 1] = mb_node(b, r, z)) < 0) return -1;
        ith[ni + 1] = oth[j + step];
        if (!merge) {
            if (mb_quad(b, in[ni], in[ni + 1], on[j + 1], on[j], region) < 0) return -1;
        } else {
            int I1, I2;
            polar(rmid, oth[j + 1], &r, &z);
            if ((I1 = mb_node(b, r, z)) < 0) return -1;
            polar(rmid, oth[j + 2], &r, &z);
            if ((I2 = mb_node(b, r, z)) < 0) return -1;
            int B0 = in[ni], B3 = in[ni + 1];
            if (mb_quad(b, B0, I1, on[j + 1], on[j], region) < 0 ||
                mb_quad(b, I1, I2, on[j + 2], on[j + 1], region) < 0 ||
                mb_quad(b, I2, B3, on[j + 3], on[j + 2], region) < 0 ||
                mb_quad(b, B0, B3, I2, I1, region) < 0)
                return -1;
        }
        ni++;
        j += step;
    }
    *nin = ni;
    return 0;
}

static void mesh_flags(asp_mesh *m, double Rp, double cand)
{
    for (int i = 0; i < m->nnode; i++) {
        double r = m->x[2 * i], z = m->x[2 * i + 1];
        unsigned char f = 0;
        if (z == 0.0) f |= ASP_NODE_BASE;
        if (r == 0.0) f |= ASP_NODE_AXIS;
        if (fabs(hypot(r, z) - Rp) < 1e-12 * Rp && r <= cand) f |= ASP_NODE_TOP;
        m->flags[i] = f;
    }
}

static stc_status check_spec(const asp_mesh_spec *s)
{
    STC_CHECK(s->R > 0.0 && isfinite(s->R), STC_EINVAL, "R = %g: must be > 0", s->R);
    STC_CHECK(s->t >= 0.0 && s->t <= 0.2 * s->R, STC_EINVAL,
              "t = %g mm: coating thickness must be in [0, 0.2 R]", s->t);
    STC_CHECK(s->a_max > 0.0 && s->a_max <= 0.25 * s->R, STC_EINVAL,
              "a_max = %g mm: contact radius must be in (0, 0.25 R] (small-strain model)", s->a_max);
    STC_CHECK(s->level >= 0 && s->level <= 6, STC_EINVAL,
              "mesh level = %d: must be in [0, 6]", s->level);
    return STC_OK;
}

/* Surface boundary layer: the top row of depth levels (size d1 = d[1]) is
 * split into nl + 1 rows halving towards the surface, d1/2^nl, d1/2^nl,
 * d1/2^(nl-1), ..., d1/2.  Why: under stick the surface near the axis is
 * held at its touch position (ε_r ≈ ε_θ ≈ 0), and at low ν the von Mises
 * maximum sits on that surface; the 2x2 Gauss points of a full-size top row
 * lie 0.21 h below it.  The rows span every θ (the band layout has no
 * depth transitions), so far from the contact they are thin, flat
 * rectangles: 2^nl more elongated than the top row already is, which the
 * direct solver takes (measured: slip Hertz load +0.004 % with 3 layers, the
 * same to 1e-5 with 6; docs/yield-discrepancies.md §1.3).  Rewrites *d,
 * returns the new count (-1: out of memory, *d untouched). */
static int surface_rows(double **d, int nd, int nl)
{
    if (nl <= 0) return nd;
    double *o = *d, d1 = o[1];
    double *nw = malloc((size_t)(nd + nl + 1) * sizeof *nw);
    if (!nw) return -1;
    nw[0] = 0.0;
    for (int i = 1; i <= nl + 1; i++) nw[i] = d1 * ldexp(1.0, i - 1 - nl);
    nw[nl + 1] = d1; /* exact */
    for (int i = 2; i <= nd; i++) nw[nl + i] = o[i];
    free(o);
    *d = nw;
    return nd + nl;
}

/* Automatic surface layers: 3 under stick, where the first yield of a low-ν
 * or thin hard-coated sphere sits on the stuck surface (ν = 0.25, level 3:
 * δc/ωc 0.785 → 0.763 with 3 layers, 6 layers a further -0.9 % at level 2;
 * t/R 0.005, Eco/Esu 4: δc1 -3 to -4 %), none under slip, whose first yield
 * is below the surface (+0.03 to +0.1 % with 3 layers; cost +6 % elements;
 * docs/yield-discrepancies.md §1.3). */
int asp_surface_layers(const asp_options *o)
{
    if (o->surface_layers >= 0) return o->surface_layers;
    return o->contact == ASP_CONTACT_STICK ? 3 : 0;
}

/* n: elements across a_max (ASP_MESH_N0 2^level, or a value between levels;
 * sq = sqrt(n / ASP_MESH_N0) keeps the level formulas for q and hmax). */
static stc_status build_axisym(const asp_mesh_spec *s, double a_min, double n, int nl,
                               mbuild *b, asp_mesh *m)
{
    double Rp = s->R + s->t, sq = sqrt(n / ASP_MESH_N0);
    double h = s->a_max / n;
    double amin = a_min > 0.0 ? fmin(a_min, s->a_max) : s->a_max;
    double h0 = amin / n;
    double q = 1.0 + 0.3 / sq, hmax = 0.15 * Rp / sq, rc = 0.4 * Rp;
    double *arc = NULL, *d = NULL, *oth = NULL, *ith = NULL;
    int *on = NULL, *in = NULL;
    stc_status st = STC_ENOMEM;
    /* the surface from 1.25 a_min to 1.25 a_max: size = arc length / n, so
     * every contact radius of a curve has about n elements across, as at
     * a_min and a_max (growing by q alone left ~4.7 across a 6 ωc contact
     * on the 1:60 ωc curve at n = 6; with it the curve's P_smooth error
     * against level 3 fell from 0.3-0.74 % to 0.15-0.46 % for n = 6..12,
     * docs/design.md §2.3) */
    int na = graded_sizes(Rp * M_PI_2, h0, 1.25 * amin, h, 1.25 * s->a_max, q, hmax,
                          amin < s->a_max ? 1.0 / n : 0.0, &arc);
    int nd = depth_levels(s, amin, h0, h, q, hmax, Rp - rc, &d);
    if (nd >= 1) nd = surface_rows(&d, nd, nl);
    if (na < 0 || nd < 0) goto fail;
    oth = malloc((size_t)(na + 1) * sizeof *oth), ith = malloc((size_t)(na + 1) * sizeof *ith);
    on = malloc((size_t)(na + 1) * sizeof *on), in = malloc((size_t)(na + 1) * sizeof *in);
    if (!oth || !ith || !on || !in) goto fail;
    oth[0] = 0.0;
    for (int j = 0; j < na; j++) oth[j + 1] = oth[j] + arc[j] / Rp;
    oth[na] = M_PI_2;
    for (int j = 0; j <= na; j++) {
        double r, z;
        polar(Rp, oth[j], &r, &z);
        if ((on[j] = mb_node(b, r, z)) < 0) goto fail;
    }
    int no = na;
    for (int k = 0; k < nd; k++) {
        int ni, reg = (d[k + 1] <= s->t * (1 + 1e-12) && s->t > 0.0) ? ASP_REGION_COATING
                                                                    : ASP_REGION_SUBSTRATE;
        if (polar_layer(b, on, oth, no, Rp - d[k], Rp - d[k + 1], reg, in, ith, &ni)) goto fail;
        int *ti = on; on = in; in = ti;
        double *tt = oth; oth = ith; ith = tt;
        no = ni;
    }
    STC_CHECK_GOTO(no >= 2, st, fail, STC_EINVAL, "mesh: core arc has %d intervals (< 2)", no);
    if (mesh_core(b, on, oth, no, rc)) goto fail;
    m->dim = 2, m->nen = 4, m->nnode = b->nnode, m->nelem = b->nelem;
    m->x = b->x, m->conn = b->conn, m->region = b->region;
    b->x = NULL, b->conn = NULL, b->region = NULL;
    m->flags = malloc((size_t)m->nnode);
    if (!m->flags) goto fail;
    mesh_flags(m, Rp, fmin(4.0 * s->a_max, 0.5 * Rp));
    st = STC_OK;
fail:
    if (st == STC_ENOMEM) STC_FAIL(STC_ENOMEM, "mesh: out of memory");
    free(arc), free(d), free(oth), free(ith), free(on), free(in);
    return st;
}

stc_status asp_mesh_axisym(const asp_mesh_spec *spec, asp_mesh **out)
{
    return asp_mesh_axisym_graded(spec, 0.0, out);
}

stc_status asp_mesh_axisym_graded(const asp_mesh_spec *spec, double a_min, asp_mesh **out)
{
    /* & 7: no undefined shift before check_spec rejects a bad level */
    return asp_mesh_axisym_n(spec, a_min, ASP_MESH_N0 * (double)(1 << (spec->level & 7)), out);
}

stc_status asp_mesh_axisym_n(const asp_mesh_spec *spec, double a_min, double n, asp_mesh **out)
{
    return asp_mesh_axisym_nl(spec, a_min, n, 0, out);
}

stc_status asp_mesh_axisym_nl(const asp_mesh_spec *spec, double a_min, double n,
                              int surface_layers, asp_mesh **out)
{
    *out = NULL;
    STC_CALL(check_spec(spec));
    STC_CHECK(n >= 3.0 && n <= ASP_MESH_N0 * 64.0, STC_EINVAL,
              "elements per contact = %g: must be in [3, %d]", n, ASP_MESH_N0 * 64);
    STC_CHECK(surface_layers >= 0 && surface_layers <= ASP_MESH_MAX_SURFACE_LAYERS, STC_EINVAL,
              "surface layers = %d: must be in [0, %d]", surface_layers,
              ASP_MESH_MAX_SURFACE_LAYERS);
    asp_mesh *m = calloc(1, sizeof *m);
    mbuild b = {0};
    STC_CHECK(m, STC_ENOMEM, "mesh: out of memory");
    stc_status st = build_axisym(spec, a_min, n, surface_layers, &b, m);
    free(b.x), free(b.conn), free(b.region);
    if (st != STC_OK) {
        asp_mesh_destroy(&m);
        return st;
    }
    *out = m;
    return STC_OK;
}

void asp_mesh_destroy(asp_mesh **m)
{
    if (!m || !*m) return;
    free((*m)->x), free((*m)->conn), free((*m)->region), free((*m)->flags);
    free((*m)->hang), free((*m)->hang_m), free((*m)->hang_w);
    free(*m);
    *m = NULL;
}

/* Scaled Jacobian of a quad corner / hex corner: the signed volume spanned
 * by the edges leaving the corner, over the product of their lengths. */
static double quad_quality(const double *X)
{
    double w = 1.0;
    for (int a = 0; a < 4; a++) {
        const double *p = X + 2 * a, *n = X + 2 * ((a + 1) % 4), *v = X + 2 * ((a + 3) % 4);
        double e1[2] = {n[0] - p[0], n[1] - p[1]}, e2[2] = {v[0] - p[0], v[1] - p[1]};
        double c = e1[0] * e2[1] - e1[1] * e2[0];
        w = fmin(w, c / (hypot(e1[0], e1[1]) * hypot(e2[0], e2[1])));
    }
    return w;
}

static double hex_quality(const double *X)
{
    /* neighbours along ξ, η, ζ of each corner in the standard hex8 order */
    static const int nb[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                 {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
    static const int sgn[8] = {1, -1, 1, -1, -1, 1, -1, 1};
    double w = 1.0;
    for (int a = 0; a < 8; a++) {
        double e[3][3], l[3];
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < 3; i++) e[k][i] = X[3 * nb[a][k] + i] - X[3 * a + i];
            l[k] = sqrt(e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2]);
        }
        double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
        w = fmin(w, sgn[a] * det / (l[0] * l[1] * l[2]));
    }
    return w;
}

const int asp_hex8_faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                  {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

int asp_mesh_on_sphere(const asp_mesh *m, int n, double R)
{
    const double *x = m->x + (size_t)m->dim * n;
    double r2 = 0.0;
    for (int i = 0; i < m->dim; i++) r2 += x[i] * x[i];
    return R > 0.0 && fabs(sqrt(r2) - R) <= 1e-9 * R;
}

stc_status asp_mesh_quality(const asp_mesh *m, double *worst)
{
    double w = 1.0, X[24];
    int bad = -1;
    for (int e = 0; e < m->nelem; e++) {
        for (int a = 0; a < m->nen; a++)
            for (int i = 0; i < m->dim; i++)
                X[m->dim * a + i] = m->x[m->dim * m->conn[m->nen * e + a] + i];
        double q = m->dim == 2 ? quad_quality(X) : hex_quality(X);
        if (q <= 0.0 && bad < 0) bad = e;
        w = fmin(w, q);
    }
    *worst = w;
    STC_CHECK(bad < 0, STC_EFORMAT, "mesh: element %d is inverted (scaled Jacobian %g)", bad, w);
    return STC_OK;
}
