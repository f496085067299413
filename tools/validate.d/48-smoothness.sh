#!/bin/sh
# make validate fragment: mu_s of single shear runs of the WSP sphere at 20
# log-spaced interferences (0.5 to 60 omega_c), default numerics and the edge
# band (--edge-refine 2), its point-to-point wiggle as run and under other
# inception readings of the same ramps.  The runs are kept in
# RESULTS_DIR/smoothness-runs: a second call with the same program reuses them.
# Called as: 48-smoothness.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-smoothness.csv and validate-smoothness.md.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-smoothness.py" "$CLI" "$OUT/validate-smoothness.csv" \
    "$OUT/validate-smoothness.md"
