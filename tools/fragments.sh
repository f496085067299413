#!/bin/sh
# make bench|validate|reproduce: run every fragment in tools/KIND.d/ in name
# order.  Usage: fragments.sh KIND CLI
# Each fragment is called as: fragment.sh CLI RESULTS_DIR and must exit 0 on success.
#
# ONLY=NAME[,NAME...] (environment or make variable) runs the fragments that
# a NAME names.  A fragment's name is its file name without the leading
# number and .sh (reproduce.d/21-asperity-fig4_4.sh: asperity-fig4_4); NAME
# names it when it is that name or one of its words between '-' (asperity,
# fig4_4).  So ONLY=fig4_4 makes that one figure, ONLY=asperity the figures
# from the same FE runs.  A NAME that names no fragment is an error that
# lists the names.
set -u
KIND=$1
CLI=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
cd "$(dirname "$0")/.."
OUT=${RESULTS:-results}

# fragment name of a file: 21-asperity-fig4_4.sh -> asperity-fig4_4
frag_name() {
    b=$(basename "$1" .sh)
    case "$b" in [0-9]*-*) b=${b#*-} ;; esac
    echo "$b"
}

# names FRAGMENT_NAME WANTED: true when WANTED is the name or one of its words
names() {
    [ "$1" = "$2" ] && return 0
    case "-$1-" in *"-$2-"*) return 0 ;; esac
    return 1
}

selected() {
    [ -z "${ONLY:-}" ] && return 0
    n=$(frag_name "$1")
    for w in $(echo "$ONLY" | tr ',' ' '); do names "$n" "$w" && return 0; done
    return 1
}

for w in $(echo "${ONLY:-}" | tr ',' ' '); do
    hit=0
    for f in tools/$KIND.d/*.sh; do
        [ -e "$f" ] && names "$(frag_name "$f")" "$w" && hit=1
    done
    if [ $hit = 0 ]; then
        echo "make $KIND: ONLY=$w names no part; the parts are:" >&2
        for f in tools/$KIND.d/*.sh; do [ -e "$f" ] && echo "  $(frag_name "$f")" >&2; done
        exit 2
    fi
done

mkdir -p "$OUT"
# the program and the BLAS kernels every time and number below comes from
echo "=== $KIND with $("$CLI" --version | paste -sd ' ' -)"
status=0
for f in tools/$KIND.d/*.sh; do
    [ -e "$f" ] || continue
    selected "$f" || continue
    echo "=== $KIND: $f"
    start=$(date +%s.%N)
    if sh "$f" "$CLI" "$OUT"; then r=ok; else r=FAILED; status=1; fi
    end=$(date +%s.%N)
    awk -v f="$f" -v r="$r" -v a="$start" -v b="$end" 'BEGIN { printf "=== %s: %s (%.1f s)\n", f, r, b - a }'
done
exit $status
