#!/bin/sh
# make reproduce fragment: thesis Fig. 4.4, L/Lc2 versus delta/delta_c2 of a coated
# sphere (t/R = 0.05, Eco/Esu = 2-10, stick) against Ronen et al. (2017) (5 FE runs), by
# tools/reproduce-asperity.py.  Called as: 21-asperity-fig4_4.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/asperity/fig4_4.png, its CSV and fig4_4.txt (the deviations).
exec python3 "$(dirname "$0")/../reproduce-asperity.py" "$1" "$2/asperity" fig4_4
