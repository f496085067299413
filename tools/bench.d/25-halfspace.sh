#!/bin/sh
# make bench fragment: work-precision of the elastic half-space reference
# (stiction halfspace, surface/halfspace.c; docs/design.md §5.6).
# WSP sphere at 0.5 omega_c, full slip at tau_c = Y/sqrt(3): for 64, 128 and
# 256 cells, the preload against Hertz, the junction growth against the
# finest grid, CG iterations and wall time.  Called as: 25-halfspace.sh CLI
# RESULTS_DIR; writes RESULTS_DIR/bench-halfspace.txt.
set -eu
CLI=$1
OUT=$2
python3 - "$CLI" <<'PY' | tee "$OUT/bench-halfspace.txt"
import json, subprocess, sys, time
cli = sys.argv[1]
args = ["halfspace", "--R", "10.5", "--E-su", "74000", "--nu", "0.33", "--Y-su", "325",
        "--delta", "0.5", "--json"]
rows = []
for n in (64, 128, 256):
    t0 = time.monotonic()
    j = json.loads(subprocess.run([cli] + args + ["--cells", str(n)], capture_output=True,
                                  text=True, check=True).stdout)
    rows.append((n, j, time.monotonic() - t0))
fin = rows[-1][1]["area_growth"]
print("Half-space reference (WSP sphere, 0.5 wc, full slip): growth vs %d cells" % rows[-1][0])
print("%6s %10s %12s %10s %12s %8s %8s" % ("cells", "cell/a0", "P0 vs Hertz", "growth",
                                            "vs finest", "CG its", "wall s"))
for n, j, w in rows:
    print("%6d %9.2f%% %+11.4f%% %+9.3f%% %+11.3f%% %8d %8.2f" % (
        n, 100 * j["cell_mm"] / j["a_hertz_mm"], 100 * (j["P0_N"] / j["P_hertz_N"] - 1),
        100 * j["area_growth"], 100 * (j["area_growth"] - fin), j["iterations"], w))
PY
