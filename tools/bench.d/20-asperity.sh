#!/bin/sh
# make bench fragment: work-precision tables of the asperity FE
# solver (error vs the finest mesh and the closed form, wall time, DOFs, peak
# memory from getrusage) for the Hertz case and for delta = 10 wc_su,
# t/R = 0.025, Eco/Esu = 2, stick; the 3D half model's Hertz point (levels
# 0-1); the slip load curve to 60 wc (levels 0-2 and 3D level 0), raw and
# sawtooth-free (P_smooth) load against the finest level; P at 60 wc against
# the load increment for the midpoint rule and the radial return; the
# target curve (1:60:12 wc, P_smooth within 0.5 % of level 3 in < 1 s) for
# levels 0-2 and --elements-per-contact 8, its robustness for n = 6..12
# (error, mid-curve bias, run and CPU time), and the same curve in 3D (level
# 0, automatic and 4 steps per node entry, and with --grade-3d: < 30 s
# target); then the Newton-Krylov table
# (tools/bench-krylov.py).
# Called as: 20-asperity.sh CLI RESULTS_DIR.
set -eu
CLI=$1
OUT=$2
python3 "$(dirname "$0")/../validate-asperity.py" bench "$CLI" | tee "$OUT/bench-asperity.txt"
# Newton-Krylov vs a factorization per Newton step (3D level 0): factorizations,
# PCG iterations, wall time, and the agreement of the answers.
python3 "$(dirname "$0")/../bench-krylov.py" "$CLI" | tee "$OUT/bench-krylov.txt"
