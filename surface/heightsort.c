/* Summits sorted by height, highest first, for the deterministic GW sums.
 *
 * A least-significant-digit radix sort on 64-bit keys that order like the
 * heights (IEEE bits, sign folded), four passes of 16 bits, each skipped
 * when every key shares its digit.  It is stable, as glibc's qsort merge
 * sort with a height comparator was, and -0 ranks with +0, so the order (and
 * every sum taken in it) is the comparator's to the bit.  1.08 million
 * random heights: 0.12-0.13 s against qsort's 0.39 s (8- and 11-bit digits:
 * 0.13-0.25 s); a table prediction sorts its summits three times, which had
 * been most of its set-up after reading the map.  An input already in order
 * is left as it is after one pass over it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "srf_impl.h"
#include "stc_check.h"

typedef struct {
    uint64_t key;
    srf_zr v;
} keyed;

/* Unsigned key that grows as z falls: ascending key order is descending z. */
static uint64_t key_desc(double z)
{
    uint64_t u;
    if (z == 0.0) z = 0.0; /* -0 ranks with +0, as the comparator has it */
    memcpy(&u, &z, sizeof u);
    u = (u >> 63) ? ~u : u | UINT64_C(0x8000000000000000); /* ascending in z */
    return ~u;
}

stc_status srf_sort_desc(srf_zr *v, int n)
{
    int sorted = 1;
    for (int i = 1; i < n && sorted; i++) sorted = !(v[i - 1].z < v[i].z);
    if (sorted) return STC_OK;
    keyed *a = malloc((size_t)n * sizeof *a), *b = malloc((size_t)n * sizeof *b);
    size_t *count = malloc(65536 * sizeof *count);
    if (!a || !b || !count) {
        free(a), free(b), free(count);
        return STC_FAIL(STC_ENOMEM, "srf_gw: out of memory sorting %d summits", n);
    }
    for (int i = 0; i < n; i++) a[i] = (keyed){key_desc(v[i].z), v[i]};
    for (int shift = 0; shift < 64; shift += 16) {
        memset(count, 0, 65536 * sizeof *count);
        for (int i = 0; i < n; i++) count[(a[i].key >> shift) & 0xffff]++;
        if (count[(a[0].key >> shift) & 0xffff] == (size_t)n) continue; /* one digit */
        size_t at = 0;
        for (int d = 0; d < 65536; d++) {
            size_t c = count[d];
            count[d] = at;
            at += c;
        }
        for (int i = 0; i < n; i++) b[count[(a[i].key >> shift) & 0xffff]++] = a[i];
        keyed *t = a;
        a = b, b = t;
    }
    for (int i = 0; i < n; i++) v[i] = a[i].v;
    free(a), free(b), free(count);
    return STC_OK;
}
