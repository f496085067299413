#!/bin/sh
# make reproduce fragment: thesis Fig. 4.19, delta = omega_c_su, Eco/Esu = 2, the three
# t/R and the homogeneous sphere (4 FE runs, those of Figs. 4.16-4.18 at delta =
# omega_c_su), by tools/reproduce-shear.py (finished runs are kept and reused).  Called
# as: 35-shear-fig4_19.sh CLI RESULTS_DIR; writes RESULTS_DIR/shear/fig4_19.png, its CSV
# and fig4_19.txt (what it printed).
exec python3 "$(dirname "$0")/../reproduce-shear.py" "$1" "$2/shear" --only fig4_19 \
    --mesh "${STICTION_SHEAR_MESH:-0}" --summary "$2/shear/fig4_19.txt"
