#!/bin/sh
# make reproduce fragment: thesis Fig. 4.8, the homogeneous sphere's Q/Pc versus
# ux/omega_c at four preloads (4 FE runs), by tools/reproduce-shear.py (finished runs
# are kept and reused).  Called as: 30-shear-fig4_8.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/shear/fig4_8.png, its CSV and fig4_8.txt (what it printed).
exec python3 "$(dirname "$0")/../reproduce-shear.py" "$1" "$2/shear" --only fig4_8 \
    --mesh "${STICTION_SHEAR_MESH:-0}" --summary "$2/shear/fig4_8.txt"
