#!/bin/sh
# make bench|validate|reproduce: run every fragment in tools/KIND.d/ in name
# order.  Usage: fragments.sh KIND CLI
# Each fragment is called as: fragment.sh CLI RESULTS_DIR and must exit 0 on success.
# ONLY=WORD (environment or make variable) runs the fragments whose file name
# contains WORD, e.g. make reproduce ONLY=fig4_21.
set -u
KIND=$1
CLI=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
cd "$(dirname "$0")/.."
OUT=${RESULTS:-results}
mkdir -p "$OUT"
status=0
for f in tools/$KIND.d/*.sh; do
    [ -e "$f" ] || continue
    case "$(basename "$f")" in *"${ONLY:-}"*) ;; *) continue ;; esac
    echo "=== $KIND: $f"
    start=$(date +%s.%N)
    if sh "$f" "$CLI" "$OUT"; then r=ok; else r=FAILED; status=1; fi
    end=$(date +%s.%N)
    awk -v f="$f" -v r="$r" -v a="$start" -v b="$end" 'BEGIN { printf "=== %s: %s (%.1f s)\n", f, r, b - a }'
done
exit $status
