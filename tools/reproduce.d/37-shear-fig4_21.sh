#!/bin/sh
# make reproduce fragment: thesis Fig. 4.21, mu_s versus P/Pc_su under load control,
# nine cases (45 FE runs), by tools/reproduce-shear.py (finished runs are kept and
# reused).  Called as: 37-shear-fig4_21.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/shear/fig4_21.png, its CSV and fig4_21.txt (what it printed).
exec python3 "$(dirname "$0")/../reproduce-shear.py" "$1" "$2/shear" --only fig4_21 \
    --mesh "${STICTION_SHEAR_MESH:-0}" --summary "$2/shear/fig4_21.txt"
