#!/bin/sh
# make bench fragment: mu_s against the converged references of the held set
# (data/fe/references.csv): one default run, one with --edge-refine 2,
# --placements 2 and --placements 4, each with its error, whether its printed
# error covers it, wall and CPU time; the targets 2 % and 20 s (homogeneous) /
# 40 s (coated).  About 75 min on two cores with 16 references.
# Called as: 55-references.sh CLI RESULTS_DIR.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../bench-references.py" "$CLI" | tee "$OUT/bench-references.txt"
