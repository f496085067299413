/* Hexahedral-mesh helpers shared by the 3D mesh tests (header-only). */
#ifndef STICTION_TESTS_HEX_UTIL_H
#define STICTION_TESTS_HEX_UTIL_H

#include <math.h>

#include "fe.h"

static inline void elem_coords(const asp_mesh *M, int e, double X[24])
{
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) X[3 * a + i] = M->x[3 * M->conn[8 * e + a] + i];
}

static inline double norm3(const double *x)
{
    return sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

/* Volume by 2x2x2 Gauss (exact for the trilinear map's Jacobian). */
static inline double hex_volume(const double X[24])
{
    static const double XI[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    double g = 1.0 / sqrt(3.0), V = 0.0;
    for (int q = 0; q < 8; q++) {
        double J[3][3] = {{0}};
        for (int a = 0; a < 8; a++) {
            double f[3], d[3];
            for (int i = 0; i < 3; i++) {
                f[i] = 0.5 * (1 + g * XI[q][i] * XI[a][i]);
                d[i] = 0.5 * XI[a][i];
            }
            double dn[3] = {d[0] * f[1] * f[2], f[0] * d[1] * f[2], f[0] * f[1] * d[2]};
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) J[i][j] += X[3 * a + i] * dn[j];
        }
        V += J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
             J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
             J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    }
    return V;
}

/* Local indices of the nodes of hex e among ids[n] as a bit mask; -1 if one
 * is absent. */
static inline int local_set(const asp_mesh *M, int e, const int *ids, int n)
{
    int mask = 0;
    for (int a = 0; a < n; a++) {
        int k = 0;
        while (k < 8 && M->conn[8 * e + k] != ids[a]) k++;
        if (k == 8) return -1;
        mask |= 1 << k;
    }
    return mask;
}

/* Whether a mask of n local nodes is a face (n = 4) or an edge (n = 2). */
static inline int is_face_or_edge(int mask, int n)
{
    static const int F[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (int f = 0; f < 6; f++) {
        if (n == 4 && mask == ((1 << F[f][0]) | (1 << F[f][1]) | (1 << F[f][2]) | (1 << F[f][3])))
            return 1;
        for (int a = 0; a < 4 && n == 2; a++)
            if (mask == ((1 << F[f][a]) | (1 << F[f][(a + 1) % 4]))) return 1;
    }
    return 0;
}

#endif
