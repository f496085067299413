#!/bin/sh
# make validate fragment: the homogeneous Wu-Shi-Polycarpou sphere under
# combined loading, mu_s of four node placements compared with the WSP fit
# 0.3 coth(0.57 (omega/omega_c)^0.41) (5 %) for omega/omega_c in
# {0.5, 1, 3, 6, 12, 24, 48, 72}, 3D mesh level 0 (STICTION_SHEAR_LEVELS=0,1
# adds the default mesh, about four times the cost), with wall times; the
# single run (member 0) against the same fit as a target.
# Called as: 40-shear.sh CLI RESULTS_DIR; writes RESULTS_DIR/validate-shear.csv
# and validate-shear.md; exits non-zero if a run fails.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-shear.py" "$CLI" "$OUT/validate-shear.csv" \
    "$OUT/validate-shear.md" --levels "${STICTION_SHEAR_LEVELS:-0}"
