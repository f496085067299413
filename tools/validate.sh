#!/bin/sh
# make validate: run every fragment in tools/validate.d/ in name order.
# Each fragment is called as: fragment.sh CLI RESULTS_DIR and must exit 0 on success.
set -u
CLI=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
cd "$(dirname "$0")/.."
OUT=${RESULTS:-results}
mkdir -p "$OUT"
status=0
for f in tools/validate.d/*.sh; do
    [ -e "$f" ] || continue
    echo "=== validate: $f"
    start=$(date +%s.%N)
    if sh "$f" "$CLI" "$OUT"; then r=ok; else r=FAILED; status=1; fi
    end=$(date +%s.%N)
    awk -v f="$f" -v r="$r" -v a="$start" -v b="$end" 'BEGIN { printf "=== %s: %s (%.1f s)\n", f, r, b - a }'
done
exit $status
