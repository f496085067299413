/* 3D half-model mesh: volumes converge to the exact half hemisphere and
 * coating shell, every Jacobian is positive (quality bound), boundary flags
 * sit on their surfaces, regions respect the interface, the contact zone has
 * the promised size and the coating >= 4 elements; the shells' 2:1
 * coarsening makes consistent hanging nodes, and without it the mesh is the
 * uncoarsened one.
 * Set STC_MESH3D_VTK=file.vtk to dump the default mesh for eyeballing. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include "fe.h"
#include "hex_util.h"
#include "stiction/formulas.h"

static const double R = 10.0;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static asp_mesh *make_c(double t, double a, int level, int coarsen)
{
    asp_mesh_spec s = {R, t, a, level, 0.0, coarsen, 0.0};
    asp_mesh *M = NULL;
    stc_status st = asp_mesh_half3d(&s, &M);
    if (st != STC_OK) fail_msg("asp_mesh_half3d: %s", stc_errmsg());
    return M;
}

static asp_mesh *make(double t, double a, int level) { return make_c(t, a, level, 0); }

/* is_hanging[n] (caller frees) */
static unsigned char *hanging_marks(const asp_mesh *M)
{
    unsigned char *is = calloc((size_t)M->nnode, 1);
    assert_non_null(is);
    for (int h = 0; h < M->nhang; h++) is[M->hang[h]] = 1;
    return is;
}

/* Relative volume errors of the whole mesh and of the coating region. */
static void volume_errors(const asp_mesh *M, double t, double *ev, double *ec)
{
    double V = 0.0, Vc = 0.0, X[24], Rp = R + t;
    for (int e = 0; e < M->nelem; e++) {
        elem_coords(M, e, X);
        double v = hex_volume(X);
        V += v;
        if (M->region[e] == ASP_REGION_COATING) Vc += v;
    }
    *ev = fabs(V / (M_PI * Rp * Rp * Rp / 3.0) - 1.0);
    *ec = t > 0.0 ? fabs(Vc / (M_PI * (Rp * Rp * Rp - R * R * R) / 3.0) - 1.0) : 0.0;
}

/* The uncoarsened mesh (coarsen < 0): < 1 % at every level.  The default
 * coarsened mesh is chordal over 4x wider far-field cells (30° of azimuth
 * at level 0 near the equator), measured 5.0e-2 / 1.5e-2 / 4.4e-3 at levels
 * 0 / 1 / 2: only its convergence is asserted (the loss is far from the
 * contact; see the mesh3d.c header). */
static void test_volume_converges(void **state)
{
    (void)state;
    for (int coarsen = -1; coarsen <= 0; coarsen++) {
        double prev_v = 1.0, prev_c = 1.0;
        int prev_n = 0;
        for (int level = 0; level <= 2; level++) {
            asp_mesh *M = make_c(0.05, 0.1, level, coarsen);
            double ev, ec;
            volume_errors(M, 0.05, &ev, &ec);
            printf("coarsen %d level %d: %d nodes, %d hex8; volume error %.2e, coating "
                   "volume error %.2e\n", coarsen, level, M->nnode, M->nelem, ev, ec);
            if (coarsen < 0) assert_true(ev < 1e-2 && ec < 1e-2);
            assert_true(ev < 0.6 * prev_v && ec < 0.6 * prev_c);
            assert_true(M->nelem > 3 * prev_n);
            prev_v = ev, prev_c = ec, prev_n = M->nelem;
            asp_mesh_destroy(&M);
            assert_null(M);
        }
    }
}

/* Positive Jacobian at every Gauss point (via the element kernel itself)
 * and the scaled-Jacobian quality bound, over a spread of geometries. */
static void test_quality(void **state)
{
    (void)state;
    const double cases[][3] = {/* t, a_max, required worst quality */
                               {0.0, 0.1, 0.3},   {0.0, 0.003, 0.3}, {0.0, 2.5, 0.3},
                               {0.02, 0.1, 0.3},  {0.02, 0.025, 0.3}, {0.05, 0.1, 0.3},
                               {0.05, 0.025, 0.3}, {0.25, 0.25, 0.3}, {0.25, 0.1, 0.3},
                               {0.5, 0.25, 0.3},  {0.5, 0.1, 0.3},   {0.5, 0.025, 0.3},
                               {0.5, 0.003, 0.3}};
    stc_material mat = {200000.0, 0.3, 200.0};
    asp_j2 m;
    asp_j2_init(&m, &mat);
    double u[24] = {0}, fe[24];
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        asp_mesh *M = make(cases[c][0], cases[c][1], 1);
        double worst;
        assert_int_equal(asp_mesh_quality(M, &worst), STC_OK);
        int bad = 0;
        /* Gauss-point Jacobians via the kernel: a few representative cases */
        for (int e = 0; e < M->nelem && (c == 0 || c == 4 || c == 11); e++) {
            double X[24];
            elem_coords(M, e, X);
            if (asp_hex8(X, u, &m, NULL, NULL, fe, NULL, NULL, NULL) < 0) bad++;
        }
        printf("t = %-5g a_max = %-6g: %6d nodes, worst scaled Jacobian %.3f%s\n",
               cases[c][0], cases[c][1], M->nnode, worst,
               (c == 0 || c == 4 || c == 11) ? ", all Gauss-point det J > 0" : "");
        assert_int_equal(bad, 0);
        assert_true(worst > cases[c][2]);
        asp_mesh_destroy(&M);
    }
}

static void test_flags_and_regions(void **state)
{
    (void)state;
    const double t = 0.05, a = 0.1, Rp = R + t;
    asp_mesh *M = make(t, a, 1);
    unsigned char *is_h = hanging_marks(M);
    int nb = 0, ns = 0, nt = 0, base_missing = 0;
    for (int n = 0; n < M->nnode; n++) {
        const double *x = M->x + 3 * n;
        unsigned f = M->flags[n];
        assert_true(x[1] >= 0.0 && x[2] >= 0.0);
        assert_true(norm3(x) <= Rp * (1 + 1e-12));
        assert_false(f & ASP_NODE_AXIS);
        if (f & ASP_NODE_BASE) { nb++; assert_true(x[2] == 0.0); }
        else if (x[2] < 1e-9 * R) base_missing++;
        if (f & ASP_NODE_SYM) { ns++; assert_true(x[1] == 0.0); }
        int on_top = fabs(norm3(x) - Rp) < 1e-12 * Rp && hypot(x[0], x[1]) <= 3.0 * a;
        if (on_top) assert_true(f & ASP_NODE_TOP);
        if (f & ASP_NODE_TOP) {
            nt++;
            assert_true(fabs(norm3(x) - Rp) < 1e-12 * Rp);
            assert_true(hypot(x[0], x[1]) <= 3.0 * a + 1e-12);
        }
    }
    assert_int_equal(base_missing, 0);
    /* every element lies on its side of the interface |X| = R (a hanging
     * node lies on its coarse face's chord: test_hanging checks it) */
    int wrong = 0, ncoat = 0;
    for (int e = 0; e < M->nelem; e++) {
        ncoat += M->region[e] == ASP_REGION_COATING;
        for (int k = 0; k < 8; k++) {
            if (is_h[M->conn[8 * e + k]]) continue;
            double r = norm3(M->x + 3 * M->conn[8 * e + k]);
            if (M->region[e] == ASP_REGION_COATING ? r < R * (1 - 1e-12)
                                                   : r > R * (1 + 1e-12))
                wrong++;
        }
    }
    printf("base %d, sym %d, top %d nodes; %d coating elements; misplaced %d\n",
           nb, ns, nt, ncoat, wrong);
    assert_int_equal(wrong, 0);
    assert_true(nb > 0 && ns > 0 && ncoat > 0);
    free(is_h);
    asp_mesh_destroy(&M);
}

/* Lengths of the surface edges (both ends ASP_NODE_TOP, both at lateral
 * distance [r0, r1] from the axis): min and max. */
static void top_edges(const asp_mesh *M, double r0, double r1, double *emin, double *emax)
{
    *emin = 1e30, *emax = 0.0;
    for (int e = 0; e < M->nelem; e++) {
        const int *c = M->conn + 8 * e;
        for (int k = 0; k < 8; k++) {
            int n0 = c[k], n1 = c[(k & 4) | ((k + 1) & 3)];
            if (!(M->flags[n0] & M->flags[n1] & ASP_NODE_TOP)) continue;
            const double *x0 = M->x + 3 * n0, *x1 = M->x + 3 * n1;
            double q0 = hypot(x0[0], x0[1]), q1 = hypot(x1[0], x1[1]);
            if (q0 < r0 || q0 > r1 || q1 < r0 || q1 > r1) continue;
            double d[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]}, L = norm3(d);
            *emin = fmin(*emin, L), *emax = fmax(*emax, L);
        }
    }
}

/* Size at the contact: edges of surface faces within a_max of the axis are
 * ≈ h = a_max / (6·2^level); the coating has >= 4 elements on the axis. */
static void contact_zone(double t, double a, int level)
{
    asp_mesh *M = make(t, a, level);
    double h = a / (6.0 * pow(2.0, level)), emin, emax;
    top_edges(M, 0.0, a, &emin, &emax);
    /* distinct node depths on the axis inside the coating */
    int nlayer = -1;
    if (t > 0.0) {
        double seen[4096];
        int ns = 0;
        for (int n = 0; n < M->nnode && ns < 4096; n++) {
            const double *x = M->x + 3 * n;
            if (fabs(x[0]) > 1e-12 || x[1] != 0.0 || norm3(x) < R * (1 - 1e-12)) continue;
            int dup = 0;
            for (int k = 0; k < ns; k++) dup |= fabs(seen[k] - x[2]) < 1e-12;
            if (!dup) seen[ns++] = x[2];
        }
        nlayer = ns - 1;
    }
    printf("t = %g a_max = %g level %d: contact edges in [%.3f, %.3f] h (h = %.3g mm); "
           "coating layers on the axis %d\n", t, a, level, emin / h, emax / h, h, nlayer);
    assert_true(emin > 0.85 * h && emax < 1.15 * h);
    if (t > 0.0) assert_true(nlayer >= 4);
    asp_mesh_destroy(&M);
}

static void test_contact_zone(void **state)
{
    (void)state;
    contact_zone(0.0, 0.1, 0);
    contact_zone(0.0, 0.1, 1);
    contact_zone(0.02, 0.1, 1); /* coating thinner than h: 4 thin layers */
    contact_zone(0.05, 0.1, 2);
    contact_zone(0.5, 0.1, 1);  /* coating much thicker than the fine zone */
}

/* Slow shell growth near the contact (what the 3D Hertz accuracy hinges on,
 * see M3_SHELL_Q in mesh3d.c): along the axis below the contact, between
 * depths a_max and 3 a_max, every step s_k is below 1.15 × 0.1/√2^level ×
 * 3^0.3 of its depth (the old q = 1.3 grading fails this). */
static void shell_growth(int level)
{
    const double a = 0.1, Rp = R;
    asp_mesh *M = make(0.0, a, level);
    double z[4096];
    int nz = 0;
    for (int n = 0; n < M->nnode && nz < 4096; n++) {
        const double *x = M->x + 3 * n;
        if (fabs(x[0]) < 1e-12 && x[1] == 0.0) z[nz++] = Rp - x[2];
    }
    for (int i = 1; i < nz; i++) /* insertion sort by depth */
        for (int k = i; k > 0 && z[k] < z[k - 1]; k--) {
            double t = z[k]; z[k] = z[k - 1]; z[k - 1] = t;
        }
    double bound = 1.15 * 0.1 / pow(sqrt(2.0), level) * pow(3.0, 0.3), worst = 0.0;
    int n = 0;
    for (int i = 1; i < nz; i++)
        if (z[i - 1] >= a && z[i] <= 3.0 * a) worst = fmax(worst, (z[i] - z[i - 1]) / z[i]), n++;
    printf("level %d: %d axis steps in [a_max, 3 a_max], worst step/depth %.3f (bound %.3f)\n",
           level, n, worst, bound);
    assert_true(n >= 5);
    assert_true(worst < bound);
    asp_mesh_destroy(&M);
}

static void test_shell_growth(void **state)
{
    (void)state;
    shell_growth(0);
    shell_growth(1);
}

static void write_vtk(const asp_mesh *M, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return;
    fprintf(f, "# vtk DataFile Version 3.0\nstiction half3d\nASCII\n"
               "DATASET UNSTRUCTURED_GRID\nPOINTS %d double\n", M->nnode);
    for (int n = 0; n < M->nnode; n++)
        fprintf(f, "%.9g %.9g %.9g\n", M->x[3 * n], M->x[3 * n + 1], M->x[3 * n + 2]);
    fprintf(f, "CELLS %d %d\n", M->nelem, 9 * M->nelem);
    for (int e = 0; e < M->nelem; e++) {
        fprintf(f, "8");
        for (int a = 0; a < 8; a++) fprintf(f, " %d", M->conn[8 * e + a]);
        fprintf(f, "\n");
    }
    fprintf(f, "CELL_TYPES %d\n", M->nelem);
    for (int e = 0; e < M->nelem; e++) fprintf(f, "12\n");
    fprintf(f, "CELL_DATA %d\nSCALARS region int 1\nLOOKUP_TABLE default\n", M->nelem);
    for (int e = 0; e < M->nelem; e++) fprintf(f, "%d\n", M->region[e]);
    fprintf(f, "POINT_DATA %d\nSCALARS flags int 1\nLOOKUP_TABLE default\n", M->nnode);
    for (int n = 0; n < M->nnode; n++) fprintf(f, "%d\n", M->flags[n]);
    fclose(f);
}

static void test_speed_and_dump(void **state)
{
    (void)state;
    asp_mesh_spec s = {R, 0.05, 0.1, 1, 0.0, 0, 0.0};
    asp_mesh *M = NULL;
    double t0 = now();
    assert_int_equal(asp_mesh_half3d(&s, &M), STC_OK);
    double dt = now() - t0;
    printf("default level, a_max/R = 0.01: %d nodes (%d DOFs), %d hex8 in %.3f s\n",
           M->nnode, 3 * M->nnode, M->nelem, dt);
    assert_true(dt < 1.0);
    const char *path = getenv("STC_MESH3D_VTK");
    if (path) write_vtk(M, path);
    asp_mesh_destroy(&M);
}

/* coarsen < 0 is exactly the mesh without shell coarsening: node and
 * element counts recorded from the mesher without it. */
static void test_uncoarsened(void **state)
{
    (void)state;
    const struct { double t, a; int level, nnode, nelem; } c[] = {
        {0.0, 0.1, 0, 7674, 6696},      {0.05, 0.1, 0, 8831, 7776},
        {0.05, 0.1, 1, 41065, 38208},   {0.02, 0.1, 1, 46223, 43200},
        {0.5, 0.1, 1, 77171, 73152},    {0.25, 0.25, 1, 46326, 43392},
        {0.0, 2.5, 1, 23135, 21312}};
    for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
        asp_mesh *M = make_c(c[k].t, c[k].a, c[k].level, -1);
        asp_mesh *M1 = make_c(c[k].t, c[k].a, c[k].level, 1);
        asp_mesh *M2 = make(c[k].t, c[k].a, c[k].level);
        printf("t = %-4g a_max = %-4g level %d: nodes %6d / %6d / %6d (coarsen -1 / 1 / 2), "
               "hanging %d / %d\n", c[k].t, c[k].a, c[k].level, M->nnode, M1->nnode,
               M2->nnode, M1->nhang, M2->nhang);
        assert_int_equal(M->nnode, c[k].nnode);
        assert_int_equal(M->nelem, c[k].nelem);
        assert_int_equal(M->nhang, 0);
        assert_null(M->hang);
        assert_true(M1->nnode < M->nnode && M2->nnode <= M1->nnode);
        asp_mesh_destroy(&M), asp_mesh_destroy(&M1), asp_mesh_destroy(&M2);
    }
}

/* Hanging-node invariants: coordinates = the masters' weighted average,
 * weights sum to 1, masters not hanging, no hanging contact candidate or
 * base node, the masters are a face (4) or an edge (2) of some element
 * (the coarse one) that does not contain the hanging node, and every node
 * is used by an element. */
static void hanging(double t, double a, int level, int coarsen)
{
    asp_mesh *M = make_c(t, a, level, coarsen);
    unsigned char *is_h = hanging_marks(M);
    int *deg = calloc((size_t)M->nnode + 1, sizeof *deg), *adj = malloc(8 * (size_t)M->nelem * sizeof *adj);
    assert_true(deg && adj);
    for (int e = 0; e < M->nelem; e++)
        for (int k = 0; k < 8; k++) deg[M->conn[8 * e + k] + 1]++;
    for (int n = 0; n < M->nnode; n++) {
        assert_true(deg[n + 1] > 0); /* no orphan node */
        deg[n + 1] += deg[n];
    }
    int *fill = calloc((size_t)M->nnode, sizeof *fill);
    assert_non_null(fill);
    for (int e = 0; e < M->nelem; e++)
        for (int k = 0; k < 8; k++) {
            int n = M->conn[8 * e + k];
            adj[deg[n] + fill[n]++] = e;
        }
    double Rp = R + t, dmin = 1e30, lat = 1e30;
    int n4 = 0;
    assert_true(M->nhang > 0);
    for (int h = 0; h < M->nhang; h++) {
        int id = M->hang[h], *ms = M->hang_m + 4 * h, n = 0;
        const double *w = M->hang_w + 4 * h, *X = M->x + 3 * id;
        double Y[3] = {0, 0, 0}, ws = 0.0;
        assert_false(is_h[id] > 1);
        while (n < 4 && ms[n] >= 0) n++;
        assert_true(n == 2 || n == 4);
        n4 += n == 4;
        for (int k = n; k < 4; k++) assert_true(ms[k] == -1 && w[k] == 0.0);
        for (int k = 0; k < n; k++) {
            assert_true(w[k] > 0.0 && w[k] < 1.0);
            assert_false(is_h[ms[k]]);
            ws += w[k];
            for (int i = 0; i < 3; i++) Y[i] += w[k] * M->x[3 * ms[k] + i];
        }
        assert_true(fabs(ws - 1.0) < 1e-14);
        for (int i = 0; i < 3; i++) assert_true(fabs(X[i] - Y[i]) <= 1e-12 * Rp);
        assert_false(M->flags[id] & (ASP_NODE_TOP | ASP_NODE_BASE));
        int coarse = 0;
        for (int q = deg[ms[0]]; q < deg[ms[0] + 1]; q++) {
            int e = adj[q], mask = local_set(M, e, ms, n);
            if (mask < 0) continue;
            coarse++;
            assert_true(is_face_or_edge(mask, n));
            assert_true(local_set(M, e, &id, 1) < 0);
        }
        assert_true(coarse >= 1);
        double d[3] = {X[0], X[1], X[2] - Rp};
        dmin = fmin(dmin, norm3(d));
        if (norm3(X) > Rp * (1 - 1e-2)) lat = fmin(lat, hypot(X[0], X[1]));
    }
    printf("t = %-4g a_max = %g level %d coarsen %d: %6d nodes, %5d hanging (%d with 4 "
           "masters); nearest %.2f a_max from P, on the surface %.2f a_max off the axis\n",
           t, a, level, coarsen, M->nnode, M->nhang, n4, dmin / a, lat / a);
    free(deg), free(adj), free(fill), free(is_h);
    asp_mesh_destroy(&M);
}

static void test_hanging(void **state)
{
    (void)state;
    const double cases[][2] = {{0.0, 0.1}, {0.02, 0.1}, {0.5, 0.1}}; /* t, a_max */
    for (int c = 0; c < 3; c++)
        for (int level = 0; level <= 1; level++) {
            hanging(cases[c][0], cases[c][1], level, 0);
            hanging(cases[c][0], cases[c][1], level, 1);
        }
}

static void expect_bad(double Rr, double t, double a, int level, const char *needle)
{
    asp_mesh_spec s = {Rr, t, a, level, 0.0, 0, 0.0};
    asp_mesh *M = (asp_mesh *)&s; /* must be reset to NULL on failure */
    stc_error_clear();
    assert_int_equal(asp_mesh_half3d(&s, &M), STC_EINVAL);
    assert_null(M);
    if (!strstr(stc_errmsg(), needle)) fail_msg("'%s' lacks '%s'", stc_errmsg(), needle);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Largest number of contact-candidate nodes that share one distance from the
 * axis (within 1e-9 r) among those with r0 <= r <= r1: they enter the
 * contact at the same δ, so this is the size of a load curve's biggest
 * node-entry tooth there. */
static int largest_ring(const asp_mesh *M, double r0, double r1)
{
    double *r = malloc((size_t)M->nnode * sizeof *r);
    int n = 0, best = 0;
    assert_non_null(r);
    for (int i = 0; i < M->nnode; i++) {
        double q = hypot(M->x[3 * i], M->x[3 * i + 1]);
        if ((M->flags[i] & ASP_NODE_TOP) && q >= r0 && q <= r1) r[n++] = q;
    }
    qsort(r, (size_t)n, sizeof *r, cmp_double);
    for (int i = 0, j = 0; i < n; i = j) {
        while (j < n && r[j] - r[i] <= 1e-9 * r[i]) j++;
        if (j - i > best) best = j - i;
    }
    free(r);
    return best;
}

/* asp_mesh_spec.a_min (the graded core of a 3D load curve): the surface
 * edges near the axis are ~a_min/6, those around r = a_max ~a_max/6 (the
 * shells grow in proportion to the distance), the quality holds, and
 * a_min = 0 or >= a_max gives exactly the uniform-core mesh. */
static void test_graded_core(void **state)
{
    (void)state;
    double a = 0.3, amin = 0.03;
    asp_mesh_spec s = {R, 0.0, a, 0, 0.0, 0, amin};
    asp_mesh *G = NULL, *U = NULL, *U2 = NULL;
    assert_int_equal(asp_mesh_half3d(&s, &G), STC_OK);
    s.a_min = 0.0;
    assert_int_equal(asp_mesh_half3d(&s, &U), STC_OK);
    s.a_min = 2.0 * a;
    assert_int_equal(asp_mesh_half3d(&s, &U2), STC_OK);
    assert_int_equal(U->nnode, U2->nnode);
    for (int i = 0; i < 3 * U->nnode; i++) assert_true(U->x[i] == U2->x[i]);
    double c0, c1, r0, r1, q;
    top_edges(G, 0.0, 0.5 * amin, &c0, &c1);
    top_edges(G, 0.8 * a, 1.2 * a, &r0, &r1);
    assert_int_equal(asp_mesh_quality(G, &q), STC_OK);
    printf("graded core a_min = %g, a_max = %g: %d nodes (uniform core %d); edges near the "
           "axis [%.2f, %.2f] a_min/6, at r = a_max [%.2f, %.2f] a_max/6; worst quality %.3f\n",
           amin, a, G->nnode, U->nnode, c0 / (amin / 6), c1 / (amin / 6), r0 / (a / 6),
           r1 / (a / 6), q);
    assert_true(c0 > 0.7 * amin / 6 && c1 < 1.3 * amin / 6);
    assert_true(r0 > 0.4 * a / 6 && r1 < 1.6 * a / 6);
    assert_true(q > 0.3);
    /* The shells round off across the graded zone (plan_make's κ), so between
     * a few a_min and a_max the surface nodes of one shell sit at different
     * radii: only mirror images (x -> -x, and across the box's diagonals)
     * share one.  Round shells there (the uniform core's rate) put a whole
     * shell's ring, 4 m + 1 = 25 nodes, at one radius. */
    int ring = largest_ring(G, 3.0 * amin, a);
    printf("graded core: at most %d surface nodes share a radius in [3 a_min, a_max]\n", ring);
    assert_true(ring <= 4);
    asp_mesh_destroy(&G), asp_mesh_destroy(&U), asp_mesh_destroy(&U2);
}

/* Checks one coated mesh: every element positive (scaled Jacobian), on its
 * side of the interface |X| = R, >= 4 coating layers on the axis, and no
 * node row on the axis down to t + 2h closer than 0.1 of the coating's
 * spacing min(h, t/4) to the next.  Returns the number of failed checks
 * (printing them); *worst, *thin: the worst quality and the thinnest row
 * over that spacing. */
static int coated_mesh_ok(double t, double a, double n, double *worst, double *thin)
{
    asp_mesh_spec s = {R, t, a, 0, n, 0, 0.0};
    asp_mesh *M = NULL;
    if (asp_mesh_half3d(&s, &M) != STC_OK) {
        printf("  t = %.9g a_max = %.9g n = %g: %s\n", t, a, n, stc_errmsg());
        return 1;
    }
    double q = -1.0, h = a / n, sp = fmin(h, t / 4.0), Rp = R + t;
    int bad = 0;
    if (asp_mesh_quality(M, &q) != STC_OK) {
        printf("  t = %.9g a_max = %.9g n = %g: %s\n", t, a, n, stc_errmsg());
        bad++;
    }
    *worst = fmin(*worst, q);
    unsigned char *is_h = hanging_marks(M);
    int wrong = 0;
    for (int e = 0; e < M->nelem; e++)
        for (int k = 0; k < 8; k++) {
            if (is_h[M->conn[8 * e + k]]) continue;
            double r = norm3(M->x + 3 * M->conn[8 * e + k]);
            if (M->region[e] == ASP_REGION_COATING ? r < R * (1 - 1e-12) : r > R * (1 + 1e-12))
                wrong++;
        }
    free(is_h);
    /* node depths on the axis (x = y = 0 exactly), down to t + 2h */
    double z[4096];
    int nz = 0, layers = 0;
    for (int k = 0; k < M->nnode && nz < 4096; k++) {
        const double *x = M->x + 3 * k;
        if (x[0] != 0.0 || x[1] != 0.0 || x[2] < Rp - t - 2.0 * h) continue;
        int i = nz++;
        for (; i > 0 && z[i - 1] < x[2]; i--) z[i] = z[i - 1]; /* descending */
        z[i] = x[2];
        layers += x[2] >= R * (1 - 1e-12);
    }
    double gap = 1e30;
    for (int i = 1; i < nz; i++) gap = fmin(gap, z[i - 1] - z[i]);
    *thin = fmin(*thin, gap / sp);
    layers--;
    if (wrong || layers < 4 || gap < 0.1 * sp) {
        printf("  t = %.9g a_max = %.9g n = %g: %d nodes off their layer, %d coating layers on "
               "the axis, thinnest row %.3g of min(h, t/4)\n", t, a, n, wrong, layers, gap / sp);
        bad++;
    }
    asp_mesh_destroy(&M);
    return bad;
}

/* A coating about as thick as the contact is wide, ending near the depth of
 * the core's last uniform row ceil(0.8 n) h (h = a_max / n): the interface
 * row used to land above that row whenever 0.8 a_max < t <= ceil(0.8 n) h,
 * inverting the elements between them (595 of 31980 CLI normal-step meshes
 * over t/R 0.002-0.1, δ 0.5-60 ωc, E/Y 133 and 1000, n 3-12, e.g. t/R 0.016,
 * E/Y 133, δ = 1 ωc, n >= 6.3), and a sliver below it (t up to ~1e-3 h
 * deeper) inverted too.  The CLI's meshes around such cases (a_max as the
 * solver sizes it, R = 10, E/Y 133) and t placed at that row's depth
 * within -1e-3 ... +5e-2 relative. */
static void test_coating_at_core_row(void **state)
{
    (void)state;
    double t0 = now(), worst = 1.0, thin = 1e30;
    int nmesh = 0, nbad = 0;
    stc_material su = {200000.0, 0.3, 1500.0};
    stc_critical c;
    assert_int_equal(stc_critical_eval(&su, R, &c), STC_OK);
    const double tRs[] = {0.008, 0.016, 0.032, 0.064}, deltas[] = {1.0, 8.0};
    const double ns[] = {3.0, 5.0, 6.0, 6.3, 6.62469, 7.0, 8.0};
    for (size_t it = 0; it < sizeof tRs / sizeof tRs[0]; it++)
        for (size_t id = 0; id < sizeof deltas / sizeof deltas[0]; id++)
            for (size_t in = 0; in < sizeof ns / sizeof ns[0]; in++) {
                double t = tRs[it] * R, d = deltas[id] * c.omega_c;
                double a = (d <= 2.0 * c.omega_c ? 1.1 : 1.45) * sqrt((R + t) * d);
                nbad += coated_mesh_ok(t, a, ns[in], &worst, &thin);
                nmesh++;
            }
    const double eps[] = {-1e-3, 0.0, 1e-9, 1e-6, 1e-4, 1e-3, 5e-2}, as[] = {0.2, 1.0};
    const double ne[] = {3.0, 6.0, 12.0};
    for (size_t ie = 0; ie < sizeof eps / sizeof eps[0]; ie++)
        for (size_t ia = 0; ia < sizeof as / sizeof as[0]; ia++)
            for (size_t in = 0; in < sizeof ne / sizeof ne[0]; in++) {
                double t = ceil(0.8 * ne[in]) * as[ia] / ne[in] * (1.0 + eps[ie]);
                nbad += coated_mesh_ok(t, as[ia], ne[in], &worst, &thin);
                nmesh++;
            }
    printf("coating at the core's last uniform row: %d meshes, %d failed; worst scaled "
           "Jacobian %.3f, thinnest axis row %.2f of min(h, t/4); %.2f s\n",
           nmesh, nbad, worst, thin, now() - t0);
    assert_int_equal(nbad, 0);
    assert_true(worst > 0.3);
}

static void test_invalid(void **state)
{
    (void)state;
    expect_bad(-1.0, 0.0, 0.1, 1, "R = -1");
    expect_bad(10.0, -0.1, 0.1, 1, "t = -0.1");
    expect_bad(10.0, 0.0, 0.0, 1, "a_max = 0");
    expect_bad(10.0, 0.0, 0.1, -1, "level = -1");
    expect_bad(10.0, 0.0, 8.0, 1, "does not fit"); /* a_max = 6 fits since the 1.0 a_max core */
    asp_mesh_spec s = {10.0, 0.0, 0.1, 1, 0.0, 3, 0.0};
    asp_mesh *M = NULL;
    assert_int_equal(asp_mesh_half3d(&s, &M), STC_EINVAL);
    assert_null(M);
    assert_non_null(strstr(stc_errmsg(), "coarsen = 3"));
    printf("invalid specs rejected with messages\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_volume_converges),
        cmocka_unit_test(test_quality),
        cmocka_unit_test(test_flags_and_regions),
        cmocka_unit_test(test_contact_zone),
        cmocka_unit_test(test_shell_growth),
        cmocka_unit_test(test_speed_and_dump),
        cmocka_unit_test(test_uncoarsened),
        cmocka_unit_test(test_hanging),
        cmocka_unit_test(test_graded_core),
        cmocka_unit_test(test_coating_at_core_row),
        cmocka_unit_test(test_invalid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
