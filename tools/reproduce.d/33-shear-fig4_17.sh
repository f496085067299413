#!/bin/sh
# make reproduce fragment: thesis Fig. 4.17, the coated grid's Q/Pc_su versus
# ux/omega_c_su at t/R = 0.025 (12 FE runs), by tools/reproduce-shear.py (finished runs
# are kept and reused).  Called as: 33-shear-fig4_17.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/shear/fig4_17.png, its CSV and fig4_17.txt (what it printed).
exec python3 "$(dirname "$0")/../reproduce-shear.py" "$1" "$2/shear" --only fig4_17 \
    --mesh "${STICTION_SHEAR_MESH:-0}" --summary "$2/shear/fig4_17.txt"
