#!/bin/sh
# make reproduce fragment: the thesis's Fig. 4.21 (mu_s versus P/Pc_su, nine
# cases) from the bundled FE friction table data/tables/thesis.h5 (a second
# or two; the table itself is `make tables`).  Called as: 40-table-fig4_21.sh
# CLI RESULTS_DIR; writes RESULTS_DIR/table/fig4_21.png and its data.
set -eu
python3 "$(dirname "$0")/../fig4_21_table.py" "$1" data/tables/thesis.h5 "$2/table"
