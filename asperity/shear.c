/* Tangential step of the asperity solver: after the normal step
 * the flat is held at δ and moved along +x by ux until the asperity slides.
 * Design and its numbers: docs/design.md §4.
 *
 *   - contact nodes keep u_z prescribed (no separation, thesis §3.2.3.3);
 *     their tangential DOFs are free and carry the shear-limited stick law
 *     of Wu, Shi & Polycarpou (2012) as a penalty return map (friction.c),
 *     assembled into each node's own 2x2 diagonal block of the fixed CSC
 *     pattern, so CHOLMOD's analysis and the SPD LLᵀ stay valid;
 *   - tributary areas from the sub-element contact radius of the normal step
 *     (surfarea.c), so full slip carries exactly τc × contact area;
 *   - ux is ramped by the inception detector / controller of slide.c, with
 *     cut-back (halving) on a failed increment; the shear criterion's
 *     fraction counts nodes that slip or whose traction has saturated
 *     (mark_saturated);
 *   - the first Newton iteration of each increment keeps stuck nodes stuck
 *     (springs), the elastic predictor of the increment.
 * The ramp's state is a struct of its own (asp_shear, s->sh); it reaches
 * the Newton loop through the solver's hooks (springs: the stick-law
 * forces and tangent after the element loop; touch: a node that touches
 * sticks), so newton.c, assemble.c and asp_contact.c never call in here.
 */
#include <hdf5.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

#include "footprint.h"
#include "solver_impl.h"
#include "stc_check.h"
#include "stiction/formulas.h"

/* Kept field snapshots: Q = 0, candidates for 0.8 Q_max (three in a window
 * of the full-slip estimate, and the last three points: the stiffness
 * criterion may stop below that window), and Q_max. */
enum { SNAP_Q0 = 0, SNAP_C0 = 1, SNAP_NC = 3, SNAP_QMAX = 4, SNAP_R0 = 5, SNAP_NR = 3,
       ASP_SHEAR_NSNAP = 8 };

/* Candidate window for the 0.8 Q_max snapshot, as a fraction of the
 * full-slip estimate τc A (A: the current contact area). */
#define SNAP_LO 0.6
#define SNAP_HI 0.95

/* A node held in a state after a stall (stalled, try_ux) must end as a
 * solution of the free stick law to round-off: stuck with |t_trial| <= τc,
 * slipping with |t_trial| >= τc, within this fraction of τc; and the
 * re-solves that flip the held nodes found otherwise are at most
 * HOLD_PASSES per try. */
#define HOLD_TOL 1e-9
enum { HOLD_PASSES = 4 };

typedef struct asp_shear_snap {
    int kept;
    double Q, P, delta, ux;
    double *u, *sig;     /* [ndof], [nelem][nqp][6] */
    asp_qp_state *st;    /* [nelem][nqp] */
} asp_shear_snap;

/* The ramp's state (s->sh), beside the solver's displacement and contact
 * state, which the ramp shares with the normal step. */
struct asp_shear {
    asp_hooks hooks;              /* the stick law in the Newton loop (s->hooks) */
    double ux, ux_conv;           /* flat displacement along x: trial, converged, mm */
    double ux_dlast;              /* last accepted ux increment, mm (0: none yet) */
    asp_fric_law fric;            /* τc and penalty k_t */
    double *carea;                /* [ncand] tributary area, mm² */
    double *carea_full;           /* [ncand] full (unclipped) tributary area, mm² */
    double *carea_prev, *carea_tgt; /* [ncand] areas of the converged state and the reading
                                       after it (the increment's target; try_ux) */
    unsigned char *cnew;          /* [ncand] 1: not in contact when the ramp started */
    double foot[3];               /* contact extent +x, -x, +y during the ramp, mm */
    asp_foot fp;                  /* node lines across the edge (footprint.c) */
    double *ctrac;                /* [ncand] |traction| at the last accepted point, MPa */
    double rate_sat;              /* d|t|/dux below which a stuck node is saturated, MPa/mm */
    unsigned char *cyield;        /* [ncand] 1: stuck but saturated in the last increment
                                     (the junction shears in the body; mark_saturated) */
    double *cslip_new;            /* [ncand][2] trial slip; s->cstick holds the converged one */
    double *cfric;                /* [ncand][2] friction force on the flat at u, N */
    unsigned char *cfst;          /* [ncand] trial ASP_CS_STICK / ASP_CS_SLIP */
    unsigned char *cflip;         /* [ncand] stick/slip switches in this try (saturating) */
    unsigned char *chold;         /* [ncand] 0, or the state (ASP_FRIC_STICK / SLIP) it
                                     is held in for the rest of this try (stalled) */
    unsigned char *cbad;          /* [ncand] 1: held in a state the law would leave
                                     (last assembly) */
    int nhold;                    /* nodes held in this try */
    int fric_evals;               /* assemblies with the stick law free, this try */
    int *cpos;                    /* [ncand][3] positions of (x,x), (x,y), (y,y) in K */
    int fric_frozen;              /* next assembly: converged stick nodes stay stuck
                                     (first iteration of an increment, springs) */
    asp_shear_snap *snap;         /* [ASP_SHEAR_NSNAP] kept field snapshots */
};

void asp_shear_options_default(asp_shear_options *o)
{
    o->criterion = ASP_SHEAR_CRIT_SHEAR;
    o->alpha = 0.1; /* Brizmer, Kligerman & Etsion 2007 */
    o->tau_c = 0.0;
    o->kappa = ASP_FRIC_KAPPA_DEFAULT;
    o->junction = ASP_JUNCTION_FOOTPRINT;
    o->max_increments = 200;
    o->keep_fields = 0;
    o->return_map = ASP_RETURN_RADIAL;
    o->ramp_refine = 1.0;
    /* the three axis lines: the node rows (foot_rows 0.6) have a third of
     * their node-placement scatter but read the elastic growth 0.7-1.6
     * points high, +3.1 % in μs at WSP 1 ωc against the half-space
     * (docs/design.md §4.2, §4.5) */
    o->foot_rows = 0.0;
    o->hold_stalled = 1;
}

/* ---- the stick-law springs (hooks called from the Newton loop) ----------- */

/* The first assembly of an increment (fric_frozen) keeps the nodes that
 * stuck at the converged state stuck (linear springs, no cap): otherwise
 * the jump of the flat, seen from the unmoved body, puts every node past
 * τc at once (k_t Δux >> τc already for Δux ~ 1e-3 ux_e), the tangent
 * loses all its tangential stiffness and Newton oscillates between the
 * two fully slipping states (measured: 30 iterations, no convergence, at
 * Δux = 0.05 ux_e).  The stuck first iteration is the elastic (tangent)
 * predictor of the increment; the return map takes over from the next
 * assembly on, the usual treatment of frictional increments (Wriggers,
 * Computational Contact Mechanics, 2006, §10.3: state of the last
 * converged step in the first iteration). */
static void springs(void *ctx, asp_solver *s, int want_K)
{
    asp_shear *sh = ctx;
    double *Kx, *Kd, *Kk;
    asp_ls_values(s->ls, &Kx, &Kd, &Kk);
    asp_fric_law stuck = sh->fric;
    stuck.tau_c = HUGE_VAL;
    int frozen = sh->fric_frozen, count = !frozen && sh->fric_evals++ > 0;
    sh->fric_frozen = 0;
    for (int k = 0; k < s->ncand; k++) {
        double *f = sh->cfric + 2 * k;
        unsigned char was = sh->cfst[k];
        f[0] = f[1] = 0.0;
        sh->cfst[k] = s->cs[k];
        if (s->cs[k] == ASP_CS_OPEN || !(sh->carea[k] > 0.0)) continue;
        int n = s->cand[k];
        double g[2] = {s->u[3 * n] - sh->ux, s->u[3 * n + 1]}, Kc[4];
        int hold = sh->chold[k]; /* 0: the law chooses */
        const asp_fric_law *law = !hold && frozen && s->cs[k] == ASP_CS_STICK ? &stuck
                                                                               : &sh->fric;
        double ratio; /* |t_trial| / τc */
        sh->cfst[k] = (unsigned char)asp_fric_update_as(law, hold, sh->carea[k], g,
                                                       s->cstick + 2 * k, sh->cslip_new + 2 * k,
                                                       f, Kc, &ratio);
        if (hold)
            sh->cbad[k] = hold == ASP_FRIC_STICK ? ratio > 1.0 + HOLD_TOL
                                                 : ratio < 1.0 - HOLD_TOL;
        if (count && sh->cfst[k] != was && sh->cflip[k] < 255) sh->cflip[k]++;
        /* the node feels -f: residual fint + f = 0 */
        s->fint[3 * n] += f[0];
        s->fint[3 * n + 1] += f[1];
        if (!want_K) continue;
        Kx[sh->cpos[3 * k]] += Kc[0];
        Kx[sh->cpos[3 * k + 1]] += Kc[1];
        Kx[sh->cpos[3 * k + 2]] += Kc[3];
    }
}

/* Newton stalled with contact nodes switching between stick and slip from
 * one iterate to the next: near |t| = τc both states give almost the same
 * force, and the tangent jumps between k_t and (nearly) zero along the
 * traction, so the iterates can cycle with the residual stuck far above the
 * tolerance (docs/design.md §4.3).  The nodes that switched twice or more
 * in this try are held in their current state for its rest, which takes
 * the cycling out of Newton; try_ux then checks every held node against
 * the free law and re-solves with the wrong ones flipped (held_flip).
 * Returns how many nodes it newly holds. */
static int stalled(void *ctx, asp_solver *s)
{
    asp_shear *sh = ctx;
    int n = 0;
    for (int k = 0; k < s->ncand; k++) {
        if (sh->chold[k] || s->cs[k] == ASP_CS_OPEN || sh->cflip[k] < 2) continue;
        sh->chold[k] = sh->cfst[k] == ASP_CS_SLIP ? ASP_FRIC_SLIP : ASP_FRIC_STICK;
        sh->cbad[k] = 0;
        n++;
    }
    sh->nhold += n;
    return n;
}

/* After a converged solve: the held nodes whose state the free law would
 * leave (cbad, from the last assembly) are flipped to the other state;
 * returns how many. */
static int held_flip(asp_solver *s)
{
    asp_shear *sh = s->sh;
    int n = 0;
    for (int k = 0; k < s->ncand; k++) {
        if (!sh->chold[k] || !sh->cbad[k]) continue;
        sh->chold[k] = sh->chold[k] == ASP_FRIC_STICK ? ASP_FRIC_SLIP : ASP_FRIC_STICK;
        sh->cbad[k] = 0;
        n++;
    }
    return n;
}

static void snap_free(asp_shear_snap *p)
{
    free(p->u), free(p->sig), free(p->st);
    memset(p, 0, sizeof *p);
}

/* A node that touches the flat during the ramp sticks there: its slip is
 * its tangential displacement relative to the flat, s = g. */
static void touch(void *ctx, asp_solver *s, int k, double lam)
{
    const asp_shear *sh = ctx;
    s->cs[k] = ASP_CS_STICK;
    s->cstick[2 * k] -= sh->ux_conv + lam * (sh->ux - sh->ux_conv);
}

void asp_shear_destroy(asp_shear **shp)
{
    asp_shear *sh = *shp;
    if (!sh) return;
    free(sh->carea), free(sh->carea_full), free(sh->cslip_new), free(sh->cfric), free(sh->cfst);
    free(sh->carea_prev), free(sh->carea_tgt), free(sh->cflip), free(sh->chold), free(sh->cbad);
    free(sh->cpos), free(sh->cnew), free(sh->ctrac), free(sh->cyield);
    asp_foot_free(&sh->fp);
    if (sh->snap)
        for (int i = 0; i < ASP_SHEAR_NSNAP; i++) snap_free(&sh->snap[i]);
    free(sh->snap);
    free(sh);
    *shp = NULL;
}

/* ---- set-up ------------------------------------------------------------ */

/* The ramp's state s->sh with its arrays and the K positions of the
 * contact nodes' 2x2 blocks. */
static stc_status alloc_shear(asp_solver *s)
{
    size_t n = (size_t)s->ncand;
    if (!s->sh) s->sh = calloc(1, sizeof *s->sh);
    asp_shear *sh = s->sh;
    STC_CHECK(sh, STC_ENOMEM, "shear: out of memory");
    if (!sh->carea) {
        sh->carea = calloc(n, sizeof *sh->carea), sh->carea_full = calloc(n, sizeof *sh->carea);
        sh->cslip_new = calloc(2 * n, sizeof *sh->carea), sh->cfric = calloc(2 * n, sizeof *sh->carea);
        sh->carea_prev = calloc(n, sizeof *sh->carea), sh->carea_tgt = calloc(n, sizeof *sh->carea);
        sh->cfst = calloc(n, 1), sh->cpos = calloc(3 * n, sizeof *sh->cpos);
        sh->cflip = calloc(n, 1), sh->chold = calloc(n, 1), sh->cbad = calloc(n, 1);
        sh->cnew = calloc(n, 1), sh->cyield = calloc(n, 1);
        sh->ctrac = calloc(n, sizeof *sh->ctrac);
        sh->snap = calloc(ASP_SHEAR_NSNAP, sizeof *sh->snap);
    }
    STC_CHECK(sh->carea && sh->carea_full && sh->carea_prev && sh->carea_tgt && sh->cslip_new &&
                  sh->cfric && sh->cfst && sh->cflip && sh->chold && sh->cbad && sh->cpos && sh->cnew &&
                  sh->cyield && sh->ctrac &&
                  sh->snap,
              STC_ENOMEM, "shear: out of memory");
    for (int k = 0; k < s->ncand; k++) {
        int n3 = 3 * s->cand[k], *pos = sh->cpos + 3 * k;
        pos[0] = asp_ls_pos(s->ls, n3, n3);
        pos[1] = asp_ls_pos(s->ls, n3, n3 + 1);
        pos[2] = asp_ls_pos(s->ls, n3 + 1, n3 + 1);
        STC_CHECK(pos[0] >= 0 && pos[1] >= 0 && pos[2] >= 0, STC_ESOLVER,
                  "shear: node %d's 2x2 block is not in the pattern", s->cand[k]);
    }
    return STC_OK;
}

/* Tributary areas (docs/design.md §4.1): contact nodes get the part
 * of their hat function on the contact disc of radius a (the sub-element
 * radius of the normal step), so Σ A_k is the cap area and not a
 * ring-quantised node count; the disc area on still-open nodes goes to the
 * edge ring of the contact (nodes only partly on the disc), scaled up.
 * During the ramp the disc becomes the footprint of the sheared contact
 * (foot_areas), or the nodes that touch get their own areas (new_node_areas).
 * The full areas carea_full are set once (full_areas). */
static stc_status node_areas(asp_solver *s, const double ext[3])
{
    asp_shear *sh = s->sh;
    double *Ad = malloc((size_t)s->mesh->nnode * sizeof *Ad), *Af = sh->carea_full;
    stc_status st = STC_OK;
    STC_CHECK_GOTO(Ad, st, done, STC_ENOMEM, "shear: out of memory");
    STC_CALL_GOTO(asp_surface_node_areas_foot(s->mesh, s->Rp, ext[0], ext[1], ext[2], Ad), st,
                  done);
    double lost = 0.0, edge = 0.0, all = 0.0;
    for (int k = 0; k < s->ncand; k++) {
        int n = s->cand[k];
        if (s->cs[k] == ASP_CS_OPEN) {
            lost += Ad[n];
            sh->carea[k] = 0.0;
            continue;
        }
        sh->carea[k] = Ad[n];
        all += Ad[n];
        if (Ad[n] < 0.999 * Af[k]) edge += Ad[n];
    }
    STC_CHECK_GOTO(all > 0.0, st, done, STC_EINVAL,
                   "shear: contact footprint (%g, %g, %g) mm covers no contact node", ext[0],
                   ext[1], ext[2]);
    /* no partly covered node: spread over the whole contact instead */
    int whole = !(edge > 0.0);
    double base = whole ? all : edge, scale = (base + lost) / base;
    for (int k = 0; k < s->ncand; k++) {
        int n = s->cand[k];
        if (s->cs[k] != ASP_CS_OPEN && (whole || Ad[n] < 0.999 * Af[k])) sh->carea[k] *= scale;
    }
done:
    free(Ad);
    return st;
}

/* Full tributary area of every candidate (the cap of new_node_areas and the
 * test for an edge node in node_areas); the mesh does not change. */
static stc_status full_areas(asp_solver *s)
{
    double *Af = malloc((size_t)s->mesh->nnode * sizeof *Af);
    STC_CHECK(Af, STC_ENOMEM, "shear: out of memory");
    stc_status st = asp_surface_node_areas(s->mesh, s->Rp, Af);
    for (int k = 0; st == STC_OK && k < s->ncand; k++) s->sh->carea_full[k] = Af[s->cand[k]];
    free(Af);
    return st;
}

/* Junction growth, rule ASP_JUNCTION_FOOTPRINT (docs/design.md
 * §4.2): after each accepted increment the contact's extent along +x, -x
 * and +y is read from the gaps ahead of its edges (asp_foot_extent),
 * never shrinking, and the areas are the hat integrals over the two
 * half-ellipses it spans, so the junction grows by fractions of an element
 * instead of a node ring at a time.  The areas are fixed within an
 * increment (the Newton tangent stays consistent).  Measured: the growth it
 * reads falls with the element size (WSP 3 ωc, area at Q_max over the
 * preload: +16.5 / +12.4 / +9.7 % at 6 / 8.5 / 12 elements per contact); the
 * first open node's gap closes faster than the edge advances on a coarse
 * mesh (the element at the edge bends).  ASP_JUNCTION_NODES errs the other
 * way: the two bracket the converged answer. */
static stc_status foot_areas(asp_solver *s)
{
    asp_shear *sh = s->sh;
    double ext[3];
    asp_foot_extent(&sh->fp, s, ext);
    for (int i = 0; i < 3; i++) sh->foot[i] = fmax(sh->foot[i], ext[i]);
    return node_areas(s, sh->foot);
}

/* τc: the option, or Y/√3 of the contacting layer (von Mises shear yield;
 * WSP 2012, thesis §3.1.2).  Also returns that layer's material. */
static double tau_c_default(const asp_solver *s, double tau_opt, stc_material *layer)
{
    stc_material su, co;
    stc_params_materials(&s->par, &su, &co);
    *layer = s->par.t_over_R > 0.0 ? co : su;
    return tau_opt > 0.0 ? tau_opt : layer->Y / sqrt(3.0);
}

/* Start the stick law with the force the normal step left at each contact
 * node: after a stick step the tangential reaction r (= fint on the frozen
 * DOFs) becomes the spring force, s = g + r/(A k_t); after a slip step the
 * traction is zero, s = g (docs/design.md §4.1). */
static void initial_slip(asp_solver *s)
{
    asp_shear *sh = s->sh;
    const asp_mesh *m = s->mesh;
    int stick = s->opt.contact == ASP_CONTACT_STICK;
    for (int k = 0; k < s->ncand; k++) {
        if (s->cs[k] == ASP_CS_OPEN) continue;
        int n = s->cand[k], sym = !!(m->flags[n] & ASP_NODE_SYM);
        double ka = sh->carea[k] * sh->fric.kt;
        for (int c = 0; c < 2; c++) {
            double r = stick && ka > 0.0 && !(c == 1 && sym) ? s->fint[3 * n + c] / ka : 0.0;
            s->cstick[2 * k + c] = s->u_conv[3 * n + c] + r;
        }
        s->cs[k] = ASP_CS_STICK;
    }
}

/* ---- one ramp point ---------------------------------------------------- */

/* Junction growth, rule ASP_JUNCTION_NODES: a node that touched during the
 * ramp gets the area over which the mean contact pressure of the normal
 * step, p_m = P0 / A0, carries its normal force, capped at its full
 * tributary area.  (Its full area, h², would add a contact strip an element
 * wide for an edge that moved by a fraction of h: at level 0, δ = 0.3 ωc,
 * one node ring raised the full-slip plateau by 6.8 %.)  An edge node's
 * pressure is below p_m, so the growth is read low on a coarse mesh (WSP
 * 3 ωc: +0 / +1.1 / +3.3 % at 6 / 8.5 / 12 elements per contact).  Updated
 * after each accepted increment. */
static void new_node_areas(asp_solver *s, double p_m)
{
    asp_shear *sh = s->sh;
    for (int k = 0; k < s->ncand; k++) {
        if (!sh->cnew[k] || s->cs[k] == ASP_CS_OPEN) continue;
        double Fz = -s->fint[3 * s->cand[k] + 2];
        sh->carea[k] = fmin(sh->carea_full[k], fmax(Fz, 0.0) / p_m);
    }
}

/* Stuck contact nodes whose traction stopped rising (d|t|/dux below
 * rate_sat, a tenth of the mean elastic rate τc/ux_e; the Mindlin centre
 * traction rises at half that mean): the material under them carries no
 * more shear, so the junction shears in the body, not at the interface.
 * With τc = Y/√3 the surface material yields before the interface traction
 * reaches τc wherever the contact pressure adds a deviatoric stress: past
 * ~3 ωc the centre of the contact never slips (measured at 6 ωc, level 0:
 * 20 % of the area stuck while Q kept rising as P relaxed and the contact
 * grew; μ = Q/P went on growing to +30 % above the WSP fit before Q was
 * flat).  Counting them as at their shear limit is the thesis's criterion
 * (§4.1.3, Fig. 4.9: Q_max when the whole contact is at its limit).
 * Counting nodes on yielding material instead fires at once past ~6 ωc,
 * where the normal step already left the whole contact surface plastic. */
static void mark_saturated(asp_solver *s)
{
    asp_shear *sh = s->sh;
    double dux = sh->ux - sh->ux_conv;
    for (int k = 0; k < s->ncand; k++) {
        double A = sh->carea[k];
        double t = A > 0.0 ? hypot(sh->cfric[2 * k], sh->cfric[2 * k + 1]) / A : 0.0;
        sh->cyield[k] = s->cs[k] != ASP_CS_OPEN && A > 0.0 && dux > 0.0 &&
                       (t - sh->ctrac[k]) / dux <= sh->rate_sat;
        sh->ctrac[k] = t;
    }
}

static void commit_shear(asp_solver *s)
{
    asp_shear *sh = s->sh;
    size_t nq = (size_t)s->mesh->nelem * s->nqp;
    mark_saturated(s);
    for (int i = 0; i < s->ndof; i++) s->du_last[i] = s->u[i] - s->u_conv[i];
    sh->ux_dlast = sh->ux - sh->ux_conv;
    memcpy(s->u_conv, s->u, (size_t)s->ndof * sizeof *s->u);
    memcpy(s->st_old, s->st_new, nq * sizeof *s->st_old);
    for (int k = 0; k < s->ncand; k++) {
        if (s->cs[k] == ASP_CS_OPEN || !(sh->carea[k] > 0.0)) continue;
        s->cstick[2 * k] = sh->cslip_new[2 * k];
        s->cstick[2 * k + 1] = sh->cslip_new[2 * k + 1];
        s->cs[k] = sh->cfst[k];
    }
    sh->ux_conv = sh->ux;
    asp_contact_results(s, &s->pt);
}

/* Q, P, areas at the committed state (half-model sums x 2). */
static void measure(const asp_solver *s, asp_shear_point *pt)
{
    asp_shear *sh = s->sh;
    const asp_mesh *m = s->mesh;
    double Q = 0.0, Qb = 0.0, A = 0.0, As = 0.0, Al = 0.0;
    int nc = 0;
    for (int k = 0; k < s->ncand; k++) {
        if (s->cs[k] == ASP_CS_OPEN) continue;
        nc++;
        Q -= sh->cfric[2 * k];
        A += sh->carea[k];
        if (s->cs[k] == ASP_CS_STICK) As += sh->carea[k];
        if (s->cs[k] == ASP_CS_STICK && !sh->cyield[k]) Al += sh->carea[k];
    }
    for (int n = 0; n < m->nnode; n++)
        if (m->flags[n] & ASP_NODE_BASE) Qb -= s->fint[3 * n];
    pt->ux = sh->ux_conv;
    pt->Q = 2.0 * Q;
    pt->Q_base = 2.0 * Qb;
    pt->P = s->pt.P;
    pt->A = 2.0 * A;
    pt->A_stick = 2.0 * As;
    pt->slip_frac = A > 0.0 ? 1.0 - As / A : 0.0;
    pt->limit_frac = A > 0.0 ? 1.0 - Al / A : 0.0;
    pt->n_contact = nc;
    pt->a_lead = sh->foot[0], pt->a_trail = sh->foot[1], pt->a_side = sh->foot[2];
}

/* ---- snapshots ------------------------------------------------------------ */

static stc_status snap_take(asp_solver *s, asp_shear_snap *p, double Q)
{
    size_t nq = (size_t)s->mesh->nelem * s->nqp;
    if (!p->u) {
        p->u = malloc((size_t)s->ndof * sizeof *p->u);
        p->sig = malloc(6 * nq * sizeof *p->sig);
        p->st = malloc(nq * sizeof *p->st);
    }
    STC_CHECK(p->u && p->sig && p->st, STC_ENOMEM, "shear: out of memory for a field snapshot");
    memcpy(p->u, s->u_conv, (size_t)s->ndof * sizeof *p->u);
    memcpy(p->sig, s->sig, 6 * nq * sizeof *p->sig);
    memcpy(p->st, s->st_old, nq * sizeof *p->st);
    p->kept = 1, p->Q = Q, p->P = s->pt.P, p->delta = s->delta, p->ux = s->sh->ux_conv;
    return STC_OK;
}

/* Keep Q = 0, up to SNAP_NC candidates near 0.8 of the full-slip estimate
 * (the one farthest from it is replaced), and the largest Q so far
 * (stiffness criterion: the latest point, where the ramp stops). */
static stc_status snap_update(asp_solver *s, const asp_shear_point *pt, double tau_c, int idx,
                              int latest_is_max)
{
    asp_shear_snap *sn = s->sh->snap;
    if (idx == 0) return snap_take(s, &sn[SNAP_Q0], pt->Q);
    if (latest_is_max || !sn[SNAP_QMAX].kept || pt->Q >= sn[SNAP_QMAX].Q)
        STC_CALL(snap_take(s, &sn[SNAP_QMAX], pt->Q));
    STC_CALL(snap_take(s, &sn[SNAP_R0 + idx % SNAP_NR], pt->Q));
    double est = tau_c * pt->A, c = 0.8 * est;
    if (!(pt->Q >= SNAP_LO * est && pt->Q <= SNAP_HI * est)) return STC_OK;
    int worst = SNAP_C0;
    for (int i = SNAP_C0; i < SNAP_C0 + SNAP_NC; i++) {
        if (!sn[i].kept) return snap_take(s, &sn[i], pt->Q);
        if (fabs(sn[i].Q - c) > fabs(sn[worst].Q - c)) worst = i;
    }
    if (fabs(pt->Q - c) < fabs(sn[worst].Q - c)) return snap_take(s, &sn[worst], pt->Q);
    return STC_OK;
}

/* The ramp point of a field file as attributes of its HDF5 root group
 * (beside the model parameters the writer stores). */
static stc_status ramp_attrs(const asp_solver *s, const char *prefix, const asp_shear_snap *p,
                             double Qmax)
{
    asp_shear *sh = s->sh;
    char path[4096];
    snprintf(path, sizeof path, "%s.h5", prefix);
    hid_t f = -1;
    H5E_BEGIN_TRY { f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK(f >= 0, STC_EIO, "fields: cannot reopen '%s'", path);
    const char *name[5] = {"ux_mm", "Q_N", "Q_over_Q_max", "tau_c_MPa", "friction_kt_MPa_per_mm"};
    double v[5] = {p->ux, p->Q, Qmax > 0.0 ? p->Q / Qmax : NAN, sh->fric.tau_c, sh->fric.kt};
    int bad = 0;
    H5E_BEGIN_TRY { /* failures are reported in the status, not on stderr */
        for (int i = 0; i < 5; i++) {
            hid_t sp = H5Screate(H5S_SCALAR);
            hid_t a = H5Acreate2(f, name[i], H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
            bad |= a < 0 || H5Awrite(a, H5T_NATIVE_DOUBLE, &v[i]) < 0;
            if (a >= 0) H5Aclose(a);
            H5Sclose(sp);
        }
        bad |= H5Fclose(f) < 0;
    } H5E_END_TRY;
    STC_CHECK(!bad, STC_EIO, "fields: cannot write the ramp attributes into '%s'", path);
    return STC_OK;
}

stc_status asp_solver_write_shear_fields(asp_solver *s, int which, const char *prefix,
                                         double *Q_over_Qmax)
{
    asp_shear *sh = s->sh;
    STC_CHECK(which >= 0 && which <= 2, STC_EINVAL,
              "which = %d: must be 0 (Q = 0), 1 (0.8 Qmax) or 2 (Qmax)", which);
    STC_CHECK(s->sh && sh->snap && sh->snap[SNAP_QMAX].kept, STC_EINVAL,
              "shear fields: no ramp with keep_fields was run");
    double Qmax = sh->snap[SNAP_QMAX].Q;
    asp_shear_snap *p = which == 0 ? &sh->snap[SNAP_Q0] : &sh->snap[SNAP_QMAX];
    if (which == 1) {
        p = NULL;
        for (int i = SNAP_C0; i < ASP_SHEAR_NSNAP; i++)
            if (i != SNAP_QMAX && sh->snap[i].kept &&
                (!p || fabs(sh->snap[i].Q - 0.8 * Qmax) < fabs(p->Q - 0.8 * Qmax)))
                p = &sh->snap[i];
        STC_CHECK(p, STC_EINVAL, "shear fields: no ramp point kept for 0.8 Q_max");
    }
    STC_CHECK(p->kept, STC_EINVAL, "shear fields: snapshot %d not kept", which);
    if (Q_over_Qmax) *Q_over_Qmax = Qmax > 0.0 ? p->Q / Qmax : NAN;
    /* the writer reads the converged state: lend it the snapshot */
    double *u = s->u_conv, *sig = s->sig, P = s->pt.P, d = s->delta;
    asp_qp_state *st = s->st_old;
    s->u_conv = p->u, s->sig = p->sig, s->st_old = p->st, s->pt.P = p->P, s->delta = p->delta;
    stc_status r = asp_solver_write_fields(s, prefix);
    s->u_conv = u, s->sig = sig, s->st_old = st, s->pt.P = P, s->delta = d;
    if (r == STC_OK) r = ramp_attrs(s, prefix, p, Qmax);
    return r;
}

/* ---- the ramp ------------------------------------------------------------ */

static stc_status check_shear(const asp_solver *s, const asp_shear_options *o)
{
    STC_CHECK(o->criterion == ASP_SHEAR_CRIT_SHEAR || o->criterion == ASP_SHEAR_CRIT_STIFFNESS,
              STC_EINVAL, "criterion = %d: must be shear or stiffness", (int)o->criterion);
    STC_CHECK(o->alpha > 0.0 && o->alpha < 1.0, STC_EINVAL,
              "alpha = %g: stiffness ratio must be in (0, 1) (BKE: 0.1)", o->alpha);
    STC_CHECK(o->tau_c >= 0.0 && isfinite(o->tau_c), STC_EINVAL,
              "tau-c = %g MPa: must be > 0 (or 0 = Y/sqrt(3) of the contacting layer)", o->tau_c);
    STC_CHECK(o->kappa > 0.0 && isfinite(o->kappa), STC_EINVAL,
              "kappa = %g: penalty factor must be > 0 (default %g)", o->kappa,
              ASP_FRIC_KAPPA_DEFAULT);
    STC_CHECK(o->max_increments >= 3 && o->max_increments <= 100000, STC_EINVAL,
              "max-increments = %d: must be in [3, 100000]", o->max_increments);
    STC_CHECK(o->junction == ASP_JUNCTION_FOOTPRINT || o->junction == ASP_JUNCTION_NODES,
              STC_EINVAL, "junction = %d: must be footprint or nodes", (int)o->junction);
    STC_CHECK(o->return_map >= ASP_RETURN_MIDPOINT && o->return_map <= ASP_RETURN_EXACT,
              STC_EINVAL, "ramp return map = %d: must be 0 (midpoint), 1 (radial) or 2 (exact)",
              (int)o->return_map);
    STC_CHECK(o->ramp_refine >= 1.0 && o->ramp_refine <= 64.0, STC_EINVAL,
              "ramp refine = %g: must be in [1, 64]", o->ramp_refine);
    STC_CHECK(o->foot_rows >= 0.0 && o->foot_rows <= 0.9, STC_EINVAL,
              "foot rows = %g: must be in [0, 0.9] (fraction of the preload contact radius)",
              o->foot_rows);
    STC_CHECK(o->hold_stalled == 0 || o->hold_stalled == 1, STC_EINVAL,
              "hold stalled = %d: must be 0 or 1", o->hold_stalled);
    STC_CHECK(s->dim == 3, STC_EINVAL,
              "shear: the tangential step needs the 3D model (geometry = 3d), not axisymmetric");
    STC_CHECK(!s->hooks, STC_EINVAL, "shear: a ramp was already run on this solver");
    STC_CHECK(!s->graded, STC_EINVAL,
              "shear: grade-3d (the graded 3D core) is not validated for the tangential step "
              "(penalty size, footprint lines); run the ramp without it");
    STC_CHECK(s->delta > 0.0 && s->pt.n_contact > 0, STC_EINVAL,
              "shear: delta = %g mm: load the flat (asp_solver_load) before the ramp", s->delta);
    return STC_OK;
}

typedef struct ramp {
    asp_shear_result *res;
    unsigned char *cs0;
    double *cst0;
    asp_shear_point *pts; /* [cap] accepted points */
    int npt, cap;
    double p_m;           /* mean contact pressure after the normal step, MPa */
} ramp;

/* The contact and stick states of the start of the try (saved in r). */
static void restore_states(asp_solver *s, const ramp *r)
{
    memcpy(s->cs, r->cs0, (size_t)s->ncand);
    memcpy(s->cstick, r->cst0, (size_t)s->ncand * 2 * sizeof *r->cst0);
}

/* One increment to ux; on failure the converged state is restored.
 *
 * lam in (0, 1]: the share of the junction reading taken in this increment.
 * The nodal areas are read after each accepted increment (accept), and the
 * stuck nodes' forces scale with them, so the reading is a load step of its
 * own: the converged state is out of equilibrium with the new areas before
 * the flat moves.  A cut-back halves that step with the flat's (lam = the
 * cut Δux over the first try's): a small enough increment then starts next
 * to equilibrium, as it does for the displacement alone.  Measured (t/R
 * 0.001, Eco/Esu 4, stick, δ = 10 ωc_su, the coating's τc four times the
 * substrate's shear yield): with the whole reading in every try the
 * residual at the start of an increment tended to 0.81 of the reaction as
 * Δux -> 0, Newton cycled between slip / plastic states and the ramp
 * failed after 10 halvings at ux = 5.85 ωc; now it reaches inception
 * (μs 0.938, 41 s).  Runs without cut-backs keep lam = 1 and their bits
 * (docs/design.md §4.2). */
static stc_status try_ux(asp_solver *s, ramp *r, double ux, double lam)
{
    asp_shear *sh = s->sh;
    /* lam = 1 is only the first try after an accept, which left carea at
     * the reading itself; a cut try overwrites it, so blend from the copies */
    if (lam < 1.0)
        for (int k = 0; k < s->ncand; k++)
            sh->carea[k] = sh->carea_prev[k] + lam * (sh->carea_tgt[k] - sh->carea_prev[k]);
    memcpy(r->cs0, s->cs, (size_t)s->ncand);
    memcpy(r->cst0, s->cstick, (size_t)s->ncand * 2 * sizeof *r->cst0);
    sh->ux = ux;
    sh->fric_frozen = 1;
    sh->fric_evals = sh->nhold = 0;
    memset(sh->cflip, 0, (size_t)s->ncand);
    memset(sh->chold, 0, (size_t)s->ncand);
    /* predictor: the last accepted increment scaled to this Δux
     * (docs/design.md §4.3).  Without it the increment starts from
     * u_conv, whose trial state at every plastic Gauss point lies on the
     * yield surface (elastic tangent there) and whose stuck nodes are
     * frozen: the first iterate is an elastic predictor, PCG on the last
     * (plastic) factor fails and the next iterate releases too many
     * nodes at once, which then re-stick one per iteration.  Measured on
     * the WSP sphere, level 0: 6 ωc 651 -> 88 Newton iterations,
     * 249 -> 19 factorizations, 8 -> 0 cut-backs; 24 ωc 864 -> 101 and
     * 367 -> 29; 12 ωc 237 -> 78 and 67 -> 21 (μs within 1.4 %). */
    double pred = sh->ux_dlast > 0.0 ? (ux - sh->ux_conv) / sh->ux_dlast : 0.0;
    stc_status st = STC_OK;
    for (int pass = 0;; pass++) {
        asp_nstat ns = {0, 0, 0, ASP_OUTCOME_NONE};
        st = asp_newton_increment(s, s->delta, pred, &ns); /* Δδ = 0 */
        r->res->newton_iterations += ns.iters, r->res->factorizations += ns.facts;
        s->pt.active_set_passes += ns.passes;
        int flipped = st == STC_OK && sh->nhold > 0 ? held_flip(s) : 0;
        if (!flipped) break;
        if (pass + 1 >= HOLD_PASSES) {
            st = STC_FAIL(STC_ENOCONV, "stick/slip cycling at %d contact nodes: held in a state, "
                          "%d still in the wrong one after %d solves", sh->nhold, flipped,
                          HOLD_PASSES);
            break;
        }
        restore_states(s, r); /* solve the try again with those nodes flipped */
        sh->fric_frozen = 1;
        r->res->hold_passes++;
    }
    if (st == STC_OK) {
        r->res->held_nodes += sh->nhold;
        return STC_OK;
    }
    memcpy(s->u, s->u_conv, (size_t)s->ndof * sizeof *s->u);
    restore_states(s, r);
    sh->ux = sh->ux_conv;
    s->k_fresh = 0;
    return st;
}

/* Accept the increment: commit, measure, feed the detector and the caller. */
static stc_status accept(asp_solver *s, const asp_shear_options *o, asp_slide *det,
                         asp_shear_fn cb, void *ctx, ramp *r, int *stop)
{
    asp_shear *sh = s->sh;
    asp_shear_point pt;
    int idx = r->npt;
    commit_shear(s);
    measure(s, &pt);
    if (idx == 0) r->p_m = pt.P / pt.A;
    memcpy(sh->carea_prev, sh->carea, (size_t)s->ncand * sizeof *sh->carea); /* see try_ux */
    if (o->junction == ASP_JUNCTION_NODES) new_node_areas(s, r->p_m); /* for the next increment */
    else STC_CALL(foot_areas(s));
    memcpy(sh->carea_tgt, sh->carea, (size_t)s->ncand * sizeof *sh->carea);
    if (r->npt == r->cap) {
        int cap = r->cap ? 2 * r->cap : 64;
        asp_shear_point *p = realloc(r->pts, (size_t)cap * sizeof *p);
        STC_CHECK(p, STC_ENOMEM, "shear: out of memory");
        r->pts = p, r->cap = cap;
    }
    r->pts[r->npt++] = pt;
    if (det) asp_slide_push(det, pt.ux, pt.Q, pt.P, pt.limit_frac, pt.n_contact);
    if (o->keep_fields)
        STC_CALL(snap_update(s, &pt, sh->fric.tau_c, idx,
                             o->criterion == ASP_SHEAR_CRIT_STIFFNESS));
    if (cb && cb(ctx, &pt)) *stop = 1;
    return STC_OK;
}

static stc_status setup_ramp(asp_solver *s, const asp_shear_options *o, asp_shear_result *res,
                             asp_slide **det)
{
    stc_material lay;
    double tau_c = tau_c_default(s, o->tau_c, &lay);
    res->tau_c = tau_c;
    res->a0 = s->pt.a;
    res->P0 = s->pt.P;
    STC_CALL(alloc_shear(s));
    asp_shear *sh = s->sh;
    STC_CALL(asp_fric_law_init(&sh->fric, tau_c, lay.E, lay.nu, s->h, o->kappa));
    for (int i = 0; i < 3; i++) sh->foot[i] = s->pt.a;
    STC_CALL(asp_foot_init(&sh->fp, s, s->pt.a, o->foot_rows));
    for (int k = 0; k < s->ncand; k++) sh->cnew[k] = s->cs[k] == ASP_CS_OPEN;
    STC_CALL(full_areas(s));
    STC_CALL(node_areas(s, sh->foot));
    initial_slip(s);
    sh->hooks = (asp_hooks){sh, springs, touch, 1, o->hold_stalled ? stalled : NULL};
    s->hooks = &sh->hooks;
    s->opt.no_separation = 1; /* thesis §3.2.3.3: the contact stays closed */
    for (int k = 0; k < 2; k++) s->mat[k].map = o->return_map;
    sh->ux = sh->ux_conv = 0.0;
    s->k_fresh = 0;
    asp_slide_params sp;
    asp_slide_params_default(&sp);
    sp.criterion = o->criterion == ASP_SHEAR_CRIT_STIFFNESS ? ASP_SLIDE_STIFFNESS : ASP_SLIDE_SHEAR;
    sp.alpha = o->alpha;
    sp.max_increments = o->max_increments;
    sp.bend /= o->ramp_refine;
    sp.du_max_frac /= o->ramp_refine;
    /* shear criterion: inception when the whole contact is at its shear
     * limit (slipping, or stuck and saturated: mark_saturated) and stays there
     * over the confirmation increments while the tangential stiffness is
     * below half the initial one; Q_max is the largest Q up to that point
     * (thesis §4.1.3: "the related force at this moment").  Requiring Q to
     * be flat (full_tol 0.01) never ends the ramp past ~3 ωc, where Q keeps
     * rising at KT/KT_1 ≈ 0.05-0.1 as P relaxes and the contact grows. */
    sp.full_tol = 0.5;
    asp_slide_setup su = {lay.E / (2.0 * (1.0 + lay.nu)), lay.nu, s->pt.a, tau_c, s->pt.P};
    sh->rate_sat = 0.1 * tau_c / asp_slide_ux_elastic(&su);
    return asp_slide_create(&sp, &su, det);
}

static void fill_result(const asp_solver *s, const ramp *r, asp_slide *det, double foot_rows,
                        asp_shear_result *res)
{
    asp_slide_result sr;
    asp_slide_get(det, &sr);
    res->Q_max = sr.Q_max;
    res->ux_slide = sr.ux;
    res->P_slide = sr.P;
    res->mu_s = sr.mu_s;
    res->mu_s_err =
        asp_mu_s_err_single(foot_rows, s->edge_refine, s->delta / s->omega_est) * sr.mu_s;
    res->mu_s_preload = sr.mu_s_preload;
    res->slip_frac = sr.slip_frac;
    res->KT_after = sr.KT_after;
    res->q_rising = sr.q_rising;
    res->mu_s_ux_slope = sr.mu_s_ux_slope;
    res->index = sr.index;
    res->increments = sr.increments;
    res->converged = sr.state == ASP_SLIDE_INCEPTION;
    res->outcome = sr.outcome;
    snprintf(res->reason, sizeof res->reason, "%s", sr.reason);
    int i = sr.index >= 0 && sr.index < r->npt ? sr.index : r->npt - 1;
    res->A_stick = i >= 0 ? r->pts[i].A_stick : NAN;
}

stc_status asp_solver_shear(asp_solver *s, const asp_shear_options *o, asp_shear_fn cb,
                            void *ctx, asp_shear_result *res)
{
    asp_shear_options def;
    if (!o) asp_shear_options_default(&def), o = &def;
    memset(res, 0, sizeof *res);
    res->criterion = o->criterion;
    res->junction = o->junction;
    res->foot_rows = o->foot_rows;
    snprintf(res->reason, sizeof res->reason, "not started");
    STC_CALL(check_shear(s, o));
    double t0 = omp_get_wtime();
    asp_slide *det = NULL;
    ramp r = {res, malloc((size_t)s->ncand), malloc((size_t)s->ncand * 2 * sizeof(double)),
              NULL, 0, 0, 0.0};
    stc_status st = STC_OK;
    asp_outcome why = ASP_OUTCOME_FAILED; /* of a failure */
    int stop = 0;
    STC_CHECK_GOTO(r.cs0 && r.cst0, st, done, STC_ENOMEM, "shear: out of memory");
    STC_CALL_GOTO(setup_ramp(s, o, res, &det), st, done);
    /* ux = 0: release the tangential constraints of a stick step, clip the
     * nodes whose reaction exceeds τc A, re-equilibrate */
    STC_CALL_GOTO(try_ux(s, &r, 0.0, 1.0), st, done);
    STC_CALL_GOTO(accept(s, o, det, cb, ctx, &r, &stop), st, done);
    int cuts = 0;
    double du = asp_slide_next(det), du0 = du;
    while (du > 0.0 && !stop) {
        stc_status t = try_ux(s, &r, s->sh->ux_conv + du, du / du0);
        if (t == STC_OK) {
            STC_CALL_GOTO(accept(s, o, det, cb, ctx, &r, &stop), st, done);
            du = du0 = asp_slide_next(det);
            cuts = 0;
            continue;
        }
        res->cutbacks++;
        if (++cuts > s->opt.max_cutbacks) {
            char msg[512];
            snprintf(msg, sizeof msg, "%s", stc_errmsg());
            if (asp_slide_mechanism(det, msg)) break; /* sliding in the material */
            why = ASP_OUTCOME_CUTBACK_LIMIT;
            st = STC_FAIL(STC_ENOCONV, "shear: %s (%d halvings) reached at ux = %g mm: %s",
                          asp_outcome_str(why), s->opt.max_cutbacks, s->sh->ux_conv, msg);
            goto done;
        }
        du *= 0.5;
    }
    fill_result(s, &r, det, o->foot_rows, res);
    if (stop) {
        why = ASP_OUTCOME_STOPPED;
        st = STC_FAIL(STC_ENOCONV, "shear: %s at ux = %g mm", asp_outcome_str(why), s->sh->ux_conv);
    } else if (!res->converged) {
        why = res->outcome;
        st = STC_FAIL(STC_ENOCONV, "shear: %s", res->reason);
    }
done:
    if (st != STC_OK) { /* what was reached stays in res; the reason says why */
        if (det && r.npt > 0 && !res->increments) fill_result(s, &r, det, o->foot_rows, res);
        res->converged = 0;
        res->outcome = why;
        snprintf(res->reason, sizeof res->reason, "%s", stc_errmsg());
    }
    res->wall_s = omp_get_wtime() - t0;
    asp_slide_destroy(&det);
    free(r.cs0), free(r.cst0), free(r.pts);
    return st;
}
