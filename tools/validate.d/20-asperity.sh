#!/bin/sh
# make validate fragment: full-size checks of the asperity FE
# solver -- Hertz with Richardson extrapolation over mesh levels 1-3 and the
# observed order, yield inception (slip vs Kogut & Etsion / Green, stick vs
# Brizmer 2006), coated first/second yield against the thesis's Table 4.2.
# Called as: 20-asperity.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-asperity.md; exits non-zero if a check fails.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-asperity.py" validate "$CLI" "$OUT/validate-asperity.md"
