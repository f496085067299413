#!/bin/sh
# make reproduce fragment: thesis Fig. 4.3, elastic P-omega curves of a coated sphere
# (Eco/Esu = 4, t/R = 0.001-0.009, slip) with the uncoated sphere and Hertz (6 FE runs),
# by tools/reproduce-asperity.py.  Called as: 20-asperity-fig4_3.sh CLI RESULTS_DIR;
# writes RESULTS_DIR/asperity/fig4_3.png, its CSV and fig4_3.txt (the deviations).
exec python3 "$(dirname "$0")/../reproduce-asperity.py" "$1" "$2/asperity" fig4_3
