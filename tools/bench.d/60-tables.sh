#!/bin/sh
# make bench fragment: the FE friction tables' cost per point (from the
# bundled tables' own records) and the normal step's share of a point (three
# asperity runs, about 2 minutes).  Called as: 60-tables.sh CLI RESULTS_DIR.
set -eu
python3 "$(dirname "$0")/../bench-tables.py" "$1" | tee "$2/bench-tables.txt"
