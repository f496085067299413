#!/bin/sh
# make check: the dynamic symbols libstiction.so exports must be exactly the
# functions declared in include/stiction/*.h (include/stiction/export.h).
# Declarations are read by the compiler (-aux-info lists every prototype
# with its file), so a function declared without STC_API shows up as
# missing, and an internal function or variable the library leaks as extra.
# Environment: STC_SHARED (default lib/libstiction.so), STC_CC (default cc,
# a GCC: -aux-info).  Prints a cmocka-style summary for tools/run-tests.sh.
set -u
lib=${STC_SHARED:-lib/libstiction.so}
cc=${STC_CC:-cc}
name="exports of $lib = the functions of include/stiction/*.h"
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT

echo "[ RUN      ] $name"
fail() {
    printf '%s\n' "$@"
    echo "[  FAILED  ] $name"
    echo "[  FAILED  ] 1 test(s), listed below:"
    echo "[  FAILED  ] exports"
    exit 1
}

[ -r "$lib" ] || fail "$lib: not found (make all builds it)"
for h in include/stiction/*.h; do
    echo "#include \"stiction/${h##*/}\""
done > "$tmp/all.c"
$cc -std=c11 -Iinclude -fsyntax-only -aux-info "$tmp/aux.txt" "$tmp/all.c" 2> "$tmp/cc.err" ||
    fail "$cc could not read the public headers:" "$(cat "$tmp/cc.err")"
# /* include/stiction/status.h:29:NC */ extern const char *stc_strerror (stc_status);
sed -n 's|^/\* include/stiction/[^ ]* \*/ .*[ *]\([A-Za-z_][A-Za-z0-9_]*\) (.*|\1|p' \
    "$tmp/aux.txt" | sort -u > "$tmp/declared"
nm -D --defined-only "$lib" | awk '{print $NF}' | sort -u > "$tmp/exported"
[ -s "$tmp/declared" ] || fail "no function declarations found in include/stiction/*.h"

extra=$(comm -13 "$tmp/declared" "$tmp/exported")
missing=$(comm -23 "$tmp/declared" "$tmp/exported")
[ -z "$extra$missing" ] || fail \
    "exported by $lib but not declared in include/stiction/ (give it hidden visibility):" \
    "${extra:-  (none)}" \
    "declared in include/stiction/ but not exported (mark it STC_API, or define it):" \
    "${missing:-  (none)}"
echo "  $(wc -l < "$tmp/declared") functions declared, the same exported"
echo "[       OK ] $name"
echo "[  PASSED  ] 1 test(s)."
