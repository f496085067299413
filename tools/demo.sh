#!/bin/sh
# make demo: the main job on bundled data.  Called as: demo.sh CLI
set -eu
CLI=$1
out=${RESULTS:-results}/demo
mkdir -p "$out"

# One hard-coated asperity from the closed-form fits: the thesis's reference
# grid (R = 10 mm, Esu = 200 GPa, E/Y = 1000 in both layers, nu = 0.32), a
# coating twice as stiff as the substrate, t/R = 0.025, pressed to 10 omega_c_su.
echo "== stiction formulas: coated asperity, t/R = 0.025, Eco/Esu = 2, delta = 10 omega_c_su"
"$CLI" formulas --t-over-R 0.025 --E-ratio 2 --delta 10

# The surface: a ground hardened-steel face (RMS 0.4 um, self-affine, fixed
# seed) synthesized and its summits found; the Greenwood-Williamson sums over
# the actual summits (each with its own radius, hence its own t/R) of the FE
# friction tables bundled in data/tables/: 1.5 um TiN on the steel, and the
# steel uncoated (the same materials in both layers).
echo
echo "== stiction surface: 1.5 um TiN on hardened steel versus the bare steel (examples/tin-on-steel-*.ini)"
"$CLI" surface synth --config examples/tin-on-steel-surface.ini --out "$out/surface.h5" \
    --png "$out/surface.png"
echo "-- coated: FE table data/tables/tin-on-steel.h5"
"$CLI" surface predict --config examples/tin-on-steel-predict.ini --surface "$out/surface.h5" \
    --table data/tables/tin-on-steel.h5 --out "$out/coated"
echo "-- uncoated: FE table data/tables/steel.h5"
"$CLI" surface predict --config examples/tin-on-steel-predict.ini --surface "$out/surface.h5" \
    --table data/tables/steel.h5 --E-ratio 1 --Y-co 1500 --out "$out/uncoated" > /dev/null
sh tools/demo-compare.sh "$out/coated/gw.csv" "$out/uncoated/gw.csv" "$out/compare.png"
echo "wrote $out/compare.png (mu_s and A/An versus nominal pressure, coated and uncoated, with"
echo "the error bands) and $out/coated/, $out/uncoated/ (gw.csv, gw.json, gw.png of each)"

# Which TiN: the same surface and table, 1, 1.5 and 2 um thick, with the
# film's modulus 300, 400 or 600 GPa (Eco/Esu 1.5, 2, 3; the table's family
# holds the coating's E/Y, so its hardness scales with it).  The bundled
# table covers these designs' summits at these loads.
echo
echo "== stiction surface sweep: TiN 1 / 1.5 / 2 um, Eco/Esu 1.5 / 2 / 3, on the same surface"
"$CLI" surface sweep --surface "$out/surface.h5" --mode deterministic \
    --table data/tables/tin-on-steel.h5 --E-su 200000 --Y-su 1500 --nu 0.3 \
    --t-mm 1e-3,1.5e-3,2e-3 --E-ratio 1.5,2,3 --pressures 1,5,20 --out "$out/sweep"
echo "wrote $out/sweep/ (sweep.csv, sweep.json, sweep.png: mu_s against the thickness)"
