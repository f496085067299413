/* Summits of a periodic height map: strict local maxima over 8 or 4
 * neighbours (Greenwood 1984, Proc. R. Soc. A 393:133, discusses both rules),
 * with mean curvature from central differences. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "srf_impl.h"
#include "stc_check.h"

/* Row pointers of rows j-1, j, j+1 with periodic wrap. */
typedef struct {
    const double *up, *mid, *dn;
} rows3;

static rows3 rows_at(const srf_map *m, int j)
{
    int ny = m->ny, nx = m->nx;
    rows3 r = {m->z + (size_t)((j + ny - 1) % ny) * nx, m->z + (size_t)j * nx,
               m->z + (size_t)((j + 1) % ny) * nx};
    return r;
}

/* Strictly higher than every neighbour of the rule (ties are not summits). */
static inline int summit_at(const rows3 *r, int i, int im, int ip, int rule)
{
    double c = r->mid[i];
    if (!(c > r->mid[im] && c > r->mid[ip] && c > r->up[i] && c > r->dn[i])) return 0;
    if (rule == SRF_RULE_4) return 1;
    return c > r->up[im] && c > r->up[ip] && c > r->dn[im] && c > r->dn[ip];
}

/* Searched range: all points of a periodic map, the interior otherwise. */
static int edge(const srf_map *m) { return m->periodic ? 0 : 1; }
static int row_searched(const srf_map *m, int j) { return j >= edge(m) && j < m->ny - edge(m); }

static int count_row(const srf_map *m, int j, int rule)
{
    rows3 r = rows_at(m, j);
    int nx = m->nx, n = 0;
    if (!row_searched(m, j)) return 0;
    for (int i = edge(m); i < nx - edge(m); i++) {
        int im = i == 0 ? nx - 1 : i - 1, ip = i == nx - 1 ? 0 : i + 1;
        n += summit_at(&r, i, im, ip, rule);
    }
    return n;
}

/* Record the summits of row j from index k on.  κ = -(z_xx + z_yy)/2 with the
 * 3-point second differences (the 5-point Laplacian). */
static void fill_row(const srf_map *m, int j, int rule, double mean, srf_summits *s, int k)
{
    rows3 r = rows_at(m, j);
    int nx = m->nx;
    double dx = m->lx / nx, dy = m->ly / m->ny;
    double idx2 = 1.0 / (dx * dx), idy2 = 1.0 / (dy * dy);
    if (!row_searched(m, j)) return;
    for (int i = edge(m); i < nx - edge(m); i++) {
        int im = i == 0 ? nx - 1 : i - 1, ip = i == nx - 1 ? 0 : i + 1;
        if (!summit_at(&r, i, im, ip, rule)) continue;
        double c = r.mid[i];
        double zxx = (r.mid[ip] - 2 * c + r.mid[im]) * idx2;
        double zyy = (r.dn[i] - 2 * c + r.up[i]) * idy2;
        double kap = -0.5 * (zxx + zyy);
        s->x[k] = i * dx;
        s->y[k] = j * dy;
        s->z[k] = c - mean;
        s->kappa[k] = kap;
        s->R[k] = kap > 0 ? 1.0 / kap : INFINITY;
        k++;
    }
}

static double map_mean(const srf_map *m)
{
    size_t n = (size_t)m->nx * m->ny;
    double sum = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
    for (size_t k = 0; k < n; k++) sum += m->z[k];
    return sum / (double)n;
}

static stc_status summits_alloc(int n, srf_summits **out)
{
    srf_summits *s = calloc(1, sizeof *s);
    STC_CHECK(s, STC_ENOMEM, "summits: out of memory");
    size_t cnt = n > 0 ? (size_t)n : 1;
    s->x = malloc(cnt * sizeof *s->x);
    s->y = malloc(cnt * sizeof *s->y);
    s->z = malloc(cnt * sizeof *s->z);
    s->kappa = malloc(cnt * sizeof *s->kappa);
    s->R = malloc(cnt * sizeof *s->R);
    s->n = n;
    *out = s;
    if (!s->x || !s->y || !s->z || !s->kappa || !s->R) {
        srf_summits_destroy(out);
        return STC_FAIL(STC_ENOMEM, "summits: out of memory for %d summits", n);
    }
    return STC_OK;
}

stc_status srf_summits_find(const srf_map *m, int rule, srf_summits **out)
{
    *out = NULL;
    STC_CHECK(m && m->z, STC_EINVAL, "summits_find: NULL map");
    STC_CHECK(rule == SRF_RULE_8 || rule == SRF_RULE_4, STC_EINVAL,
              "rule = %d: must be 8 or 4", rule);
    STC_CHECK(m->nx >= 3 && m->ny >= 3, STC_EINVAL, "map %d x %d: needs at least 3 x 3",
              m->nx, m->ny);
    int ny = m->ny;
    int *start = malloc(((size_t)ny + 1) * sizeof *start);
    STC_CHECK(start, STC_ENOMEM, "summits: out of memory");
    /* pass 1: count per row, so pass 2 writes each row's summits in place */
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++) start[j + 1] = count_row(m, j, rule);
    start[0] = 0;
    for (int j = 0; j < ny; j++) start[j + 1] += start[j];
    stc_status st = summits_alloc(start[ny], out);
    if (st != STC_OK) {
        free(start);
        return st;
    }
    double mean = map_mean(m);
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++) fill_row(m, j, rule, mean, *out, start[j]);
    (*out)->rule = rule;
    (*out)->area = (m->nx - 2 * edge(m)) * (m->lx / m->nx) * (m->ny - 2 * edge(m)) * (m->ly / m->ny);
    free(start);
    return STC_OK;
}

void srf_summits_destroy(srf_summits **ps)
{
    if (!ps || !*ps) return;
    srf_summits *s = *ps;
    free(s->x);
    free(s->y);
    free(s->z);
    free(s->kappa);
    free(s->R);
    free(s);
    *ps = NULL;
}
