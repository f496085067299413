/* Private layout of a friction table (include/stiction/table.h), shared by
 * table.c (the handle), table_io.c (HDF5), table_build.c (sweeps and the
 * journal) and table_interp.c (interpolation and the asperity model). */
#ifndef STICTION_TABLE_IMPL_H
#define STICTION_TABLE_IMPL_H

#include "stiction/table.h"
#include "table_fit.h"

/* Stored format (docs/table-format.md); a reader refuses other versions. */
#define TBL_FORMAT_NAME "stiction friction table"
#define TBL_FORMAT_VERSION 1

/* The reference sphere every point is computed on (the response is
 * independent of both, include/stiction/table.h). */
#define TBL_REF_R_MM 10.0
#define TBL_REF_E_SU_MPA 200000.0

struct tbl_table {
    tbl_family fam;
    tbl_numerics num;
    int n[3];          /* axis lengths: w, t/R, Eco/Esu */
    double *ax[3];     /* [n[k]] */
    tbl_point *pt;     /* [n[2]][n[1]][n[0]] */
    char command[512]; /* provenance: how it was built */
    double build_wall_s;
    tbl_gp *gp;        /* μs surrogate, NULL until tbl_fit */
    tbl_fit_info fit;
};

/* Parameters of the reference sphere for a point of family f. */
void tbl_point_params(const tbl_family *f, double t_over_R, double E_ratio, stc_params *p);

/* Index of the axis node at or below x (clamped to [0, n-2]) and the linear
 * weight of the node above in ln x (0..1 inside; clamped outside). */
int tbl_bracket(const double *ax, int n, double x, double *frac);

/* 64-bit FNV-1a of the build's definition (family, numerics, axes): the
 * journal's header, so a journal is only ever read by its own build. */
unsigned long long tbl_build_hash(const tbl_table *t);

#endif
