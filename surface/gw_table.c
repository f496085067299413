/* The FE friction table points a Greenwood–Williamson prediction reads
 * (include/stiction/gw.h). */
#include <math.h>
#include <stdlib.h>

#include "stiction/gw.h"
#include "stc_check.h"

stc_status srf_gw_table_needs(srf_gw *g, const tbl_table *t, double E_ratio, int by_pressure,
                              const double *loads, int n, unsigned char *need, int *pending)
{
    STC_CHECK(g && t && loads && need && pending, STC_EINVAL,
              "srf_gw_table_needs: handle, table, loads, need and pending required");
    STC_CHECK(n >= 1, STC_EINVAL, "srf_gw_table_needs: n = %d: must be >= 1", n);
    *pending = 0;
    const double *w_ax;
    tbl_axis(t, 0, &w_ax);
    double w_lo = w_ax[0];
    for (int i = 0; i < n; i++) {
        srf_gw_point q;
        STC_CALL(by_pressure ? srf_gw_at_pressure(g, loads[i], &q)
                             : srf_gw_at_separation(g, loads[i], &q));
        if (!(q.pressure_MPa > 0) || !(q.delta_max_over_omega_c > 0)) continue;
        double w_hi = fmax(q.delta_max_over_omega_c, w_lo);
        int k = tbl_mark_needed(t, w_lo, w_hi, q.tR_min, q.tR_max, E_ratio, need);
        STC_CHECK(k >= 0, STC_EINVAL, "srf_gw_table_needs: load %g: contact state out of "
                  "bounds (delta/omega_c <= %g, t/R %g .. %g)", loads[i], w_hi, q.tR_min,
                  q.tR_max);
        *pending += k;
    }
    return STC_OK;
}
