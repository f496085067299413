#!/bin/sh
# make validate fragment: the default single shear run (no numerical option)
# against the stored converged references of the held set
# (data/fe/references.csv: four node placements one full refinement finer,
# made by tools/references.py): its error and whether its printed error
# estimate covers it; the 2 % goal as a target.
# Called as: 42-references.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-references.csv and validate-references.md.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-references.py" "$CLI" "$OUT/validate-references.csv" \
    "$OUT/validate-references.md"
