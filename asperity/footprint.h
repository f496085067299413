/* The contact footprint of the tangential ramp (footprint.c; not
 * installed): node lines across the contact edge and the extent of the
 * sheared contact read from their gaps. */
#ifndef STICTION_FOOTPRINT_H
#define STICTION_FOOTPRINT_H

#include "solver_impl.h"

/* Surface nodes on one line from the axis: candidate index, distance from
 * the axis (ascending), gap when the ramp started, and room for the gaps
 * now. */
typedef struct asp_foot_line {
    int dir;    /* extent it reads: 0 lead (+x), 1 trail (-x), 2 side (+y) */
    double off; /* the line's offset across it: y (lead, trail) or x (side), mm */
    int hold;   /* 1: the reading is at least the last node in contact (rows) */
    int n;
    int *k;
    double *r, *g0, *g;
} asp_foot_line;

enum { ASP_FOOT_MAXLINES = 96 }; /* 32 per direction */

typedef struct asp_foot {
    double a0;  /* contact radius when the ramp started (the preload's), mm */
    int nline;
    asp_foot_line line[ASP_FOOT_MAXLINES];
} asp_foot;

/* The lines within rows a0 of the axis (rows 0: the three axis lines) that
 * cross the edge of solver s's contact now, with their gaps (f zeroed or
 * freed before); asp_foot_free frees them. */
stc_status asp_foot_init(asp_foot *f, const asp_solver *s, double a0, double rows);
void asp_foot_free(asp_foot *f);

/* The contact extent along +x, -x, +y from a0 and the gaps of s now, mm. */
void asp_foot_extent(const asp_foot *f, const asp_solver *s, double ext[3]);

#endif
