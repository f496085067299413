/* Which BLAS kernels the solver runs on, and which this CPU would run
 * faster (asperity.h: asp_blas_kernels_get).  Reads only: OpenBLAS chose
 * its kernels when it was loaded. */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "stiction/asperity.h"

/* OpenBLAS extensions (its cblas.h is not on the default include path) */
char *openblas_get_corename(void);
char *openblas_get_config(void);

static void copy(char *dst, size_t n, const char *src)
{
    snprintf(dst, n, "%s", src ? src : "");
}

/* The kernels OpenBLAS's dynamic dispatch falls back to for a CPU model it
 * does not know (0.3.21: Prescott, SSE3 only). */
static int generic(const char *core)
{
    return strcasecmp(core, "prescott") == 0;
}

/* The fastest kernel family of OpenBLAS this CPU can run.  SkylakeX needs
 * AVX-512 F, CD, BW, DQ and VL; Haswell AVX2 and FMA. */
static const char *best_for_cpu(void)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512vl"))
        return "SkylakeX";
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
    return "";
}

void asp_blas_kernels_get(asp_blas_kernels *out)
{
    memset(out, 0, sizeof *out);
    copy(out->in_use, sizeof out->in_use, openblas_get_corename());
    copy(out->config, sizeof out->config, openblas_get_config());
    if (generic(out->in_use)) copy(out->suggested, sizeof out->suggested, best_for_cpu());
    snprintf(out->summary, sizeof out->summary, "%s; kernels %s", out->config, out->in_use);
}
