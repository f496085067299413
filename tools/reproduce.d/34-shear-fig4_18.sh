#!/bin/sh
# make reproduce fragment: thesis Fig. 4.18, the coated grid's Q/Pc_su versus
# ux/omega_c_su at t/R = 0.05 (12 FE runs), by tools/reproduce-shear.py (finished runs
# are kept and reused).  Called as: 34-shear-fig4_18.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/shear/fig4_18.png, its CSV and fig4_18.txt (what it printed).
exec python3 "$(dirname "$0")/../reproduce-shear.py" "$1" "$2/shear" --only fig4_18 \
    --mesh "${STICTION_SHEAR_MESH:-0}" --summary "$2/shear/fig4_18.txt"
