#!/bin/sh
# make bench fragment: Greenwood-Williamson summation.
#   statistical:   a 100-point mu_s-load curve (pressure-controlled: a Brent
#                  solve per point) in < 50 ms;
#   deterministic: < 0.1 s per load point over >= 10^6 summits (OpenMP
#                  reduction), pressure-controlled and separation-controlled;
#   a design sweep over those summits against one predict (reported).
# Times come from `surface predict --timing` (wall clock around the load
# points only; set-up -- reading the map, finding summits -- reported apart),
# best of 3 runs.
# Called as: 40-gw.sh CLI RESULTS_DIR; writes RESULTS_DIR/bench-gw.json.
set -eu
CLI=$1
OUT=$2
MAP="$OUT/bench-gw-4096.h5"
MAT="--E-su 200000 --E-ratio 2 --nu 0.3 --Y-su 1500 --Y-co 7000 --t-mm 1.5e-3"

# Best of 3 runs: the 2 cores are shared, and the minimum is the machine's
# speed rather than its neighbours'.
best3() {
    for k in 1 2 3; do "$@" --timing 2>&1 >/dev/null | timing; done |
        sort -g -k4 | head -n 1
}

# field N of the timing line: "timing: set-up S s (...); N load points in T s = P s per point; MODE, K summits"
timing() { sed -n 's/^timing: set-up \([^ ]*\) s .*; \([0-9]*\) load points in \([^ ]*\) s = \([^ ]*\) s per point; \([a-z]*\), \([0-9]*\) summits$/\1 \2 \3 \4 \6/p'; }

# shellcheck disable=SC2086
stat=$(best3 "$CLI" surface predict --summit-density 2300 --summit-radius 0.07 --sigma-s 3.9e-4 \
    $MAT --pressures 0.1:400:100)
# 4096^2 map with an exponential ACF (beta* = 4 um at a 1 um pixel): ~1.08e6 summits
"$CLI" surface synth --size 4096 --length 4 --rms 4e-4 --spectrum exponential \
    --corr-length 0.004 --seed 3 --no-png --out "$MAP" > /dev/null
# shellcheck disable=SC2086
detp=$(best3 "$CLI" surface predict --surface "$MAP" --mode deterministic $MAT --pressures 1:400:10)
# shellcheck disable=SC2086
dets=$(best3 "$CLI" surface predict --surface "$MAP" --mode deterministic $MAT --separations -1:3:10)
# a design sweep over the same summits (read once) against one predict of one
# design: three TiN thicknesses at three pressures (table data/tables/tin-on-steel.h5)
SW="--surface $MAP --mode deterministic --table data/tables/tin-on-steel.h5 --E-su 200000 --Y-su 1500 --nu 0.3 --E-ratio 2 --pressures 1,5,20"
wall() { s=$(date +%s.%N); "$@" > /dev/null 2>&1; e=$(date +%s.%N); awk -v s="$s" -v e="$e" "BEGIN { print e - s }"; }
# shellcheck disable=SC2086
sweep=$(for k in 1 2 3; do wall "$CLI" surface sweep $SW --t-mm 1e-3,1.5e-3,2e-3; done | sort -g | head -n 1)
# shellcheck disable=SC2086
one=$(for k in 1 2 3; do wall "$CLI" surface predict $SW --Y-co 7000 --t-mm 1.5e-3; done | sort -g | head -n 1)
rm -f "$MAP"

echo "$stat" "$detp" "$dets" "$sweep" "$one" | awk -v out="$OUT" '{
    st = $3; dp = $9; ds = $14; n = $10; sw = $16; one = $17
    printf "GW statistical: 100-point mu_s-load curve (pressure-controlled) in %.4f s (limit 0.05 s)\n", st
    printf "GW deterministic, %d summits: %.4f s per load point pressure-controlled, %.4f s separation-controlled (limit 0.1 s); set-up %.2f s\n", n, dp, ds, $6
    printf "surface sweep over the same summits: 3 TiN thicknesses x 3 pressures in %.2f s wall; one surface predict of one of them %.2f s (3 of them: %.2f s)\n", sw, one, 3 * one
    printf "{\"statistical_100_points_s\": %.5f, \"deterministic_summits\": %d, \"deterministic_per_pressure_point_s\": %.5f, \"deterministic_per_separation_point_s\": %.5f, \"deterministic_setup_s\": %.3f, \"sweep_3_designs_s\": %.3f, \"predict_1_design_s\": %.3f, \"limits_s\": {\"statistical_curve\": 0.05, \"deterministic_point\": 0.1}}\n", st, n, dp, ds, $6, sw, one > (out "/bench-gw.json")
    exit (st < 0.05 && dp < 0.1 && ds < 0.1 && n >= 1000000) ? 0 : 1
}'
