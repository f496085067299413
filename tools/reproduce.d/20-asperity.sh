#!/bin/sh
# make reproduce fragment: thesis Fig. 4.3 (coated elastic P-omega
# curves with the uncoated sphere) and Figs. 4.4-4.5 (L/Lc2, A/Ac2 versus
# delta/delta_c2 against the Ronen relations), from the asperity FE solver.
# Called as: 20-asperity.sh CLI RESULTS_DIR; writes RESULTS_DIR/asperity/.
set -eu
CLI=$1
OUT=$2
mkdir -p "$OUT/asperity"
python3 "$(dirname "$0")/../reproduce-asperity.py" "$CLI" "$OUT/asperity" > "$OUT/asperity/summary.txt"
cat "$OUT/asperity/summary.txt"
