/* Building a friction table: the points of a shard computed concurrently,
 * each finished point appended to a journal before anything else, the table
 * written atomically at the end (include/stiction/table.h, tbl_build).
 *
 * Journal: a header (8-byte magic, the build's hash) and then one record per
 * finished point or normal curve, and per finished placement member of a
 * point (so that a build killed during a long point keeps its finished
 * members): magic, index, the point's (the curve's and its values', the
 * member's) bytes, a checksum.  Each record
 * is written with one write() and flushed (fdatasync) before the next point
 * is reported, so a build killed at any moment leaves whole records plus at
 * most one torn one, which the checksum rejects; the file is cut back to its
 * last whole record when the build goes on.  The records are raw structs:
 * a journal is a crash log of one binary on one machine, never an exchange
 * format (its header carries sizeof(tbl_point) in the hash).
 *
 * Under `mpirun -n N` (N > 1) the points are shared out by the MPI
 * farm of table_mpi.c; this process then journals and writes only when it
 * is rank 0, with the same resume logic as the serial path. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <omp.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "stc_check.h"
#include "table_impl.h"

static const char JOURNAL_MAGIC[8] = {'S', 'T', 'C', 'T', 'B', 'L', 'J', '2'};
#define POINT_MAGIC 0x50544254u /* "TBTP" */
#define CURVE_MAGIC 0x43544254u /* "TBTC" */
#define MEMBER_MAGIC 0x4d544254u /* "TBTM" */

/* A record: this head, the payload (a tbl_point, or a tbl_curve and the
 * curve's P[n_w] and A[n_w]), a checksum of everything before it. */
typedef struct {
    uint32_t magic;
    int32_t index;
} record_head;

static size_t payload_size(const tbl_table *t, uint32_t magic)
{
    if (magic == POINT_MAGIC) return sizeof(tbl_point);
    if (magic == MEMBER_MAGIC) return sizeof(tbl_member_rec);
    return sizeof(tbl_curve) + 2 * (size_t)t->nrm.n[0] * sizeof(double);
}

static uint64_t fnv64(const unsigned char *b, size_t n)
{
    uint64_t h = 14695981039346656037ULL;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211ULL;
    return h;
}

void tbl_build_opts_default(tbl_build_opts *o)
{
    memset(o, 0, sizeof *o);
    o->shards = 1;
}

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Write all of n bytes (a signal may cut a write short). */
static int write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return -1;
        p += w, n -= (size_t)w;
    }
    return 0;
}

void tbl_member_rec_fill(tbl_member_rec *r, int i, const asp_placement_result *e, int j)
{
    memset(r, 0, sizeof *r);
    r->index = i, r->slot = asp_placement_slot(j, e->k);
    r->edge_refine = e->edge_refine;
    r->period = e->period, r->delta = e->delta, r->delta_mesh = e->delta_mesh;
    r->edge_a0 = e->edge_a0;
    r->m = e->m[j];
}

/* Keep member record r for its point (pending in b's table): b->mem. */
static int keep_member(tbl_build_state *b, const tbl_member_rec *r)
{
    if (b->n_mem == b->cap_mem) { /* room doubles: a journal holds hundreds */
        int cap = b->cap_mem ? 2 * b->cap_mem : 16;
        tbl_member_rec *m = realloc(b->mem, (size_t)cap * sizeof *m);
        if (!m) return -1;
        b->mem = m, b->cap_mem = cap;
    }
    b->mem[b->n_mem++] = *r;
    return 0;
}

/* A point or curve in this state is computed by b's build: pending, or
 * failed where the build retries failed ones (--retry-failed). */
static int reopens(const tbl_build_state *b, int state)
{
    return state == TBL_PENDING ||
           ((b->o->retry_failed || b->o->only_failed) && state == TBL_FAILED);
}

/* A journal record in state `rec` for a point or curve in state `was`: taken
 * where this build computes it (reopens), and a done record of a failed
 * one in any case: only a retry of this build can have written it, and a
 * build resumed without --retry-failed must not lose it. */
static int takes_record(const tbl_build_state *b, int was, int rec)
{
    return rec != TBL_PENDING &&
           (reopens(b, was) || (was == TBL_FAILED && rec == TBL_DONE));
}

/* Item k (a point, or curve k - points) was failed and an earlier run of
 * this build journaled its retry: b->retried[k].  0, or -1 out of memory. */
static int mark_retried(tbl_build_state *b, int state, int k)
{
    if (state != TBL_FAILED) return 0;
    if (!b->retried &&
        !(b->retried = calloc((size_t)(tbl_points(b->t) + tbl_curves(b->t)), 1)))
        return -1;
    b->retried[k] = 1;
    return 0;
}

/* Open the journal of b's table at jpath: take its whole records into the
 * table (pending points and curves only) and the members of its pending
 * points into b->mem, cut off a torn tail, or start a new journal.  b->fd
 * open for appending; *taken, *taken_curves the points and curves taken. */
static stc_status journal_open(tbl_build_state *b, const char *jpath, int *taken,
                               int *taken_curves)
{
    tbl_table *t = b->t;
    uint64_t hash = tbl_build_hash(t);
    *taken = *taken_curves = 0;
    int *fd = &b->fd;
    *fd = open(jpath, O_RDWR | O_CREAT, 0666);
    STC_CHECK(*fd >= 0, STC_EIO, "%s: cannot open the build journal: %s", jpath,
              strerror(errno));
    char magic[8];
    uint64_t h = 0;
    ssize_t got = read(*fd, magic, sizeof magic);
    if (got == (ssize_t)sizeof magic && read(*fd, &h, sizeof h) == (ssize_t)sizeof h) {
        if (memcmp(magic, JOURNAL_MAGIC, sizeof magic) != 0 || h != hash) {
            close(*fd);
            *fd = -1;
            return STC_FAIL(STC_EINVAL, "%s: the journal of another build (family, numerics or "
                            "axes differ, or another stiction binary): remove it, or build with "
                            "the options and binary that made it", jpath);
        }
        off_t good = (off_t)(sizeof magic + sizeof h);
        size_t cap = sizeof(tbl_point);
        if (payload_size(t, CURVE_MAGIC) > cap) cap = payload_size(t, CURVE_MAGIC);
        if (sizeof(tbl_member_rec) > cap) cap = sizeof(tbl_member_rec);
        unsigned char *buf = malloc(sizeof(record_head) + cap + sizeof(uint64_t));
        STC_CHECK(buf, STC_ENOMEM, "tbl_build: out of memory");
        int oom = 0;
        for (;;) {
            record_head rh;
            if (read(*fd, &rh, sizeof rh) != (ssize_t)sizeof rh) break;
            if (rh.magic != POINT_MAGIC && rh.magic != MEMBER_MAGIC &&
                (rh.magic != CURVE_MAGIC || tbl_curves(t) == 0))
                break;
            size_t n = payload_size(t, rh.magic);
            memcpy(buf, &rh, sizeof rh);
            uint64_t sum;
            if (read(*fd, buf + sizeof rh, n) != (ssize_t)n ||
                read(*fd, &sum, sizeof sum) != (ssize_t)sizeof sum ||
                sum != fnv64(buf, sizeof rh + n))
                break;
            if (rh.magic != CURVE_MAGIC && (rh.index < 0 || rh.index >= tbl_points(t))) break;
            if (rh.magic == POINT_MAGIC) {
                tbl_point p;
                memcpy(&p, buf + sizeof rh, sizeof p);
                int was = t->pt[rh.index].state;
                if (takes_record(b, was, p.state) && tbl_point_set(t, rh.index, &p) == STC_OK) {
                    (*taken)++;
                    oom = mark_retried(b, was, rh.index) != 0;
                }
            } else if (rh.magic == MEMBER_MAGIC) {
                tbl_member_rec r;
                memcpy(&r, buf + sizeof rh, sizeof r);
                oom = r.index == rh.index && r.slot >= 0 && r.slot < ASP_PLACEMENTS_MAX &&
                      keep_member(b, &r) != 0;
            } else {
                if (rh.index < 0 || rh.index >= tbl_curves(t)) break;
                tbl_curve c;
                const double *v = (const double *)(buf + sizeof rh + sizeof c);
                memcpy(&c, buf + sizeof rh, sizeof c);
                int was = t->nrm.c[rh.index].state;
                if (takes_record(b, was, c.state) &&
                    tbl_curve_set(t, rh.index, &c, v, v + t->nrm.n[0]) == STC_OK) {
                    (*taken_curves)++;
                    oom = mark_retried(b, was, tbl_points(t) + rh.index) != 0;
                }
            }
            if (oom) break;
            good += (off_t)(sizeof rh + n + sizeof sum);
        }
        free(buf);
        STC_CHECK(!oom, STC_ENOMEM, "tbl_build: out of memory");
        /* members only of the points still to compute (pending, or failed
         * and to be retried), and only those that reached inception: a
         * member that failed runs again (taken, it would fail its point
         * again without a run, also where the retry follows a solver fix) */
        int kept = 0;
        for (int r = 0; r < b->n_mem; r++) {
            const tbl_member_rec *x = &b->mem[r];
            if (reopens(b, t->pt[x->index].state) && !(b->retried && b->retried[x->index]) &&
                x->m.status == STC_OK && x->m.res.converged)
                b->mem[kept++] = *x;
        }
        b->n_mem = kept;
        /* a torn last record (killed mid-write) is dropped and recomputed */
        STC_CHECK(ftruncate(*fd, good) == 0 && lseek(*fd, good, SEEK_SET) == good, STC_EIO,
                  "%s: cannot cut the journal back to its last whole record: %s", jpath,
                  strerror(errno));
        return STC_OK;
    }
    /* new (or cut before its header was whole) */
    int bad = ftruncate(*fd, 0) != 0 || lseek(*fd, 0, SEEK_SET) != 0 ||
              write_all(*fd, JOURNAL_MAGIC, sizeof JOURNAL_MAGIC) != 0 ||
              write_all(*fd, &hash, sizeof hash) != 0 || fdatasync(*fd) != 0;
    STC_CHECK(!bad, STC_EIO, "%s: cannot write the build journal: %s", jpath, strerror(errno));
    return STC_OK;
}

/* One record (magic, index, the payload's parts a and b), checksummed,
 * written with one write() and synced. */
static int journal_append(int fd, uint32_t magic, int index, const void *a, size_t na,
                          const void *b, size_t nb)
{
    record_head rh = {magic, index};
    size_t n = sizeof rh + na + nb;
    unsigned char *buf = malloc(n + sizeof(uint64_t));
    if (!buf) return -1;
    memcpy(buf, &rh, sizeof rh);
    memcpy(buf + sizeof rh, a, na);
    if (nb) memcpy(buf + sizeof rh + na, b, nb);
    uint64_t sum = fnv64(buf, n);
    memcpy(buf + n, &sum, sizeof sum);
    int r = write_all(fd, buf, n + sizeof sum) == 0 && fdatasync(fd) == 0 ? 0 : -1;
    free(buf);
    return r;
}

static int journal_point(int fd, int index, const tbl_point *p)
{
    tbl_point q;
    memset(&q, 0, sizeof q); /* no stray padding bytes in the checksum */
    q = *p;
    return journal_append(fd, POINT_MAGIC, index, &q, sizeof q, NULL, 0);
}

/* A curve's record: the tbl_curve, then P[n_w] and A[n_w]. */
static int journal_curve(int fd, const tbl_table *t, int c, const tbl_curve *cv,
                         const double *P, const double *A)
{
    int nw = t->nrm.n[0];
    size_t nv = 2 * (size_t)nw * sizeof(double);
    double *v = malloc(nv);
    if (!v) return -1;
    memcpy(v, P, (size_t)nw * sizeof *v);
    memcpy(v + nw, A, (size_t)nw * sizeof *v);
    tbl_curve q;
    memset(&q, 0, sizeof q);
    q = *cv;
    int r = journal_append(fd, CURVE_MAGIC, c, &q, sizeof q, v, nv);
    free(v);
    return r;
}

/* A member's record: r (its padding zeroed by the caller). */
static int journal_member(int fd, const tbl_member_rec *r)
{
    return journal_append(fd, MEMBER_MAGIC, r->index, r, sizeof *r, NULL, 0);
}

/* The members point p of the file keeps, as member records of point i for
 * b's store (a refinement goes on from them). */
static int keep_file_members(tbl_build_state *b, int i, const tbl_point *p)
{
    if (p->ens.k < 1 || p->ens.k > ASP_PLACEMENTS_MAX) return 0;
    asp_placement_result *e = malloc(sizeof *e);
    tbl_member_rec *r = malloc(sizeof *r);
    int bad = !e || !r;
    if (!bad) tbl_members_unpack(p, e);
    for (int j = 0; !bad && j < e->k; j++) {
        tbl_member_rec_fill(r, i, e, j);
        bad = keep_member(b, r) != 0;
    }
    free(e);
    free(r);
    return bad ? -1 : 0;
}

/* Points and curves of an existing table at path (same build) join b's
 * table t.  A file without a normal grid (format version 1, say) gives its
 * points to a build that has one, which then computes the curves.  A build
 * that adds or extends refinement (tbl_refines) takes the file's points but
 * leaves those it refines pending (*reopened of them): each is computed
 * again as a build with this refinement from the start computes it, going
 * on from the members the file keeps (b->mem; a file before format 6 keeps
 * none: then from its first member; the members are deterministic), so the
 * table ends up as that build's. */
static stc_status take_existing(tbl_build_state *b, const char *path, int *taken,
                                int *taken_curves, int *reopened)
{
    tbl_table *t = b->t;
    *taken = *taken_curves = *reopened = 0;
    struct stat st;
    if (stat(path, &st) != 0) return STC_OK;
    tbl_table *old = NULL;
    STC_CALL(tbl_read(path, &old));
    int refine = !tbl_same_points(t, old) && tbl_refines(t, old);
    if ((!tbl_same_points(t, old) && !refine) ||
        (old->nrm.level >= 0 && !tbl_same_normal(t, old))) {
        tbl_destroy(&old);
        return STC_FAIL(STC_EINVAL, "%s: a table of another build is there (family, numerics "
                        "or axes differ): choose another file or remove it", path);
    }
    for (int i = 0; i < tbl_points(t); i++) {
        if (t->pt[i].state != TBL_PENDING || old->pt[i].state == TBL_PENDING) continue;
        /* a point another point's run gives is filled from it again */
        if (refine && tbl_point_source(t, i) != i) continue;
        if (refine && tbl_point_refinable(old, &t->num, i)) { /* by t's refinement */
            (*reopened)++;
            if (keep_file_members(b, i, &old->pt[i]) != 0) {
                tbl_destroy(&old);
                return STC_FAIL(STC_ENOMEM, "tbl_build: out of memory");
            }
            continue;
        }
        t->pt[i] = old->pt[i];
        (*taken)++;
    }
    const tbl_normal *g = &old->nrm;
    for (int c = 0; g->level >= 0 && c < tbl_curves(t); c++)
        if (t->nrm.c[c].state == TBL_PENDING && g->c[c].state != TBL_PENDING &&
            tbl_curve_set(t, c, &g->c[c], g->P + (size_t)c * g->n[0],
                          g->A + (size_t)c * g->n[0]) == STC_OK)
            (*taken_curves)++;
    /* the file's build time, not added to t's: a t read from that same file
     * (a fill onto it) holds it already */
    t->build_wall_s = isfinite(old->build_wall_s) ? old->build_wall_s : 0.0;
    tbl_history_carry(t, old->history, old->command);
    tbl_destroy(&old);
    tbl_gp_destroy(&t->gp);
    return STC_OK;
}

/* Report to the caller (holding the build's lock): point i (p), curve c
 * (cv) or member j (m) of k of point i's ensemble; nonzero: stop. */
static int report(tbl_build_state *b, int i, const tbl_point *p, int c, const tbl_curve *cv,
                  const asp_placement_member *m, int j, int k)
{
    if (!b->o->progress) return 0;
    double el = wall_now() - b->t0, eta;
    if (cv) /* during the curves: the rest of the curves */
        eta = b->curves_done < b->curves_total
                  ? el / b->curves_computed * (b->curves_total - b->curves_done)
                  : 0.0;
    else if (m) /* no estimate before the first point */
        eta = b->computed > 0 ? (el - b->curves_wall) / b->computed * (b->total - b->done) : NAN;
    else
        eta = b->done < b->total ? (el - b->curves_wall) / b->computed * (b->total - b->done)
                                 : 0.0;
    tbl_progress pr = {.index = i, .point = p, .curve = c, .c = cv,
                       .member = m ? j : -1, .members = m ? k : 0, .m = m,
                       .curves_done = b->curves_done, .curves_total = b->curves_total,
                       .done = b->done, .total = b->total, .resumed = b->resumed,
                       .failed = b->failed, .elapsed_s = el, .eta_s = eta};
    return b->o->progress(b->o->ctx, &pr);
}

/* After a point: journal first, then the table, then the caller. */
static void build_finish(tbl_build_state *b, int i, const tbl_point *p)
{
    omp_set_lock(&b->lock);
    {
        int stop = 0;
        if (journal_point(b->fd, i, p) != 0) b->io_error = errno ? errno : EIO, stop = 1;
        else {
            b->t->pt[i] = *p;
            b->done++, b->computed++;
            b->failed += p->state == TBL_FAILED;
            b->cpu += p->cpu_s;
            stop = report(b, i, p, -1, NULL, NULL, 0, 0);
        }
        if (stop) {
#pragma omp atomic write
            b->stop = 1;
        }
    }
    omp_unset_lock(&b->lock);
}

/* After a curve: the same. */
static void finish_curve(tbl_build_state *b, int c, const tbl_curve *cv, const double *P,
                         const double *A)
{
    omp_set_lock(&b->lock);
    {
        int stop = 0;
        if (journal_curve(b->fd, b->t, c, cv, P, A) != 0) {
            b->io_error = errno ? errno : EIO, stop = 1;
        } else {
            tbl_curve_set(b->t, c, cv, P, A);
            b->curves_done++, b->curves_computed++;
            b->curves_failed += cv->state == TBL_FAILED;
            b->curves_wall = wall_now() - b->t0;
            stop = report(b, -1, NULL, c, tbl_curve_get(b->t, c), NULL, 0, 0);
        }
        if (stop) {
#pragma omp atomic write
            b->stop = 1;
        }
    }
    omp_unset_lock(&b->lock);
}

/* r NULL: out of memory (the build stops as on a journal error). */
void tbl_member_journal(tbl_build_state *b, const tbl_member_rec *r, int j, int k)
{
    omp_set_lock(&b->lock);
    {
        int stop = 0;
        if (!r || journal_member(b->fd, r) != 0) b->io_error = errno ? errno : EIO, stop = 1;
        else if (b->o->report_members) stop = report(b, r->index, NULL, -1, NULL, &r->m, j, k);
        if (stop) {
#pragma omp atomic write
            b->stop = 1;
        }
    }
    omp_unset_lock(&b->lock);
}

/* asp_placement_store.put of point ctx->i: journal member j of e, then
 * report it. */
static void member_put(void *ctx, const asp_placement_result *e, int j)
{
    const tbl_member_ctx *mc = ctx;
    tbl_member_rec *r = malloc(sizeof *r);
    if (r) tbl_member_rec_fill(r, mc->i, e, j);
    tbl_member_journal(mc->b, r, j, e->k);
    free(r);
}

int tbl_member_recs(tbl_build_state *b, int i, tbl_member_rec *out)
{
    int n = 0, have[ASP_PLACEMENTS_MAX] = {0};
    omp_set_lock(&b->lock);
    for (int r = 0; r < b->n_mem; r++) { /* the first of a slot, as member_get takes */
        const tbl_member_rec *x = &b->mem[r];
        if (x->index != i || have[x->slot]) continue;
        have[x->slot] = 1;
        out[n++] = *x;
    }
    omp_unset_lock(&b->lock);
    return n;
}

void tbl_member_rec_take(const tbl_member_rec *r, asp_placement_result *geom,
                         asp_placement_member *m)
{
    *m = r->m;
    geom->period = r->period, geom->edge_refine = r->edge_refine;
    geom->delta = r->delta, geom->delta_mesh = r->delta_mesh, geom->edge_a0 = r->edge_a0;
}

/* asp_placement_store.get of point ctx->i: a member an earlier run journaled. */
static int member_get(void *ctx, int slot, asp_placement_result *geom, asp_placement_member *m)
{
    tbl_member_ctx *mc = ctx; /* the point's own: its ensemble takes on one thread */
    tbl_build_state *b = mc->b;
    int got = 0;
    omp_set_lock(&b->lock);
    for (int r = 0; r < b->n_mem && !got; r++) {
        const tbl_member_rec *x = &b->mem[r];
        if (x->index != mc->i || x->slot != slot) continue;
        tbl_member_rec_take(x, geom, m);
        got = 1;
    }
    omp_unset_lock(&b->lock);
    if (got) mc->taken++, mc->taken_cpu += m->cpu_s;
    return got;
}

void tbl_member_store(tbl_build_state *b, int i, tbl_member_ctx *ctx, asp_placement_store *s)
{
    ctx->b = b, ctx->i = i, ctx->taken = 0, ctx->taken_cpu = 0.0;
    s->put = member_put, s->get = member_get, s->ctx = ctx;
}

void tbl_members_taken(tbl_build_state *b, int n, double cpu)
{
    omp_set_lock(&b->lock);
    b->members_taken += n;
    b->cpu -= cpu;
    omp_unset_lock(&b->lock);
}

void tbl_member_done(const tbl_member_ctx *ctx)
{
    tbl_members_taken(ctx->b, ctx->taken, ctx->taken_cpu);
}

/* Item k of a todo list: a point i >= 0 (its members on up to `threads`
 * threads), or the curve c coded as -(c + 1). */
static stc_status run_item(tbl_build_state *b, int item, int threads, double *P, double *A)
{
    tbl_point p;
    tbl_curve cv;
    tbl_member_ctx mc;
    asp_placement_store store;
    tbl_member_store(b, item, &mc, &store);
    STC_CALL(tbl_build_item(b->t, item, threads, &store, &p, &cv, P, A));
    if (item >= 0) build_finish(b, item, &p), tbl_member_done(&mc);
    else finish_curve(b, -item - 1, &cv, P, A);
    return STC_OK;
}

/* The serial path: the items (curves first, then points) on this process's
 * threads, one per item; fewer points than threads: a point's members
 * share them (the same numbers; a curve takes seconds beside them). */
static stc_status run_items(tbl_build_state *b, const int *todo, int n)
{
    int want = b->o->jobs > 0 ? b->o->jobs : omp_get_num_procs();
    int jobs = want > n ? (n > 0 ? n : 1) : want;
    int points = 0;
    for (int k = 0; k < n; k++) points += todo[k] >= 0;
    int per = points > 0 && points < want ? want / points : 1; /* threads of a point */
    int nw = tbl_curves(b->t) > 0 ? b->t->nrm.n[0] : 1;
    /* one thread per item, its OpenMP regions and OpenBLAS on it
     * (tbl_build_compute, tbl_build_curve), or per for a point's members */
    stc_status bad = STC_OK;
    char why[512] = "";
#pragma omp parallel num_threads(jobs)
    {
        double *P = malloc((size_t)nw * sizeof *P), *A = malloc((size_t)nw * sizeof *A);
#pragma omp for schedule(dynamic, 1)
        for (int k = 0; k < n; k++) {
            int stop;
#pragma omp atomic read
            stop = b->stop;
            if (stop) continue;
            stc_status s = P && A ? run_item(b, todo[k], per, P, A)
                                  : STC_FAIL(STC_ENOMEM, "tbl_build: out of memory");
            if (s != STC_OK) {
                omp_set_lock(&b->lock);
                if (bad == STC_OK) bad = s, snprintf(why, sizeof why, "%s", stc_errmsg());
                omp_unset_lock(&b->lock);
#pragma omp atomic write
                b->stop = 1;
            }
        }
        free(P);
        free(A);
    }
    if (bad != STC_OK) return STC_FAIL(bad, "%s", why);
    return STC_OK;
}

/* The todo list of this shard: curves (coded -(c + 1)) first, then points;
 * counts into b.  A point whose source is another is not in any share: it
 * is filled from it at the end.  Returns the length. */
static int share(tbl_build_state *b, const tbl_build_opts *o, int *todo, unsigned char *need)
{
    const tbl_table *t = b->t;
    int n = 0;
    if (o->only) tbl_normal_needed(t, o->only, need);
    for (int c = o->shard; c < tbl_curves(t); c += o->shards) {
        int st_c = t->nrm.c[c].state;
        if (tbl_curve_source(t, c) != c) continue; /* filled from its source */
        if ((o->only && !need[c]) || (o->only_failed && st_c == TBL_PENDING)) continue;
        b->curves_total++;
        if (reopens(b, st_c) && !(b->retried && b->retried[tbl_points(t) + c]))
            todo[n++] = -c - 1;
        else b->curves_done++;
    }
    for (int i = o->shard; i < tbl_points(t); i += o->shards) {
        int st_i = t->pt[i].state;
        if (o->curves_only || tbl_point_source(t, i) != i || !tbl_point_wanted(t, o->only, i) ||
            (o->only_failed && st_i == TBL_PENDING))
            continue;
        b->total++;
        if (reopens(b, st_i) && !(b->retried && b->retried[i]))
            todo[n++] = i;
        else b->done++, b->resumed++, b->failed += st_i == TBL_FAILED;
    }
    return n;
}

/* The writer's build (serial, or rank 0 of a distributed one): take the
 * points and curves of an earlier run, compute the rest (the curves first,
 * on this process: they are cheap), write the table. */
static stc_status build_here(tbl_mpi *m, tbl_table *t, const char *path,
                             const tbl_build_opts *o, tbl_build_summary *sum)
{
    tbl_build_state b = {.t = t, .o = o, .finish = build_finish, .finish_curve = finish_curve,
                         .fd = -1, .t0 = wall_now()};
    int from_file = 0, from_journal = 0, cf = 0, cj = 0; /* taken from an earlier run */
    int reopened = 0; /* done points of the file that this build refines */
    int *todo = NULL;
    unsigned char *need = NULL;
    char jpath[4200];
    stc_status st = take_existing(&b, path, &from_file, &cf, &reopened);
    if (st == STC_OK && snprintf(jpath, sizeof jpath, "%s.journal", path) >= (int)sizeof jpath)
        st = STC_FAIL(STC_EINVAL, "%s: path too long", path);
    if (st == STC_OK) st = journal_open(&b, jpath, &from_journal, &cj);
    int np = tbl_points(t), nc = tbl_curves(t), n = 0;
    if (st == STC_OK && (!(todo = malloc((size_t)(np + nc) * sizeof *todo)) ||
                         !(need = calloc((size_t)nc + 1, 1))))
        st = STC_FAIL(STC_ENOMEM, "tbl_build: out of memory");
    if (st != STC_OK) {
        /* the other ranks are waiting for work: release them first */
        if (m->size > 1) tbl_mpi_release(m, st, stc_errmsg());
        if (b.fd >= 0) close(b.fd);
        free(todo);
        free(b.mem);
        free(b.retried);
        return st;
    }
    n = share(&b, o, todo, need);
    free(need);
    /* a lock of this build rather than a named critical section, whose lock
     * would be a global symbol of the shared library */
    omp_init_lock(&b.lock);
    if (m->size > 1) {
        st = tbl_mpi_serve(m, &b, todo, n); /* curves first, as here */
    } else {
        st = run_items(&b, todo, n);
    }
    omp_destroy_lock(&b.lock);
    tbl_mpi_end(m); /* every rank is done: the other ranks need not wait for the file */
    free(todo);
    free(b.mem);
    free(b.retried);
    close(b.fd);
    if (sum) {
        sum->computed = b.computed;
        sum->resumed = b.resumed;
        sum->reopened = reopened;
        sum->failed = b.failed;
        sum->share = b.total;
        sum->members_taken = b.members_taken;
        sum->curves_computed = b.curves_computed;
        sum->curves_failed = b.curves_failed;
        sum->wall_s = wall_now() - b.t0;
        sum->cpu_s = b.cpu;
    }
    if (st != STC_OK) return st;
    STC_CHECK(!b.io_error, STC_EIO, "%s: cannot append to the build journal: %s (the points "
              "finished before are kept)", jpath, strerror(b.io_error));
    STC_CHECK(!b.stop, STC_ENOCONV, "build stopped by the caller after %d of %d points (the "
              "finished ones are in %s; run the build again to go on)", b.done, b.total, jpath);
    t->build_wall_s += wall_now() - b.t0;
    int copied = tbl_fill_copies(t);
    if (sum) sum->copied = copied;
    int done;
    tbl_count(t, &done, NULL, NULL);
    if (done >= 3 && !t->gp) {
        stc_status fs = tbl_fit(t); /* the file records the fit's summary */
        if (fs != STC_OK) stc_error_clear();
    }
    STC_CALL(tbl_write(t, path));
    unlink(jpath); /* the table holds every journal record now */
    return STC_OK;
}

stc_status tbl_build(tbl_table *t, const char *path, const tbl_build_opts *o,
                     tbl_build_summary *sum)
{
    tbl_build_opts def;
    if (!o) tbl_build_opts_default(&def), o = &def;
    STC_CHECK(t && path && *path, STC_EINVAL, "tbl_build: table and path required");
    STC_CHECK(o->shards >= 1 && o->shard >= 0 && o->shard < o->shards, STC_EINVAL,
              "shard = %d/%d: must be i/N with 0 <= i < N", o->shard, o->shards);
    STC_CHECK(o->jobs >= 0 && o->jobs <= 1024, STC_EINVAL, "jobs = %d: must be in [0, 1024]",
              o->jobs);
    if (sum) memset(sum, 0, sizeof *sum);
    tbl_mpi m;
    STC_CALL(tbl_mpi_begin(&m));
    stc_status st = m.rank > 0 ? tbl_mpi_work(t, o, sum) : build_here(&m, t, path, o, sum);
    tbl_mpi_end(&m);
    return st;
}
