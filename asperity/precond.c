/* The Krylov iteration's two kernels, on two threads: the float
 * preconditioner solve with the factor, P' L^-T L^-1 P b, and the mat-vec
 * with the tangent (the upper-stored symmetric K, plus the listed entries
 * of its non-factorized part Kd + W).  A PCG/GMRES iteration is one of
 * each plus vector updates; both are memory bound and ran on one core
 * while the other idled: 7.7 s of the 24 s graded 3D load curve (n = 4,
 * docs/design.md §3.6).
 *
 * Each kernel is split into two fixed parts, whatever the number
 * of threads that runs them, and the parts' contributions to shared entries
 * are summed in part order: the result is the same on one or two threads.
 *
 * Solve.  The supernodes of CHOLMOD's factor form a tree (the parent of a
 * supernode is the one holding its first row below the diagonal block) and
 * are numbered in postorder, so every subtree is a contiguous range
 * (CHOLMOD User Guide, "cholmod_factor"; checked here, else the whole tree
 * is the top and the parts are empty).  The plan cuts the tree into disjoint subtrees packed
 * into the parts and a "top" (the supernodes above the cut: the last
 * separators).  Forward, L y = P b: the parts run their subtrees
 * concurrently; a supernode's update of rows of its own subtree is applied
 * at once, its update of top rows goes to the part's buffer; then the
 * buffers are subtracted and the top is solved.  Backward, L' x = y: the
 * top first, then the parts, which read only rows of their own subtrees and
 * of the top.  The cut is chosen by expanding the heaviest subtree (its
 * root moves to the top) while that lowers the estimated time, top +
 * heaviest part, counted in factor entries (the data a solve reads).  On
 * the 3D meshes the top is the last one or two separators, 26-36 % of the
 * entries (tests/test_precond.c).
 *
 * Mat-vec.  K's columns are cut where half its stored entries lie; each
 * part forms its columns' share (column j gives y_j its dot product and
 * y_i, i < j, the transposed terms), the second part's terms in rows of
 * the first go to a buffer added afterwards. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "linsolve_impl.h"
#include "stc_check.h"

enum { PREC_MAX_EXPAND = 256 }; /* cut: at most this many supernodes moved to the top */

struct asp_prec {
    int *range;       /* [2 nr]: the subtrees, supernodes range[2i] .. range[2i+1] */
    int nr;
    int rptr[ASP_PREC_PARTS + 1]; /* part p's subtrees: rptr[p] .. rptr[p+1] */
    int *top;         /* [ntop] top supernodes, ascending */
    int ntop;
    int *topcol;      /* [ntopcol] their columns */
    int ntopcol;
    unsigned char *intop; /* [n] column in the top */
    float *buf;       /* [PARTS][n] top-row updates of each part */
    float *tmp;       /* [PARTS][n] gemv output per part */
    double top_w, part_w[ASP_PREC_PARTS]; /* entries read (the plan's estimate) */
};

struct asp_mvplan {
    int cut;   /* columns [0, cut) are part 0, [cut, n) part 1 */
    int lo;    /* smallest row index in part 1's columns */
    double *buf; /* [cut - lo] part 1's contributions to rows < cut */
};

/* ---- the plan ------------------------------------------------------------ */

typedef struct cand {
    int k;    /* subtree root */
    double w; /* subtree entries */
} cand;

static int cmp_cand(const void *a, const void *b)
{
    double wa = ((const cand *)a)->w, wb = ((const cand *)b)->w;
    return wa < wb ? 1 : wa > wb ? -1 : ((const cand *)a)->k - ((const cand *)b)->k;
}

/* Longest-processing-time packing of the candidates into the parts (sorted
 * heaviest first on return); bin[i] receives the part, w the loads. */
static void pack(cand *c, int nc, int *bin, double w[ASP_PREC_PARTS])
{
    qsort(c, (size_t)nc, sizeof *c, cmp_cand);
    for (int p = 0; p < ASP_PREC_PARTS; p++) w[p] = 0.0;
    for (int i = 0; i < nc; i++) {
        int b = 0;
        for (int p = 1; p < ASP_PREC_PARTS; p++)
            if (w[p] < w[b]) b = p;
        bin[i] = b;
        w[b] += c[i].w;
    }
}

static double heaviest(const double w[ASP_PREC_PARTS])
{
    double m = 0.0;
    for (int p = 0; p < ASP_PREC_PARTS; p++) m = fmax(m, w[p]);
    return m;
}

/* Cut the supernodal tree of L (see the file comment) into pr's range,
 * rptr, top, topcol, intop (pr zeroed on entry). */
static stc_status plan_cut(const cholmod_factor *L, struct asp_prec *pr)
{
    const int *super = L->super, *pi = L->pi, *ls = L->s;
    int n = (int)L->n, ns = (int)L->nsuper;
    stc_status st = STC_OK;
    int *col2s = malloc((size_t)n * sizeof *col2s), *par = malloc((size_t)ns * sizeof *par);
    int *first = malloc((size_t)ns * sizeof *first), *cnt = malloc((size_t)ns * sizeof *cnt);
    int *kids = malloc((size_t)(ns + 1) * sizeof *kids), *kid = malloc((size_t)ns * sizeof *kid);
    double *W = malloc((size_t)ns * sizeof *W);
    unsigned char *istop = calloc((size_t)ns, 1), *best_top = calloc((size_t)ns, 1);
    cand *c = malloc((size_t)(ns + 1) * sizeof *c), *best = malloc((size_t)(ns + 1) * sizeof *best);
    int *bin = malloc((size_t)(ns + 1) * sizeof *bin), nbest = 0;
    pr->range = malloc((size_t)(2 * ns + 2) * sizeof *pr->range);
    pr->top = malloc((size_t)ns * sizeof *pr->top);
    pr->intop = calloc((size_t)n, 1);
    pr->topcol = malloc((size_t)n * sizeof *pr->topcol);
    STC_CHECK_GOTO(col2s && par && first && cnt && kids && kid && W && istop && best_top && c &&
                       best && bin && pr->range && pr->top && pr->intop && pr->topcol,
                   st, done, STC_ENOMEM, "solver: out of memory for the solve plan");
    for (int k = 0; k < ns; k++)
        for (int j = super[k]; j < super[k + 1]; j++) col2s[j] = k;
    for (int k = 0; k < ns; k++) {
        int nc = super[k + 1] - super[k], nrow = pi[k + 1] - pi[k];
        par[k] = nrow > nc ? col2s[ls[pi[k] + nc]] : -1;
        W[k] = (double)nrow * nc;
        first[k] = k, cnt[k] = 1;
    }
    int post = 1;
    for (int k = 0; k < ns; k++) { /* children before parents */
        if (par[k] < 0) continue;
        post &= par[k] > k;
        if (!post) break;
        W[par[k]] += W[k], cnt[par[k]] += cnt[k];
        if (first[k] < first[par[k]]) first[par[k]] = first[k];
    }
    for (int k = 0; k < ns && post; k++) post = first[k] == k - cnt[k] + 1;
    if (!post) { /* not postordered: everything is top, solved in order */
        for (int k = 0; k < ns; k++) pr->top[k] = k;
        pr->ntop = ns;
        goto done;
    }
    /* children lists (CSR by parent) */
    memset(kids, 0, (size_t)(ns + 1) * sizeof *kids);
    for (int k = 0; k < ns; k++)
        if (par[k] >= 0) kids[par[k] + 1]++;
    for (int k = 0; k < ns; k++) kids[k + 1] += kids[k];
    {
        int *fill = cnt; /* reuse: cnt is no longer needed */
        memcpy(fill, kids, (size_t)ns * sizeof *fill);
        for (int k = 0; k < ns; k++)
            if (par[k] >= 0) kid[fill[par[k]]++] = k;
    }
    int nc = 0;
    for (int k = 0; k < ns; k++)
        if (par[k] < 0) c[nc++] = (cand){k, W[k]};
    double top_w = 0.0, w[ASP_PREC_PARTS], best_cost = INFINITY;
    for (int it = 0; it <= PREC_MAX_EXPAND && nc > 0; it++) {
        pack(c, nc, bin, w);
        double cost = top_w + heaviest(w);
        if (cost < best_cost) {
            best_cost = cost, nbest = nc;
            memcpy(best, c, (size_t)nc * sizeof *c);
            memcpy(best_top, istop, (size_t)ns);
            pr->top_w = top_w;
        }
        /* expand the heaviest candidate: its root joins the top */
        int k = c[0].k;
        istop[k] = 1;
        top_w += W[k];
        for (int q = kids[k]; q < kids[k + 1]; q++) top_w -= W[kid[q]];
        c[0] = c[--nc];
        for (int q = kids[k]; q < kids[k + 1]; q++) c[nc++] = (cand){kid[q], W[kid[q]]};
    }
    /* the best cut: ranges grouped by part */
    pack(best, nbest, bin, pr->part_w);
    for (int p = 0; p < ASP_PREC_PARTS; p++) {
        pr->rptr[p] = pr->nr;
        for (int i = 0; i < nbest; i++)
            if (bin[i] == p) {
                int k = best[i].k;
                pr->range[2 * pr->nr] = first[k], pr->range[2 * pr->nr + 1] = k;
                pr->nr++;
            }
    }
    pr->rptr[ASP_PREC_PARTS] = pr->nr;
    pr->ntop = pr->ntopcol = 0;
    for (int k = 0; k < ns; k++)
        if (best_top[k]) {
            pr->top[pr->ntop++] = k;
            for (int j = super[k]; j < super[k + 1]; j++)
                pr->intop[j] = 1, pr->topcol[pr->ntopcol++] = j;
        }
done:
    free(col2s), free(par), free(first), free(cnt), free(kids), free(kid), free(W);
    free(istop), free(best_top), free(c), free(best), free(bin);
    return st;
}

void asp_prec_free(asp_linsolve *ls)
{
    struct asp_prec *pr = ls->prec;
    if (pr) {
        free(pr->range), free(pr->top), free(pr->topcol), free(pr->intop);
        free(pr->buf), free(pr->tmp);
        free(pr);
        ls->prec = NULL;
    }
    if (ls->mv) {
        free(ls->mv->buf);
        free(ls->mv);
        ls->mv = NULL;
    }
    free(ls->fx), free(ls->fy);
    ls->fx = NULL, ls->fy = NULL, ls->fx_size = 0, ls->fx_ok = 0;
}

static stc_status prec_plan(asp_linsolve *ls)
{
    const cholmod_factor *L = ls->L;
    struct asp_prec *pr = calloc(1, sizeof *pr);
    STC_CHECK(pr, STC_ENOMEM, "solver: out of memory for the solve plan");
    ls->prec = pr;
    pr->buf = malloc(ASP_PREC_PARTS * L->n * sizeof *pr->buf);
    pr->tmp = malloc(ASP_PREC_PARTS * L->n * sizeof *pr->tmp);
    STC_CHECK(pr->buf && pr->tmp, STC_ENOMEM, "solver: out of memory for the solve plan");
    return plan_cut(L, pr);
}

/* Float copy of the supernodal factor, after each factorization (the plan
 * is made once: the supernodes are those of the analysis).
 *
 * Single precision: a Krylov iteration is two triangular solves with the
 * factor, which are memory bound (3D: 2-12e6 entries read twice).  The
 * preconditioner reads a float copy of the supernodal factor instead and
 * works in double: half the traffic.  Rounding the factor to float left
 * the WSP 3 ωc shear ramp at the same mu_s (10 digits), Newton 147 -> 148
 * and the same 26 factorizations.  With the float solves (idle machine):
 * WSP 3 ωc ramp, one thread, Krylov 11.2 -> 7.2 s but 26 -> 29
 * factorizations (they converge a little slower, so the refactorization
 * rule fires more), solver 20.5 -> 17.1 s; coated t/R .025 Eco/Esu 2
 * δ = 10 stick ramp, two threads, 66.7 -> 61.9 s (mu_s moved 1e-7: stick
 * positions follow the iterates).  Layout of a
 * CHOLMOD supernode k: columns super[k] .. super[k+1]-1, row indices
 * s[pi[k] .. pi[k+1]) (the columns themselves first), values column-major
 * from px[k] (CHOLMOD User Guide, "cholmod_factor"). */
stc_status asp_prec_update(asp_linsolve *ls)
{
    const cholmod_factor *L = ls->L;
    ls->fx_ok = 0;
    if (!L->is_super || !L->is_ll) return STC_OK;
    if (ls->fx_size < L->xsize) {
        free(ls->fx);
        ls->fx = malloc(L->xsize * sizeof *ls->fx);
        ls->fx_size = ls->fx ? L->xsize : 0;
        STC_CHECK(ls->fx, STC_ENOMEM, "solver: out of memory for the factor copy");
    }
    if (!ls->fy) {
        ls->fy = malloc((size_t)ls->n * sizeof *ls->fy);
        STC_CHECK(ls->fy, STC_ENOMEM, "solver: out of memory");
    }
    if (!ls->prec) STC_CALL(prec_plan(ls));
    const double *x = L->x;
    for (size_t k = 0; k < L->xsize; k++) ls->fx[k] = (float)x[k];
    ls->fx_ok = 1;
    return STC_OK;
}

/* ---- the solve ----------------------------------------------------------- */

/* Forward step of supernode k: y_k = L_kk^-1 y_k, then the rows below get
 * -L_bk y_k, those in the top into buf when buf is given. */
static void fwd_node(const asp_linsolve *ls, int k, float *y, float *t, float *buf,
                     const unsigned char *intop)
{
    const cholmod_factor *L = ls->L;
    const int *super = L->super, *pi = L->pi, *px = L->px;
    int k1 = super[k], nc = super[k + 1] - k1, nr = pi[k + 1] - pi[k], nb = nr - nc;
    const float *Lk = ls->fx + px[k];
    const int *rows = (const int *)L->s + pi[k] + nc, one = 1;
    const float f0 = 0.0f, f1 = 1.0f;
    strsv_("L", "N", "N", &nc, Lk, &nr, y + k1, &one);
    if (nb == 0) return;
    sgemv_("N", &nb, &nc, &f1, Lk + nc, &nr, y + k1, &one, &f0, t, &one);
    if (buf) {
        for (int i = 0; i < nb; i++) {
            int r = rows[i];
            if (intop[r]) buf[r] += t[i];
            else y[r] -= t[i];
        }
    } else {
        for (int i = 0; i < nb; i++) y[rows[i]] -= t[i];
    }
}

/* Backward step of supernode k: y_k -= L_bk' y_b, then y_k = L_kk^-T y_k. */
static void bwd_node(const asp_linsolve *ls, int k, float *y, float *t)
{
    const cholmod_factor *L = ls->L;
    const int *super = L->super, *pi = L->pi, *px = L->px;
    int k1 = super[k], nc = super[k + 1] - k1, nr = pi[k + 1] - pi[k], nb = nr - nc;
    const float *Lk = ls->fx + px[k];
    const int *rows = (const int *)L->s + pi[k] + nc, one = 1;
    const float f1 = 1.0f, fm1 = -1.0f;
    if (nb > 0) {
        for (int i = 0; i < nb; i++) t[i] = y[rows[i]];
        sgemv_("T", &nb, &nc, &fm1, Lk + nc, &nr, t, &one, &f1, y + k1, &one);
    }
    strsv_("L", "T", "N", &nc, Lk, &nr, y + k1, &one);
}

/* out = P' L^-T L^-1 P b with the float factor (A = P' L L' P), in float;
 * per supernode as CHOLMOD does in double (cholmod_super_lsolve / ltsolve).
 * Threads: ls->nthr; OpenBLAS must run on one thread (the caller's). */
void asp_prec_solve(const asp_linsolve *ls, const double *b, double *out)
{
    const struct asp_prec *pr = ls->prec;
    const int *perm = ls->L->Perm;
    int n = ls->n;
    float *y = ls->fy;
    for (int i = 0; i < n; i++) y[i] = (float)b[perm[i]];
    int nthr = ls->nthr < ASP_PREC_PARTS ? ls->nthr : ASP_PREC_PARTS;
#pragma omp parallel num_threads(nthr) if (nthr > 1)
    {
#pragma omp for schedule(static, 1)
        for (int p = 0; p < ASP_PREC_PARTS; p++) {
            float *buf = pr->buf + (size_t)p * n, *t = pr->tmp + (size_t)p * n;
            for (int i = 0; i < pr->ntopcol; i++) buf[pr->topcol[i]] = 0.0f;
            for (int r = pr->rptr[p]; r < pr->rptr[p + 1]; r++)
                for (int k = pr->range[2 * r]; k <= pr->range[2 * r + 1]; k++)
                    fwd_node(ls, k, y, t, buf, pr->intop);
        }
#pragma omp single
        {
            for (int p = 0; p < ASP_PREC_PARTS; p++) {
                const float *buf = pr->buf + (size_t)p * n;
                for (int i = 0; i < pr->ntopcol; i++) y[pr->topcol[i]] -= buf[pr->topcol[i]];
            }
            for (int i = 0; i < pr->ntop; i++) fwd_node(ls, pr->top[i], y, pr->tmp, NULL, NULL);
            for (int i = pr->ntop - 1; i >= 0; i--) bwd_node(ls, pr->top[i], y, pr->tmp);
        }
#pragma omp for schedule(static, 1)
        for (int p = 0; p < ASP_PREC_PARTS; p++) {
            float *t = pr->tmp + (size_t)p * n;
            for (int r = pr->rptr[p]; r < pr->rptr[p + 1]; r++)
                for (int k = pr->range[2 * r + 1]; k >= pr->range[2 * r]; k--)
                    bwd_node(ls, k, y, t);
        }
    }
    for (int i = 0; i < n; i++) out[perm[i]] = y[i];
}

/* ---- the mat-vec --------------------------------------------------------- */

/* Split K's columns where half its stored entries lie (once per pattern). */
stc_status asp_matvec_setup(asp_linsolve *ls)
{
    if (ls->mv) return STC_OK;
    const int *Kp = ls->K->p, *Ki = ls->K->i;
    int n = ls->n;
    struct asp_mvplan *mv = calloc(1, sizeof *mv);
    STC_CHECK(mv, STC_ENOMEM, "solver: out of memory for the mat-vec plan");
    ls->mv = mv;
    int cut = 0;
    while (cut < n && 2 * Kp[cut] < Kp[n]) cut++;
    int lo = cut;
    for (int k = Kp[cut]; k < Kp[n]; k++)
        if (Ki[k] < lo) lo = Ki[k];
    mv->cut = cut, mv->lo = lo;
    mv->buf = malloc((size_t)(cut - lo + 1) * sizeof *mv->buf);
    STC_CHECK(mv->buf, STC_ENOMEM, "solver: out of memory for the mat-vec plan");
    return STC_OK;
}

/* y[j0..j1) and y's rows within [j0, j1) += columns j0..j1 of K times x;
 * rows below j0 into low[i - lo] when low is given. */
static void matvec_cols(const cholmod_sparse *K, const double *x, double *y, int j0, int j1,
                        double *low, int lo)
{
    const int *Kp = K->p, *Ki = K->i;
    const double *Kx = K->x;
    for (int j = j0; j < j1; j++) {
        double yj = 0.0, xj = x[j];
        for (int k = Kp[j]; k < Kp[j + 1]; k++) {
            int i = Ki[k];
            if (i == j) {
                yj += Kx[k] * xj;
                continue;
            }
            yj += Kx[k] * x[i];
            if (i >= j0) y[i] += Kx[k] * xj;
            else low[i - lo] += Kx[k] * xj;
        }
        y[j] += yj;
    }
}

/* The same for the entries l0 .. l1 of the tangent's non-factorized part
 * Kd + W (linsolve_impl.h: Kd symmetric, W skew, W_ji = -W_ij); free_only:
 * their free-free block. */
static void skew_entries(const asp_linsolve *ls, const double *x, double *y, int l0, int l1,
                         int j0, double *low, int lo, int free_only)
{
    const int *Ki = ls->K->i;
    for (int l = l0; l < l1; l++) {
        int k = ls->sk_k[l], i = Ki[k], j = ls->sk_j[l];
        if (free_only && (ls->fixed[j] || ls->fixed[i])) continue;
        double v = (ls->Kd[k] + ls->Kk[k]) * x[j];
        if (i >= j0) y[i] += v;
        else low[i - lo] += v;
        if (i != j) y[j] += (ls->Kd[k] - ls->Kk[k]) * x[i];
    }
}

/* y = A x, A the upper-stored symmetric K (skew 0), the tangent K + Kd + W
 * (skew 1) or K plus the free-free block of Kd + W (skew 2); in two parts
 * (see the file comment; asp_matvec_setup first).  Threads: ls->nthr. */
void asp_tangent_matvec(const asp_linsolve *ls, const double *x, double *y, int skew)
{
    const struct asp_mvplan *mv = ls->mv;
    int n = ls->n, nthr = ls->nthr < 2 ? ls->nthr : 2, nsk = skew && ls->skew ? ls->nsk : 0;
    int lcut = 0, hi = nsk; /* first listed entry in a column >= cut (sk_j ascends) */
    while (lcut < hi) {
        int mid = (lcut + hi) / 2;
        if (ls->sk_j[mid] < mv->cut) lcut = mid + 1;
        else hi = mid;
    }
    memset(y, 0, (size_t)n * sizeof *y);
#pragma omp parallel num_threads(nthr) if (nthr > 1)
    {
#pragma omp for schedule(static, 1)
        for (int p = 0; p < 2; p++) {
            if (p == 0) {
                matvec_cols(ls->K, x, y, 0, mv->cut, NULL, 0);
                skew_entries(ls, x, y, 0, lcut, 0, NULL, 0, skew == 2);
            } else {
                memset(mv->buf, 0, (size_t)(mv->cut - mv->lo) * sizeof *mv->buf);
                matvec_cols(ls->K, x, y, mv->cut, n, mv->buf, mv->lo);
                skew_entries(ls, x, y, lcut, nsk, mv->cut, mv->buf, mv->lo, skew == 2);
            }
        }
#pragma omp single
        for (int i = mv->lo; i < mv->cut; i++) y[i] += mv->buf[i - mv->lo];
    }
}

int asp_prec_parts(const asp_linsolve *ls, double *top_w, double *part_w)
{
    const struct asp_prec *pr = ls->prec;
    if (!pr) return 0;
    int np = 0;
    *top_w = pr->top_w;
    for (int p = 0; p < ASP_PREC_PARTS; p++) {
        part_w[p] = pr->part_w[p];
        np += pr->rptr[p + 1] > pr->rptr[p];
    }
    return np;
}
