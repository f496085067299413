#!/bin/sh
# make bench fragment: FFT synthesis of a 4096² self-affine surface plus
# summit extraction must take < 3 s on the 2-core reference machine.
# Called as: 30-surface-synth.sh CLI RESULTS_DIR.  Times the two CLI steps
# (synthesis + HDF5 write; read + spectral moments + 8-neighbour summits) and
# writes RESULTS_DIR/bench-surface-synth.json.
set -eu
CLI=$1
OUT=$2
LIMIT=3.0
MAP="$OUT/bench-surface-4096.h5"

now() { date +%s.%N; }
t0=$(now)
"$CLI" surface synth --size 4096 --length 1 --spectrum self-affine --hurst 0.8 \
    --rms 0.001 --seed 1 --no-png --out "$MAP" > /dev/null
t1=$(now)
"$CLI" surface stats "$MAP" --json > "$OUT/bench-surface-stats.json"
t2=$(now)
summits=$(sed -n 's/^ *"summits": \([0-9]*\),*$/\1/p' "$OUT/bench-surface-stats.json")
rm -f "$MAP"
awk -v a="$t0" -v b="$t1" -v c="$t2" -v n="$summits" -v lim="$LIMIT" -v out="$OUT" 'BEGIN {
    s = b - a; t = c - b; tot = c - a
    printf "surface synth 4096^2: %.2f s (synthesis + HDF5 write); stats: %.2f s (%d summits); total %.2f s (limit %.1f s)\n", s, t, n, tot, lim
    f = out "/bench-surface-synth.json"
    printf "{\"grid\": 4096, \"synth_s\": %.3f, \"stats_s\": %.3f, \"total_s\": %.3f, \"summits\": %d, \"limit_s\": %.1f}\n", s, t, tot, n, lim > f
    exit (tot < lim) ? 0 : 1
}'
