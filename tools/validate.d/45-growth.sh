#!/bin/sh
# make validate fragment: the elastic junction growth of the FE
# tangential step against the elastic half-space boundary elements
# (stiction halfspace), WSP sphere kept elastic at 0.5, 1 and 3 omega_c, FE at
# two node placements (--elements-per-contact 6 and 6.6), 3 % band on the area.
# Called as: 45-growth.sh CLI RESULTS_DIR; writes RESULTS_DIR/validate-growth.csv
# and validate-growth.md.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-growth.py" "$CLI" "$OUT/validate-growth.csv" "$OUT/validate-growth.md"
