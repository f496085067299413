/* Fields of the asperity solver as HDF5 heavy data plus an XDMF 2 index
 * that ParaView opens (Quadrilateral / Hexahedron topology).  Nodal
 * displacement; element-averaged stress, von Mises stress and equivalent
 * plastic strain; layer id.  Every model parameter is stored as an attribute
 * of the HDF5 root group.  Stress components in the Voigt order of fe.h
 * (axisymmetric: rr, zz, θθ, rz, 0, 0; 3D: xx, yy, zz, xy, yz, zx), exposed
 * as a 6-column "Matrix" attribute (XDMF's Tensor6 uses another order).  Both files are written under temporary names and
 * renamed on success, so a failure leaves no partial output.
 */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "solver_impl.h"
#include "stc_check.h"

static int write_ds(hid_t f, const char *name, hid_t type, int rank, hsize_t n0, hsize_t n1,
                    const void *data)
{
    hsize_t dims[2] = {n0, n1};
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    if (sp < 0) return -1;
    hid_t ds = H5Dcreate2(f, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int rc = ds < 0 || H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0;
    if (ds >= 0) H5Dclose(ds);
    H5Sclose(sp);
    return rc ? -1 : 0;
}

static int write_attr(hid_t f, const char *name, double v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a < 0 || H5Awrite(a, H5T_NATIVE_DOUBLE, &v) < 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    return rc ? -1 : 0;
}

static int write_params(hid_t f, const asp_solver *s)
{
    stc_material su, co;
    stc_params_materials(&s->par, &su, &co);
    return write_attr(f, "R_mm", s->par.R) | write_attr(f, "t_over_R", s->par.t_over_R) |
           write_attr(f, "E_su_MPa", su.E) | write_attr(f, "nu_su", su.nu) |
           write_attr(f, "Y_su_MPa", su.Y) | write_attr(f, "E_co_MPa", co.E) |
           write_attr(f, "nu_co", co.nu) | write_attr(f, "Y_co_MPa", co.Y) |
           write_attr(f, "delta_mm", s->delta) | write_attr(f, "P_N", s->pt.P) |
           write_attr(f, "contact_stick", s->opt.contact == ASP_CONTACT_STICK) |
           write_attr(f, "no_separation", s->opt.no_separation) |
           write_attr(f, "mesh_level", s->level) | write_attr(f, "a_max_mm", s->a_max) |
           write_attr(f, "rtol", s->opt.rtol) | write_attr(f, "utol", s->opt.utol);
}

/* Element averages of the quadrature-point fields: sv [nelem][8] =
 * stress[6], von Mises, ε̄p. */
static void cell_fields(const asp_solver *s, double *sv)
{
    int nq = s->nqp;
    for (int e = 0; e < s->mesh->nelem; e++) {
        double *o = sv + 8 * (size_t)e;
        memset(o, 0, 8 * sizeof *o);
        for (int q = 0; q < nq; q++) {
            size_t iq = (size_t)e * nq + q;
            for (int k = 0; k < 6; k++) o[k] += s->sig[6 * iq + k] / nq;
            o[6] += asp_von_mises(s->sig + 6 * iq) / nq;
            o[7] += s->st_old[iq].epbar / nq;
        }
    }
}

static stc_status write_h5(const asp_solver *s, const char *path)
{
    const asp_mesh *m = s->mesh;
    size_t nn = (size_t)m->nnode, ne = (size_t)m->nelem;
    double *xyz = calloc(3 * nn, sizeof *xyz), *u = calloc(3 * nn, sizeof *u);
    double *sv = malloc(8 * ne * sizeof *sv), *col = malloc(6 * ne * sizeof *col);
    stc_status st = STC_OK;
    STC_CHECK_GOTO(xyz && u && sv && col, st, done, STC_ENOMEM, "fields: out of memory");
    for (size_t i = 0; i < nn; i++) {
        for (int k = 0; k < s->dim; k++) xyz[3 * i + k] = m->x[s->dim * i + k];
        asp_node_u(s, s->u_conv, (int)i, u + 3 * i);
    }
    cell_fields(s, sv);
    for (size_t e = 0; e < ne; e++)
        for (int k = 0; k < 6; k++) col[6 * e + k] = sv[8 * e + k];
    hid_t f;
    /* library code does not print: HDF5's error stack stays quiet here only */
    H5E_BEGIN_TRY { f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT); } H5E_END_TRY;
    STC_CHECK_GOTO(f >= 0, st, done, STC_EIO, "fields: cannot create '%s'", path);
    int rc = 0;
    H5E_BEGIN_TRY {
        rc = write_ds(f, "/geometry", H5T_NATIVE_DOUBLE, 2, nn, 3, xyz) |
             write_ds(f, "/topology", H5T_NATIVE_INT, 2, ne, (hsize_t)m->nen, m->conn) |
             write_ds(f, "/layer", H5T_NATIVE_INT, 1, ne, 1, m->region) |
             write_ds(f, "/displacement", H5T_NATIVE_DOUBLE, 2, nn, 3, u) | write_params(f, s) |
             write_ds(f, "/stress", H5T_NATIVE_DOUBLE, 2, ne, 6, col);
        for (size_t e = 0; e < ne; e++) col[e] = sv[8 * e + 6];
        rc |= write_ds(f, "/von_mises", H5T_NATIVE_DOUBLE, 1, ne, 1, col);
        for (size_t e = 0; e < ne; e++) col[e] = sv[8 * e + 7];
        rc |= write_ds(f, "/plastic_strain", H5T_NATIVE_DOUBLE, 1, ne, 1, col);
        rc |= H5Fclose(f) < 0;
    } H5E_END_TRY;
    STC_CHECK_GOTO(!rc, st, done, STC_EIO, "fields: writing '%s' failed", path);
done:
    free(xyz), free(u), free(sv), free(col);
    return st;
}

static stc_status write_xmf(const asp_solver *s, const char *path, const char *h5name)
{
    const asp_mesh *m = s->mesh;
    FILE *f = fopen(path, "w");
    STC_CHECK(f, STC_EIO, "fields: cannot create '%s'", path);
    int nn = m->nnode, ne = m->nelem;
    fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n<Domain>\n"
               "<Grid Name=\"asperity\" GridType=\"Uniform\">\n"
               "<Time Value=\"%.9g\"/>\n"
               "<Topology TopologyType=\"%s\" NumberOfElements=\"%d\">\n"
               "<DataItem Dimensions=\"%d %d\" NumberType=\"Int\" Format=\"HDF\">%s:/topology"
               "</DataItem>\n</Topology>\n"
               "<Geometry GeometryType=\"XYZ\">\n<DataItem Dimensions=\"%d 3\" "
               "NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry</DataItem>\n"
               "</Geometry>\n",
            s->delta, s->dim == 2 ? "Quadrilateral" : "Hexahedron", ne, ne, m->nen, h5name, nn,
            h5name);
    const char *names[] = {"displacement", "stress", "von_mises", "plastic_strain", "layer"};
    const char *types[] = {"Vector", "Matrix", "Scalar", "Scalar", "Scalar"};
    for (int k = 0; k < 5; k++) {
        int node = k == 0, cols = k == 0 ? 3 : k == 1 ? 6 : 1;
        fprintf(f, "<Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n"
                   "<DataItem Dimensions=\"%d %d\" NumberType=\"%s\" Precision=\"%d\" "
                   "Format=\"HDF\">%s:/%s</DataItem>\n</Attribute>\n",
                names[k], types[k], node ? "Node" : "Cell", node ? nn : ne, cols,
                k == 4 ? "Int" : "Float", k == 4 ? 4 : 8, h5name, names[k]);
    }
    fprintf(f, "</Grid>\n</Domain>\n</Xdmf>\n");
    STC_CHECK(fclose(f) == 0, STC_EIO, "fields: writing '%s' failed", path);
    return STC_OK;
}

stc_status asp_solver_write_fields(const asp_solver *s, const char *prefix)
{
    size_t n = strlen(prefix) + 16;
    char *h5 = malloc(n), *h5t = malloc(n), *xm = malloc(n), *xmt = malloc(n);
    stc_status st = STC_OK;
    STC_CHECK_GOTO(h5 && h5t && xm && xmt, st, done, STC_ENOMEM, "fields: out of memory");
    snprintf(h5, n, "%s.h5", prefix), snprintf(h5t, n, "%s.h5.tmp", prefix);
    snprintf(xm, n, "%s.xmf", prefix), snprintf(xmt, n, "%s.xmf.tmp", prefix);
    const char *base = strrchr(h5, '/');
    base = base ? base + 1 : h5;
    STC_CALL_GOTO(write_h5(s, h5t), st, done);
    STC_CALL_GOTO(write_xmf(s, xmt, base), st, done);
    STC_CHECK_GOTO(rename(h5t, h5) == 0 && rename(xmt, xm) == 0, st, done, STC_EIO,
                   "fields: cannot rename into '%s'", xm);
done:
    if (st != STC_OK && h5t) remove(h5t);
    if (st != STC_OK && xmt) remove(xmt);
    free(h5), free(h5t), free(xm), free(xmt);
    return st;
}
