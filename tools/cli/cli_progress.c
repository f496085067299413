/* The progress line of a table build (stiction table build, surface predict
 * --fill). */
#include <math.h>
#include <stdio.h>

#include "cli.h"

static void fmt_dur(double s, char *buf, size_t n)
{
    if (!isfinite(s)) snprintf(buf, n, "?");
    else if (s < 120) snprintf(buf, n, "%.0f s", s);
    else if (s < 7200) snprintf(buf, n, "%.1f min", s / 60);
    else snprintf(buf, n, "%.1f h", s / 3600);
}

/* After a normal curve. */
static int curve_line(const cli_table_progress *c, const tbl_progress *p)
{
    const double *ax1, *ax2;
    int n1 = tbl_normal_axis(c->t, 1, &ax1);
    tbl_normal_axis(c->t, 2, &ax2);
    char el[32], eta[32];
    fmt_dur(p->elapsed_s, el, sizeof el);
    fmt_dur(p->eta_s, eta, sizeof eta);
    fprintf(stderr, "%s[normal %d/%d] t/R %g E-ratio %g: %s (%.1f s); elapsed %s, curves eta "
            "%s%s", c->tty ? "\r\033[K" : "", p->curves_done, p->curves_total,
            ax1[p->curve % n1], ax2[p->curve / n1],
            p->c->state == TBL_DONE ? "done" : "FAILED", p->c->wall_s, el, eta,
            c->tty ? "" : "\n");
    if (p->c->state == TBL_FAILED)
        fprintf(stderr, "%s  normal curve %d failed: %s\n", c->tty ? "\n" : "", p->curve,
                p->c->reason);
    fflush(stderr);
    return 0;
}

/* After a placement member of a point: on a terminal always (the line is
 * rewritten in place), else when the member took a while, so that a long
 * point shows progress in a log without a line per member of short ones. */
#define MEMBER_LINE_S 30.0

static int member_line(const cli_table_progress *c, const tbl_progress *p)
{
    double mw = p->m->pt.wall_s + p->m->res.wall_s;
    if (!c->tty && !(mw >= MEMBER_LINE_S)) return 0;
    double w, tR, E;
    tbl_coords(c->t, p->index, &w, &tR, &E);
    char el[32], mu[64];
    fmt_dur(p->elapsed_s, el, sizeof el);
    if (p->m->status == STC_OK && p->m->res.converged)
        snprintf(mu, sizeof mu, "mu_s %.4f", p->m->res.mu_s);
    else snprintf(mu, sizeof mu, "no inception");
    fprintf(stderr, "%s[%d/%d] delta %g t/R %g E-ratio %g: member %d of %d %s (%.1f s); "
            "elapsed %s%s", c->tty ? "\r\033[K" : "", p->done, p->total, w, tR, E,
            p->member + 1, p->members, mu, mw, el, c->tty ? "" : "\n");
    fflush(stderr);
    return 0;
}

/* A line per finished point (stderr): on a terminal one line rewritten in
 * place, else a line each. */
int cli_table_progress_line(void *ctx, const tbl_progress *p)
{
    const cli_table_progress *c = ctx;
    if (c->quiet) return 0;
    if (p->curve >= 0) return curve_line(c, p);
    if (p->m) return member_line(c, p);
    double w, tR, E;
    tbl_coords(c->t, p->index, &w, &tR, &E);
    char el[32], eta[32], mu[64];
    fmt_dur(p->elapsed_s, el, sizeof el);
    fmt_dur(p->eta_s, eta, sizeof eta);
    tbl_numerics n;
    tbl_get_numerics(c->t, &n);
    if (p->point->state == TBL_DONE && n.placements_max > 0) /* how far it was refined */
        snprintf(mu, sizeof mu, "mu_s %.4f +- %.4f, %d placements", p->point->mu_s,
                 p->point->mu_s_err, p->point->members);
    else if (p->point->state == TBL_DONE)
        snprintf(mu, sizeof mu, "mu_s %.4f +- %.4f", p->point->mu_s, p->point->mu_s_err);
    else snprintf(mu, sizeof mu, "FAILED");
    fprintf(stderr, "%s[%d/%d] delta %g t/R %g E-ratio %g: %s (%.1f s); elapsed %s, eta %s%s",
            c->tty ? "\r\033[K" : "", p->done, p->total, w, tR, E, mu, p->point->wall_s, el, eta,
            c->tty ? "" : "\n");
    if (p->point->state == TBL_FAILED)
        fprintf(stderr, "%s  point %d failed: %s\n", c->tty ? "\n" : "", p->index,
                p->point->reason);
    fflush(stderr);
    return 0;
}

