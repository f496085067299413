/* The Krylov kernels of asperity/precond.c on a 3D solver's own factor and
 * tangent: the split supernodal solve and the split mat-vec give the same
 * bits on one thread as on two, the solve agrees with CHOLMOD's double
 * solve to float precision, the mat-vec with a plain one to rounding, and
 * the plan really splits the tree. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "linsolve_impl.h"
#include "solver_impl.h"
#include "stiction/formulas.h"

/* A 3D coated slip solver loaded past first yield (its last factor kept). */
static asp_solver *loaded_3d(void)
{
    stc_params p;
    asp_options o;
    asp_solver *s = NULL;
    asp_point pt;
    stc_params_default(&p);
    p.t_over_R = 0.025, p.E_ratio = 2.0;
    asp_options_default(&o);
    o.contact = ASP_CONTACT_SLIP, o.mesh_level = 0, o.geom = ASP_GEOM_3D, o.threads = 2;
    o.elements_per_contact = 4.0;
    stc_material su, co;
    stc_critical c;
    stc_params_materials(&p, &su, &co);
    assert_int_equal(stc_critical_eval(&su, p.R, &c), STC_OK);
    assert_int_equal(asp_solver_create(&p, &o, 3.0 * c.omega_c, &s), STC_OK);
    assert_int_equal(asp_solver_load(s, 3.0 * c.omega_c, &pt), STC_OK);
    return s;
}

/* Deterministic test vector in [-1, 1), zero on the fixed DOFs. */
static void fill(const asp_solver *s, double *v)
{
    unsigned long long x = 88172645463325252ULL;
    for (int i = 0; i < s->ndof; i++) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        v[i] = s->fixed[i] ? 0.0 : (double)(x >> 11) / 4503599627370496.0 - 1.0;
    }
}

static double rel_diff(const double *a, const double *b, int n)
{
    double d = 0.0, r = 0.0;
    for (int i = 0; i < n; i++) d += (a[i] - b[i]) * (a[i] - b[i]), r += b[i] * b[i];
    return sqrt(d / r);
}

/* Measured (16k DOFs): top 36.2 % of the factor's entries, parts 33.0 /
 * 30.8 % (critical path 69 %; 66 % with CHOLMOD's default supernode
 * amalgamation); see the printout for the two differences. */
static void test_precond(void **state)
{
    (void)state;
    asp_solver *s = loaded_3d();
    asp_linsolve *ls = s->ls;
    int n = s->ndof;
    assert_true(ls->fx_ok);
    double top, w[ASP_PREC_PARTS];
    int np = asp_prec_parts(ls, &top, w);
    double all = top + w[0] + w[1];
    printf("# precond: %d DOFs, factor entries: top %.1f %%, parts %.1f / %.1f %%\n", n,
           100 * top / all, 100 * w[0] / all, 100 * w[1] / all);
    assert_int_equal(np, 2);
    /* the critical path (top + heavier part) reads at most 3/4 of what one
     * thread reads, and the parts are balanced */
    assert_true(top + fmax(w[0], w[1]) < 0.75 * all);
    assert_true(fmax(w[0], w[1]) < 0.6 * (w[0] + w[1]));

    double *r = malloc(4 * (size_t)n * sizeof *r), *z1 = r + n, *z2 = z1 + n, *zd = z2 + n;
    assert_non_null(r);
    fill(s, r);
    ls->nthr = 1;
    asp_prec_solve(ls, r, z1);
    ls->nthr = 2;
    asp_prec_solve(ls, r, z2);
    assert_memory_equal(z1, z2, (size_t)n * sizeof *z1);
    cholmod_dense *b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &ls->cc);
    assert_non_null(b);
    memcpy(b->x, r, (size_t)n * sizeof *r);
    cholmod_dense *x = cholmod_solve(CHOLMOD_A, ls->L, b, &ls->cc);
    assert_non_null(x);
    memcpy(zd, x->x, (size_t)n * sizeof *zd);
    double es = rel_diff(z1, zd, n);
    cholmod_free_dense(&x, &ls->cc), cholmod_free_dense(&b, &ls->cc);

    /* mat-vec against the plain upper-triangle product */
    const int *Kp = ls->K->p, *Ki = ls->K->i;
    const double *Kx = ls->K->x;
    memset(zd, 0, (size_t)n * sizeof *zd);
    for (int j = 0; j < n; j++)
        for (int k = Kp[j]; k < Kp[j + 1]; k++) {
            zd[Ki[k]] += Kx[k] * r[j];
            if (Ki[k] != j) zd[j] += Kx[k] * r[Ki[k]];
        }
    ls->nthr = 1;
    asp_tangent_matvec(ls, r, z1, ASP_LS_K);
    ls->nthr = 2;
    asp_tangent_matvec(ls, r, z2, ASP_LS_K);
    assert_memory_equal(z1, z2, (size_t)n * sizeof *z1);
    double em = rel_diff(z1, zd, n);
    printf("# precond: float solve vs CHOLMOD %.1e, mat-vec vs plain %.1e\n", es, em);
    assert_true(es < 1e-4);
    assert_true(em < 1e-13);
    free(r);
    asp_solver_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_precond)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
