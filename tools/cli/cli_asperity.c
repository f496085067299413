/* stiction asperity: the FE model of one coated asperity under normal
 * loading (a thin layer over include/stiction/asperity.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "stiction/asperity.h"
#include "stiction/formulas.h"

static const char usage[] =
    "(--delta LIST | --delta-mm LIST | --load X) [--shear]\n"
    "       [sphere, coating, materials] [--contact slip|stick] [--mesh coarse|default|fine]\n"
    "       [--placements K] [--json] [--out DIR]\n"
    "\n"
    "One coated sphere pressed by a rigid flat, by finite elements (the normal step):\n"
    "load P, contact radius a and area A, first yield of the coating (delta_c1) and of\n"
    "the substrate (delta_c2).  With --shear the flat then moves along x, the\n"
    "interference held, until the asperity slides (sliding inception; 3D model):\n"
    "Q_max and the static friction coefficient mu_s = Q_max / P.\n"
    "LIST is a,b,c or start:stop:count, increasing; several values give a load curve\n"
    "in one solver run (normal step only).  P_smooth is the load with the mesh's\n"
    "node-entry sawtooth averaged out.  Small-strain model: delta <= 0.01 R.";

static const cli_opt opts[] = {
    CLI_COATED_SPHERE_SECTIONS,
    CLI_HEADING("Loading"),
    {"delta", "LIST", "interference(s) / omega_c_su, the substrate's critical interference "
                      "(> 0, increasing)"},
    {"delta-mm", "LIST", "interference(s) in mm (> 0, increasing)"},
    {"load", "X", "load control: the normal load P = X Pc_su instead of --delta, then shear "
                  "(implies --shear; with --placements K member 0 finds the interference and "
                  "the others run at it)"},
    {"shear", NULL, "after the normal step to one interference, shear to sliding inception "
                    "(3D model; implied by --load, --criterion, --alpha, --tau-c)"},
    CLI_HEADING("Contact and friction"),
    {"contact", "slip|stick", "contact condition of the normal step: frictionless, or a node "
                              "that touches stops moving tangentially (default slip)"},
    {"no-separation", NULL, "a node in contact never opens"},
    {"criterion", "shear|stiffness",
     "sliding inception: the whole contact at tau_c and Q flat (default; Wu, Shi & "
     "Polycarpou 2012), or the tangential stiffness KT/KT1 <= alpha (Brizmer et al. 2007)"},
    {"alpha", "A", "stiffness criterion ratio KT_i/KT_1 in (0, 1) (default 0.1)"},
    {"tau-c", "MPa", "critical shear stress of the interface (default Y/sqrt(3) of the "
                     "coating, or of the sphere if uncoated)"},
    CLI_HEADING("Accuracy"),
    {"mesh", "LEVEL",
     "coarse (level 0), default, fine (one level finer than the default) or a level 0..6.  "
     "Axisymmetric normal step: default = level 1; a slip curve to 60 omega_c is within "
     "0.29 / 0.24 / 0.07 % of the converged load at level 0 / 1 / 2, in 0.6 / 3 / 19 s.  "
     "3D (--shear, --model 3d): default = level 0; each level costs 5-10x the one below (a "
     "level-1 shear point 12-36 min) and moved mu_s by up to 3 %, less than node placement "
     "does (docs/design.md §2.3, §2.6)"},
    {"placements", "K",
     "--shear: average K meshes whose surface nodes are shifted by 1/K of a node spacing at "
     "the contact edge (node-placement ensemble), K in [1, 8] (default 1).  One level-0 "
     "mesh's mu_s scatters with where its nodes fall by up to 10.1 % (standard deviation; "
     "3.8 % with --foot-rows 0.6); the members' mean and spread are reported, with the "
     "mean's standard error.  Costs K times the CPU time or more (two: 1.9-4.0x one run); "
     "the members run concurrently, "
     "one thread each (docs/design.md §4.5)"},
    {"placements-max", "K",
     "--shear: refine the ensemble while its standard error exceeds --refine-err of mu_s: "
     "twice the placements, halfway between, up to K (0 = none, the default; else "
     "2 x placements..8; from one run when --placements is not given)"},
    {"refine-err", "X", "--shear: the relative standard error that refines, (0, 0.5] "
                        "(default 0.04)"},
    CLI_HEADING("Common options"),
    {"model", "axisym|3d|auto", "geometry of the model (default auto: axisymmetric for the "
                                "normal step, 3D half model with --shear)"},
    {"out", "DIR", "write curve.csv and fields_NNN.{h5,xmf} (ParaView) into DIR (--shear: "
                   "shear.csv and fields_Q0, fields_Q080, fields_Qmax; --placements: "
                   "placements.csv; columns in docs/output-files.md)"},
    {"json", NULL, "print JSON (one object, or an array for a curve)"},
    {"progress-every", "S",
     "--shear, stderr not a terminal (a log, a batch job): a progress line of the ramp at "
     "most every S seconds (default 60; 0: none); on a terminal one line is rewritten in "
     "place at every ramp point"},
    CLI_CONFIG_HELP,
    CLI_HEADING("Expert numerics (defaults: the measured choices of docs/design.md)"),
    {"elements-per-contact", "N",
     "elements across the largest contact radius, overrides --mesh (6 2^level; 4 2^level "
     "across every contact on the graded 3D core); values between levels, e.g. 8 (in "
     "[3, 384]; 3D: the shells follow the level log2(N/6))"},
    {"surface-layers", "N",
     "axisymmetric: split the top element row into N+1 rows halving towards the surface "
     "(N in [0, 6]; default auto = 3 under stick, 0 under slip)"},
    {"shell-coarsen", "N",
     "3D: 2:1 angular coarsenings of the mesh's outer shells (hanging nodes), 0..2 "
     "(default: 1, from 6 a_max on, with --shear; 0 for the normal step alone)"},
    {"edge-refine", "K",
     "--shear: K nested 2:1 refinements of the elements in a band around the preload's "
     "contact edge (placed from the axisymmetric model's contact radius), 0..2 (default 0); "
     "K = 2: one run within 2 % of the converged mu_s at 11 of 16 held cases (the default "
     "mesh: 5), at 4-15x the time; its error estimate is 7 % of mu_s from 3 omega_c on "
     "(the default mesh: 10 %)"},
    {"grade-3d", NULL,
     "3D: core sized to the smallest contact a curve resolves, shells growing with the "
     "distance (4 2^level elements across every contact, no shell coarsening); the default "
     "for a 3D load curve, --grade-3d=no keeps the uniform core sized to the largest"},
    {"steps-per-node", "X",
     "load increments per surface node entering the contact past yield, in [0.5, 16] "
     "(default auto: 4 slip, 2 slip 3D, 1 stick)"},
    {"return-map", "midpoint|radial|exact",
     "plastic integration over an increment: midpoint rule (second order), radial return "
     "(backward Euler, first order) or exact along the increment's strain path "
     "(default midpoint)"},
    {"junction", "footprint|nodes",
     "--shear: reading of the contact's growth: the edge advance from the gaps ahead of it "
     "(footprint, default) or F_z/p_m of the nodes that touch (nodes); the two bracket the "
     "mesh-converged answer (docs/design.md §4.2)"},
    {"foot-rows", "F",
     "--shear, footprint reading: read the edge advance on every row of surface nodes "
     "within F a0 of the axis and average them, F in [0, 0.9] (default 0: the three axis "
     "lines only).  Over eight node placements mu_s scatters by 1.0-3.8 % (standard "
     "deviation) on the rows at F = 0.6 against 2.6-10.1 % on the axis lines, and reads "
     "1.5-4.4 % higher; against the elastic half-space the rows read 0.7-1.6 points more "
     "junction growth, the axis lines -2.3 ... +0.7 (docs/design.md §4.2, §4.5)"},
    {"ramp-return-map", "radial|midpoint|exact",
     "--shear: plastic integration during the ramp (default radial: the midpoint rule, "
     "used in the normal step, can be far off over the ramp's long increments)"},
    {"ramp-refine", "K",
     "--shear: divide the ramp's increment targets by K in [1, 64] (default 1), to check "
     "the ramp's increment convergence: K = 2 moves mu_s by <= 0.2 % in ordinary cases; "
     "more where Q still rises past inception (KT_over_KT1_after_slide; docs/design.md "
     "§4.3, §4.4)"},
    {"newton-reuse", "K", "reuse a factorization for up to K Newton iterations (default 1)"},
    {"krylov", "off|auto|on",
     "solve Newton steps by PCG preconditioned with the last factorization (auto: where a "
     "factorization costs many PCG iterations, i.e. 3D; default auto)"},
    {"krylov-max", "N", "PCG iterations before refactorizing (default 50)"},
    {"threads", "N",
     "OpenMP threads for the element loop and the Krylov solves; 1 runs the factorizations on "
     "one thread too (default: runtime)"},
    {NULL, NULL, NULL},
};

typedef struct {
    double *delta;
    int ndelta, in_mm, json;
    int grade; /* --grade-3d: 0 or 1; -1 not given (asp_options_for_curve decides) */
    char *out;
    asp_options o;
    cli_shear_args sh; /* --shear and its options (cli_asperity_shear.c) */
} aopts;

static stc_status bad(const char *key, const char *value, const char *what)
{
    return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '%s': must be %s", key, value, what);
}

static stc_status set_opt(void *ctx, const char *key, const char *value)
{
    aopts *a = ctx;
    if (!strcmp(key, "delta") || !strcmp(key, "delta-mm")) {
        free(a->delta);
        a->delta = NULL;
        stc_status s = cli_parse_list(key, value, &a->delta, &a->ndelta);
        if (s) return s;
        for (int i = 0; i < a->ndelta; i++)
            if (!(a->delta[i] > 0.0) || (i && a->delta[i] <= a->delta[i - 1]))
                return bad(key, value, "positive and increasing");
        a->in_mm = !strcmp(key, "delta-mm");
    } else if (!strcmp(key, "contact")) {
        if (!strcmp(value, "slip")) a->o.contact = ASP_CONTACT_SLIP;
        else if (!strcmp(value, "stick")) a->o.contact = ASP_CONTACT_STICK;
        else return bad(key, value, "slip or stick");
    } else if (!strcmp(key, "model")) {
        if (!strcmp(value, "auto")) a->o.geom = ASP_GEOM_AUTO;
        else if (!strcmp(value, "axisym")) a->o.geom = ASP_GEOM_AXISYM;
        else if (!strcmp(value, "3d")) a->o.geom = ASP_GEOM_3D;
        else return bad(key, value, "axisym, 3d or auto");
    } else if (!strcmp(key, "mesh")) {
        long l;
        if (!strcmp(value, "coarse")) a->o.mesh_level = 0;
        else if (!strcmp(value, "default")) a->o.mesh_level = ASP_MESH_DEFAULT;
        else if (!strcmp(value, "fine")) a->o.mesh_level = ASP_MESH_FINE;
        else if (stc_parse_long(key, value, &l) == STC_OK && l >= 0 && l <= 6)
            a->o.mesh_level = (int)l;
        else return bad(key, value, "coarse, default, fine or a level in [0, 6]");
    } else if (!strcmp(key, "surface-layers")) {
        long l;
        if (!strcmp(value, "auto")) a->o.surface_layers = -1;
        else if (stc_parse_long(key, value, &l) == STC_OK && l >= 0 && l <= 6)
            a->o.surface_layers = (int)l;
        else return bad(key, value, "auto or an integer in [0, 6]");
    } else if (!strcmp(key, "elements-per-contact")) {
        double v;
        if (stc_parse_double(key, value, &v) != STC_OK || !(v >= 3.0 && v <= 384.0))
            return bad(key, value, "a number in [3, 384]");
        a->o.elements_per_contact = v;
    } else if (!strcmp(key, "grade-3d")) {
        int f;
        stc_status st = cli_parse_flag(key, value, &f);
        if (st) return st;
        a->o.grade_3d = a->grade = f;
    } else if (!strcmp(key, "edge-refine")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 0 || l > 2)
            return bad(key, value, "an integer in [0, 2]");
        a->o.edge_refine = (int)l;
    } else if (!strcmp(key, "shell-coarsen")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 0 || l > 2)
            return bad(key, value, "an integer in [0, 2]");
        a->o.shell_coarsen = (int)l;
    } else if (!strcmp(key, "newton-reuse")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 1 || l > 100)
            return bad(key, value, "an integer in [1, 100]");
        a->o.newton_reuse = (int)l;
    } else if (!strcmp(key, "krylov")) {
        if (!strcmp(value, "off")) a->o.krylov = ASP_KRYLOV_OFF;
        else if (!strcmp(value, "auto")) a->o.krylov = ASP_KRYLOV_AUTO;
        else if (!strcmp(value, "on")) a->o.krylov = ASP_KRYLOV_ON;
        else return bad(key, value, "off, auto or on");
    } else if (!strcmp(key, "krylov-max")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 1 || l > 1000)
            return bad(key, value, "an integer in [1, 1000]");
        a->o.krylov_max = (int)l;
    } else if (!strcmp(key, "return-map")) {
        return cli_parse_return_map(key, value, &a->o.return_map);
    } else if (!strcmp(key, "steps-per-node")) {
        double v;
        if (!strcmp(value, "auto")) a->o.steps_per_node = 0.0;
        else if (stc_parse_double(key, value, &v) == STC_OK && v >= 0.5 && v <= 16.0)
            a->o.steps_per_node = v;
        else return bad(key, value, "auto or a number in [0.5, 16]");
    } else if (!strcmp(key, "threads")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 1 || l > 256)
            return bad(key, value, "an integer in [1, 256]");
        a->o.threads = (int)l;
    } else if (!strcmp(key, "no-separation")) {
        return cli_parse_flag(key, value, &a->o.no_separation);
    } else if (!strcmp(key, "json")) {
        return cli_parse_flag(key, value, &a->json);
    } else if (!strcmp(key, "out")) {
        free(a->out);
        a->out = strdup(value);
        if (!a->out) return stc_error(STC_ENOMEM, __FILE__, __LINE__, "out of memory");
    } else {
        return cli_shear_opt(&a->sh, key, value);
    }
    return STC_OK;
}

static const asp_yield *first_yield(const asp_curve_point *r, int *layer)
{
    const asp_yield *a = &r->yield[0], *b = &r->yield[1];
    *layer = -1;
    if (a->reached && (!b->reached || a->delta <= b->delta)) return *layer = 0, a;
    if (b->reached) return *layer = 1, b;
    return NULL;
}

static void json_row(cli_json *j, const asp_curve_point *r, const stc_critical *c,
                     const asp_info *in, int coated)
{
    int layer;
    const asp_yield *fy = first_yield(r, &layer);
    cj_obj(j, NULL);
    cj_num(j, "delta_mm", r->pt.delta);
    cj_num(j, "delta_over_omega_c_su", r->pt.delta / c->omega_c);
    cj_num(j, "P_N", r->pt.P);
    cj_num(j, "P_over_P_c", r->pt.P / c->P_c);
    if (isfinite(r->P_smooth)) {
        cj_num(j, "P_smooth_N", r->P_smooth);
        cj_num(j, "P_smooth_over_P_c", r->P_smooth / c->P_c);
    } else {
        cj_null(j, "P_smooth_N");
        cj_null(j, "P_smooth_over_P_c");
    }
    cj_num(j, "P_base_N", r->pt.P_base);
    cj_num(j, "A_mm2", r->pt.A);
    cj_num(j, "A_over_A_c", r->pt.A / c->A_c);
    if (isfinite(r->A_smooth)) {
        cj_num(j, "A_smooth_mm2", r->A_smooth);
        cj_num(j, "A_smooth_over_A_c", r->A_smooth / c->A_c);
    } else {
        cj_null(j, "A_smooth_mm2");
        cj_null(j, "A_smooth_over_A_c");
    }
    cj_num(j, "a_mm", r->pt.a);
    cj_int(j, "nodes_in_contact", r->pt.n_contact);
    cj_num(j, "max_penetration_mm", r->pt.max_penetration);
    cj_num(j, "vm_over_Y_substrate", r->pt.vm_over_Y[0]);
    if (coated) cj_num(j, "vm_over_Y_coating", r->pt.vm_over_Y[1]);
    else cj_null(j, "vm_over_Y_coating");
    if (fy) {
        cj_num(j, "first_yield_delta_over_omega_c_su", fy->delta / c->omega_c);
        cj_num(j, "first_yield_P_over_P_c", fy->P / c->P_c);
        cj_str(j, "first_yield_layer", layer ? "coating" : "substrate");
        cj_num(j, "first_yield_r_mm", fy->r);
        cj_num(j, "first_yield_z_mm", fy->z);
    } else {
        cj_null(j, "first_yield_delta_over_omega_c_su");
        cj_null(j, "first_yield_P_over_P_c");
        cj_null(j, "first_yield_layer");
        cj_null(j, "first_yield_r_mm");
        cj_null(j, "first_yield_z_mm");
    }
    if (r->yield[1].reached)
        cj_num(j, "delta_c1_over_omega_c_su", r->yield[1].delta / c->omega_c);
    else cj_null(j, "delta_c1_over_omega_c_su");
    if (r->yield[0].reached)
        cj_num(j, "delta_c2_over_omega_c_su", r->yield[0].delta / c->omega_c);
    else cj_null(j, "delta_c2_over_omega_c_su");
    cj_bool(j, "converged", r->status == STC_OK);
    cj_str(j, "reason", r->status == STC_OK ? "converged" : r->reason);
    cj_int(j, "dofs", in->dofs);
    cj_int(j, "elements", in->elements);
    cj_num(j, "mesh_quality", in->mesh_quality);
    cj_int(j, "increments", r->pt.increments);
    cj_int(j, "newton_iterations", r->pt.newton_iterations);
    cj_int(j, "factorizations", r->pt.factorizations);
    cj_int(j, "krylov_iterations", r->pt.krylov_iterations);
    cj_int(j, "assemblies", r->pt.assemblies);
    cj_int(j, "active_set_passes", r->pt.active_set_passes);
    cj_num(j, "wall_s", r->pt.wall_s);
    cj_num(j, "time_assembly_s", r->time_assembly_s);
    cj_num(j, "time_factorize_s", r->time_factorize_s);
    cj_num(j, "time_pcg_s", r->time_pcg_s);
    cj_end_obj(j);
}

static void print_table(const asp_curve_point *rows, int n, const stc_critical *c,
                        const asp_info *in)
{
    printf("mesh: %d elements, %d DOFs, worst scaled Jacobian %.3f, h = %.3g mm at the "
           "contact (sized for a <= %.4g mm",
           in->elements, in->dofs, in->mesh_quality, in->h_contact, in->a_max);
    if (in->a_min < in->a_max)
        printf("; %.3g elements across every a in [%.4g, %.4g] mm", in->elements_per_contact,
               in->a_min, in->a_max);
    printf(")\n");
    printf("omega_c_su = %.5g mm, P_c_su = %.5g N, A_c_su = %.5g mm^2\n\n", c->omega_c, c->P_c,
           c->A_c);
    printf("%10s %11s %11s %9s %9s %10s %9s %7s %7s %7s %6s %8s\n", "delta/wc", "delta mm",
           "P N", "P/Pc", "Psm/Pc", "a mm", "A/Ac", "vm/Ysu", "vm/Yco", "newton", "incr",
           "wall s");
    for (int i = 0; i < n; i++) {
        const asp_point *p = &rows[i].pt;
        char sm[32]; /* P_smooth: n/a where the increments do not surround the point */
        printf("%10.4g %11.5g %11.5g %9.5g %9s %10.5g %9.5g %7.3f %7.3f %7d %6d %8.3f%s\n",
               p->delta / c->omega_c, p->delta, p->P, p->P / c->P_c,
               cli_num(sm, sizeof sm, "%.5g", rows[i].P_smooth / c->P_c, "n/a"), p->a,
               p->A / c->A_c,
               p->vm_over_Y[0], p->vm_over_Y[1], p->newton_iterations, p->increments, p->wall_s,
               rows[i].status == STC_OK ? "" : "  NOT CONVERGED");
    }
    if (n == 0) return;
    const asp_curve_point *r = &rows[n - 1];
    const char *name[2] = {"substrate (delta_c2)", "coating (delta_c1)"};
    for (int k = 1; k >= 0; k--) {
        const asp_yield *y = &r->yield[k];
        if (y->reached)
            printf("first yield in the %s: delta/wc = %.4g, P/Pc = %.4g at r = %.4g mm, "
                   "z = %.6g mm\n",
                   name[k], y->delta / c->omega_c, y->P / c->P_c, y->r, y->z);
    }
}

static int write_csv(const char *dir, const asp_curve_point *rows, int n, const stc_critical *c)
{
    cli_out o;
    FILE *f = cli_out_open(&o, dir, "curve.csv");
    if (!f) return -1;
    fprintf(f, "delta_mm,delta_over_omega_c_su,P_N,P_over_P_c,P_smooth_N,a_mm,A_mm2,A_over_A_c,"
               "A_smooth_mm2,vm_over_Y_su,vm_over_Y_co,newton_iterations,wall_s\n");
    for (int i = 0; i < n; i++) {
        const asp_point *p = &rows[i].pt;
        char sm[32], am[32];
        fprintf(f, "%.9g,%.9g,%.9g,%.9g,%s,%.9g,%.9g,%.9g,%s,%.6g,%.6g,%d,%.4f\n", p->delta,
                p->delta / c->omega_c, p->P, p->P / c->P_c,
                cli_num(sm, sizeof sm, "%.9g", rows[i].P_smooth, ""), p->a, p->A,
                p->A / c->A_c, cli_num(am, sizeof am, "%.9g", rows[i].A_smooth, ""),
                p->vm_over_Y[0], p->vm_over_Y[1], p->newton_iterations, p->wall_s);
    }
    return cli_out_close(&o);
}

/* --out: the fields at each converged point of the curve. */
typedef struct {
    const char *cmd, *dir;
    int failed;
} fields_ctx;

static void write_point_fields(void *ctx, const asp_solver *sv, int i)
{
    fields_ctx *f = ctx;
    char prefix[4096];
    snprintf(prefix, sizeof prefix, "%s/fields_%03d", f->dir, i);
    stc_status s = asp_solver_write_fields(sv, prefix);
    if (s != STC_OK) cli_fail(f->cmd, s), f->failed = 1;
}

static int run(const char *cmd, const stc_params *p, aopts *a)
{
    stc_material su;
    stc_critical c;
    stc_params_materials(p, &su, NULL);
    stc_status s = stc_critical_eval(&su, p->R, &c);
    if (s) return cli_fail(cmd, s);
    double scale = a->in_mm ? 1.0 : c.omega_c;
    if (a->delta[a->ndelta - 1] * scale > 0.01 * p->R) {
        fprintf(stderr, "stiction %s: delta = %g mm: must be <= 0.01 R = %g mm (small strain)\n",
                cmd, a->delta[a->ndelta - 1] * scale, 0.01 * p->R);
        return CLI_EXIT_USAGE;
    }
    int rc = a->out ? cli_out_dir(cmd, a->out, NULL) : CLI_EXIT_OK;
    if (rc != CLI_EXIT_OK) return rc;
    asp_options_for_curve(&a->o, a->ndelta);
    if (a->grade >= 0) a->o.grade_3d = a->grade; /* --grade-3d given */
    double *dmm = malloc((size_t)a->ndelta * sizeof *dmm);
    asp_curve_point *rows = calloc((size_t)a->ndelta, sizeof *rows);
    if (!dmm || !rows) return free(dmm), free(rows), cli_fail(cmd, STC_ENOMEM);
    for (int i = 0; i < a->ndelta; i++) dmm[i] = a->delta[i] * scale;
    fields_ctx fc = {cmd, a->out, 0};
    asp_curve_result res;
    s = asp_curve_run(p, &a->o, dmm, a->ndelta, a->out ? write_point_fields : NULL, &fc, rows,
                      &res);
    free(dmm);
    if (s != STC_OK && res.n == 0) return free(rows), cli_fail(cmd, s);
    if (s != STC_OK) fprintf(stderr, "stiction %s: %s\n", cmd, rows[res.n - 1].reason);
    if (res.tail != STC_OK)
        fprintf(stderr, "stiction %s: note: loading past the last point for P_smooth stopped: "
                        "%s; P_smooth near the end uses one side\n", cmd, res.tail_reason);
    rc = s != STC_OK || fc.failed ? CLI_EXIT_FAIL : CLI_EXIT_OK;
    int n = res.n;
    if (a->json) {
        cli_json j;
        cj_init(&j, stdout);
        if (a->ndelta > 1) cj_arr(&j, NULL);
        for (int i = 0; i < n; i++) json_row(&j, &rows[i], &c, &res.info, p->t_over_R > 0.0);
        if (a->ndelta > 1) cj_end_arr(&j);
        cj_done(&j);
    } else {
        print_table(rows, n, &c, &res.info);
    }
    if (a->out && rc == CLI_EXIT_OK && write_csv(a->out, rows, n, &c) != 0) {
        fprintf(stderr, "stiction %s: cannot write %s/curve.csv\n", cmd, a->out);
        rc = CLI_EXIT_FAIL;
    }
    free(rows);
    return rc;
}

int cli_asperity(const cli_cmd *cmd, int argc, char **argv)
{
    stc_params p;
    aopts a = {.grade = -1};
    int done;
    stc_params_default(&p);
    asp_options_default(&a.o);
    cli_shear_args_default(&a.sh);
    int rc = cli_parse(cmd->name, usage, argc, argv, opts, &p, set_opt, &a, &done);
    if (rc == CLI_EXIT_OK && !done) {
        if (a.sh.on) {
            rc = cli_asperity_shear(cmd->name, &p, &a.o, &a.sh, a.delta, a.ndelta, a.in_mm,
                                    a.json, a.out);
        } else if (a.o.edge_refine > 0) {
            /* the band sits at the preload's contact edge, for the ramp */
            fprintf(stderr, "stiction %s: edge-refine = %d: only with --shear\n", cmd->name,
                    a.o.edge_refine);
            rc = CLI_EXIT_USAGE;
        } else if (!a.delta) {
            fprintf(stderr, "stiction %s: one of --delta, --delta-mm or --load is required\n",
                    cmd->name);
            rc = CLI_EXIT_USAGE;
        } else {
            rc = run(cmd->name, &p, &a);
        }
    }
    free(a.delta);
    free(a.out);
    return rc;
}
