/* Local 2:1 refinement of the 3D mesh (asperity/refine3d.c): a band around
 * a contact edge, one and two levels deep, on uncoated and coated meshes.
 * The refined mesh fills the same volume, keeps its quality, keeps its
 * surface and interface nodes on their spheres, and its hanging nodes are
 * consistent (masters an edge or face of a coarse element that does not use
 * the node, never hanging themselves, weights summing to one); surface areas
 * are unchanged and none sits on a hanging node; a refinement that would
 * leave a node hanging from a hanging node is refused. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fe.h"
#include "hex_util.h"
#include "tangential.h"

static const double R = 10.0;

static double volume(const asp_mesh *M, int region)
{
    double V = 0.0, X[24];
    for (int e = 0; e < M->nelem; e++) {
        if (region >= 0 && M->region[e] != region) continue;
        elem_coords(M, e, X);
        V += hex_volume(X);
    }
    return V;
}

static asp_mesh *make(double t, double a)
{
    asp_mesh_spec s = {R, t, a, 0, 0.0, 0, 0.0};
    asp_mesh *M = NULL;
    if (asp_mesh_half3d(&s, &M) != STC_OK) fail_msg("asp_mesh_half3d: %s", stc_errmsg());
    return M;
}

/* Hanging-node invariants of M; returns how many hanging nodes were moved
 * off their masters' average onto a sphere. */
static int check_hanging(const asp_mesh *M, double Rp, double Ri, double h)
{
    unsigned char *is_h = calloc((size_t)M->nnode, 1);
    assert_non_null(is_h);
    for (int k = 0; k < M->nhang; k++) is_h[M->hang[k]]++;
    int near = 0;
    for (int k = 0; k < M->nhang; k++) {
        int id = M->hang[k], *ms = M->hang_m + 4 * k, n = 0;
        const double *w = M->hang_w + 4 * k, *X = M->x + 3 * id;
        double Y[3] = {0, 0, 0}, ws = 0.0;
        assert_int_equal(is_h[id], 1);
        while (n < 4 && ms[n] >= 0) n++;
        assert_true(n == 2 || n == 4);
        for (int a = 0; a < n; a++) {
            assert_false(is_h[ms[a]]);
            ws += w[a];
            for (int i = 0; i < 3; i++) Y[i] += w[a] * M->x[3 * ms[a] + i];
        }
        assert_true(fabs(ws - 1.0) < 1e-14);
        assert_false(M->flags[id] & (ASP_NODE_TOP | ASP_NODE_BASE));
        /* on the masters' average, or moved radially onto a sphere by at
         * most the chord's sag (h²/(8 R) for an element of size h) */
        double d[3] = {X[0] - Y[0], X[1] - Y[1], X[2] - Y[2]};
        if (norm3(d) > 1e-12 * Rp) {
            near++;
            double r = norm3(X);
            assert_true(fabs(r - Rp) < 1e-12 * Rp || (Ri > 0.0 && fabs(r - Ri) < 1e-12 * Ri));
            assert_true(norm3(d) < h * h / R);
        }
        /* some element holds the masters as an edge or face without the node */
        int coarse = 0;
        for (int e = 0; e < M->nelem && !coarse; e++) {
            int mask = local_set(M, e, ms, n);
            if (mask >= 0 && is_face_or_edge(mask, n) && local_set(M, e, &id, 1) < 0) coarse = 1;
        }
        assert_true(coarse);
    }
    free(is_h);
    return near;
}

/* Band refinement of one mesh, one and two levels, against the unrefined. */
static void band(double t, double a)
{
    asp_mesh *M0 = make(t, a);
    double Rp = R + t, Ri = t > 0.0 ? R : 0.0, h = a / 6.0, a0 = a / 1.3, q0, V0 = volume(M0, -1);
    double Vc0 = t > 0.0 ? volume(M0, ASP_REGION_COATING) : 0.0;
    assert_int_equal(asp_mesh_quality(M0, &q0), STC_OK);
    double *A0 = malloc((size_t)M0->nnode * sizeof *A0), S0 = 0.0;
    assert_non_null(A0);
    assert_int_equal(asp_surface_node_areas_disc(M0, Rp, 1.2 * a0, A0), STC_OK);
    for (int i = 0; i < M0->nnode; i++) S0 += A0[i];
    int prev_nodes = M0->nnode;
    for (int levels = 1; levels <= 2; levels++) {
        asp_mesh *M = make(t, a);
        assert_int_equal(asp_mesh_refine_band(&M, Rp, Ri, h, a0, levels), STC_OK);
        assert_true(M->nnode > prev_nodes);
        prev_nodes = M->nnode;
        double q, V = volume(M, -1);
        assert_int_equal(asp_mesh_quality(M, &q), STC_OK);
        /* the refined nodes on the sphere add the sag of the coarse chords */
        assert_true(fabs(V / V0 - 1.0) < 1e-5);
        if (t > 0.0) assert_true(fabs(volume(M, ASP_REGION_COATING) / Vc0 - 1.0) < 1e-3);
        assert_true(q >= 0.95 * q0);
        int near = check_hanging(M, Rp, Ri, h);
        /* surface nodes of the refinement stay on the sphere, flags follow */
        int top = 0;
        for (int i = M0->nnode; i < M->nnode; i++) {
            if (!(M->flags[i] & ASP_NODE_TOP)) continue;
            top++;
            assert_true(fabs(norm3(M->x + 3 * i) / Rp - 1.0) < 1e-12);
            double r = hypot(M->x[3 * i], M->x[3 * i + 1]);
            assert_true(r > a0 - 2.5 * h && r < a0 + 3.5 * h);
        }
        assert_true(top > 0);
        double *A = malloc((size_t)M->nnode * sizeof *A), S = 0.0;
        assert_non_null(A);
        assert_int_equal(asp_surface_node_areas_disc(M, Rp, 1.2 * a0, A), STC_OK);
        for (int i = 0; i < M->nnode; i++) S += A[i];
        for (int k = 0; k < M->nhang; k++) assert_true(A[M->hang[k]] == 0.0);
        /* the disc's area on a finer surface: the same within the sag */
        assert_true(fabs(S / S0 - 1.0) < 1e-4);
        printf("t = %-4g a_max = %g, %d level(s): %5d -> %5d nodes, %4d -> %4d hanging (%d "
               "on a sphere), quality %.3f -> %.3f, volume %+.1e, disc area %+.1e\n",
               t, a, levels, M0->nnode, M->nnode, M0->nhang, M->nhang, near, q0, q,
               V / V0 - 1.0, S / S0 - 1.0);
        free(A);
        asp_mesh_destroy(&M);
    }
    free(A0);
    asp_mesh_destroy(&M0);
}

static void test_band(void **state)
{
    (void)state;
    band(0.0, 0.3);
    band(0.05, 0.3);  /* coating rows through the band */
    band(0.5, 0.3);   /* coating deeper than the band */
}

/* Marking every element touches the shells' hanging nodes: refused. */
static void test_refused(void **state)
{
    (void)state;
    asp_mesh *M = make(0.0, 0.3), *Rm = (asp_mesh *)M;
    assert_true(M->nhang > 0);
    unsigned char *mark = malloc((size_t)M->nelem);
    assert_non_null(mark);
    memset(mark, 1, (size_t)M->nelem);
    stc_error_clear();
    assert_int_equal(asp_mesh_refine3d(M, mark, R, 0.0, &Rm), STC_EINVAL);
    assert_null(Rm);
    assert_non_null(strstr(stc_errmsg(), "hanging node"));
    free(mark);
    asp_mesh_destroy(&M);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_band),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
