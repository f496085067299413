#!/bin/sh
# make reproduce fragment: thesis Figs. 4.8, 4.10 (homogeneous WSP
# sphere under combined loading) and 4.16-4.21 (coated grid: Q-ux curves and
# mu_s under load control) from the 3D FE solver's tangential step.  About
# 80 combined-loading runs; each finished run is kept in
# RESULTS_DIR/shear/runs/, so an interrupted reproduce resumes.  Runs two
# at a time (STICTION_JOBS).  3D mesh level STICTION_SHEAR_MESH, default 0
# (coarse: the default level 1 costs too much per run today).
# Called as: 30-shear.sh CLI RESULTS_DIR; writes RESULTS_DIR/shear/.
set -eu
CLI=$1
OUT=$2
mkdir -p "$OUT/shear"
rc=0
python3 "$(dirname "$0")/../reproduce-shear.py" "$CLI" "$OUT/shear" --mesh "${STICTION_SHEAR_MESH:-0}" > "$OUT/shear/summary.txt" || rc=$?
cat "$OUT/shear/summary.txt"
exit $rc
