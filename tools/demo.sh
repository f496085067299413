#!/bin/sh
# make demo: the main job on bundled defaults.  Called as: demo.sh CLI
set -eu
CLI=$1

# Closed-form models (SPEC §3-§5) for one hard-coated asperity of the thesis's
# reference grid: R = 10 mm, Esu = 200 GPa, E/Y = 1000 in both layers,
# nu = 0.32, a coating twice as stiff as the substrate, t/R = 0.025, pressed
# to 10 omega_c_su.  (The surface-level prediction will follow this block.)
demo_formulas() {
    echo "== stiction formulas: coated asperity, t/R = 0.025, Eco/Esu = 2, delta = 10 omega_c_su"
    "$CLI" formulas --t-over-R 0.025 --E-ratio 2 --delta 10
}

demo_formulas
