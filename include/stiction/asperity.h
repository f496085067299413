/* stiction — finite-element model of one coated spherical asperity pressed
 * by a rigid flat (docs/design.md §2–§3): implicit static Newton, CHOLMOD,
 * active-set contact with an analytic plane.
 *
 * Model: substrate sphere of radius R with a bonded coating of thickness t,
 * both elastic–perfectly plastic (von Mises); base plane fixed; flat at
 * z = R' - δ.  Small-strain kinematics: adequate for δ/R below about 1e-2
 * (a/R below about 0.1); the reference grid of the thesis stays below 1e-3.
 *
 * Usage: asp_solver_create() meshes the sphere for the largest interference
 * to be reached; asp_solver_load() then advances the flat monotonically
 * (adaptive increments, cut-back) and returns the response at each requested
 * δ.  All numbers the CLI prints come from the structs below.
 *
 * Thread safety: one solver per thread; the solver itself uses OpenMP for
 * the element loop.
 *
 * Process-wide state: asp_solver_load, _load_tail, _load_to_P,
 * asp_solver_shear and asp_shear_placements set OpenBLAS to one thread
 * while a Krylov solve (3D), a small axisymmetric factorization, any
 * factorization of a solver with threads = 1 or an ensemble's members run
 * (openblas_set_num_threads: the linked pthread build of OpenBLAS has no
 * per-call control), and restore the count they found when the last such
 * section of the process ends.  No other
 * process-wide or caller setting changes (CHOLMOD's OpenMP regions are
 * serialized inside the library's own one-thread region).
 */
#ifndef STICTION_ASPERITY_H
#define STICTION_ASPERITY_H

#include "stiction/export.h"
#include "stiction/params.h"
#include "stiction/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct asp_solver asp_solver;

typedef enum asp_geom {
    ASP_GEOM_AUTO = 0,  /* axisymmetric unless something breaks the symmetry */
    ASP_GEOM_AXISYM = 1,
    ASP_GEOM_3D = 2     /* half model, symmetry plane y = 0 */
} asp_geom;

typedef enum asp_contact_law {
    ASP_CONTACT_SLIP = 0, /* frictionless */
    ASP_CONTACT_STICK = 1 /* a node that touches stops moving tangentially */
} asp_contact_law;

/* Solver options.  Defaults from asp_options_default(). */
/* When Newton steps are solved by PCG instead of a new factorization. */
typedef enum {
    ASP_KRYLOV_OFF = 0,  /* factorize the tangent for every step */
    ASP_KRYLOV_AUTO = 1, /* where a factorization costs many PCG iterations (3D) */
    ASP_KRYLOV_ON = 2    /* always (tests, experiments) */
} asp_krylov;

/* asp_options.mesh_level relative to the model's default level */
enum { ASP_MESH_DEFAULT = -1, ASP_MESH_FINE = -2 };

/* How the von Mises return map integrates an increment (asperity/j2.c).
 * Radial return (backward Euler) is first-order accurate in the increment
 * size; the midpoint rule (normal at the average of the start and end
 * stresses) is second order, at the price of a non-symmetric tangent;
 * exact integration solves the law along the increment's straight strain
 * path in closed form (also a non-symmetric tangent). */
typedef enum asp_return_map {
    ASP_RETURN_MIDPOINT = 0, /* generalized midpoint, α = 1/2 (Ortiz & Popov 1985) */
    ASP_RETURN_RADIAL = 1,   /* backward Euler radial return (Simo & Hughes 1998) */
    ASP_RETURN_EXACT = 2     /* constant strain rate, exact (Krieg & Krieg 1977) */
} asp_return_map;

typedef struct asp_options {
    asp_geom geom;           /* default ASP_GEOM_AUTO */
    asp_contact_law contact; /* default ASP_CONTACT_SLIP */
    int no_separation;       /* 1: a node in contact never opens; default 0 */
    int mesh_level;          /* 0 coarse, 1, 2 fine, 3+ finer, or ASP_MESH_DEFAULT /
                                ASP_MESH_FINE: the model's default level (1
                                axisymmetric, 0 3D) / one finer; default
                                ASP_MESH_DEFAULT */
    double elements_per_contact; /* elements across a_max, overrides 6 2^mesh_level
                                    when > 0 (values between levels, e.g. 8; in 3D
                                    the shells follow the level log2(n / 6));
                                    0 = from mesh_level; default 0 */
    double a_safety;         /* a_max = a_safety sqrt(R' δmax) sizes the fine zone;
                                0 = automatic (1.1 elastic, 1.45 plastic); default 0 */
    double rtol;             /* Newton: residual / reaction norm; default 1e-8 */
    double utol;             /* Newton: increment / displacement norm; default 1e-6 */
    int max_newton;          /* Newton iterations per active set; default 30 */
    int newton_reuse;        /* reuse a factorization for up to k iterations
                                (1 = full Newton); default 1 */
    asp_krylov krylov;       /* Newton-Krylov: solve the Newton steps by PCG
                                preconditioned with the last Cholesky factor;
                                default ASP_KRYLOV_AUTO */
    int krylov_max;          /* PCG iterations before refactorizing; default 50 */
    double steps_per_node;   /* load increments per surface node entering the
                                contact past first yield (samples the P(δ)
                                sawtooth for asp_solver_P_smooth), in
                                [0.5, 16]; 0 = automatic: 4 slip axisymmetric,
                                2 slip 3D, 1 stick (load.c: step_limit);
                                default 0 */
    int max_active_set;      /* active-set passes per increment; default 40 */
    int max_cutbacks;        /* consecutive increment halvings; default 10 */
    int threads;             /* OpenMP threads for assembly and the Krylov kernels (at
                                most 2 used there), 0 = runtime default; 1 also
                                factorizes on one thread (no CHOLMOD or OpenBLAS
                                threads) */
    int surface_layers;      /* axisymmetric: the top element row is split into
                                N + 1 rows halving towards the surface (h/2^N
                                there; resolves a stuck-surface stress maximum),
                                N in [0, 6]; -1 = automatic: 3 under stick, 0
                                under slip (3D: no layers); default -1 */
    int shell_coarsen;       /* 3D: 2:1 angular coarsenings of the mesh's outer
                                shells (hanging nodes), in [0, 2]; -1 = the
                                mesh's default (1, from 6 a_max on; see
                                asperity/mesh3d.c); default -1 */
    asp_return_map return_map; /* plastic integration over an increment;
                                  default ASP_RETURN_MIDPOINT */
    int grade_3d;            /* 3D, normal loading only (refused by the shear ramp):
                                1 = size the core box to the smallest contact a
                                load curve resolves (at 0.8 ωc, as the axisymmetric
                                mesh) and let the shells grow in proportion to the
                                distance out to a_max, so every contact radius of
                                the curve gets about n elements across.  Needs a
                                coating within the small core's depth (t <= 0.8
                                a_min), else the uniform core is kept.  Its
                                levels have 4 2^level elements across every
                                contact and no coarsened shells (uniform: 6 2^level
                                across a_max).  Slip curve 1:60:12, level 0:
                                within 0.50 % of the converged curve at every
                                point in 13.7 s (uniform core: -33 % at 1 ωc,
                                -6.2 % at 6.4 ωc in 6.5 s; docs/design.md §2.4);
                                default 0 (asp_options_for_curve sets it for a 3D load
                                curve) */
    int sample_elastic;      /* slip: 1 = while all is elastic, step through the
                                surface node entries from δ/2 on (δ the target of
                                asp_solver_load), steps_per_node per entry, so that
                                asp_solver_P_smooth at an elastic or just-yielded
                                point averages over both sides of it instead of
                                fitting across the yield bend; 0 = jump to the
                                predicted yield.  asp_options_for_curve sets it
                                for load curves; default 0 */
    int edge_refine;         /* 3D: nested 2:1 refinements of the elements in a band
                                around the preload's contact edge (hanging nodes,
                                asperity/refine3d.c), in [0, 2]; needs edge_a0,
                                none on the graded core of a load curve
                                (asp_info.edge_refine says what the mesh has);
                                default 0 */
    double edge_a0;          /* 3D: the preload's contact radius the band is centred
                                on, mm; 0 with edge_refine > 0: asp_shear_preload and
                                the placement ensembles find it in their copy of the
                                options from the axisymmetric model (asp_options_edge;
                                asp_info.edge_a0 reports it); default 0 */
} asp_options;

STC_API void asp_options_default(asp_options *o);

/* Mesh and problem size. */
typedef struct asp_info {
    int dim;             /* 2 axisymmetric, 3 half model */
    int nodes, elements, dofs;
    double mesh_quality; /* worst scaled Jacobian in (0, 1] */
    double h_contact;    /* element size at the contact, mm */
    double a_max;        /* contact radius the mesh was sized for, mm */
    double elements_per_contact; /* a_max / h_contact: the option, or 6 2^level
                                    (4 2^level on the graded 3D core) */
    double a_min;        /* smallest contact radius with about elements_per_contact
                            elements across (a load curve's mesh: between a_min
                            and a_max every contact has); a_max if none, mm */
    int edge_refine;     /* 2:1 refinements of the band around the preload's contact
                            edge in the mesh (asp_options.edge_refine), 0 if none */
    double edge_a0;      /* the contact radius that band is centred on, mm (0: none) */
    /* where the time went since create (wall, s): element loops (tangent and
     * residual), numeric factorizations, PCG iterations (solves + mat-vecs) */
    double time_assembly_s, time_factorize_s, time_pcg_s;
} asp_info;

/* Response at one interference. */
typedef struct asp_point {
    double delta;           /* interference, mm */
    double P;               /* normal load = sum of contact reactions, N */
    double P_base;          /* reaction of the fixed base, N (equilibrium check) */
    double a;               /* contact radius, mm (sub-element, from the nodal forces) */
    double A;               /* contact area π a², mm² */
    int n_contact;          /* nodes in contact */
    double max_penetration; /* largest penetration of any node into the flat, mm */
    double vm_over_Y[2];    /* max von Mises / Y in substrate [0] and coating [1] */
    int plastic_points;     /* quadrature points with plastic strain */
    int increments;         /* cumulative accepted load increments */
    int cutbacks;           /* cumulative increment halvings */
    int newton_iterations;  /* cumulative */
    int factorizations;     /* cumulative */
    int krylov_iterations;  /* cumulative PCG iterations (see krylov_max) */
    int assemblies;         /* cumulative element-loop evaluations (the main cost) */
    int active_set_passes;  /* cumulative contact active-set passes */
    double wall_s;          /* cumulative wall time in the solver, s */
} asp_point;

/* First yield of one layer (first = substrate/uncoated: layer 0, coating: 1). */
typedef struct asp_yield {
    int reached;   /* 0 if the layer has not yielded up to the current δ */
    double delta;  /* interference at first yield, mm (interpolated, see asp_contact.c) */
    double P;      /* load at that interference, N */
    double r, z;   /* location (axisymmetric r, z; 3D: x = r, z), mm */
} asp_yield;

/* How an iterative loop of the solver ended (Newton, Krylov, active set,
 * load stepping, the shear ramp); asp_outcome_str gives it in words.  The
 * messages and reasons name the loop and its numbers. */
typedef enum asp_outcome {
    ASP_OUTCOME_NONE = 0,       /* not run yet */
    ASP_OUTCOME_CONVERGED,      /* within tolerance (the ramp: sliding inception) */
    ASP_OUTCOME_MECHANISM,      /* ramp: inception at a plastic mechanism (no
                                   equilibrium past a contact wholly at its limit) */
    ASP_OUTCOME_DIVERGED,       /* Newton: residual grew past 1e8 of the first */
    ASP_OUTCOME_STAGNATED,      /* Newton: residual stopped halving its best */
    ASP_OUTCOME_MAX_ITERATIONS, /* an iteration or increment limit was reached */
    ASP_OUTCOME_CYCLING,        /* contact active set did not settle */
    ASP_OUTCOME_INVERTED,       /* an element inverted */
    ASP_OUTCOME_NOT_POSDEF,     /* factorization: matrix not positive definite */
    ASP_OUTCOME_SOLVER_FAILED,  /* factorization, solve or Krylov breakdown */
    ASP_OUTCOME_CUTBACK_LIMIT,  /* max_cutbacks halvings of one increment failed */
    ASP_OUTCOME_GAVE_UP,        /* ramp: its ux limit, or no tangential stiffness */
    ASP_OUTCOME_STOPPED,        /* ramp: the caller's callback stopped it */
    ASP_OUTCOME_FAILED          /* another failure (input, memory, I/O) */
} asp_outcome;

/* Static text of an outcome ("converged", "diverged", ...); thread-safe. */
STC_API const char *asp_outcome_str(asp_outcome o);

/* Create a solver for the parameters `p` (copied) and options `o` (copied,
 * NULL = defaults), meshed for interferences up to delta_max (mm).
 * Returns new in *out. */
STC_API stc_status asp_solver_create(const stc_params *p, const asp_options *o, double delta_max,
                                     asp_solver **out);
STC_API void asp_solver_destroy(asp_solver **s); /* sets *s = NULL */

/* Advance the flat to interference `delta` (mm, >= the current one, <= the
 * delta_max of create) and fill `out` (nullable).  On failure the solver stays
 * at the last converged state and the message gives the reason
 * (STC_ENOCONV: Newton / active set / cut-back limit; STC_ESOLVER: CHOLMOD). */
STC_API stc_status asp_solver_load(asp_solver *s, double delta, asp_point *out);

STC_API void asp_solver_info(const asp_solver *s, asp_info *info);

/* Load at interference `delta` (mm) with the node-entry sawtooth removed:
 * past first yield P(δ) of a node-to-flat contact jumps each time a surface
 * node touches (about ±2 % rms at mesh level 1); this is a local linear
 * fit of ln P against ln δ (tricube weights times each increment's share
 * of the ln δ axis, i.e. an average over δ; window δ/2 .. 2 δ, widened
 * up to 3.4x if fewer than 5 increments fall in it) through ALL converged
 * increments so far, so it is best called after the whole curve is solved.
 * A linear fit across the concave bend of ln P(ln δ) reads low: about
 * -0.2 % past first yield (-0.13 ... -0.23 % against a local quadratic on
 * the mesh-converged slip curve to 60 ωc, docs/design.md §3.2).
 * Writes *P (N; NaN if not enough increments) and returns the number of
 * increments used (0: no estimate). */
STC_API int asp_solver_P_smooth(const asp_solver *s, double delta, double *P);

/* Contact area at `delta` (mm) with the node-entry steps removed: the same
 * local regression as asp_solver_P_smooth on ln A (asp_point.A, the
 * sub-element radius of each converged increment).  The radius steps with
 * the node entries (axisymmetric level 1, stick, t/R 0.035, Eco/Esu 4:
 * A/(Ac δ/ωc) 1.2330, 1.2295, 1.2287, 1.2672, 1.3577 at 21-42 ωc).  Writes
 * *A (mm²; NaN if not enough increments) and returns the increments used. */
STC_API int asp_solver_A_smooth(const asp_solver *s, double delta, double *A);

/* Load on past the meshed maximum δ_max (same mesh), to 1.5 δ_max (at most
 * the small-strain limit 0.01 R), so that asp_solver_P_smooth at the last
 * points of a curve averages increments on both sides of them instead of
 * one (at 60 ωc on mesh level 0 that halves its error, see load.c).  Call
 * it after the last point's results and fields are taken: the state is then
 * past the curve.  A failure is returned like asp_solver_load's; the
 * increments that converged before it stay in the estimate. */
STC_API stc_status asp_solver_load_tail(asp_solver *s, asp_point *out);

/* First yield of layer 0 (substrate) or 1 (coating). */
STC_API void asp_solver_yield(const asp_solver *s, int layer, asp_yield *y);

/* Write the current fields (displacement, stress, von Mises, equivalent
 * plastic strain, layer id) to `prefix`.h5 and an XDMF index `prefix`.xmf
 * (ParaView).  `prefix` is borrowed. */
STC_API stc_status asp_solver_write_fields(const asp_solver *s, const char *prefix);

/* ---- tangential step: shear to sliding inception -------------------------
 * After the normal step (asp_solver_load or asp_solver_load_to_P) the flat
 * is held at δ and moved along +x by ux (3D half model only).  Contact
 * stays closed (thesis §3.2.3.3); the interface follows the shear-limited
 * stick law of Wu, Shi & Polycarpou (2012): a point sticks until its shear
 * stress reaches τc, then slips at τc.  Design: docs/design.md §4. */

typedef enum asp_shear_criterion {
    ASP_SHEAR_CRIT_SHEAR = 0,    /* WSP 2012: whole contact at τc and Q stopped rising */
    ASP_SHEAR_CRIT_STIFFNESS = 1 /* Brizmer, Kligerman & Etsion 2007: KT_i/KT_1 <= α */
} asp_shear_criterion;

/* Defaults from asp_shear_options_default(). */
/* Area of the contact as it grows during the ramp (junction growth); the
 * two rules bracket the mesh-converged answer (docs/design.md §4.2). */
typedef enum asp_junction {
    ASP_JUNCTION_FOOTPRINT = 0, /* the edge advance read from the gaps ahead of it */
    ASP_JUNCTION_NODES = 1      /* a node that touches gets F_z / p_m */
} asp_junction;

typedef struct asp_shear_options {
    asp_shear_criterion criterion; /* default ASP_SHEAR_CRIT_SHEAR */
    double alpha;        /* stiffness criterion ratio, in (0, 1); default 0.1 (BKE 2007) */
    double tau_c;        /* critical shear stress, MPa; 0 = Y/√3 of the coating (of the
                            sphere if uncoated); default 0 */
    double kappa;        /* tangential penalty k_t = κ G / h; default 100 */
    asp_junction junction; /* contact growth rule; default ASP_JUNCTION_FOOTPRINT */
    int max_increments;  /* accepted ramp increments before giving up; default 200 */
    int keep_fields;     /* 1: keep snapshots for asp_solver_write_shear_fields
                            (memory: ~2 copies of the state); default 0 */
    asp_return_map return_map; /* plastic integration during the ramp; default
                                  ASP_RETURN_RADIAL: with the ramp's long
                                  increments the midpoint rule can be far off
                                  (docs/design.md §3.4) */
    double ramp_refine;  /* divides the ramp increment targets (bend, the largest
                            increment), for increment-convergence studies;
                            in [1, 64], default 1 */
    double foot_rows;    /* junction footprint on node rows: > 0 reads the edge
                            advance on every row of surface nodes within
                            foot_rows a0 of the axis (each row crosses the edge
                            at its own place between nodes), each row at least
                            its last node in contact, and averages them; 0 = the
                            three axis lines only; in [0, 0.9], default 0
                            (docs/design.md §4.2, §4.5: at 0.6 the node-placement
                            scatter is 1.0-3.8 % against 2.6-10.1 % on the axis
                            lines, but the rows read the elastic half-space's
                            growth 0.7-1.6 points high) */
    int hold_stalled;    /* 1 (default): when Newton stalls with contact nodes
                            cycling between stick and slip, hold them in their
                            state, solve, and flip the ones the stick law would
                            not keep there (an active set, up to 4 solves); 0:
                            the stall fails the increment, which is cut back
                            (docs/design.md §4.3) */
} asp_shear_options;

STC_API void asp_shear_options_default(asp_shear_options *o);

/* One accepted point of the ramp (full model: the half model's sums x 2). */
typedef struct asp_shear_point {
    double ux;         /* flat displacement along x, mm */
    double Q;          /* tangential load on the flat, N (-2 Σ friction forces) */
    double Q_base;     /* the same from the base reactions, N (equilibrium check) */
    double P;          /* normal load, N (changes under shear) */
    double A;          /* contact area (tributary areas of the contact nodes), mm² */
    double A_stick;    /* area of the sticking nodes, mm² */
    double slip_frac;  /* 1 - A_stick / A */
    double limit_frac; /* area fraction at its shear limit: slipping, or stuck on
                          material that yielded in the increment (the shear
                          criterion's fraction; thesis §4.1.3, Fig. 4.9) */
    int n_contact;     /* contact nodes (half model) */
    double a_lead;     /* contact footprint: extent from the axis along +x (the flat's */
    double a_trail;    /*   motion), along -x and along y, mm; A integrates over */
    double a_side;     /*   two half-ellipses with these semi-axes (shear.c) */
} asp_shear_point;

typedef struct asp_shear_result {
    double Q_max;        /* N (stiffness criterion: Q where KT_i/KT_1 <= α) */
    double ux_slide;     /* ux at inception, mm */
    double P_slide;      /* P at inception, N */
    double P0;           /* preload: P at the end of the normal step, N */
    double mu_s;         /* Q_max / P_slide: the answer (thesis, WSP 2012) */
    double mu_s_err;     /* its error estimate, one standard error (absolute): the
                            node-placement scatter of one mesh with the reading
                            used at this δ, asp_mu_s_err_single μs */
    double mu_s_preload; /* Q_max / P0 */
    double A_stick;      /* stick area at inception, mm² */
    double slip_frac;    /* at inception: area fraction at its shear limit (limit_frac) */
    double KT_after;     /* secant tangential stiffness / KT_1 from inception to the
                            end of the ramp (the confirmation increments).  Near 0:
                            Q is flat past inception.  Well above 0: Q was still
                            rising (stuck but saturated nodes, P relaxing), so μs
                            depends on where inception is declared, not only on
                            the Q(ux) curve (docs/design.md §4.4) */
    int q_rising;        /* 1: inception declared with the whole contact at its
                            shear limit while Q still rose past it (KT_after >
                            0.01): a flagged result */
    double mu_s_ux_slope;/* d ln(Q/P) / d ln ux at inception (from there to the end
                            of the ramp, or over the increment that reached it):
                            per cent of μs per per cent of the ux where inception
                            is declared.  ~0 where Q/P is flat there; 0.1 and more
                            past ~10 ωc, where Q still rises and a stop 20 % later
                            (another mesh) reads μs 2 % or more higher
                            (docs/design.md §4.4).  NaN: not measured */
    double tau_c;        /* τc used, MPa */
    double a0;           /* contact radius after the normal step, mm */
    asp_shear_criterion criterion;
    asp_junction junction;
    double foot_rows;    /* the footprint's rows (asp_shear_options.foot_rows) */
    int converged;       /* 1: inception found; 0: gave up or failed (see reason) */
    asp_outcome outcome; /* how the ramp ended (CONVERGED or MECHANISM: inception) */
    int index;           /* ramp point of inception (0 = ux = 0) */
    int increments;      /* accepted ramp increments */
    int cutbacks;        /* ramp increment halvings */
    int held_nodes;      /* contact nodes held in a stick or slip state after a
                            Newton stall (their state cycled), summed over the
                            increments */
    int hold_passes;     /* re-solves that flipped held nodes the stick law would
                            not keep in their state */
    int newton_iterations, factorizations; /* of the ramp */
    double wall_s;       /* wall time of the ramp, s */
    char reason[256];    /* in words */
} asp_shear_result;

/* Called once per accepted ramp point (first: ux = 0); a nonzero return
 * stops the ramp (reason "stopped by the caller"). */
typedef int (*asp_shear_fn)(void *ctx, const asp_shear_point *pt);

/* Run the ramp from the current normal state (δ > 0 reached, 3D model)
 * until sliding inception.  `o` NULL = defaults; cb nullable.  Returns
 * STC_OK when inception was found (res->converged = 1); STC_ENOCONV with
 * res->reason when the ramp gave up or Newton failed beyond the cut-back
 * limit (res holds what was reached; Q_max is then not an answer);
 * STC_EINVAL for bad options or an axisymmetric solver.  After a failure
 * the solver is not reusable for another ramp. */
STC_API stc_status asp_solver_shear(asp_solver *s, const asp_shear_options *o, asp_shear_fn cb,
                                    void *ctx, asp_shear_result *res);

/* After asp_solver_shear with keep_fields: write the fields at Q = 0
 * (which = 0), at the kept point nearest 0.8 Q_max (1) and at inception (2)
 * like asp_solver_write_fields, plus root attributes ux_mm, Q_N,
 * Q_over_Q_max, tau_c_MPa.  Q_max here is the largest Q of the ramp (the
 * stiffness criterion: the last point).  *Q_over_Qmax (nullable) gets the
 * point's Q / Q_max.  STC_EINVAL if that snapshot was not kept. */
STC_API stc_status asp_solver_write_shear_fields(asp_solver *s, int which, const char *prefix,
                                                 double *Q_over_Qmax);

/* Load control: advance the flat to the δ at which P = P_target (N, within
 * rel_tol, e.g. 1e-3) by the log-log secant of asp_find_delta, restoring a
 * checkpoint when a step must go back.  Fills `out` like asp_solver_load.
 * STC_ERANGE if P(delta_max of create) < P_target. */
STC_API stc_status asp_solver_load_to_P(asp_solver *s, double P_target, double rel_tol,
                                        asp_point *out);

/* Hertz interference (mm) of an elastic sphere of radius R (mm), modulus E
 * (MPa) and Poisson ratio nu pressed on a rigid flat by the load P (N):
 * δ = (3 P / (4 E* √R))^{2/3}, E* = E / (1 − ν²) (docs/design.md §6.1).
 * An elastic–plastic sphere needs more δ for the same P (its P(δ) lies
 * below Hertz), so a multiple of this sizes the mesh (asp_solver_create's
 * delta_max) for asp_solver_load_to_P, and it is that solve's first guess.
 * Pure, thread-safe. */
STC_API double asp_hertz_delta_guess(double P, double E, double nu, double R);

/* Node-placement ensemble (docs/design.md §4.5).  One mesh reads the
 * junction growth in whole node closures, so a single μs depends on where the
 * surface nodes sit relative to the contact edge (about ±10 % at level 0).
 * asp_shear_placements runs the normal step to δ (mm) and the ramp on k
 * meshes, elements_per_contact N_j = N_0 + j T / k (N_0 from o, T = a_max / a0
 * from member 0's preload: the shift that moves the surface grid by one node
 * spacing at the contact edge), i.e. k evenly spaced phases of the sawtooth,
 * and averages them.  Members run concurrently, one thread each, at most
 * o->threads (0: all cores) at a time.  o->geom must be ASP_GEOM_3D.
 * STC_OK when every member reached inception; otherwise STC_ENOCONV naming the
 * first failed member (the others' results are kept, the means are not an
 * answer). */
enum { ASP_PLACEMENTS_MAX = 8 };

/* Error model of μs, relative (docs/design.md §4.5).  One mesh: the largest
 * standard deviation of μs over node placements measured in its regime,
 * with the floor below.  Read on the three axis lines: 2.6 % up to the
 * first-yield interference (ASP_MU_S_ERR_ELASTIC; WSP sphere at 1 ωc, coated
 * t/R 0.05 at 1 ωc_su), 10 % from 3 times it on (ASP_MU_S_ERR_SINGLE; 10.1 %
 * over eight placements at WSP 6 ωc), log-linear in δ between; on the node
 * rows 3.8 % (WSP 48 ωc; ASP_MU_S_ERR_ROWS), or the axis lines' value where that is
 * smaller.  With two levels of the edge band (asp_options.edge_refine 2) the
 * plastic value is 7 % (ASP_MU_S_ERR_BAND; 6.8 % over four placements at WSP
 * 72 ωc, 1.3-3.4 % elsewhere).  An ensemble: the members' standard error of
 * the mean with, in quadrature, the floor, the move of four-member means from
 * the default 3D mesh to one full refinement (docs/design.md §4.6). */
#define ASP_MU_S_ERR_SINGLE 0.10
#define ASP_MU_S_ERR_ELASTIC 0.026
#define ASP_MU_S_ERR_ROWS 0.04
#define ASP_MU_S_ERR_BAND 0.07
#define ASP_MU_S_ERR_FLOOR 0.015
/* The relative error of one mesh's μs read with asp_shear_options.foot_rows
 * on a mesh with edge_refine levels of the edge band (asp_info.edge_refine)
 * at the interference delta_over_omega, δ over the first-yield interference
 * of the softer-yielding layer (the smaller ωc of the two layers as if
 * each were the whole sphere; ωc of a homogeneous sphere).  Pure. */
STC_API double asp_mu_s_err_single(double foot_rows, int edge_refine, double delta_over_omega);
/* That first-yield interference of p's sphere, mm: the smaller ωc of the
 * two layers as if each were the whole sphere (the substrate's when
 * uncoated); the solver's estimate, which also sizes a load curve's
 * smallest contact. */
STC_API stc_status asp_omega_yield(const stc_params *p, double *omega_y);

typedef struct asp_placement_member {
    double elements_per_contact;
    asp_point pt;            /* end of the normal step */
    asp_shear_result res;    /* the ramp */
    stc_status status;
    char message[256];       /* why it failed */
    double cpu_s;            /* CPU s of its normal step and ramp */
} asp_placement_member;

typedef struct asp_placement_result {
    int k, n_ok;             /* members, members that reached inception */
    double mu_s;             /* mean of the members' μs */
    double mu_s_err;         /* its error estimate, one standard error (absolute):
                                asp_placement_mu_s_err with member 0's relative
                                error (one member) and ASP_MU_S_ERR_FLOOR */
    double mu_s_min, mu_s_max;
    double mu_s_preload, Q_max, P_slide; /* means */
    double period;           /* T = a_max / a0 / 2^edge_refine, in elements per contact:
                                the shift that moves the surface nodes at the edge by
                                one spacing */
    int edge_refine;         /* the members' edge band (asp_info.edge_refine), 0 if none */
    double delta;            /* the members' interference, mm (member 0's under load control) */
    double delta_mesh;       /* the interference their meshes are sized for, mm */
    double edge_a0;          /* the edge band's contact radius, mm (asp_options.edge_a0) */
    double wall_s;           /* summed over the refinements */
    double cpu_s;            /* CPU s of all its threads, summed over the refinements */
    asp_placement_member m[ASP_PLACEMENTS_MAX];
} asp_placement_result;

STC_API stc_status asp_shear_placements(const stc_params *p, const asp_options *o,
                                        const asp_shear_options *so, double delta, int k,
                                        asp_placement_result *out);
/* The same at a preload given by delta (mm) or, with P > 0 (N; delta 0), by
 * load control: member 0 is asp_shear_preload's run to P, and the others
 * run at member 0's interference on meshes sized as its own (its delta_max),
 * so their phases stay evenly spaced; their preloads differ from P by their
 * meshes' (within about 1 %).  asp_shear_placements is this with P = 0. */
STC_API stc_status asp_shear_placements_preload(const stc_params *p, const asp_options *o,
                                                const asp_shear_options *so, double delta,
                                                double P, int k, asp_placement_result *out);

/* Twice the members of a finished ensemble (all k reached inception, 2k <=
 * ASP_PLACEMENTS_MAX): k more at the phases halfway between (N_0 + j T / 2k,
 * j odd), in phase order with the k there, which keep their places and
 * results; the means and the error as for 2k members at once.  A
 * refined ensemble equals one made with 2k members, member by member (each
 * runs alone on one thread).  p, o, so: those of the call that made out.
 * Failures as asp_shear_placements (out is then the 2k members, the new
 * ones' messages set). */
STC_API stc_status asp_shear_placements_refine(const stc_params *p, const asp_options *o,
                                               const asp_shear_options *so,
                                               asp_placement_result *out);

/* An ensemble of k members refined (asp_shear_placements_refine) while the
 * members' standard error of the mean μs, without the floor (one member: its
 * own error), exceeds rel_err μs and 2k <= k_max; k_max 0: none (then
 * asp_shear_placements_preload).  k_max is 0 or in [2k, ASP_PLACEMENTS_MAX],
 * rel_err in (0, 0.5] (STC_EINVAL naming them; asp_placements_refine_check
 * checks only that, pure). */
#define ASP_REFINE_ERR 0.04 /* the default rel_err of the CLI and of tables */
STC_API stc_status asp_placements_refine_check(int k, int k_max, double rel_err);
STC_API stc_status asp_shear_placements_adaptive(const stc_params *p, const asp_options *o,
                                                 const asp_shear_options *so, double delta,
                                                 double P, int k, int k_max, double rel_err,
                                                 asp_placement_result *out);

/* Members kept across runs: an ensemble run again after its process was
 * killed (a long table point) takes the members an earlier run finished
 * instead of computing them again.  A member is known by its phase slot
 * s = j (ASP_PLACEMENTS_MAX / k), integer division (asp_placement_slot;
 * member j of k; a refinement, which doubles k, keeps a member's slot), and
 * it is the same to the bit whichever run computed it. */
typedef struct asp_placement_store {
    /* Member j of e has finished (e->m[j]: reached inception or failed, with
     * its cpu_s); e's period, edge_refine, delta, delta_mesh and edge_a0 are
     * set.  Called on the thread that ran the member, possibly several at
     * once: thread-safe. */
    void (*put)(void *ctx, const asp_placement_result *e, int j);
    /* The member at slot s, if an earlier run finished it: copied to *m, its
     * ensemble's period, edge_refine, delta, delta_mesh and edge_a0 to *geom
     * (no other field of geom is written); returns 1, else 0.
     * Thread-safe. */
    int (*get)(void *ctx, int s, asp_placement_result *geom, asp_placement_member *m);
    void *ctx;
} asp_placement_store;
/* The phase slot of member j of k (k in [1, ASP_PLACEMENTS_MAX]).  Pure. */
STC_API int asp_placement_slot(int j, int k);

/* asp_shear_placements_adaptive with its members kept in and taken from
 * store (nullable: none).  A taken member is not run; its CPU time counts
 * in out->cpu_s as when it ran; member 0 taken, its normal step is not run
 * either (the ensemble's geometry is the stored one).  The result equals
 * the one of a run that computed every member, but for wall_s and the
 * members' wall times. */
STC_API stc_status asp_shear_placements_stored(const stc_params *p, const asp_options *o,
                                               const asp_shear_options *so, double delta,
                                               double P, int k, int k_max, double rel_err,
                                               const asp_placement_store *store,
                                               asp_placement_result *out);

/* One standard error of an ensemble's mean μs (absolute), the error model
 * above with these relative errors: err_single μs for one member, else the
 * members' standard error of the mean and err_floor μs in quadrature.  NaN
 * unless every member reached inception.  Pure. */
STC_API double asp_placement_mu_s_err(const asp_placement_result *e, double err_single,
                                      double err_floor);

/* ---- runs as `stiction asperity` makes them (asperity/policy.c) ----------
 * The solver settings the CLI chooses for what is asked, here so that a C
 * caller gets the numbers the CLI prints.  Set the model, contact, mesh and
 * any expert option on asp_options first, then call these. */

/* Normal loading to n interferences (n > 1: a load curve, one solver run;
 * docs/design.md §2.4, §2.5, §3.3): an axisymmetric (or auto) curve steps
 * through the elastic node entries (sample_elastic), a 3D curve gets the
 * graded core (grade_3d; to keep the uniform core clear it after this call);
 * a 3D point or curve keeps its outer shells uncoarsened (shell_coarsen 0,
 * unless set).  An axisymmetric point (n = 1) is unchanged. */
STC_API void asp_options_for_curve(asp_options *o, int n);

/* The tangential step needs the 3D half model: ASP_GEOM_AUTO becomes
 * ASP_GEOM_3D, ASP_GEOM_AXISYM fails (STC_EINVAL). */
STC_API stc_status asp_options_for_shear(asp_options *o);

/* One point of a curve run by asp_curve_run. */
typedef struct asp_curve_point {
    asp_point pt;          /* the response (delta in mm) */
    double P_smooth;       /* N, NaN without an estimate (asp_solver_P_smooth after the
                              whole curve and its tail) */
    double A_smooth;       /* mm², likewise (asp_solver_A_smooth) */
    asp_yield yield[2];    /* first yield of substrate [0] and coating [1] up to here */
    double time_assembly_s, time_factorize_s, time_pcg_s; /* cumulative since create */
    stc_status status;     /* STC_OK, or why the point failed (the curve stops there) */
    char reason[256];
} asp_curve_point;

typedef struct asp_curve_result {
    int n;                 /* points filled: the converged ones, then a failed one */
    asp_info info;         /* the mesh, after create */
    stc_status tail;       /* loading on past the last point (axisymmetric curve): STC_OK,
                              or why it stopped (P_smooth near the end then one-sided) */
    char tail_reason[256];
} asp_curve_result;

/* Called after each converged point with the solver there (borrowed: e.g.
 * asp_solver_write_fields). */
typedef void (*asp_curve_fn)(void *ctx, const asp_solver *s, int i);

/* Normal loading to delta[0..n-1] (mm, increasing) in one solver meshed for
 * delta[n-1] with o (NULL = defaults; asp_options_for_curve for the CLI's
 * settings); an axisymmetric curve of n > 1 points (or of one point with
 * o->sample_elastic) is then loaded on past its end (asp_solver_load_tail)
 * and P_smooth read at every point.  pts[n]
 * and res are written; cb is nullable.  Returns STC_OK, the failure of
 * create (res->n = 0) or of the first point that failed (its status). */
STC_API stc_status asp_curve_run(const stc_params *p, const asp_options *o,
                                 const double *delta, int n, asp_curve_fn cb, void *ctx,
                                 asp_curve_point *pts, asp_curve_result *res);

/* With o->edge_refine > 0 and o->edge_a0 = 0: sets o->edge_a0 to the
 * preload's contact radius from the axisymmetric model (level 0) at the
 * interference delta (mm) or brought to the load P (N), one of them > 0.
 * Otherwise leaves o as it is.  asp_shear_preload and the placement
 * ensembles call it. */
STC_API stc_status asp_options_edge(const stc_params *p, asp_options *o, double delta, double P);

/* The solver of a shear run at its preload: meshed for delta (mm) and
 * loaded to it; or, with P > 0 (N; delta 0), meshed for twice the Hertz
 * interference of P (plasticity puts P(δ) below Hertz; at most 0.01 R) and
 * brought to P within 1e-3 (asp_solver_load_to_P).  o: after
 * asp_options_for_shear.  Returns new in *out (NULL on failure) and the
 * preload in *pt; then asp_solver_shear. */
STC_API stc_status asp_shear_preload(const stc_params *p, const asp_options *o, double delta,
                                     double P, asp_solver **out, asp_point *pt);

/* ---- the BLAS kernels (asperity/blas_kernels.c) ---------------------------
 *
 * The factorizations (CHOLMOD's supernodes) and the Krylov solves spend most
 * of a run in OpenBLAS, which picks its kernels once, when it is loaded,
 * from the CPU's model number.  A model newer than the OpenBLAS release
 * gets the generic Prescott kernels: on a CPU with AVX-512 that OpenBLAS
 * 0.3.21 does not know, a shear run took 11.5 s on them and 4.8 s on the
 * SkylakeX ones (docs/design.md §3.6).  OPENBLAS_CORETYPE, set before the
 * library is loaded, chooses them; the library only reports (it cannot
 * change them once loaded).  The CLI re-executes itself with the
 * suggestion when OPENBLAS_CORETYPE is not set. */
typedef struct asp_blas_kernels {
    char in_use[32];    /* the kernels OpenBLAS runs (openblas_get_corename) */
    char suggested[32]; /* faster kernels this CPU runs: set only when in_use is
                           the generic fallback and the CPU has AVX2 (Haswell)
                           or AVX-512 (SkylakeX); "" otherwise */
    char config[160];   /* openblas_get_config: version and build options */
    char summary[208];  /* "CONFIG; kernels IN_USE": `stiction --version`, a table's
                           blas attribute */
} asp_blas_kernels;

STC_API void asp_blas_kernels_get(asp_blas_kernels *out);

#ifdef __cplusplus
}
#endif
#endif
