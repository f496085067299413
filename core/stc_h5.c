/* Scalar and short vector HDF5 attributes (stc_h5.h). */
#include <string.h>

#include "stc_h5.h"

int stc_h5_attr_exists(hid_t obj, const char *name)
{
    htri_t e;
    H5E_BEGIN_TRY { e = H5Aexists(obj, name); } H5E_END_TRY;
    return e > 0;
}

static int attr_write(hid_t obj, const char *name, hid_t type, const void *v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(obj, name, type, sp, H5P_DEFAULT, H5P_DEFAULT);
    int ok = a >= 0 && H5Awrite(a, type, v) >= 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    return ok ? 0 : -1;
}

int stc_h5_put_d(hid_t o, const char *n, double v) { return attr_write(o, n, H5T_NATIVE_DOUBLE, &v); }
int stc_h5_put_i(hid_t o, const char *n, int v) { return attr_write(o, n, H5T_NATIVE_INT, &v); }
int stc_h5_put_u(hid_t o, const char *n, unsigned long v) { return attr_write(o, n, H5T_NATIVE_ULONG, &v); }

int stc_h5_put_s(hid_t o, const char *n, const char *v)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, strlen(v) + 1);
    H5Tset_strpad(t, H5T_STR_NULLTERM);
    int r = attr_write(o, n, t, v);
    H5Tclose(t);
    return r;
}

/* Open attribute n of o if it holds exactly one element (an array attribute
 * in a foreign file would overrun the single value read into); -1 if not. */
static hid_t attr_open_one(hid_t o, const char *n)
{
    if (!stc_h5_attr_exists(o, n)) return -1;
    hid_t a = H5Aopen(o, n, H5P_DEFAULT);
    if (a < 0) return -1;
    hid_t sp = H5Aget_space(a);
    hssize_t cnt = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
    if (sp >= 0) H5Sclose(sp);
    if (cnt != 1) {
        H5Aclose(a);
        return -1;
    }
    return a;
}

int stc_h5_get_d(hid_t o, const char *n, double *v)
{
    hid_t a = attr_open_one(o, n);
    int ok = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, v) >= 0;
    if (a >= 0) H5Aclose(a);
    return ok ? 0 : -1;
}

int stc_h5_get_i(hid_t o, const char *n, int *v)
{
    hid_t a = attr_open_one(o, n);
    int ok = a >= 0 && H5Aread(a, H5T_NATIVE_INT, v) >= 0;
    if (a >= 0) H5Aclose(a);
    return ok ? 0 : -1;
}

int stc_h5_get_u(hid_t o, const char *n, unsigned long *v)
{
    hid_t a = attr_open_one(o, n);
    int ok = a >= 0 && H5Aread(a, H5T_NATIVE_ULONG, v) >= 0;
    if (a >= 0) H5Aclose(a);
    return ok ? 0 : -1;
}

int stc_h5_get_s(hid_t o, const char *n, char *buf, size_t cap)
{
    hid_t a = attr_open_one(o, n);
    if (a < 0) return -1;
    hid_t ft = H5Aget_type(a);
    int ok = H5Tget_class(ft) == H5T_STRING && !H5Tis_variable_str(ft) && H5Tget_size(ft) <= cap;
    if (ok) {
        hid_t t = H5Tcopy(H5T_C_S1);
        H5Tset_size(t, cap);
        H5Tset_strpad(t, H5T_STR_NULLTERM);
        ok = H5Aread(a, t, buf) >= 0;
        H5Tclose(t);
    }
    H5Tclose(ft);
    H5Aclose(a);
    return ok ? 0 : -1;
}

int stc_h5_put_dv(hid_t o, const char *n, int len, const double *v)
{
    if (len < 1) return -1;
    hsize_t d = (hsize_t)len;
    hid_t sp = H5Screate_simple(1, &d, NULL);
    hid_t a = H5Acreate2(o, n, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    int ok = a >= 0 && H5Awrite(a, H5T_NATIVE_DOUBLE, v) >= 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    return ok ? 0 : -1;
}

int stc_h5_get_dv(hid_t o, const char *n, int cap, double *v, int *len)
{
    if (!stc_h5_attr_exists(o, n)) return -1;
    hid_t a = H5Aopen(o, n, H5P_DEFAULT);
    if (a < 0) return -1;
    hid_t sp = H5Aget_space(a);
    hsize_t d = 0;
    int ok = sp >= 0 && H5Sget_simple_extent_ndims(sp) == 1 &&
             H5Sget_simple_extent_dims(sp, &d, NULL) == 1 && d >= 1 && d <= (hsize_t)cap;
    if (sp >= 0) H5Sclose(sp);
    hid_t ft = H5Aget_type(a);
    ok = ok && ft >= 0 && H5Tget_class(ft) == H5T_FLOAT;
    if (ft >= 0) H5Tclose(ft);
    ok = ok && H5Aread(a, H5T_NATIVE_DOUBLE, v) >= 0;
    H5Aclose(a);
    if (ok) *len = (int)d;
    return ok ? 0 : -1;
}
