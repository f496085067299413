#!/bin/sh
# Run every cmocka test program given on the command line, show each
# program's own summary and wall time, and close with one aggregate line.
set -u
passed=0; failed=0; broken=0
for t in "$@"; do
    echo "=== $t"
    s=$(date +%s.%N)
    out=$("$t" 2>&1); rc=$?
    e=$(date +%s.%N)
    printf '%s\n' "$out"
    awk -v t="$t" -v s="$s" -v e="$e" 'BEGIN {printf "--- %s: %.1f s\n", t, e - s}'
    p=$(printf '%s\n' "$out" | sed -n 's/^\[  PASSED  \] \([0-9]*\) test(s)\./\1/p' | awk '{s+=$1} END {print s+0}')
    f=$(printf '%s\n' "$out" | sed -n 's/^\[  FAILED  \] \([0-9]*\) test(s), listed below:/\1/p' | awk '{s+=$1} END {print s+0}')
    passed=$((passed + p)); failed=$((failed + f))
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "!!! $t exited with status $rc without a cmocka summary"
        broken=$((broken + 1)); failed=$((failed + 1))
    fi
done
echo
echo "check: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$broken" -eq 0 ]
