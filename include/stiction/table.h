/* stiction — FE friction tables (docs/table-format.md): sweeps of the single-asperity
 * solver over (δ/ωc_su, t/R, Eco/Esu) for one material family, stored in
 * HDF5, interpolated with error bars, and turned into an asperity model for
 * the Greenwood–Williamson sum (include/stiction/gw.h).
 *
 * Similarity: in the small-strain elastic–perfectly plastic model the
 * response normalised by ωc_su, Pc_su, Ac_su depends only on δ/ωc_su, t/R,
 * Eco/Esu and the family (E/Y and ν of each layer, the normal step's contact
 * condition, the τc rule, the sliding criterion), not on R or on Esu itself.
 * A point is therefore computed once, at R = 10 mm and Esu = 200 GPa, and
 * serves every radius and modulus of its family.
 *
 * Layout of the grid: point (iE, it, iw) has index (iE n_tR + it) n_w + iw.
 *
 * Files: docs/table-format.md.  Units: mm, N, MPa; every stored response is
 * normalised (P/Pc_su, A/Ac_su, Q/Pc_su, ux/ωc_su).
 *
 * Thread safety: a table handle is not locked; tbl_query and tbl_model_create
 * only read it and may run concurrently once the fit exists (tbl_fit).
 */
#ifndef STICTION_TABLE_H
#define STICTION_TABLE_H

#include "stiction/export.h"
#include "stiction/asperity.h"
#include "stiction/model.h"
#include "stiction/params.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- material family and numerical settings ----------------------------- */

/* What the normalised response depends on besides the three axes.  Along
 * the Eco/Esu axis E/Y of each layer is held (so Yco/Ysu = Eco/Esu × (E/Y)_su
 * / (E/Y)_co), as in the thesis's grid. */
typedef struct tbl_family {
    double E_over_Y_su, E_over_Y_co; /* E/Y of substrate and coating; default 1000, 1000 */
    double nu_su, nu_co;             /* Poisson ratios; default 0.32, 0.32 */
    asp_contact_law contact;         /* normal step; default ASP_CONTACT_STICK */
    double tau_c_over_Y_co;          /* τc = this × Y of the coating; default 1/√3 */
    asp_shear_criterion criterion;   /* sliding criterion; default ASP_SHEAR_CRIT_SHEAR */
    double alpha;                    /* stiffness criterion's KT ratio; default 0.1 */
} tbl_family;

/* The family of Patel's thesis grid (its Table 4.1; docs/table-format.md). */
STC_API void tbl_family_default(tbl_family *f);
/* Ranges of every field; STC_EINVAL naming the field. */
STC_API stc_status tbl_family_validate(const tbl_family *f);
/* One line naming every field, e.g. for messages. */
STC_API void tbl_family_describe(const tbl_family *f, char *buf, int n);

/* How each point is computed (written into the file with the results). */
typedef struct tbl_numerics {
    int mesh_level;    /* 3D mesh level of asp_options (0 = the default 3D mesh); default 0 */
    double elements_per_contact; /* asp_options.elements_per_contact: 0 = the level's;
                                    a smaller value (>= 3) makes a quick, coarse table
                                    for tests; default 0 */
    int placements;    /* node-placement members averaged per point (asp_shear_placements),
                          in [1, ASP_PLACEMENTS_MAX]; default 2 */
    int placements_max; /* refinement: while a point's members' standard error of the
                           mean exceeds refine_err of its μs (one member: its own
                           error), its ensemble doubles (asp_shear_placements_refine),
                           to at most this many members; 0 = none (the default), else
                           in [2 placements, ASP_PLACEMENTS_MAX] */
    double refine_err;  /* the relative standard error that refines, in (0, 0.5];
                           default ASP_REFINE_ERR (0.04) */
    double err_floor;  /* relative μs error added in quadrature to the members' standard
                          error (the mesh bias the placements do not average out);
                          default ASP_MU_S_ERR_FLOOR */
    double err_single; /* relative μs error of a point with one member (the single-mesh
                          node-placement scatter); default ASP_MU_S_ERR_SINGLE */
    double foot_rows;  /* junction reading of every member (asp_shear_options.foot_rows):
                          0 = the three axis lines, > 0 = every node row within
                          foot_rows a0 of the axis; in [0, 0.9]; default the
                          solver's (asp_shear_options_default: 0); tables of format
                          versions 1-2 are read as 0 */
    int normal_level;  /* the preload's P and A from the normal grid: axisymmetric load
                          curves at this axisymmetric mesh level, one per (t/R, Eco/Esu)
                          of a grid denser than the points' (the normal step is
                          axisymmetric; docs/table-format.md), in [0, 3]; -1 = no
                          normal grid: P and A from the 3D points; default 1 */
} tbl_numerics;
STC_API void tbl_numerics_default(tbl_numerics *n);
STC_API stc_status tbl_numerics_validate(const tbl_numerics *n);

/* ---- points --------------------------------------------------------------- */

typedef enum tbl_state {
    TBL_PENDING = 0, /* not computed (yet, or in another shard) */
    TBL_DONE = 1,    /* computed: the numbers are an answer */
    TBL_FAILED = 2   /* computed and failed: reason says why, no numbers */
} tbl_state;
STC_API const char *tbl_state_name(tbl_state s); /* "pending", "done", "failed" */

enum { TBL_REASON_MAX = 192 };

/* A done point's node-placement members (asp_placement_result), as far as a
 * build that refines the point needs them to go on from them instead of
 * computing them again: the ensemble's geometry and, per member, what the
 * point's means and error are made of.  Raw values at the reference sphere
 * every point is computed on (R = 10 mm, Esu = 200 GPa): mm, N. */
typedef struct tbl_member {
    double elements_per_contact;
    double P, A;             /* preload (end of the normal step), N, mm² */
    double P_slide, Q_max;   /* at inception, N */
    double ux_slide;         /* mm */
    double mu_s, mu_s_preload, mu_s_err; /* as the member's run gave them (err absolute) */
    double cpu_s;            /* its CPU time, s */
    int newton_iterations, factorizations; /* both steps */
    double mu_s_ux_slope;    /* its asp_shear_result.mu_s_ux_slope (NaN: not known, as
                                read from a file before format 7) */
} tbl_member;

typedef struct tbl_members {
    int k;                   /* members stored: the point's members, or 0 (not done, a
                                copy, or read from a file before format 6) */
    int edge_refine;         /* asp_placement_result's geometry: */
    double period, delta, delta_mesh, edge_a0; /* elements per contact; mm */
    tbl_member m[ASP_PLACEMENTS_MAX]; /* in phase order, as the ensemble's m[] */
} tbl_members;

/* One grid point.  Responses normalised by the substrate's ωc, Pc, Ac
 * (Kogut & Etsion 2002) at the point's R. */
typedef struct tbl_point {
    int state;            /* tbl_state */
    double P_Pc, A_Ac;    /* preload (end of the normal step), means over the members */
    double P_slide_Pc;    /* normal load at sliding inception */
    double Q_max_Pc;      /* tangential load at inception */
    double mu_s;          /* Q_max / P at inception (mean over the members) */
    double mu_s_err;      /* error estimate of mu_s (absolute, one standard error) */
    double mu_s_preload;  /* Q_max / preload */
    double mu_s_min, mu_s_max; /* over the members */
    double ux_slide_wc;   /* ux at inception / ωc_su (mean) */
    int members;          /* members that reached inception */
    double mu_s_ux_slope; /* d ln μs / d ln ux at inception, mean over the members
                             (asp_shear_result.mu_s_ux_slope): how much μs depends on
                             where inception is declared.  NaN: not known (a file
                             before format 7, or members taken from one) */
    int newton_iterations, factorizations; /* summed over members, both steps */
    double wall_s;        /* wall time of the point, s */
    double cpu_s;         /* CPU time of the point, s */
    int copied;           /* 1: its source's answer (tbl_point_source), not a run of its
                             own (costs, iterations 0); the μs surrogate fits each answer
                             once.  0: computed as itself */
    char reason[TBL_REASON_MAX]; /* why it failed, or the first member's criterion reason */
    tbl_members ens;      /* its members, for a refinement to go on from */
} tbl_point;

/* Compute one point: params at R = 10 mm, Esu = 200 GPa, the family's
 * ratios, Eco/Esu = E_ratio, t/R (where the coating is the substrate,
 * E_ratio 1 in a family with the same E/Y and ν in both layers, the
 * uncoated sphere: t/R has no meaning there); the normal step to δ = w ωc_su, then the
 * shear ramp on `placements` node placements (asp_shear_placements), one
 * thread.  Never fails for a point that does not converge: out->state is
 * TBL_FAILED and out->reason says why; returns STC_EINVAL for bad arguments
 * only (then *out is untouched). */
STC_API stc_status tbl_point_compute(const tbl_family *f, const tbl_numerics *num, double w,
                                     double t_over_R, double E_ratio, tbl_point *out);

/* One axisymmetric load curve of the normal grid (tbl_numerics.normal_level):
 * the normal step at one (t/R, Eco/Esu) through every δ of the grid. */
typedef struct tbl_curve {
    int state;            /* tbl_state */
    int increments, newton_iterations; /* of the curve's solver run */
    double wall_s, cpu_s; /* time of the curve, s */
    char reason[TBL_REASON_MAX]; /* why it failed; "" when done */
    int copied;           /* 1: its source's run (tbl_curve_source; costs 0); 0: its own */
} tbl_curve;

/* Compute one curve: params at R = 10 mm, Esu = 200 GPa as tbl_point_compute,
 * the axisymmetric model at mesh `level` loaded through w[0..n_w-1]
 * (δ/ωc_su, increasing) and on past the last one (asp_solver_load_tail), one
 * thread.  P_Pc[k] is the load with the node-entry sawtooth removed
 * (asp_solver_P_smooth) / Pc_su, A_Ac[k] the contact area with its node-entry
 * steps removed (asp_solver_A_smooth) / Ac_su (both
 * [n_w], written; NaN when not done).  Never fails for a curve that does not
 * converge: out->state is TBL_FAILED with the reason; STC_EINVAL for bad
 * arguments only. */
STC_API stc_status tbl_curve_compute(const tbl_family *f, int level, double t_over_R, double E_ratio,
                             const double *w, int n_w, double *P_Pc, double *A_Ac,
                             tbl_curve *out);

/* ---- the table ------------------------------------------------------------- */

typedef struct tbl_table tbl_table;

/* Axes: strictly increasing, > 0 (w and t/R), >= 1 (E_ratio is not checked
 * beyond > 0); copied.  Every point starts pending.  Returns new in *out. */
STC_API stc_status tbl_create(const tbl_family *f, const tbl_numerics *num, const double *w,
                              int n_w, const double *t_over_R, int n_tR, const double *E_ratio,
                              int n_E, tbl_table **out);
STC_API void tbl_destroy(tbl_table **t); /* sets *t = NULL */

STC_API void tbl_get_family(const tbl_table *t, tbl_family *f);
STC_API void tbl_get_numerics(const tbl_table *t, tbl_numerics *n);
STC_API int tbl_points(const tbl_table *t); /* n_E n_tR n_w */
/* Axis 0 (w), 1 (t/R) or 2 (E_ratio): its length, and a borrowed array. */
STC_API int tbl_axis(const tbl_table *t, int axis, const double **values);
/* Coordinates of point i. */
STC_API void tbl_coords(const tbl_table *t, int i, double *w, double *t_over_R, double *E_ratio);
STC_API const tbl_point *tbl_point_get(const tbl_table *t, int i); /* borrowed */
/* Store a computed point (copied); invalidates the fit.  Its kept members
 * (ens) are stored where they are all of a done point's (ens.k = members),
 * else none are. */
STC_API stc_status tbl_point_set(tbl_table *t, int i, const tbl_point *p);
/* The point whose FE run gives point i: i itself, except where the coating
 * is the substrate (Eco/Esu = 1 in a family with the same E/Y and ν in both
 * layers), whose response does not depend on t/R: there every t/R column
 * holds the run of the first, at the same δ.  A build computes only the
 * points that are their own source and fills the others from theirs. */
STC_API int tbl_point_source(const tbl_table *t, int i);
/* Counts by state; any pointer nullable. */
STC_API void tbl_count(const tbl_table *t, int *done, int *failed, int *pending);

/* The normal grid (tbl_numerics.normal_level >= 0): axes 0 (δ/ωc_su), 1 (t/R),
 * 2 (Eco/Esu), each the table's nodes with every interval divided evenly in
 * ln: 4 per factor 2 along δ and t/R, 2 along Eco/Esu.  Curve c is at (t/R,
 * Eco/Esu) = (axis 1 [c % n_tR], axis 2 [c / n_tR]).  tbl_curves is 0 for a
 * table without one. */
STC_API int tbl_curves(const tbl_table *t);
STC_API int tbl_normal_axis(const tbl_table *t, int axis, const double **values);
STC_API const tbl_curve *tbl_curve_get(const tbl_table *t, int c); /* borrowed; NULL if out of range */
/* The curve whose run gives curve c: c itself, or where the coating is the
 * substrate (as tbl_point_source) the curve at the first t/R of its Eco/Esu.
 * A build computes only the curves that are their own source. */
STC_API int tbl_curve_source(const tbl_table *t, int c);
/* The curve's values at δ node k of the normal grid; NaN when not done. */
STC_API void tbl_curve_values(const tbl_table *t, int c, int k, double *P_Pc, double *A_Ac);
/* Store a computed curve (copied; P_Pc, A_Ac: [n_w] of the normal grid). */
STC_API stc_status tbl_curve_set(tbl_table *t, int c, const tbl_curve *cv, const double *P_Pc,
                         const double *A_Ac);
STC_API void tbl_curve_count(const tbl_table *t, int *done, int *failed, int *pending);
/* Pending curves a build restricted to the points only[] (NULL: all) would
 * compute: those at the t/R and Eco/Esu the chosen points span; -1 when out
 * of memory. */
STC_API int tbl_curves_pending(const tbl_table *t, const unsigned char *only);

/* Same family, numerics and axes (bitwise on the numbers): a journal or a
 * shard belongs to the build. */
STC_API int tbl_same_build(const tbl_table *a, const tbl_table *b);

/* Provenance written into the file (borrowed strings, copied; a command of
 * 512 bytes or more is cut at a character's start and ends in "..."). */
STC_API void tbl_set_provenance(tbl_table *t, const char *command, double build_wall_s);
STC_API const char *tbl_provenance(const tbl_table *t, double *build_wall_s);
/* The commands that built the table before its own (tbl_provenance), oldest
 * first, one a line (a line break within one kept as a space); "" when one
 * command built it all.  A build onto a file
 * (tbl_build: a resumed or refined build, a fill) adds the file's command
 * when it differs from the table's; a first line "..." says the oldest ones
 * were dropped. */
STC_API const char *tbl_history(const tbl_table *t);

/* ---- files (docs/table-format.md) ------------------------------------------ */

/* Write atomically: a temporary file beside `path`, synced, renamed over it;
 * a failure leaves no file. */
STC_API stc_status tbl_write(const tbl_table *t, const char *path);
/* Read a table and fit its μs surrogate (tbl_fit: from the file's stored
 * hyperparameters while its points are those they were fitted to);
 * STC_EFORMAT naming what is wrong for a file that is not one. */
STC_API stc_status tbl_read(const char *path, tbl_table **out);

/* ---- building -------------------------------------------------------------- */

/* Progress of a build, after each finished point or normal curve (a build
 * computes its normal curves first: they are cheap, and every prediction
 * reads them), and with tbl_build_opts.report_members after each finished
 * placement member of a point (then point is NULL and m is set). */
typedef struct tbl_progress {
    int index;              /* the point just finished (or whose member finished), or -1
                               after a curve */
    const tbl_point *point; /* its result (borrowed), or NULL */
    int curve;              /* the normal curve just finished, or -1 after a point */
    const tbl_curve *c;     /* its result (borrowed), or NULL */
    int member, members;    /* the member just finished (j of the point's ensemble of
                               members, asp_placement_result.m[j]); -1 and 0 otherwise */
    const asp_placement_member *m; /* that member (borrowed; wall time: m->pt.wall_s +
                                      m->res.wall_s), or NULL */
    int curves_done, curves_total; /* curves finished of this build's share */
    int done, total;        /* points finished of this build's share (resumed included) */
    int resumed;            /* points taken from an earlier run */
    int failed;             /* failed points so far */
    double elapsed_s, eta_s; /* wall time of this run; estimate of the rest (NaN unknown) */
} tbl_progress;
/* Nonzero return stops the build after the points under way (reason
 * "stopped by the caller"; the finished points are kept). */
typedef int (*tbl_progress_fn)(void *ctx, const tbl_progress *p);

typedef struct tbl_build_opts {
    int jobs;           /* points computed at once, one thread each; 0 = one per core;
                           fewer points than jobs: a point's members share the threads
                           (the same numbers) */
    int shard, shards;  /* compute only points with index % shards == shard; default 0, 1 */
    const unsigned char *only; /* nullable: [tbl_points] compute only the points i with
                                  only[i] != 0 (the rest stay as they are); default NULL */
    int retry_failed;   /* compute the failed points of the share again (after a change
                           to the solver, say); default 0: they stay failed */
    int only_failed;    /* compute the failed points again and no pending one; default 0 */
    int curves_only;    /* compute the normal grid's pending curves and no point (a table
                           without a normal grid, or from before a change to the curves,
                           completed); default 0 */
    tbl_progress_fn progress; /* nullable */
    void *ctx;
    int report_members; /* call progress after each finished placement member of a point
                           too (a long point shows its progress); default 0 */
} tbl_build_opts;
STC_API void tbl_build_opts_default(tbl_build_opts *o);

typedef struct tbl_build_summary {
    int computed, resumed, failed, share; /* points of this run, from before, failed, in shard */
    int reopened; /* done points of an existing file re-opened to refine (a build that adds
                     or extends refinement: tbl_numerics.placements_max), in every shard;
                     this run computes those of its share */
    int copied;   /* points filled from their source (tbl_point_source), in no share */
    int members_taken; /* placement members of this run's points that an earlier run had
                          finished, not computed again: from the journal (a killed build)
                          or from the file a refinement goes on from (tbl_point.ens) */
    int curves_computed, curves_failed;   /* normal curves of this run, failed */
    double wall_s;  /* this run */
    double cpu_s;   /* of the points this run computed, this run's alone (not the members
                       it took; the curves' own are in tbl_curve) */
} tbl_build_summary;

/* Compute the pending normal curves and then the pending points of t that
 * fall in the shard and write the table to `path` (curve c falls in shard
 * c % shards; with opts.only, the curves at the t/R and Eco/Esu the chosen
 * points span).  Crash-safe and resumable: each finished point is appended to
 * the journal `path`.journal (synced) before anything else, and so is each
 * finished placement member of a point; a build started again with the same
 * table (tbl_same_build) takes the journal's points and members and those of
 * an existing `path` instead of recomputing them, so a build killed at any
 * moment loses at most the members under way (the table is the one an
 * uninterrupted build writes, but for the timings; a point's cpu_s counts
 * its taken members' CPU time as when they ran; under MPI, the members of
 * the points rank 0 computes itself: another rank's point is computed again
 * whole).  At the end the table is
 * written atomically and the journal removed.  The points of t that are not
 * pending stay as they are.  A journal or `path` of another build is refused
 * (STC_EINVAL, naming the difference), except a `path` built as t but without
 * t's refinement or with less of it (placements_max no higher, refine_err no
 * lower, the same err_floor): its points are taken, and those that t's refinement
 * would give more members are computed again from their first member, so the
 * table written is the one a build with t's refinement from the start writes
 * (summary: reopened).  The build time written is an existing `path`'s plus
 * this run's (t's own replaced by the file's, so a t read from `path` and
 * built onto it counts the earlier builds once).  A point whose source is another point
 * (tbl_point_source) is in no shard: it is filled from its source when the
 * table is written (here and by tbl_merge; summary: copied).  Returns STC_OK when every point of the
 * share is done or failed (failed points are counted in the summary).
 * While a point is computed, OpenBLAS runs on one thread process-wide
 * (restored after; see include/stiction/asperity.h, process-wide state). */
STC_API stc_status tbl_build(tbl_table *t, const char *path, const tbl_build_opts *o,
                             tbl_build_summary *sum);

/* What a build with refinement up to placements_max members at refine_err
 * onto t (tbl_build) would refine: *points done points, whose stored CPU
 * time sums to *cpu_s (the members added cost at least as much again), and
 * of them *unkept (nullable) whose members t does not keep (tbl_point.ens:
 * a file written before format 6), whose first members are computed once
 * more.  STC_EINVAL for values out of range or refining less than t
 * already does (that build would be another). */
STC_API stc_status tbl_refine_plan(const tbl_table *t, int placements_max, double refine_err,
                                   int *points, double *cpu_s, int *unkept);

/* Join tables of one build (shards of it, or partial runs): each point is
 * taken from the table that has it done or failed, a done one from the table
 * where it has the most members (a refinement sharded over copies of one
 * table), and a point whose source is another (tbl_point_source) filled from
 * it; new in *out.  Refused (STC_EINVAL) when the tables are of different
 * builds. */
STC_API stc_status tbl_merge(tbl_table *const *parts, int n, tbl_table **out);

/* ---- interpolation ----------------------------------------------------------- */

/* Flags of a query (bitwise OR; ASP_OUT_* of model.h for w and t/R). */
enum {
    TBL_OUT_W_LOW = ASP_OUT_W_LOW,
    TBL_OUT_W_HIGH = ASP_OUT_W_HIGH,
    TBL_OUT_T_OVER_R = ASP_OUT_T_OVER_R,
    TBL_OUT_E_RATIO = 1 << 4, /* Eco/Esu outside the axis (clamped) */
    TBL_GAP = 1 << 5          /* a neighbouring grid point is not done */
};

/* Fit the μs surrogate (required before tbl_query / tbl_model_create; done
 * by tbl_read for a table with done points): a Gaussian process in (ln w,
 * ln t/R - ½ ln w, ln Eco/Esu) on ln μs less the Wu–Shi–Polycarpou trend:
 * a term in ln w (the uncoated sphere) plus ln Eco/Esu times a term in all
 * three, whose length scales vary along the second; each point weighted by
 * its own error estimate (asperity/table_fit.h, docs/table-format.md).  STC_ERANGE with
 * fewer than 3 done points.  The hyperparameters found are kept with the
 * table (tbl_write stores them) and reused, with no search, as long as the
 * done points are unchanged: the same surrogate, bit for bit, at a small
 * part of the cost (tbl_fit_info.reused). */
STC_API stc_status tbl_fit(tbl_table *t);

typedef struct tbl_fit_info {
    int n;                /* done points fitted */
    double ell[3];        /* length scales in ln w, ln t/R - ½ ln w (ln t/R with one t/R
                             value), ln Eco/Esu (inf: one value), at the middle of the
                             second input's range */
    double gamma;         /* their modulation: each scaled by exp(gamma (x2 - middle)),
                             x2 = ln t/R - ½ ln w; 0 with one t/R value */
    double ell_base;      /* length scale in ln w of the uncoated term (inf with one
                             Eco/Esu value: no separate term) */
    double noise_scale;   /* factor on the points' error estimates the data asked for */
    double loo_rms, loo_max; /* leave-one-out relative μs errors, rms and largest */
    double loo_cover2;    /* share of points within 2 LOO standard deviations */
    int reused;           /* 1: the hyperparameters stored with the table were reused (its
                             points unchanged since they were fitted), 0: searched anew */
} tbl_fit_info;
STC_API stc_status tbl_get_fit_info(const tbl_table *t, tbl_fit_info *out);

/* Interpolated response with one-standard-error bars. */
typedef struct tbl_value {
    double P_Pc, P_Pc_err;  /* preload: monotone cubics in ln P vs ln w and ln t/R, linear
                               in ln Eco/Esu, on the normal grid where its curves around
                               the query are done (else on the points); err = |cubic -
                               linear| along w and t/R in quadrature */
    double A_Ac, A_Ac_err;
    double P_slide_Pc;      /* P_Pc times the points' P_slide / P at the query */
    int from_normal;        /* 1: P and A from the normal grid, 0: from the 3D points */
    double mu_s, mu_s_err;  /* the surrogate and its standard error */
    double Q_max_Pc, Q_max_Pc_err; /* mu_s P_slide_Pc */
    double mu_s_ux_slope;   /* d ln μs / d ln ux at inception of the done grid points
                               around the query (tbl_point.mu_s_ux_slope), weighted as
                               multilinear interpolation in ln w, ln t/R, ln Eco/Esu
                               weighs them: how much μs there depends on where
                               inception is declared.  NaN where a point does not say */
    unsigned flags;
} tbl_value;
STC_API stc_status tbl_query(const tbl_table *t, double w, double t_over_R, double E_ratio,
                             tbl_value *out);

/* Mark (need[i] = 1; other entries left as they are) the grid points that
 * queries with δ/ωc in [w_lo, w_hi], t/R in [tR_lo, tR_hi] and Eco/Esu =
 * E_ratio read: on each axis the nodes inside the range and those bracketing
 * its ends (clamped to the axis; a value on a node needs that node only),
 * along δ one more node each side (the monotone cubic's slopes).  need has
 * tbl_points entries.  A point whose source is another (tbl_point_source)
 * marks its source too.  Returns how many of the points it newly marked are
 * pending and their own source (so over calls sharing one need[], the
 * points a build restricted to need[] computes), or -1 with bad arguments. */
STC_API int tbl_mark_needed(const tbl_table *t, double w_lo, double w_hi, double tR_lo,
                            double tR_hi, double E_ratio, unsigned char *need);

/* Nonzero when the table is of one material: the same E/Y and ν in both
 * layers and an Eco/Esu axis of the one value 1.  Its t/R axis then has one
 * value that stands for every t/R (no t/R range flag). */
STC_API int tbl_is_homogeneous(const tbl_table *t);

/* ---- the surface prediction's asperity model --------------------------------- */

/* What the model's P and Qmax are (the GW sum's μs = ΣQmax/ΣP, docs/table-format.md). */
typedef enum tbl_model_kind {
    TBL_MODEL_PRELOAD = 0, /* P = preload, Qmax = μs P_slide: the sum at a separation */
    TBL_MODEL_SLIDE = 1,   /* P = P at inception, Qmax as above */
    TBL_MODEL_ERR = 2,     /* P = preload, Qmax = σ(μs) P_slide: the error band's sum */
    TBL_MODEL_SLOPE = 3    /* P = preload, Qmax = s μs P_slide, s the points'
                              mu_s_ux_slope (tbl_value; at least 0.01, the log
                              interpolation's floor: a smaller or negative s, Q/P flat or
                              falling past a maximum, counts as 0.01): over the table
                              model's sum of Qmax, the surface μs's d ln μs / d ln ux for
                              inception declared at a ux the same per cent later on
                              every summit.
                              Below the table's first δ the two sums follow their own
                              power laws (summits flagged outside, as with every model).
                              STC_ERANGE where the table does not keep s (format < 7) */
} tbl_model_kind;

/* STC_OK when the materials p (E/Y and ν of both layers, Eco/Esu) can use the
 * table: STC_EINVAL when p is not of the table's family (the message names
 * both), STC_ERANGE when Eco/Esu is outside the table's axis. */
STC_API stc_status tbl_check_params(const tbl_table *t, const stc_params *p);

/* The table's response for the materials `p` (E_su, E_ratio, Y and ν of both
 * layers; R and t/R unused) with a coating of t_mm, resampled on a dense
 * (w, t/R) grid at p's Eco/Esu and returned as an asperity model (model.h's
 * data model: in-range flags as there).  Refused as tbl_check_params.  A
 * partly built table gives a model over its usable part: the longest run of
 * t/R columns with 2 or more done points at that Eco/Esu, and the δ nodes
 * done in all of them; the model's range (and flags) is that part.
 * STC_ERANGE when there is none.  Returns new in *out. */
STC_API stc_status tbl_model_create(const tbl_table *t, const stc_params *p, double t_mm,
                                    tbl_model_kind kind, asp_model **out);

/* The family of the materials p (E/Y and ν of each layer from p; the rest
 * from `like`): to compare with a table's. */
STC_API void tbl_family_of_params(const stc_params *p, const tbl_family *like, tbl_family *out);

#ifdef __cplusplus
}
#endif
#endif
