#!/bin/sh
# make validate fragment: the homogeneous
# Wu-Shi-Polycarpou sphere under combined loading, mu_s against the WSP fit
# 0.3 coth(0.57 (omega/omega_c)^0.41) within 5 % for omega/omega_c in
# {0.5, 1, 3, 6, 12, 24, 48, 72}, 3D mesh level 0 (STICTION_SHEAR_LEVELS=0,1 adds the default mesh: very slow today), with wall times.
# Called as: 40-shear.sh CLI RESULTS_DIR; writes RESULTS_DIR/validate-shear.csv;
# exits non-zero if a run fails or misses the band.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-shear.py" "$CLI" "$OUT/validate-shear.csv" --levels "${STICTION_SHEAR_LEVELS:-0}"
