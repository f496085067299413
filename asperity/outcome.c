/* Outcomes of the solver's iterative loops in words (asp_outcome,
 * include/stiction/asperity.h).  A file of its own: every loop (Newton,
 * Krylov, active set, load stepping, the ramp) reports through it, and it
 * depends on nothing. */
#include "stiction/asperity.h"

const char *asp_outcome_str(asp_outcome o)
{
    static const char *const text[] = {
        [ASP_OUTCOME_NONE] = "not run",
        [ASP_OUTCOME_CONVERGED] = "converged",
        [ASP_OUTCOME_MECHANISM] = "plastic mechanism",
        [ASP_OUTCOME_DIVERGED] = "diverged",
        [ASP_OUTCOME_STAGNATED] = "stagnated",
        [ASP_OUTCOME_MAX_ITERATIONS] = "iteration limit",
        [ASP_OUTCOME_CYCLING] = "did not settle",
        [ASP_OUTCOME_INVERTED] = "element inverted",
        [ASP_OUTCOME_NOT_POSDEF] = "matrix not positive definite",
        [ASP_OUTCOME_SOLVER_FAILED] = "numerical failure",
        [ASP_OUTCOME_CUTBACK_LIMIT] = "cut-back limit",
        [ASP_OUTCOME_GAVE_UP] = "gave up",
        [ASP_OUTCOME_STOPPED] = "stopped by the caller",
        [ASP_OUTCOME_FAILED] = "failed",
    };
    if ((int)o < 0 || (size_t)o >= sizeof text / sizeof *text) return "unknown outcome";
    return text[o];
}
