/* stiction halfspace: the elastic half-space reference for the asperity's
 * tangential step (surface/halfspace.c): a homogeneous sphere pressed by a
 * rigid flat to δ without friction, then sheared in full slip at τc with no
 * separation.  Reports the preload (against Hertz), the junction growth and
 * the elastic μs = τc A / P. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "stiction/formulas.h"
#include "stiction/halfspace.h"

static const char usage[] =
    "(--delta X | --delta-mm X) [sphere, materials] [--tau-c MPa] [--cells N] [--json]\n"
    "\n"
    "The elastic reference for the junction growth of stiction asperity --shear\n"
    "(docs/design.md §5.6): a homogeneous elastic sphere (no coating) pressed by a\n"
    "rigid flat to delta without friction, then the flat slides along +x in full slip\n"
    "(traction tau_c on the whole contact) and no point that touched separates.\n"
    "Elastic half-space boundary elements (Boussinesq and Cerruti influence of uniform\n"
    "cells, FFT, Polonsky-Keer CG).  Contact areas are cell counts (a sub-cell edge\n"
    "error of about one cell along the perimeter).";

static const cli_opt opts[] = {
    CLI_HEADING("Sphere (homogeneous; units mm, N, MPa)"),
    {"R", "MM", "radius R of the sphere, mm (default 10)"},
    CLI_SUBSTRATE_OPTS,
    CLI_HEADING("Loading"),
    {"delta", "X", "interference in units of omega_c_su, the sphere's critical interference "
                   "(> 0)"},
    {"delta-mm", "X", "interference in mm (> 0)"},
    CLI_HEADING("Friction"),
    {"tau-c", "MPa", "shear strength of the interface (default Y-su/sqrt(3))"},
    CLI_HEADING("Accuracy"),
    {"cells", "N", "cells across the grid, in [16, 4096] (default 256).  WSP sphere at 0.5 "
                   "omega_c: area growth +4.88 / +4.89 / +4.92 % with 128 / 256 / 512 cells, "
                   "in 1.8 / 3.9 / 152 s"},
    CLI_HEADING("Common options"),
    {"json", NULL, "print one JSON object instead of the report"},
    CLI_CONFIG_HELP,
    CLI_HEADING("Expert numerics"),
    {"span", "S", "grid half-width in Hertz radii sqrt(R delta), in [1.05, 4] (default 1.3)"},
    {"steps", "K",
     "traction steps to full slip, in [1, 1000] (default 2; 1, 10 and 40 give the same "
     "growth to 0.01 %)"},
    {NULL, NULL, NULL},
};

typedef struct {
    double delta, delta_mm, tau_c, span;
    int cells, steps, json;
} hopts;

static stc_status set_num(const char *key, const char *value, double lo, int lo_incl, double hi,
                          double *v)
{
    stc_status s = stc_parse_double(key, value, v);
    return s != STC_OK ? s : stc_check_range(key, *v, lo, lo_incl, hi, 1);
}

static stc_status set_opt(void *ctx, const char *key, const char *value)
{
    hopts *o = ctx;
    if (!strcmp(key, "delta")) return set_num(key, value, 0.0, 0, INFINITY, &o->delta);
    if (!strcmp(key, "delta-mm")) return set_num(key, value, 0.0, 0, INFINITY, &o->delta_mm);
    if (!strcmp(key, "tau-c")) return set_num(key, value, 0.0, 0, INFINITY, &o->tau_c);
    if (!strcmp(key, "span")) return set_num(key, value, 1.05, 1, 4.0, &o->span);
    if (!strcmp(key, "cells")) return cli_parse_int(key, value, 16, 4096, &o->cells);
    if (!strcmp(key, "steps")) return cli_parse_int(key, value, 1, 1000, &o->steps);
    if (!strcmp(key, "json")) return cli_parse_flag(key, value, &o->json);
    return STC_EUNSUPPORTED;
}

static int run(const char *cmd, const stc_params *p, const hopts *o)
{
    stc_material su, co;
    stc_critical c;
    stc_status s;
    stc_params_materials(p, &su, &co);
    if ((s = stc_critical_eval(&su, p->R, &c)) != STC_OK) return cli_fail(cmd, s);
    double delta = o->delta_mm > 0.0 ? o->delta_mm : o->delta * c.omega_c;
    double tau_c = o->tau_c > 0.0 ? o->tau_c : su.Y / sqrt(3.0);
    srf_slide_result r;
    s = srf_halfspace_sphere_slide(p->R, delta, su.E, su.nu, tau_c, o->cells, o->span, o->steps,
                                   &r);
    if (s != STC_OK) return cli_fail(cmd, s);
    stc_hertz hz;
    if ((s = stc_hertz_eval(&su, p->R, delta, &hz)) != STC_OK) return cli_fail(cmd, s);
    double a0 = sqrt(r.A0 / M_PI), mu0 = tau_c * r.A0 / r.P0, mu = tau_c * r.A / r.P;
    if (o->json) {
        cli_json j;
        cj_init(&j, stdout);
        cj_obj(&j, NULL);
        cj_params(&j, p);
        cj_num(&j, "delta_mm", delta);
        cj_num(&j, "delta_over_omega_c_su", delta / c.omega_c);
        cj_num(&j, "tau_c_MPa", tau_c);
        cj_int(&j, "cells", o->cells);
        cj_num(&j, "cell_mm", r.h);
        cj_int(&j, "steps", o->steps);
        cj_num(&j, "P_hertz_N", hz.P);
        cj_num(&j, "a_hertz_mm", hz.a);
        cj_num(&j, "P0_N", r.P0);
        cj_num(&j, "A0_mm2", r.A0);
        cj_num(&j, "P_N", r.P);
        cj_num(&j, "A_mm2", r.A);
        cj_num(&j, "area_growth", r.A / r.A0 - 1.0);
        cj_num(&j, "a_lead_over_a0", r.a_lead / a0);
        cj_num(&j, "a_trail_over_a0", r.a_trail / a0);
        cj_num(&j, "a_side_over_a0", r.a_side / a0);
        cj_num(&j, "tension_N", r.tension);
        cj_num(&j, "mu_s_no_growth", mu0);
        cj_num(&j, "mu_s", mu);
        cj_int(&j, "iterations", r.iterations);
        cj_end_obj(&j);
        cj_done(&j);
        return CLI_EXIT_OK;
    }
    printf("Elastic half-space, rigid flat, delta = %.6g mm (%.4g omega_c_su), tau_c = %.6g MPa\n"
           "  grid %d x %d cells of %.4g mm (%.2f %% of a0), %d traction steps, %d CG "
           "iterations\n"
           "  preload: P0 = %.6g N (Hertz %.6g, %+.3f %%), A0 = %.6g mm2 (Hertz %+.2f %%)\n"
           "  full slip: A/A0 - 1 = %+.2f %%, P/P0 - 1 = %+.2f %%, tension %.4g N\n"
           "  extents / a0: lead %.4f, trail %.4f, side %.4f (cell %.4f)\n"
           "  mu_s = tau_c A / P = %.5f (no growth: %.5f, %+.2f %%)\n",
           delta, delta / c.omega_c, tau_c, o->cells, o->cells, r.h, 100 * r.h / a0, o->steps,
           r.iterations, r.P0, hz.P, 100 * (r.P0 / hz.P - 1), r.A0,
           100 * (r.A0 / (M_PI * hz.a * hz.a) - 1), 100 * (r.A / r.A0 - 1),
           100 * (r.P / r.P0 - 1), r.tension, r.a_lead / a0, r.a_trail / a0, r.a_side / a0,
           r.h / a0, mu, mu0, 100 * (mu / mu0 - 1));
    return CLI_EXIT_OK;
}

int cli_halfspace(const cli_cmd *cmd, int argc, char **argv)
{
    stc_params p;
    hopts o = {.span = 1.3, .cells = 256, .steps = 2};
    int done, rc;
    stc_params_default(&p);
    rc = cli_parse(cmd->name, usage, argc, argv, opts, &p, set_opt, &o, &done);
    if (rc != CLI_EXIT_OK || done) return rc;
    if ((o.delta > 0.0) == (o.delta_mm > 0.0)) {
        fprintf(stderr, "stiction %s: give one of --delta and --delta-mm\n", cmd->name);
        return CLI_EXIT_USAGE;
    }
    /* a coating would be ignored: refused, naming the key that gives one */
    stc_material su;
    stc_params_materials(&p, &su, NULL);
    char key[64] = "";
    if (p.t_mm_set && p.t_mm != 0.0) snprintf(key, sizeof key, "t-mm = %g", p.t_mm);
    else if (p.t_over_R != 0.0) snprintf(key, sizeof key, "t-over-R = %g", p.t_over_R);
    else if (p.E_ratio != 1.0) snprintf(key, sizeof key, "E-ratio = %g", p.E_ratio);
    else if (p.Y_co > 0.0 && p.Y_co != su.Y) snprintf(key, sizeof key, "Y-co = %g", p.Y_co);
    else if (p.nu_co_set && p.nu_co != p.nu) snprintf(key, sizeof key, "nu-co = %g", p.nu_co);
    if (*key) {
        fprintf(stderr, "stiction %s: %s: the half-space reference is a homogeneous sphere "
                "(no coating: t-over-R and t-mm 0, E-ratio 1, Y-co and nu-co those of the "
                "substrate)\n", cmd->name, key);
        return CLI_EXIT_USAGE;
    }
    return run(cmd->name, &p, &o);
}
