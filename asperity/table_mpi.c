/* Distributed table builds: an MPI farm behind tbl_build, where rank 0
 * hands out the points and every rank computes them
 * (include/stiction/table_mpi.h).
 *
 * One binary.  libstiction and the CLI are always linked against Open MPI,
 * but MPI is initialised only when mpirun started the process with more
 * than one rank (OMPI_COMM_WORLD_SIZE > 1), or used when the caller
 * initialised it with more than one process.  A plain run, and `mpirun -n 1`,
 * take the serial OpenMP path of table_build.c and never initialise MPI: the
 * library only asks MPI_Initialized / MPI_Finalized, which the standard
 * allows before MPI_Init.  (A second, MPI-only binary would double the build
 * and the tests for no gain: loading libmpi adds 0.7 ms to a plain run's
 * start-up, measured on an empty program, and nothing else.)  When the
 * library initialised MPI it finalises it as soon as the farm is over, so
 * one process runs one distributed build; a caller that wants more
 * initialises MPI itself.
 *
 * Roles.  Rank 0 is the single writer: it takes the points of an earlier
 * run exactly as the serial path does (the table at the path, then the
 * journal), owns the journal, reports progress through the caller's
 * callback and writes the table at the end.  Ranks >= 1 write no file: they
 * say hello, get a point, compute it on one thread, send it back as bytes,
 * and get the next one in the reply (dynamic scheduling, one point at a
 * time: point costs vary about 10x).  A point comes with the placement
 * members an earlier run finished (the journal's, or those the file keeps
 * for a refinement), which it takes instead of running them, and each
 * member it finishes goes to rank 0 at once, which journals it before its
 * receipt, so a kill loses no finished member on any rank.  The normal
 * grid's curves are handed out the same way, before the points (a curve's
 * values follow its result in a second message), so that no rank waits
 * while rank 0 computes them.
 * --shard combines with the farm: the farm shares out the shard's pending
 * curves and points.
 *
 * Rank 0 computes too: its main thread serves the messages (MPI_THREAD_
 * FUNNELED: only that thread calls MPI) while opts.jobs threads (default 1,
 * as mpirun gives each rank one core) compute points taken from the same
 * queue.  So `mpirun -n N` keeps N cores busy, like the serial path with N
 * threads, instead of leaving one rank to wait.  The serving thread never
 * spins: it polls with MPI_Iprobe and sleeps NAP_NS between polls
 * (measured: 0.14 CPU s in a 7 s build, start-up included; a point takes
 * seconds, so a millisecond of latency does not matter); ranks >= 1 wait
 * for their replies the same way, so no rank relies on Open MPI's
 * mpi_yield_when_idle.
 *
 * Messages are fixed-size structs sent as bytes (every rank runs the same
 * binary; a message of another size is refused, not read).  The hello
 * carries the hash of the rank's build (tbl_build_hash, which covers
 * sizeof(tbl_point)) and its shard, so a rank started with other options
 * fails the build instead of filling it with wrong points.
 *
 * Failures.  A rank whose point cannot be computed sends the message to rank
 * 0; rank 0 then hands out no more points, journals the points still under
 * way as they arrive, answers every rank with the failure (which each
 * returns) and returns it, naming the failing rank.  A failure of rank 0
 * before the farm (a table of another build at the path, the journal) is
 * answered to every rank the same way, so no rank waits for work that will
 * not come.  MPI errors keep MPI_ERRORS_ARE_FATAL: mpirun then ends every
 * rank, and the journal, synced after each point, keeps the finished ones;
 * a rank that dies likewise ends the job (mpirun's default).
 *
 * Measured on the 2-core test machine, otherwise idle, wall time of the
 * whole command for 6 points (--deltas 0.5,1,2 --t-over-R 0.01 --E-ratio 1,2
 * --contact slip --elements-per-contact 3 --placements 1; about 2.2 CPU s a
 * point), range of five runs each:
 *     serial, 2 threads              7.2 - 8.3 s
 *     mpirun -n 2                    7.5 - 8.1 s
 *     mpirun -n 3 --oversubscribe    7.5 - 8.4 s
 * So two cores give the same wall time either way: mpirun's own start-up
 * and finalisation (about 0.3 s) are lost in the spread, and -n 3 just puts
 * three points on two cores.  Every number of every point equals the
 * one-thread serial build's bit for bit (tests/test_table_mpi.c).
 */
#include <mpi.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stc_check.h"
#include "stiction/table_mpi.h"
#include "table_impl.h"

/* Message tags: worker -> rank 0, rank 0 -> worker, a curve's values, a
 * handed-out point's members an earlier run finished (rank 0 -> worker, after
 * the point's TAG_DOWN), rank 0's receipt of a member (no payload). */
enum { TAG_UP = 1, TAG_DOWN = 2, TAG_VALUES = 3, TAG_MEMBERS = 4, TAG_ACK = 5 };
/* Kinds of a worker's message. */
enum { UP_HELLO = 1, UP_POINT = 2, UP_FAIL = 3, UP_CURVE = 4, UP_MEMBER = 5 };
/* Room for a message (stc_errmsg holds up to 1023 characters). */
enum { WHY_MAX = 1024 };
/* given[] of a rank without an item (items are points >= 0 and curves < 0). */
#define NO_ITEM INT32_MIN
/* Pause between two polls of a waiting rank, ns. */
#define NAP_NS 1000000L

typedef struct {
    int32_t kind;      /* UP_* */
    int32_t index;     /* UP_POINT, UP_CURVE: the item (a point i, or curve c as -(c + 1)) */
    int32_t code;      /* UP_FAIL: the stc_status */
    int32_t shard, shards;
    uint64_t hash;     /* UP_HELLO: tbl_build_hash of the rank's table */
    tbl_point p;       /* UP_POINT */
    int32_t taken;     /* UP_POINT: members it took from an earlier run, */
    double taken_cpu;  /*   and their CPU s */
    tbl_curve c;       /* UP_CURVE; its P[n_w] and A[n_w] follow, tagged TAG_VALUES */
    tbl_member_rec rec;/* UP_MEMBER: a finished member of the point the rank computes, */
    int32_t j, k;      /*   member j of k (answered with TAG_ACK, not TAG_DOWN) */
    char why[WHY_MAX]; /* UP_FAIL */
} msg_up;

typedef struct {
    int32_t stop;      /* 0: compute item; 1: stop */
    int32_t item;      /* a point i >= 0, or curve c as -(c + 1) */
    int32_t code;      /* with stop: STC_OK (all handed out) or why the build failed */
    char why[WHY_MAX];
} msg_down;

static int launched_size(void)
{
    const char *s = getenv("OMPI_COMM_WORLD_SIZE");
    return s ? atoi(s) : 0;
}

void tbl_build_rank(int *rank, int *size)
{
    int init = 0, fin = 0;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    *rank = 0, *size = 1;
    if (init && !fin) {
        MPI_Comm_rank(MPI_COMM_WORLD, rank);
        MPI_Comm_size(MPI_COMM_WORLD, size);
    } else if (launched_size() > 1) {
        const char *r = getenv("OMPI_COMM_WORLD_RANK");
        *size = launched_size();
        *rank = r ? atoi(r) : 0;
    }
}

stc_status tbl_mpi_begin(tbl_mpi *m)
{
    memset(m, 0, sizeof *m);
    m->size = 1;
    int init = 0, fin = 0, level = MPI_THREAD_SINGLE;
    MPI_Initialized(&init);
    MPI_Finalized(&fin); /* MPI_Initialized stays true after MPI_Finalize */
    if (fin || !init) {
        if (launched_size() <= 1) return STC_OK; /* a plain run, or mpirun -n 1 */
        STC_CHECK(!fin, STC_EUNSUPPORTED, "this process ran a distributed build already and "
                  "MPI is finalised: one build per process under mpirun, unless the caller "
                  "initialises MPI (MPI_Init_thread, MPI_THREAD_FUNNELED) for all of them");
        MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &level);
        m->owned = 1;
    } else {
        MPI_Query_thread(&level);
    }
    int main_thread = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &m->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m->size);
    MPI_Is_thread_main(&main_thread);
    m->threads = (level >= MPI_THREAD_FUNNELED && main_thread) ||
                 level >= MPI_THREAD_SERIALIZED;
    if (m->size == 1) tbl_mpi_end(m);
    return STC_OK;
}

void tbl_mpi_end(tbl_mpi *m)
{
    if (m->owned) MPI_Finalize();
    m->owned = 0;
    m->rank = 0, m->size = 1;
}

static void nap(void)
{
    struct timespec ts = {0, NAP_NS};
    nanosleep(&ts, NULL);
}

/* Wait without spinning for a message with tag from src; its status in *st. */
static void wait_message(int src, int tag, MPI_Status *st)
{
    for (;;) {
        int flag = 0;
        MPI_Iprobe(src, tag, MPI_COMM_WORLD, &flag, st);
        if (flag) return;
        nap();
    }
}

/* ---- rank 0 ----------------------------------------------------------------- */

typedef struct {
    tbl_build_state *b; /* NULL when only releasing the other ranks */
    const int *todo;    /* items: points i >= 0, curves c as -(c + 1) */
    int n, next;        /* todo[next] is handed out next (atomic) */
    int *given;         /* [size]: the item each rank computes, NO_ITEM none */
    int open;           /* ranks not yet told to stop */
    uint64_t hash;
    int shard, shards;
    stc_status fail;    /* the first failure (under lock) */
    char why[WHY_MAX];
    omp_lock_t lock;    /* guards fail and why while the farm runs (farm_run); a
                           lock of the farm's, not a named critical section,
                           whose lock would be a global symbol of the library */
} farm;

static void farm_fail(farm *f, stc_status s, const char *msg)
{
    omp_set_lock(&f->lock);
    if (f->fail == STC_OK) {
        f->fail = s;
        snprintf(f->why, sizeof f->why, "%s", msg);
    }
    omp_unset_lock(&f->lock);
    if (f->b) {
#pragma omp atomic write
        f->b->stop = 1;
    }
}

/* The next item to compute into *item: 1, or 0 when the farm is stopped or
 * empty. */
static int farm_take(farm *f, int *item)
{
    int stop = 1, k;
    if (f->b) {
#pragma omp atomic read
        stop = f->b->stop;
    }
    if (stop) return 0;
#pragma omp atomic capture
    k = f->next++;
    if (k >= f->n) return 0;
    *item = f->todo[k];
    return 1;
}

/* The reply to rank src: its next item, or stop with the farm's outcome. */
static void farm_reply(farm *f, int src)
{
    msg_down d;
    memset(&d, 0, sizeof d);
    d.stop = !farm_take(f, &d.item);
    if (f->given) f->given[src] = d.stop ? NO_ITEM : d.item;
    if (d.stop) {
        stc_status fail;
        int stop = 0;
        omp_set_lock(&f->lock);
        fail = f->fail;
        snprintf(d.why, sizeof d.why, "%s", f->why);
        omp_unset_lock(&f->lock);
        if (f->b) {
#pragma omp atomic read
            stop = f->b->stop;
        }
        d.code = fail != STC_OK ? (int32_t)fail : stop ? STC_ENOCONV : STC_OK;
        if (fail == STC_OK && stop)
            snprintf(d.why, sizeof d.why, "rank 0 stopped the build (a journal error or "
                     "its caller's request; rank 0's message says which)");
        f->open--;
    }
    MPI_Send(&d, (int)sizeof d, MPI_BYTE, src, TAG_DOWN, MPI_COMM_WORLD);
    if (!d.stop && d.item >= 0) { /* the point's members an earlier run finished */
        tbl_member_rec *r = calloc(ASP_PLACEMENTS_MAX, sizeof *r);
        int n = r && f->b ? tbl_member_recs(f->b, d.item, r) : 0; /* none: computed anew */
        MPI_Send(r, n * (int)sizeof *r, MPI_BYTE, src, TAG_MEMBERS, MPI_COMM_WORLD);
        free(r);
    }
}

/* A curve's result from rank src (u) and the values that follow it. */
static void curve_values(farm *f, int src, const msg_up *u, char *msg, size_t n)
{
    int nw = f->b && tbl_curves(f->b->t) > 0 ? f->b->t->nrm.n[0] : 0, count = 0;
    MPI_Status st;
    wait_message(src, TAG_VALUES, &st);
    MPI_Get_count(&st, MPI_DOUBLE, &count);
    double *v = malloc((size_t)(count > 0 ? count : 1) * sizeof *v);
    if (!v) {
        snprintf(msg, n, "rank 0: out of memory");
        return; /* MPI's truncation error ends the job on the unread values */
    }
    MPI_Recv(v, count, MPI_DOUBLE, src, TAG_VALUES, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!f->given || u->index != f->given[src] || u->index >= 0 || u->index == NO_ITEM)
        snprintf(msg, n, "rank %d: sent curve %d, which it was not given", src,
                 (int)(-u->index - 1));
    else if (count != 2 * nw)
        snprintf(msg, n, "rank %d: a curve of %d values, not %d", src, count, 2 * nw);
    else f->b->finish_curve(f->b, -u->index - 1, &u->c, v, v + nw);
    free(v);
}

/* One message from another rank, and the reply to it. */
static void farm_handle(farm *f)
{
    MPI_Status st;
    wait_message(MPI_ANY_SOURCE, TAG_UP, &st);
    int src = st.MPI_SOURCE, bytes = 0;
    MPI_Get_count(&st, MPI_BYTE, &bytes);
    msg_up u;
    char msg[WHY_MAX + 64] = "";
    stc_status bad = STC_EINVAL;
    if (bytes != (int)sizeof u) {
        /* read and dropped (with no room for it, MPI's truncation error ends the job) */
        char *junk = malloc(bytes > 0 ? (size_t)bytes : 1);
        MPI_Recv(junk ? (void *)junk : (void *)&u, junk ? bytes : (int)sizeof u, MPI_BYTE, src,
                 TAG_UP, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        free(junk);
        snprintf(msg, sizeof msg, "rank %d: a message of %d bytes, not %d: every rank must "
                 "run the same stiction binary", src, bytes, (int)sizeof u);
    } else {
        MPI_Recv(&u, (int)sizeof u, MPI_BYTE, src, TAG_UP, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (u.kind == UP_HELLO) {
            if (u.hash != f->hash || u.shard != f->shard || u.shards != f->shards)
                snprintf(msg, sizeof msg, "rank %d: another build (family, numerics, axes or "
                         "shard differ from rank 0's): start every rank with the same "
                         "options", src);
        } else if (u.kind == UP_MEMBER) { /* answered with a receipt, not the next item */
            if (!f->b || !f->given || u.index != f->given[src] || u.index < 0 ||
                u.rec.index != u.index || u.rec.slot < 0 || u.rec.slot >= ASP_PLACEMENTS_MAX ||
                u.k < 1 || u.k > ASP_PLACEMENTS_MAX || u.j < 0 || u.j >= u.k)
                snprintf(msg, sizeof msg, "rank %d: sent a member of point %d, which it was "
                         "not given", src, (int)u.index);
            else tbl_member_journal(f->b, &u.rec, u.j, u.k);
            if (msg[0]) farm_fail(f, bad, msg);
            MPI_Send(NULL, 0, MPI_BYTE, src, TAG_ACK, MPI_COMM_WORLD);
            return;
        } else if (u.kind == UP_POINT) {
            if (!f->b || !f->given || u.index != f->given[src] || u.index < 0)
                snprintf(msg, sizeof msg, "rank %d: sent point %d, which it was not given",
                         src, (int)u.index);
            else {
                f->b->finish(f->b, u.index, &u.p);
                tbl_members_taken(f->b, u.taken, u.taken_cpu);
            }
        } else if (u.kind == UP_CURVE) {
            curve_values(f, src, &u, msg, sizeof msg);
        } else if (u.kind == UP_FAIL) {
            u.why[WHY_MAX - 1] = '\0';
            if (u.code > STC_OK && u.code < STC_NSTATUS) bad = (stc_status)u.code;
            snprintf(msg, sizeof msg, "rank %d: %s", src, u.why);
        } else {
            snprintf(msg, sizeof msg, "rank %d: a message of unknown kind %d", src,
                     (int)u.kind);
        }
    }
    if (msg[0]) farm_fail(f, bad, msg);
    farm_reply(f, src);
}

/* Rank 0's compute threads: items from the shared queue until it is empty
 * or stopped. */
static void farm_compute(farm *f)
{
    int item, nw = tbl_curves(f->b->t) > 0 ? f->b->t->nrm.n[0] : 1;
    double *v = malloc(2 * (size_t)nw * sizeof *v);
    if (!v) {
        farm_fail(f, STC_ENOMEM, "rank 0: out of memory");
        return;
    }
    while (farm_take(f, &item)) {
        tbl_point p;
        tbl_curve cv;
        tbl_member_ctx mc; /* rank 0 journals its own points' members */
        asp_placement_store store;
        tbl_member_store(f->b, item, &mc, &store);
        stc_status s = tbl_build_item(f->b->t, item, 1, &store, &p, &cv, v, v + nw);
        if (s != STC_OK) {
            char msg[WHY_MAX + 64];
            snprintf(msg, sizeof msg, "rank 0: %s", stc_errmsg());
            farm_fail(f, s, msg);
            break;
        }
        if (item >= 0) f->b->finish(f->b, item, &p), tbl_member_done(&mc);
        else f->b->finish_curve(f->b, -item - 1, &cv, v, v + nw);
    }
    free(v);
}

static stc_status farm_run(const tbl_mpi *m, farm *f)
{
    omp_init_lock(&f->lock);
    f->open = m->size - 1;
    f->given = malloc((size_t)m->size * sizeof *f->given);
    if (f->given) for (int r = 0; r < m->size; r++) f->given[r] = NO_ITEM;
    else farm_fail(f, STC_ENOMEM, "rank 0: out of memory"); /* still release every rank */
    int jobs = 0; /* compute threads besides the serving one */
    if (f->b && m->threads) jobs = f->b->o->jobs > 0 ? f->b->o->jobs : 1;
    if (jobs > f->n) jobs = f->n;
    /* a point's OpenMP regions and OpenBLAS run on its compute thread, as
     * in the serial path (table.c, tbl_build_compute) */
#pragma omp parallel num_threads(1 + jobs)
    {
        if (omp_get_thread_num() == 0) { /* the thread that called MPI_Init */
            while (f->open > 0) farm_handle(f);
        } else {
            farm_compute(f);
        }
    }
    free(f->given);
    f->given = NULL;
    omp_destroy_lock(&f->lock);
    if (f->fail != STC_OK) return STC_FAIL(f->fail, "%s", f->why);
    return STC_OK;
}

stc_status tbl_mpi_serve(const tbl_mpi *m, tbl_build_state *b, const int *todo, int n)
{
    farm f = {.b = b, .todo = todo, .n = n, .hash = tbl_build_hash(b->t),
              .shard = b->o->shard, .shards = b->o->shards};
    return farm_run(m, &f);
}

void tbl_mpi_release(const tbl_mpi *m, stc_status s, const char *why)
{
    farm f = {.fail = s};
    snprintf(f.why, sizeof f.why, "%s", why);
    farm_run(m, &f); /* returns s again, with the same message */
}

/* ---- ranks >= 1 ---------------------------------------------------------------- */

/* The members of the point a rank computes: those an earlier run finished,
 * as rank 0 handed them out with the point, and each one finished here
 * sent to rank 0 to journal (the point runs on the thread that called
 * MPI_Init: one thread, its members one after another). */
typedef struct {
    int i, n;
    tbl_member_rec rec[ASP_PLACEMENTS_MAX];
    int taken;
    double taken_cpu;
    msg_up *u; /* a message's room */
} worker_members;

static void worker_put(void *ctx, const asp_placement_result *e, int j)
{
    worker_members *w = ctx;
    memset(w->u, 0, sizeof *w->u);
    w->u->kind = UP_MEMBER;
    w->u->index = w->i;
    tbl_member_rec_fill(&w->u->rec, w->i, e, j);
    w->u->j = j, w->u->k = e->k;
    MPI_Send(w->u, (int)sizeof *w->u, MPI_BYTE, 0, TAG_UP, MPI_COMM_WORLD);
    MPI_Status st;
    wait_message(0, TAG_ACK, &st);
    MPI_Recv(NULL, 0, MPI_BYTE, 0, TAG_ACK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

static int worker_get(void *ctx, int slot, asp_placement_result *geom, asp_placement_member *m)
{
    worker_members *w = ctx;
    for (int r = 0; r < w->n; r++) {
        const tbl_member_rec *x = &w->rec[r];
        if (x->slot != slot) continue;
        tbl_member_rec_take(x, geom, m);
        w->taken++, w->taken_cpu += m->cpu_s;
        return 1;
    }
    return 0;
}

/* After the TAG_DOWN that handed out point i: its members from rank 0. */
static void worker_members_recv(worker_members *w, int i)
{
    MPI_Status st;
    int bytes = 0;
    wait_message(0, TAG_MEMBERS, &st);
    MPI_Get_count(&st, MPI_BYTE, &bytes);
    /* a count that does not fit is MPI's truncation error, which ends the job */
    MPI_Recv(w->rec, (int)sizeof w->rec, MPI_BYTE, 0, TAG_MEMBERS, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    w->i = i;
    w->n = bytes / (int)sizeof w->rec[0];
    w->taken = 0, w->taken_cpu = 0.0;
}

static double seconds_since(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return (double)(t1.tv_sec - t0->tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0->tv_nsec);
}

stc_status tbl_mpi_work(tbl_table *t, const tbl_build_opts *o, tbl_build_summary *sum)
{
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    msg_up u;
    msg_down d;
    stc_status st = STC_OK;
    int computed = 0, failed = 0, share = 0, curves = 0, curves_failed = 0;
    int nw = tbl_curves(t) > 0 ? t->nrm.n[0] : 1;
    double cpu = 0;
    double *v = malloc(2 * (size_t)nw * sizeof *v);
    worker_members *wm = malloc(sizeof *wm);
    msg_up *mu = malloc(sizeof *mu);
    if (!v || !wm || !mu) {
        free(v), free(wm), free(mu);
        return STC_FAIL(STC_ENOMEM, "tbl_build: out of memory"); /* rank 0 sees this rank end */
    }
    wm->u = mu;
    asp_placement_store store = {worker_put, worker_get, wm};
    memset(&u, 0, sizeof u); /* no stray bytes on the wire */
    u.kind = UP_HELLO;
    u.hash = tbl_build_hash(t);
    u.shard = o->shard, u.shards = o->shards;
    for (int i = o->shard; i < tbl_points(t); i += o->shards)
        share += tbl_point_source(t, i) == i && tbl_point_wanted(t, o->only, i);
    /* one thread per point, its OpenMP regions (CHOLMOD's) and OpenBLAS on
     * it too, as on the writer's threads (table.c, tbl_build_compute; measured:
     * CHOLMOD's own threads made no difference to the numbers) */
    for (;;) {
        MPI_Status ms;
        MPI_Send(&u, (int)sizeof u, MPI_BYTE, 0, TAG_UP, MPI_COMM_WORLD);
        if (u.kind == UP_CURVE) MPI_Send(v, 2 * nw, MPI_DOUBLE, 0, TAG_VALUES, MPI_COMM_WORLD);
        wait_message(0, TAG_DOWN, &ms);
        MPI_Recv(&d, (int)sizeof d, MPI_BYTE, 0, TAG_DOWN, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (d.stop) break;
        memset(&u, 0, sizeof u);
        u.index = d.item;
        int c = -d.item - 1;
        if (d.item >= 0) worker_members_recv(wm, d.item);
        stc_status s = d.item < tbl_points(t)
                           ? tbl_build_item(t, d.item, 1, d.item >= 0 ? &store : NULL, &u.p,
                                            &u.c, v, v + nw)
                           : STC_FAIL(STC_EINVAL, "point %d: not in the table of %d points",
                                      (int)d.item, tbl_points(t));
        if (s != STC_OK) { /* told to rank 0 in the next message; kept as our status */
            if (st == STC_OK) st = s;
            u.kind = UP_FAIL;
            u.code = s;
            snprintf(u.why, sizeof u.why, "%s", stc_errmsg());
            continue;
        }
        if (d.item < 0) { /* sent next, its values after it */
            u.kind = UP_CURVE;
            tbl_curve_set(t, c, &u.c, v, v + nw);
            curves++;
            curves_failed += u.c.state == TBL_FAILED;
            continue;
        }
        u.kind = UP_POINT;
        u.taken = wm->taken, u.taken_cpu = wm->taken_cpu;
        tbl_point_set(t, d.item, &u.p);
        computed++;
        failed += u.p.state == TBL_FAILED;
        cpu += u.p.cpu_s - wm->taken_cpu;
    }
    free(v);
    free(wm);
    free(mu);
    if (st == STC_OK && d.code != STC_OK) {
        d.why[WHY_MAX - 1] = '\0';
        st = STC_FAIL(d.code > STC_OK && d.code < STC_NSTATUS ? (stc_status)d.code : STC_EINVAL,
                      "rank 0 stopped the build: %s", d.why);
    }
    if (sum) {
        sum->computed = computed;
        sum->failed = failed;
        sum->share = share;
        sum->curves_computed = curves;
        sum->curves_failed = curves_failed;
        sum->wall_s = seconds_since(&t0);
        sum->cpu_s = cpu;
    }
    return st;
}
