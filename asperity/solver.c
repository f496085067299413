/* Implicit static FE solver of a coated sphere pressed by a rigid flat.
 *
 * Structure (PETSc/SUNDIALS style): create() meshes, builds the fixed CSC
 * sparsity pattern (upper triangle) and the element → matrix scatter map,
 * and runs cholmod_analyze ONCE; every Newton iteration only refills the
 * values, factorizes numerically and solves.  Boundary conditions and
 * contact are imposed WITHOUT changing the pattern: a constrained DOF keeps
 * its prescribed value and gets an identity row/column in K (values
 * only), so the symbolic analysis stays valid.  A prescribed value that
 * changes (the flat advancing, a node entering the contact) is not written
 * into u directly: the Newton step carries it (du = ubc - u on the fixed
 * DOFs, -K_fc du_c on the free ones), so the neighbours of a node that
 * enters follow it instead of a ring of elements being strained and
 * turned plastic (this halved the element evaluations of a load curve).
 *
 * Contact: node-to-analytic-plane, exact (zero penetration for an active
 * node) by an active set iterated to consistency inside each increment:
 * an active node has u_z prescribed onto the flat; its reaction is the
 * contact force; a node whose reaction turns tensile is released (unless
 * no_separation), a node that penetrates is added.  Stick: tangential DOFs
 * of a node are frozen at their value when it touched.
 *
 * Loading: increments in δ; while all is elastic under slip they jump to
 * the predicted first yield and just past it; past yield at least four per
 * surface node entering the contact (so the sawtooth of P(δ) is sampled
 * evenly for asp_solver_P_smooth), stick at most one element of contact
 * growth; grown after easy convergence and halved on failure (cut-back).
 * Predictor: the last converged increment, scaled; nodes the predicted
 * surface pushes through the flat are all made active before the first
 * solve.  Every failure ends with a reason in the message.
 *
 * Tangent: under the midpoint return (j2.c) the consistent tangent is not
 * symmetric.  K holds an SPD approximation of it (factorized: the
 * pattern, the analysis and CHOLMOD's LLᵀ stay), Kd and Kk the rest
 * (symmetric, skew); Newton stays quadratic through corrections / GMRES
 * against K + Kd + Kk (skew_correct, gmres).
 *
 * Cost: the element loop and the factorization are each ~1-5 ms on an
 * axisymmetric mesh, so the work is the NUMBER of evaluations; small
 * axisymmetric systems run on one thread (see create).
 * Target for the axisymmetric slip curve to 60 ωc: P_smooth within 0.5 % of
 * the level-3 curve in < 1 s.  The P_smooth error is set by how the
 * node-entry sawtooth is sampled, not monotone in n, and has three parts
 * (curve3d helper, against level 3, n = 6..12):
 *   - a mid-curve (22-38 ωc) bias, the same for every n and ~1/steps per
 *     node (-1.1 | -0.55 | -0.35 | -0.2 % at 2 | 4 | 6 | 8): the radial
 *     return's first-order error in the increment, not the sampling; the
 *     midpoint return (the default, j2.c) leaves -0.15 .. -0.2 %;
 *   - the end point, -0.8 .. +1.9 % at 60 ωc whatever the steps with a
 *     one-sided window: loading on to 1.5 δ_max (asp_solver_load_tail, the
 *     CLI does it for axisymmetric curves) gives it a two-sided one (against
 *     a level-3 curve loaded to 120 ωc, 60 ωc: +0.21 .. +0.32 %);
 *   - 1 ωc, +0.46 .. +0.80 % without the next two measures: first yield,
 *     ~6 elements across that contact (+0.33 % on a mesh sized to it alone)
 *     plus where its edge falls.  The elastic node entries are sampled
 *     before a curve point (asp_options.sample_elastic, step_limit) and the
 *     surface between a_min and a_max is sized to arc length / n (mesh.c).
 * With all of them the max error over the 12 points for n = 6..12 is 0.29
 * 0.46 0.26 0.22 0.23 0.16 0.24 % (1 ωc +0.10 .. +0.26 %), level 0 in 0.6 s:
 * the target is met (docs/design.md §2.3, §3.3).  Tried and not robust:
 * windows 1.5x and 3x, loading 15 % past the end (0.37-0.86 %), dithered
 * steps (0.52-1.37 %).
 * 3D (speed3d): a factorization costs ~50 triangular solves there, so the
 * Newton steps are solved by PCG preconditioned with the last factor
 * (Newton-Krylov, see linear_step); level-0 slip curve to 60 ωc: the same
 * 160 Newton iterations and answers, 160 -> 15 factorizations + 1334 PCG
 * iterations, 91 -> 38 s on the shared machine (CPU 96 -> 37 s).  With 2
 * increments per node entry in 3D (steps_per_node): 31 increments, 126
 * Newton, 15 factorizations, 1113 PCG, 157 element loops, 33 s wall, 32 s
 * CPU (OMP_WAIT_POLICY=passive: 29-31 s, the idle thread stops spinning
 * during the serial PCG).  The level-0 3D curve is 1.2-6 % below the
 * converged one (4 elements across the final contact, no small-δ grading;
 * 1 contact node at 1 ωc: -33 %).
 */
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"
#include "stiction/formulas.h"


/* Increments per surface node entering the contact past yield (step_limit;
 * asp_options.steps_per_node overrides).  Stick: 1 (P at 10 ωc, t/R 0.025,
 * Eco/Esu 2, level 1 moved 0.27 % from 1 to 4 per node, at 1.8x the cost).
 * Slip, 3D: 2.  Level-0 curve 1:60:12 ωc against the axisymmetric level-3
 * P_smooth, steps/node 4 | 2 | 1.5: 49 | 31 | 20 increments, 37 | 31 | 21 s
 * CPU on the shared 2-core machine; max |P_smooth| shift from 4 to 2 is
 * 0.55 % (6 ωc; 0.3-0.4 % elsewhere), to 1.5 2.1 %, against a level-0
 * discretization error of -1.2 % (60 ωc) to -6 % (6 ωc) (curve3d helper). */
#define ASP_STEPS_PER_NODE 4.0
#define ASP_STEPS_PER_NODE_3D 2.0
#define ASP_STEPS_PER_NODE_STICK 1.0

/* Below this size an axisymmetric model runs on one thread (see create). */
enum { ASP_SERIAL_MAX_DOF = 40000 };

void asp_options_default(asp_options *o)
{
    o->geom = ASP_GEOM_AUTO;
    o->contact = ASP_CONTACT_SLIP;
    o->no_separation = 0;
    o->mesh_level = ASP_MESH_DEFAULT;
    o->elements_per_contact = 0.0;
    o->a_safety = 0.0;
    o->rtol = 1e-8;
    o->utol = 1e-6;
    o->max_newton = 30;
    o->newton_reuse = 1;
    o->krylov = ASP_KRYLOV_AUTO;
    o->krylov_max = 50;
    o->steps_per_node = 0.0;
    o->return_map = ASP_RETURN_MIDPOINT;
    o->max_active_set = 40;
    o->max_cutbacks = 10;
    o->threads = 0;
    o->surface_layers = -1;
    o->shell_coarsen = -1;
    o->grade_3d = 0;
    o->sample_elastic = 0;
}

static stc_status check_options(const asp_options *o)
{
    STC_CHECK(o->mesh_level >= ASP_MESH_FINE && o->mesh_level <= 6, STC_EINVAL,
              "mesh level = %d: must be in [0, 6], or %d (default) / %d (fine) for the "
              "model's own levels", o->mesh_level, ASP_MESH_DEFAULT, ASP_MESH_FINE);
    STC_CHECK(o->elements_per_contact == 0.0 ||
                  (o->elements_per_contact >= 3.0 && o->elements_per_contact <= 384.0),
              STC_EINVAL, "elements per contact = %g: must be 0 (from the level) or in [3, 384]",
              o->elements_per_contact);
    STC_CHECK(o->grade_3d == 0 || o->grade_3d == 1, STC_EINVAL,
              "grade-3d = %d: must be 0 or 1", o->grade_3d);
    STC_CHECK(o->sample_elastic == 0 || o->sample_elastic == 1, STC_EINVAL,
              "sample-elastic = %d: must be 0 or 1", o->sample_elastic);
    STC_CHECK(o->shell_coarsen >= -1 && o->shell_coarsen <= 2, STC_EINVAL,
              "shell coarsenings = %d: must be -1 (default) or in [0, 2]", o->shell_coarsen);
    STC_CHECK(o->surface_layers >= -1 && o->surface_layers <= ASP_MESH_MAX_SURFACE_LAYERS,
              STC_EINVAL, "surface layers = %d: must be -1 (auto) or in [0, %d]",
              o->surface_layers, ASP_MESH_MAX_SURFACE_LAYERS);
    STC_CHECK(o->surface_layers <= 0 || o->geom != ASP_GEOM_3D, STC_EINVAL,
              "surface layers = %d: axisymmetric model only (3D: -1 or 0)", o->surface_layers);
    STC_CHECK(o->a_safety == 0.0 || (o->a_safety >= 1.0 && o->a_safety <= 5.0), STC_EINVAL,
              "a-safety = %g: must be 0 (auto) or in [1, 5]", o->a_safety);
    STC_CHECK(o->steps_per_node == 0.0 ||
                  (o->steps_per_node >= 0.5 && o->steps_per_node <= 16.0),
              STC_EINVAL, "steps per node = %g: must be 0 (automatic) or in [0.5, 16]",
              o->steps_per_node);
    STC_CHECK(o->rtol > 0.0 && o->rtol < 1e-2, STC_EINVAL, "rtol = %g: must be in (0, 1e-2)",
              o->rtol);
    STC_CHECK(o->utol > 0.0 && o->utol < 1e-2, STC_EINVAL, "utol = %g: must be in (0, 1e-2)",
              o->utol);
    STC_CHECK(o->krylov >= ASP_KRYLOV_OFF && o->krylov <= ASP_KRYLOV_ON, STC_EINVAL,
              "krylov = %d: must be 0 (off), 1 (auto) or 2 (on)", (int)o->krylov);
    STC_CHECK(o->return_map >= ASP_RETURN_MIDPOINT && o->return_map <= ASP_RETURN_EXACT,
              STC_EINVAL, "return map = %d: must be 0 (midpoint), 1 (radial) or 2 (exact)",
              (int)o->return_map);
    STC_CHECK(o->krylov_max >= 1 && o->krylov_max <= 1000, STC_EINVAL,
              "krylov max = %d: must be in [1, 1000]", o->krylov_max);
    STC_CHECK(o->max_newton >= 2 && o->newton_reuse >= 1 && o->max_active_set >= 2 &&
                  o->max_cutbacks >= 0,
              STC_EINVAL, "Newton limits: max-newton >= 2, newton-reuse >= 1, "
                          "max-active-set >= 2, max-cutbacks >= 0");
    return STC_OK;
}

/* ---- create / destroy ---------------------------------------------------- */

static stc_status alloc_state(asp_solver *s)
{
    size_t n = (size_t)s->ndof, nq = (size_t)s->mesh->nelem * s->nqp;
    s->u = calloc(n, sizeof *s->u), s->u_conv = calloc(n, sizeof *s->u);
    s->du_last = calloc(n, sizeof *s->u), s->fint = calloc(n, sizeof *s->u);
    s->sig = calloc(6 * nq, sizeof *s->sig);
    s->st_old = calloc(nq, sizeof *s->st_old), s->st_new = calloc(nq, sizeof *s->st_new);
    s->fixed = calloc(n, 1);
    s->ubc = calloc(n, sizeof *s->u), s->cvec = calloc(n, sizeof *s->u);
    s->du_scr = malloc(n * sizeof *s->u), s->u0_scr = malloc(n * sizeof *s->u);
    STC_CHECK(s->u && s->u_conv && s->du_last && s->fint && s->sig && s->st_old && s->st_new &&
                  s->fixed && s->ubc && s->cvec && s->du_scr && s->u0_scr,
              STC_ENOMEM, "solver: out of memory for %zu DOFs", n);
    return STC_OK;
}

static stc_status make_mesh(asp_solver *s, double delta_max)
{
    stc_material su, co;
    stc_critical c;
    stc_params_materials(&s->par, &su, &co);
    asp_j2_init(&s->mat[ASP_REGION_SUBSTRATE], &su);
    asp_j2_init(&s->mat[ASP_REGION_COATING], &co);
    for (int k = 0; k < 2; k++) s->mat[k].map = s->opt.return_map;
    double t = stc_params_t(&s->par);
    s->Rp = s->par.R + t;
    STC_CALL(stc_critical_eval(&su, s->par.R, &c));
    /* elastic: a = sqrt(R δ) (Hertz); well past yield the contact grows
     * towards the truncated cap, a² -> 2 R δ (Kogut & Etsion 2002, fig. 6) */
    double safety = s->opt.a_safety > 0.0 ? s->opt.a_safety
                    : delta_max <= 2.0 * c.omega_c ? 1.1 : 1.45;
    s->a_max = safety * sqrt(s->Rp * delta_max);
    /* a load curve past first yield also resolves the contact at yield
     * (0.8 of the smaller layer's ωc; for a coating in stick δc1 ≈ ωc_co) */
    stc_critical cc;
    STC_CALL(stc_critical_eval(&co, s->par.R, &cc));
    s->omega_est = fmin(c.omega_c, t > 0.0 ? cc.omega_c : c.omega_c);
    double dres = 0.8 * s->omega_est;
    s->a_min = delta_max > 2.0 * dres ? 1.1 * sqrt(s->Rp * dres) : s->a_max;
    /* default level: 1 axisymmetric, 0 in 3D.  A 3D level costs ~5-10x the
     * one below (3D Hertz point level 0: <= 0.2 %); the μs of a
     * combined-loading run moved by <= 1 % from 6 to 8.5 elements across
     * a_max (WSP 3 and 6 ωc; t/R 0.025, Eco/Esu 2, δ = 1 and 30 ωc_su) and
     * by +3.3 % / +0.6 % / +3.0 % to level 1 (WSP 3 / 6 ωc, coated δ = 30;
     * 12-36 min a point);
     * docs/design.md §2.2, §2.6 */
    int base = s->opt.geom == ASP_GEOM_3D ? 0 : 1;
    s->level = s->opt.mesh_level >= 0 ? s->opt.mesh_level
                                      : base + (ASP_MESH_DEFAULT - s->opt.mesh_level);
    /* The graded 3D core's levels: 4 2^level elements across every contact
     * and no coarsened shells, where the uniform core has 6 2^level across
     * a_max.  Slip curve 1:60:12 ωc against the axisymmetric level 3 (two
     * threads): graded n = 4 without coarsening 0.50 % in 13.7 s (0.44 to
     * 0.76 % as the node placement shifts), graded n = 6 with it 0.57 % in
     * 54 s, uniform level 0 -33 % at 1 ωc and -6.2 % at 6.4 ωc in 6.5 s
     * (docs/design.md §2.4) */
    int graded = s->opt.geom == ASP_GEOM_3D && s->opt.grade_3d && s->a_min < s->a_max &&
                 t <= 0.8 * s->a_min;
    int sc = (graded && s->opt.shell_coarsen < 0) ? 0 : s->opt.shell_coarsen;
    /* asp_mesh_spec.coarsen: 0 = default, < 0 = none */
    int crs = sc < 0 ? 0 : sc == 0 ? -1 : sc;
    double n = s->opt.elements_per_contact > 0.0 ? s->opt.elements_per_contact
                                                 : (graded ? 4.0 : 6.0) * (1 << s->level);
    asp_mesh_spec spec = {s->par.R, t, s->a_max, s->level, graded ? n : s->opt.elements_per_contact,
                          crs, 0.0};
    if (s->opt.geom == ASP_GEOM_3D) {
        if (graded) {
            spec.a_min = s->a_min;
            s->graded = 1;
        } else {
            s->a_min = s->a_max; /* the 3D mesh is uniform over the a_max zone */
        }
        STC_CALL(asp_mesh_half3d(&spec, &s->mesh));
    } else {
        STC_CALL(asp_mesh_axisym_nl(&spec, s->a_min, n, asp_surface_layers(&s->opt), &s->mesh));
    }
    STC_CALL(asp_mesh_quality(s->mesh, &s->quality));
    s->dim = s->mesh->dim, s->nen = s->mesh->nen;
    s->nqp = s->dim == 2 ? ASP_QUAD4_NQP : ASP_HEX8_NQP;
    s->nde = s->dim * s->nen;
    s->ndof = s->dim * s->mesh->nnode;
    s->n_contact = n;
    s->h = s->a_max / n; /* mesh.c: h = a_max / n, n = 6 2^level by default */
    s->h0 = s->a_min / n;
    return STC_OK;
}

/* The linear solver on the pattern of the mesh (linsolve.c); small:
 * factorize on one thread (see asp_solver_create). */
static stc_status make_linsolve(asp_solver *s, int small)
{
    int *Kp = NULL, *Ki = NULL;
    STC_CALL(asp_asm_pattern(s, &Kp, &Ki));
    asp_ls_options lo = {s->opt.krylov, s->opt.krylov_max, s->nthr, small, s->dim == 3};
    stc_status st = asp_ls_create(s->ndof, Kp, Ki, s->fixed, &lo, &s->ls);
    free(Kp), free(Ki);
    return st;
}

stc_status asp_solver_create(const stc_params *p, const asp_options *o, double delta_max,
                             asp_solver **out)
{
    *out = NULL;
    STC_CALL(stc_params_validate(p));
    asp_solver *s = calloc(1, sizeof *s);
    STC_CHECK(s, STC_ENOMEM, "solver: out of memory");
    s->par = *p;
    if (o) s->opt = *o;
    else asp_options_default(&s->opt);
    stc_status st;
    STC_CALL_GOTO(check_options(&s->opt), st, fail);
    STC_CHECK_GOTO(delta_max > 0.0 && delta_max <= 0.01 * p->R, st, fail, STC_EINVAL,
                   "delta = %g mm: must be in (0, 0.01 R] (small-strain model)", delta_max);
    s->delta_max = delta_max;
    STC_CALL_GOTO(make_mesh(s, delta_max), st, fail);
    STC_CALL_GOTO(asp_contact_setup(s), st, fail);
    STC_CALL_GOTO(alloc_state(s), st, fail);
    /* Threads: measured on the 4.6k-DOF axisymmetric level-1 mesh, a load
     * curve to 60 ωc took 2.6 s with CHOLMOD simplicial, 1.7 s supernodal
     * run serially, 3.6 s with a 2-thread assembly and 5.2 s (4.6 s of it
     * system time) with CHOLMOD's and OpenBLAS's threads; METIS ordering
     * did not reduce the fill (2.1e5 nonzeros in L either way). */
    int small = s->dim == 2 && s->ndof < ASP_SERIAL_MAX_DOF;
    s->nthr = s->opt.threads > 0 ? s->opt.threads : small ? 1 : omp_get_max_threads();
    STC_CALL_GOTO(asp_asm_create(s), st, fail);
    STC_CALL_GOTO(make_linsolve(s, small), st, fail);
    STC_CALL_GOTO(asp_asm_maps(s), st, fail);
    for (int k = 0; k < 2; k++) s->yt[k].y.reached = 0;
    *out = s;
    return STC_OK;
fail:
    asp_solver_destroy(&s);
    return st;
}

void asp_solver_destroy(asp_solver **sp)
{
    if (!sp || !*sp) return;
    asp_solver *s = *sp;
    asp_ls_destroy(&s->ls);
    free(s->du_scr), free(s->u0_scr);
    asp_mesh_destroy(&s->mesh);
    asp_asm_destroy(&s->as);
    free(s->u), free(s->u_conv), free(s->du_last), free(s->fint), free(s->sig);
    free(s->ubc), free(s->cvec), free(s->hd), free(s->hP);
    free(s->st_old), free(s->st_new), free(s->fixed), free(s->cand), free(s->cs), free(s->cstick);
    asp_shear_release(s);
    free(s);
    *sp = NULL;
}

void asp_solver_info(const asp_solver *s, asp_info *info)
{
    info->dim = s->dim;
    info->nodes = s->mesh->nnode;
    info->elements = s->mesh->nelem;
    info->dofs = s->ndof - s->dim * s->mesh->nhang; /* hanging nodes are not unknowns */
    info->mesh_quality = s->quality;
    info->h_contact = s->h;
    info->a_max = s->a_max;
    info->elements_per_contact = s->n_contact;
    info->a_min = s->a_min;
    asp_ls_stats ls;
    int n_asm;
    asp_ls_get_stats(s->ls, &ls);
    asp_asm_work(s->as, &n_asm, &info->time_assembly_s);
    info->time_factorize_s = ls.time_factorize_s;
    info->time_pcg_s = ls.time_krylov_s;
}

void asp_solver_yield(const asp_solver *s, int layer, asp_yield *y)
{
    *y = s->yt[layer ? 1 : 0].y;
}

/* ---- load stepping ------------------------------------------------------- */

/* Increment that lands just below (σvm/Y < 0.97) or just past the first
 * yield of layer k predicted by its elastic trend σvm ∝ δ^m: m = ½ exactly
 * for a homogeneous elastic sphere (Hertz; Johnson, Contact Mechanics,
 * 1985, §4.2), otherwise the local exponent of the last two elastic
 * increments.  Brackets the yield within about 2.5 % in two increments
 * instead of creeping up on it. */
static double yield_aim(const asp_solver *s, int k)
{
    const asp_ytrack *t = &s->yt[k];
    double f = s->pt.vm_over_Y[k];
    if (t->y.reached || f <= 0.0 || s->delta <= 0.0) return INFINITY;
    double m = 0.5;
    if (t->n == 2 && t->f[1] > t->f[0] && t->d[1] > t->d[0])
        m = fmin(fmax(log(t->f[1] / t->f[0]) / log(t->d[1] / t->d[0]), 0.25), 1.0);
    double dy = s->delta * pow(1.0 / f, 1.0 / m);
    if (f < 0.97) return 0.985 * dy - s->delta;
    return fmax(1.01 * dy - s->delta, 0.005 * s->delta);
}

/* Largest increment from δ.  Elastic frictionless contact is path
 * independent, so while everything is elastic it jumps (the active set does
 * the rest): first to half the closed-form first-yield estimate, then to the
 * predicted yield (yield_aim).  Otherwise the contact may grow by about one
 * surface element per increment under stick (a node's stick position is
 * taken when it touches) and three under slip. */
static double steps_per_node(const asp_solver *s)
{
    if (s->opt.steps_per_node > 0.0) return s->opt.steps_per_node;
    if (s->opt.contact == ASP_CONTACT_STICK) return ASP_STEPS_PER_NODE_STICK;
    return s->dim == 3 ? ASP_STEPS_PER_NODE_3D : ASP_STEPS_PER_NODE;
}

/* Element size at the contact edge of radius a: two zones (axisymmetric),
 * or growing with the distance (graded 3D shells). */
static double edge_size(const asp_solver *s, double a)
{
    return s->graded ? fmin(fmax(a * s->h / s->a_max, s->h0), s->h) : a < s->a_min ? s->h0 : s->h;
}

/* target: the δ asp_solver_load is loading to. */
static double step_limit(const asp_solver *s, double target, int *aimed)
{
    int elastic = s->pt.plastic_points == 0;
    double lim = INFINITY;
    for (int k = 0; k < 2; k++) lim = fmin(lim, yield_aim(s, k));
    *aimed = lim < INFINITY;
    if (s->opt.contact == ASP_CONTACT_SLIP && elastic) {
        /* sample_elastic: from the start of the target's P_smooth window on,
         * steps_per_node increments per node entry (Hertz: a² = R' δ, a node
         * enters every Δδ = 2 a h / R') */
        if (s->delta <= 0.0) {
            double first = 0.5 * s->omega_est;
            return s->opt.sample_elastic ? fmin(first, target / (1.05 * ASP_SMOOTH_W)) : first;
        }
        if (s->opt.sample_elastic) {
            double w0 = target / (1.05 * ASP_SMOOTH_W);
            double a = s->pt.a > 0.0 ? s->pt.a : sqrt(s->Rp * s->delta);
            lim = fmin(lim, s->delta < w0 * (1 - 1e-9)
                                ? w0 - s->delta
                                : 2.0 * a * edge_size(s, a) / (steps_per_node(s) * s->Rp));
        }
        /* at most x4 per step: the trend is unreliable on a few-node contact */
        return fmax(fmin(lim, 3.0 * s->delta), 0.005 * s->delta);
    }
    /* past yield: P(δ) is a sawtooth with one tooth per surface node that
     * enters (asp_contact.c); a node enters every Δδ ≈ a h / R' (a² ∝ R' δ).
     * steps_per_node() increments per tooth sample it evenly for
     * asp_solver_P_smooth (fewer, landing just after the entries where
     * Newton is slow, biased it by -1.5 % on mesh level 0; with 4: within
     * 0.4 % of the finest mesh at level 1) */
    double a = fmin(fmax(s->pt.a, 0.0), sqrt(2.0 * s->Rp * s->delta));
    double hc = edge_size(s, a);
    double spn = steps_per_node(s);
    if (!elastic) lim = fmin(lim, a * hc / (spn * s->Rp));
    /* stick: the contact grows by at most about one surface element */
    if (s->opt.contact == ASP_CONTACT_STICK) {
        double ag = sqrt(2.0 * s->Rp * s->delta);
        lim = fmin(lim, ((ag + hc) * (ag + hc) - ag * ag) / (2.0 * s->Rp));
    }
    return lim;
}

static void commit(asp_solver *s, double delta, const asp_nstat *ns)
{
    size_t nq = (size_t)s->mesh->nelem * s->nqp;
    for (int i = 0; i < s->ndof; i++) s->du_last[i] = s->u[i] - s->u_conv[i];
    memcpy(s->u_conv, s->u, (size_t)s->ndof * sizeof *s->u);
    memcpy(s->st_old, s->st_new, nq * sizeof *s->st_old);
    s->dlast = delta - s->delta;
    s->delta = delta;
    s->pt.increments++;
    s->pt.newton_iterations += ns->iters;
    s->pt.factorizations += ns->facts;
    s->pt.active_set_passes += ns->passes;
    asp_contact_results(s, &s->pt);
    asp_yield_track(s, &s->pt);
    asp_history_push(s, delta, s->pt.P);
}

stc_status asp_solver_load(asp_solver *s, double delta, asp_point *out)
{
    STC_CHECK(delta >= s->delta && delta <= s->delta_max * (1 + 1e-12), STC_EINVAL,
              "delta = %g mm: must be in [%g, %g] (current, meshed maximum)", delta, s->delta,
              s->delta_max);
    unsigned char *cs0 = malloc((size_t)s->ncand);
    double *cst0 = malloc((size_t)s->ncand * 2 * sizeof *cst0);
    if (!cs0 || !cst0) {
        free(cs0), free(cst0);
        return STC_FAIL(STC_ENOMEM, "solver: out of memory");
    }
    double t0 = omp_get_wtime();
    stc_status st = STC_OK;
    int cuts = 0;
    while (s->delta < delta * (1 - 1e-14)) {
        int aimed;
        double lim = step_limit(s, delta, &aimed);
        if (s->step <= 0.0) s->step = lim;
        double dnew = fmin(delta, s->delta + fmin(s->step, lim));
        /* no sliver steps, unless the step brackets a first yield */
        int at_yield = aimed && lim < s->step;
        if (delta - dnew < 0.2 * fmin(s->step, lim) && !at_yield) dnew = delta;
        asp_nstat ns = {0, 0, 0, ASP_OUTCOME_NONE};
        memcpy(cs0, s->cs, (size_t)s->ncand);
        memcpy(cst0, s->cstick, (size_t)s->ncand * 2 * sizeof *cst0);
        /* predictor: the last increment scaled to this Δδ */
        st = asp_newton_increment(s, dnew, s->dlast > 0.0 ? (dnew - s->delta) / s->dlast : 0.0, &ns);
        if (st == STC_OK) {
            commit(s, dnew, &ns);
            /* a step shortened to bracket a yield does not shrink the next */
            if (!at_yield) s->step = ns.iters <= 6 ? 1.5 * s->dlast : s->dlast;
            cuts = 0;
            continue;
        }
        /* cut back: restore the converged state and halve */
        s->pt.newton_iterations += ns.iters;
        s->pt.factorizations += ns.facts;
        s->pt.active_set_passes += ns.passes;
        memcpy(s->u, s->u_conv, (size_t)s->ndof * sizeof *s->u);
        memcpy(s->cs, cs0, (size_t)s->ncand);
        memcpy(s->cstick, cst0, (size_t)s->ncand * 2 * sizeof *cst0);
        s->step = 0.5 * (dnew - s->delta);
        s->pt.cutbacks++;
        if (++cuts > s->opt.max_cutbacks) {
            char why[512];
            snprintf(why, sizeof why, "%s", stc_errmsg());
            st = STC_FAIL(STC_ENOCONV, "%s (%d halvings) reached at δ = %g mm: %s",
                          asp_outcome_str(ASP_OUTCOME_CUTBACK_LIMIT), s->opt.max_cutbacks,
                          s->delta, why);
            break;
        }
        st = STC_OK;
    }
    free(cs0), free(cst0);
    s->pt.wall_s += omp_get_wtime() - t0;
    double t_asm;
    asp_asm_work(s->as, &s->pt.assemblies, &t_asm);
    asp_ls_stats ls;
    asp_ls_get_stats(s->ls, &ls);
    s->pt.krylov_iterations = ls.krylov_iterations;
    if (out) *out = s->pt;
    return st;
}

/* How far asp_solver_load_tail loads past the meshed maximum.  At the end of
 * a curve the P_smooth window (δ/2 .. 2 δ) is one-sided and its estimate
 * takes the phase of the last node-entry tooth.  Measured on the slip curve
 * 1:60:12 ωc, level 0 (n = 6), against level 3 loaded to 120 ωc (two level-3
 * meshes agree within 0.06 %): error at 60 / 54.6 ωc +0.69 / +0.56 % without
 * a tail; with a tail to 1.25 / 1.5 / 1.75 / 2 x: -0.31 / +0.31 / +0.14 /
 * +0.15 % at 60 ωc, 42 -> 46 / 49 / 51 / 54 increments.  1.5 keeps the
 * contact inside the fine zone (a ~ 1.22 a(δ_max) < 1.25 a_max axisymmetric)
 * and the tooth phase averaged (n = 6..12: +0.19 .. +0.35 % at 60 ωc). */
#define ASP_SMOOTH_TAIL 1.5

stc_status asp_solver_load_tail(asp_solver *s, asp_point *out)
{
    double target = fmin(ASP_SMOOTH_TAIL * s->delta_max, 0.01 * s->par.R);
    if (!(target > s->delta)) {
        if (out) *out = s->pt;
        return STC_OK;
    }
    double meshed = s->delta_max;
    s->delta_max = target;
    stc_status st = asp_solver_load(s, target, out);
    s->delta_max = meshed;
    return st;
}
