/* Building a friction table: the points of a shard computed concurrently,
 * each finished point appended to a journal before anything else, the table
 * written atomically at the end (include/stiction/table.h, tbl_build).
 *
 * Journal: a header (8-byte magic, the build's hash) and then one record per
 * finished point: magic, index, the point's bytes, a checksum.  Each record
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

void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);

static const char JOURNAL_MAGIC[8] = {'S', 'T', 'C', 'T', 'B', 'L', 'J', '1'};
#define RECORD_MAGIC 0x50544254u /* "TBTP" */

typedef struct {
    uint32_t magic;
    int32_t index;
    tbl_point p;
    uint64_t sum;
} record;

static uint64_t record_sum(const record *r)
{
    uint64_t h = 14695981039346656037ULL;
    const unsigned char *b = (const unsigned char *)r;
    for (size_t i = 0; i < offsetof(record, sum); i++) h = (h ^ b[i]) * 1099511628211ULL;
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

/* Open the journal of t at jpath: take its whole records into t (pending
 * points only), cut off a torn tail, or start a new journal.  *fd open for
 * appending; *taken the points taken. */
static stc_status journal_open(tbl_table *t, const char *jpath, int *fd, int *taken)
{
    uint64_t hash = tbl_build_hash(t);
    *taken = 0;
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
                            "axes differ): remove it, or build with the options that made it",
                            jpath);
        }
        off_t good = (off_t)(sizeof magic + sizeof h);
        record r;
        while (read(*fd, &r, sizeof r) == (ssize_t)sizeof r && r.magic == RECORD_MAGIC &&
               r.sum == record_sum(&r) && r.index >= 0 && r.index < tbl_points(t)) {
            if (t->pt[r.index].state == TBL_PENDING && r.p.state != TBL_PENDING) {
                if (tbl_point_set(t, r.index, &r.p) == STC_OK) (*taken)++;
            }
            good += (off_t)sizeof r;
        }
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

static int journal_append(int fd, int index, const tbl_point *p)
{
    record r;
    memset(&r, 0, sizeof r); /* no stray padding bytes in the checksum */
    r.magic = RECORD_MAGIC;
    r.index = index;
    r.p = *p;
    r.sum = record_sum(&r);
    return write_all(fd, &r, sizeof r) == 0 && fdatasync(fd) == 0 ? 0 : -1;
}

/* Points of an existing table at path (same build) join t. */
static stc_status take_existing(tbl_table *t, const char *path, int *taken)
{
    *taken = 0;
    struct stat st;
    if (stat(path, &st) != 0) return STC_OK;
    tbl_table *old = NULL;
    STC_CALL(tbl_read(path, &old));
    if (!tbl_same_build(t, old)) {
        tbl_destroy(&old);
        return STC_FAIL(STC_EINVAL, "%s: a table of another build is there (family, numerics "
                        "or axes differ): choose another file or remove it", path);
    }
    for (int i = 0; i < tbl_points(t); i++)
        if (t->pt[i].state == TBL_PENDING && old->pt[i].state != TBL_PENDING) {
            t->pt[i] = old->pt[i];
            (*taken)++;
        }
    if (isfinite(old->build_wall_s)) t->build_wall_s += old->build_wall_s;
    tbl_destroy(&old);
    tbl_gp_destroy(&t->gp);
    return STC_OK;
}

stc_status tbl_build_compute(const tbl_table *t, int i, tbl_point *p)
{
    double w, tR, E;
    tbl_coords(t, i, &w, &tR, &E);
    return tbl_point_compute(&t->fam, &t->num, w, tR, E, p);
}

/* After a point: journal first, then the table, then the caller. */
void tbl_build_finish(tbl_build_state *b, int i, const tbl_point *p)
{
    omp_set_lock(&b->lock);
    {
        int stop = 0;
        if (journal_append(b->fd, i, p) != 0) b->io_error = errno ? errno : EIO, stop = 1;
        else {
            b->t->pt[i] = *p;
            b->done++, b->computed++;
            b->failed += p->state == TBL_FAILED;
            b->cpu += p->cpu_s;
            if (b->o->progress) {
                double el = wall_now() - b->t0;
                tbl_progress pr = {i, p, b->done, b->total, b->resumed, b->failed, el,
                                   b->done < b->total
                                       ? el / b->computed * (b->total - b->done)
                                       : 0.0};
                if (b->o->progress(b->o->ctx, &pr)) stop = 1;
            }
        }
        if (stop) {
#pragma omp atomic write
            b->stop = 1;
        }
    }
    omp_unset_lock(&b->lock);
}

/* The serial path: the points on this process's threads, one per point. */
static stc_status run_points(tbl_build_state *b, const int *todo, int n)
{
    int jobs = b->o->jobs > 0 ? b->o->jobs : omp_get_num_procs();
    if (jobs > n) jobs = n > 0 ? n : 1;
    /* one thread per point: the solver's own OpenMP regions (CHOLMOD's)
     * run on that thread.  Two or more points at once: one active level,
     * the points'.  One at a time: none, since inside a team of one thread
     * the solver's regions would be the first active level, and creating a
     * nested team that often made a point 3x slower (1.33 -> 4.0 s, same
     * numbers) */
    int levels = omp_get_max_active_levels();
    omp_set_max_active_levels(jobs > 1 ? 1 : 0);
    /* OpenBLAS on one thread too: the table's numbers then do not depend on
     * jobs, shards or ranks (both restored below) */
    int bt = openblas_get_num_threads();
    openblas_set_num_threads(1);
    stc_status bad = STC_OK;
    char why[512] = "";
#pragma omp parallel for schedule(dynamic, 1) num_threads(jobs)
    for (int k = 0; k < n; k++) {
        int stop;
#pragma omp atomic read
        stop = b->stop;
        if (stop) continue;
        tbl_point p;
        stc_status s = tbl_build_compute(b->t, todo[k], &p);
        if (s != STC_OK) {
            omp_set_lock(&b->lock);
            if (bad == STC_OK) bad = s, snprintf(why, sizeof why, "%s", stc_errmsg());
            omp_unset_lock(&b->lock);
#pragma omp atomic write
            b->stop = 1;
            continue;
        }
        tbl_build_finish(b, todo[k], &p);
    }
    openblas_set_num_threads(bt);
    omp_set_max_active_levels(levels);
    if (bad != STC_OK) return STC_FAIL(bad, "%s", why);
    return STC_OK;
}

/* The writer's build (serial, or rank 0 of a distributed one): take the
 * points of an earlier run, compute the rest, write the table. */
static stc_status build_here(tbl_mpi *m, tbl_table *t, const char *path,
                             const tbl_build_opts *o, tbl_build_summary *sum)
{
    tbl_build_state b = {.t = t, .o = o, .fd = -1, .t0 = wall_now()};
    int from_file = 0, from_journal = 0; /* points taken from an earlier run */
    int *todo = NULL;
    char jpath[4200];
    stc_status st = take_existing(t, path, &from_file);
    if (st == STC_OK && snprintf(jpath, sizeof jpath, "%s.journal", path) >= (int)sizeof jpath)
        st = STC_FAIL(STC_EINVAL, "%s: path too long", path);
    if (st == STC_OK) st = journal_open(t, jpath, &b.fd, &from_journal);
    int np = tbl_points(t), n = 0;
    if (st == STC_OK && !(todo = malloc((size_t)np * sizeof *todo)))
        st = STC_FAIL(STC_ENOMEM, "tbl_build: out of memory");
    if (st != STC_OK) {
        /* the other ranks are waiting for work: release them first */
        if (m->size > 1) tbl_mpi_release(m, st, stc_errmsg());
        if (b.fd >= 0) close(b.fd);
        return st;
    }
    for (int i = o->shard; i < np; i += o->shards) {
        int st_i = t->pt[i].state;
        if ((o->only && !o->only[i]) || (o->only_failed && st_i == TBL_PENDING)) continue;
        b.total++;
        if (st_i == TBL_PENDING || ((o->retry_failed || o->only_failed) && st_i == TBL_FAILED))
            todo[n++] = i;
        else b.done++, b.resumed++, b.failed += st_i == TBL_FAILED;
    }
    /* a lock of this build rather than a named critical section, whose lock
     * would be a global symbol of the shared library */
    omp_init_lock(&b.lock);
    st = m->size > 1 ? tbl_mpi_serve(m, &b, todo, n) : run_points(&b, todo, n);
    omp_destroy_lock(&b.lock);
    tbl_mpi_end(m); /* every rank is done: the other ranks need not wait for the file */
    free(todo);
    close(b.fd);
    if (sum) {
        sum->computed = b.computed;
        sum->resumed = b.resumed;
        sum->failed = b.failed;
        sum->share = b.total;
        sum->wall_s = wall_now() - b.t0;
        sum->cpu_s = b.cpu;
    }
    if (st != STC_OK) return st;
    STC_CHECK(!b.io_error, STC_EIO, "%s: cannot append to the build journal: %s (the points "
              "finished before are kept)", jpath, strerror(b.io_error));
    STC_CHECK(!b.stop, STC_ENOCONV, "build stopped by the caller after %d of %d points (the "
              "finished ones are in %s; run the build again to go on)", b.done, b.total, jpath);
    t->build_wall_s += wall_now() - b.t0;
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
