#!/bin/sh
# make reproduce fragment: thesis Fig. 4.5, A/Ac2 versus delta/delta_c2: the 5 FE runs
# of Fig. 4.4 (reused from RESULTS_DIR/asperity/runs/ when there) against Ronen et al.
# (2017), by tools/reproduce-asperity.py.  Called as: 22-asperity-fig4_5.sh CLI
# RESULTS_DIR; writes RESULTS_DIR/asperity/fig4_5.png, its CSV and fig4_5.txt (the
# deviations).
exec python3 "$(dirname "$0")/../reproduce-asperity.py" "$1" "$2/asperity" fig4_5
