#!/bin/sh
# make validate fragment: full-size checks of the surface layer --
# Nayak/McCool summit statistics over seeds of 2048^2 maps (8- and
# 4-neighbour rules), random-amplitude moments across seeds against their
# delta-method bound, and GW statistical vs deterministic sums on a 4096^2
# map.  The checks live in tools/validate-surface.py (CLI --json runs parsed
# by python3).  Called as: 30-surface.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-surface.md; exits non-zero if a check fails.
set -eu
CLI=$1
OUT=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
python3 "$(dirname "$0")/../validate-surface.py" "$CLI" "$tmp" "$OUT/validate-surface.md"
