#!/bin/sh
# make tables: build the FE friction tables of data/tables/ (resuming: the
# points a file or its journal holds are kept, so on the bundled files this
# only computes what they lack).  Usage: tables.sh CLI [DIR]
# DIR (default data/tables) may be an empty directory for a build from
# scratch.  Uses every core: mpirun -n NPROC when Open MPI's mpirun is there
# (one process per point; the numbers do not depend on the process count),
# else --jobs NPROC in one process.
set -eu
CLI=$1
DIR=${2:-data/tables}
mkdir -p "$DIR"
n=$(nproc 2>/dev/null || echo 1)
build() { # build NAME CONFIG
    echo "== $DIR/$1.h5 from $2"
    start=$(date +%s)
    if [ "$n" -gt 1 ] && command -v mpirun > /dev/null 2>&1; then
        mpirun -n "$n" "$CLI" table build --config "$2" --out "$DIR/$1.h5"
    else
        "$CLI" table build --config "$2" --out "$DIR/$1.h5" --jobs "$n"
    fi
    echo "== $DIR/$1.h5: $(( $(date +%s) - start )) s"
}
build thesis examples/thesis-table.ini
build steel examples/steel-table.ini
build tin-on-steel examples/tin-on-steel-table.ini
