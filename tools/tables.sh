#!/bin/sh
# make tables: build the FE friction tables of data/tables/ (resuming: the
# points a file or its journal holds are kept, so on the bundled files this
# only computes what they lack).  Usage: tables.sh CLI [DIR]
# DIR (default data/tables) may be an empty directory for a build from
# scratch.  Uses every core of this machine in one process (--jobs NPROC):
# the normal grid's curves and then the points, NPROC at a time (many
# machines: mpirun or --shard, README).
set -eu
CLI=$1
DIR=${2:-data/tables}
mkdir -p "$DIR"
n=$(nproc 2>/dev/null || echo 1)
build() { # build NAME CONFIG
    echo "== $DIR/$1.h5 from $2"
    start=$(date +%s)
    "$CLI" table build --config "$2" --out "$DIR/$1.h5" --jobs "$n"
    echo "== $DIR/$1.h5: $(( $(date +%s) - start )) s"
}
build thesis examples/thesis-table.ini
build steel examples/steel-table.ini
build tin-on-steel examples/tin-on-steel-table.ini
