/* Assembly of the asperity FE model: the sparsity pattern of K from the
 * mesh (hanging nodes coupled through their masters), the element → matrix
 * scatter maps, the element colouring of the threaded loop, the elastic K
 * assembled once, and the element loop that evaluates the internal force
 * and the tangent at the current displacement.  Separate from the Newton
 * iteration (newton.c) and the linear solver (linsolve.c): it fills the
 * solver's fint, stresses and states and the linear solver's value arrays,
 * and nothing else; terms of other models (the ramp's stick-law springs)
 * come through the solver's hooks (solver_impl.h).
 *
 * Cost: the element loop is ~1-5 ms on an axisymmetric mesh, so the work
 * is the NUMBER of evaluations; the elastic elements (most of the mesh)
 * evaluate only their stresses and internal force (build_elastic_K), the
 * plastic ones add their tangent minus the elastic one.
 */
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"

/* The assembly's own state (s->as). */
struct asp_asm {
    int ncolor, *cptr, *celem; /* element colours (no shared node within one):
                                  celem[cptr[c] .. cptr[c+1]); ncolor 0: none */
    int *emap;            /* [nelem][nde][nde] position in K's values or -1 */
    int *hidx;            /* [nnode] hanging-node index (mesh->hang) or -1; NULL if none */
    int *hoff;            /* [nelem] start in hpos of an element that uses a hanging
                             node (scatter_hang), else -1; NULL if none */
    int *hpos;            /* positions in K's values of those elements' T^T Ke T terms */
    double *kel;          /* [nelem][nde (nde + 1) / 2] elastic Ke, upper triangles */
    double *kglob;        /* [nnz(K)] the elastic K (build_elastic_K), NULL until built */
    unsigned char *eplastic; /* [nelem] plastic at the last assembly with K */
    int n_asm;            /* element-loop evaluations (cumulative) */
    double t_asm;         /* their wall time, s */
};

/* hidx and hoff from the mesh's hanging nodes (none: both NULL); hoff is
 * 0 for an element with a hanging node until build_hang_map sets it. */
static stc_status index_hanging(asp_solver *s)
{
    asp_asm *A = s->as;
    const asp_mesh *m = s->mesh;
    if (m->nhang == 0) return STC_OK;
    A->hidx = malloc((size_t)m->nnode * sizeof *A->hidx);
    A->hoff = malloc((size_t)m->nelem * sizeof *A->hoff);
    STC_CHECK(A->hidx && A->hoff, STC_ENOMEM, "solver: out of memory");
    for (int i = 0; i < m->nnode; i++) A->hidx[i] = -1;
    for (int k = 0; k < m->nhang; k++) A->hidx[m->hang[k]] = k;
    for (int e = 0; e < m->nelem; e++) {
        A->hoff[e] = -1;
        for (int a = 0; a < m->nen; a++)
            if (A->hidx[m->conn[m->nen * e + a]] >= 0) A->hoff[e] = 0;
    }
    return STC_OK;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Nodes element e couples, a hanging node replaced by its masters
 * (duplicates possible); returns the count (<= 4 nen). */
static int eff_nodes(const asp_mesh *m, const int *hidx, int e, int *out)
{
    int k = 0;
    for (int a = 0; a < m->nen; a++) {
        int n = m->conn[m->nen * e + a], h = hidx ? hidx[n] : -1;
        if (h < 0) {
            out[k++] = n;
            continue;
        }
        for (int b = 0; b < 4; b++)
            if (m->hang_m[4 * h + b] >= 0) out[k++] = m->hang_m[4 * h + b];
    }
    return k;
}

/* Node adjacency through elements (a hanging node's coupling goes to its
 * masters; every node is its own neighbour, so a hanging node keeps its
 * diagonal): nb[ptr[i] .. ptr[i+1]) sorted, unique. */
static stc_status node_graph(const asp_mesh *m, const int *hidx, int **ptr_out, int **nb_out)
{
    int n = m->nnode, en[32];
    int *cnt = calloc((size_t)n + 1, sizeof *cnt);
    STC_CHECK(cnt, STC_ENOMEM, "solver: out of memory");
    for (int i = 0; i < n; i++) cnt[i + 1] = 1;
    for (int e = 0; e < m->nelem; e++) {
        int k = eff_nodes(m, hidx, e, en);
        for (int a = 0; a < k; a++) cnt[en[a] + 1] += k;
    }
    for (int i = 0; i < n; i++) cnt[i + 1] += cnt[i];
    int *nb = malloc((size_t)cnt[n] * sizeof *nb), *fill = malloc((size_t)n * sizeof *fill);
    if (!nb || !fill) {
        free(cnt), free(nb), free(fill);
        return STC_FAIL(STC_ENOMEM, "solver: out of memory");
    }
    memcpy(fill, cnt, (size_t)n * sizeof *fill);
    for (int i = 0; i < n; i++) nb[fill[i]++] = i;
    for (int e = 0; e < m->nelem; e++) {
        int k = eff_nodes(m, hidx, e, en);
        for (int a = 0; a < k; a++)
            for (int b = 0; b < k; b++) nb[fill[en[a]]++] = en[b];
    }
    /* sort and compact in place */
    int w = 0;
    for (int i = 0; i < n; i++) {
        int lo = cnt[i], hi = cnt[i + 1];
        qsort(nb + lo, (size_t)(hi - lo), sizeof *nb, cmp_int);
        cnt[i] = w;
        for (int k = lo; k < hi; k++)
            if (k == lo || nb[k] != nb[k - 1]) nb[w++] = nb[k];
    }
    cnt[n] = w;
    free(fill);
    *ptr_out = cnt;
    *nb_out = nb;
    return STC_OK;
}

/* The DOFs of element e with each DOF of a hanging node replaced by its
 * masters' (gi) and weights (gw); gn: how many per element DOF. */
static void hang_expand(const asp_solver *s, int e, int gi[24][4], double gw[24][4], int gn[24])
{
    const asp_mesh *m = s->mesh;
    const int *c = m->conn + (size_t)s->nen * e;
    int d = s->dim;
    for (int a = 0; a < s->nde; a++) {
        int n = c[a / d], h = s->as->hidx[n];
        gn[a] = 0;
        if (h < 0) {
            gi[a][0] = d * n + a % d, gw[a][0] = 1.0, gn[a] = 1;
            continue;
        }
        for (int b = 0; b < 4; b++)
            if (m->hang_m[4 * h + b] >= 0) {
                gi[a][gn[a]] = d * m->hang_m[4 * h + b] + a % d;
                gw[a][gn[a]++] = m->hang_w[4 * h + b];
            }
    }
}

/* hoff/hpos: for every element with a hanging node, the positions in K->x
 * of its expanded (a, b, master of a, master of b) terms, in scatter_hang's
 * order (-1 below the diagonal), looked up once per mesh. */
static stc_status build_hang_map(asp_solver *s)
{
    asp_asm *A = s->as;
    int gi[24][4], gn[24], nde = s->nde;
    double gw[24][4];
    size_t n = 0;
    for (int e = 0; e < s->mesh->nelem; e++) {
        if (A->hoff[e] < 0) continue;
        hang_expand(s, e, gi, gw, gn);
        int t = 0;
        for (int a = 0; a < nde; a++) t += gn[a];
        n += (size_t)t * t;
    }
    STC_CHECK(n <= INT_MAX, STC_ENOMEM, "solver: %zu hanging-node terms", n);
    A->hpos = malloc((n ? n : 1) * sizeof *A->hpos);
    STC_CHECK(A->hpos, STC_ENOMEM, "solver: out of memory for the hanging-node map");
    n = 0;
    for (int e = 0; e < s->mesh->nelem; e++) {
        if (A->hoff[e] < 0) continue;
        A->hoff[e] = (int)n;
        hang_expand(s, e, gi, gw, gn);
        for (int a = 0; a < nde; a++)
            for (int b = 0; b < nde; b++)
                for (int ka = 0; ka < gn[a]; ka++)
                    for (int kb = 0; kb < gn[b]; kb++) {
                        int I = gi[a][ka], J = gi[b][kb];
                        A->hpos[n++] = I <= J ? asp_ls_pos(s->ls, I, J) : -1;
                    }
    }
    return STC_OK;
}

/* Upper-triangular CSC pattern of K, DOF by DOF from the node adjacency:
 * *Kp [ndof + 1] and *Ki [Kp[ndof]] returned new (the caller frees). */
stc_status asp_asm_pattern(const asp_solver *s, int **Kp_out, int **Ki_out)
{
    const asp_mesh *m = s->mesh;
    int d = s->dim, *ptr = NULL, *nb = NULL;
    STC_CALL(node_graph(m, s->as->hidx, &ptr, &nb));
    size_t nnz = 0;
    for (int i = 0; i < m->nnode; i++)
        for (int k = ptr[i]; k < ptr[i + 1]; k++)
            for (int c = 0; c < d; c++)
                for (int r = 0; r < d; r++)
                    nnz += (size_t)(nb[k] * d + r <= i * d + c);
    int *Kp = malloc(((size_t)s->ndof + 1) * sizeof *Kp), *Ki = malloc((nnz ? nnz : 1) * sizeof *Ki);
    if (!Kp || !Ki || nnz > INT_MAX) {
        free(ptr), free(nb), free(Kp), free(Ki);
        return STC_FAIL(STC_ENOMEM, "solver: cannot allocate the %zu-entry matrix", nnz);
    }
    int w = 0;
    for (int i = 0; i < m->nnode; i++)
        for (int c = 0; c < d; c++) {
            int col = i * d + c;
            Kp[col] = w;
            for (int k = ptr[i]; k < ptr[i + 1]; k++)
                for (int r = 0; r < d; r++)
                    if (nb[k] * d + r <= col) Ki[w++] = nb[k] * d + r;
        }
    Kp[s->ndof] = w;
    free(ptr), free(nb);
    *Kp_out = Kp, *Ki_out = Ki;
    return STC_OK;
}

/* The element scatter map emap (and the hanging-node one) into the linear
 * solver's value arrays. */
stc_status asp_asm_maps(asp_solver *s)
{
    asp_asm *A = s->as;
    const asp_mesh *m = s->mesh;
    int d = s->dim;
    size_t nmap = (size_t)m->nelem * s->nde * s->nde;
    A->emap = malloc(nmap * sizeof *A->emap);
    STC_CHECK(A->emap, STC_ENOMEM, "solver: out of memory");
    for (int e = 0; e < m->nelem; e++)
        for (int a = 0; a < s->nde; a++)
            for (int b = 0; b < s->nde; b++) {
                int I = m->conn[s->nen * e + a / d] * d + a % d;
                int J = m->conn[s->nen * e + b / d] * d + b % d;
                size_t at = ((size_t)e * s->nde + a) * s->nde + b;
                A->emap[at] = I <= J && !(A->hoff && A->hoff[e] >= 0) ? asp_ls_pos(s->ls, I, J) : -1;
            }
    return A->hoff ? build_hang_map(s) : STC_OK;
}

/* ---- assembly -------------------------------------------------------------- */

void asp_node_u(const asp_solver *s, const double *u, int n, double *out)
{
    const asp_asm *A = s->as;
    int d = s->dim, h = A->hidx ? A->hidx[n] : -1;
    if (h < 0) {
        for (int i = 0; i < d; i++) out[i] = u[d * n + i];
        return;
    }
    const int *mm = s->mesh->hang_m + 4 * h;
    const double *w = s->mesh->hang_w + 4 * h;
    for (int i = 0; i < d; i++) out[i] = 0.0;
    for (int b = 0; b < 4; b++)
        if (mm[b] >= 0)
            for (int i = 0; i < d; i++) out[i] += w[b] * u[d * mm[b] + i];
}

/* Node coordinates of element e, X [nen][dim]. */
static void element_X(const asp_solver *s, int e, double *X)
{
    const asp_mesh *m = s->mesh;
    const int *c = m->conn + (size_t)s->nen * e;
    for (int a = 0; a < s->nen; a++)
        for (int i = 0; i < s->dim; i++) X[s->dim * a + i] = m->x[s->dim * c[a] + i];
}

/* Element e at s->u: fe, Ke (if want_K), stress and state; < 0 if inverted. */
static int element(asp_solver *s, int e, int want_K, double *fe, double *Ke, double *Kp)
{
    const asp_mesh *m = s->mesh;
    int d = s->dim, nen = s->nen;
    double X[24], ue[24];
    const int *c = m->conn + (size_t)nen * e;
    element_X(s, e, X);
    for (int a = 0; a < nen; a++) asp_node_u(s, s->u, c[a], ue + d * a);
    size_t q0 = (size_t)e * s->nqp;
    const asp_j2 *mat = &s->mat[m->region[e]];
    return d == 2 ? asp_quad4_axi(X, ue, mat, s->st_old + q0, s->st_new + q0, fe,
                                  want_K ? Ke : NULL, Kp, s->sig + 6 * q0)
                  : asp_hex8(X, ue, mat, s->st_old + q0, s->st_new + q0, fe,
                             want_K ? Ke : NULL, Kp, s->sig + 6 * q0);
}

/* Scatter of an element with hanging nodes: each DOF of a hanging node
 * goes to its masters' with their weights (K += T^T Ke T, f += T^T fe). */
static void scatter_hang(asp_solver *s, int e, int want_K, const double *fe, const double *Ke,
                         const double *Kp, int atomic)
{
    asp_asm *A = s->as;
    int nde = s->nde, gi[24][4], gn[24];
    double gw[24][4], *Kx, *Kk, *Kd, *f = s->fint;
    asp_ls_values(s->ls, &Kx, &Kd, &Kk);
    hang_expand(s, e, gi, gw, gn);
    for (int a = 0; a < nde; a++)
        for (int k = 0; k < gn[a]; k++) {
            double v = gw[a][k] * fe[a];
            if (atomic) {
#pragma omp atomic
                f[gi[a][k]] += v;
            } else {
                f[gi[a][k]] += v;
            }
        }
    if (!want_K) return;
    const int *pos = A->hpos + A->hoff[e];
    for (int a = 0; a < nde; a++)
        for (int b = 0; b < nde; b++)
            for (int ka = 0; ka < gn[a]; ka++)
                for (int kb = 0; kb < gn[b]; kb++, pos++) {
                    if (*pos < 0) continue;
                    double ab = Ke[a * nde + b], ba = Ke[b * nde + a], ww = gw[a][ka] * gw[b][kb];
                    double v = ww * Kp[a * nde + b], k = ww * 0.5 * (ab - ba);
                    double dd = ww * 0.5 * (ab + ba) - v;
                    if (atomic) {
#pragma omp atomic
                        Kx[*pos] += v;
                        if (k != 0.0) {
#pragma omp atomic
                            Kk[*pos] += k;
                        }
                        if (dd != 0.0) {
#pragma omp atomic
                            Kd[*pos] += dd;
                        }
                    } else {
                        Kx[*pos] += v, Kk[*pos] += k, Kd[*pos] += dd;
                    }
                }
}

/* Scatter one element into fint and K; atomic when threads share them. */
static void scatter(asp_solver *s, int e, int want_K, const double *fe, const double *Ke,
                    const double *Kp, int atomic, int elastic)
{
    asp_asm *A = s->as;
    int nde = s->nde, d = s->dim;
    if (A->hoff && A->hoff[e] >= 0) {
        scatter_hang(s, e, want_K, fe, Ke, Kp, atomic);
        return;
    }
    const int *c = s->mesh->conn + (size_t)s->nen * e;
    const int *map = A->emap + (size_t)e * nde * nde;
    double *Kx, *Kk, *Kd, *f = s->fint;
    asp_ls_values(s->ls, &Kx, &Kd, &Kk);
    if (!atomic) {
        for (int a = 0; a < nde; a++) f[d * c[a / d] + a % d] += fe[a];
        if (want_K && elastic) { /* Ke = Kp, symmetric: nothing for Kk, Kd */
            for (int k = 0; k < nde * nde; k++)
                if (map[k] >= 0) Kx[map[k]] += Ke[k];
        } else if (want_K)
            for (int a = 0; a < nde; a++)
                for (int b = 0; b < nde; b++) {
                    int k = map[a * nde + b];
                    if (k < 0) continue;
                    double ab = Ke[a * nde + b], ba = Ke[b * nde + a], p = Kp[a * nde + b];
                    Kx[k] += p, Kk[k] += 0.5 * (ab - ba), Kd[k] += 0.5 * (ab + ba) - p;
                }
        return;
    }
    for (int a = 0; a < nde; a++) {
#pragma omp atomic
        f[d * c[a / d] + a % d] += fe[a];
    }
    if (want_K)
        for (int a = 0; a < nde; a++)
            for (int b = 0; b < nde; b++) {
                int k = map[a * nde + b];
                if (k < 0) continue;
                double ab = Ke[a * nde + b], ba = Ke[b * nde + a], p = Kp[a * nde + b];
                double dd = 0.5 * (ab + ba) - p;
#pragma omp atomic
                Kx[k] += p;
                if (ab != ba) {
#pragma omp atomic
                    Kk[k] += 0.5 * (ab - ba);
                }
                if (dd != 0.0) {
#pragma omp atomic
                    Kd[k] += dd;
                }
            }
}

/* Greedy element colouring for the threaded assembly: an element takes the
 * lowest colour none of its nodes (a hanging node's masters included) has
 * yet; a node's colours are a 64-bit mask, so a mesh needing more keeps the
 * atomic scatter (ncolor 0).  Measured on the 3D graded level-0 load curve
 * to 60 ωc (30.6k DOFs, 2 threads): docs/design.md §3.6. */
static stc_status build_colors(asp_solver *s)
{
    asp_asm *A = s->as;
    const asp_mesh *m = s->mesh;
    int ne = m->nelem, en[40], *col = malloc((size_t)ne * sizeof *col);
    unsigned long long *used = calloc((size_t)m->nnode, sizeof *used);
    if (!col || !used) {
        free(col), free(used);
        return STC_FAIL(STC_ENOMEM, "solver: out of memory");
    }
    int nc = 0;
    for (int e = 0; e < ne && nc >= 0; e++) {
        int k = eff_nodes(m, A->hidx, e, en);
        for (int a = 0; a < m->nen; a++) en[k++] = m->conn[(size_t)m->nen * e + a];
        unsigned long long taken = 0;
        for (int a = 0; a < k; a++) taken |= used[en[a]];
        if (taken == ~0ULL) {
            nc = -1; /* more than 64 colours */
            break;
        }
        int c = 0;
        while (taken >> c & 1ULL) c++;
        col[e] = c;
        for (int a = 0; a < k; a++) used[en[a]] |= 1ULL << c;
        if (c + 1 > nc) nc = c + 1;
    }
    free(used);
    if (nc <= 0) {
        free(col);
        return STC_OK;
    }
    A->cptr = calloc((size_t)nc + 1, sizeof *A->cptr);
    A->celem = malloc((size_t)ne * sizeof *A->celem);
    if (!A->cptr || !A->celem) {
        free(col);
        return STC_FAIL(STC_ENOMEM, "solver: out of memory");
    }
    for (int e = 0; e < ne; e++) A->cptr[col[e] + 1]++;
    for (int c = 0; c < nc; c++) A->cptr[c + 1] += A->cptr[c];
    int *fill = malloc((size_t)nc * sizeof *fill);
    if (!fill) {
        free(col);
        return STC_FAIL(STC_ENOMEM, "solver: out of memory");
    }
    memcpy(fill, A->cptr, (size_t)nc * sizeof *fill);
    for (int e = 0; e < ne; e++) A->celem[fill[col[e]]++] = e;
    free(fill), free(col);
    A->ncolor = nc;
    return STC_OK;
}

/* The elastic stiffness, once per mesh: every element's elastic Ke (its
 * upper triangle kept in kel) summed into kglob.  asp_assemble() then
 * starts K from kglob and adds, for the elements plastic in this
 * iteration only, their tangent minus their elastic Ke: the elastic ones
 * (most of the mesh) only evaluate their stresses and internal force.
 * Measured: docs/design.md §3.6. */
static stc_status build_elastic_K(asp_solver *s)
{
    const asp_mesh *m = s->mesh;
    int nde = s->nde, d = s->dim, npk = nde * (nde + 1) / 2;
    size_t nnz = asp_ls_nnz(s->ls);
    double *Kx, *Kd, *Kk;
    asp_ls_values(s->ls, &Kx, &Kd, &Kk);
    s->as->kglob = malloc(nnz * sizeof *s->as->kglob);
    s->as->kel = malloc((size_t)m->nelem * npk * sizeof *s->as->kel);
    STC_CHECK(s->as->kglob && s->as->kel, STC_ENOMEM, "solver: out of memory for the elastic stiffness");
    memset(Kx, 0, nnz * sizeof(double));
    for (int e = 0; e < m->nelem; e++) {
        double X[24], zero[24] = {0}, fe[24] = {0}, Ke[24 * 24];
        element_X(s, e, X);
        const asp_j2 *mat = &s->mat[m->region[e]];
        int np = d == 2 ? asp_quad4_axi(X, zero, mat, NULL, NULL, NULL, Ke, NULL, NULL)
                        : asp_hex8(X, zero, mat, NULL, NULL, NULL, Ke, NULL, NULL);
        STC_CHECK(np == 0, STC_EINVAL, "mesh: element %d has a non-positive Jacobian", e);
        double *k = s->as->kel + (size_t)npk * e;
        for (int i = 0; i < nde; i++)
            for (int j = i; j < nde; j++) *k++ = Ke[i * nde + j];
        scatter(s, e, 1, fe, Ke, Ke, 0, 1);
    }
    memcpy(s->as->kglob, Kx, nnz * sizeof *s->as->kglob);
    return STC_OK;
}

/* One element's share: fe always; with want_K and plastic points, its
 * tangent minus its elastic Ke (already in K from kglob).  An element
 * plastic at the last assembly with K is evaluated with its tangent at
 * once; any other is evaluated without, and again (the same state update,
 * now with D) only if it turned out plastic. */
static int element_share(asp_solver *s, int e, int want_K, int atomic)
{
    asp_asm *A = s->as;
    double fe[24], Ke[24 * 24], Kp[24 * 24];
    int withK = want_K && A->eplastic[e];
    int np = element(s, e, withK, fe, Ke, withK ? Kp : NULL);
    if (np > 0 && want_K && !withK) np = element(s, e, 1, fe, Ke, Kp), withK = 1;
    if (want_K && np >= 0) A->eplastic[e] = np > 0;
    if (np <= 0 || !withK) {
        if (np >= 0) scatter(s, e, 0, fe, NULL, NULL, atomic, 1);
        return np;
    }
    int nde = s->nde;
    const double *k = A->kel + (size_t)e * (nde * (nde + 1) / 2);
    for (int i = 0; i < nde; i++)
        for (int j = i; j < nde; j++, k++) {
            Ke[i * nde + j] -= *k, Kp[i * nde + j] -= *k;
            if (j != i) Ke[j * nde + i] -= *k, Kp[j * nde + i] -= *k;
        }
    scatter(s, e, 1, fe, Ke, Kp, atomic, 0);
    return np;
}

/* Internal forces (and K if want_K) at s->u from the converged state st_old.
 * Fills fint, sig, st_new.  Returns STC_ENOCONV if an element inverted.
 * Threads: s->nthr (1 for the axisymmetric model, where the atomic scatter
 * of two threads was measured slower than one thread). */
stc_status asp_assemble(asp_solver *s, int want_K)
{
    asp_asm *A = s->as;
    const asp_mesh *m = s->mesh;
    int bad = -1, nthr = s->nthr;
    double t0 = omp_get_wtime();
    A->n_asm++;
    memset(s->fint, 0, (size_t)s->ndof * sizeof *s->fint);
    s->k_fresh = 0;
    if (want_K) {
        if (!A->kglob) STC_CALL(build_elastic_K(s));
        asp_ls_begin_tangent(s->ls, A->kglob);
    }
    if (A->ncolor > 0) {
        /* colour by colour: no two elements of a colour share a node, so
         * the scatter needs no atomics, and every entry of K and fint sums
         * its terms in colour order whatever the thread count: the same K
         * on 1 or 2 threads (the atomic scatter's order varied by run).
         * Dynamic: the plastic elements (tangent, return map) cost several
         * elastic ones and cluster in the core; measured on the graded 3D
         * curve (n = 4, 16k DOFs, 2 threads): element loop 5.8 -> 3.7 s */
#pragma omp parallel num_threads(nthr) if (nthr > 1)
        for (int c = 0; c < A->ncolor; c++) {
#pragma omp for schedule(dynamic, 8)
            for (int l = A->cptr[c]; l < A->cptr[c + 1]; l++)
                if (element_share(s, A->celem[l], want_K, 0) < 0) {
#pragma omp critical
                    bad = A->celem[l];
                }
        }
    } else {
#pragma omp parallel for schedule(static) num_threads(nthr) if (nthr > 1)
        for (int e = 0; e < m->nelem; e++)
            if (element_share(s, e, want_K, nthr > 1) < 0) {
#pragma omp critical
                bad = e;
            }
    }
    A->t_asm += omp_get_wtime() - t0;
    STC_CHECK(bad < 0, STC_ENOCONV, "element %d inverted at δ = %g mm", bad, s->delta);
    if (s->hooks && s->hooks->forces) /* e.g. the ramp's stick-law springs (shear.c) */
        s->hooks->forces(s->hooks->ctx, s, want_K);
    if (want_K) asp_ls_end_tangent(s->ls);
    s->k_fresh = want_K;
    return STC_OK;
}

stc_status asp_asm_create(asp_solver *s)
{
    s->as = calloc(1, sizeof *s->as);
    STC_CHECK(s->as, STC_ENOMEM, "solver: out of memory");
    s->as->eplastic = calloc((size_t)s->mesh->nelem, 1);
    STC_CHECK(s->as->eplastic, STC_ENOMEM, "solver: out of memory");
    STC_CALL(index_hanging(s));
    return build_colors(s);
}

void asp_asm_destroy(asp_asm **ap)
{
    asp_asm *a = *ap;
    if (!a) return;
    free(a->emap), free(a->hidx), free(a->hoff), free(a->hpos);
    free(a->cptr), free(a->celem);
    free(a->kel), free(a->kglob), free(a->eplastic);
    free(a);
    *ap = NULL;
}

void asp_asm_work(const asp_asm *a, int *evaluations, double *wall_s)
{
    *evaluations = a->n_asm;
    *wall_s = a->t_asm;
}
