#!/bin/sh
# make bench fragment (issue 3): work-precision tables of the asperity FE
# solver (error vs the finest mesh and the closed form, wall time, DOFs, peak
# memory from getrusage) for the Hertz case and for delta = 10 wc_su,
# t/R = 0.025, Eco/Esu = 2, stick; plus the wall time of a load curve.
# Called as: 20-asperity.sh CLI RESULTS_DIR.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-asperity.py" bench "$CLI" | tee "$OUT/bench-asperity.txt"
