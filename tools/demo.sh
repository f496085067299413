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

# Surface level (SPEC §7): the bundled example of examples/ -- a ground
# hardened-steel face (RMS 0.4 um, self-affine, fixed seed) carrying a 1.5 um
# TiN coating -- synthesized, its summits found, and the Greenwood-Williamson
# sum over the actual summits (each with its own radius and t/R) giving mu_s
# and the real contact area versus nominal pressure, with a PNG.
demo_surface() {
    out=${RESULTS:-results}/demo
    mkdir -p "$out"
    echo
    echo "== stiction surface: 1.5 um TiN on hardened steel, ground surface (examples/tin-on-steel-*.ini)"
    "$CLI" surface synth --config examples/tin-on-steel-surface.ini --out "$out/surface.h5" \
        --png "$out/surface.png"
    "$CLI" surface predict --config examples/tin-on-steel-predict.ini --surface "$out/surface.h5" \
        --out "$out"
    echo "-- the same with the coating's properties in the closed-form model (the other bound)"
    "$CLI" surface predict --config examples/tin-on-steel-predict.ini --surface "$out/surface.h5" \
        --layer coating --pressures 1,10,100 | tail -n 4
    echo "wrote $out/gw.csv, $out/gw.json, $out/gw.png (mu_s and A/An vs nominal pressure)"
}

demo_formulas
demo_surface
