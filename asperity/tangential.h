/* Internal building blocks of the tangential (shear) step of the asperity
 * solver (not installed).  Design: docs/design.md §4.
 *
 *   friction.c  nodal shear-limited stick law (penalty-regularised return
 *               map with its consistent 2x2 tangent), pure kernel
 *   surfarea.c  tributary areas of the outer-surface nodes of an asp_mesh
 *   slide.c     sliding-inception detector + ux ramp controller, and the
 *               load-control root finder asp_find_delta()
 *
 * Units: mm, N, MPa.  Tangential vectors have 2 components (x, y) in the
 * plane of the flat; in the 3D half model a node on y = 0 has g_y = 0 and
 * stays there (the law is objective, see friction.c).
 */
#ifndef STICTION_TANGENTIAL_H
#define STICTION_TANGENTIAL_H

#include "fe.h"
#include "stiction/asperity.h" /* asp_hertz_delta_guess (slide.c), asp_outcome */
#include "stiction/status.h"

/* ---- nodal stick law (friction.c) ------------------------------------- */

/* Shear-limited stick law of Wu, Shi & Polycarpou (2012): a contact point
 * sticks until its frictional shear stress reaches τc, then slips at τc.
 * Regularised by a tangential penalty k_t per unit area:
 *   t = k_t (g - s),  |t| <= τc,
 * g = tangential displacement of the node relative to the flat, s = slip
 * accumulated so far (the internal variable). */
typedef struct asp_fric_law {
    double tau_c; /* critical shear stress τc, MPa (WSP: Y/√3 of the coating) */
    double kt;    /* penalty stiffness per unit area, MPa/mm (asp_fric_law_init) */
} asp_fric_law;

/* Return values of asp_fric_update: equal to ASP_CS_STICK / ASP_CS_SLIP of
 * solver_impl.h, so the result can be stored in the solver's cs[]. */
enum { ASP_FRIC_STICK = 1, ASP_FRIC_SLIP = 2 };

/* Default penalty factor κ in k_t = κ G / h (see asp_fric_law_init). */
#define ASP_FRIC_KAPPA_DEFAULT 100.0

/* k_t = kappa G / h with G = E / (2 (1 + ν)) of the contacting layer and h
 * the element size at the contact.  The stick error (elastic slip) of a
 * node is |t| / k_t <= τc h / (κ G); the relative error of the initial
 * tangential stiffness of the contact is about 8 h / (π κ (2 - ν) a) (the
 * penalty springs, k_t π a², in series with the Mindlin stiffness 8 G a /
 * (2 - ν); Johnson 1985 §7.2), i.e. 0.25 % for κ = 100, a = 6 h.
 * Fails (STC_EINVAL, naming the value and range) unless tau_c, E, h,
 * kappa > 0 and -1 < nu < 0.5. */
stc_status asp_fric_law_init(asp_fric_law *law, double tau_c, double E, double nu, double h,
                             double kappa);

/* Return map of one contact node with tributary area `area` (mm²).
 * In:  g[2] current relative tangential displacement (mm), s_old[2] slip at
 *      the last converged state (mm).
 * Out: s_new[2] updated slip, f[2] = area · t (N), K[4] = ∂f/∂g (N/mm,
 *      row major 2x2, symmetric positive semidefinite; nullable), *ratio
 *      (nullable) = |t_trial| / τc.
 * Sign: f is the force of the node's spring on the FLAT (the node feels
 * -f).  The solver adds f to the node's internal force and K to its 2x2
 * diagonal block (like an element); the flat's tangential load is
 * Q = -Σ f_x (times 2 in the half model).
 * Returns ASP_FRIC_STICK (|t_trial| <= τc, K = area k_t I) or ASP_FRIC_SLIP
 * (t = τc n, n = t_trial/|t_trial|, K = area k_t (τc/|t_trial|)(I - n nᵀ)).
 * Pure: no allocation, no globals, thread-safe. */
int asp_fric_update(const asp_fric_law *law, double area, const double g[2],
                    const double s_old[2], double s_new[2], double f[2], double K[4],
                    double *ratio);

/* The same with the state imposed: state ASP_FRIC_STICK takes the stick
 * branch and ASP_FRIC_SLIP the slip branch whatever |t_trial| is (slip at
 * |t| = τc along t_trial; stick when t_trial = 0), 0 chooses as
 * asp_fric_update does.  *ratio = |t_trial| / τc tells whether the imposed
 * state is the law's own (stick: <= 1, slip: >= 1). */
int asp_fric_update_as(const asp_fric_law *law, int state, double area, const double g[2],
                       const double s_old[2], double s_new[2], double f[2], double K[4],
                       double *ratio);

/* ---- tributary areas (surfarea.c) ------------------------------------- */

/* Consistent tributary area of every node on the outer sphere |x| = R_outer:
 *   dim 2 (axisymmetric): area_i = 2π ∫ r N_i ds over the outer-surface edges
 *   dim 3 (half model):   area_i = ∫ N_i dA over the outer-sphere quad faces
 * on the (chordal) faces of the mesh; 0 for every other node.  area:
 * [nnode], written.  A node is on the sphere when ||x| - R_outer| <=
 * 1e-9 R_outer (the generators snap surface nodes exactly).  Sums converge
 * to the hemisphere area 2π R'² (dim 2) / π R'² (dim 3) at second order in
 * the element size.  Fails with STC_EINVAL for R_outer <= 0 or a mesh with
 * no surface face. */
stc_status asp_surface_node_areas(const asp_mesh *m, double R_outer, double *area);

/* The same restricted to the contact disc: area_i = ∫_{r < rc} N_i dA (r =
 * distance from the axis; dim 2 exactly on the chordal edges, dim 3 on
 * 32x32 sub-cells of the faces the circle cuts; measured
 * cap-area error <= 3e-4 at level 0, 6e-5 at level 2).  Use with the sub-element
 * contact radius of the normal step (asp_point.a) so that a uniform
 * traction τc gives Σ f_i = τc × cap area exactly.  STC_EINVAL as above,
 * or for rc <= 0. */
stc_status asp_surface_node_areas_disc(const asp_mesh *m, double R_outer, double rc,
                                       double *area);

/* 3D: the same over a footprint of two half-ellipses, semi-axes ap along
 * +x, am along -x and ay along y (shear.c: the contact of a sheared
 * asperity); ap = am = ay = rc is the disc. */
stc_status asp_surface_node_areas_foot(const asp_mesh *m, double R_outer, double ap, double am,
                                       double ay, double *area);

/* Contact edge on a line of nodes at increasing distances r[0..nr-1]
 * during the ramp, from the preload radius a0 and the gap of the first open
 * node now (g) against the ramp's start (g0), for a profile g ∝ (r - a)^(3/2)
 * translating with the edge (footprint.c).  Nodes in contact: g <= 0. */
double asp_contact_edge_advance(const double *r, const double *g0, const double *g, int nr,
                                double a0);

/* ---- sliding inception and ramp control (slide.c) -------------------- */

typedef enum asp_slide_criterion {
    ASP_SLIDE_SHEAR = 0,    /* WSP 2012: whole contact at τc and Q stops rising */
    ASP_SLIDE_STIFFNESS = 1 /* BKE 2007: KT_i / KT_1 <= α */
} asp_slide_criterion;

/* Inception criteria and ramp control.  Defaults: asp_slide_params_default. */
typedef struct asp_slide_params {
    asp_slide_criterion criterion; /* default ASP_SLIDE_SHEAR */
    double alpha;      /* BKE stiffness ratio KT_i/KT_1 at inception; default 0.1 */
    double slip_tol;   /* shear: slipping area fraction >= 1 - slip_tol; default 1e-3 */
    double flat_tol;   /* shear: |KT_i| / KT_1 <= flat_tol means Q stopped rising;
                          default 0.01 (Qmax error ~ flat_tol/2 on a tanh-like knee) */
    double full_tol;   /* shear: after full slip, |KT_i| / KT_1 <= full_tol over the
                          n_flat confirmation increments confirms inception (Q_max is
                          then the largest Q up to the full-slip point); default 0.01
                          (= flat_tol).  Past ~3 ωc Q keeps rising slowly after the
                          whole contact is at its limit (junction growth, P relaxing):
                          the solver uses 0.5 there, see shear.c */
    int n_flat;        /* increments over which Q must stay flat; default 2 */
    double bend;       /* target change of KT/KT_1 per increment (step control);
                          default 0.08 */
    double first_frac; /* first increment / elastic slide estimate ux_e; default 0.05 */
    double confirm_frac; /* shear: overshoot past the predicted full-slip point and
                            confirmation increments once Q is flat, / ux; default 0.02 */
    double grow_max;   /* largest increment growth factor; default 2 */
    double du_max_frac;/* largest increment / ux_e; default 0.5 */
    int max_increments;/* accepted increments before giving up; default 200 */
    double ux_max;     /* give up beyond this ux, mm (0 = 20 ux_e); default 0 */
} asp_slide_params;

void asp_slide_params_default(asp_slide_params *p);

/* What the detector needs to know of the contact before the ramp. */
typedef struct asp_slide_setup {
    double G;      /* shear modulus of the contacting layer, MPa */
    double nu;     /* its Poisson ratio */
    double a;      /* contact radius after the normal step, mm */
    double tau_c;  /* critical shear stress, MPa */
    double P0;     /* normal load after the normal step (preload), N */
} asp_slide_setup;

/* Elastic estimates (Mindlin 1949; Johnson 1985 §7.2, rigid flat):
 * K_T0 = 8 G a / (2 - ν), and the ux at which the linear response would
 * carry Q_e = τc π a² (the whole contact at τc):  ux_e = Q_e / K_T0. */
double asp_slide_KT0(const asp_slide_setup *su);
double asp_slide_ux_elastic(const asp_slide_setup *su);

typedef enum asp_slide_state {
    ASP_SLIDE_RUNNING = 0,  /* keep ramping: ask asp_slide_next() */
    ASP_SLIDE_INCEPTION = 1,/* sliding inception confirmed: stop */
    ASP_SLIDE_GAVE_UP = 2   /* increment or ux limit reached without inception */
} asp_slide_state;

typedef struct asp_slide_result {
    asp_slide_state state;
    double Q_max;        /* shear: largest Q of the ramp; stiffness: Q_i where
                            KT_i/KT_1 <= α first holds (BKE), N */
    double ux;           /* ux at inception (the accepted point), mm */
    double P;            /* normal load there, N */
    double mu_s;         /* Q_max / P */
    double mu_s_preload; /* Q_max / P0 */
    double slip_frac;    /* slipping area fraction there */
    double KT_ratio;     /* KT_i / KT_1 there (secant stiffnesses) */
    double KT_after;     /* secant (Q_last - Q_i) / (ux_last - ux_i) / KT_1 from
                            there to the last point pushed (the confirmation
                            increments); KT_ratio if none */
    int q_rising;        /* 1: the whole contact at its limit while Q still rose
                            past it (KT_after > flat_tol): μs depends on where
                            inception is declared */
    double mu_s_ux_slope;/* d ln(Q/P) / d ln ux at inception: the secant from
                            there to the last point pushed, or over the increment
                            that reached it when none was pushed past it; how
                            many per cent μs moves per per cent of ux where
                            inception is declared.  NaN: no secant */
    int n_contact;       /* contact nodes there */
    int index;           /* index of that point in the ramp (0 = ux = 0) */
    int increments;      /* accepted increments pushed */
    asp_outcome outcome; /* CONVERGED or MECHANISM (inception), MAX_ITERATIONS,
                            GAVE_UP, FAILED; NONE while running */
    char reason[160];    /* in words */
} asp_slide_result;

typedef struct asp_slide asp_slide;

/* New detector (returns new in *out).  `par` NULL = defaults.  Both are
 * copied.  STC_EINVAL (naming parameter, value and range) on bad input.
 * A detector is used by one thread; distinct detectors are independent. */
stc_status asp_slide_create(const asp_slide_params *par, const asp_slide_setup *su,
                            asp_slide **out);
void asp_slide_destroy(asp_slide **d); /* sets *d = NULL */

/* Feed one ACCEPTED ramp point (ux strictly increasing; the first point
 * pushed may be ux = 0, Q = 0, which is implied otherwise).  slip_frac: fraction
 * of the contact AREA whose traction is at τc; n_contact: contact nodes.
 * Returns the state after the point (also in the result). */
asp_slide_state asp_slide_push(asp_slide *d, double ux, double Q, double P, double slip_frac,
                               int n_contact);

/* Proposed next increment Δux > 0 (mm) while RUNNING, 0 otherwise.  A
 * cut-back of the solver is the caller's business (halve and retry); the
 * next proposal adapts to the increment that was actually accepted. */
double asp_slide_next(const asp_slide *d);

void asp_slide_get(const asp_slide *d, asp_slide_result *res);

/* The solver found no equilibrium past the last point pushed (cut-back limit).
 * Under the shear criterion, if that point has the whole contact at its shear
 * limit and the last increment's secant stiffness is at most full_tol KT_1,
 * the asperity can carry no more tangential load there: a plastic mechanism
 * (perfect plasticity under a contact at τc; the tangent lost positive
 * definiteness).  That point is then declared inception (Q_max the largest Q
 * up to it) and 1 is returned; otherwise 0 and nothing changes.  `why` (the
 * solver's message) is quoted in the reason. */
int asp_slide_mechanism(asp_slide *d, const char *why);

/* ---- load control (slide.c) ------------------------------------------- */

/* P(δ) callback: fills *P (N).  Returns STC_OK or a failure (with a message
 * via stc_error), which asp_find_delta propagates. */
typedef stc_status (*asp_load_fn)(void *ctx, double delta, double *P);

typedef struct asp_find_delta_opts {
    double tol;        /* |P - P_target| <= tol · P_target; default 1e-3 */
    int max_solves;    /* default 20 */
    double delta_max;  /* upper limit of δ, mm (the meshed maximum); required > 0 */
} asp_find_delta_opts;

void asp_find_delta_opts_default(asp_find_delta_opts *o);

typedef struct asp_find_delta_result {
    double delta;  /* δ found, mm */
    double P;      /* P(δ), N */
    int solves;    /* callback evaluations */
    int backward;  /* evaluations below a δ already evaluated (needs a checkpoint) */
} asp_find_delta_result;

/* Solve P(δ) = P_target for a monotone increasing P, δ in (0, delta_max].
 * delta0 > 0 is the first guess (e.g. Hertz, asp_hertz_delta_guess, or the
 * power-law through the last two solves).  Log-log secant (exact for a
 * power law), safeguarded by the bracket [lo, hi] and bisection in log δ
 * (Brent-style).  STC_ERANGE if P(delta_max) < P_target; STC_ENOCONV
 * after max_solves; a failing callback's status is returned with its
 * message prefixed. */
stc_status asp_find_delta(asp_load_fn fn, void *ctx, double P_target, double delta0,
                          const asp_find_delta_opts *o, asp_find_delta_result *res);

#endif
