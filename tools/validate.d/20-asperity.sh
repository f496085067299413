#!/bin/sh
# make validate fragment: full-size checks of the asperity FE
# solver -- Hertz against the converged model and the closed form, yield
# inception (slip against the Hertz stress field; stick against its own
# converged value and CalculiX, compared with Brizmer 2006), coated first and
# second yield compared with the Ronen fits of the thesis's Table 4.2.
# Called as: 20-asperity.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-asperity.md; exits non-zero if a check fails (a fit's
# disagreement is a finding, not a failure).
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-asperity.py" validate "$CLI" "$OUT/validate-asperity.md"
