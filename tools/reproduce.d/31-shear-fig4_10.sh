#!/bin/sh
# make reproduce fragment: thesis Fig. 4.10, the homogeneous sphere's mu_s versus
# omega/omega_c (0.5-72) against the WSP fit (8 FE runs, the 4 of Fig. 4.8 among them),
# by tools/reproduce-shear.py (finished runs are kept and reused).  Called as:
# 31-shear-fig4_10.sh CLI RESULTS_DIR; writes RESULTS_DIR/shear/fig4_10.png, its CSV and
# fig4_10.txt (what it printed).
exec python3 "$(dirname "$0")/../reproduce-shear.py" "$1" "$2/shear" --only fig4_10 \
    --mesh "${STICTION_SHEAR_MESH:-0}" --summary "$2/shear/fig4_10.txt"
