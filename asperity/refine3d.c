/* Local 2x2x2 refinement of a hex8 mesh with hanging nodes: the 3D mesh
 * made finer in a band around the preload's contact edge only
 * (asp_mesh_refine_band), where the junction's growth is read, while the
 * contact's interior and the shells that carry the far field keep their
 * size (docs/design.md §4.6).
 *
 * Each marked hexahedron is split into eight at its edge midpoints, face
 * centres and centre.  A new node on an edge or a face that an unmarked
 * element also uses is a hanging node of that element's edge (2 masters,
 * weights 1/2) or face (4 masters, 1/4): its displacement is the coarse
 * element's there, so the mesh stays conforming (asp_mesh.hang, eliminated
 * by the assembly as the shells' are).  Positions are the parent's
 * trilinear midpoints, moved radially onto the outer sphere R' or the
 * coating interface R where the parent edge or face lies on it, hanging
 * nodes too: a contact surface must be one sphere for the gaps and the
 * tributary areas; the coarse neighbour's chord lies h²/(8R') inside it, a
 * geometric offset of ~1e-3 h that the constrained displacement does not
 * open.  A hanging node is never a contact candidate (its TOP flag is
 * cleared); its share of a surface area goes to its masters
 * (surfarea.c).
 *
 * One refinement of a 1-irregular mesh stays 1-irregular when no marked
 * element touches an existing hanging node (checked): a second level is
 * marked inside the first with a margin of one coarse element.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fe.h"
#include "stc_check.h"

/* The band of level lv (0, 1, ...) in units of the coarse element size h
 * at the contact: lateral distance a0 - (ASP_BAND_IN - lv) h to a0 +
 * (ASP_BAND_OUT - lv) h, depth (ASP_BAND_DEPTH - lv) h below the surface;
 * each level one h inside the last, the margin a 1-irregular mesh needs.
 * The junction's edge advances by up to ~13 % of a0 (0.5-0.8 h at six
 * elements across a_max) before sliding.  WSP 12 ωc, two levels: a band
 * of 2 / 3 / 2 h gave μs 0.3343 at 36795 DOFs and 126 s, this one 0.3340
 * at 22356 DOFs and 47 s; over four placements at WSP 3 ωc the wider band
 * scattered 0.5 %, this one 2.1 % (docs/design.md §4.6). */
static const double ASP_BAND_IN = 1.5, ASP_BAND_OUT = 2.0, ASP_BAND_DEPTH = 1.5;

/* Hex8 corner a at local (ξ, η, ζ) ∈ {0, 1}³ (mesh3d.c's order). */
static const int CORNER_AT[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}}; /* [ξ][η][ζ] */
static const int HEX_EDGES[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                     {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

/* Open-addressing table from a sorted set of 2 or 4 corner ids (an edge or a
 * face of the parent mesh) to the new node on it. */
typedef struct rf_key { int n, id[4]; } rf_key;
typedef struct rf_table {
    size_t cap;
    rf_key *key;
    int *node; /* -1 empty */
} rf_table;

static void key_make(rf_key *k, const int *ids, int n)
{
    k->n = n;
    for (int a = 0; a < 4; a++) k->id[a] = a < n ? ids[a] : -1;
    for (int a = 1; a < n; a++) /* insertion sort */
        for (int b = a; b > 0 && k->id[b - 1] > k->id[b]; b--) {
            int t = k->id[b]; k->id[b] = k->id[b - 1]; k->id[b - 1] = t;
        }
}

static size_t key_hash(const rf_key *k, size_t cap)
{
    uint64_t h = 1469598103934665603ull;
    for (int a = 0; a < 4; a++) h = (h ^ (uint32_t)k->id[a]) * 1099511628211ull;
    h ^= h >> 32; /* the high bits into the slot: node ids reach far beyond cap */
    return (size_t)(h & (cap - 1));
}

static stc_status table_init(rf_table *t, size_t want)
{
    t->cap = 64;
    while (t->cap < 2 * want) t->cap *= 2;
    t->key = malloc(t->cap * sizeof *t->key);
    t->node = malloc(t->cap * sizeof *t->node);
    STC_CHECK(t->key && t->node, STC_ENOMEM, "refine: out of memory");
    for (size_t i = 0; i < t->cap; i++) t->node[i] = -1;
    return STC_OK;
}

static void table_free(rf_table *t)
{
    free(t->key), free(t->node);
    memset(t, 0, sizeof *t);
}

/* Slot of key k: its entry, or the empty slot where it goes. */
static size_t table_slot(const rf_table *t, const rf_key *k)
{
    size_t i = key_hash(k, t->cap);
    while (t->node[i] >= 0 && memcmp(&t->key[i], k, sizeof *k) != 0) i = (i + 1) & (t->cap - 1);
    return i;
}

static int table_get(const rf_table *t, const rf_key *k)
{
    return t->node[table_slot(t, k)];
}

/* Everything the refinement builds. */
typedef struct rf_build {
    const asp_mesh *M;
    double R_out, R_if;   /* spheres to keep nodes on (R_if 0: none) */
    rf_table tab;
    int nnew;             /* new nodes so far (ids M->nnode + i) */
    double *x;            /* [nnode_new][3] */
    unsigned char *flags; /* [nnode_new] */
    int cap;
} rf_build;

/* The node at the centre of corner set ids[0..n) (n = 2, 4, 8): found or
 * created.  Creation places it at the corners' mean and snaps it onto a
 * sphere all its corners lie on. */
static int node_at(rf_build *b, const int *ids, int n)
{
    rf_key k;
    size_t slot = 0;
    if (n < 8) {
        key_make(&k, ids, n);
        slot = table_slot(&b->tab, &k);
        if (b->tab.node[slot] >= 0) return b->tab.node[slot];
    }
    int id = b->M->nnode + b->nnew;
    double *X = b->x + 3 * (size_t)id;
    unsigned char f = 0xff;
    int out = 1, itf = 1;
    X[0] = X[1] = X[2] = 0.0;
    for (int a = 0; a < n; a++) {
        const double *y = b->M->x + 3 * (size_t)ids[a];
        for (int i = 0; i < 3; i++) X[i] += y[i] / n;
        f &= b->M->flags[ids[a]];
        out &= asp_mesh_on_sphere(b->M, ids[a], b->R_out);
        itf &= asp_mesh_on_sphere(b->M, ids[a], b->R_if);
    }
    if (n < 8 && (out || itf)) {
        double r = sqrt(X[0] * X[0] + X[1] * X[1] + X[2] * X[2]), R = out ? b->R_out : b->R_if;
        for (int i = 0; i < 3; i++) X[i] *= R / r;
    }
    if (f & ASP_NODE_SYM) X[1] = 0.0;
    b->flags[id] = f;
    if (n < 8) {
        b->tab.key[slot] = k;
        b->tab.node[slot] = id;
    }
    b->nnew++;
    return id;
}

/* The eight children of element e: sub-grid node (i, j, k) ∈ {0, 1, 2}³ is
 * the centre of the parent corners whose local coordinates match i, j, k
 * where those are even (so 1, 2, 4 or 8 corners). */
static void split(rf_build *b, int e, int *conn_out)
{
    const int *c = b->M->conn + 8 * (size_t)e;
    int sub[3][3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                int ids[8], n = 0;
                for (int a = 0; a < 2; a++)
                    for (int bb = 0; bb < 2; bb++)
                        for (int g = 0; g < 2; g++)
                            if ((i == 1 || a == i / 2) && (j == 1 || bb == j / 2) &&
                                (k == 1 || g == k / 2))
                                ids[n++] = c[CORNER_AT[a][bb][g]];
                sub[i][j][k] = n == 1 ? ids[0] : node_at(b, ids, n);
            }
    int ch = 0;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++, ch++) {
                int *o = conn_out + 8 * ch;
                for (int h = 0; h < 2; h++) {
                    o[4 * h + 0] = sub[i][j][k + h];
                    o[4 * h + 1] = sub[i + 1][j][k + h];
                    o[4 * h + 2] = sub[i + 1][j + 1][k + h];
                    o[4 * h + 3] = sub[i][j + 1][k + h];
                }
            }
}

/* Stops a refinement that would make the mesh 2-irregular: a marked element
 * with a hanging corner, or with an existing hanging node on one of its
 * edges or faces. */
static stc_status check_marked(const asp_mesh *M, const unsigned char *mark)
{
    if (M->nhang == 0) return STC_OK;
    unsigned char *hang = calloc((size_t)M->nnode, 1);
    rf_table t = {0};
    stc_status st = table_init(&t, (size_t)M->nhang);
    STC_CHECK_GOTO(hang, st, done, STC_ENOMEM, "refine: out of memory");
    if (st != STC_OK) goto done;
    for (int h = 0; h < M->nhang; h++) {
        int ids[4], n = 0;
        hang[M->hang[h]] = 1;
        for (int a = 0; a < 4 && M->hang_m[4 * h + a] >= 0; a++) ids[n++] = M->hang_m[4 * h + a];
        rf_key k;
        key_make(&k, ids, n);
        size_t s = table_slot(&t, &k);
        t.key[s] = k, t.node[s] = M->hang[h];
    }
    for (int e = 0; e < M->nelem && st == STC_OK; e++) {
        if (!mark[e]) continue;
        const int *c = M->conn + 8 * (size_t)e;
        int bad = 0;
        for (int a = 0; a < 8; a++) bad |= hang[c[a]];
        for (int g = 0; g < 12; g++) {
            int ids[2] = {c[HEX_EDGES[g][0]], c[HEX_EDGES[g][1]]};
            rf_key k;
            key_make(&k, ids, 2);
            bad |= table_get(&t, &k) >= 0;
        }
        for (int f = 0; f < 6; f++) {
            int ids[4];
            for (int a = 0; a < 4; a++) ids[a] = c[asp_hex8_faces[f][a]];
            rf_key k;
            key_make(&k, ids, 4);
            bad |= table_get(&t, &k) >= 0;
        }
        if (bad)
            st = STC_FAIL(STC_EINVAL, "refine: element %d touches a hanging node (the marked "
                          "zone must lie inside the previous refinement with a margin)", e);
    }
done:
    free(hang);
    table_free(&t);
    return st;
}

/* Hanging nodes: every new edge or face node that an unmarked element's
 * edge or face holds. */
static stc_status collect_hanging(rf_build *b, const unsigned char *mark, asp_mesh *R)
{
    const asp_mesh *M = b->M;
    int cap = M->nhang + b->nnew;
    R->hang = malloc((size_t)(cap > 0 ? cap : 1) * sizeof *R->hang);
    R->hang_m = malloc((size_t)(cap > 0 ? cap : 1) * 4 * sizeof *R->hang_m);
    R->hang_w = malloc((size_t)(cap > 0 ? cap : 1) * 4 * sizeof *R->hang_w);
    unsigned char *is = calloc((size_t)b->nnew + 1, 1);
    if (!R->hang || !R->hang_m || !R->hang_w || !is) {
        free(is);
        return STC_FAIL(STC_ENOMEM, "refine: out of memory");
    }
    R->nhang = M->nhang;
    if (M->nhang) {
        memcpy(R->hang, M->hang, (size_t)M->nhang * sizeof *R->hang);
        memcpy(R->hang_m, M->hang_m, (size_t)M->nhang * 4 * sizeof *R->hang_m);
        memcpy(R->hang_w, M->hang_w, (size_t)M->nhang * 4 * sizeof *R->hang_w);
    }
    for (int e = 0; e < M->nelem; e++) {
        if (mark[e]) continue;
        const int *c = M->conn + 8 * (size_t)e;
        for (int q = 0; q < 18; q++) {
            int ids[4], n = q < 12 ? 2 : 4;
            for (int a = 0; a < n; a++)
                ids[a] = q < 12 ? c[HEX_EDGES[q][a]] : c[asp_hex8_faces[q - 12][a]];
            rf_key k;
            key_make(&k, ids, n);
            int id = table_get(&b->tab, &k);
            if (id < 0 || is[id - M->nnode]) continue;
            is[id - M->nnode] = 1;
            int h = R->nhang++;
            R->hang[h] = id;
            for (int a = 0; a < 4; a++) {
                R->hang_m[4 * h + a] = a < n ? ids[a] : -1;
                R->hang_w[4 * h + a] = a < n ? 1.0 / n : 0.0;
            }
            R->flags[id] &= (unsigned char)~ASP_NODE_TOP;
        }
    }
    free(is);
    return STC_OK;
}

stc_status asp_mesh_refine3d(const asp_mesh *M, const unsigned char *mark, double R_outer,
                             double R_interface, asp_mesh **out)
{
    *out = NULL;
    STC_CHECK(M && M->dim == 3 && M->nen == 8, STC_EINVAL, "refine: needs a hex8 3D mesh");
    int nm = 0;
    for (int e = 0; e < M->nelem; e++) nm += mark[e] != 0;
    STC_CALL(check_marked(M, mark));
    rf_build b;
    memset(&b, 0, sizeof b);
    b.M = M, b.R_out = R_outer, b.R_if = R_interface;
    asp_mesh *R = calloc(1, sizeof *R);
    stc_status st = STC_OK;
    STC_CHECK_GOTO(R, st, done, STC_ENOMEM, "refine: out of memory");
    /* at most 19 new nodes per marked element (12 edges, 6 faces, 1 centre) */
    b.cap = 19 * nm;
    R->dim = 3, R->nen = 8;
    R->nelem = M->nelem + 7 * nm;
    b.x = malloc((size_t)(M->nnode + b.cap) * 3 * sizeof *b.x);
    b.flags = malloc((size_t)(M->nnode + b.cap) + 1);
    R->conn = malloc((size_t)R->nelem * 8 * sizeof *R->conn);
    R->region = malloc((size_t)R->nelem * sizeof *R->region);
    STC_CHECK_GOTO(b.x && b.flags && R->conn && R->region, st, done,
                   STC_ENOMEM, "refine: out of memory (%d marked elements)", nm);
    STC_CALL_GOTO(table_init(&b.tab, (size_t)b.cap), st, done);
    memcpy(b.x, M->x, (size_t)M->nnode * 3 * sizeof *b.x);
    memcpy(b.flags, M->flags, (size_t)M->nnode);
    int e_out = 0;
    for (int e = 0; e < M->nelem; e++) {
        if (mark[e]) {
            split(&b, e, R->conn + 8 * (size_t)e_out);
            for (int c = 0; c < 8; c++) R->region[e_out + c] = M->region[e];
            e_out += 8;
        } else {
            memcpy(R->conn + 8 * (size_t)e_out, M->conn + 8 * (size_t)e, 8 * sizeof *R->conn);
            R->region[e_out++] = M->region[e];
        }
    }
    R->nnode = M->nnode + b.nnew;
    R->x = b.x, R->flags = b.flags;
    b.x = NULL, b.flags = NULL;
    STC_CALL_GOTO(collect_hanging(&b, mark, R), st, done);
    *out = R;
    R = NULL;
done:
    asp_mesh_destroy(&R);
    free(b.x), free(b.flags);
    table_free(&b.tab);
    return st;
}

/* Marks the elements that reach into the band r_in < r < r_out (lateral
 * distance from the z axis) within depth d of the outer sphere R'. */
static int mark_band(const asp_mesh *M, double Rp, double r_in, double r_out, double d,
                     unsigned char *mark)
{
    int n = 0;
    for (int e = 0; e < M->nelem; e++) {
        const int *c = M->conn + 8 * (size_t)e;
        double rmin = INFINITY, rmax = 0.0, dmin = INFINITY;
        for (int a = 0; a < 8; a++) {
            const double *x = M->x + 3 * (size_t)c[a];
            double rl = hypot(x[0], x[1]);
            rmin = fmin(rmin, rl), rmax = fmax(rmax, rl);
            dmin = fmin(dmin, Rp - sqrt(rl * rl + x[2] * x[2]));
        }
        mark[e] = rmax > r_in && rmin < r_out && dmin < d;
        n += mark[e];
    }
    return n;
}

stc_status asp_mesh_refine_band(asp_mesh **M, double Rp, double R_interface, double h,
                                double a0, int levels)
{
    STC_CHECK(levels >= 0 && levels <= 2, STC_EINVAL,
              "edge refinement: levels = %d: must be in [0, 2] (a third band, one h inside "
              "the second, is empty)", levels);
    STC_CHECK(a0 > 0.0 && h > 0.0, STC_EINVAL,
              "edge refinement: a0 = %g mm, h = %g mm: both must be > 0", a0, h);
    for (int lv = 0; lv < levels; lv++) {
        /* level lv: the band a0 - (ASP_BAND_IN - lv) h ... a0 + (ASP_BAND_OUT - lv) h,
         * ASP_BAND_DEPTH - lv coarse sizes deep: each inside the last with one
         * coarse element of margin */
        double r_in = a0 - (ASP_BAND_IN - lv) * h, r_out = a0 + (ASP_BAND_OUT - lv) * h;
        double d = (ASP_BAND_DEPTH - lv) * h;
        unsigned char *mark = malloc((size_t)(*M)->nelem);
        STC_CHECK(mark, STC_ENOMEM, "edge refinement: out of memory");
        int n = mark_band(*M, Rp, r_in, r_out, d, mark);
        asp_mesh *R = NULL;
        stc_status st = n > 0 ? asp_mesh_refine3d(*M, mark, Rp, R_interface, &R) : STC_OK;
        free(mark);
        STC_CALL(st);
        if (R) {
            asp_mesh_destroy(M);
            *M = R;
        }
    }
    return STC_OK;
}
