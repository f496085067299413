/* Private layout of asp_solver, shared by the solver's files (solver.c,
 * load.c, newton.c, assemble.c, asp_contact.c, shear.c, footprint.c,
 * placements.c, xdmf.c), and their internal prototypes. */
#ifndef STICTION_SOLVER_IMPL_H
#define STICTION_SOLVER_IMPL_H

#include "fe.h"
#include "linsolve.h"
#include "stiction/asperity.h"
#include "tangential.h"

/* Per-node contact state; keeps the design open for the tangential step. */
enum { ASP_CS_OPEN = 0, ASP_CS_STICK = 1, ASP_CS_SLIP = 2 };

/* Elastic history of one layer, for the first-yield interpolation. */
typedef struct asp_ytrack {
    int n;               /* elastic points stored (0..2) */
    double d[2], f[2];   /* δ and max σvm/Y of the last two elastic increments */
    double P[2];         /* load there */
    double loc[2][3];    /* location of the maximum */
    double cur_loc[3];   /* location of the maximum at the converged state */
    asp_yield y;
} asp_ytrack;

typedef struct asp_asm asp_asm;
typedef struct asp_shear asp_shear;

/* Terms of another model in the Newton loop, so that the loop calls it
 * without knowing it (shear.c installs the ramp's; the normal step has
 * none).  ctx is the model's state. */
typedef struct asp_hooks {
    void *ctx;
    /* after the element loop: add nodal forces to s->fint and, with want_K,
     * their tangent to the linear solver's K, at s->u */
    void (*forces)(void *ctx, asp_solver *s, int want_K);
    /* candidate k touched the flat at the fraction lam of the increment
     * (asp_contact_update has made it active, stuck where it touched) */
    void (*touch)(void *ctx, asp_solver *s, int k, double lam);
    int tangential; /* 1: the contact nodes' tangential DOFs stay free (forces
                       holds them), even under stick */
    /* Newton stalled (newton.c): settle the discrete states of the forces
     * that cycled; returns how many it settled now (0: none, the stall is
     * a failure).  NULL: no such states. */
    int (*stalled)(void *ctx, asp_solver *s);
} asp_hooks;

struct asp_solver {
    stc_params par;
    asp_options opt;
    asp_mesh *mesh;
    asp_j2 mat[2];        /* per region */
    int dim, nen, nqp, nde; /* nde = dim * nen */
    int ndof;
    double omega_est;     /* closed-form first-yield estimate (smaller layer ωc), mm */
    double Rp, h, h0, a_max, a_min, delta_max, quality; /* h0: size at a_min */
    double n_contact;     /* elements across a_max (h = a_max / n_contact) */
    int graded;           /* 3D: core sized to a_min, shells h ∝ distance */
    int edge_refine;      /* 3D: 2:1 refinements of the contact-edge band in the mesh */

    asp_linsolve *ls;     /* the linear solver (linsolve.c) on K's fixed pattern */
    asp_asm *as;          /* assembly: pattern, scatter maps, colours (assemble.c) */
    int nthr;             /* threads of the element loop and the Krylov kernels */
    int level;            /* mesh level in use (opt.mesh_level resolved) */

    /* the FE state (newton.c, load.c, shear.c) */
    double *u, *u_conv, *du_last; /* [ndof] current, last converged, last increment */
    double *du_scr, *u0_scr;      /* [ndof] scratch of newton.c: step, line-search base */
    double *fint;                 /* [ndof] internal force at u */
    double *sig;                  /* [nelem][nqp][6] stress at u */
    asp_qp_state *st_old, *st_new; /* [nelem][nqp] */
    unsigned char *fixed;         /* [ndof] Dirichlet flag */
    double *ubc;                  /* [ndof] prescribed values of the fixed DOFs */
    double *cvec;                 /* [ndof] scratch: constraint defect */
    int k_fresh;                  /* K holds the unconstrained tangent at u */

    /* contact (asp_contact.c) */
    int ncand;                    /* contact candidates, sorted by distance from the axis */
    int *cand;                    /* node ids */
    unsigned char *cs;            /* [ncand] ASP_CS_* */
    double *cstick;               /* [ncand][dim - 1] tangential displacement when stuck */

    /* loading (load.c) and the results (asp_contact.c) */
    double delta;                 /* current converged interference */
    double step;                  /* next increment, mm */
    double dlast;                 /* size of the last accepted increment */
    asp_point pt;                 /* response at the converged state */
    asp_ytrack yt[2];
    double *hd, *hP, *hA;         /* history of converged increments: δ, P, A */
    int nh, caph;

    const asp_hooks *hooks;       /* terms of another model in the Newton loop (the
                                     ramp's stick law), NULL for the normal step */
    asp_shear *sh;                /* the ramp's state (shear.c), NULL until a ramp */
};

/* asp_solver_P_smooth's window: increments within a factor ASP_SMOOTH_W of δ
 * (asp_contact.c; load.c samples the elastic range from its start). */
#define ASP_SMOOTH_W 2.0

/* mesh.c: asp_mesh_axisym_graded with n elements across a_max instead of
 * 6 2^level (n in [3, 384], any real value; spec->level is still checked). */
stc_status asp_mesh_axisym_n(const asp_mesh_spec *spec, double a_min, double n, asp_mesh **out);
/* ... and with the top row split into surface_layers + 1 rows halving towards
 * the surface (asp_options.surface_layers; in [0, ASP_MESH_MAX_SURFACE_LAYERS]). */
enum { ASP_MESH_MAX_SURFACE_LAYERS = 6 };
stc_status asp_mesh_axisym_nl(const asp_mesh_spec *spec, double a_min, double n,
                              int surface_layers, asp_mesh **out);
/* mesh.c: asp_options.surface_layers with -1 (automatic) resolved. */
int asp_surface_layers(const asp_options *o);

/* assemble.c: asp_asm_create indexes the hanging nodes and colours the
 * elements (s->as); asp_asm_pattern gives the CSC pattern of K, Kp
 * [ndof + 1] and Ki returned new; asp_asm_maps the scatter maps once
 * s->ls holds it; asp_assemble: fint, sig, st_new (and K, Kd, W into
 * s->ls if want_K) at s->u from st_old, STC_ENOCONV if an element
 * inverted; asp_asm_work: element loops and their wall time so far. */
stc_status asp_asm_create(asp_solver *s);
stc_status asp_asm_pattern(const asp_solver *s, int **Kp, int **Ki);
stc_status asp_asm_maps(asp_solver *s);
stc_status asp_assemble(asp_solver *s, int want_K);
void asp_asm_work(const asp_asm *a, int *evaluations, double *wall_s);
void asp_asm_destroy(asp_asm **a);
/* Displacement of node n from the DOF vector u (dim components into out):
 * a hanging node's is the weighted average of its masters' (assemble.c). */
void asp_node_u(const asp_solver *s, const double *u, int n, double *out);

/* asp_contact.c: the candidates (asp_contact_setup, once); the fixed DOFs
 * and their values at δ (asp_contact_dirichlet); the active set updated
 * from the current state (asp_contact_update: returns the changes; add_only
 * keeps every active node) or started from the Hertz radius
 * (asp_contact_hertz). */
stc_status asp_contact_setup(asp_solver *s);
void asp_contact_dirichlet(asp_solver *s, double delta);
int asp_contact_update(asp_solver *s, double delta, int add_only);
void asp_contact_hertz(asp_solver *s, double delta);

/* asp_contact.c: results at the converged state, first-yield tracking and
 * the history of P_smooth. */
void asp_contact_results(asp_solver *s, asp_point *pt);
void asp_yield_track(asp_solver *s, const asp_point *pt);
void asp_history_push(asp_solver *s, double delta, double P, double A);

/* shear.c: frees the ramp's state (*sh = NULL). */
void asp_shear_destroy(asp_shear **sh);

/* newton.c: one increment to `delta`, started from the predictor u_conv +
 * pred du_last (pred: this increment over the last accepted one, in the
 * caller's load parameter), the active set iterated to consistency; its
 * Newton iterations, factorizations and active-set passes are added to ns.
 * On failure the caller restores the converged state. */
typedef struct asp_nstat {
    int iters, facts, passes;
    asp_outcome why; /* how the last Newton solve or active-set loop ended */
} asp_nstat;
stc_status asp_newton_increment(asp_solver *s, double delta, double pred, asp_nstat *ns);

#endif
