/* The contact footprint of the tangential ramp (shear.c, junction rule
 * ASP_JUNCTION_FOOTPRINT; docs/design.md §4.2): node lines across the
 * contact edge along +x, -x and +y, their gaps when the ramp started, and
 * the extent of the sheared contact read from how those gaps close.
 * Separate from the active set and the results of asp_contact.c: it is
 * state of the ramp only (asp_foot, in the ramp's struct), reading the
 * contact candidates' gaps and nothing else.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "footprint.h"
#include "stc_check.h"

/* How far the contact edge on a line of nodes has advanced since the ramp
 * started, from the gap of the first open node past it.  Near an edge where
 * the pressure falls as a square root, the gap grows as g = C (r - a)^(3/2)
 * (the leading term of the Hertz separation outside the contact, Johnson
 * 1985 §4.2).  If the profile translates with the edge, from a0 (the
 * force-fit radius of the normal step, asp_contact_results) to a, the open
 * node at r_j sees g_j / g_j0 = ((r_j - a) / (r_j - a0))^(3/2), so
 *     a = r_j - (r_j - a0) (g_j / g_j0)^(2/3):
 * a0 while its gap is unchanged, r_j as it closes, after which the next
 * node takes over, continuously if the shape holds.  Only the ratio of one
 * node's gaps enters, so neither C nor the node spacing biases it; the
 * preload radius stays the force fit's.  (A two-node fit of the exponent law
 * to the current gaps reads the edge itself, but it is biased by the nodes'
 * distance from it: at the end of the normal step, against the force fit,
 * +1.7 / +0.3 / +2.8 % at 6 / 8.5 / 12 elements per contact, WSP 3 ωc, and
 * below the last contact node at 12 and 24 ωc, where the flattened profile
 * is not that shape.)  r ascending; g0 the gaps when the ramp started, g
 * now, <= 0 for nodes in contact.  Never below a0: the contact does not
 * recede under no-separation.  (The profile does not translate on a coarse
 * mesh: WSP 3 ωc at 6 elements per contact, a node 16 % past a0 closed
 * while the one beyond kept 97.5 % of its gap, so once a node has closed
 * this reads less than the contact holds; the caller keeps the maximum
 * over the ramp, or with rows each row holds its last closed node,
 * asp_foot_extent.) */
/* Index of the last node in contact (gap <= 0) of a line, -1 if none. */
static int last_closed(const double *g, int n)
{
    int L = -1;
    for (int i = 0; i < n; i++)
        if (!(g[i] > 0.0)) L = i;
    return L;
}

double asp_contact_edge_advance(const double *r, const double *g0, const double *g, int nr,
                                double a0)
{
    int L = last_closed(g, nr), j = L + 1;
    if (L < 0 || j >= nr) return L < 0 ? a0 : fmax(a0, r[L]);
    if (!(r[j] > a0) || !(g0[j] > 0.0)) return a0;
    double f = fmin(1.0, g[j] / g0[j]);
    return fmax(a0, r[j] - (r[j] - a0) * pow(f, 2.0 / 3.0));
}

static int cmp_foot(const void *a, const void *b)
{
    double x = ((const double *)a)[0], y = ((const double *)b)[0];
    return (x > y) - (x < y);
}

/* The gap of candidate k now, <= 0 when it is in contact. */
static double cand_gap(const asp_solver *s, int k)
{
    int n = s->cand[k];
    if (s->cs[k] != ASP_CS_OPEN) return 0.0;
    return s->Rp - s->delta - (s->mesh->x[3 * n + 2] + s->u[3 * n + 2]);
}

/* Distinct values of v[0..n) (sorted in place), merged within tol; returns
 * their count. */
static int distinct(double *v, int n, double tol)
{
    qsort(v, (size_t)n, sizeof *v, cmp_foot);
    int m = 0;
    for (int i = 0; i < n; i++)
        if (m == 0 || v[i] - v[m - 1] > tol) v[m++] = v[i];
    return m;
}

/* The nodes of one line: candidates within tol of offset `off` across it, on
 * its side of the axis, ordered by the distance along it. */
static stc_status foot_line(const asp_solver *s, asp_foot_line *fl, int dir, double off,
                            double tol, double *tmp)
{
    const asp_mesh *m = s->mesh;
    fl->dir = dir, fl->off = off, fl->n = 0;
    for (int k = 0; k < s->ncand; k++) {
        int n = s->cand[k];
        double x = m->x[3 * n], y = m->x[3 * n + 1];
        int on = dir < 2 ? fabs(y - off) <= tol && (dir == 0 ? x >= 0.0 : x <= 0.0)
                         : fabs(x - off) <= tol && y >= 0.0;
        if (!on) continue;
        tmp[2 * fl->n] = dir == 0 ? x : dir == 1 ? -x : y;
        tmp[2 * fl->n + 1] = k;
        fl->n++;
    }
    qsort(tmp, (size_t)fl->n, 2 * sizeof *tmp, cmp_foot);
    size_t n = fl->n > 0 ? (size_t)fl->n : 1;
    fl->k = malloc(n * sizeof *fl->k);
    fl->r = malloc(n * sizeof *fl->r);
    fl->g0 = malloc(n * sizeof *fl->g0);
    fl->g = malloc(n * sizeof *fl->g);
    if (!fl->k || !fl->r || !fl->g0 || !fl->g)
        return STC_FAIL(STC_ENOMEM, "shear: out of memory for the contact footprint");
    for (int i = 0; i < fl->n; i++) {
        fl->r[i] = tmp[2 * i], fl->k[i] = (int)tmp[2 * i + 1];
        fl->g0[i] = cand_gap(s, fl->k[i]);
    }
    return STC_OK;
}

/* Drop line fl unless it crosses the edge: a node in contact when the ramp
 * starts and an open one past it.  The axis lines always stay. */
static void keep_if_crossing(asp_foot *f, asp_foot_line *fl)
{
    int L = last_closed(fl->g0, fl->n);
    if (fl->off == 0.0 || (L >= 0 && L + 1 < fl->n)) return;
    free(fl->k), free(fl->r), free(fl->g0), free(fl->g);
    memset(fl, 0, sizeof *fl);
    f->nline--;
}

stc_status asp_foot_init(asp_foot *f, const asp_solver *s, double a0, double rows)
{
    const asp_mesh *m = s->mesh;
    asp_foot_free(f);
    f->a0 = a0;
    double tol = 0.02 * s->h, reach = rows * a0 + tol;
    double *tmp = malloc((size_t)s->ncand * 3 * sizeof *tmp), *v = tmp + 2 * s->ncand;
    STC_CHECK(tmp, STC_ENOMEM, "shear: out of memory for the contact footprint");
    stc_status st = STC_OK;
    enum { PER_DIR = ASP_FOOT_MAXLINES / 3 };
    for (int dir = 0; dir < 3 && st == STC_OK; dir++) {
        /* offsets of the rows of contact nodes within `reach` of the axis */
        int nv = 0;
        for (int k = 0; k < s->ncand; k++) {
            if (s->cs[k] == ASP_CS_OPEN) continue;
            const double *x = m->x + 3 * s->cand[k];
            double o = dir < 2 ? x[1] : x[0];
            if ((dir < 2 || x[1] >= 0.0) && fabs(o) <= reach) v[nv++] = fabs(o) <= tol ? 0.0 : o;
        }
        nv = distinct(v, nv, tol);
        if (nv == 0) v[nv++] = 0.0;
        /* more rows than room: every stride-th one counted from the axis row */
        int i0 = 0, stride = (nv + PER_DIR - 1) / PER_DIR;
        while (i0 < nv - 1 && v[i0] < 0.0) i0++;
        for (int i = 0; i < nv && st == STC_OK; i++) {
            if ((i - i0) % stride) continue;
            asp_foot_line *fl = &f->line[f->nline++];
            st = foot_line(s, fl, dir, v[i], tol, tmp);
            fl->hold = rows > 0.0;
            if (st == STC_OK) keep_if_crossing(f, fl);
        }
    }
    free(tmp);
    return st;
}

void asp_foot_free(asp_foot *f)
{
    for (int line = 0; line < f->nline; line++) {
        asp_foot_line *fl = &f->line[line];
        free(fl->k), free(fl->r), free(fl->g0), free(fl->g);
        memset(fl, 0, sizeof *fl);
    }
    f->nline = 0;
}

/* 3D half model: the contact extent along +x, -x and +y (ext[0..2]) from
 * the preload radius a0 and the edge advance on each node line
 * (asp_contact_edge_advance): the footprint of a sheared contact,
 * two half-ellipses whose edges move outward.  A line at offset o across
 * its direction crosses the preload circle at sqrt(a0² - o²) and the
 * ellipse at t, which gives the semi-axis t / sqrt(1 - o²/b²), b the other
 * semi-axis; the lines of one direction are averaged. */
void asp_foot_extent(const asp_foot *f, const asp_solver *s, double ext[3])
{
    double t[ASP_FOOT_MAXLINES], a0 = f->a0;
    for (int line = 0; line < f->nline; line++) {
        const asp_foot_line *fl = &f->line[line];
        for (int i = 0; i < fl->n; i++) fl->g[i] = cand_gap(s, fl->k[i]);
        double c0 = sqrt(fmax(a0 * a0 - fl->off * fl->off, 0.0));
        t[line] = asp_contact_edge_advance(fl->r, fl->g0, fl->g, fl->n, c0);
        int L = fl->hold ? last_closed(fl->g, fl->n) : -1;
        if (L >= 0) t[line] = fmax(t[line], fl->r[L]); /* r ascending */
    }
    for (int i = 0; i < 3; i++) ext[i] = a0;
    for (int it = 0; it < 4; it++) {
        double sum[3] = {0, 0, 0};
        int cnt[3] = {0, 0, 0};
        for (int line = 0; line < f->nline; line++) {
            const asp_foot_line *fl = &f->line[line];
            double b = fl->dir < 2 ? ext[2] : fl->off >= 0.0 ? ext[0] : ext[1];
            double q = 1.0 - fl->off * fl->off / (b * b);
            if (!(q > 0.05)) continue;
            sum[fl->dir] += t[line] / sqrt(q);
            cnt[fl->dir]++;
        }
        for (int i = 0; i < 3; i++) ext[i] = cnt[i] ? fmax(a0, sum[i] / cnt[i]) : a0;
    }
}
