/* Newton's method for one load increment of the asperity FE model: the
 * increment (predictor, active-set passes to consistency, loose then full
 * tolerance), the Newton iteration with backtracking line search, its
 * exits (converged, diverged, stagnated, iteration limit, element
 * inverted; asp_outcome) and the inexact-Newton forcing term of the
 * Krylov solves.  Separate from the linear solver (linsolve.c), the
 * assembly (assemble.c), the contact (asp_contact.c) and the load stepping
 * around it (load.c, shear.c), which all call in here or are called from
 * here one way.  Design: docs/design.md §3.5.
 *
 * Boundary conditions and contact are imposed without changing the
 * pattern: a constrained DOF keeps its prescribed value and gets an
 * identity row/column in K (linsolve.c).  A prescribed value that changes
 * (the flat advancing, a node entering the contact) is not written into u
 * directly: the Newton step carries it (du = ubc - u on the fixed DOFs,
 * -K_fc du_c on the free ones), so the neighbours of a node that enters
 * follow it instead of a ring of elements being strained and turned
 * plastic (this halved the element evaluations of a load curve).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"

static double norm_sel(const asp_solver *s, const double *v, int want_fixed)
{
    double a = 0.0;
    for (int i = 0; i < s->ndof; i++)
        if (!s->fixed[i] == !want_fixed) a += v[i] * v[i];
    return sqrt(a);
}

/* Constraint defect c = ubc - u on the fixed DOFs (0 elsewhere); returns |c|. */
static double constraint_defect(const asp_solver *s, double *c)
{
    double a = 0.0;
    for (int i = 0; i < s->ndof; i++) {
        c[i] = s->fixed[i] ? s->ubc[i] - s->u[i] : 0.0;
        a += c[i] * c[i];
    }
    return sqrt(a);
}

/* Newton step for K du = -r with du = c on the fixed DOFs (lifting: the
 * free DOFs get -K_fc c, the linear response to the prescribed jump), into
 * the linear solver's right-hand side.  When cn > 0, du holds K c
 * (unconstrained K) on entry. */
static void newton_rhs(const asp_solver *s, const double *c, double cn, const double *du)
{
    double *bx = asp_ls_rhs(s->ls);
    if (cn > 0.0) {
        for (int i = 0; i < s->ndof; i++) bx[i] = s->fixed[i] ? c[i] : -s->fint[i] - du[i];
    } else {
        for (int i = 0; i < s->ndof; i++) bx[i] = s->fixed[i] ? 0.0 : -s->fint[i];
    }
}

/* Krylov tolerance: the smaller of an absolute 1e-3 rtol |reaction|, the
 * smallest residual the tests of newton() distinguish, so the iterates
 * pass the same tests as with the exact solve, and 1e-6 of the step's
 * right-hand side (linsolve.c), so a step near convergence still lowers
 * the residual (the line search needs it).  Measured on the coated stick
 * axisymmetric case δ = 10 ωc (PCG forced): the same 98 Newton iterations
 * and answers as factorizing; a relative 1e-2 moved P by 1 % (the stick
 * positions come from the iterates), and a floor at 1e-2 rtol |reaction|
 * cost 25 % more Newton iterations and 50 % more line-search evaluations. */
#define KRYLOV_ABS 1e-3

/* Inexact Newton: the Krylov solve of a Newton step need only be as
 * accurate as the step's linear model is useful, which it is to about the
 * square of the last residual ratio.  Forcing term η_k = γ (|r_k| /
 * |r_k-1|)², γ = 0.9 (Eiseasp_nstat & Walker, SIAM J. Sci. Comput. 17 (1996)
 * 16, choice 2), capped at KRYLOV_EW_MAX (the first step of a Newton solve
 * uses the cap; their safeguard against a too-fast decrease, γ η_k-1²,
 * never exceeds their 0.1 under this cap); the Krylov tolerance is then
 * the larger of η_k |r| and the fixed one above, and a step that jumps the
 * constraints is solved to the fixed one.  Measured (idle machine, two
 * threads): graded 3D slip curve n = 4 17.4 -> 13.7 s (Krylov iterations
 * 2812 -> 1966, factorizations 20 -> 15, Newton iterations 191 -> 209),
 * P to 9 digits unchanged; WSP 3 / 12 ωc shear 11.1 / 13.6 -> 8.5 / 11.3 s,
 * μs moved 1e-8; coated stick δ = 10 shear ~38 -> 35.9 s, μs moved 1e-7
 * (the stick positions follow the iterates).  A cap of 0.1 moved the
 * curve's last P by +0.2 % (the active set settles on loose iterates), and
 * γ = 0.5 ran as fast as 0.9. */
#define KRYLOV_EW_GAMMA 0.9
#define KRYLOV_EW_MAX 1e-2

static double forcing(double ratio)
{
    return fmin(KRYLOV_EW_GAMMA * ratio * ratio, KRYLOV_EW_MAX);
}

/* A failed factorization in words, at the converged δ. */
static stc_status linear_failed(const asp_solver *s, asp_nstat *ns, stc_status st)
{
    asp_ls_stats ls;
    asp_ls_get_stats(s->ls, &ls);
    if (ls.factor != ASP_OUTCOME_NOT_POSDEF && ls.factor != ASP_OUTCOME_SOLVER_FAILED) return st;
    ns->why = ls.factor;
    return STC_FAIL(STC_ESOLVER, "CHOLMOD factorization at δ = %g mm: %s (column %d of %d)",
                    s->delta, asp_outcome_str(ls.factor), ls.minor, s->ndof);
}

/* One Newton step at a fresh tangent (linsolve.c: Krylov with the last
 * factor, or factorize and solve; K gets the identity rows).  When cn > 0,
 * du holds K c (unconstrained K) on entry, as for newton_solve. */
static stc_status linear_step(asp_solver *s, asp_nstat *ns, const double *c, double cn, double *du,
                              double tol, double eta)
{
    newton_rhs(s, c, cn, du);
    s->k_fresh = 0;
    int f;
    stc_status st = asp_ls_step(s->ls, du, tol, eta, &f);
    ns->facts += f;
    return st == STC_OK || !f ? st : linear_failed(s, ns, st);
}

/* A Newton step with the factor of an earlier one (newton_reuse). */
static stc_status newton_solve(asp_solver *s, const double *c, double cn, double *du)
{
    newton_rhs(s, c, cn, du);
    return asp_ls_resolve(s->ls, du);
}

/* Iterations without halving the best residual before Newton gives up.
 * On the graded 3D slip curve (level 0, and n = 4 with a finer shell step)
 * the failing increments (30-40 ωc) cycled for 24 of their 30 iterations at
 * ~3e-3 of the reaction (the tangential DOFs of an edge ring of contact
 * nodes; a full step always raised the residual) before the cut-back, after
 * which they converged in 5.  Measured: level-0 curve 76.4 -> 68.5 s, same
 * increments and answers.  6 was too few: WSP 3 / 12 ωc shear ramps have
 * increments that converge after such a plateau (μs moved 2.6e-4, 40 %
 * slower); with 10 they are unchanged; docs/design.md §3.5. */
enum { NEWTON_STALL = 10 };

/* A Newton exit: records why in ns; with a message (fmt not NULL) it is a
 * failure, STC_ENOCONV. */
static stc_status newton_exit(asp_nstat *ns, asp_outcome why, const char *fmt, ...)
{
    ns->why = why;
    if (!fmt) return STC_OK;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return STC_FAIL(STC_ENOCONV, "%s", msg);
}

/* Where a Newton solve stands between its iterations. */
typedef struct ntrack {
    double rtol, utol; /* this solve's tolerances (loosened or not) */
    double r_first;    /* first residual without a constraint jump (-1: none yet) */
    double r_best;     /* the best residual so far and its iteration */
    int it_best;
    double dun;        /* free-DOF norm of the last step taken */
} ntrack;

/* The exits at an iterate without a constraint jump: *done = 1 when it
 * converged, -1 when a stall made the hooks change their forces (the caller
 * reassembles); a failure (diverged, stagnated) is returned with its
 * reason. */
static stc_status newton_test(asp_solver *s, asp_nstat *ns, ntrack *t, int it, double rn,
                              double ref, double delta, int *done)
{
    const asp_options *o = &s->opt;
    double uscale = fmax(norm_sel(s, s->u, 0), delta);
    *done = 0;
    if (t->r_first < 0.0) t->r_first = rn;
    /* diverged: 1e8 times the first residual, or, when that one is already
     * converged (a predictor that hit the answer), past the reactions
     * themselves; measured: a ramp increment of the coated t/R .025
     * Eco/Esu 4 delta = 1 case started at ~1e-12 N and was cut back as
     * "diverged" at 5e-4 N (P = 1.3 N) */
    if (!(isfinite(rn) && rn <= 1e8 * fmax(t->r_first, o->rtol * ref)))
        return newton_exit(ns, ASP_OUTCOME_DIVERGED, "Newton %s at δ = %g mm (residual %.3g N)",
                           asp_outcome_str(ASP_OUTCOME_DIVERGED), delta, rn);
    /* (rn <= 1e-300: nothing loads the body yet) */
    if ((rn <= t->rtol * ref && (t->dun <= t->utol * uscale || rn <= 1e-3 * t->rtol * ref)) ||
        rn <= 1e-300) {
        *done = 1;
        return newton_exit(ns, ASP_OUTCOME_CONVERGED, NULL);
    }
    /* stagnation: the residual has not halved its best in NEWTON_STALL
     * iterations, so no linear rate gets it to the tolerance within
     * max_newton; the caller cuts the increment back now instead */
    if (rn < 0.5 * t->r_best) t->r_best = rn, t->it_best = it;
    /* a stall the forces of another model can settle (their discrete
     * states cycling; shear.c's stick law) gets NEWTON_STALL more */
    if (it - t->it_best >= NEWTON_STALL && s->hooks && s->hooks->stalled &&
        s->hooks->stalled(s->hooks->ctx, s) > 0) {
        t->r_best = rn, t->it_best = it;
        *done = -1; /* the forces changed: reassemble */
        return STC_OK;
    }
    if (it - t->it_best >= NEWTON_STALL)
        return newton_exit(ns, ASP_OUTCOME_STAGNATED, "Newton %s at δ = %g mm: residual %.3g, "
                           "not below half of %.3g in %d iterations (tolerance %.3g)",
                           asp_outcome_str(ASP_OUTCOME_STAGNATED), delta,
                           rn / fmax(ref, 1e-300), t->r_best / fmax(ref, 1e-300), NEWTON_STALL,
                           o->rtol);
    return STC_OK;
}

/* Backtracking line search from u0 = u along du (at most four halvings),
 * assembling with the tangent if want_K; a step that imposes a constraint
 * jump (cn > 0) is taken whole, since the residual before it does not see
 * the jump.  *alpha: the step length taken. */
static stc_status line_search(asp_solver *s, asp_nstat *ns, const double *du, double *u0,
                              double rn, double cn, int want_K, double delta, double *alpha)
{
    memcpy(u0, s->u, (size_t)s->ndof * sizeof *u0);
    double a = 1.0;
    for (int ls = 0;; ls++) {
        for (int i = 0; i < s->ndof; i++) s->u[i] = u0[i] + a * du[i];
        if (a == 1.0)
            for (int i = 0; i < s->ndof; i++)
                if (s->fixed[i]) s->u[i] = s->ubc[i];
        stc_status st = asp_assemble(s, want_K);
        double rt = st == STC_OK ? norm_sel(s, s->fint, 0) : INFINITY;
        if ((cn > 0.0 && st == STC_OK) || rt <= (1.0 - 1e-4 * a) * rn || ls == 4) {
            if (st != STC_OK)
                return newton_exit(ns, ASP_OUTCOME_INVERTED, "line search: %s at δ = %g mm",
                                   asp_outcome_str(ASP_OUTCOME_INVERTED), delta);
            *alpha = a;
            return STC_OK;
        }
        a *= 0.5;
    }
}

/* Newton with backtracking line search for the current constraints.  With
 * need_asm = 0 the caller guarantees fint (and, if k_fresh, K) belong to u.
 * A fresh tangent every newton_reuse iterations and at a constraint jump
 * (linear_step), the last factor in between (newton_solve). */
static stc_status newton(asp_solver *s, double delta, asp_nstat *ns, double *du, double *u0,
                         double loose, int need_asm)
{
    const asp_options *o = &s->opt;
    ntrack t = {o->rtol * loose, o->utol * loose, -1.0, INFINITY, 0, INFINITY};
    double *c = s->cvec;
    double r_prev = -1.0; /* the last iteration's residual, for the forcing term */
    int age = o->newton_reuse;
    if (need_asm || !s->k_fresh) STC_CALL(asp_assemble(s, 1));
    for (int it = 0;; it++) {
        double cn = constraint_defect(s, c);
        double rn = norm_sel(s, s->fint, 0), ref = norm_sel(s, s->fint, 1);
        if (cn == 0.0) {
            int done;
            STC_CALL(newton_test(s, ns, &t, it, rn, ref, delta, &done));
            if (done > 0) return STC_OK;
            if (done < 0) { /* fresh forces and tangent, then a fresh step */
                STC_CALL(asp_assemble(s, 1));
                age = o->newton_reuse;
                rn = norm_sel(s, s->fint, 0);
            }
        }
        if (it >= o->max_newton)
            return newton_exit(ns, ASP_OUTCOME_MAX_ITERATIONS, "Newton: %d iterations at "
                               "δ = %g mm, residual %.3g (tolerance %.3g)", it, delta,
                               rn / fmax(ref, 1e-300), o->rtol);
        if (age >= o->newton_reuse || cn > 0.0) {
            STC_CHECK(s->k_fresh, STC_ESOLVER, "solver: stale stiffness at δ = %g mm", delta);
            if (cn > 0.0) /* before the identity rows */
                asp_ls_matvec(s->ls, c, du, ASP_LS_TANGENT);
            double eta = cn > 0.0 ? 0.0 : r_prev > 0.0 ? forcing(rn / r_prev) : KRYLOV_EW_MAX;
            STC_CALL(linear_step(s, ns, c, cn, du, KRYLOV_ABS * o->rtol * ref, eta));
            age = 0;
        } else {
            STC_CALL(newton_solve(s, c, cn, du));
        }
        age++;
        ns->iters++;
        r_prev = cn == 0.0 ? rn : -1.0;
        double alpha = 1.0;
        STC_CALL(line_search(s, ns, du, u0, rn, cn, age >= o->newton_reuse, delta, &alpha));
        t.dun = alpha * norm_sel(s, du, 0);
    }
}

/* One increment to `delta`, iterating the active set, started from the
 * predictor u_conv + pred du_last (pred: this increment over the last
 * accepted one, in the caller's load parameter).  On failure the caller
 * restores the converged state. */
stc_status asp_newton_increment(asp_solver *s, double delta, double pred, asp_nstat *ns)
{
    int n = s->ndof;
    double *du = s->du_scr, *u0 = s->u0_scr;
    stc_status st = STC_OK;
    for (int i = 0; i < n; i++) s->u[i] = s->u_conv[i] + pred * s->du_last[i];
    /* nodes the predicted surface pushes through the flat touch now, all at
     * once (a pass each would cost a Newton solve each); from the unloaded
     * state the geometric overlap r < sqrt(2 R' δ) is twice the Hertz
     * contact area, so start from the Hertz radius sqrt(R' δ) instead
     * (Johnson 1985 §4.2; saves two passes, i.e. factorizations) */
    if (s->delta <= 0.0) asp_contact_hertz(s, delta);
    else asp_contact_update(s, delta, 1);
    double loose = fmin(1e4, 1e-4 / s->opt.rtol);
    for (int pass = 0;; pass++) {
        ns->passes++;
        if (pass >= s->opt.max_active_set) {
            ns->why = ASP_OUTCOME_CYCLING;
            st = STC_FAIL(STC_ENOCONV, "contact active set %s in %d passes at δ = %g mm "
                          "(cycling)", asp_outcome_str(ns->why), pass, delta);
            goto done;
        }
        /* settle the active set on loosely converged states first, then
         * converge fully and check it once more */
        asp_contact_dirichlet(s, delta);
        STC_CALL_GOTO(newton(s, delta, ns, du, u0, loose, pass == 0), st, done);
        int ch = asp_contact_update(s, delta, 0);
        if (ch == 0 && loose > 1.0) {
            loose = 1.0;
            STC_CALL_GOTO(newton(s, delta, ns, du, u0, loose, 0), st, done);
            ch = asp_contact_update(s, delta, 0);
        }
        if (ch == 0) break;
    }
done:
    return st;
}
