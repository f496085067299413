#!/bin/sh
# make demo: the main job on bundled defaults.
set -eu
CLI=$1
"$CLI" formulas --delta 10
