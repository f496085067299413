#!/bin/sh
# make bench fragment: work-precision of mu_s (error vs the
# finest 3D level run, wall time, DOFs, Newton iterations, factorizations,
# ramp increments, peak memory) at omega/omega_c = 3 and 12 (homogeneous WSP
# sphere) and delta = 1 and 10 omega_c_su, t/R = 0.025, Eco/Esu = 2 (stick); at
# level 0 also with its surface nodes shifted by about half an element at the
# contact edge (n6.6: the node-placement spread, docs/design.md §4.5),
# with --junction nodes, the other side of the junction bracket, and with the
# outer shells uncoarsened (--shell-coarsen 0: the time saved).  Then the
# four-placement ensemble (--placements 4) at level 0 against the same at
# N = 8.5 for WSP 3 omega_c: the target as an ensemble (docs/design.md §4.6).
# Called as: 50-shear.sh CLI RESULTS_DIR.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../bench-shear.py" "$CLI" "${STICTION_SHEAR_LEVELS:-0,n6.6,0:nodes,0:c0,1}" | tee "$OUT/bench-shear.txt"
python3 "$(dirname "$0")/../bench-shear.py" "$CLI" "0:p4,n8.5:p4" "omega = 3 " | tee -a "$OUT/bench-shear.txt"
