#!/bin/sh
# make validate fragment (numerical stability): the normal
# step and the shear ramp at the edges of the parameter space (Poisson's
# ratio 0.05 / 0.49, E/Y 100 / 10000, t/R 1e-4 ... 0.2, Eco/Esu 0.2 ... 50,
# tau_c 1 / 5000 MPa, delta 0.1 ... 100 wc, load control, a thin coating far
# stronger than its substrate); every case must converge to finite numbers or
# be refused by name.  Called as: 50-stress.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-stress.csv and validate-stress.md; exits non-zero if a
# case fails.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-stress.py" "$CLI" "$OUT/validate-stress.csv" "$OUT/validate-stress.md"
