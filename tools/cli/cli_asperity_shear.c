/* stiction asperity --shear: normal step (to δ, or to a load with --load)
 * then the tangential ramp to sliding inception.  A thin layer over
 * asp_shear_preload / asp_solver_shear / asp_shear_placements
 * (include/stiction/asperity.h); the parser of the shear options lives here,
 * their help lines in cli_asperity.c's table, which dispatches. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "stiction/asperity.h"
#include "stiction/formulas.h"

static stc_status bad(const char *key, const char *value, const char *what)
{
    return stc_error(STC_EINVAL, __FILE__, __LINE__, "%s = '%s': must be %s", key, value, what);
}

stc_status cli_parse_return_map(const char *key, const char *value, asp_return_map *rm)
{
    if (!strcmp(value, "midpoint")) *rm = ASP_RETURN_MIDPOINT;
    else if (!strcmp(value, "radial")) *rm = ASP_RETURN_RADIAL;
    else if (!strcmp(value, "exact")) *rm = ASP_RETURN_EXACT;
    else return bad(key, value, "midpoint, radial or exact");
    return STC_OK;
}

void cli_shear_args_default(cli_shear_args *sa)
{
    memset(sa, 0, sizeof *sa);
    asp_shear_options_default(&sa->so);
    sa->progress_every = CLI_PROGRESS_EVERY_S;
    sa->refine_err = ASP_REFINE_ERR;
}

stc_status cli_shear_opt(cli_shear_args *sa, const char *key, const char *value)
{
    double v;
    if (!strcmp(key, "shear")) {
        int f;
        stc_status s = cli_parse_flag(key, value, &f);
        if (s) return s;
        sa->on = f;
    } else if (!strcmp(key, "criterion")) {
        if (!strcmp(value, "shear")) sa->so.criterion = ASP_SHEAR_CRIT_SHEAR;
        else if (!strcmp(value, "stiffness")) sa->so.criterion = ASP_SHEAR_CRIT_STIFFNESS;
        else return bad(key, value, "shear or stiffness");
        sa->on = 1;
    } else if (!strcmp(key, "junction")) {
        if (!strcmp(value, "footprint")) sa->so.junction = ASP_JUNCTION_FOOTPRINT;
        else if (!strcmp(value, "nodes")) sa->so.junction = ASP_JUNCTION_NODES;
        else return bad(key, value, "footprint or nodes");
        sa->on = 1;
    } else if (!strcmp(key, "ramp-return-map")) {
        stc_status st = cli_parse_return_map(key, value, &sa->so.return_map);
        if (st) return st;
        sa->on = 1;
    } else if (!strcmp(key, "ramp-refine")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v >= 1.0 && v <= 64.0))
            return bad(key, value, "a factor in [1, 64] dividing the ramp increment targets");
        sa->so.ramp_refine = v;
        sa->on = 1;
    } else if (!strcmp(key, "foot-rows")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v >= 0.0 && v <= 0.9))
            return bad(key, value, "a fraction in [0, 0.9] of the preload contact radius");
        sa->so.foot_rows = v;
        sa->on = 1;
    } else if (!strcmp(key, "placements")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 1 || l > ASP_PLACEMENTS_MAX)
            return bad(key, value, "a whole number of meshes in [1, 8]");
        sa->placements = (int)l;
        sa->on = 1;
    } else if (!strcmp(key, "placements-max")) {
        long l;
        if (stc_parse_long(key, value, &l) != STC_OK || l < 0 || l > ASP_PLACEMENTS_MAX)
            return bad(key, value, "0 (no refinement) or a whole number of meshes in [2, 8]");
        sa->placements_max = (int)l;
        sa->on = 1;
    } else if (!strcmp(key, "refine-err")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v > 0.0 && v <= 0.5))
            return bad(key, value, "a relative standard error in (0, 0.5]");
        sa->refine_err = v;
        sa->on = 1;
    } else if (!strcmp(key, "alpha")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v > 0.0 && v < 1.0))
            return bad(key, value, "a number in (0, 1) (stiffness ratio KT_i/KT_1; BKE: 0.1)");
        sa->so.alpha = v;
        sa->alpha_set = sa->on = 1;
    } else if (!strcmp(key, "tau-c")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v > 0.0) || !isfinite(v))
            return bad(key, value, "a critical shear stress > 0 MPa");
        sa->so.tau_c = v;
        sa->on = 1;
    } else if (!strcmp(key, "progress-every")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v >= 0.0 && v <= 86400.0))
            return bad(key, value, "seconds in [0, 86400] (0: no progress lines)");
        sa->progress_every = v;
    } else if (!strcmp(key, "load")) {
        if (stc_parse_double(key, value, &v) != STC_OK || !(v > 0.0 && v <= 1e4))
            return bad(key, value, "P/Pc_su in (0, 1e4]");
        sa->load = v;
        sa->on = 1;
    } else {
        return STC_EUNSUPPORTED;
    }
    return STC_OK;
}

/* ---- the ramp's points, collected for the CSV -------------------------- */

typedef struct {
    asp_shear_point *p;
    int n, cap;
    int oom;
    int tty;           /* stderr is a terminal: a progress line per ramp point */
    double every;      /* else a line at most every this many seconds (0: none) */
    double t0, t_last; /* monotonic clock at the ramp's start and at the last line, s */
    const char *cmd;
    double omega_c, P_c;
} ptlist;

static int collect(void *ctx, const asp_shear_point *pt)
{
    ptlist *l = ctx;
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 64;
        asp_shear_point *q = realloc(l->p, (size_t)cap * sizeof *q);
        if (!q) return l->oom = 1; /* stops the ramp */
        l->p = q, l->cap = cap;
    }
    l->p[l->n++] = *pt;
    /* the share of the contact at its shear limit reaches 1 at inception */
    if (l->tty) {
        fprintf(stderr, "\r  shear ramp: point %d, ux/wc %.3g, Q/Pc %.4g, at the shear limit "
                        "%3.0f %% of the contact ", l->n, pt->ux / l->omega_c, pt->Q / l->P_c,
                100.0 * pt->limit_frac);
    } else if (l->every > 0.0) { /* a log or a batch job: a line now and then */
        double t = cli_now_s();
        if (t - l->t_last >= l->every) {
            fprintf(stderr, "stiction %s: shear ramp: point %d, ux/wc %.3g, Q/Pc %.4g, at the "
                            "shear limit %.0f %% of the contact; %.0f s\n", l->cmd, l->n,
                    pt->ux / l->omega_c, pt->Q / l->P_c, 100.0 * pt->limit_frac, t - l->t0);
            fflush(stderr);
            l->t_last = t;
        }
    }
    return 0;
}

static int write_csv(const char *dir, const ptlist *l, const stc_critical *c)
{
    cli_out o;
    FILE *f = cli_out_open(&o, dir, "shear.csv");
    if (!f) return -1;
    fprintf(f, "ux_mm,ux_over_omega_c,Q_N,Q_over_P_c,P_N,A_mm2,stick_area_mm2,slip_fraction,"
               "n_contact,a_lead_mm,a_trail_mm,a_side_mm,limit_fraction\n");
    for (int i = 0; i < l->n; i++) {
        const asp_shear_point *p = &l->p[i];
        fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%d,%.9g,%.9g,%.9g,%.6g\n", p->ux,
                p->ux / c->omega_c, p->Q, p->Q / c->P_c, p->P, p->A, p->A_stick, p->slip_frac,
                p->n_contact, p->a_lead, p->a_trail, p->a_side, p->limit_frac);
    }
    return cli_out_close(&o);
}

/* fields_Q0, fields_Q080 (the kept point nearest 0.8 Q_max: its Q/Q_max in
 * *q08), fields_Qmax */
static int write_fields(const char *cmd, asp_solver *sv, const char *dir, double *q08)
{
    static const char *name[3] = {"fields_Q0", "fields_Q080", "fields_Qmax"};
    for (int w = 0; w < 3; w++) {
        char prefix[4096];
        snprintf(prefix, sizeof prefix, "%s/%s", dir, name[w]);
        stc_status s = asp_solver_write_shear_fields(sv, w, prefix, w == 1 ? q08 : NULL);
        if (s) {
            fprintf(stderr, "stiction %s: %s: %s\n", cmd, name[w], stc_errmsg());
            return -1;
        }
    }
    return 0;
}

/* ---- output ------------------------------------------------------------ */

static void print_json(const asp_point *pt, const asp_info *in, const asp_shear_result *r,
                       const stc_critical *c, const ptlist *l, stc_status st, double load,
                       double q08)
{
    cli_json j;
    cj_init(&j, stdout);
    cj_obj(&j, NULL);
    cj_num(&j, "delta_mm", pt->delta);
    cj_num(&j, "delta_over_omega_c_su", pt->delta / c->omega_c);
    if (load > 0.0) cj_num(&j, "load_P_over_P_c", load);
    else cj_null(&j, "load_P_over_P_c");
    cj_num(&j, "P_N", pt->P);
    cj_num(&j, "P_over_P_c", pt->P / c->P_c);
    cj_num(&j, "A_mm2", pt->A);
    cj_num(&j, "A_over_A_c", pt->A / c->A_c);
    cj_num(&j, "a_mm", pt->a);
    cj_int(&j, "nodes_in_contact", pt->n_contact);
    cj_num(&j, "vm_over_Y_substrate", pt->vm_over_Y[0]);
    cj_num(&j, "vm_over_Y_coating", pt->vm_over_Y[1]);
    cj_int(&j, "dofs", in->dofs);
    cj_int(&j, "elements", in->elements);
    cj_num(&j, "elements_per_contact", in->elements_per_contact);
    cj_num(&j, "a_max_mm", in->a_max);
    cj_int(&j, "edge_refine", in->edge_refine);
    cj_num(&j, "edge_a0_mm", in->edge_a0);
    cj_int(&j, "increments", pt->increments);
    cj_int(&j, "newton_iterations", pt->newton_iterations + r->newton_iterations); /* both steps */
    cj_num(&j, "wall_s", pt->wall_s);
    int ok = st == STC_OK && r->converged;
    /* a failed ramp gives its reason, never a number */
    if (ok) {
        cj_num(&j, "Q_max_N", r->Q_max);
        cj_num(&j, "Q_max_over_P_c", r->Q_max / c->P_c);
        cj_num(&j, "mu_s", r->mu_s);
        cj_num(&j, "mu_s_err", r->mu_s_err);
        cj_bool(&j, "Q_still_rising", r->q_rising);
        cj_num(&j, "mu_s_preload", r->mu_s_preload);
        cj_num(&j, "ux_at_slide_mm", r->ux_slide);
        cj_num(&j, "ux_at_slide_over_omega_c", r->ux_slide / c->omega_c);
        cj_num(&j, "P_at_slide_N", r->P_slide);
        cj_num(&j, "stick_radius_mm", sqrt(r->A_stick / M_PI));
        cj_num(&j, "slip_fraction_at_slide", r->slip_frac);
        cj_num(&j, "KT_over_KT1_after_slide", r->KT_after);
        cj_num(&j, "mu_s_ux_slope", r->mu_s_ux_slope);
    } else {
        const char *k[] = {"Q_max_N", "Q_max_over_P_c", "mu_s", "mu_s_err", "Q_still_rising",
                           "mu_s_preload", "ux_at_slide_mm", "ux_at_slide_over_omega_c",
                           "P_at_slide_N", "stick_radius_mm", "slip_fraction_at_slide",
                           "KT_over_KT1_after_slide", "mu_s_ux_slope"};
        for (size_t i = 0; i < sizeof k / sizeof *k; i++) cj_null(&j, k[i]);
    }
    cj_num(&j, "P_preload_N", r->P0);
    cj_str(&j, "criterion", r->criterion == ASP_SHEAR_CRIT_STIFFNESS ? "stiffness" : "shear");
    cj_num(&j, "tau_c_MPa", r->tau_c);
    cj_str(&j, "junction", r->junction == ASP_JUNCTION_NODES ? "nodes" : "footprint");
    cj_num(&j, "foot_rows", r->foot_rows);
    cj_int(&j, "shear_increments", r->increments);
    cj_int(&j, "shear_points", l->n);
    cj_int(&j, "shear_cutbacks", r->cutbacks);
    cj_int(&j, "shear_held_nodes", r->held_nodes);
    cj_int(&j, "shear_hold_passes", r->hold_passes);
    cj_int(&j, "shear_newton_iterations", r->newton_iterations);
    cj_int(&j, "factorizations", pt->factorizations + r->factorizations);
    cj_num(&j, "shear_wall_s", r->wall_s);
    cj_num(&j, "time_assembly_s", in->time_assembly_s); /* normal step + ramp */
    cj_num(&j, "time_factorize_s", in->time_factorize_s);
    cj_num(&j, "time_pcg_s", in->time_pcg_s);
    cj_num(&j, "fields_Q080_Q_over_Q_max", q08); /* null without --out */
    cj_bool(&j, "converged", ok);
    cj_str(&j, "reason", r->reason);
    cj_end_obj(&j);
    cj_done(&j);
}

static void print_text(const asp_point *pt, const asp_info *in, const asp_shear_result *r,
                       const stc_critical *c, const ptlist *l, stc_status st)
{
    printf("mesh: %d elements, %d DOFs (3D half model), h = %.3g mm at the contact, %.4g "
           "elements across a_max", in->elements, in->dofs, in->h_contact,
           in->elements_per_contact);
    if (in->edge_refine > 0)
        printf(", %d times finer around the contact edge at %.4g mm", 1 << in->edge_refine,
               in->edge_a0);
    printf("\n");
    printf("normal step: delta/wc = %.5g, P = %.6g N (P/Pc = %.5g), a = %.5g mm, %d increments, "
           "%.2f s\n\n", pt->delta / c->omega_c, pt->P, pt->P / c->P_c, pt->a, pt->increments,
           pt->wall_s);
    printf("%12s %10s %12s %9s %12s %8s %6s\n", "ux mm", "ux/wc", "Q N", "Q/Pc", "P N", "slip",
           "nodes");
    for (int i = 0; i < l->n; i++) {
        const asp_shear_point *p = &l->p[i];
        printf("%12.5g %10.5g %12.6g %9.5g %12.6g %8.4f %6d\n", p->ux, p->ux / c->omega_c, p->Q,
               p->Q / c->P_c, p->P, p->slip_frac, p->n_contact);
    }
    printf("\ncriterion %s, tau_c = %.5g MPa: %s\n",
           r->criterion == ASP_SHEAR_CRIT_STIFFNESS ? "stiffness" : "shear", r->tau_c,
           r->reason);
    if (st == STC_OK && r->converged) {
        printf("Q_max = %.6g N (Q/Pc = %.5g) at ux = %.5g mm, P = %.6g N there; %d increments, "
               "%d factorizations, %.2f s\n\n", r->Q_max, r->Q_max / c->P_c, r->ux_slide,
               r->P_slide, r->increments, r->factorizations, r->wall_s);
        printf("mu_s = %.4f ± %.4f  (Q_max / P at sliding inception; ± one standard error: "
               "one mesh's node-placement scatter; --placements 2 or 4 narrows it at about "
               "2.5 or 5x the time)%s\n",
               r->mu_s, r->mu_s_err, r->q_rising ? "  [Q still rising]" : "");
    } else printf("NOT CONVERGED: no static friction coefficient\n");
}

/* The flag of a result whose Q still rose past inception (stderr). */
static void warn_rising(const char *cmd, int n, int k, double KT_after, double slope)
{
    if (n == 0) return;
    if (k == 1)
        fprintf(stderr, "stiction %s: warning: Q still rising past sliding inception "
                        "(KT/KT1 = %.3g after it): mu_s depends on where inception is declared, "
                        "by %.3g %% per %% of ux there (docs/design.md §4.4)\n", cmd, KT_after,
                slope);
    else
        fprintf(stderr, "stiction %s: warning: Q still rising past sliding inception in %d of "
                        "%d members: their mu_s depends on where inception is declared "
                        "(docs/design.md §4.4)\n", cmd, n, k);
}

/* ---- node-placement ensemble (--placements K) ---------------------------- */

static const char *member_reason(const asp_placement_member *m)
{
    return m->status == STC_OK ? m->res.reason : m->message;
}

static int rising_members(const asp_placement_result *e)
{
    int n = 0;
    for (int j = 0; j < e->k; j++) n += e->m[j].status == STC_OK && e->m[j].res.q_rising;
    return n;
}

static int write_members_csv(const char *dir, const asp_placement_result *e)
{
    cli_out o;
    FILE *f = cli_out_open(&o, dir, "placements.csv");
    if (!f) return -1;
    fprintf(f, "member,elements_per_contact,converged,mu_s,mu_s_preload,Q_max_N,P_at_slide_N,"
               "P_preload_N,a0_mm,ux_at_slide_mm,shear_wall_s,reason\n");
    for (int j = 0; j < e->k; j++) {
        const asp_placement_member *m = &e->m[j];
        int ok = m->status == STC_OK && m->res.converged;
        fprintf(f, "%d,%.6g,%d,", j, m->elements_per_contact, ok);
        if (ok)
            fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.4g,", m->res.mu_s,
                    m->res.mu_s_preload, m->res.Q_max, m->res.P_slide, m->pt.P, m->pt.a,
                    m->res.ux_slide, m->res.wall_s);
        else fprintf(f, ",,,,,,,,");
        fputc('"', f);
        for (const char *c = member_reason(m); *c; c++) fputc(*c == '"' ? '\'' : *c, f);
        fprintf(f, "\"\n");
    }
    return cli_out_close(&o);
}

static void print_placements_json(const asp_placement_result *e, const stc_critical *c,
                                   double delta, double load, stc_status st)
{
    cli_json j;
    int ok = st == STC_OK;
    cj_init(&j, stdout);
    cj_obj(&j, NULL);
    cj_num(&j, "delta_mm", delta);
    cj_num(&j, "delta_over_omega_c_su", delta / c->omega_c);
    if (load > 0.0) cj_num(&j, "load_P_over_P_c", load);
    else cj_null(&j, "load_P_over_P_c");
    cj_int(&j, "placements", e->k);
    cj_num(&j, "placement_period", e->period);
    cj_int(&j, "edge_refine", e->edge_refine);
    if (ok) {
        cj_num(&j, "mu_s", e->mu_s);
        cj_num(&j, "mu_s_err", e->mu_s_err);
        cj_int(&j, "members_Q_still_rising", rising_members(e));
        cj_num(&j, "mu_s_min", e->mu_s_min);
        cj_num(&j, "mu_s_max", e->mu_s_max);
        cj_num(&j, "mu_s_spread", 0.5 * (e->mu_s_max - e->mu_s_min) / e->mu_s);
        cj_num(&j, "mu_s_preload", e->mu_s_preload);
        cj_num(&j, "Q_max_N", e->Q_max);
        cj_num(&j, "Q_max_over_P_c", e->Q_max / c->P_c);
        cj_num(&j, "P_at_slide_N", e->P_slide);
    } else {
        const char *k[] = {"mu_s", "mu_s_err", "members_Q_still_rising", "mu_s_min", "mu_s_max",
                           "mu_s_spread", "mu_s_preload", "Q_max_N", "Q_max_over_P_c",
                           "P_at_slide_N"};
        for (size_t i = 0; i < sizeof k / sizeof *k; i++) cj_null(&j, k[i]);
    }
    const asp_shear_result *r0 = &e->m[0].res;
    cj_str(&j, "criterion", r0->criterion == ASP_SHEAR_CRIT_STIFFNESS ? "stiffness" : "shear");
    cj_num(&j, "tau_c_MPa", r0->tau_c);
    cj_str(&j, "junction", r0->junction == ASP_JUNCTION_NODES ? "nodes" : "footprint");
    cj_num(&j, "foot_rows", r0->foot_rows);
    cj_arr(&j, "members");
    for (int i = 0; i < e->k; i++) {
        const asp_placement_member *m = &e->m[i];
        int mok = m->status == STC_OK && m->res.converged;
        cj_obj(&j, NULL);
        cj_num(&j, "elements_per_contact", m->elements_per_contact);
        cj_num(&j, "P_preload_N", m->pt.P);
        cj_num(&j, "a_mm", m->pt.a);
        if (mok) {
            cj_num(&j, "mu_s", m->res.mu_s);
            cj_num(&j, "mu_s_err", m->res.mu_s_err);
            cj_bool(&j, "Q_still_rising", m->res.q_rising);
            cj_num(&j, "mu_s_ux_slope", m->res.mu_s_ux_slope);
            cj_num(&j, "Q_max_N", m->res.Q_max);
            cj_num(&j, "P_at_slide_N", m->res.P_slide);
            cj_num(&j, "ux_at_slide_mm", m->res.ux_slide);
        } else {
            cj_null(&j, "mu_s"), cj_null(&j, "mu_s_err"), cj_null(&j, "Q_still_rising");
            cj_null(&j, "mu_s_ux_slope");
            cj_null(&j, "Q_max_N");
            cj_null(&j, "P_at_slide_N"), cj_null(&j, "ux_at_slide_mm");
        }
        cj_num(&j, "shear_wall_s", m->res.wall_s);
        cj_bool(&j, "converged", mok);
        cj_str(&j, "reason", member_reason(m));
        cj_end_obj(&j);
    }
    cj_end_arr(&j);
    cj_num(&j, "wall_s", e->wall_s);
    cj_bool(&j, "converged", ok);
    cj_str(&j, "reason", ok ? "every member reached inception" : stc_errmsg());
    cj_end_obj(&j);
    cj_done(&j);
}

static void print_placements_text(const asp_placement_result *e, const stc_critical *c,
                                  double delta, double load, stc_status st)
{
    if (load > 0.0)
        printf("load control: P = %.6g Pc reached by member 0 at delta = %.6g mm (%.5g omega_c); "
               "the others run at that delta\n", load, delta, delta / c->omega_c);
    printf("node-placement ensemble: %d meshes, elements per contact shifted by %.4g / %d "
           "(one node spacing at the contact edge", e->k, e->period, e->k);
    if (e->edge_refine > 0) printf(", in a band %d times finer", 1 << e->edge_refine);
    printf(")\n\n");
    printf("%8s %12s %10s %12s %12s %10s %8s\n", "member", "elem/contact", "a0 mm", "Q_max N",
           "P slide N", "mu_s", "ramp s");
    for (int j = 0; j < e->k; j++) {
        const asp_placement_member *m = &e->m[j];
        if (m->status == STC_OK && m->res.converged)
            printf("%8d %12.5g %10.5g %12.6g %12.6g %10.5f %8.1f\n", j, m->elements_per_contact,
                   m->pt.a, m->res.Q_max, m->res.P_slide, m->res.mu_s, m->res.wall_s);
        else printf("%8d %12.5g  FAILED: %s\n", j, m->elements_per_contact, member_reason(m));
    }
    if (st == STC_OK)
        printf("\nQ_max/Pc = %.5g, members' mu_s %.5f … %.5f (half range %.2f %% of the mean), "
               "%.1f s\n\nmu_s = %.4f ± %.4f  (Q_max / P at sliding inception, mean of %d "
               "placements; ± one standard error: the members' and the %.1f %% mesh floor)\n",
               e->Q_max / c->P_c, e->mu_s_min, e->mu_s_max,
               50.0 * (e->mu_s_max - e->mu_s_min) / e->mu_s, e->wall_s, e->mu_s, e->mu_s_err,
               e->k, 100.0 * ASP_MU_S_ERR_FLOOR);
    else printf("\nNOT CONVERGED: no static friction coefficient\n");
}

static int run_placements(const char *cmd, const stc_params *p, asp_options *o,
                          const cli_shear_args *sa, const stc_critical *c, double dmm, int json,
                          const char *out)
{
    asp_placement_result *e = malloc(sizeof *e);
    if (!e) return cli_fail(cmd, STC_ENOMEM);
    int k = sa->placements > 1 ? sa->placements : 1;
    if (isatty(2)) {
        fprintf(stderr, "stiction %s: %d node placement%s", cmd, k, k > 1 ? "s" : "");
        if (sa->placements_max > 0)
            fprintf(stderr, " (doubled while their standard error exceeds %g %%, up to %d)",
                    100 * sa->refine_err, sa->placements_max);
        fprintf(stderr, ": normal step and shear ramp on each (member 0 first, then the "
                        "others side by side) ...\n");
    }
    stc_status st = asp_shear_placements_adaptive(p, o, &sa->so, dmm, sa->load * c->P_c, k,
                                                  sa->placements_max, sa->refine_err, e);
    if (st == STC_EINVAL || (st != STC_OK && e->k == 0)) {
        free(e);
        return cli_fail(cmd, st);
    }
    char why[512];
    snprintf(why, sizeof why, "%s", st == STC_OK ? "" : stc_errmsg());
    double delta = sa->load > 0.0 ? e->m[0].pt.delta : dmm;
    if (json) print_placements_json(e, c, delta, sa->load, st);
    else print_placements_text(e, c, delta, sa->load, st);
    if (st == STC_OK) warn_rising(cmd, rising_members(e), e->k, NAN, NAN);
    int rc = CLI_EXIT_OK;
    if (st != STC_OK) {
        fprintf(stderr, "stiction %s: %s\n", cmd, why);
        rc = CLI_EXIT_FAIL;
    } else if (out && write_members_csv(out, e) != 0) {
        fprintf(stderr, "stiction %s: cannot write the results into '%s'\n", cmd, out);
        rc = CLI_EXIT_FAIL;
    }
    free(e);
    return rc;
}

/* ---- run ----------------------------------------------------------------- */

static int check_args(const char *cmd, const stc_params *p, asp_options *o,
                      const cli_shear_args *sa, int ndelta, double delta_mm)
{
    stc_status s = asp_options_for_shear(o);
    if (s != STC_OK) return cli_fail(cmd, s);
    if (sa->alpha_set && sa->so.criterion != ASP_SHEAR_CRIT_STIFFNESS) {
        fprintf(stderr, "stiction %s: alpha = %g: only used by --criterion stiffness\n", cmd,
                sa->so.alpha);
        return CLI_EXIT_USAGE;
    }
    if (sa->load > 0.0 && ndelta > 0) {
        fprintf(stderr, "stiction %s: --load conflicts with --delta/--delta-mm: give one\n", cmd);
        return CLI_EXIT_USAGE;
    }
    if (sa->load <= 0.0 && ndelta != 1) {
        fprintf(stderr, "stiction %s: delta: --shear needs one interference (--delta X or "
                        "--delta-mm X) or --load X, got %d values\n", cmd, ndelta);
        return CLI_EXIT_USAGE;
    }
    if (delta_mm > 0.01 * p->R) {
        fprintf(stderr, "stiction %s: delta = %g mm: must be <= 0.01 R = %g mm (small strain)\n",
                cmd, delta_mm, 0.01 * p->R);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

int cli_asperity_shear(const char *cmd, const stc_params *p, asp_options *o,
                       const cli_shear_args *sa, const double *delta, int ndelta, int in_mm,
                       int json, const char *out)
{
    stc_material su;
    stc_critical c;
    stc_params_materials(p, &su, NULL);
    stc_status s = stc_params_validate(p);
    if (!s) s = stc_critical_eval(&su, p->R, &c);
    if (s) return cli_fail(cmd, s);
    double dmm = ndelta > 0 ? delta[0] * (in_mm ? 1.0 : c.omega_c) : 0.0;
    int rc = check_args(cmd, p, o, sa, ndelta, dmm);
    if (rc) return rc;
    int rc_out = out ? cli_out_dir(cmd, out, NULL) : CLI_EXIT_OK;
    if (rc_out != CLI_EXIT_OK) return rc_out;
    if (sa->placements > 1 || sa->placements_max > 0)
        return run_placements(cmd, p, o, sa, &c, dmm, json, out);
    asp_solver *sv;
    asp_point pt;
    int tty = isatty(2);
    if (tty) fprintf(stderr, "stiction %s: normal step (3D mesh, load and solve) ...", cmd);
    if ((s = asp_shear_preload(p, o, dmm, sa->load * c.P_c, &sv, &pt))) {
        if (tty) fputc('\n', stderr);
        return cli_fail(cmd, s);
    }
    if (tty) fprintf(stderr, " done: P/Pc %.4g\n", pt.P / c.P_c);
    asp_info in;
    asp_shear_options so = sa->so;
    so.keep_fields = out != NULL;
    asp_shear_result r;
    ptlist l = {0};
    l.tty = tty, l.omega_c = c.omega_c, l.P_c = c.P_c;
    l.every = sa->progress_every, l.cmd = cmd;
    l.t0 = l.t_last = cli_now_s();
    stc_status st = asp_solver_shear(sv, &so, collect, &l, &r);
    if (tty && l.n > 0) fputc('\n', stderr);
    if (l.oom) fprintf(stderr, "stiction %s: out of memory for the ramp points\n", cmd);
    int ok = st == STC_OK && r.converged;
    double q08 = NAN;
    asp_solver_info(sv, &in); /* the time split of the whole run */
    rc = CLI_EXIT_OK;
    if (ok && out && write_fields(cmd, sv, out, &q08) != 0) rc = CLI_EXIT_FAIL;
    if (json) print_json(&pt, &in, &r, &c, &l, st, sa->load, q08);
    else print_text(&pt, &in, &r, &c, &l, st);
    if (ok) warn_rising(cmd, r.q_rising, 1, r.KT_after, r.mu_s_ux_slope);
    if (!ok) {
        fprintf(stderr, "stiction %s: %s\n", cmd, r.reason);
        /* the ramp points reached are kept for the diagnosis (no μs is claimed) */
        if (out && l.n > 0 && write_csv(out, &l, &c) == 0)
            fprintf(stderr, "stiction %s: the %d ramp points reached are in %s/shear.csv\n", cmd,
                    l.n, out);
        rc = CLI_EXIT_FAIL;
    } else if (out && (rc != CLI_EXIT_OK || write_csv(out, &l, &c) != 0)) {
        fprintf(stderr, "stiction %s: cannot write the results into '%s'\n", cmd, out);
        rc = CLI_EXIT_FAIL;
    }
    free(l.p);
    asp_solver_destroy(&sv);
    return rc;
}
