/* stiction — command-line entry point: dispatch to subcommands. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/auxv.h>
#include <unistd.h>

#include "cli.h"
#include "stiction/asperity.h"


static const cli_cmd commands[] = {
    {"formulas", "closed-form contact models (Hertz, yield inception, coated fits, WSP)",
     cli_formulas},
    {"surface", "rough surfaces: synth, stats, predict (stiction surface --help)", cli_surface},
    {"asperity", "FE model of one coated asperity: pressed (P, A, yield); --shear: sheared "
                 "to sliding (mu_s)",
     cli_asperity},
    {"table", "FE friction tables: build, info, query, merge (stiction table --help)", cli_table},
    {"halfspace", "elastic half-space reference: sphere on a rigid flat, full-slip junction growth",
     cli_halfspace},
    {NULL, NULL, NULL},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: stiction COMMAND [options]   (stiction COMMAND --help for details)\n"
               "       stiction --version              (the version and the BLAS kernels "
               "in use)\n\n"
               "Commands:\n");
    for (const cli_cmd *c = commands; c->name; c++) fprintf(f, "  %-12s %s\n", c->name, c->summary);
    fprintf(f, "\nUnits: mm, N, MPa throughout.\n");
}

/* Run on the BLAS kernels this CPU is fastest on (stiction/asperity.h:
 * asp_blas_kernels): OpenBLAS picks them when it is loaded, so where it fell
 * back to its generic ones and OPENBLAS_CORETYPE is not set, the program
 * starts again with it set (set it, to any kernels, to keep them).  Nothing
 * has run yet, so nothing is lost; if the new start fails, this one carries
 * on as it is.  Not when the kernel did not load this program through its
 * interpreter (AT_BASE 0: started as `ld.so stiction ...`, where
 * /proc/self/exe is ld.so), or without /proc. */
static void blas_kernels(char **argv)
{
    if (getenv("OPENBLAS_CORETYPE") || getauxval(AT_BASE) == 0) return;
    asp_blas_kernels k;
    asp_blas_kernels_get(&k);
    /* the file /proc/self/exe links to, not the link: the process keeps
     * its name (ps, top, kill by name) */
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (!k.suggested[0] || n <= 0) return;
    self[n] = '\0';
    if (setenv("OPENBLAS_CORETYPE", k.suggested, 1) != 0) return;
    execv(self, argv);
    unsetenv("OPENBLAS_CORETYPE");
}

static void version(void)
{
#ifdef STC_COMMIT
    printf("stiction %s (commit %s)\n", STC_VERSION, STC_COMMIT);
#else
    printf("stiction %s\n", STC_VERSION);
#endif
    asp_blas_kernels k;
    asp_blas_kernels_get(&k);
    printf("BLAS: %s%s\n", k.summary, getenv("OPENBLAS_CORETYPE") ? " (OPENBLAS_CORETYPE)" : "");
}

int main(int argc, char **argv)
{
    blas_kernels(argv);
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        version();
        return CLI_EXIT_OK;
    }
    cli_near near;
    cli_near_init(&near, argv[1]);
    for (const cli_cmd *c = commands; c->name; c++) {
        if (strcmp(argv[1], c->name) == 0) return c->run(c, argc - 2, argv + 2);
        cli_near_add(&near, c->name);
    }
    const char *guess = cli_near_best(&near);
    fprintf(stderr, "stiction: unknown command '%s'%s%s%s\n\n", argv[1],
            guess ? " (did you mean " : "", guess ? guess : "", guess ? "?)" : "");
    usage(stderr);
    return CLI_EXIT_USAGE;
}
