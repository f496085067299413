/* 3D half model of the coated hemisphere (y >= 0): hex8 mesh graded
 * towards the contact point P = (0, 0, R').
 *
 * Idea: an "onion" mesh around a point is the natural way to grade a hex
 * mesh geometrically with constant element shape, and an inversion turns
 * the hemisphere into exactly the domain such an onion fills.
 *
 * 1. Reference domain D = {|p| <= 1, w <= 0, y >= 0} (p = (x, y, w)), a
 *    quarter ball whose flat face w = 0 will become the outer sphere and
 *    whose curved face |p| = 1 will become the base plane.
 * 2. The inversion I(p) = C + 2 (p - C) / |p - C|², C = (0, 0, 1), maps D
 *    onto itself, swapping the flat and the curved face and sending the
 *    origin to the south pole (it is the stereographic inversion; conformal,
 *    so element angles survive).  The physical point is
 *    X = R' (q_x, q_y, -q_w), q = I(p): the reference origin becomes P, the
 *    face w = 0 the sphere |X| = R', the face |p| = 1 the base z = 0, and
 *    near P lengths scale by 2 R'.  The coating interface |X| = R is the
 *    image of a sphere in D (centre (0, 0, W), radius r_i, found from the
 *    two points where it crosses the w axis) lying just below w = 0.
 * 3. In D: a structured core box [-c, c] x [0, c] x [-c_w, 0] of uniform
 *    lateral size h (the contact zone: c = m h >= 1.25 a_max, as in the
 *    axisymmetric mesh), with rows in depth that put >= 4 elements through
 *    the coating and a row exactly on the interface; then S shells: every
 *    node of the box's exposed surface (sides x = ±c, y = c and bottom
 *    w = -c_w) is carried outward, its distance growing geometrically to
 *    1 (the last shell is the unit sphere, i.e. the base): away from the
 *    axis segment under the box for a deep box (thick coating), along rays
 *    from P otherwise (see skel_pos).  The shells keep the box's surface
 *    grid, so there are no degenerate hexes anywhere (no axis singularity:
 *    the box is an O-grid core).  On the side faces each shell's column of
 *    rows is re-placed along its meridian: the coating rows between the
 *    surface and the interface (snapped exactly onto the interface sphere),
 *    the rows below between the interface and the bottom edge, so every
 *    element lies in one layer.
 *
 * Sizes (shared `level` semantics, see asperity/mesh.c): n = 6·2^level
 * elements across a_max (h = a_max / n), fine zone 1.0 a_max laterally
 * (the axisymmetric mesh: 1.25) and 0.8 a_max in depth; shells growing by
 * q_s = 1 + (0.1 / √2^level) (ρ/c)^0.3 per shell (1.10 at the core, ~1.5
 * at the base, level 0; see M3_SHELL_Q), far-field size hmax = 0.15 R' /
 * √2^level, coating >= 4 elements (spacing min(h, t/4)).  A coating thicker
 * than the fine zone deepens the core box down to the interface (uniform h
 * to 0.8 a_max, then rows growing by q = 1 + 0.3 / √2^level); one that ends
 * less than h/4 below the fine zone's last uniform row (M3_THICK_REST) is
 * meshed like a thin one, with uniform rows t / ceil(t/h).  Worst scaled
 * Jacobian measured >= 0.34 for 0 <= t <= 0.5 mm, 0.003 <= a_max <= 2.5 mm
 * (R = 10, levels 0-2; tests/test_mesh3d.c).  Linear (chordal) boundary
 * faces: the volume error is ~0.3 % at level 1, halving per level.
 *
 * Coarsening (spec->coarsen; default 1 step, up to 2, < 0 none = exactly
 * the mesh above): the shells carry the box's full surface grid (92 % of
 * the nodes, uncoarsened Hertz case) with the contact's angular resolution
 * down to the base.  From the shell whose radius reaches 6 c (then 24 c,
 * M3_COARSEN_T) on, the elements use every other grid line in x, y and
 * depth (2:1; the coating rows and the first row below the interface are
 * kept; at most one step per shell, none on the last two).  The fine-side
 * points of a transition shell that are not on the coarse grid are hanging
 * nodes (asp_mesh.hang): interpolated from the 2 or 4 coarse-grid
 * neighbours on the same shell (index-space weights: 1/2, or 1/3 and 2/3
 * next to a kept odd end) and moved onto the coarse face, so the mesh
 * conforms.  Nodes (coarsen -1 / 1 / 2 with thresholds 3 c and 8 c), level
 * 0, R' = 10.5, t = 0, a_max = 0.35: n = 6: 6810 / 4128 / 3699, n = 8.5:
 * 16337 / 9848 / 8652, n = 12: 35360 / 20385 / 18150.  Worst quality
 * unchanged within 0.01.  The chordal volume error of the coarse far field
 * grows (t = 0.05, a_max = 0.1, two steps at 3 c / 8 c: 5.0 / 1.5 / 0.44 %
 * at levels 0 / 1 / 2 against 0.73 / 0.31 / 0.14 %), all far from the
 * contact.
 *
 * Flags: ASP_NODE_BASE on z = 0, ASP_NODE_SYM on y = 0 (coordinates set
 * exactly), ASP_NODE_TOP on the outer sphere within lateral distance
 * max(3 a_max, core half-width) of the axis, never on a hanging node.
 * ASP_NODE_AXIS is not used in 3D.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fe.h"
#include "stc_check.h"

enum { M3_N0 = 6 };              /* elements across a_max at level 0 (mesh.c) */
/* Fine zone half-width / a_max.  1.0, not the axisymmetric 1.25: the box's
 * surface grid is carried by every shell, so its width sets the cost of the
 * whole mesh; the contact radius stays below a_max (solver safety 1.1), and
 * measured (Hertz, a/R = 0.01, level 0) 1.25 -> 1.0 cut the DOFs by 22 %
 * with the P error unchanged within 0.1 % (docs/design.md §2.4). */
static const double M3_FINE_LAT = 1.0;
static const double M3_FINE_DEP = 0.8;  /* fine zone depth / a_max (Hertz τmax at 0.48 a) */
static const double M3_TOP_FLAG = 3.0;  /* ASP_NODE_TOP within this × a_max of the axis */
static const double M3_MAX_CORE = 0.5;  /* core must stay inside |p| < this (reference units) */
/* Least depth, in units of h, by which the coating must reach below the fine
 * zone's last uniform row (depth ceil(0.8 a_max / h) h) to get the
 * thick-coating rows (make_rows); a coating that ends above that depth gets
 * uniform rows t / ceil(t/h) <= h instead.  The thick-coating rows between
 * the last uniform row and the interface are as thin as that remainder: a
 * coating ending on or above the last uniform row made the interface row
 * overtake it (inverted elements, e.g. t/R 0.016, n = 6.3-8 at δ = 1 ωc,
 * E/Y 133), and a remainder below ~1e-3 h still inverted elements once the
 * interface row was snapped onto the sphere.  With h/4 the thin-coating rows
 * are >= 0.6 h and the thick-coating rows >= 0.11 h (n = 3 to 384). */
static const double M3_THICK_REST = 0.25;
/* Shell growth: step ratio q_s(ρ) = 1 + (M3_SHELL_Q / √2^level) (ρ/c)^M3_SHELL_G.
 * The P error of the 3D Hertz point (a/R = 0.01) is dominated by the radial
 * step of the shells, not by the size at the contact: fitted to 12 runs,
 * P/P_conv - 1 ≈ C_q (q_s - 1)² - 0.38 % (6 / n)², C_q ≈ 25 (n = 6..9,
 * hex8 stiffening) rising to ≈ 40 at n = 12 (finer angular grid, longer
 * elements), the contact zone itself slightly soft, O(h²).  So the shells
 * grow slowly near the contact (1.10 instead of 1.30) and faster outside,
 * where the Boussinesq field's energy (~ a/r per log-shell) is small.
 * Measured: Hertz level 0 +2.07 % -> +0.66 % (converged +0.62 %) at the same
 * DOFs; a coated case (t/R = 0.005, Eco/Esu = 4) +1.7 % -> +0.75 % against
 * the converged axisymmetric P (its soft part is smaller, so less cancels). */
static const double M3_SHELL_Q = 0.1;
static const double M3_SHELL_G = 0.3;
/* 2:1 angular coarsening of the shells: level g is used from the first
 * shell whose reference radius reaches M3_COARSEN_T[g-1] c (c ~ a_max, the
 * lateral distance ≈ 2 R' ρ near P).  The coarse far field is stiffer by
 * plain interpolation error of the smooth field, not by locking (elastic
 * incompatible-mode hexahedra there changed P by <= 0.02 %): with one step
 * at T c the 3D Hertz point (a/R = 0.01, level 0) stiffens by about
 * 1 % / T (T = 2, 3, 4, 6: +0.56, +0.35, +0.26, +0.16 % against the
 * uncoarsened mesh), the energy beyond T a_max being ~1/T of the total
 * (Boussinesq).  6 c and one step by default: Hertz +0.16 % (level 0) /
 * +0.05 % (level 1); μs of a combined-loading run moves by +0.23 % (WSP
 * 3 ωc) / -0.23 % (t/R 0.025, Eco/Esu 2, δ = 30 ωc_su) for 1.8x / 1.5x
 * less wall time (docs/design.md §2.5).  A second step at 24 c
 * adds +0.07 % (level 0) to Hertz. */
enum { M3_NCOARSEN = 2, M3_COARSEN_DEFAULT = 1 };
static const double M3_COARSEN_T[M3_NCOARSEN] = {6.0, 24.0};

/* Everything derived from the spec, in reference units unless stated. */
typedef struct m3_plan {
    double Rp, R, a;   /* outer radius R', substrate radius R, a_max, mm */
    double c, cw;      /* core half-width and depth */
    double c_ref;      /* the a_max core's half-width (coarsening thresholds) */
    double W, ri;      /* interface sphere: centre (0, 0, W), radius ri */
    double kappa;      /* rate at which the shells round off (ray_beta) */
    double zs;         /* skeleton depth max(0, c_w - c) (skel_pos) */
    int coated;
    int m, L, lint;    /* half-width in elements, depth rows, interface row */
    int S;             /* number of shells (shell S = unit sphere) */
    double *d;         /* [L+1] nominal row depths */
    double *rho;       /* [S+1] shell radii of the reference ray |σ| = c */
    /* numbering */
    int nx, ny;        /* 2m+1, m+1 */
    int ncore, nsp;    /* core nodes, exposed-surface points */
    int *sp_core;      /* [nsp] core node of each surface point */
    int *sp_row;       /* [nsp] row l of a side point, -1 for bottom-only */
    /* coarsening (plan_coarsen): line sets of level g = 0..G (g = 0: all) */
    int G;             /* levels in use, 0 = none */
    unsigned char *inI, *inJ, *inR, *inU; /* [G+1][2m+1], [m+1], [L+1], [4m+1] */
    int *lev;          /* [S+1] level of the elements between shells k and k+1 */
    int *act;          /* [G+1][nsp] index of a point among level g's, -1 if off */
    int *base;         /* [S+2] first node of shell k >= 1; base[S+1] = nnode */
    int nelem;
} m3_plan;

static void plan_free(m3_plan *p)
{
    free(p->d), free(p->rho), free(p->sp_core), free(p->sp_row);
    free(p->inI), free(p->inJ), free(p->inR), free(p->inU);
    free(p->lev), free(p->act), free(p->base);
}

static int core_id(const m3_plan *p, int i, int j, int l)
{
    return (l * p->ny + j) * p->nx + i;
}

/* Row depths of the core (physical mm, converted by the caller): nf =
 * ceil(zf / h) uniform rows of h through the fine zone (depth zf), and a
 * row exactly at the coating's depth t.  Returns the number of rows L
 * (depths d[0..L], strictly increasing) or -1 when more than cap. */
static int make_rows(double h, double t, double zf, double q, double *d, int cap,
                     int *lint)
{
    int L = 0, nf = (int)ceil(zf / h - 1e-9);
    d[0] = 0.0;
    *lint = -1;
    if (t > 0.0 && t < (nf + M3_THICK_REST) * h) {
        /* thin coating (t <= zf), or one ending less than M3_THICK_REST h
         * below the last uniform row: >= 4 uniform rows of t / ceil(t/h)
         * <= h, then grow back to h */
        int nc = (int)ceil(t / h - 1e-9);
        if (nc < 4) nc = 4;
        double s = t / nc;
        for (int k = 1; k <= nc && L < cap; k++) d[++L] = t * k / nc;
        *lint = L;
        while ((d[L] < zf || L < *lint + 2) && L < cap) {
            s = fmin(s * q, h);
            d[L + 1] = d[L] + s;
            L++;
        }
    } else {
        for (int k = 1; k <= nf && L < cap; k++) d[++L] = h * k;
        if (t > 0.0) {
            /* thick coating: grow by q from h and land exactly on t */
            double sum = 0.0, s = h;
            int n = 0;
            while (zf + sum < t) { s *= q; sum += s; n++; }
            double scale = (t - d[L]) / sum, dl = d[L];
            s = h;
            for (int k = 1; k <= n && L < cap; k++) {
                s *= q;
                dl += s * scale;
                d[++L] = k == n ? t : dl;
            }
            *lint = L;
            for (int k = 0; k < 2 && L < cap; k++) {
                s *= q;
                d[L + 1] = d[L] + s * fmax(scale, 0.5);
                L++;
            }
        }
    }
    return L < cap ? L : -1;
}

/* Interface |X| = R in reference coordinates: the sphere through the images
 * of the axis points q = (0, 0, ∓s), s = R/R' (I is an involution). */
static void interface_sphere(double s, double *W, double *ri)
{
    double w1 = 1.0 - 2.0 / (1.0 + s), w2 = 1.0 - 2.0 / (1.0 - s);
    *W = 0.5 * (w1 + w2);
    *ri = 0.5 * (w1 - w2);
}

static stc_status plan_make(const asp_mesh_spec *spec, m3_plan *p)
{
    memset(p, 0, sizeof *p);
    p->Rp = spec->R + spec->t;
    p->a = spec->a_max;
    /* a fractional level between the integer ones scales every size alike */
    double lv = spec->n > 0.0 ? log2(spec->n / M3_N0) : spec->level;
    double a_core = spec->a_min > 0.0 && spec->a_min < spec->a_max ? spec->a_min : spec->a_max;
    double n = M3_N0 * pow(2.0, lv), h = a_core / n, sl = pow(sqrt(2.0), lv);
    double q = 1.0 + 0.3 / sl;                             /* core row growth */
    double qs = M3_SHELL_Q / sl;                           /* q_s - 1 at the core */
    double hmax = 0.15 * p->Rp / sl;
    double to_ref = 1.0 / (2.0 * p->Rp); /* lengths near P scale by 2 R' */
    p->m = (int)ceil(M3_FINE_LAT * n - 1e-9);
    p->c = p->m * h * to_ref;
    p->c_ref = p->c * spec->a_max / a_core;
    p->coated = spec->t > 0.0;
    enum { CAP = 4096 };
    p->d = malloc(CAP * sizeof *p->d);
    STC_CHECK(p->d, STC_ENOMEM, "mesh3d: out of memory");
    p->L = make_rows(h, spec->t, M3_FINE_DEP * a_core, q, p->d, CAP, &p->lint);
    STC_CHECK(p->L > 0, STC_EINVAL, "mesh3d: t/a_max = %g needs too many rows",
              spec->t / spec->a_max);
    for (int l = 0; l <= p->L; l++) p->d[l] *= to_ref;
    p->cw = p->d[p->L];
    double corner = sqrt(2.0 * p->c * p->c + p->cw * p->cw);
    STC_CHECK(corner < M3_MAX_CORE, STC_EINVAL,
              "mesh3d: a_max/R' = %g, t/R' = %g: the fine zone does not fit in the "
              "hemisphere (a_max must be < ~0.3 R', t < ~0.5 R')",
              spec->a_max / p->Rp, spec->t / p->Rp);
    if (p->coated) interface_sphere(spec->R / p->Rp, &p->W, &p->ri);
    p->zs = fmax(0.0, p->cw - p->c);
    double umax = sqrt(2.0 * p->c * p->c + (p->cw - p->zs) * (p->cw - p->zs)) / p->c;
    /* Rounding rate: as fast as the corner points' growth allows (0.9 / ln umax, see
     * skel_pos), but never so slow that the shells are not round at the base (1 / ln(1/c)).
     * A graded core (c_ref > c) rounds off across the graded zone instead, reaching round
     * at the a_max core's width: on rounded-square shells a node ring's points enter the
     * contact at different δ, so a load curve's node-entry sawtooth is finer.  Measured
     * (slip curve 1:60:12 ωc, n = 4, coarsen 1, against the axisymmetric level 3): the raw
     * P's worst tooth -2.68 -> -1.39 %, the smoothed P's worst error 0.68 -> 0.55 %;
     * docs/design.md §2.4. */
    double k_fast = 0.9 / log(umax);
    if (p->c_ref > p->c) k_fast = fmin(k_fast, 1.0 / log(p->c_ref / p->c));
    p->kappa = fmax(1.0 / log(1.0 / p->c), k_fast);

    /* Shell radii of the ray |σ| = c: step ρ(q_s(ρ)-1), capped so the physical
     * step (scale 2/(1+ρ²) near the surface) stays <= hmax; then rescaled
     * (log-wise) to end exactly on 1. */
    int capS = 1024;
    p->rho = malloc((size_t)(capS + 1) * sizeof *p->rho);
    STC_CHECK(p->rho, STC_ENOMEM, "mesh3d: out of memory");
    p->rho[0] = p->c;
    int S = 0;
    while (p->rho[S] < 1.0 && S < capS) {
        double r = p->rho[S];
        double step = fmin(r * qs * pow(fmax(r / p->c_ref, 1.0), M3_SHELL_G),
                           hmax * (1.0 + r * r) / (2.0 * p->Rp));
        p->rho[++S] = r + step;
    }
    STC_CHECK(S < capS, STC_EINVAL, "mesh3d: too many shells");
    double gam = log(1.0 / p->c) / log(p->rho[S] / p->c);
    for (int k = 1; k <= S; k++) p->rho[k] = p->c * pow(p->rho[k] / p->c, gam);
    p->rho[S] = 1.0;
    p->S = S;
    return STC_OK;
}

/* Surface points: the core nodes on x = ±c, y = c or the bottom row.
 * Ordered: the side strip U (u = 0..4m, rows 0..L) first, then the bottom
 * points not on the strip. */
static int u_to_ij(const m3_plan *p, int u, int *i, int *j)
{
    int m = p->m;
    if (u <= m) { *i = 2 * m; *j = u; }
    else if (u <= 3 * m) { *i = 2 * m - (u - m); *j = m; }
    else { *i = 0; *j = 4 * m - u; }
    return 0;
}

static int sp_side(const m3_plan *p, int u, int l) { return l * (4 * p->m + 1) + u; }

static stc_status plan_number(m3_plan *p)
{
    int m = p->m;
    p->nx = 2 * m + 1;
    p->ny = m + 1;
    p->ncore = p->nx * p->ny * (p->L + 1);
    p->nsp = (4 * m + 1) * (p->L + 1) + (2 * m - 1) * m;
    p->sp_core = malloc((size_t)p->nsp * sizeof *p->sp_core);
    p->sp_row = malloc((size_t)p->nsp * sizeof *p->sp_row);
    STC_CHECK(p->sp_core && p->sp_row, STC_ENOMEM, "mesh3d: out of memory");
    for (int l = 0; l <= p->L; l++)
        for (int u = 0; u <= 4 * m; u++) {
            int i, j;
            u_to_ij(p, u, &i, &j);
            p->sp_core[sp_side(p, u, l)] = core_id(p, i, j, l);
            p->sp_row[sp_side(p, u, l)] = l;
        }
    int k = (4 * m + 1) * (p->L + 1);
    for (int j = 0; j < m; j++)
        for (int i = 1; i < 2 * m; i++) {
            p->sp_core[k] = core_id(p, i, j, p->L);
            p->sp_row[k++] = -1;
        }
    return STC_OK;
}

/* Surface point of the bottom face (i, j) (boundary ones are on the strip). */
static int sp_bottom(const m3_plan *p, int i, int j)
{
    int m = p->m;
    if (i == 2 * m) return sp_side(p, j, p->L);
    if (j == m) return sp_side(p, m + (2 * m - i), p->L);
    if (i == 0) return sp_side(p, 4 * m - j, p->L);
    return (4 * m + 1) * (p->L + 1) + j * (2 * m - 1) + (i - 1);
}

/* ---- coarsening ----
 * Line sets: I ⊂ {0..2m} (x index), J ⊂ {0..m} (y index), R ⊂ {0..L}
 * (rows); the strip's columns U follow through u_to_ij, so the strip and
 * the bottom face agree on their shared edge and at the corners.  A shell
 * k >= 1 holds the points of level lev[k-1] (its fine side); those not on
 * level lev[k]'s grid are hanging on the coarse element's face. */
static const unsigned char *set_I(const m3_plan *p, int g)
{
    return p->inI + (size_t)g * (2 * p->m + 1);
}

static const unsigned char *set_J(const m3_plan *p, int g)
{
    return p->inJ + (size_t)g * (p->m + 1);
}

static const unsigned char *set_R(const m3_plan *p, int g)
{
    return p->inR + (size_t)g * (p->L + 1);
}

static const unsigned char *set_U(const m3_plan *p, int g)
{
    return p->inU + (size_t)g * (4 * p->m + 1);
}

/* Next level of the set prev ⊂ {0..n} (0 and n members): keep the first,
 * the last, every x <= upto (mandatory) and every member after a dropped
 * one.  So each dropped member has both neighbours kept. */
static void set_coarsen(const unsigned char *prev, int n, int upto, unsigned char *next)
{
    int kept = 0;
    for (int x = 0; x <= n; x++) {
        next[x] = 0;
        if (!prev[x]) continue;
        next[x] = x <= upto || x == n || !kept;
        kept = next[x];
    }
}

/* The members of in ⊂ {0..n} around x: x itself (returns 1), or the nearest
 * on each side (returns 2) with the weights of linear interpolation in
 * index space (1/2 each when x is the midpoint, the regular case; a set
 * ending in a unit gap has a second-level member at 1/3 or 2/3). */
static int bracket(const unsigned char *in, int n, int x, int *idx, double *w)
{
    if (in[x]) { idx[0] = x; w[0] = 1.0; return 1; }
    int lo = x, hi = x;
    while (lo > 0 && !in[lo]) lo--;
    while (hi < n && !in[hi]) hi++;
    idx[0] = lo, idx[1] = hi;
    w[0] = (double)(hi - x) / (hi - lo);
    w[1] = 1.0 - w[0];
    return 2;
}

static int next_in(const unsigned char *in, int n, int x)
{
    do x++; while (x < n && !in[x]);
    return x;
}

static int set_count(const unsigned char *in, int n)
{
    int c = 0;
    for (int x = 0; x <= n; x++) c += in[x];
    return c;
}

static void sp_bottom_ij(const m3_plan *p, int sp, int *i, int *j)
{
    int cid = p->sp_core[sp];
    *i = cid % p->nx;
    *j = (cid / p->nx) % p->ny;
}

/* The points of level g's grid that interpolate surface point sp:
 * ms (surface points) and weights ws, tensor products of bracket(); a
 * return of 1 means sp is on the grid. */
static int grid_masters(const m3_plan *p, int g, int sp, int *ms, double *ws)
{
    int a[2], b[2], na, nb, n = 0, m = p->m;
    double wa[2], wb[2];
    if (p->sp_row[sp] >= 0) {
        na = bracket(set_U(p, g), 4 * m, sp % (4 * m + 1), a, wa);
        nb = bracket(set_R(p, g), p->L, p->sp_row[sp], b, wb);
    } else {
        int i, j;
        sp_bottom_ij(p, sp, &i, &j);
        na = bracket(set_I(p, g), 2 * m, i, a, wa);
        nb = bracket(set_J(p, g), m, j, b, wb);
    }
    for (int ib = 0; ib < nb; ib++)
        for (int ia = 0; ia < na; ia++) {
            ms[n] = p->sp_row[sp] >= 0 ? sp_side(p, a[ia], b[ib]) : sp_bottom(p, a[ia], b[ib]);
            ws[n++] = wa[ia] * wb[ib];
        }
    return n;
}

static int on_grid(const m3_plan *p, int g, int sp)
{
    if (p->sp_row[sp] >= 0)
        return set_U(p, g)[sp % (4 * p->m + 1)] && set_R(p, g)[p->sp_row[sp]];
    int i, j;
    sp_bottom_ij(p, sp, &i, &j);
    return set_I(p, g)[i] && set_J(p, g)[j];
}

static int cells(const m3_plan *p, int g)
{
    int m = p->m;
    return (set_count(set_U(p, g), 4 * m) - 1) * (set_count(set_R(p, g), p->L) - 1) +
           (set_count(set_I(p, g), 2 * m) - 1) * (set_count(set_J(p, g), m) - 1);
}

/* Shell levels: lev[k] = number of thresholds ρ_k has reached (capped at
 * G), rising by at most one per shell and never on the last two shells
 * (the base shell S and the one before keep their fine grid: no hanging
 * node is ever on the base). */
static void plan_levels(m3_plan *p)
{
    p->lev[0] = 0;
    for (int k = 1; k <= p->S; k++) {
        int g = 0;
        while (g < p->G && p->rho[k] >= M3_COARSEN_T[g] * p->c_ref) g++;
        if (g > p->lev[k - 1] + 1) g = p->lev[k - 1] + 1;
        if (k >= p->S - 1) g = p->lev[k - 1];
        p->lev[k] = g;
    }
}

static stc_status plan_coarsen(m3_plan *p, int coarsen)
{
    int m = p->m, L = p->L, G = coarsen < 0 ? 0 : coarsen == 0 ? M3_COARSEN_DEFAULT : coarsen;
    int nI = 2 * m + 1, nJ = m + 1, nR = L + 1, nU = 4 * m + 1;
    p->G = G;
    p->inI = malloc((size_t)(G + 1) * nI);
    p->inJ = malloc((size_t)(G + 1) * nJ);
    p->inR = malloc((size_t)(G + 1) * nR);
    p->inU = malloc((size_t)(G + 1) * nU);
    p->lev = malloc((size_t)(p->S + 1) * sizeof *p->lev);
    p->act = malloc((size_t)(G + 1) * p->nsp * sizeof *p->act);
    p->base = malloc((size_t)(p->S + 2) * sizeof *p->base);
    STC_CHECK(p->inI && p->inJ && p->inR && p->inU && p->lev && p->act && p->base, STC_ENOMEM,
              "mesh3d: out of memory");
    memset(p->inI, 1, (size_t)nI), memset(p->inJ, 1, (size_t)nJ), memset(p->inR, 1, (size_t)nR);
    /* the coating rows and the first below the interface stay (rows run
     * along the meridian: coarsening them would halve the coating's
     * through-thickness resolution) */
    int rkeep = p->coated ? p->lint + 1 : 0;
    for (int g = 0; g < G; g++) {
        set_coarsen(p->inI + g * nI, 2 * m, 0, p->inI + (g + 1) * nI);
        set_coarsen(p->inJ + g * nJ, m, 0, p->inJ + (g + 1) * nJ);
        set_coarsen(p->inR + g * nR, L, rkeep, p->inR + (g + 1) * nR);
    }
    for (int g = 0; g <= G; g++)
        for (int u = 0; u < nU; u++) {
            int i, j;
            u_to_ij(p, u, &i, &j);
            p->inU[g * nU + u] = set_I(p, g)[i] && set_J(p, g)[j];
        }
    for (int g = 0; g <= G; g++) {
        int n = 0, *a = p->act + (size_t)g * p->nsp;
        for (int sp = 0; sp < p->nsp; sp++) a[sp] = on_grid(p, g, sp) ? n++ : -1;
    }
    plan_levels(p);
    p->nelem = 2 * m * m * L;
    p->base[1] = p->ncore;
    for (int k = 0; k < p->S; k++) {
        int gf = p->lev[k]; /* shell k+1's fine side */
        const int *a = p->act + (size_t)gf * p->nsp;
        int n = 0;
        for (int sp = 0; sp < p->nsp; sp++) n += a[sp] >= 0;
        p->base[k + 2] = p->base[k + 1] + n;
        p->nelem += cells(p, p->lev[k]);
    }
    return STC_OK;
}

/* Depth of the interface below w = 0 at lateral distance rl. */
static double interface_depth(const m3_plan *p, double rl)
{
    return -(p->W + sqrt(p->ri * p->ri - rl * rl));
}

/* Reference position of core node (i, j, l). */
static void core_pos(const m3_plan *p, int i, int j, int l, double *x)
{
    x[0] = p->c * (i - p->m) / p->m;
    x[1] = p->c * j / p->m;
    double dl = p->d[l];
    if (p->coated) {
        double di = interface_depth(p, hypot(x[0], x[1]));
        double dint = p->d[p->lint];
        if (l <= p->lint)
            dl = di * p->d[l] / dint;
        else
            dl = di + (p->d[l] - dint) / (p->cw - dint) * (p->cw - di);
    }
    x[2] = -dl;
}

/* Shells.  A box point σ sits at distance ns = |σ - π(σ)| from its
 * projection π(σ) = (0, 0, -min(depth, zs)) on the "skeleton" segment of
 * the axis, zs = max(0, c_w - c) (zs = 0 for a box no deeper than wide:
 * then π = origin and this is a plain ray from P).  On shell k the point is
 *   x = (1 - τ_k) π + r_k (σ - (1 - τ_k) π) / |σ - (1 - τ_k) π|,
 *   r_k = rho_k (ns_k / c)^β_k,
 * i.e. it moves away from the skeleton (sideways from a deep box's sides,
 * diagonally off its bottom edges) with the reference growth; β_k = 1 -
 * κ ln(rho_k/c) (floored at 0) rounds the shells off around the skeleton
 * (κ small enough that every point still grows by >= 10 % of the
 * reference ratio per shell), and τ_k (0 -> 1 while rho_k grows
 * over the whole domain: 0 -> min(100 zs, 1); a slow
 * shrink keeps the shells from shearing) shrinks the skeleton to the origin, so the last shell
 * (β = 0, τ = 1, rho = 1) is the unit sphere. */
static double ray_beta(const m3_plan *p, int k)
{
    return k == p->S ? 0.0 : fmax(0.0, 1.0 - p->kappa * log(p->rho[k] / p->c));
}

static double skel_tau(const m3_plan *p, int k)
{
    if (k == p->S || p->zs <= 0.0) return 1.0;
    double b = fmin(100.0 * p->zs, 1.0);
    double u = fmin(1.0, p->rho[k] / b);
    return u * u * (3.0 - 2.0 * u); /* smoothstep */
}

static void skel_pos(const m3_plan *p, int k, const double s[3], double *x)
{
    double zc = -fmin(-s[2], p->zs) * (1.0 - skel_tau(p, k));
    double v[3] = {s[0], s[1], s[2] - zc};
    double ns = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double r = k == p->S ? 1.0 : p->rho[k] * pow(ns / p->c, ray_beta(p, k));
    x[0] = r * v[0] / ns;
    x[1] = r * v[1] / ns;
    x[2] = zc + r * v[2] / ns;
}

/* Signed distance-like test: > 0 above the interface (coating side). */
static double interface_side(const m3_plan *p, const double *x)
{
    return sqrt(x[0] * x[0] + x[1] * x[1] + (x[2] - p->W) * (x[2] - p->W)) - p->ri;
}

/* Point at arc length t along the polyline P[n][3] with cumulative lengths
 * S[n]. */
static void polyline_at(const double *P, const double *S, int n, double t, double *x)
{
    int a = 0;
    while (a < n - 2 && S[a + 1] < t) a++;
    double f = S[a + 1] > S[a] ? (t - S[a]) / (S[a + 1] - S[a]) : 0.0;
    f = fmin(1.0, fmax(0.0, f));
    for (int i = 0; i < 3; i++) x[i] = P[3 * a + i] + f * (P[3 * (a + 1) + i] - P[3 * a + i]);
}

/* Coated side column on shell k (rows 0..L in P, reference coordinates):
 * find where the meridian polyline crosses the interface and re-place the
 * rows along it, the interface row exactly on the crossing, the rows above
 * and below keeping their relative arc-length spacing.  Q: output. */
static int column_remap(const m3_plan *p, const double *P, double *S, double *Q)
{
    int n = p->L + 1, a = -1;
    S[0] = 0.0;
    for (int l = 1; l < n; l++) {
        double d2 = 0.0;
        for (int i = 0; i < 3; i++) d2 += (P[3 * l + i] - P[3 * (l - 1) + i]) * (P[3 * l + i] - P[3 * (l - 1) + i]);
        S[l] = S[l - 1] + sqrt(d2);
    }
    for (int l = 0; l + 1 < n && a < 0; l++)
        if (interface_side(p, P + 3 * l) > 0.0 && interface_side(p, P + 3 * (l + 1)) <= 0.0) a = l;
    if (a < 0) return -1;
    double lo = S[a], hi = S[a + 1], x[3];
    for (int it = 0; it < 60; it++) { /* bisection on the segment */
        double mid = 0.5 * (lo + hi);
        polyline_at(P, S, n, mid, x);
        if (interface_side(p, x) > 0.0) lo = mid; else hi = mid;
    }
    double sc = 0.5 * (lo + hi), si = S[p->lint], sL = S[n - 1];
    for (int l = 0; l < n; l++) {
        double t = l <= p->lint ? S[l] * sc / si : sc + (S[l] - si) * (sL - sc) / (sL - si);
        polyline_at(P, S, n, t, Q + 3 * l);
    }
    /* the interface row exactly on the interface sphere (in D) */
    double *q = Q + 3 * p->lint, v[3] = {q[0], q[1], q[2] - p->W};
    double nv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++) q[i] = (i == 2 ? p->W : 0.0) + v[i] * p->ri / nv;
    return 0;
}

/* Box point of surface point sp (nominal depths). */
static void box_point(const m3_plan *p, int sp, double *s)
{
    int cid = p->sp_core[sp], l = p->sp_row[sp];
    int i = cid % p->nx, j = (cid / p->nx) % p->ny;
    s[0] = p->c * (i - p->m) / p->m;
    s[1] = p->c * j / p->m;
    s[2] = -p->d[l < 0 ? p->L : l];
}

/* Inversion to physical coordinates.  `radius` > 0 snaps the node onto the
 * sphere |X| = radius (outer surface, interface); base and symmetry nodes
 * get z = 0 / y = 0 exactly. */
static void to_physical(const m3_plan *p, const double *pr, double radius,
                        int on_base, int on_sym, double *X)
{
    double v[3] = {pr[0], pr[1], pr[2] - 1.0};
    double f = 2.0 / (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    X[0] = p->Rp * f * v[0];
    X[1] = p->Rp * f * v[1];
    X[2] = -p->Rp * (1.0 + f * v[2]);
    if (on_sym) X[1] = 0.0;
    if (on_base) X[2] = 0.0;
    if (radius > 0.0) {
        double n = sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2]);
        for (int a = 0; a < 3; a++) X[a] *= radius / n;
    }
}

/* Signed volume-ish orientation of a hex at its centre (det J sign). */
static double hex_orient(const double *x, const int *c)
{
    double e[3][3];
    for (int i = 0; i < 3; i++) {
        /* centre derivatives of the trilinear map along ξ, η, ζ */
        e[0][i] = (x[3 * c[1] + i] + x[3 * c[2] + i] + x[3 * c[5] + i] + x[3 * c[6] + i]) -
                  (x[3 * c[0] + i] + x[3 * c[3] + i] + x[3 * c[4] + i] + x[3 * c[7] + i]);
        e[1][i] = (x[3 * c[2] + i] + x[3 * c[3] + i] + x[3 * c[6] + i] + x[3 * c[7] + i]) -
                  (x[3 * c[0] + i] + x[3 * c[1] + i] + x[3 * c[4] + i] + x[3 * c[5] + i]);
        e[2][i] = (x[3 * c[4] + i] + x[3 * c[5] + i] + x[3 * c[6] + i] + x[3 * c[7] + i]) -
                  (x[3 * c[0] + i] + x[3 * c[1] + i] + x[3 * c[2] + i] + x[3 * c[3] + i]);
    }
    return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
           e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

/* Node of surface point sp on shell k (-1 if not on its fine grid). */
static int node_of(const m3_plan *p, int k, int sp)
{
    if (k == 0) return p->sp_core[sp];
    int a = p->act[(size_t)p->lev[k - 1] * p->nsp + sp];
    return a < 0 ? -1 : p->base[k] + a;
}

static void put_hex(asp_mesh *M, int *e, const int n[8], int region)
{
    int *c = M->conn + 8 * (*e);
    memcpy(c, n, 8 * sizeof *c);
    if (hex_orient(M->x, c) < 0.0) { /* mirror: swap 1<->3, 5<->7 */
        int t = c[1]; c[1] = c[3]; c[3] = t;
        t = c[5]; c[5] = c[7]; c[7] = t;
    }
    M->region[*e] = region;
    (*e)++;
}

/* Physical radius a row is snapped to: R' (surface), R (interface), 0. */
static double row_radius(const m3_plan *p, int l)
{
    if (l == 0) return p->Rp;
    if (p->coated && l == p->lint) return p->R;
    return 0.0;
}

static unsigned char node_flags(const m3_plan *p, const double *X, int l, int j,
                                int base, double top_r)
{
    unsigned char f = 0;
    if (j == 0) f |= ASP_NODE_SYM;
    if (base) f |= ASP_NODE_BASE;
    if (l == 0 && hypot(X[0], X[1]) <= top_r) f |= ASP_NODE_TOP;
    (void)p;
    return f;
}

static stc_status fill_nodes(const m3_plan *p, asp_mesh *M, double top_r, double *buf)
{
    int m = p->m;
    for (int l = 0; l <= p->L; l++)
        for (int j = 0; j <= m; j++)
            for (int i = 0; i <= 2 * m; i++) {
                int id = core_id(p, i, j, l);
                double pr[3], *X = M->x + 3 * id;
                core_pos(p, i, j, l, pr);
                to_physical(p, pr, row_radius(p, l), 0, j == 0, X);
                M->flags[id] = node_flags(p, X, l, j, 0, top_r);
            }
    /* shells: one side column (rows 0..L) at a time, so coated columns can
     * be re-placed along their meridian; then the bottom-only points */
    int n1 = p->L + 1, ncol = 4 * m + 1;
    for (int k = 1; k <= p->S; k++) {
        const unsigned char *inU = set_U(p, p->lev[k - 1]), *inR = set_R(p, p->lev[k - 1]);
        for (int u = 0; u < ncol; u++) {
            if (!inU[u]) continue;
            for (int l = 0; l < n1; l++) {
                double s[3];
                box_point(p, sp_side(p, u, l), s);
                skel_pos(p, k, s, buf + 3 * l);
            }
            const double *Q = buf;
            if (p->coated) {
                if (column_remap(p, buf, buf + 6 * n1, buf + 3 * n1) != 0)
                    return STC_FAIL(STC_EINVAL, "mesh3d: shell %d does not cross the "
                                    "coating interface (t = %g mm too thick for this mesh)",
                                    k, p->Rp - p->R);
                Q = buf + 3 * n1;
            }
            for (int l = 0; l < n1; l++) {
                if (!inR[l]) continue;
                int sp = sp_side(p, u, l), id = node_of(p, k, sp);
                int j = (p->sp_core[sp] / p->nx) % p->ny;
                double *X = M->x + 3 * id;
                to_physical(p, Q + 3 * l, row_radius(p, l), k == p->S, j == 0, X);
                M->flags[id] = node_flags(p, X, l, j, k == p->S, top_r);
            }
        }
        for (int sp = ncol * n1; sp < p->nsp; sp++) {
            int id = node_of(p, k, sp), j = (p->sp_core[sp] / p->nx) % p->ny;
            if (id < 0) continue;
            double s[3], pr[3], *X = M->x + 3 * id;
            box_point(p, sp, s);
            skel_pos(p, k, s, pr);
            to_physical(p, pr, 0.0, k == p->S, j == 0, X);
            M->flags[id] = node_flags(p, X, -1, j, k == p->S, top_r);
        }
    }
    return STC_OK;
}

/* Hanging nodes of shell k: the points of its fine grid (level lev[k-1])
 * that are not on its coarse grid (lev[k]), interpolated from the coarse
 * grid's points on the same shell.  Counts them, and records them when M's
 * arrays exist. */
static int hang_scan(const m3_plan *p, asp_mesh *M)
{
    int nh = 0, ms[4];
    double ws[4];
    for (int k = 1; k < p->S; k++) {
        if (p->lev[k] == p->lev[k - 1]) continue;
        for (int sp = 0; sp < p->nsp; sp++) {
            int id = node_of(p, k, sp), n;
            if (id < 0 || (n = grid_masters(p, p->lev[k], sp, ms, ws)) == 1) continue;
            if (M->hang) {
                M->hang[nh] = id;
                for (int a = 0; a < 4; a++) {
                    M->hang_m[4 * nh + a] = a < n ? node_of(p, k, ms[a]) : -1;
                    M->hang_w[4 * nh + a] = a < n ? ws[a] : 0.0;
                }
            }
            nh++;
        }
    }
    return nh;
}

/* Records the hanging nodes and moves each onto the coarse element's
 * bilinear face (its masters' weighted average), so the fine elements that
 * use it conform; hanging nodes are never contact candidates. */
static stc_status fill_hanging(const m3_plan *p, asp_mesh *M)
{
    int nh = hang_scan(p, M);
    if (nh == 0) return STC_OK;
    M->hang = malloc((size_t)nh * sizeof *M->hang);
    M->hang_m = malloc((size_t)nh * 4 * sizeof *M->hang_m);
    M->hang_w = malloc((size_t)nh * 4 * sizeof *M->hang_w);
    unsigned char *is = calloc((size_t)M->nnode, 1);
    if (!M->hang || !M->hang_m || !M->hang_w || !is) {
        free(is);
        return STC_FAIL(STC_ENOMEM, "mesh3d: out of memory (%d hanging nodes)", nh);
    }
    M->nhang = hang_scan(p, M);
    for (int h = 0; h < nh; h++) is[M->hang[h]] = 1;
    int bad = -1;
    for (int h = 0; h < nh; h++) {
        double *X = M->x + 3 * M->hang[h], Y[3] = {0.0, 0.0, 0.0};
        for (int a = 0; a < 4 && M->hang_m[4 * h + a] >= 0; a++) {
            int mn = M->hang_m[4 * h + a];
            if (is[mn]) bad = h;
            for (int i = 0; i < 3; i++) Y[i] += M->hang_w[4 * h + a] * M->x[3 * mn + i];
        }
        if (M->hang_m[4 * h + 1] < 0 || (M->flags[M->hang[h]] & ASP_NODE_BASE)) bad = h;
        memcpy(X, Y, sizeof Y);
        M->flags[M->hang[h]] &= (unsigned char)~ASP_NODE_TOP;
    }
    free(is);
    STC_CHECK(bad < 0, STC_EINVAL, "mesh3d: internal error: hanging node %d has a hanging "
              "or missing master, or lies on the base", bad < 0 ? 0 : M->hang[bad]);
    return STC_OK;
}

static int side_region(const m3_plan *p, int l)
{
    return p->coated && l < p->lint ? ASP_REGION_COATING : ASP_REGION_SUBSTRATE;
}

static int fill_elements(const m3_plan *p, asp_mesh *M)
{
    int m = p->m, e = 0, n[8];
    for (int l = 0; l < p->L; l++) /* core */
        for (int j = 0; j < m; j++)
            for (int i = 0; i < 2 * m; i++) {
                for (int h = 0; h < 2; h++) {
                    n[4 * h + 0] = core_id(p, i, j, l + h);
                    n[4 * h + 1] = core_id(p, i + 1, j, l + h);
                    n[4 * h + 2] = core_id(p, i + 1, j + 1, l + h);
                    n[4 * h + 3] = core_id(p, i, j + 1, l + h);
                }
                put_hex(M, &e, n, side_region(p, l));
            }
    for (int k = 0; k < p->S; k++) { /* shells: side strip, then bottom */
        int g = p->lev[k];
        const unsigned char *inU = set_U(p, g), *inR = set_R(p, g);
        const unsigned char *inI = set_I(p, g), *inJ = set_J(p, g);
        for (int l = 0, l1 = next_in(inR, p->L, 0); l < p->L; l = l1, l1 = next_in(inR, p->L, l))
            for (int u = 0, u1; u < 4 * m; u = u1) {
                u1 = next_in(inU, 4 * m, u);
                int q[4] = {sp_side(p, u, l), sp_side(p, u1, l),
                            sp_side(p, u1, l1), sp_side(p, u, l1)};
                for (int a = 0; a < 4; a++) {
                    n[a] = node_of(p, k, q[a]);
                    n[4 + a] = node_of(p, k + 1, q[a]);
                }
                put_hex(M, &e, n, side_region(p, l));
            }
        for (int j = 0, j1 = next_in(inJ, m, 0); j < m; j = j1, j1 = next_in(inJ, m, j))
            for (int i = 0, i1; i < 2 * m; i = i1) {
                i1 = next_in(inI, 2 * m, i);
                int q[4] = {sp_bottom(p, i, j), sp_bottom(p, i1, j),
                            sp_bottom(p, i1, j1), sp_bottom(p, i, j1)};
                for (int a = 0; a < 4; a++) {
                    n[a] = node_of(p, k, q[a]);
                    n[4 + a] = node_of(p, k + 1, q[a]);
                }
                put_hex(M, &e, n, ASP_REGION_SUBSTRATE);
            }
    }
    return e;
}

static stc_status check_spec(const asp_mesh_spec *s)
{
    STC_CHECK(s->R > 0.0 && isfinite(s->R), STC_EINVAL, "mesh3d: R = %g: must be > 0", s->R);
    STC_CHECK(s->t >= 0.0 && s->t < s->R, STC_EINVAL,
              "mesh3d: t = %g: must be in [0, R = %g)", s->t, s->R);
    STC_CHECK(s->a_max > 0.0 && s->a_max < s->R, STC_EINVAL,
              "mesh3d: a_max = %g: must be in (0, R = %g)", s->a_max, s->R);
    STC_CHECK(s->level >= 0 && s->level <= 6, STC_EINVAL,
              "mesh3d: level = %d: must be in [0, 6]", s->level);
    STC_CHECK(s->n == 0.0 || (s->n >= 3.0 && s->n <= 384.0), STC_EINVAL,
              "mesh3d: n = %g elements across a_max: must be 0 (from the level) or in [3, 384]",
              s->n);
    STC_CHECK(s->coarsen <= M3_NCOARSEN, STC_EINVAL,
              "mesh3d: coarsen = %d: must be <= %d (< 0 none, 0 default = %d)", s->coarsen,
              M3_NCOARSEN, M3_COARSEN_DEFAULT);
    return STC_OK;
}

stc_status asp_mesh_half3d(const asp_mesh_spec *spec, asp_mesh **out)
{
    m3_plan p;
    asp_mesh *M = NULL;
    double *buf = NULL;
    stc_status st = STC_OK;
    *out = NULL;
    STC_CALL(check_spec(spec));
    STC_CALL_GOTO(plan_make(spec, &p), st, done);
    p.R = spec->R;
    STC_CALL_GOTO(plan_number(&p), st, done);
    STC_CALL_GOTO(plan_coarsen(&p, spec->coarsen), st, done);
    M = calloc(1, sizeof *M);
    STC_CHECK_GOTO(M, st, done, STC_ENOMEM, "mesh3d: out of memory");
    M->dim = 3;
    M->nen = 8;
    M->nnode = p.base[p.S + 1];
    M->nelem = p.nelem;
    M->x = malloc((size_t)M->nnode * 3 * sizeof *M->x);
    M->flags = malloc((size_t)M->nnode);
    M->conn = malloc((size_t)M->nelem * 8 * sizeof *M->conn);
    M->region = malloc((size_t)M->nelem * sizeof *M->region);
    STC_CHECK_GOTO(M->x && M->flags && M->conn && M->region, st, done, STC_ENOMEM,
                   "mesh3d: out of memory (%d nodes, %d elements)", M->nnode, M->nelem);
    buf = malloc((size_t)(p.L + 1) * 7 * sizeof *buf); /* column rows, remap, lengths */
    STC_CHECK_GOTO(buf, st, done, STC_ENOMEM, "mesh3d: out of memory");
    STC_CALL_GOTO(fill_nodes(&p, M, fmax(M3_TOP_FLAG * spec->a_max, 2.0 * p.Rp * p.c), buf),
                  st, done);
    STC_CALL_GOTO(fill_hanging(&p, M), st, done);
    STC_CHECK_GOTO(fill_elements(&p, M) == M->nelem, st, done, STC_EINVAL,
                   "mesh3d: internal error: element count");
    *out = M;
    M = NULL;
done:
    asp_mesh_destroy(&M);
    plan_free(&p);
    free(buf);
    return st;
}
