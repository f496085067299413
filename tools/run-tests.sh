#!/bin/sh
# Run every cmocka test program given on the command line, STC_TEST_JOBS of
# them at a time (default: the number of cores), in the order given (put
# the long ones first), and close with one aggregate line.  Each program's
# output is shown whole when it ends, with its wall time.
#
# A program still running after STC_TEST_TIMEOUT seconds (default 1200) is
# stopped and counted as failed, with the output it wrote.
#
# With more than one at a time every program runs on one thread
# (OMP_NUM_THREADS and OPENBLAS_NUM_THREADS = 1 unless set): two
# single-threaded programs on two cores take about the time of one, while a
# threaded solver gains 1.5x on two cores and loses more than that when it
# shares them.  Each program gets a scratch directory of its own as TMPDIR,
# removed with whatever it left there when the run ends; programs that start
# several processes of their own give each its own directory inside it.
set -u

if [ "${1:-}" = "--one" ]; then # worker: --one SCRATCH INDEX PROGRAM
    scratch=$2 i=$3 t=$4
    s=$(date +%s.%N)
    mkdir "$scratch/$i.tmp" || exit 1
    TMPDIR="$scratch/$i.tmp" timeout "${STC_TEST_TIMEOUT:-1200}" "$t" > "$scratch/$i.out" 2>&1
    rc=$?
    e=$(date +%s.%N)
    out="$scratch/$i.out"
    p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test(s)\./\1/p' "$out" | awk '{s+=$1} END {print s+0}')
    f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test(s), listed below:/\1/p' "$out" |
        awk '{s+=$1} END {print s+0}')
    b=0
    if [ "$rc" -eq 124 ]; then
        echo "!!! $t stopped after ${STC_TEST_TIMEOUT:-1200} s (STC_TEST_TIMEOUT)" >> "$out"
        b=1
    elif [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "!!! $t exited with status $rc without a cmocka summary" >> "$out"
        b=1
    fi
    echo "$p $f $b" > "$scratch/$i.sum"
    {
        flock 9
        echo "=== $t"
        cat "$out"
        awk -v t="$t" -v s="$s" -v e="$e" 'BEGIN {printf "--- %s: %.1f s\n", t, e - s}'
    } 9> "$scratch/lock"
    exit 0
fi

jobs=${STC_TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
case $jobs in '' | *[!0-9]*) jobs=0 ;; esac
if [ "$((jobs))" -lt 1 ]; then
    echo "run-tests.sh: STC_TEST_JOBS = '${STC_TEST_JOBS:-}' is not a whole number >= 1" >&2
    exit 2
fi
jobs=$((jobs))
if [ "$jobs" -gt 1 ]; then
    export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}" OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}"
fi
# The BLAS kernels the CLI runs (it picks faster ones where OpenBLAS does not
# know the CPU: `stiction --version`), for the test programs too, so that
# they and the CLI runs they start compute alike.  STICTION_CLI: the CLI, as
# the tests find it.
if [ -z "${OPENBLAS_CORETYPE:-}" ] && [ -x "${STICTION_CLI:-}" ]; then
    k=$("$STICTION_CLI" --version | sed -n 's/^BLAS: .*; kernels \([A-Za-z0-9]*\).*/\1/p')
    [ -z "$k" ] || export OPENBLAS_CORETYPE="$k"
fi
scratch=$(mktemp -d "${TMPDIR:-/tmp}/stiction-check-XXXXXX") || exit 1
trap 'rm -rf "$scratch"' EXIT
trap 'exit 130' INT TERM

s=$(date +%s.%N)
i=0
for t in "$@"; do
    i=$((i + 1))
    printf '%s %s\n' "$i" "$t"
done | xargs -r -P "$jobs" -n 2 sh "$0" --one "$scratch"
e=$(date +%s.%N)

passed=0; failed=0; broken=0; missing=0
i=0
for t in "$@"; do
    i=$((i + 1))
    if [ ! -f "$scratch/$i.sum" ]; then
        echo "!!! $t did not run"
        missing=$((missing + 1))
        continue
    fi
    read -r p f b < "$scratch/$i.sum"
    passed=$((passed + p)); failed=$((failed + f)); broken=$((broken + b))
done
failed=$((failed + broken + missing))
echo
awk -v n="$#" -v j="$jobs" -v s="$s" -v e="$e" \
    'BEGIN {printf "%d programs, %d at a time: %.1f s\n", n, j, e - s}'
echo "check: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
