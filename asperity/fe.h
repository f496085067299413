/* Internal finite-element building blocks of the asperity solver (not
 * installed).  Shared contract between mesh generators, element kernels,
 * the material kernel and the solver.
 *
 * Coordinates: the sphere's axis is z, the centre of the substrate sphere is
 * the origin, the top of the outer (coated) surface is at z = R' = R + t and
 * the base plane z = 0 is fixed.  The rigid flat sits at z = R' - δ.
 *   axisymmetric (dim 2): (r, z), r >= 0; u_r = 0 on the axis.
 *   3D half model (dim 3): (x, y, z) with y >= 0; the tangential load is
 *   along x, and the symmetry plane y = 0 has u_y = 0.
 * Voigt order for stress/strain: [xx, yy, zz, xy, yz, zx] with engineering
 * shear strains.  In the axisymmetric case the six slots hold
 * [rr, zz, θθ, rz, 0, 0].
 * Small-strain kinematics: adequate for δ/R below about 1e-2 (docs/design.md §2.1).
 */
#ifndef STICTION_FE_H
#define STICTION_FE_H

#include "stiction/params.h"
#include "stiction/status.h"

/* ---- mesh ------------------------------------------------------------- */

enum {
    ASP_NODE_BASE = 1, /* on the fixed base plane z = 0 */
    ASP_NODE_AXIS = 2, /* on the axis (axisymmetric: u_r = 0) */
    ASP_NODE_SYM = 4,  /* on the symmetry plane y = 0 (3D: u_y = 0) */
    ASP_NODE_TOP = 8   /* on the outer spherical surface near the top: contact candidate */
};

enum { ASP_REGION_SUBSTRATE = 0, ASP_REGION_COATING = 1 };

typedef struct asp_mesh {
    int dim;              /* 2 = axisymmetric, 3 = half model */
    int nnode, nelem, nen;/* nen = 4 (quad4) or 8 (hex8) */
    double *x;            /* [nnode][dim] coordinates, mm */
    int *conn;            /* [nelem][nen], counter-clockwise / positive Jacobian */
    int *region;          /* [nelem] ASP_REGION_* */
    unsigned char *flags; /* [nnode] ASP_NODE_* bits */
    /* Hanging nodes (3D shell coarsening, mesh3d.c; the edge band,
     * refine3d.c): node hang[k] is not an unknown; its displacement is
     * sum_a hang_w[4k+a] u(hang_m[4k+a]) over its masters (hang_m = -1 for
     * unused slots; weights sum to 1; a master is never itself hanging).
     * Its coordinates are the same average of the masters', so the fine
     * elements that use it conform to the coarse face it lies on, except on
     * the outer sphere and the coating interface, where the band's are
     * moved radially onto the sphere (h²/(8R) off the chord).  nhang = 0 and
     * NULL arrays when there are none (the band's may be allocated). */
    int nhang;
    int *hang;            /* [nhang] node ids */
    int *hang_m;          /* [nhang][4] master node ids or -1 */
    double *hang_w;       /* [nhang][4] weights */
} asp_mesh;

/* What to mesh and how finely. */
typedef struct asp_mesh_spec {
    double R;       /* substrate radius, mm */
    double t;       /* coating thickness, mm (0 = uncoated) */
    double a_max;   /* largest expected contact radius, mm: sets the fine zone */
    int level;      /* resolution: 0 coarse, 1 default, 2 fine, 3+ finer */
    double n;       /* 3D: elements across a_max, overrides level (an equivalent
                       level log2(n / 6) also scales the shells); 0 = 6 2^level */
    int coarsen;    /* 3D: 2:1 angular coarsenings of the shells with hanging
                       nodes (mesh3d.c); 0 = the default count, < 0 = none */
    double a_min;   /* 3D: smallest contact radius to resolve, mm: the core box is
                       sized to it and the shells, whose sizes grow in proportion
                       to the distance, carry n elements across every larger
                       contact; 0 (or >= a_max) = core sized to a_max */
} asp_mesh_spec;

stc_status asp_mesh_axisym(const asp_mesh_spec *spec, asp_mesh **out); /* returns new */
stc_status asp_mesh_half3d(const asp_mesh_spec *spec, asp_mesh **out); /* returns new */
/* --- added by the solver engineer (mesh.c) ---
 * Axisymmetric mesh that also resolves a smaller contact radius a_min (the
 * first yield of a load curve): size a_min/n near the axis growing to
 * a_max/n (see mesh.c).  a_min <= 0 or >= a_max: same as asp_mesh_axisym. */
stc_status asp_mesh_axisym_graded(const asp_mesh_spec *spec, double a_min, asp_mesh **out);
void asp_mesh_destroy(asp_mesh **m); /* sets *m = NULL */
/* Worst element quality in [0, 1] (1 = perfect square/cube; min over
 * elements of the scaled Jacobian).  Returns STC_EFORMAT if an element is
 * inverted. */
stc_status asp_mesh_quality(const asp_mesh *m, double *worst);
/* Whether node n lies on the sphere |x| = R about the origin (relative
 * tolerance 1e-9; the meshes put surface and interface nodes on it exactly
 * up to rounding); 0 for R <= 0. */
int asp_mesh_on_sphere(const asp_mesh *m, int n, double R);
/* The faces of the hex8 (mesh3d.c's corner order), corners in cyclic order. */
extern const int asp_hex8_faces[6][4];
/* Local refinement (refine3d.c).  Splits every hex with mark[e] != 0 into
 * eight; new edge and face nodes shared with unmarked elements become
 * hanging nodes; new nodes on the spheres R_outer and R_interface (0: none)
 * stay on them.  Refuses a marked element that touches a hanging node. */
stc_status asp_mesh_refine3d(const asp_mesh *m, const unsigned char *mark, double R_outer,
                             double R_interface, asp_mesh **out); /* returns new */
/* `levels` (0..2) nested 2:1 refinements of the elements near the contact
 * edge a0 (h the element size there): the band a0 - 1.5 h ... a0 + 2 h
 * laterally, the elements that start less than 1.5 h deep, each further
 * level one h narrower on every side and shallower; replaces *m. */
stc_status asp_mesh_refine_band(asp_mesh **m, double R_outer, double R_interface, double h,
                                double a0, int levels);

/* ---- material: isotropic elasticity + von Mises perfect plasticity ----- */

typedef struct asp_qp_state {
    double eps_p[6]; /* plastic strain, Voigt, engineering shear */
    double epbar;    /* equivalent plastic strain */
    double s[6];     /* deviatoric stress, Voigt, tensor shear (MPa) */
} asp_qp_state;

typedef struct asp_j2 {
    double E, nu, Y;     /* MPa, -, MPa */
    double lambda, mu, kappa; /* Lamé constants and bulk modulus, MPa */
    int map;             /* asp_return_map: midpoint (default), radial, exact */
} asp_j2;

void asp_j2_init(asp_j2 *m, const stc_material *mat);

/* Return map for total strain eps given the converged state `old`:
 * midpoint rule (m->map, the default of asp_j2_init), radial return
 * or exact integration.  Writes stress sig[6], the updated state `upd` and (if D !=
 * NULL) the consistent tangent D[6][6] (row major, engineering-shear
 * Voigt; not symmetric under the midpoint rule and exact integration).  Returns 1 if the point
 * is plastic in this step, 0 if elastic.  Pure. */
int asp_j2_update(const asp_j2 *m, const double eps[6], const asp_qp_state *old,
                  asp_qp_state *upd, double sig[6], double *D);
/* The same, also writing (if D and Dp != NULL) a symmetric positive
 * definite approximation Dp of D to factorize: D itself where D is
 * symmetric (elastic, radial return), else the tangent of a
 * proportional increment along the same flow direction. */
int asp_j2_update_pc(const asp_j2 *m, const double eps[6], const asp_qp_state *old,
                     asp_qp_state *upd, double sig[6], double *D, double *Dp);

/* Von Mises equivalent stress of a Voigt stress. */
double asp_von_mises(const double sig[6]);

/* ---- elements (B-bar, mean dilatation; 2x2 / 2x2x2 Gauss) -------------- */

enum { ASP_QUAD4_NQP = 4, ASP_HEX8_NQP = 8 };

/* Axisymmetric 4-node quadrilateral.  X: [4][2] (r, z); u: [8] (ur, uz per
 * node).  Computes fe[8] = ∫ Bbarᵀ σ 2πr dA (internal force, N) and, if Ke
 * is not NULL, Ke[8][8] row major (the exact tangent: not symmetric under
 * the midpoint return); if Kp is not NULL too, Kp[8][8] from the SPD
 * approximation of asp_j2_update_pc.  sig (nullable): [4][6] stress per qp.
 * Returns the number of plastic qps, or -1 for a non-positive Jacobian. */
int asp_quad4_axi(const double *X, const double *u, const asp_j2 *m,
                  const asp_qp_state *old, asp_qp_state *upd,
                  double *fe, double *Ke, double *Kp, double *sig);

/* 3D 8-node hexahedron, same conventions: X [8][3], u [24], fe [24],
 * Ke, Kp [24][24], sig [8][6]. */
int asp_hex8(const double *X, const double *u, const asp_j2 *m,
             const asp_qp_state *old, asp_qp_state *upd,
             double *fe, double *Ke, double *Kp, double *sig);

/* Gauss-point coordinates of an element (for yield location reporting):
 * xq [nqp][dim]. */
void asp_quad4_qp_coords(const double *X, double *xq);
void asp_hex8_qp_coords(const double *X, double *xq);

#endif
