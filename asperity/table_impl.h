/* Private layout of a friction table (include/stiction/table.h), shared by
 * table.c (the handle), table_io.c (HDF5), table_build.c (sweeps and the
 * journal), table_mpi.c (distributed sweeps) and table_interp.c
 * (interpolation and the asperity model). */
#ifndef STICTION_TABLE_IMPL_H
#define STICTION_TABLE_IMPL_H

#include <omp.h>
#include <stdint.h>

#include "stiction/table.h"
#include "table_fit.h"

/* Stored format (docs/table-format.md); a reader refuses other versions. */
#define TBL_FORMAT_NAME "stiction friction table"
#define TBL_FORMAT_VERSION 7 /* 2: the normal grid (/normal), 3: foot_rows, 4: copied
                                points, 5: copied curves, 6: the points' members
                                (/members), 7: mu_s_ux_slope (points and members);
                                1 to 6 are read too */

/* The reference sphere every point is computed on (the response is
 * independent of both, include/stiction/table.h). */
#define TBL_REF_R_MM 10.0
#define TBL_REF_E_SU_MPA 200000.0

/* The normal grid (table_normal.c): axisymmetric load curves, one per
 * (t/R, Eco/Esu) node, through every δ node. */
typedef struct tbl_normal {
    int level;         /* axisymmetric mesh level; -1: no normal grid (all else empty) */
    int n[3];          /* axis lengths: w, t/R, Eco/Esu */
    double *ax[3];     /* [n[k]] */
    tbl_curve *c;      /* [n[2]][n[1]] */
    double *P, *A;     /* [n[2]][n[1]][n[0]]: P/Pc_su (smoothed), A/Ac_su; NaN unless done */
} tbl_normal;

struct tbl_table {
    tbl_family fam;
    tbl_numerics num;
    int n[3];          /* axis lengths: w, t/R, Eco/Esu */
    double *ax[3];     /* [n[k]] */
    tbl_point *pt;     /* [n[2]][n[1]][n[0]] */
    char command[512]; /* provenance: how it was built */
    char history[2048]; /* the commands that built it before, oldest first, one a line */
    double build_wall_s;
    tbl_gp *gp;        /* μs surrogate, NULL until tbl_fit */
    tbl_fit_info fit;
    /* The surrogate's hyperparameters and a hash of the data they fit
     * (tbl_fit sets them, tbl_read takes them from /fit); tbl_fit reuses
     * them instead of searching while its data hash the same. */
    uint64_t fit_hash;
    int fit_npar;      /* -1: none */
    double fit_par[TBL_GP_MAXPAR];
    tbl_normal nrm;
};

/* t's history from the file it is built onto: that file's history, then
 * the file's command when it is not t's own (a fill onto a build, a build
 * onto a fill); the oldest lines give way to a first line "..." when it
 * would not fit. */
void tbl_history_carry(tbl_table *t, const char *history, const char *command);

/* ---- the normal grid (table_normal.c) ---- */

/* The normal grid of t from its axes and t->num.normal_level (none when
 * that is -1): every curve pending. */
stc_status tbl_normal_init(tbl_table *t);
/* The same on the given axes (a file's); copied. */
stc_status tbl_normal_init_axes(tbl_table *t, double *const ax[3], const int n[3]);
void tbl_normal_free(tbl_normal *g);
/* Same level and axes (bitwise): curves of one may be taken into the other. */
int tbl_same_normal(const tbl_table *a, const tbl_table *b);
/* ---- the normal curves (table_curve.c) ---- */

/* The curves a build restricted to the points only[] needs: those at the
 * t/R and Eco/Esu the chosen points span (need[c] = 1, else 0). */
void tbl_normal_needed(const tbl_table *t, const unsigned char *only, unsigned char *need);
/* Curve c of t computed on the calling thread (tbl_curve_compute); P, A:
 * [n_w of the normal grid]. */
stc_status tbl_build_curve(const tbl_table *t, int c, tbl_curve *out, double *P, double *A);

/* The monotonic wall clock, s (a point's and a curve's costs; their CPU
 * time: asp_thread_cpu, threads.h). */
double tbl_wall_now(void);

/* Eco/Esu = E_ratio makes the coating the substrate in family f: E_ratio 1
 * with the same E/Y and ν in both layers (τc = its rule times Y_co = Y_su). */
int tbl_family_one_material(const tbl_family *f, double E_ratio);
/* Parameters of the reference sphere for a point of family f (where the
 * coating is the substrate, the uncoated sphere: t/R 0). */
void tbl_point_params(const tbl_family *f, double t_over_R, double E_ratio, stc_params *p);

/* Index of the axis node at or below x (clamped to [0, n-2]) and the linear
 * weight of the node above in ln x (0..1 inside; clamped outside). */
int tbl_bracket(const double *ax, int n, double x, double *frac);

/* 64-bit FNV-1a of the build's definition (family, numerics, axes): the
 * journal's header, so a journal is only ever read by its own build. */
unsigned long long tbl_build_hash(const tbl_table *t);
/* The same without the normal grid: the points of a and b are of one build
 * (a file without a normal grid may be completed by one). */
int tbl_same_points(const tbl_table *a, const tbl_table *b);
/* t's build is old's with refinement added or extended: the same points but
 * for the refinement settings, and t refining at least where old did
 * (placements_max no lower, refine_err no higher, the same floor). */
int tbl_refines(const tbl_table *t, const tbl_table *old);
/* Point i of t is done and the refinement of numerics n (t's, or one that
 * extends it) would give it more members, as asp_shear_placements_adaptive
 * decides: twice its members still within placements_max, and their standard
 * error of the mean (the stored error without the floor; one member: the
 * error its run printed, from the point's δ over asp_omega_yield) above
 * refine_err of μs. */
int tbl_point_refinable(const tbl_table *t, const tbl_numerics *n, int i);

/* Point i is asked for by only[] (NULL: every point), itself or through a
 * point it is the source of (tbl_point_source). */
int tbl_point_wanted(const tbl_table *t, const unsigned char *only, int i);
/* Fill every point whose source (tbl_point_source) is another point from it:
 * a pending one, an earlier copy, or a failed one whose source is done; a
 * copy keeps its source's numbers and records no cost (wall, CPU, iterations
 * 0).  The curves of the normal grid the same way (tbl_curve_source).
 * Returns how many points were filled (tbl_point.copied set). */
int tbl_fill_copies(tbl_table *t);

/* ---- a build under way (table_build.c; the MPI farm of table_mpi.c) ---- */

/* The writer's state: the table, its journal and the counts the progress
 * reports carry.  Shared by the writer's threads: finish serialises them;
 * stop is read and written atomically. */
typedef struct tbl_build_state {
    tbl_table *t;               /* borrowed */
    const tbl_build_opts *o;    /* borrowed */
    /* a finished point: journal it (synced), store it in the table, report
     * it.  Thread-safe (lock).  Sets stop on a journal error or when the
     * progress callback asks to stop.  (A pointer, so that the farm of
     * table_mpi.c reaches table_build.c's writer without a call back into
     * that file.) */
    void (*finish)(struct tbl_build_state *b, int i, const tbl_point *p);
    /* the same for a finished curve c (P, A: [n_w of the normal grid]) */
    void (*finish_curve)(struct tbl_build_state *b, int c, const tbl_curve *cv, const double *P,
                         const double *A);
    int fd;                     /* the journal, open for appending */
    int done, total, resumed, failed, computed; /* points, as in tbl_progress */
    int curves_done, curves_total, curves_computed, curves_failed; /* normal curves */
    double curves_wall;         /* wall s the curves took (the points' ETA leaves it out) */
    int stop;                   /* nonzero: hand out no more points */
    int io_error;               /* errno of a failed journal append, else 0 */
    double t0, cpu;             /* start (monotonic s); CPU s of the computed points */
    omp_lock_t lock;            /* serialises finish and the first-failure
                                   record; initialised around the computing phase */
    /* members of pending points that an earlier run of the build finished
     * (the journal's member records, table_build.c) */
    struct tbl_member_rec *mem;
    int n_mem, cap_mem;
    int members_taken;          /* of them, taken by this run's points */
    /* [points + curves]: 1 where an earlier run of this build retried the
     * failed point (curve np + c) and journaled it: not retried again (NULL:
     * none) */
    unsigned char *retried;
} tbl_build_state;

/* Done point p's ensemble as it held its members, as far as p.ens keeps
 * them (the geometry and what the means, error and point are made of; the
 * reason is the point's): the inverse of what the point keeps of it. */
void tbl_members_unpack(const tbl_point *p, asp_placement_result *e);

/* A finished placement member of point `index` at phase slot `slot`
 * (asp_placement_store) and its ensemble's geometry: a journal record's
 * payload (table_build.c) and an MPI message's (table_mpi.c). */
typedef struct tbl_member_rec {
    int32_t index, slot, edge_refine, pad;
    double period, delta, delta_mesh, edge_a0;
    asp_placement_member m;
} tbl_member_rec;

/* Member j of ensemble e, of point i, as a record (zeroed first: no stray
 * padding bytes). */
void tbl_member_rec_fill(tbl_member_rec *r, int i, const asp_placement_result *e, int j);
/* Its member into *m and its ensemble's geometry into *geom (the fields
 * asp_placement_store.get writes). */
void tbl_member_rec_take(const tbl_member_rec *r, asp_placement_result *geom,
                         asp_placement_member *m);
/* The members of point i that an earlier run finished (b->mem), one per
 * slot, into out[ASP_PLACEMENTS_MAX]; returns how many.  Thread-safe. */
int tbl_member_recs(tbl_build_state *b, int i, tbl_member_rec *out);
/* Member record r, member j of k of its point, finished (this process's,
 * or another rank's): journaled (synced), then reported.  Thread-safe. */
void tbl_member_journal(tbl_build_state *b, const tbl_member_rec *r, int j, int k);
/* n members taken by a point from an earlier run, cpu their CPU s: into the
 * build's counts, out of this run's CPU time.  Thread-safe. */
void tbl_members_taken(tbl_build_state *b, int n, double cpu);

/* The store of point i's members in b's journal (table_build.c), for
 * tbl_build_compute: each finished member is journaled (synced) and
 * reported, and those an earlier run journaled are taken.  *s refers to
 * *ctx, which must outlive the point's computation. */
typedef struct tbl_member_ctx {
    tbl_build_state *b;
    int i;
    int taken;        /* members handed to the point from an earlier run (within one
                         build a handed member always fits its ensemble) */
    double taken_cpu; /* their CPU s, which the point's cpu_s counts */
} tbl_member_ctx;
void tbl_member_store(tbl_build_state *b, int i, tbl_member_ctx *ctx, asp_placement_store *s);
/* After point ctx->i was finished (b->finish): its taken members into the
 * build's counts, their CPU time out of this run's (tbl_build_summary). */
void tbl_member_done(const tbl_member_ctx *ctx);

/* Point i of t computed on the calling thread alone: tbl_point_compute at
 * the point's coordinates (table.c); threads > 1: its members on up to that
 * many threads, with the same numbers.  store (nullable): its members kept
 * there and taken from there (asp_shear_placements_stored). */
stc_status tbl_build_compute(const tbl_table *t, int i, int threads,
                             const asp_placement_store *store, tbl_point *p);
/* Item `item` of a build's todo list on the calling thread: point item
 * (>= 0) into *p, or curve -(item + 1) into *cv, P and A (tbl_build_curve). */
stc_status tbl_build_item(const tbl_table *t, int item, int threads,
                          const asp_placement_store *store, tbl_point *p, tbl_curve *cv,
                          double *P, double *A);

/* ---- distributed builds: the MPI farm (table_mpi.c) ---- */

/* This process in a build: rank and size in MPI_COMM_WORLD, or 0 and 1
 * when the build is not distributed. */
typedef struct tbl_mpi {
    int rank, size;
    int owned;   /* MPI initialised by tbl_mpi_begin: tbl_mpi_end finalises it */
    int threads; /* MPI_THREAD_FUNNELED on the main thread: the writer may
                    compute points on threads while its main thread serves */
} tbl_mpi;

/* Decide how this build runs: distributed when MPI is initialised with
 * more than one process, or when mpirun started this process with more
 * than one (then MPI is initialised here).  Otherwise MPI is not touched
 * beyond MPI_Initialized / MPI_Finalized.  STC_EUNSUPPORTED when mpirun
 * started more than one process but MPI was finalised already. */
stc_status tbl_mpi_begin(tbl_mpi *m);
/* Finalise MPI if tbl_mpi_begin initialised it; then m is not distributed.
 * Collective; idempotent. */
void tbl_mpi_end(tbl_mpi *m);

/* Rank 0: hand out the items todo[n] (points i >= 0, curves c coded as
 * -(c + 1)) to the other ranks one at a time, compute some on this rank's
 * threads, journal and report every finished one through b; returns when
 * every rank has been told to stop.  A failure
 * on any rank stops the farm after the points under way and is returned
 * with its message. */
stc_status tbl_mpi_serve(const tbl_mpi *m, tbl_build_state *b, const int *todo, int n);
/* Rank 0 failed before the farm started (status s, message why): tell every
 * other rank to stop with that failure, so that none waits for work. */
void tbl_mpi_release(const tbl_mpi *m, stc_status s, const char *why);
/* Ranks >= 1: ask rank 0 for points and curves, compute them on this
 * thread, send them back, until told to stop.  They are kept in t too;
 * nothing is written to any file.  sum counts this rank's. */
stc_status tbl_mpi_work(tbl_table *t, const tbl_build_opts *o, tbl_build_summary *sum);

#endif
