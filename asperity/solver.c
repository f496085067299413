/* Set-up of the implicit static FE solver of a coated sphere pressed by a
 * rigid flat: options, mesh sizing, create / destroy, info.
 *
 * Structure (PETSc/SUNDIALS style): create() sizes and builds the mesh
 * for the largest δ to be reached, has the fixed CSC sparsity pattern and
 * the element → matrix scatter map built (assemble.c) and the pattern
 * analysed ONCE by the linear solver (linsolve.c); every Newton iteration
 * (newton.c) only refills the values, factorizes numerically and solves.
 * One job per file, each calling the ones below it and none above:
 *   placements.c  the node-placement ensemble of ramps
 *   load.c        load stepping in δ, the tail, load control to a P
 *   shear.c       the tangential ramp (its state: struct asp_shear)
 *   newton.c      one increment: active-set passes, Newton, line search
 *   asp_contact.c candidates, active set, Dirichlet values, results
 *   assemble.c    pattern, scatter maps, colours, elastic K, element loop
 *   linsolve.c    CHOLMOD, direct and Krylov steps (precond.c: kernels)
 *   solver.c      options, mesh sizing, create / destroy, info
 * The ramp's stick-law springs reach the element loop through the solver's
 * hooks (solver_impl.h), not by a call back into shear.c.
 *
 * Cost: the element loop and the factorization are each ~1-5 ms on an
 * axisymmetric mesh, so the work is the NUMBER of evaluations; small
 * axisymmetric systems run on one thread (see create).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"
#include "stiction/formulas.h"


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
    o->edge_refine = 0;
    o->edge_a0 = 0.0;
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
    STC_CHECK(o->edge_refine >= 0 && o->edge_refine <= 2, STC_EINVAL,
              "edge refinements = %d: must be in [0, 2]", o->edge_refine);
    STC_CHECK(o->edge_a0 >= 0.0 && isfinite(o->edge_a0), STC_EINVAL,
              "edge a0 = %g mm: must be >= 0", o->edge_a0);
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

stc_status asp_omega_yield(const stc_params *p, double *omega_y)
{
    STC_CHECK(p && omega_y, STC_EINVAL, "asp_omega_yield: NULL argument");
    stc_material su, co;
    stc_critical c, cc;
    stc_params_materials(p, &su, &co);
    STC_CALL(stc_critical_eval(&su, p->R, &c));
    STC_CALL(stc_critical_eval(&co, p->R, &cc));
    *omega_y = fmin(c.omega_c, stc_params_t(p) > 0.0 ? cc.omega_c : c.omega_c);
    return STC_OK;
}

/* Contact sizes for a mesh loaded up to delta_max: the layers' material
 * laws, R', a_max (the largest contact, with a safety factor), the
 * first-yield estimate and a_min (the smallest contact a load curve past
 * yield resolves). */
static stc_status size_contact(asp_solver *s, double delta_max)
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
    STC_CALL(asp_omega_yield(&s->par, &s->omega_est));
    double dres = 0.8 * s->omega_est;
    s->a_min = delta_max > 2.0 * dres ? 1.1 * sqrt(s->Rp * dres) : s->a_max;
    return STC_OK;
}

/* The mesh for the sizes of size_contact: its level, the graded or uniform
 * 3D core, the axisymmetric surface layers; the solver's dimensions. */
static stc_status make_mesh(asp_solver *s, double delta_max)
{
    STC_CALL(size_contact(s, delta_max));
    double t = stc_params_t(&s->par);
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
        if (s->opt.edge_refine > 0 && s->opt.edge_a0 > 0.0 && !graded) {
            STC_CALL(asp_mesh_refine_band(&s->mesh, s->Rp, t > 0.0 ? s->par.R : 0.0,
                                          s->a_max / n, s->opt.edge_a0, s->opt.edge_refine));
            s->edge_refine = s->opt.edge_refine;
        }
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

/* The linear solver on the pattern of the mesh (linsolve.c); serial:
 * factorize on one thread (see asp_solver_create). */
static stc_status make_linsolve(asp_solver *s, int serial)
{
    int *Kp = NULL, *Ki = NULL;
    STC_CALL(asp_asm_pattern(s, &Kp, &Ki));
    asp_ls_options lo = {s->opt.krylov, s->opt.krylov_max, s->nthr, serial, s->dim == 3};
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
    /* one thread asked for: the factorization too (CHOLMOD's and OpenBLAS's
     * threads would take a second core from a run beside it) */
    STC_CALL_GOTO(make_linsolve(s, small || s->nthr == 1), st, fail);
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
    free(s->ubc), free(s->cvec), free(s->hd), free(s->hP), free(s->hA);
    free(s->st_old), free(s->st_new), free(s->fixed), free(s->cand), free(s->cs), free(s->cstick);
    asp_shear_destroy(&s->sh);
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
    info->edge_refine = s->edge_refine;
    info->edge_a0 = s->edge_refine > 0 ? s->opt.edge_a0 : 0.0;
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
