#!/bin/sh
# make validate fragment: the bundled thesis-family FE friction table against
# FE runs at held-out points between its nodes, and the surface checks on it
# (stiffer coating, coated versus uncoated).  10 FE points, each with the
# table's two node placements and with eight, read from
# data/fe/table-heldout.csv (computed there once, about an hour of CPU, when
# missing; runs in progress are kept in RESULTS_DIR/tables/, so an interrupted
# validation resumes).
# Called as: 60-tables.sh CLI RESULTS_DIR; writes
# RESULTS_DIR/validate-tables.md; exits non-zero if a check fails.
set -eu
CLI=$1
OUT=$2
mkdir -p "$OUT/tables"
python3 "$(dirname "$0")/../validate-tables.py" "$CLI" "$OUT/tables" "$OUT/validate-tables.md"
